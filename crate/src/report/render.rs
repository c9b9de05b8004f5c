//! The report rendered: the self-contained HTML file ([`super::html`]) and its Markdown
//! twin ([`super::markdown`]), both from the same blocks ([`super::document`]), and the
//! figures as SVG ([`super::figures`]).

use super::{document, figures, html, markdown, MethodReport};
use crate::error::Result;

/// The report's documents: the HTML file, its Markdown twin and the figures (the
/// Markdown links to them as `figures/<key>.svg`).
#[derive(Debug, Clone, PartialEq)]
pub struct Documents {
    /// The self-contained HTML file.
    pub html: String,
    /// The Markdown twin.
    pub markdown: String,
    /// The figures, in order.
    pub figures: Vec<figures::Figure>,
}

impl MethodReport {
    /// Renders the HTML and Markdown documents and the figures.
    pub fn documents(&self) -> Result<Documents> {
        let figs = figures::figures(self)?;
        let all: Vec<figures::Figure> = figs.iter().flat_map(|(_, f)| f.clone()).collect();
        let blocks = document::blocks(self, figs);
        Ok(Documents {
            html: html::render(&self.title(), &blocks),
            markdown: markdown::render(&blocks),
            figures: all,
        })
    }
}
