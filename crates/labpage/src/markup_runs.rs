//! Markup split into its tags and its text: two renderings of the same
//! structure (an equation with other numbers in it) differ only in their
//! text runs, so the page can rewrite the text nodes it has instead of
//! parsing the markup anew (see labweb's math panel).

/// The markup `html` as its skeleton (every tag, with a `\u{0}` where a
/// text run stood) and its text runs, decoded, in document order: the text
/// nodes an HTML parser makes of it, one a run.
///
/// `None` where the markup holds something this does not decode (an entity
/// other than `&amp;`, `&lt;`, `&gt;`, `&quot;`, `&#39;` and numeric ones, a
/// comment, an unclosed tag): the caller then writes the markup whole.
#[must_use]
pub fn markup_runs(html: &str) -> Option<(String, Vec<String>)> {
    let mut skeleton = String::with_capacity(html.len() / 2);
    let mut runs = Vec::new();
    let mut rest = html;
    while !rest.is_empty() {
        if rest.starts_with("<!") {
            return None;
        }
        if rest.starts_with('<') {
            let end = rest.find('>')? + 1;
            skeleton.push_str(&rest[..end]);
            rest = &rest[end..];
        } else {
            let end = rest.find('<').unwrap_or(rest.len());
            runs.push(decode(&rest[..end])?);
            skeleton.push('\u{0}');
            rest = &rest[end..];
        }
    }
    Some((skeleton, runs))
}

/// Text with its character references decoded (the ones the lab writes).
fn decode(text: &str) -> Option<String> {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(amp) = rest.find('&') {
        out.push_str(&rest[..amp]);
        let semi = rest[amp..].find(';')? + amp;
        let name = &rest[amp + 1..semi];
        let c = match name {
            "amp" => '&',
            "lt" => '<',
            "gt" => '>',
            "quot" => '"',
            "#39" => '\'',
            _ => {
                let code = if let Some(hex) = name.strip_prefix("#x").or(name.strip_prefix("#X")) {
                    u32::from_str_radix(hex, 16).ok()?
                } else {
                    name.strip_prefix('#')?.parse().ok()?
                };
                char::from_u32(code)?
            }
        };
        out.push(c);
        rest = &rest[semi + 1..];
    }
    out.push_str(rest);
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_renderings_of_one_equation_share_a_skeleton_and_differ_in_their_runs() {
        let a = "<span class=\"eq-part\"><math><mo>=</mo><mn>1.00</mn><mo>&#x2061;</mo></math></span> <span><math><mo>+</mo><mn>0.80</mn></math></span>";
        let b = a.replace("1.00", "1.25").replace("0.80", "-0.05");
        let (sa, ra) = markup_runs(a).unwrap();
        let (sb, rb) = markup_runs(&b).unwrap();
        assert_eq!(sa, sb);
        assert_eq!(ra, ["=", "1.00", "\u{2061}", " ", "+", "0.80"]);
        assert_eq!(rb, ["=", "1.25", "\u{2061}", " ", "+", "-0.05"]);
        assert_eq!(sa.matches('\u{0}').count(), ra.len());
    }

    #[test]
    fn another_structure_is_another_skeleton() {
        let (a, _) = markup_runs("<mn>1</mn>").unwrap();
        let (b, _) = markup_runs("<mn>1</mn><mo>+</mo>").unwrap();
        assert_ne!(a, b);
    }

    #[test]
    fn plain_text_is_one_run_and_references_are_decoded() {
        let (s, r) = markup_runs("x &lt; 3 &amp;&amp; y &gt; &quot;2&quot; &#39;&#955;").unwrap();
        assert_eq!(s, "\u{0}");
        assert_eq!(r, ["x < 3 && y > \"2\" 'λ"]);
        assert_eq!(markup_runs("").unwrap(), (String::new(), Vec::new()));
    }

    #[test]
    fn what_it_cannot_decode_is_none() {
        assert!(markup_runs("a &nbsp; b").is_none());
        assert!(markup_runs("a &amp b").is_none());
        assert!(markup_runs("<!-- c -->").is_none());
        assert!(markup_runs("<mn>1</mn").is_none());
        assert!(markup_runs("&#xZZ;").is_none());
    }
}
