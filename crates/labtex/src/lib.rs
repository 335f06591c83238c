//! The content files' formulas, written in LaTeX and turned into MathML when
//! the lab is built.
//!
//! A text field of `assets/<id>.json` writes a formula between dollars:
//! `$…$` inline, `$$…$$` as a display formula; `\$` is a literal dollar
//! sign. [`render`] replaces each formula with its MathML, written by the
//! `math-core` crate, with every accent in the form all three browser engines
//! draw over its letter ([`accents::portable`]); everything between formulas
//! is left as it is. The content files hold no hand-written `<math>` markup:
//! a field that does is refused, so every formula on a page came from LaTeX.
//!
//! `\live{key}{symbol}` marks a symbol that names one of the experiment's
//! live quantities (`\live{t1}{\theta_1}`): its MathML is wrapped in
//! `<mrow data-live="t1" tabindex="0">`, which the page finds to highlight
//! what the symbol names and to show its value ([`live_keys`] lists them;
//! labcore checks each key is a quantity of the experiment).
//!
//! labcore's `build.rs` renders every text field before compiling the files
//! in (the quiz text the wasm modules show and the reading pages alike), and
//! labcore's `reading` parser does the same for a file read at run time by
//! the build tool and the tests. This crate runs at build time only: no
//! shipped wasm module links it.

pub mod accents;

use math_core::{LatexToMathML, MathCoreConfig, MathDisplay};
use std::fmt;

/// A formula that cannot be written as MathML, or a text whose dollars do
/// not pair up.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TexError {
    /// The formula's LaTeX as written between its dollars (for an unclosed
    /// formula, the rest of the text).
    pub formula: String,
    /// Where in `formula` the problem is, counted in characters from 1.
    pub at_char: usize,
    /// What is wrong there.
    pub message: String,
}

impl fmt::Display for TexError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "LaTeX error at character {} of the formula `{}`: {}",
            self.at_char, self.formula, self.message
        )
    }
}

impl std::error::Error for TexError {}

/// `text` with every `$…$` and `$$…$$` formula replaced by its MathML
/// (`<math>…</math>`, `<math display="block">…</math>`) and every `\$`
/// by `$`. Text without a dollar comes back unchanged.
pub fn render(text: &str) -> Result<String, TexError> {
    if let Some(at) = text.find("<math") {
        return Err(TexError {
            formula: text[at..].chars().take(40).collect(),
            at_char: 1,
            message: "write the formula in LaTeX between dollars ($…$ or $$…$$), not as MathML"
                .into(),
        });
    }
    if !text.contains('$') {
        return Ok(text.to_owned());
    }
    let converter = LatexToMathML::new(MathCoreConfig::default())
        .expect("the default configuration defines no macros");
    let mut out = String::with_capacity(text.len() * 4);
    let mut rest = text;
    while let Some(at) = rest.find(['$', '\\']) {
        out.push_str(&rest[..at]);
        let after = &rest[at..];
        if let Some(tail) = after.strip_prefix("\\$") {
            out.push('$');
            rest = tail;
            continue;
        }
        if let Some(tail) = after.strip_prefix('\\') {
            out.push('\\');
            rest = tail;
            continue;
        }
        let (fence, display) = if after.starts_with("$$") {
            ("$$", MathDisplay::Block)
        } else {
            ("$", MathDisplay::Inline)
        };
        let body = &after[fence.len()..];
        let Some(end) = closing(body, fence) else {
            return Err(TexError {
                formula: body.to_owned(),
                at_char: 1,
                message: format!("the formula opened with `{fence}` is not closed"),
            });
        };
        let latex = &body[..end];
        if latex.trim().is_empty() {
            return Err(TexError {
                formula: latex.to_owned(),
                at_char: 1,
                message: format!(
                    "an empty formula (`{fence}{fence}`); write a literal dollar as \\$"
                ),
            });
        }
        let marked = expand_live(latex)?;
        let mathml = converter
            .convert_with_local_state(&marked.latex, display)
            .map_err(|e| TexError {
                formula: latex.to_owned(),
                at_char: marked.original_char(
                    marked.latex[..e.0.start.min(marked.latex.len())]
                        .chars()
                        .count(),
                ) + 1,
                message: e.error_message(),
            })?
            .mathml;
        let mathml = marked.wrap_live(&mathml);
        let mathml = without_inline_styles(&mathml).map_err(|message| TexError {
            formula: latex.to_owned(),
            at_char: 1,
            message,
        })?;
        out.push_str(&accents::portable(&mathml));
        rest = &body[end + fence.len()..];
    }
    out.push_str(rest);
    Ok(out)
}

