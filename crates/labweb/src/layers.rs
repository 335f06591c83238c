//! Kept layers: pictures the page keeps between frames, so a frame pays for
//! what changed rather than for the whole scene (issue 16 §3).
//!
//! - A [`labcore::scene::SegmentLayer`], whatever its size, is drawn into an RGBA
//!   buffer that stays in wasm memory, with a coverage count per device
//!   pixel: drawing a segment adds one to each pixel of its Bresenham line,
//!   erasing subtracts one, and a pixel is lit while its count is positive.
//!   Each frame applies the layer's [`labcore::scene::LayerPlan`] (new slots,
//!   rewritten slots) or, when the layer, its epoch, the viewport, the canvas
//!   size, the device pixel ratio or the colour changed, redraws it from
//!   scratch. Counts make the result independent of the order of operations,
//!   so the kept picture is byte for byte the one a full redraw makes, which is
//!   the one [`labcore::Item::Segments`] makes today. Only the rectangle the
//!   frame touched is uploaded (`putImageData` with a dirty rectangle) into the
//!   layer's off-screen canvas, and the canvas is composited with one
//!   `drawImage`.
//! - A [`labcore::Item::VersionedRaster`] keeps its image in an off-screen
//!   canvas of one pixel per cell, rebuilt and uploaded only when its
//!   version, its size or its colours change; otherwise a frame is one
//!   scaled `drawImage`.
//!
//! [`counters`] counts the work (segments stroked and erased, full redraws,
//! uploads) so tests assert operations, never milliseconds.

use crate::palette::{hex_rgb, Palette};
use crate::viewport::{clip_segment, round_px, Viewport};
use glam::DVec2;
use labcore::scene::{LayerMark, LayerOp, SegmentLayer};
use labcore::RasterColour;
use std::cell::{Cell, RefCell};
use wasm_bindgen::JsCast;
use web_sys::{CanvasRenderingContext2d, HtmlCanvasElement};

/// Work done by kept layers since the last [`reset_counters`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Segments drawn into kept segment layers (a full redraw draws all).
    pub segments_drawn: u64,
    /// Segments erased from kept segment layers (rewired edges).
    pub segments_erased: u64,
    /// Kept segment layers redrawn from scratch (without coverage counts).
    pub full_redraws: u64,
    /// Kept segment layers redrawn from scratch with coverage counts, for
    /// an erase after a full redraw that did not count.
    pub recounts: u64,
    /// Uploads of segment-layer pixels to their canvas (`putImageData`).
    pub layer_uploads: u64,
    /// Pixels uploaded by those (the dirty rectangles' areas).
    pub layer_upload_px: u64,
    /// Versioned rasters rebuilt and uploaded.
    pub raster_uploads: u64,
    /// Kept pictures composited onto a canvas (`drawImage`).
    pub composites: u64,
    /// Backdrops painted into their kept picture.
    pub backdrop_draws: u64,
    /// Resizes of the off-screen canvas a blit goes through (each one
    /// reallocates it).
    pub blit_resizes: u64,
}

thread_local! {
    static COUNTERS: Cell<Counters> = const { Cell::new(Counters {
        segments_drawn: 0,
        segments_erased: 0,
        full_redraws: 0,
        recounts: 0,
        layer_uploads: 0,
        layer_upload_px: 0,
        raster_uploads: 0,
        composites: 0,
        backdrop_draws: 0,
        blit_resizes: 0,
    }) };
    static SEGMENT_CACHES: RefCell<Vec<SegmentCache>> = const { RefCell::new(Vec::new()) };
    static RASTER_CACHES: RefCell<Vec<RasterCache>> = const { RefCell::new(Vec::new()) };
    /// Drafts asked for ([`set_draft`]), and whether a layer was drawn as one.
    static DRAFT: Cell<(bool, bool)> = const { Cell::new((false, false)) };
}

/// Paints kept segment layers as drafts until set back ([`draft_dpr`]):
/// the scene of a timeline drag that is still moving, where every frame
/// shows another tree and redraws it in full.
pub(crate) fn set_draft(draft: bool) {
    DRAFT.with(|d| d.set((draft, false)));
}

