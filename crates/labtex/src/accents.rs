//! Accents over a letter (θ̇, θ̈, μ̄, x̂) in the one MathML form that Chromium,
//! Firefox and WebKit all draw above their letter.
//!
//! A converter (math-core among them) writes an accent the usual way,
//! `<mover><mi>θ</mi><mo>˙</mo></mover>`. WebKit
//! (WebKitGTK 2.50, Safari's engine) lays out a non-stretchy `<mo>` over a
//! base by its font box, not its ink: the dot lands well above and to the
//! left of the θ and lifts a superscript with it (θ̇² reads "θ ·2"), with or
//! without a math font. A *stretchy* `<mo>` is laid out by its ink and sits
//! right in all three engines, so every accent becomes
//!
//! ```text
//! <mover accent="true"><mi>θ</mi><mo stretchy="true">˙</mo></mover>   dot   U+02D9
//! <mover accent="true"><mi>θ</mi><mo stretchy="true">¨</mo></mover>   ddot  U+00A8
//! <mover accent="true"><mi>x</mi><mo stretchy="true">^</mo></mover>   hat   U+005E
//! <mover accent="true"><mi>μ</mi><mo stretchy="true" lspace="0" rspace="0">−</mo></mover>   bar U+2212
//! ```
//!
//! The bar is a minus sign: WebKit stretches a macron (U+00AF, U+0304,
//! U+0305) but still places it by its font box, and draws no overline
//! (U+203E, U+02C9) at all; a minus sign with no operator spacing sits on the
//! letter in all three. Compared by screenshots in `tests/e2e/browsers.test.mjs`
//! (with no math font, TeX Gyre DejaVu Math and Latin Modern Math).
//!
//! [`crate::render`] applies [`portable`] to every formula it writes, so the
//! reading pages and the quiz text in the wasm modules carry only this form.

/// The accent characters an author or converter writes, each with the one
/// the portable form uses.
const ACCENTS: [(char, Accent); 13] = [
    ('\u{02D9}', Accent::Dot),
    ('\u{0307}', Accent::Dot),
    ('\u{00A8}', Accent::DoubleDot),
    ('\u{0308}', Accent::DoubleDot),
    ('\u{00AF}', Accent::Bar),
    ('\u{0304}', Accent::Bar),
    ('\u{0305}', Accent::Bar),
    ('\u{02C9}', Accent::Bar),
    ('\u{203E}', Accent::Bar),
    ('\u{2212}', Accent::Bar),
    ('^', Accent::Hat),
    ('\u{02C6}', Accent::Hat),
    ('\u{0302}', Accent::Hat),
];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Accent {
    Dot,
    DoubleDot,
    Bar,
    Hat,
}

impl Accent {
    /// The over-script in the portable form.
    fn mo(self) -> &'static str {
        match self {
            Accent::Dot => "<mo stretchy=\"true\">\u{02D9}</mo>",
            Accent::DoubleDot => "<mo stretchy=\"true\">\u{00A8}</mo>",
            Accent::Hat => "<mo stretchy=\"true\">^</mo>",
            Accent::Bar => "<mo stretchy=\"true\" lspace=\"0\" rspace=\"0\">\u{2212}</mo>",
        }
    }
}

/// The opening tag of an accent in the portable form.
const OPEN: &str = "<mover accent=\"true\">";

