//! Paints a [`Scene`] on a 2D canvas.
//!
//! World coordinates (metres, y up) map to CSS pixels with one uniform scale
//! that fits the experiment's [`ViewBox`] into the canvas; the backing store
//! is `devicePixelRatio` times larger so lines stay crisp.

use crate::palette::hex_rgb;
pub use crate::palette::Palette;
use crate::viewport::nearest_px;
pub use crate::viewport::Viewport;
use glam::DVec2;
use labcore::layout::arrow::arrow_head;
use labcore::layout::scale_bar::{ScaleBar, SCALE_BAR_MAX_PX};
use labcore::math;
use labcore::scene::style;
use labcore::{Item, RasterColour, Role, Scene};
use std::f64::consts::TAU;
use wasm_bindgen::JsValue;
use web_sys::CanvasRenderingContext2d;

fn set_dash(ctx: &CanvasRenderingContext2d, dashed: bool) {
    // The two patterns are built once: a new array (and a call per entry)
    // for every line cost 0.2 ms of a workspace scrub frame.
    thread_local! {
        static PATTERNS: [js_sys::Array; 2] = [
            js_sys::Array::new(),
            style::DASH_PX.iter().map(|&d| JsValue::from_f64(d)).collect(),
        ];
    }
    PATTERNS.with(|p| {
        let _ = ctx.set_line_dash(&p[usize::from(dashed)]);
    });
}

/// The font of scene labels.
const LABEL_FONT: &str = "600 13px system-ui, sans-serif";

/// Paints `scene` into a canvas of `width_px` × `height_px` CSS pixels whose
/// backing store is `dpr` times larger.
pub fn paint(
    ctx: &CanvasRenderingContext2d,
    scene: &Scene,
    viewport: &Viewport,
    width_px: f64,
    height_px: f64,
    dpr: f64,
    palette: &Palette,
) {
    paint_items(
        ctx,
        &scene.items,
        viewport,
        width_px,
        height_px,
        dpr,
        palette,
        true,
    );
}

/// As [`paint`], keeping the picture of the scene's backdrop
/// ([`Scene::backdrop`]) in `backdrop` between frames: while its key
/// ([`Scene::backdrop_key`]) stays the same, a frame composites that picture
/// and paints only the items after it. The pixels are those [`paint`] gives.
#[allow(clippy::too_many_arguments)]
pub fn paint_with_backdrop(
    ctx: &CanvasRenderingContext2d,
    scene: &Scene,
    viewport: &Viewport,
    width_px: f64,
    height_px: f64,
    dpr: f64,
    palette: &Palette,
    backdrop: &mut crate::layers::Backdrop,
) {
    let split = scene.backdrop.min(scene.items.len());
    let (below, above) = scene.items.split_at(split);
    let kept = split > 0
        && backdrop.composite(
            ctx,
            scene.backdrop_key,
            viewport,
            (width_px, height_px),
            dpr,
            palette,
            |bctx| {
                paint_items(
                    bctx, below, viewport, width_px, height_px, dpr, palette, true,
                );
            },
        );
    if kept {
        paint_items(
            ctx, above, viewport, width_px, height_px, dpr, palette, false,
        );
    } else {
        paint(ctx, scene, viewport, width_px, height_px, dpr, palette);
    }
}

/// Paints the parts of the scene tagged `key` as a halo over the picture
/// (issue 27 §3): a wide translucent band, then a dashed line between two of
/// the background's, in the focus colour; a single point gets a dashed ring.
/// More than colour: the shape is thicker, outlined and dashed.
pub fn paint_tags(
    ctx: &CanvasRenderingContext2d,
    tags: &[labcore::scene::Tag],
    key: &str,
    viewport: &Viewport,
    palette: &Palette,
    dpr: f64,
) {
    let _ = ctx.set_transform(dpr, 0.0, 0.0, dpr, 0.0, 0.0);
    for (colour, width, alpha, dashed) in [
        (&palette.focus, 16.0, 0.45, false),
        (&palette.background, 7.0, 1.0, false),
        (&palette.focus, 4.0, 1.0, true),
    ] {
        ctx.set_global_alpha(alpha);
        ctx.set_stroke_style_str(colour);
        ctx.set_line_width(width);
        set_dash(ctx, dashed);
        ctx.begin_path();
        for tag in tags.iter().filter(|t| t.key == key) {
            if let [p] = tag.points[..] {
                let c = viewport.to_px(p);
                ctx.move_to(c.x + 14.0, c.y);
                let _ = ctx.arc(c.x, c.y, 14.0, 0.0, TAU);
            } else {
                for (i, p) in tag.points.iter().enumerate() {
                    let q = viewport.to_px(*p);
                    if i == 0 {
                        ctx.move_to(q.x, q.y);
                    } else {
                        ctx.line_to(q.x, q.y);
                    }
                }
            }
        }
        ctx.stroke();
    }
    ctx.set_global_alpha(1.0);
}