/// The declarations math-core writes as `style` attributes on table cells
/// (a `cases` column is left-aligned, its columns spaced), each with the
/// class of `web/style.css` that says the same: the site's
/// Content-Security-Policy allows no inline style.
const STYLE_CLASSES: [(&str, &str); 6] = [
    ("text-align: left", "tex-left"),
    ("justify-items: start", "tex-left"),
    ("text-align: right", "tex-right"),
    ("justify-items: end", "tex-right"),
    ("padding-right: 0", "tex-pad-right-0"),
    ("padding-left:1em", "tex-pad-left-1em"),
];

/// `mathml` with each `style="…"` attribute written as the classes of
/// [`STYLE_CLASSES`]; a declaration without one is an error (the page would
/// lose it to the Content-Security-Policy).
fn without_inline_styles(mathml: &str) -> Result<String, String> {
    let mut out = String::with_capacity(mathml.len());
    let mut rest = mathml;
    while let Some(at) = rest.find(" style=\"") {
        out.push_str(&rest[..at]);
        let value_start = at + " style=\"".len();
        let Some(len) = rest[value_start..].find('"') else {
            return Err("an unclosed style attribute in the MathML".into());
        };
        let mut classes: Vec<&str> = Vec::new();
        for declaration in rest[value_start..value_start + len]
            .split(';')
            .map(str::trim)
            .filter(|d| !d.is_empty())
        {
            let Some(&(_, class)) = STYLE_CLASSES.iter().find(|(d, _)| *d == declaration) else {
                return Err(format!(
                    "this needs the inline style `{declaration}`, which the site's \
                     Content-Security-Policy blocks; give it a class in labtex and web/style.css"
                ));
            };
            if !classes.contains(&class) {
                classes.push(class);
            }
        }
        out.push_str(&format!(" class=\"{}\"", classes.join(" ")));
        rest = &rest[value_start + len + 1..];
    }
    out.push_str(rest);
    Ok(out)
}

/// The command that marks a live symbol: `\live{key}{symbol}`.
const LIVE: &str = "\\live";
/// What `\live{key}{` becomes for the converter: a group coloured with a
/// marker colour whose last two hex digits number the mark, which comes out
/// as `<mrow style="color:#FEEDnn;">` and is then rewritten by
/// [`Marked::wrap_live`]. (Content cannot use `\color` itself: the
/// Content-Security-Policy blocks its inline style.)
const MARKER: &str = "{\\color[HTML]{FEED";

/// A formula's LaTeX with its `\live` marks turned into marker groups.
struct Marked {
    latex: String,
    /// The keys, in the order of their marker numbers.
    keys: Vec<String>,
    /// Each replacement: where it starts in `latex` (chars), its length
    /// there and in the original (chars).
    edits: Vec<(usize, usize, usize)>,
}

impl Marked {
    /// The character of the original formula that character `at` of
    /// `latex` came from.
    fn original_char(&self, at: usize) -> usize {
        let mut shift = 0isize;
        for &(start, new_len, old_len) in &self.edits {
            if at < start {
                break;
            }
            if at < start + new_len {
                return (start as isize - shift) as usize;
            }
            shift += new_len as isize - old_len as isize;
        }
        (at as isize - shift) as usize
    }

    /// `mathml` with each marker group written as a focusable
    /// `<mrow data-live="key" tabindex="0">`.
    fn wrap_live(&self, mathml: &str) -> String {
        let mut out = mathml.to_owned();
        for (i, key) in self.keys.iter().enumerate() {
            let marker = format!("<mrow style=\"color:#FEED{i:02X};\">");
            let Some(at) = out.find(&marker) else {
                continue;
            };
            // A function name (`\cos`) keeps the thin space it has before a
            // bare symbol: the converter leaves it out before a group.
            let mut head = out[..at].to_owned();
            if let Some(name_at) = head.rfind(" rspace=\"0\">") {
                let name = &head[name_at + " rspace=\"0\">".len()..];
                if name
                    .strip_suffix("</mo>")
                    .is_some_and(|n| n.len() > 1 && n.chars().all(|c| c.is_ascii_alphabetic()))
                {
                    head.replace_range(name_at..name_at + 12, " rspace=\"0.1667em\">");
                }
            }
            out = format!(
                "{head}<mrow data-live=\"{key}\" tabindex=\"0\">{}",
                &out[at + marker.len()..]
            );
        }
        out
    }
}