/// Whether a layer was drawn as a draft since [`set_draft`] (the scene is
/// to be painted again, sharp, once the drag rests).
pub(crate) fn drafted() -> bool {
    DRAFT.with(|d| d.get().1)
}

/// The pixel ratio a kept segment layer is drawn at: the canvas's, or at
/// most 1 for a draft ([`set_draft`]). On a phone at DPR 2 a draft lights a
/// quarter of the pixels and its lines are one pixel wide: RRT*'s tree of
/// 4,000 edges redrawn for each position of a drag cost 11 ms of a 4×
/// throttled frame, nearly all of it per-pixel writes. The frame after the
/// drag rests draws it sharp again.
fn draft_dpr(dpr: f64) -> f64 {
    DRAFT.with(|d| match d.get() {
        (true, _) if dpr > 1.0 => {
            d.set((true, true));
            1.0
        }
        _ => dpr,
    })
}

/// The work counted since the last [`reset_counters`].
#[must_use]
pub fn counters() -> Counters {
    COUNTERS.with(Cell::get)
}

/// Sets every counter to zero.
pub fn reset_counters() {
    COUNTERS.with(|c| c.set(Counters::default()));
}

/// Drops every kept picture (the next frame redraws each layer in full).
pub fn forget_all() {
    SEGMENT_CACHES.with(|c| c.borrow_mut().clear());
    RASTER_CACHES.with(|c| c.borrow_mut().clear());
}

/// Adds to the counters: only in builds with the `bench-exports` feature
/// (the wasm tests and the browser benchmark); a shipped module counts
/// nothing, and carries no code for it.
pub(crate) fn count(f: impl FnOnce(&mut Counters)) {
    #[cfg(feature = "bench-exports")]
    COUNTERS.with(|c| {
        let mut v = c.get();
        f(&mut v);
        c.set(v);
    });
    #[cfg(not(feature = "bench-exports"))]
    let _ = f;
}

/// Segment layers kept at once (each holds a count and an RGBA value per
/// device pixel of its canvas, 8 bytes).
const KEPT_SEGMENT_LAYERS: usize = 2;
/// Versioned rasters kept at once.
const KEPT_RASTERS: usize = 3;

/// Everything besides the layer's own content that its kept picture depends on.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SegmentKey {
    viewport: Viewport,
    size: (usize, usize),
    dpr_bits: u64,
    pixel: [u8; 4],
    thick: bool,
}

struct SegmentCache {
    key: SegmentKey,
    mark: Option<LayerMark>,
    /// Coverage per device pixel; meaningful only while `counted`.
    counts: Vec<u32>,
    /// Whether `counts` hold the picture's coverage. A full redraw lights
    /// its pixels without counting (a scrub redraws in full every frame and
    /// never erases); the first plan that erases draws again, counting.
    counted: bool,
    rgba: Vec<u8>,
    canvas: HtmlCanvasElement,
    ctx: CanvasRenderingContext2d,
}

/// A detached canvas and its 2D context.
pub(crate) fn offscreen() -> Option<(HtmlCanvasElement, CanvasRenderingContext2d)> {
    let canvas: HtmlCanvasElement = crate::dom::document()
        .create_element("canvas")
        .ok()?
        .dyn_into()
        .ok()?;
    let ctx = canvas.get_context("2d").ok()??.dyn_into().ok()?;
    Some((canvas, ctx))
}

/// The kept picture of a scene's backdrop ([`labcore::Scene::backdrop`]):
/// the items a run does not move, painted once into an off-screen canvas
/// and composited with one `drawImage` while their key
/// ([`labcore::Scene::backdrop_key`]), the viewport, the canvas size, the
/// pixel ratio and the colours stay the same. A quiver of 300 force arrows
/// stroked at every frame cost about 7 ms of raster a frame on a
/// 4x-throttled phone.
///
/// While the key changes at every frame (a dragged obstacle), the frame
/// paints the backdrop directly and keeps nothing: a picture is made only
/// once the key has been the same for two frames in a row.
/// What a backdrop picture was drawn with: the backdrop's key, the
/// viewport, the size in device pixels, the pixel ratio's bits and the
/// palette's reading.
type BackdropDrawn = (u64, Viewport, (u32, u32), u64, u64);