/// Paints `items` (over the background when `background`) into a canvas of
/// `width_px` × `height_px` CSS pixels at `dpr` device pixels per CSS pixel.
#[allow(clippy::too_many_arguments)]
fn paint_items(
    ctx: &CanvasRenderingContext2d,
    items: &[Item],
    viewport: &Viewport,
    width_px: f64,
    height_px: f64,
    dpr: f64,
    palette: &Palette,
    background: bool,
) {
    let _ = ctx.set_transform(dpr, 0.0, 0.0, dpr, 0.0, 0.0);
    if background {
        ctx.set_fill_style_str(&palette.background);
        ctx.fill_rect(0.0, 0.0, width_px, height_px);
    }
    ctx.set_line_cap("round");
    ctx.set_line_join("round");
    let mut canvas = Canvas {
        ctx,
        viewport,
        palette,
        size: (width_px, height_px),
        dpr,
        label_font: false,
    };
    for item in items {
        ctx.set_global_alpha(1.0);
        canvas.item(item);
    }
    ctx.set_global_alpha(1.0);
}

/// One paint's canvas and what its items are drawn with.
struct Canvas<'a> {
    ctx: &'a CanvasRenderingContext2d,
    viewport: &'a Viewport,
    palette: &'a Palette,
    /// CSS pixels.
    size: (f64, f64),
    /// Device pixels per CSS pixel.
    dpr: f64,
    /// Whether the context's font and baseline are the labels' (the scale
    /// bar and the off-view marks set their own).
    label_font: bool,
}