/// `latex` with each `\live{key}{` replaced by a numbered marker group (the
/// symbol and its closing brace stay as written); a malformed mark or key is
/// an error at its position.
fn expand_live(latex: &str) -> Result<Marked, TexError> {
    let mut marked = Marked {
        latex: String::with_capacity(latex.len()),
        keys: Vec::new(),
        edits: Vec::new(),
    };
    let mut rest = latex;
    let mut new_chars = 0;
    while let Some(at) = rest.find(LIVE) {
        let head = &rest[..at];
        marked.latex.push_str(head);
        new_chars += head.chars().count();
        let after = &rest[at + LIVE.len()..];
        let error = |message: &str| TexError {
            formula: latex.to_owned(),
            at_char: latex[..latex.len() - rest.len() + at].chars().count() + 1,
            message: message.to_owned(),
        };
        let key = after
            .strip_prefix('{')
            .and_then(|a| a.split_once("}{"))
            .map(|(key, _)| key)
            .filter(|key| {
                !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            });
        let Some(key) = key else {
            return Err(error(
                "write a live symbol as \\live{key}{symbol}, the key in letters, digits and _",
            ));
        };
        if marked.keys.len() > 0xFF {
            return Err(error("more than 256 live symbols in one formula"));
        }
        let replacement = format!("{MARKER}{:02X}}}", marked.keys.len());
        let old_len = LIVE.len() + key.len() + 3;
        marked.edits.push((new_chars, replacement.len(), old_len));
        new_chars += replacement.len();
        marked.latex.push_str(&replacement);
        marked.keys.push(key.to_owned());
        rest = &after[key.len() + 3..];
    }
    marked.latex.push_str(rest);
    Ok(marked)
}

/// The keys of the live symbols (`data-live="…"`) in rendered `html`, in
/// order, each as often as it is marked.
#[must_use]
pub fn live_keys(html: &str) -> Vec<&str> {
    html.split(" data-live=\"")
        .skip(1)
        .filter_map(|part| part.split('"').next())
        .collect()
}

/// Byte offset in `body` of the `fence` that closes a formula: the first one
/// not escaped as `\$` (inside a formula `\$` is LaTeX's dollar sign).
fn closing(body: &str, fence: &str) -> Option<usize> {
    let mut at = 0;
    while at < body.len() {
        let rest = &body[at..];
        if let Some(escaped) = rest.strip_prefix('\\') {
            // Skip the backslash and the character it escapes.
            at += 1 + escaped.chars().next().map_or(0, char::len_utf8);
        } else if rest.starts_with(fence) {
            return Some(at);
        } else {
            at += rest.chars().next().map_or(1, char::len_utf8);
        }
    }
    None
}