#[derive(Default)]
pub struct Backdrop {
    key: Option<BackdropDrawn>,
    picture: Option<(HtmlCanvasElement, CanvasRenderingContext2d)>,
    drawn: bool,
}

impl Backdrop {
    /// Composites the kept picture of the backdrop fingerprinted by `key`
    /// onto `ctx` and returns true; `draw` paints the picture when it is
    /// missing. Returns false, having drawn nothing, when the backdrop
    /// changed since the last frame (the caller then paints the whole scene).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn composite(
        &mut self,
        ctx: &CanvasRenderingContext2d,
        key: u64,
        viewport: &Viewport,
        (css_w, css_h): (f64, f64),
        dpr: f64,
        palette: &Palette,
        draw: impl FnOnce(&CanvasRenderingContext2d),
    ) -> bool {
        let size = (
            (css_w * dpr).round().max(1.0) as u32,
            (css_h * dpr).round().max(1.0) as u32,
        );
        let key = (key, *viewport, size, dpr.to_bits(), palette.reading);
        if self.key != Some(key) {
            self.key = Some(key);
            self.drawn = false;
            return false;
        }
        if self.picture.is_none() {
            self.picture = offscreen();
        }
        let Some((canvas, pctx)) = &self.picture else {
            return false;
        };
        if !self.drawn {
            if canvas.width() != size.0 || canvas.height() != size.1 {
                canvas.set_width(size.0);
                canvas.set_height(size.1);
            }
            draw(pctx);
            self.drawn = true;
            count(|c| c.backdrop_draws += 1);
        }
        let _ = ctx.set_transform(1.0, 0.0, 0.0, 1.0, 0.0, 0.0);
        ctx.set_global_alpha(1.0);
        let _ = ctx.draw_image_with_html_canvas_element(canvas, 0.0, 0.0);
        count(|c| c.composites += 1);
        true
    }
}

/// A rectangle of device pixels touched this frame, inclusive bounds.
#[derive(Clone, Copy, Debug)]
struct Dirty {
    min: (i64, i64),
    max: (i64, i64),
}

impl Dirty {
    const EMPTY: Dirty = Dirty {
        min: (i64::MAX, i64::MAX),
        max: (i64::MIN, i64::MIN),
    };

    fn add(&mut self, x: i64, y: i64) {
        self.min = (self.min.0.min(x), self.min.1.min(y));
        self.max = (self.max.0.max(x), self.max.1.max(y));
    }

    /// `(x, y, width, height)` clipped to a `w` × `h` image, if not empty.
    fn rect(&self, w: usize, h: usize) -> Option<(usize, usize, usize, usize)> {
        let x0 = self.min.0.max(0);
        let y0 = self.min.1.max(0);
        let x1 = self.max.0.min(w as i64 - 1);
        let y1 = self.max.1.min(h as i64 - 1);
        (x0 <= x1 && y0 <= y1).then(|| {
            (
                x0 as usize,
                y0 as usize,
                (x1 - x0 + 1) as usize,
                (y1 - y0 + 1) as usize,
            )
        })
    }
}

/// `buffer` as `len` zeros, in place when it has that length already.
fn zeroed<T: Copy + Default>(buffer: &mut Vec<T>, len: usize) {
    if buffer.len() == len {
        buffer.fill(T::default());
    } else {
        *buffer = vec![T::default(); len];
    }
}

/// A coverage-counted RGBA image that segments are drawn into and erased from.
struct Coverage<'a> {
    counts: &'a mut [u32],
    rgba: &'a mut [u8],
    w: usize,
    h: usize,
    pixel: [u8; 4],
    thick: bool,
    /// Counting coverage (needed to erase); otherwise a draw only lights.
    counting: bool,
    dirty: Dirty,
}