impl Canvas<'_> {
    fn colour(&self, role: Role) -> &str {
        self.palette.colour(role)
    }

    /// One item of the display list, by its kind.
    fn item(&mut self, item: &Item) {
        let (ctx, viewport, palette) = (self.ctx, self.viewport, self.palette);
        match item {
            Item::Line {
                from,
                to,
                width_px,
                role,
                dashed,
            } => self.line(*from, *to, *width_px, *role, *dashed),
            Item::Circle {
                center,
                radius_m,
                role,
                fill,
                dashed,
            } => self.circle(*center, *radius_m, *role, *fill, *dashed),
            Item::Dot {
                center,
                radius_px,
                role,
            } => self.dot(*center, *radius_px, *role),
            Item::Points {
                points,
                radius_px,
                role,
            } => self.points(points, *radius_px, *role),
            Item::Ellipse {
                center,
                semi_axis_a,
                semi_axis_b,
                role,
            } => self.ellipse(*center, *semi_axis_a, *semi_axis_b, *role),
            Item::Label {
                pos,
                text,
                role,
                offset_px,
            } => self.label(*pos, *offset_px, text, *role),
            Item::Polyline {
                points,
                width_px,
                role,
                dashed,
                closed,
            } => self.polyline(points, *width_px, *role, *dashed, *closed),
            Item::Polygon { points, role } => self.polygon(points, *role),
            Item::Rect {
                min,
                max,
                role,
                fill,
            } => self.rect(*min, *max, *role, *fill),
            Item::Arrow {
                from,
                to,
                width_px,
                role,
            } => self.arrows(&[(*from, *to)], *width_px, *role),
            Item::Arrows {
                arrows,
                width_px,
                role,
            } => self.arrows(arrows, *width_px, *role),
            Item::Heatmap { .. }
            | Item::Segments { .. }
            | Item::SegmentLayer { .. }
            | Item::VersionedRaster { .. }
            | Item::Raster { .. } => self.image(item),
            Item::ScaleBar => {
                paint_scale_bar(ctx, viewport, palette, self.size.1);
                self.label_font = false;
            }
            Item::OffView { at, label, role } => {
                paint_off_view(ctx, viewport, palette, self.size, *at, label, *role);
                self.label_font = false;
            }
            Item::FocusRing { center, radius_px } => self.focus_ring(*center, *radius_px),
        }
    }

    /// The items painted as images or pixel by pixel: heat maps, rasters
    /// and segment batches (big ones in wasm, kept ones in their layer).
    fn image(&self, item: &Item) {
        let (ctx, viewport, palette, dpr) = (self.ctx, self.viewport, self.palette, self.dpr);
        match item {
            Item::Heatmap {
                min,
                cell_m,
                cols,
                rows,
                values,
                role,
            } => paint_heatmap(
                ctx,
                viewport,
                self.colour(*role),
                *min,
                *cell_m,
                *cols,
                *rows,
                values,
            ),
            Item::Segments {
                segments,
                width_px,
                role,
            } if segments.len() >= RASTER_SEGMENTS_MIN => paint_segments_raster(
                ctx,
                viewport,
                self.colour(*role),
                segments,
                *width_px,
                self.size,
                dpr,
            ),
            Item::Segments {
                segments,
                width_px,
                role,
            } => stroke_segments(ctx, viewport, self.colour(*role), segments, *width_px),
            // Kept whatever its size: a frame draws only the new and rewired
            // edges. Stroked as a path, a tree of 3,000 edges cost about 40 ms
            // of raster a frame on a 4x-throttled phone, and a tree grows
            // through that size in its first seconds.
            Item::SegmentLayer {
                layer,
                width_px,
                role,
            } => crate::layers::paint_segment_layer(
                ctx,
                viewport,
                self.colour(*role),
                layer,
                *width_px,
                self.size,
                dpr,
            ),
            Item::VersionedRaster {
                id,
                version,
                min,
                cell_m,
                cols,
                rows,
                cells,
                palette: states,
            } => crate::layers::paint_versioned_raster(
                ctx,
                viewport,
                palette,
                (*id, *version),
                *min,
                *cell_m,
                (*cols, *rows),
                cells,
                states,
            ),
            Item::Raster {
                min,
                cell_m,
                cols,
                rows,
                cells,
                palette: states,
            } => paint_raster(
                ctx,
                viewport,
                palette,
                *min,
                *cell_m,
                (*cols, *rows),
                cells,
                states,
            ),
            _ => {}
        }
    }

    fn line(&self, from: DVec2, to: DVec2, width_px: f64, role: Role, dashed: bool) {
        let ctx = self.ctx;
        let (a, b) = (self.viewport.to_px(from), self.viewport.to_px(to));
        ctx.set_stroke_style_str(self.colour(role));
        ctx.set_line_width(width_px);
        set_dash(ctx, dashed);
        let opacity = role.style().line_opacity;
        if opacity < 1.0 {
            ctx.set_global_alpha(opacity);
        }
        ctx.begin_path();
        ctx.move_to(a.x, a.y);
        ctx.line_to(b.x, b.y);
        ctx.stroke();
    }

    fn circle(&self, center: DVec2, radius_m: f64, role: Role, fill: bool, dashed: bool) {
        let ctx = self.ctx;
        let c = self.viewport.to_px(center);
        let r = radius_m * self.viewport.scale_px_per_m;
        ctx.begin_path();
        let _ = ctx.arc(c.x, c.y, r.max(0.0), 0.0, TAU);
        if fill {
            ctx.set_fill_style_str(self.colour(role));
            ctx.set_global_alpha(style::FILL_OPACITY_LIGHT);
            ctx.fill();
        } else {
            ctx.set_stroke_style_str(self.colour(role));
            ctx.set_line_width(style::OUTLINE_PX);
            set_dash(ctx, dashed);
            ctx.stroke();
        }
    }

    fn dot(&self, center: DVec2, radius_px: f64, role: Role) {
        let ctx = self.ctx;
        let c = self.viewport.to_px(center);
        ctx.begin_path();
        let _ = ctx.arc(c.x, c.y, radius_px, 0.0, TAU);
        ctx.set_fill_style_str(self.colour(role));
        ctx.fill();
        ctx.set_line_width(style::OUTLINE_PX);
        ctx.set_stroke_style_str(&self.palette.background);
        set_dash(ctx, false);
        ctx.stroke();
    }

    fn points(&self, points: &[DVec2], radius_px: f64, role: Role) {
        let ctx = self.ctx;
        if points.len() >= RASTER_SEGMENTS_MIN {
            paint_points_raster(
                ctx,
                self.viewport,
                self.colour(role),
                points,
                radius_px,
                self.size,
            );
            return;
        }
        ctx.set_fill_style_str(self.colour(role));
        ctx.set_global_alpha(style::POINTS_OPACITY);
        ctx.begin_path();
        let d = radius_px * 2.0;
        for p in points {
            let c = self.viewport.to_px(*p);
            ctx.rect(c.x - radius_px, c.y - radius_px, d, d);
        }
        ctx.fill();
    }

    fn ellipse(&self, center: DVec2, semi_axis_a: DVec2, semi_axis_b: DVec2, role: Role) {
        let ctx = self.ctx;
        let c = self.viewport.to_px(center);
        let ra = semi_axis_a.length() * self.viewport.scale_px_per_m;
        let rb = semi_axis_b.length() * self.viewport.scale_px_per_m;
        // Screen y is flipped, so the rotation angle changes sign.
        let rotation = -math::atan2(semi_axis_a.y, semi_axis_a.x);
        ctx.begin_path();
        let _ = ctx.ellipse(c.x, c.y, ra.max(0.5), rb.max(0.5), rotation, 0.0, TAU);
        ctx.set_fill_style_str(self.colour(role));
        ctx.set_global_alpha(style::FILL_OPACITY_LIGHT);
        ctx.fill();
        ctx.set_global_alpha(1.0);
        ctx.set_stroke_style_str(self.colour(role));
        ctx.set_line_width(style::OUTLINE_PX);
        set_dash(ctx, false);
        ctx.stroke();
    }

    fn label(&mut self, pos: DVec2, offset_px: DVec2, text: &str, role: Role) {
        let ctx = self.ctx;
        let (width_px, height_px) = self.size;
        let c = self.viewport.to_px(pos) + offset_px;
        // The font is set once a paint (setting it parses it).
        if !self.label_font {
            ctx.set_font(LABEL_FONT);
            ctx.set_text_baseline("middle");
            self.label_font = true;
        }
        let text_w = crate::text::width(ctx, LABEL_FONT, text);
        // Keep labels inside the canvas.
        let x = c.x.min(width_px - text_w - 4.0).max(4.0);
        let y = c.y.clamp(10.0, height_px - 10.0);
        ctx.set_line_width(style::LABEL_HALO_PX);
        ctx.set_stroke_style_str(&self.palette.background);
        set_dash(ctx, false);
        let _ = ctx.stroke_text(text, x, y);
        ctx.set_fill_style_str(self.colour(role));
        let _ = ctx.fill_text(text, x, y);
    }

    fn polyline(&self, points: &[DVec2], width_px: f64, role: Role, dashed: bool, closed: bool) {
        if points.len() < 2 {
            return;
        }
        let ctx = self.ctx;
        trace_polyline(ctx, self.viewport, points, closed);
        ctx.set_stroke_style_str(self.colour(role));
        ctx.set_line_width(width_px);
        set_dash(ctx, dashed);
        ctx.stroke();
    }

    fn polygon(&self, points: &[DVec2], role: Role) {
        if points.len() < 3 {
            return;
        }
        trace_polyline(self.ctx, self.viewport, points, true);
        fill_and_outline(self.ctx, self.colour(role));
    }

    fn rect(&self, min: DVec2, max: DVec2, role: Role, fill: bool) {
        let ctx = self.ctx;
        let (a, b) = (self.viewport.to_px(min), self.viewport.to_px(max));
        ctx.begin_path();
        ctx.rect(
            a.x.min(b.x),
            a.y.min(b.y),
            (b.x - a.x).abs(),
            (b.y - a.y).abs(),
        );
        if fill {
            fill_and_outline(ctx, self.colour(role));
        } else {
            ctx.set_stroke_style_str(self.colour(role));
            ctx.set_line_width(style::OUTLINE_PX);
            set_dash(ctx, false);
            ctx.stroke();
        }
    }

    /// Arrows of one role as one path, one stroke.
    fn arrows(&self, arrows: &[(DVec2, DVec2)], width_px: f64, role: Role) {
        let ctx = self.ctx;
        ctx.begin_path();
        for (from, to) in arrows {
            let (a, b) = (self.viewport.to_px(*from), self.viewport.to_px(*to));
            trace_arrow(ctx, a, b, width_px);
        }
        ctx.set_stroke_style_str(self.colour(role));
        ctx.set_line_width(width_px);
        set_dash(ctx, false);
        ctx.stroke();
    }

    /// A 3 px ring in the focus colour between two thin lines of the
    /// background, so it shows on any colour under it.
    fn focus_ring(&self, center: DVec2, radius_px: f64) {
        let ctx = self.ctx;
        let c = self.viewport.to_px(center);
        set_dash(ctx, false);
        for (colour, width, r) in [
            (self.palette.background.as_str(), 1.5, radius_px - 2.25),
            (self.palette.background.as_str(), 1.5, radius_px + 2.25),
            (self.palette.focus.as_str(), 3.0, radius_px),
        ] {
            ctx.set_stroke_style_str(colour);
            ctx.set_line_width(width);
            ctx.begin_path();
            let _ = ctx.arc(c.x, c.y, r, 0.0, TAU);
            ctx.stroke();
        }
    }
}