/// `markup` with every accent `<mover>` (an over-script that is one `<mo>`
/// holding one accent character) in the portable form; everything else is
/// left as it is. Idempotent.
#[must_use]
pub fn portable(markup: &str) -> String {
    // (start, end, replacement) of each piece to replace, in order.
    let mut edits: Vec<(usize, usize, &'static str)> = Vec::new();
    // Start and end of each open `<mover…>` tag.
    let mut open: Vec<(usize, usize)> = Vec::new();
    let mut at = 0;
    while let Some(found) = markup[at..].find("<mover") {
        let tag_start = at + found;
        let close_start = markup[at..].find("</mover>").map(|i| at + i);
        // A closing tag comes first: it ends the innermost open mover.
        if let Some(close) = close_start.filter(|&c| c < tag_start) {
            finish(markup, close, &mut open, &mut edits);
            at = close + "</mover>".len();
            continue;
        }
        let Some(tag_len) = markup[tag_start..].find('>') else {
            break;
        };
        let tag_end = tag_start + tag_len + 1;
        let name_end = tag_start + "<mover".len();
        // `<moverfoo>` is another element; `<mover/>` closes itself.
        let next = markup[name_end..].chars().next();
        if matches!(next, Some('>' | ' ')) && !markup[..tag_end].ends_with("/>") {
            open.push((tag_start, tag_end));
        }
        at = tag_end;
    }
    while let Some(found) = markup[at..].find("</mover>") {
        let close = at + found;
        finish(markup, close, &mut open, &mut edits);
        at = close + "</mover>".len();
    }
    edits.sort_by_key(|e| e.0);
    let mut out = String::with_capacity(markup.len() + edits.len() * 24);
    let mut from = 0;
    for (start, end, replacement) in edits {
        out.push_str(&markup[from..start]);
        out.push_str(replacement);
        from = end;
    }
    out.push_str(&markup[from..]);
    out
}

/// At a `</mover>` starting at `close`: if the innermost open mover's
/// over-script is an accent `<mo>`, records the two edits that make it
/// portable.
fn finish(
    markup: &str,
    close: usize,
    open: &mut Vec<(usize, usize)>,
    edits: &mut Vec<(usize, usize, &'static str)>,
) {
    let Some((tag_start, tag_end)) = open.pop() else {
        return;
    };
    let body = &markup[..close];
    let Some(mo_start) = body.rfind("<mo") else {
        return;
    };
    if mo_start < tag_end {
        return;
    }
    let Some(text_start) = body[mo_start..].find('>').map(|i| mo_start + i + 1) else {
        return;
    };
    let Some(text) = body[text_start..].strip_suffix("</mo>") else {
        return;
    };
    let mut chars = text.trim().chars();
    let (Some(c), None) = (chars.next(), chars.next()) else {
        return;
    };
    let Some(&(_, accent)) = ACCENTS.iter().find(|(a, _)| *a == c) else {
        return;
    };
    // Only the second child: the base must end before the `<mo>` begins, so
    // the `<mo>` is not inside it (a base that is itself a lone `<mo>` is
    // not an accent case worth guessing at).
    if !body[tag_end..mo_start].trim_end().ends_with('>') {
        return;
    }
    edits.push((tag_start, tag_end, OPEN));
    edits.push((mo_start, close, accent.mo()));
}

/// The accents in `markup` that are not in the portable form, each as the
/// `<mover>…</mover>` source text (at most 80 characters of it). Used by
/// the tests that keep the old form from coming back.
#[must_use]
pub fn non_portable(markup: &str) -> Vec<String> {
    let fixed = portable(markup);
    if fixed == markup {
        return Vec::new();
    }
    let mut found = Vec::new();
    let mut at = 0;
    while let Some(i) = markup[at..].find("<mover") {
        let start = at + i;
        let end = markup[start..]
            .find("</mover>")
            .map_or(markup.len(), |j| start + j + "</mover>".len());
        let piece = &markup[start..end];
        if portable(piece) != piece {
            found.push(piece.chars().take(80).collect());
        }
        at = start + "<mover".len();
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dot_over_theta_becomes_a_stretchy_accent() {
        assert_eq!(
            portable("<math><mover><mi>θ</mi><mo>˙</mo></mover></math>"),
            "<math><mover accent=\"true\"><mi>θ</mi><mo stretchy=\"true\">˙</mo></mover></math>"
        );
    }

    #[test]
    fn every_accent_character_maps_to_its_portable_form() {
        for (c, accent) in ACCENTS {
            let before = format!("<mover><mi>x</mi><mo>{c}</mo></mover>");
            assert_eq!(
                portable(&before),
                format!("{OPEN}<mi>x</mi>{}</mover>", accent.mo()),
                "{c:?}"
            );
        }
    }

    #[test]
    fn the_portable_form_is_left_as_it_is() {
        let once = portable(
            "<msup><mover><mi>θ</mi><mo>˙</mo></mover><mn>2</mn></msup><mover><mi>P</mi><mo>¯</mo></mover>",
        );
        assert_eq!(portable(&once), once);
        assert!(non_portable(&once).is_empty());
    }

    #[test]
    fn nested_accents_and_other_movers() {
        // A bar over a dotted x: both accents.
        assert_eq!(
            portable("<mover><mover><mi>x</mi><mo>˙</mo></mover><mo>¯</mo></mover>"),
            format!(
                "{OPEN}{OPEN}<mi>x</mi>{}</mover>{}</mover>",
                Accent::Dot.mo(),
                Accent::Bar.mo()
            )
        );
        // An over-script that is not an accent is left alone (a limit, an arrow label).
        let limit =
            "<mover><mo>→</mo><mtext>def</mtext></mover><mover><mi>x</mi><mo>→</mo></mover>";
        assert_eq!(portable(limit), limit);
        // Text without MathML, and an unclosed mover, pass through.
        assert_eq!(portable("a < b and c > d"), "a < b and c > d");
        assert_eq!(portable("<mover><mi>x</mi>"), "<mover><mi>x</mi>");
    }

    #[test]
    fn non_portable_names_the_accents_left_in_the_old_form() {
        let markup = "<mover><mi>θ</mi><mo>˙</mo></mover> and <mover accent=\"true\"><mi>x</mi><mo stretchy=\"true\">^</mo></mover>";
        assert_eq!(
            non_portable(markup),
            vec!["<mover><mi>θ</mi><mo>˙</mo></mover>".to_string()]
        );
    }
}