impl Coverage<'_> {
    fn touch(&mut self, x: i64, y: i64, draw: bool) {
        if x < 0 || y < 0 || x as usize >= self.w || y as usize >= self.h {
            return;
        }
        let i = y as usize * self.w + x as usize;
        // One 4-byte store a pixel: `copy_from_slice` on a sub-slice was a
        // call with its own length check for every pixel of every line.
        let pixels = self.rgba.as_chunks_mut::<4>().0;
        if !self.counting {
            debug_assert!(draw, "an erase without coverage counts");
            pixels[i] = self.pixel;
            return;
        }
        let c = &mut self.counts[i];
        if draw {
            *c += 1;
            if *c == 1 {
                pixels[i] = self.pixel;
            }
        } else if *c > 0 {
            *c -= 1;
            if *c == 0 {
                pixels[i] = [0; 4];
            }
        }
    }

    /// Adds (or removes) the device pixels of segment `a`–`b` (device
    /// pixels), exactly the pixels the plain segment painter lights.
    fn segment(&mut self, a: DVec2, b: DVec2, draw: bool) {
        let Some((a, b)) = clip_segment(a, b, self.w as f64 - 1.0, self.h as f64 - 1.0) else {
            return;
        };
        // The line's bounding box, one pixel more right and down when thick.
        let grow = i64::from(self.thick);
        let ((ax, ay), (bx, by)) = (round_px(a), round_px(b));
        self.dirty.add(ax.min(bx), ay.min(by));
        self.dirty.add(ax.max(bx) + grow, ay.max(by) + grow);
        let thick = self.thick;
        labcore::bresenham::line((ax, ay), (bx, by), |x, y| {
            self.touch(x, y, draw);
            if thick {
                self.touch(x + 1, y, draw);
                self.touch(x, y + 1, draw);
            }
        });
    }
}

/// Lights in `rgba` (`w` × `h` pixels) the device pixels of each segment
/// (device pixels), as a kept layer's full redraw does: the plain painter of
/// a big batch of segments ([`crate::draw`]) and the kept layers share it.
pub(crate) fn light_segments(
    rgba: &mut [u8],
    (w, h): (usize, usize),
    pixel: [u8; 4],
    thick: bool,
    segments: impl IntoIterator<Item = (DVec2, DVec2)>,
) {
    let mut cover = Coverage {
        counts: &mut [],
        rgba,
        w,
        h,
        pixel,
        thick,
        counting: false,
        dirty: Dirty::EMPTY,
    };
    for (a, b) in segments {
        cover.segment(a, b, true);
    }
}