/// A small batch of segments as one anti-aliased path, one stroke.
fn stroke_segments(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    colour: &str,
    segments: &[(DVec2, DVec2)],
    width_px: f64,
) {
    ctx.begin_path();
    for (a, b) in segments {
        let (a, b) = (viewport.to_px(*a), viewport.to_px(*b));
        ctx.move_to(a.x, a.y);
        ctx.line_to(b.x, b.y);
    }
    ctx.set_stroke_style_str(colour);
    ctx.set_line_width(width_px);
    set_dash(ctx, false);
    ctx.stroke();
}

/// Distance of edge marks and the scale bar from the canvas edge, CSS pixels.
const EDGE_INSET_PX: f64 = 14.0;

/// A metre scale bar in the lower-left corner, on a plate of the background.
fn paint_scale_bar(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    palette: &Palette,
    height_px: f64,
) {
    let Some(ScaleBar { length_m, label }) =
        ScaleBar::fit(viewport.scale_px_per_m, SCALE_BAR_MAX_PX)
    else {
        return;
    };
    let len_px = length_m * viewport.scale_px_per_m;
    let x0 = EDGE_INSET_PX;
    let y = height_px - EDGE_INSET_PX;
    ctx.set_font("600 12px system-ui, sans-serif");
    let text_w = ctx.measure_text(&label).map_or(0.0, |m| m.width());
    ctx.set_fill_style_str(&palette.background);
    ctx.set_global_alpha(0.85);
    ctx.fill_rect(x0 - 6.0, y - 22.0, len_px.max(text_w) + 12.0, 28.0);
    ctx.set_global_alpha(1.0);
    let ink = palette.colour(Role::Text).to_owned();
    ctx.set_stroke_style_str(&ink);
    ctx.set_line_width(2.0);
    set_dash(ctx, false);
    ctx.begin_path();
    ctx.move_to(x0, y - 5.0);
    ctx.line_to(x0, y);
    ctx.line_to(x0 + len_px, y);
    ctx.line_to(x0 + len_px, y - 5.0);
    ctx.stroke();
    ctx.set_fill_style_str(&ink);
    ctx.set_text_align("left");
    ctx.set_text_baseline("bottom");
    let _ = ctx.fill_text(&label, x0, y - 6.0);
}

