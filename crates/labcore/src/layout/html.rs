//! HTML escaping: one rule for every page, report and package the lab writes.

/// Escapes `text` for HTML element content *and* attribute values: `&`, `<`,
/// `>`, `"` and `'`. The apostrophe matters inside a single-quoted attribute
/// (`title='…'`), where an unescaped `'` would end the value early; escaping
/// it everywhere lets a caller put the result in either kind of attribute.
#[must_use]
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::escape;

    #[test]
    fn each_special_character_has_its_entity() {
        assert_eq!(escape("&"), "&amp;");
        assert_eq!(escape("<"), "&lt;");
        assert_eq!(escape(">"), "&gt;");
        assert_eq!(escape("\""), "&quot;");
        assert_eq!(escape("'"), "&#39;");
    }

    #[test]
    fn other_text_passes_through_and_ampersands_are_escaped_once() {
        assert_eq!(escape("θ₁ = 30° · m/s²"), "θ₁ = 30° · m/s²");
        assert_eq!(escape("a &amp; b"), "a &amp;amp; b");
        assert_eq!(escape(""), "");
    }

    #[test]
    fn an_apostrophe_cannot_end_a_single_quoted_attribute() {
        let attr = format!("<p title='{}'>", escape("robot's arm"));
        assert_eq!(attr, "<p title='robot&#39;s arm'>");
        assert_eq!(attr.matches('\'').count(), 2);
    }
}
