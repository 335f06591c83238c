//! The page's theme colours as the canvas paints them: each role's colour
//! read from the CSS custom property the style table names
//! ([`labcore::scene::style`]), so the canvas follows light and dark, more
//! contrast and forced colours as the rest of the page does.

use labcore::scene::style::{CANVAS, PLOT_BAND};
use labcore::{Role, SeriesRole};
use wasm_bindgen::JsCast;
use web_sys::Element;

/// Theme colours per role, read from CSS custom properties (`--c-link`, …).
#[derive(Clone, Debug)]
pub struct Palette {
    /// Each role's colour, at index `role as usize` ([`Role::ALL`]'s order).
    colours: Vec<String>,
    vars: Vec<(&'static str, String)>,
    pub background: String,
    /// The focus ring's colour: the page's focus outline (`--focus`).
    pub focus: String,
    /// Which reading of the CSS this is (each [`Palette::from_css`] takes
    /// the next number): kept pictures compare it instead of the colours.
    pub(crate) reading: u64,
}

thread_local! {
    static PALETTE_READINGS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// The theme colours the plots use besides the series' own.
const PLOT_EXTRA_VARS: [&str; 2] = [PLOT_BAND.var, "--muted"];

impl Palette {
    /// Reads the current theme from the computed style of `el`.
    pub fn from_css(el: &Element) -> Self {
        let style = crate::dom::window().get_computed_style(el).ok().flatten();
        let read = |var: &str, fallback: &str| {
            style
                .as_ref()
                .and_then(|s| s.get_property_value(var).ok())
                .map(|v| v.trim().to_owned())
                .filter(|v| !v.is_empty())
                .map(|v| resolve_colour(&v))
                .unwrap_or_else(|| fallback.to_owned())
        };
        // Plain loops: iterator adaptors here cost the module bytes.
        let mut colours = Vec::with_capacity(Role::ALL.len());
        for role in Role::ALL {
            colours.push(read(role.style().var(), "#888"));
        }
        let mut vars = Vec::with_capacity(SeriesRole::ALL.len() + PLOT_EXTRA_VARS.len());
        for role in SeriesRole::ALL {
            let var = role.style().colour.var;
            vars.push((var, read(var, "#888")));
        }
        for var in PLOT_EXTRA_VARS {
            vars.push((var, read(var, "#888")));
        }
        Self {
            colours,
            vars,
            background: read(CANVAS.var, "#fff"),
            focus: read("--focus", "#E69F00"),
            reading: PALETTE_READINGS.with(|n| {
                n.set(n.get() + 1);
                n.get()
            }),
        }
    }

    /// A plot's theme colour by its CSS custom property name: a series
    /// role's ([`SeriesRole::style`]), the band's or `--muted`.
    pub fn var(&self, name: &str) -> String {
        self.vars
            .iter()
            .find(|(v, _)| *v == name)
            .map_or_else(|| "#888".to_owned(), |(_, c)| c.clone())
    }

    /// The role's colour in the current theme.
    pub fn colour(&self, role: Role) -> &str {
        self.colours
            .get(role as usize)
            .map_or("#888", String::as_str)
    }
}

/// A theme colour as `#rrggbb`: hex as it is; anything else (a system colour
/// such as `CanvasText` under `forced-colors: active`, `rgb()`…) through a
/// probe element's computed colour, so the canvas and the raster tables get
/// the user's own colours.
fn resolve_colour(value: &str) -> String {
    if value.starts_with('#') {
        return value.to_owned();
    }
    let resolved = (|| {
        let doc = crate::dom::document();
        let probe: web_sys::HtmlElement = doc.create_element("span").ok()?.dyn_into().ok()?;
        let style = probe.style();
        style.set_property("color", value).ok()?;
        // The probe keeps the colour asked for (forced colours would repaint it).
        let _ = style.set_property("forced-color-adjust", "none");
        let _ = style.set_property("display", "none");
        doc.body()?.append_child(&probe).ok()?;
        let computed = crate::dom::window()
            .get_computed_style(&probe)
            .ok()
            .flatten()
            .and_then(|s| s.get_property_value("color").ok());
        probe.remove();
        rgb_to_hex(&computed?)
    })();
    resolved.unwrap_or_else(|| value.to_owned())
}

/// `rgb(12, 34, 56)` or `rgba(12, 34, 56, 1)` → `#0c2238`.
fn rgb_to_hex(css: &str) -> Option<String> {
    let inner = css.trim().split_once('(')?.1.strip_suffix(')')?;
    let parts: Vec<u8> = inner
        .split([',', ' ', '/'])
        .filter(|p| !p.is_empty())
        .take(3)
        .map(|p| {
            p.trim()
                .parse::<f64>()
                .ok()
                .map(|v| v.round().clamp(0.0, 255.0) as u8)
        })
        .collect::<Option<_>>()?;
    (parts.len() == 3).then(|| format!("#{:02x}{:02x}{:02x}", parts[0], parts[1], parts[2]))
}

/// `#rrggbb` → RGB; anything else gives a mid grey.
pub(crate) fn hex_rgb(colour: &str) -> [u8; 3] {
    let hex = colour.trim().trim_start_matches('#');
    let channel = |i: usize| {
        hex.get(i..i + 2)
            .and_then(|h| u8::from_str_radix(h, 16).ok())
    };
    match (hex.len(), channel(0), channel(2), channel(4)) {
        (6, Some(r), Some(g), Some(b)) => [r, g, b],
        _ => [136, 136, 136],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn computed_colours_become_hex_for_the_raster_tables() {
        assert_eq!(rgb_to_hex("rgb(12, 34, 56)").as_deref(), Some("#0c2238"));
        assert_eq!(
            rgb_to_hex("rgba(255, 255, 255, 1)").as_deref(),
            Some("#ffffff")
        );
        assert_eq!(
            rgb_to_hex("rgb(0 128 255 / 0.5)").as_deref(),
            Some("#0080ff")
        );
        assert_eq!(rgb_to_hex("CanvasText"), None);
        assert_eq!(rgb_to_hex("rgb(1, 2)"), None);
    }
}