/// Where the edge mark for an off-view point at `p` (CSS px) goes: the point
/// where the ray from the canvas centre toward `p` meets the canvas rectangle
/// inset by `inset`, and the ray's direction (radians, screen y down).
/// `None` while `p` is in view.
#[must_use]
pub fn off_view_mark(p: DVec2, size: (f64, f64), inset: f64) -> Option<(DVec2, f64)> {
    let (w, h) = size;
    if !p.is_finite() || (p.x >= 0.0 && p.x <= w && p.y >= 0.0 && p.y <= h) {
        return None;
    }
    let c = DVec2::new(w, h) * 0.5;
    let d = p - c;
    let half = (c - DVec2::splat(inset)).max(DVec2::splat(1.0));
    let tx = if d.x.abs() > 1e-12 {
        half.x / d.x.abs()
    } else {
        f64::INFINITY
    };
    let ty = if d.y.abs() > 1e-12 {
        half.y / d.y.abs()
    } else {
        f64::INFINITY
    };
    let t = tx.min(ty);
    Some((c + d * t, math::atan2(d.y, d.x)))
}

/// An arrowhead on the canvas edge pointing at a point outside the view, with
/// its label beside it (kept inside the canvas).
#[allow(clippy::too_many_arguments)]
fn paint_off_view(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    palette: &Palette,
    (w, h): (f64, f64),
    at: DVec2,
    label: &str,
    role: Role,
) {
    let Some((tip, angle)) = off_view_mark(viewport.to_px(at), (w, h), EDGE_INSET_PX) else {
        return;
    };
    let colour = palette.colour(role).to_owned();
    let (sin, cos) = math::sin_cos(angle);
    let u = DVec2::new(cos, sin);
    let n = DVec2::new(-u.y, u.x);
    let back = tip - u * 14.0;
    ctx.begin_path();
    ctx.move_to(tip.x, tip.y);
    ctx.line_to(back.x + n.x * 8.0, back.y + n.y * 8.0);
    ctx.line_to(back.x - n.x * 8.0, back.y - n.y * 8.0);
    ctx.close_path();
    ctx.set_fill_style_str(&colour);
    ctx.fill();
    ctx.set_stroke_style_str(&palette.background);
    ctx.set_line_width(1.5);
    set_dash(ctx, false);
    ctx.stroke();
    if label.is_empty() {
        return;
    }
    ctx.set_font("600 12px system-ui, sans-serif");
    let text_w = ctx.measure_text(label).map_or(0.0, |m| m.width());
    // Beside the arrow, toward the inside, kept on the canvas.
    let at_text = back - u * 6.0;
    let x = (at_text.x - text_w / 2.0).clamp(4.0, (w - text_w - 4.0).max(4.0));
    let y = at_text.y.clamp(14.0, h - 6.0);
    ctx.set_text_align("left");
    ctx.set_text_baseline("middle");
    ctx.set_line_width(4.0);
    ctx.set_stroke_style_str(&palette.background);
    let _ = ctx.stroke_text(label, x, y);
    ctx.set_fill_style_str(&colour);
    let _ = ctx.fill_text(label, x, y);
}

