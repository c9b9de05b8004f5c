//! The report as Markdown: the same blocks as the HTML, the figures as links to
//! `figures/<key>.svg` beside the file.

use super::document::Block;

/// Escapes a table cell (pipes would end it).
fn cell(s: &str) -> String {
    s.replace('|', "\\|")
}

/// The Markdown document of `blocks`.
pub fn render(blocks: &[Block]) -> String {
    let mut s = String::new();
    for b in blocks {
        match b {
            Block::Heading(level, text) => {
                s += &format!("{} {text}\n\n", "#".repeat(*level as usize));
            }
            Block::Paragraph(text) => s += &format!("{text}\n\n"),
            Block::Table(head, rows) => {
                let line = |cells: &[String]| {
                    format!(
                        "| {} |\n",
                        cells
                            .iter()
                            .map(|c| cell(c))
                            .collect::<Vec<_>>()
                            .join(" | ")
                    )
                };
                s += &line(head);
                s += &format!("|{}\n", "---|".repeat(head.len()));
                for row in rows {
                    s += &line(row);
                }
                s += "\n";
            }
            Block::Figure(f) => {
                s += &format!("![{}](figures/{}.svg)\n\n", f.caption, f.key);
            }
        }
    }
    s
}
