//! The page's own colours (ground, text, lines, focus) and its tones (good,
//! warning, bad), in both themes: written once here, held to `web/style.css`
//! by `tests/style_table.rs` and printed into the report's stylesheet.
//!
//! The scene's and plots' colours are the style table's
//! (`scene::style`); these are the colours around them.

use crate::scene::style::ThemeColour;

const fn colour(var: &'static str, light: &'static str, dark: &'static str) -> ThemeColour {
    ThemeColour { var, light, dark }
}

/// The page's ground (outside the panels).
pub const BG: ThemeColour = colour("--bg", "#f6f7f9", "#0f1216");
/// A panel's ground, and the report's paper.
pub const PANEL: ThemeColour = colour("--panel", "#ffffff", "#171b21");
/// Body text.
pub const TEXT: ThemeColour = colour("--text", "#1b1f24", "#e7eaee");
/// Secondary text: captions, hints.
pub const MUTED: ThemeColour = colour("--muted", "#5a6470", "#9aa4af");
/// Rules and borders.
pub const LINE: ThemeColour = colour("--line", "#d8dde3", "#2c333c");
/// Links, headings' rules, the primary button.
pub const ACCENT: ThemeColour = colour("--accent", "#0072B2", "#56B4E9");
/// Text on the accent.
pub const ACCENT_INK: ThemeColour = colour("--accent-ink", "#ffffff", "#0f1216");
/// The keyboard focus ring.
pub const FOCUS: ThemeColour = colour("--focus", "#E69F00", "#F0E442");
/// A good outcome: a right answer, a met goal.
pub const GOOD: ThemeColour = colour("--good", "#007a5a", "#4fd1a5");
/// A warning: a run that needs a look.
pub const WARN: ThemeColour = colour("--warn", "#a65a00", "#f0b450");
/// A bad outcome: a wrong answer, a failed run.
pub const BAD: ThemeColour = colour("--bad", "#b3261e", "#ff8a80");

/// Every page colour, in `web/style.css`'s order.
pub const PAGE: [ThemeColour; 11] = [
    BG, PANEL, TEXT, MUTED, LINE, ACCENT, ACCENT_INK, FOCUS, GOOD, WARN, BAD,
];

#[cfg(test)]
mod tests {
    use super::*;

    /// `#rrggbb` → linear-light relative luminance (WCAG 2).
    fn luminance(hex: &str) -> f64 {
        let channel = |i: usize| {
            let c = f64::from(u8::from_str_radix(&hex[i..i + 2], 16).unwrap()) / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        0.2126 * channel(1) + 0.7152 * channel(3) + 0.0722 * channel(5)
    }

    fn contrast(a: &str, b: &str) -> f64 {
        let (la, lb) = (luminance(a), luminance(b));
        (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
    }

    #[test]
    fn every_page_colour_is_a_hex_colour_with_its_own_property() {
        for (i, c) in PAGE.iter().enumerate() {
            assert!(c.var.starts_with("--"), "{}", c.var);
            for v in [c.light, c.dark] {
                assert!(v.len() == 7 && v.starts_with('#'), "{}: {v}", c.var);
                assert!(u32::from_str_radix(&v[1..], 16).is_ok(), "{}: {v}", c.var);
            }
            assert!(PAGE[i + 1..].iter().all(|o| o.var != c.var), "{}", c.var);
        }
    }

    /// The tones are text (a status, a verdict): each reads on its theme's
    /// panel at WCAG AA for normal text (4.5 : 1), and so do text and muted.
    #[test]
    fn tones_and_text_read_on_the_panel_in_both_themes() {
        for c in [TEXT, MUTED, GOOD, WARN, BAD] {
            let light = contrast(c.light, PANEL.light);
            let dark = contrast(c.dark, PANEL.dark);
            assert!(light >= 4.5, "{} light {light:.2}", c.var);
            assert!(dark >= 4.5, "{} dark {dark:.2}", c.var);
        }
    }
}