fn trace_polyline(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    points: &[DVec2],
    closed: bool,
) {
    ctx.begin_path();
    for (i, p) in points.iter().enumerate() {
        let q = viewport.to_px(*p);
        if i == 0 {
            ctx.move_to(q.x, q.y);
        } else {
            ctx.line_to(q.x, q.y);
        }
    }
    if closed {
        ctx.close_path();
    }
}

/// Fills the current path translucently and outlines it in the same colour.
fn fill_and_outline(ctx: &CanvasRenderingContext2d, colour: &str) {
    ctx.set_fill_style_str(colour);
    ctx.set_global_alpha(style::FILL_OPACITY);
    ctx.fill();
    ctx.set_global_alpha(1.0);
    ctx.set_stroke_style_str(colour);
    ctx.set_line_width(style::OUTLINE_PX);
    set_dash(ctx, false);
    ctx.stroke();
}

/// Adds a shaft and a two-stroke head (sized in pixels) to the current path.
fn trace_arrow(ctx: &CanvasRenderingContext2d, a: DVec2, b: DVec2, width_px: f64) {
    let Some([l, tip, r]) = arrow_head(a, b, width_px) else {
        return;
    };
    ctx.move_to(a.x, a.y);
    ctx.line_to(tip.x, tip.y);
    ctx.move_to(l.x, l.y);
    ctx.line_to(tip.x, tip.y);
    ctx.line_to(r.x, r.y);
}

/// Segment batches at least this large are rasterised in wasm into one image
/// (a call per vertex across the wasm boundary costs more than the drawing:
/// 100,000 edges took about 24 ms stroked as a path in software-rendered
/// Chromium); smaller batches are stroked as an anti-aliased path.
pub(crate) const RASTER_SEGMENTS_MIN: usize = 4000;

