//! HTML for the reading tabs (Aim, Theory, Procedure, References).
//!
//! Content files are ours and compiled in, so their text (with MathML and a
//! few inline tags) goes into the page as HTML; anything from the URL never does.

use crate::dom::escape;
use labcore::content::{Block, Content, Reference};

pub fn aim(content: &Content) -> String {
    content.aim.iter().map(|p| format!("<p>{p}</p>")).collect()
}

pub fn theory(content: &Content) -> String {
    content
        .theory
        .iter()
        .map(|b| match b {
            Block::Heading(h) => format!("<h3>{h}</h3>"),
            Block::Paragraph(p) => format!("<p>{p}</p>"),
            Block::Formula(f) => format!("<div class=\"formula\">{f}</div>"),
            Block::Note(n) => format!("<aside class=\"note\">{n}</aside>"),
        })
        .collect()
}

pub fn procedure(content: &Content) -> String {
    let steps: String = content
        .procedure
        .iter()
        .map(|s| format!("<li>{s}</li>"))
        .collect();
    format!("<ol class=\"steps\">{steps}</ol>")
}

fn reference(r: &Reference) -> String {
    let mut s = format!(
        "<span class=\"ref-authors\">{}</span> — <cite>{}</cite>. {}",
        r.authors, r.title, r.venue
    );
    if let Some(year) = r.year {
        s.push_str(&format!(", {year}"));
    }
    if let Some(detail) = &r.detail {
        s.push_str(&format!(". {detail}"));
    }
    s.push('.');
    if let Some(link) = r.link() {
        // Validated by labcore (an http(s) URL or a DOI); escaped all the same.
        let shown = match &r.doi {
            Some(doi) => format!("doi:{doi}"),
            None => link.clone(),
        };
        s.push_str(&format!(
            " <a class=\"ref-link\" href=\"{}\" rel=\"noopener\">{}</a>",
            escape(&link),
            escape(&shown)
        ));
    }
    s
}

pub fn references(content: &Content) -> String {
    let items: String = content
        .references
        .iter()
        .map(|r| format!("<li>{}</li>", reference(r)))
        .collect();
    format!("<ol class=\"refs\">{items}</ol>")
}

/// Shown in place of a tab whose content file failed to load.
pub fn content_error(message: &str) -> String {
    format!(
        "<p class=\"sim-error\" role=\"alert\">This experiment's text could not be loaded: {}</p>",
        escape(message)
    )
}