/// [`render`] for the field at `path` (a JSON path such as
/// `theory[2].formula`), its error prefixed with that path.
pub fn render_field(path: &str, text: &str) -> Result<String, String> {
    render(text).map_err(|e| format!("{path}: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_without_formulas_is_left_as_it_is() {
        let prose = "The arm has <strong>two</strong> links &amp; a tip.";
        assert_eq!(render(prose).unwrap(), prose);
    }

    #[test]
    fn inline_and_display_formulas_become_mathml() {
        assert_eq!(
            render("where $x_1$ is").unwrap(),
            "where <math><msub><mi>x</mi><mn>1</mn></msub></math> is"
        );
        let block = render("$$f(n)=g(n)+h(n)$$").unwrap();
        assert!(block.starts_with("<math display=\"block\">"), "{block}");
        assert!(block.ends_with("</math>"), "{block}");
        assert_eq!(block.matches("<math").count(), 1);
    }

    #[test]
    fn an_escaped_dollar_is_a_dollar_sign() {
        assert_eq!(render("costs \\$5").unwrap(), "costs $5");
        assert_eq!(
            render("$\\$x$ and \\$").unwrap(),
            format!(
                "{} and $",
                render("$\\$x$").unwrap().split(" and").next().unwrap()
            )
        );
        assert!(render("$\\$x$").unwrap().contains('$'));
        // A backslash that escapes nothing stays.
        assert_eq!(render("a \\ b").unwrap(), "a \\ b");
    }

    #[test]
    fn accents_come_out_in_the_form_every_engine_draws_over_its_letter() {
        for latex in [
            "$\\dot{\\theta}$",
            "$\\ddot{x}$",
            "$\\bar{\\mu}$",
            "$\\hat{x}$",
        ] {
            let mathml = render(latex).unwrap();
            assert!(mathml.contains("<mover accent=\"true\">"), "{mathml}");
            assert!(mathml.contains("<mo stretchy=\"true\""), "{mathml}");
            assert_eq!(accents::non_portable(&mathml), Vec::<String>::new());
        }
    }

    /// The site's Content-Security-Policy blocks `style` attributes: the
    /// left-aligned column of `cases` comes out as classes.
    #[test]
    fn csp_cases_columns_are_aligned_by_class_not_by_inline_style() {
        let mathml = render(
            "$$x = \\begin{cases} 1 & \\text{if } a \\\\ 0 & \\text{otherwise} \\end{cases}$$",
        )
        .unwrap();
        assert!(!mathml.contains(" style="), "{mathml}");
        assert!(
            mathml.contains("<mtd class=\"tex-left tex-pad-right-0\">"),
            "{mathml}"
        );
        assert!(mathml.contains("tex-pad-left-1em"), "{mathml}");
        assert_eq!(
            without_inline_styles("<mtd style=\"color: red\">").unwrap_err(),
            "this needs the inline style `color: red`, which the site's \
             Content-Security-Policy blocks; give it a class in labtex and web/style.css"
        );
    }

    #[test]
    fn a_broken_formula_is_named_with_its_position() {
        let e = render("so $x + \\frac{a}{b$ here").unwrap_err();
        assert_eq!(e.formula, "x + \\frac{a}{b");
        assert!(e.at_char > 1, "{e:?}");
        let shown = e.to_string();
        assert!(
            shown.starts_with("LaTeX error at character ") && shown.contains("`x + \\frac{a}{b`"),
            "{shown}"
        );
        let e = render("$x + \\nosuchcommand y$").unwrap_err();
        assert_eq!(e.at_char, 5, "{e}");
        assert!(e.message.contains("nosuchcommand"), "{e}");
        assert_eq!(
            render_field("theory[2].formula", "$\\nosuchcommand$")
                .unwrap_err()
                .split(": LaTeX error at character 1")
                .next(),
            Some("theory[2].formula")
        );
    }

    #[test]
    fn unpaired_dollars_empty_formulas_and_hand_written_mathml_are_refused() {
        let e = render("costs $5 a month").unwrap_err();
        assert!(e.message.contains("not closed"), "{e}");
        let e = render("$$x = 1$ ").unwrap_err();
        assert!(e.message.contains("`$$` is not closed"), "{e}");
        assert!(render("a $$ b").is_err());
        let e = render("so <math><mi>x</mi></math>").unwrap_err();
        assert!(e.message.contains("LaTeX"), "{e}");
    }

    /// Issue 27 §3: `\live{key}{symbol}` wraps the symbol's MathML in a
    /// focusable `<mrow data-live="key">`, wherever the symbol sits (a
    /// subscript's base, inside brackets, under an accent).
    #[test]
    fn live_a_marked_symbol_is_a_focusable_mrow_naming_its_key() {
        assert_eq!(
            render("$x = \\live{l1}{L_1} \\cos \\live{t1}{\\theta_1}$").unwrap(),
            "<math><mi>x</mi><mo>=</mo>\
             <mrow data-live=\"l1\" tabindex=\"0\"><msub><mi>L</mi><mn>1</mn></msub></mrow>\
             <mo lspace=\"0.1667em\" rspace=\"0.1667em\">cos</mo>\
             <mrow data-live=\"t1\" tabindex=\"0\"><msub><mi>θ</mi><mn>1</mn></msub></mrow></math>"
        );
        let html = render(
            "$\\cos(\\live{t1}{\\theta_1} + \\live{t2}{\\theta_2})$ and $\\live{t1}{\\theta}_1^2$",
        )
        .unwrap();
        assert_eq!(live_keys(&html), vec!["t1", "t2", "t1"]);
        assert!(!html.contains("style"), "{html}");
        // The function name keeps its thin space before the marked symbol.
        assert_eq!(
            render("$\\cos\\live{t1}{\\theta_1}$").unwrap(),
            render("$\\cos\\theta_1$")
                .unwrap()
                .replace("<msub>", "<mrow data-live=\"t1\" tabindex=\"0\"><msub>")
                .replace("</msub>", "</msub></mrow>")
        );
        let dotted = render("$\\dot{\\live{de}{e}}$").unwrap();
        assert_eq!(live_keys(&dotted), vec!["de"]);
        assert_eq!(accents::non_portable(&dotted), Vec::<String>::new());
        // Sixteen and more marks in one formula keep their own keys.
        let many: String = (0..20).map(|i| format!("\\live{{k{i}}}{{x}}+")).collect();
        let html = render(&format!("${many}1$")).unwrap();
        let expected: Vec<String> = (0..20).map(|i| format!("k{i}")).collect();
        assert_eq!(live_keys(&html), expected);
    }

    /// A malformed mark is named with its position; an error after a mark
    /// is placed in the formula as written, not as rewritten.
    #[test]
    fn live_a_malformed_mark_is_refused_at_its_position() {
        for bad in [
            "$a + \\live{t 1}{x}$",
            "$a + \\live{}{x}$",
            "$a + \\live{t1} x$",
            "$a + \\live x$",
        ] {
            let e = render(bad).unwrap_err();
            assert_eq!(e.at_char, 5, "{bad}: {e}");
            assert!(e.message.contains("\\live{key}{symbol}"), "{e}");
        }
        let e = render("$\\live{t1}{\\theta_1} + \\nosuch$").unwrap_err();
        assert_eq!(e.at_char, 23, "{e}");
        assert!(e.message.contains("nosuch"), "{e}");
        assert_eq!(live_keys("<p>no marks</p>"), Vec::<&str>::new());
    }
}