thread_local! {
    /// The RGBA buffer big segment batches are drawn into, reused across frames.
    static SEGMENT_BUFFER: std::cell::RefCell<Vec<u8>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Draws a large batch of segments as 1–2 device-pixel lines (Bresenham,
/// clipped to the canvas by Liang–Barsky) into one RGBA image, then composites
/// it with a single `drawImage`.
fn paint_segments_raster(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    colour: &str,
    segments: &[(DVec2, DVec2)],
    width_px: f64,
    (css_w, css_h): (f64, f64),
    dpr: f64,
) {
    let w = (css_w * dpr).round().max(1.0) as usize;
    let h = (css_h * dpr).round().max(1.0) as usize;
    let [r, g, b] = hex_rgb(colour);
    let pixel = [r, g, b, 235];
    let thick = (width_px * dpr).round() >= 2.0;
    SEGMENT_BUFFER.with(|buffer| {
        let mut rgba = buffer.borrow_mut();
        rgba.clear();
        rgba.resize(w * h * 4, 0);
        crate::layers::light_segments(
            &mut rgba,
            (w, h),
            pixel,
            thick,
            segments
                .iter()
                .map(|(a, b)| (viewport.to_px(*a) * dpr, viewport.to_px(*b) * dpr)),
        );
        blit_to(ctx, &rgba, (w, h), (0.0, 0.0, css_w, css_h), true);
    });
}

/// Draws a large cloud of small square dots into one RGBA image (like
/// [`paint_segments_raster`]: one `drawImage` instead of a call per dot).
///
/// The image has one pixel per CSS pixel, whatever the pixel ratio, and
/// covers only the dots' bounding box: a streaming cloud (the workspace
/// sweep adds to it at every frame) is uploaded at every frame, and at a
/// pixel ratio of 2 a full-canvas device-pixel image is four times the
/// bytes for dots that are a pixel or two across anyway.
fn paint_points_raster(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    colour: &str,
    points: &[DVec2],
    radius_px: f64,
    (css_w, css_h): (f64, f64),
) {
    let [r, g, b] = hex_rgb(colour);
    let pixel = [r, g, b, 140];
    let half = radius_px.round().max(1.0) as i64;
    // Each dot's nearest CSS pixel, worked out once; and their bounding box
    // in whole CSS pixels, within the canvas.
    let centres: Vec<(i64, i64)> = points
        .iter()
        .map(|p| viewport.to_px(*p))
        .filter(|q| q.is_finite())
        .map(|q| (nearest_px(q.x), nearest_px(q.y)))
        .collect();
    let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
    for &(cx, cy) in &centres {
        x0 = x0.min(cx - half + 1);
        y0 = y0.min(cy - half + 1);
        x1 = x1.max(cx + half);
        y1 = y1.max(cy + half);
    }
    let (x0, y0) = (x0.max(0), y0.max(0));
    let (x1, y1) = (x1.min(css_w.ceil() as i64), y1.min(css_h.ceil() as i64));
    if x1 <= x0 || y1 <= y0 {
        return;
    }
    let (w, h) = ((x1 - x0) as usize, (y1 - y0) as usize);
    SEGMENT_BUFFER.with(|buffer| {
        let mut rgba = buffer.borrow_mut();
        rgba.clear();
        rgba.resize(w * h * 4, 0);
        let pixels = rgba.as_chunks_mut::<4>().0;
        for &(cx, cy) in &centres {
            let (cx, cy) = (cx - x0, cy - y0);
            for y in (cy - half + 1).max(0)..(cy + half).min(h as i64) {
                for x in (cx - half + 1).max(0)..(cx + half).min(w as i64) {
                    pixels[y as usize * w + x as usize] = pixel;
                }
            }
        }
        // Crisp: each image pixel becomes a square of device pixels.
        blit_to(
            ctx,
            &rgba,
            (w, h),
            (x0 as f64, y0 as f64, w as f64, h as f64),
            false,
        );
    });
}

/// Cell states as one RGBA image drawn by a single `drawImage`.
#[allow(clippy::too_many_arguments)]
fn paint_raster(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    palette: &Palette,
    min: DVec2,
    cell_m: f64,
    (cols, rows): (usize, usize),
    cells: &[u8],
    states: &[RasterColour],
) {
    if cols == 0 || rows == 0 || cells.len() < cols * rows {
        return;
    }
    let lut = crate::layers::raster_lut(palette, states);
    let mut rgba = Vec::new();
    crate::layers::raster_rgba(cells, (cols, rows), &lut, &mut rgba);
    blit(ctx, viewport, &rgba, min, cell_m, cols, rows);
}

thread_local! {
    /// The off-screen canvases (and contexts) every blit goes through: one
    /// for crisp blits, one for smoothed ones (see [`blit_to`]).
    static BLIT_CANVASES: [Option<(web_sys::HtmlCanvasElement, CanvasRenderingContext2d)>; 2] =
        [crate::layers::offscreen(), crate::layers::offscreen()];
}

/// Density cells as one RGBA image (alpha grows with density), drawn scaled
/// by a single `drawImage`: cost independent of the cell count.
#[allow(clippy::too_many_arguments)]
fn paint_heatmap(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    colour: &str,
    min: DVec2,
    cell_m: f64,
    cols: usize,
    rows: usize,
    values: &[f32],
) {
    if cols == 0 || rows == 0 || values.len() < cols * rows {
        return;
    }
    let [r, g, b] = hex_rgb(colour);
    // Image rows run top-down; density rows run bottom-up (row 0 at min.y).
    let mut rgba = vec![0u8; cols * rows * 4];
    let pixels = rgba.as_chunks_mut::<4>().0;
    for row in 0..rows {
        for col in 0..cols {
            let v = values[row * cols + col];
            if v > 0.0 {
                pixels[(rows - 1 - row) * cols + col] =
                    [r, g, b, (40.0 + 200.0 * v.min(1.0)) as u8];
            }
        }
    }
    blit(ctx, viewport, &rgba, min, cell_m, cols, rows);
}

/// Draws an RGBA image of `cols` × `rows` cells (top row first) scaled onto
/// the world rectangle starting at `min` with square cells of `cell_m`.
fn blit(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    rgba: &[u8],
    min: DVec2,
    cell_m: f64,
    cols: usize,
    rows: usize,
) {
    let top_left = viewport.to_px(min + DVec2::new(0.0, rows as f64 * cell_m));
    let size = cell_m * viewport.scale_px_per_m;
    let rect = (
        top_left.x,
        top_left.y,
        cols as f64 * size,
        rows as f64 * size,
    );
    // Crisp cells: smoothing would smear them across boundaries.
    blit_to(ctx, rgba, (cols, rows), rect, false);
}

/// Puts `rgba` (`w` × `h` pixels) on a reused off-screen canvas and draws
/// it into `(x, y, width, height)` (CSS pixels) with one `drawImage`.
///
/// A crisp blit (nearest pixel) uses the top-left `w` × `h` of a canvas that
/// only grows: a streaming cloud's box changes size at every frame, and
/// resizing a canvas reallocates it (about 1 ms a frame on the phone
/// stand-in). A smoothed blit would sample past that corner's edge, so it
/// has its own canvas of exactly its size.
fn blit_to(
    ctx: &CanvasRenderingContext2d,
    rgba: &[u8],
    (w, h): (usize, usize),
    (x, y, width, height): (f64, f64, f64, f64),
    smooth: bool,
) {
    BLIT_CANVASES.with(|canvases| {
        let Some((offscreen, octx)) = &canvases[usize::from(smooth)] else {
            return;
        };
        let (cw, ch) = (offscreen.width() as usize, offscreen.height() as usize);
        let (nw, nh) = if smooth {
            (w, h)
        } else {
            (cw.max(w), ch.max(h))
        };
        if (nw, nh) != (cw, ch) {
            offscreen.set_width(nw as u32);
            offscreen.set_height(nh as u32);
            crate::layers::count(|c| c.blit_resizes += 1);
        }
        let Ok(image) = web_sys::ImageData::new_with_u8_clamped_array_and_sh(
            wasm_bindgen::Clamped(rgba),
            w as u32,
            h as u32,
        ) else {
            return;
        };
        let _ = octx.put_image_data(&image, 0.0, 0.0);
        ctx.set_image_smoothing_enabled(smooth);
        let _ = ctx.draw_image_with_html_canvas_element_and_sw_and_sh_and_dx_and_dy_and_dw_and_dh(
            offscreen, 0.0, 0.0, w as f64, h as f64, x, y, width, height,
        );
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_off_view_mark_sits_on_the_edge_toward_the_point() {
        let size = (400.0, 300.0);
        assert_eq!(off_view_mark(DVec2::new(200.0, 150.0), size, 10.0), None);
        // Far to the right, level with the centre: right edge, pointing right.
        let (p, a) = off_view_mark(DVec2::new(1000.0, 150.0), size, 10.0).unwrap();
        assert!((p.x - 390.0).abs() < 1e-9 && (p.y - 150.0).abs() < 1e-9);
        assert!(a.abs() < 1e-12);
        // Below and left: on the inset rectangle, inside the canvas.
        let (p, _) = off_view_mark(DVec2::new(-50.0, 900.0), size, 10.0).unwrap();
        assert!((p.y - 290.0).abs() < 1e-9 && p.x > 10.0 && p.x < 200.0);
    }
}
