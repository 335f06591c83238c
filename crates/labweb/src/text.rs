//! Canvas text widths, measured once per font and text.
//!
//! `measureText` calls into the page's text shaper every time; the labels
//! of plots and scenes (tick values, axis titles, "1 m") repeat from frame to
//! frame, so their widths are kept. Only fonts the page owns are used
//! (`system-ui`, no web fonts that could load later and change a width).

use std::cell::RefCell;
use std::collections::HashMap;
use web_sys::CanvasRenderingContext2d;

/// Most widths kept; the cache starts over beyond this (a run of changing
/// numbers cannot grow it without bound).
pub const WIDTHS_MAX: usize = 2048;

/// Widths by font, then by text (looked up without allocating).
type Widths = Vec<(&'static str, HashMap<String, f64>)>;

thread_local! {
    static WIDTHS: RefCell<Widths> = const { RefCell::new(Vec::new()) };
}

/// The width of `text` in `font`, CSS px. `ctx`'s font must be `font`
/// (it measures a text not seen before). With no metrics, 7 px a byte.
pub fn width(ctx: &CanvasRenderingContext2d, font: &'static str, text: &str) -> f64 {
    let known = WIDTHS.with(|c| {
        c.borrow()
            .iter()
            .find(|(f, _)| *f == font)
            .and_then(|(_, m)| m.get(text).copied())
    });
    if let Some(w) = known {
        return w;
    }
    let w = ctx
        .measure_text(text)
        .map_or(7.0 * text.len() as f64, |m| m.width());
    WIDTHS.with(|c| {
        let mut c = c.borrow_mut();
        if c.iter().map(|(_, m)| m.len()).sum::<usize>() >= WIDTHS_MAX {
            c.clear();
        }
        let i = match c.iter().position(|(f, _)| *f == font) {
            Some(i) => i,
            None => {
                c.push((font, HashMap::new()));
                c.len() - 1
            }
        };
        c[i].1.insert(text.to_owned(), w);
    });
    w
}

/// How many widths are kept now (tests).
#[must_use]
pub fn cached() -> usize {
    WIDTHS.with(|c| c.borrow().iter().map(|(_, m)| m.len()).sum())
}