/// Paints a kept segment layer (see the module documentation) onto `ctx`, whose CSS size is
/// `css_w` × `css_h` at `dpr` device pixels per CSS pixel.
pub(crate) fn paint_segment_layer(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    colour: &str,
    layer: &SegmentLayer,
    width_px: f64,
    (css_w, css_h): (f64, f64),
    dpr: f64,
) {
    let dpr = draft_dpr(dpr);
    let w = (css_w * dpr).round().max(1.0) as usize;
    let h = (css_h * dpr).round().max(1.0) as usize;
    let [r, g, b] = hex_rgb(colour);
    let key = SegmentKey {
        viewport: *viewport,
        size: (w, h),
        dpr_bits: dpr.to_bits(),
        pixel: [r, g, b, 235],
        thick: (width_px * dpr).round() >= 2.0,
    };
    SEGMENT_CACHES.with(|caches| {
        let mut caches = caches.borrow_mut();
        let found = caches
            .iter()
            .position(|c| c.mark.is_some_and(|m| m.id == layer.id()));
        let mut cache = match found {
            Some(i) => caches.remove(i),
            None if caches.len() >= KEPT_SEGMENT_LAYERS => {
                // Reuse the least recently painted layer's buffers and canvas.
                let mut c = caches.pop().expect("a kept layer");
                c.mark = None;
                c
            }
            None => {
                let Some((canvas, octx)) = offscreen() else {
                    return;
                };
                SegmentCache {
                    key,
                    mark: None,
                    counts: Vec::new(),
                    counted: false,
                    rgba: Vec::new(),
                    canvas,
                    ctx: octx,
                }
            }
        };
        let since = cache.mark.filter(|_| cache.key == key);
        let mut plan = layer.plan(since.as_ref());
        let mut full = plan.is_full() || cache.rgba.len() != w * h * 4;
        let counting = if full {
            false
        } else if cache.counted || !plan.erases() {
            cache.counted
        } else {
            // An erase needs the counts the last full redraw skipped.
            plan = layer.plan(None);
            full = true;
            count(|c| c.recounts += 1);
            true
        };
        let mut dirty = Dirty::EMPTY;
        if full {
            // Zeroed as whole slices (one `memory.fill` each): `resize`
            // after `clear` wrote them element by element.
            zeroed(&mut cache.rgba, w * h * 4);
            if counting {
                zeroed(&mut cache.counts, w * h);
            } else {
                count(|c| c.full_redraws += 1);
            }
            if cache.canvas.width() != w as u32 || cache.canvas.height() != h as u32 {
                cache.canvas.set_width(w as u32);
                cache.canvas.set_height(h as u32);
            }
            dirty.add(0, 0);
            dirty.add(w as i64 - 1, h as i64 - 1);
        }
        cache.counted = counting;
        let (mut drawn, mut erased) = (0u64, 0u64);
        {
            let mut cover = Coverage {
                counts: &mut cache.counts,
                rgba: &mut cache.rgba,
                w,
                h,
                pixel: key.pixel,
                thick: key.thick,
                counting,
                dirty,
            };
            let to_px = |p: DVec2| viewport.to_px(p) * dpr;
            for op in plan.ops() {
                match op {
                    LayerOp::Draw((a, b)) => {
                        cover.segment(to_px(a), to_px(b), true);
                        drawn += 1;
                    }
                    LayerOp::Erase((a, b)) => {
                        cover.segment(to_px(a), to_px(b), false);
                        erased += 1;
                    }
                }
            }
            dirty = cover.dirty;
        }
        if let Some((x, y, dw, dh)) = dirty.rect(w, h) {
            // Only the dirty rows are copied out of wasm memory (the image
            // is built from a copy of its bytes): a frame that grows a tree
            // by a few edges copied the whole picture before.
            if let Ok(image) = web_sys::ImageData::new_with_u8_clamped_array_and_sh(
                wasm_bindgen::Clamped(&cache.rgba[y * w * 4..(y + dh) * w * 4]),
                w as u32,
                dh as u32,
            ) {
                let _ = cache
                    .ctx
                    .put_image_data_with_dirty_x_and_dirty_y_and_dirty_width_and_dirty_height(
                        &image, 0.0, y as f64, x as f64, 0.0, dw as f64, dh as f64,
                    );
                count(|c| {
                    c.layer_uploads += 1;
                    c.layer_upload_px += (dw * dh) as u64;
                });
            }
        }
        count(|c| {
            c.segments_drawn += drawn;
            c.segments_erased += erased;
            c.composites += 1;
        });
        cache.key = key;
        cache.mark = Some(layer.mark());
        ctx.set_image_smoothing_enabled(true);
        let _ = ctx.draw_image_with_html_canvas_element_and_dw_and_dh(
            &cache.canvas,
            0.0,
            0.0,
            css_w,
            css_h,
        );
        caches.insert(0, cache);
    });
}

/// The RGBA colour of each raster state (`states[s - 1]` for state `s`).
pub(crate) fn raster_lut(palette: &Palette, states: &[RasterColour]) -> Vec<[u8; 4]> {
    states
        .iter()
        .map(|s| {
            let [r, g, b] = hex_rgb(palette.colour(s.role));
            [r, g, b, (s.alpha.clamp(0.0, 1.0) * 255.0) as u8]
        })
        .collect()
}

/// Cells as an RGBA image, top row first (cell rows run bottom-up); state 0
/// and states without a colour are transparent.
pub(crate) fn raster_rgba(
    cells: &[u8],
    (cols, rows): (usize, usize),
    lut: &[[u8; 4]],
    rgba: &mut Vec<u8>,
) {
    rgba.clear();
    rgba.resize(cols * rows * 4, 0);
    let pixels = rgba.as_chunks_mut::<4>().0;
    for row in 0..rows {
        let out_row = &mut pixels[(rows - 1 - row) * cols..(rows - row) * cols];
        for (out, &state) in out_row.iter_mut().zip(&cells[row * cols..(row + 1) * cols]) {
            if let Some(c) = (state as usize).checked_sub(1).and_then(|i| lut.get(i)) {
                *out = *c;
            }
        }
    }
}

