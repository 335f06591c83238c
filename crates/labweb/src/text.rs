//! Canvas text widths, measured once per font and text.
//!
//! `measureText` calls into the page's text shaper every time; the labels
//! of plots and scenes (tick values, axis titles, "1 m") repeat from frame to
//! frame, so their widths are kept. Only fonts the page owns are used
//! (`system-ui`, no web fonts that could load later and change a width).

use std::cell::RefCell;
use web_sys::CanvasRenderingContext2d;

/// Most widths kept; the cache starts over beyond this (a run of changing
/// numbers cannot grow it without bound).
pub const WIDTHS_MAX: usize = 2048;

/// Widths by font and text, sorted by both so that a lookup is a binary
/// search that does not allocate. A sorted list rather than a `HashMap`:
/// the hash table and its hasher were about 1 KB of every wasm module's
/// gzip bytes for a cache of at most [`WIDTHS_MAX`] short labels.
type Widths = Vec<(&'static str, String, f64)>;

thread_local! {
    static WIDTHS: RefCell<Widths> = const { RefCell::new(Vec::new()) };
}

/// Where `(font, text)` is, or would be inserted, in the sorted list.
fn find(widths: &Widths, font: &str, text: &str) -> Result<usize, usize> {
    widths.binary_search_by(|(f, t, _)| (*f, t.as_str()).cmp(&(font, text)))
}

/// The width of `text` in `font`, CSS px. `ctx`'s font must be `font`
/// (it measures a text not seen before). With no metrics, 7 px a byte.
pub fn width(ctx: &CanvasRenderingContext2d, font: &'static str, text: &str) -> f64 {
    let known = WIDTHS.with(|c| {
        let c = c.borrow();
        find(&c, font, text).ok().map(|i| c[i].2)
    });
    if let Some(w) = known {
        return w;
    }
    let w = ctx
        .measure_text(text)
        .map_or(7.0 * text.len() as f64, |m| m.width());
    WIDTHS.with(|c| {
        let mut c = c.borrow_mut();
        if c.len() >= WIDTHS_MAX {
            c.clear();
        }
        if let Err(i) = find(&c, font, text) {
            c.insert(i, (font, text.to_owned(), w));
        }
    });
    w
}

/// How many widths are kept now (tests).
#[must_use]
pub fn cached() -> usize {
    WIDTHS.with(|c| c.borrow().len())
}
