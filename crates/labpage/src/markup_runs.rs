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

/// The markup `html` as its top-level nodes, in order: each element with
/// everything inside it, and each text run between them (the child nodes an
/// HTML parser makes of it, one an entry). `None` for markup
/// [`markup_runs`] refuses, or with a tag left open or closed twice.
///
/// Two renderings whose shape differs in one place (a number that changed
/// sign gains its parentheses) still share their other top-level nodes, so
/// the page rewrites only the node that changed.
#[must_use]
pub fn top_level_nodes(html: &str) -> Option<Vec<&str>> {
    let mut nodes = Vec::new();
    let (mut depth, mut start, mut at) = (0usize, 0usize, 0usize);
    while at < html.len() {
        let rest = &html[at..];
        if rest.starts_with("<!") {
            return None;
        }
        if let Some(tag) = rest.strip_prefix('<') {
            let end = rest.find('>')? + 1;
            if tag.starts_with('/') {
                depth = depth.checked_sub(1)?;
                at += end;
                if depth == 0 {
                    nodes.push(&html[start..at]);
                    start = at;
                }
                continue;
            }
            if depth == 0 && start < at {
                nodes.push(&html[start..at]);
                start = at;
            }
            // Void elements the lab writes (`<br>`, `<wbr>`) have no end tag.
            let name: String = tag
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric())
                .collect();
            let void = matches!(name.as_str(), "br" | "wbr" | "img" | "hr" | "input")
                || rest[..end].ends_with("/>");
            at += end;
            if void {
                if depth == 0 {
                    nodes.push(&html[start..at]);
                    start = at;
                }
            } else {
                depth += 1;
            }
        } else {
            at += rest.find('<').unwrap_or(rest.len());
        }
    }
    if depth != 0 {
        return None;
    }
    if start < html.len() {
        nodes.push(&html[start..]);
    }
    Some(nodes)
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
    fn top_level_nodes_are_the_elements_and_the_text_between_them() {
        let html = "<span class=\"eq-part\"><math><mo>=</mo><mn>1</mn></math></span> <span><math><mo>(</mo><mn>2</mn></math></span>x<br>y";
        assert_eq!(
            top_level_nodes(html).unwrap(),
            [
                "<span class=\"eq-part\"><math><mo>=</mo><mn>1</mn></math></span>",
                " ",
                "<span><math><mo>(</mo><mn>2</mn></math></span>",
                "x",
                "<br>",
                "y"
            ]
        );
        assert_eq!(top_level_nodes("= 0.83").unwrap(), ["= 0.83"]);
        assert!(top_level_nodes("").unwrap().is_empty());
        assert!(top_level_nodes("<span><mn>1</mn>").is_none(), "left open");
        assert!(
            top_level_nodes("<mn>1</mn></span>").is_none(),
            "closed twice"
        );
        // Every node's own runs are the whole's runs, in order.
        let all: Vec<String> = top_level_nodes(html)
            .unwrap()
            .iter()
            .flat_map(|n| markup_runs(n).unwrap().1)
            .collect();
        assert_eq!(all, markup_runs(html).unwrap().1);
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