struct RasterCache {
    id: u64,
    version: u64,
    size: (usize, usize),
    lut: Vec<[u8; 4]>,
    canvas: HtmlCanvasElement,
    ctx: CanvasRenderingContext2d,
}

/// Paints a versioned raster (see the module documentation): its image is
/// rebuilt and uploaded only when `version`, the size or the colours change.
#[allow(clippy::too_many_arguments)]
pub(crate) fn paint_versioned_raster(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    palette: &Palette,
    (id, version): (u64, u64),
    min: DVec2,
    cell_m: f64,
    (cols, rows): (usize, usize),
    cells: &[u8],
    states: &[RasterColour],
) {
    if cols == 0 || rows == 0 || cells.len() < cols * rows {
        return;
    }
    let lut = raster_lut(palette, states);
    RASTER_CACHES.with(|caches| {
        let mut caches = caches.borrow_mut();
        let cache = match caches.iter().position(|c| c.id == id) {
            Some(i) => Some(caches.remove(i)),
            None if caches.len() >= KEPT_RASTERS => caches.pop(),
            None => None,
        };
        let mut cache = match cache {
            Some(mut c) => {
                if c.id != id {
                    // Another raster's canvas: nothing in it is fresh.
                    c.id = id;
                    c.size = (0, 0);
                }
                c
            }
            None => {
                let Some((canvas, octx)) = offscreen() else {
                    return;
                };
                RasterCache {
                    id,
                    version: 0,
                    size: (0, 0),
                    lut: Vec::new(),
                    canvas,
                    ctx: octx,
                }
            }
        };
        let fresh = cache.version == version && cache.size == (cols, rows) && cache.lut == lut;
        if !fresh {
            if cache.canvas.width() != cols as u32 || cache.canvas.height() != rows as u32 {
                cache.canvas.set_width(cols as u32);
                cache.canvas.set_height(rows as u32);
            }
            let mut rgba = Vec::new();
            raster_rgba(cells, (cols, rows), &lut, &mut rgba);
            if let Ok(image) = web_sys::ImageData::new_with_u8_clamped_array_and_sh(
                wasm_bindgen::Clamped(&rgba),
                cols as u32,
                rows as u32,
            ) {
                let _ = cache.ctx.put_image_data(&image, 0.0, 0.0);
            }
            cache.version = version;
            cache.size = (cols, rows);
            cache.lut = lut;
            count(|c| c.raster_uploads += 1);
        }
        let top_left = viewport.to_px(min + DVec2::new(0.0, rows as f64 * cell_m));
        let size = cell_m * viewport.scale_px_per_m;
        // Crisp cells: smoothing would smear them across boundaries.
        ctx.set_image_smoothing_enabled(false);
        let _ = ctx.draw_image_with_html_canvas_element_and_dw_and_dh(
            &cache.canvas,
            top_left.x,
            top_left.y,
            cols as f64 * size,
            rows as f64 * size,
        );
        count(|c| c.composites += 1);
        caches.insert(0, cache);
    });
}

#[cfg(test)]
mod tests {
    /// `draw.rs` paints kept layers through this module; this module and
    /// what it builds on (the palette, the viewport) must not reach back
    /// into `draw.rs`, or the two form an import circle (issue 25 §6).
    #[test]
    fn draw_and_layers_form_no_import_circle() {
        for (file, source) in [
            ("layers.rs", include_str!("layers.rs")),
            ("palette.rs", include_str!("palette.rs")),
            ("viewport.rs", include_str!("viewport.rs")),
        ] {
            let code: String = source
                .lines()
                .filter(|l| !l.trim_start().starts_with("//"))
                .collect::<Vec<_>>()
                .join("\n");
            // Spelt in two parts, so this test's own text is no match.
            for path in ["crate", "super", "labweb"] {
                let needle = format!("{path}::{}", "draw");
                assert!(!code.contains(&needle), "{file} names {needle}");
            }
        }
    }
}
