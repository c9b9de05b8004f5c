//! The report as one self-contained HTML file: inline CSS, the figures inline as SVG,
//! no script and no reference to any other origin.

use super::document::Block;

/// Escapes text for HTML.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

const STYLE: &str = "body{font:16px/1.45 system-ui,-apple-system,'Segoe UI',sans-serif;max-width:72rem;margin:2rem auto;padding:0 1rem;color:#111}\
h1{font-size:1.6rem}h2{font-size:1.3rem;margin-top:2.2rem;border-bottom:1px solid #ccc}h3{font-size:1.1rem}\
table{border-collapse:collapse;margin:.6rem 0;font-variant-numeric:tabular-nums}\
th,td{border:1px solid #bbb;padding:.2rem .5rem;text-align:left;vertical-align:top}th{background:#f0f0f0}\
figure{margin:1rem 0;display:inline-block;vertical-align:top;max-width:100%}figure svg{max-width:100%;height:auto}\
figcaption{font-size:.9rem;color:#333;max-width:640px}";

/// The HTML document of `blocks`, titled `title`.
pub fn render(title: &str, blocks: &[Block]) -> String {
    let mut s = format!(
        "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n",
        esc(title)
    );
    for b in blocks {
        match b {
            Block::Heading(level, text) => {
                s += &format!("<h{level}>{}</h{level}>\n", esc(text));
            }
            Block::Paragraph(text) => s += &format!("<p>{}</p>\n", esc(text)),
            Block::Table(head, rows) => {
                s += "<table>\n<thead><tr>";
                for h in head {
                    s += &format!("<th scope=\"col\">{}</th>", esc(h));
                }
                s += "</tr></thead>\n<tbody>\n";
                for row in rows {
                    s += "<tr>";
                    for cell in row {
                        s += &format!("<td>{}</td>", esc(cell));
                    }
                    s += "</tr>\n";
                }
                s += "</tbody>\n</table>\n";
            }
            Block::Figure(f) => {
                // The core's SVG documents carry no XML declaration; inline as they are.
                s += &format!(
                    "<figure id=\"{}\">\n{}\n<figcaption>{}</figcaption>\n</figure>\n",
                    esc(&f.key),
                    f.svg.trim(),
                    esc(&f.caption)
                );
            }
        }
    }
    s + "</body>\n</html>\n"
}
