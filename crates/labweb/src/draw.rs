//! Paints a [`Scene`] on a 2D canvas.
//!
//! World coordinates (metres, y up) map to CSS pixels with one uniform scale
//! that fits the experiment's [`ViewBox`] into the canvas; the backing store
//! is `devicePixelRatio` times larger so lines stay crisp.

use glam::DVec2;
use labcore::{Item, RasterColour, Role, Scene, ViewBox};
use std::f64::consts::TAU;
use wasm_bindgen::{JsCast, JsValue};
use web_sys::{CanvasRenderingContext2d, Element};

/// Theme colours per role, read from CSS custom properties (`--c-link`, …).
#[derive(Clone, Debug)]
pub struct Palette {
    colours: Vec<(Role, String)>,
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

/// Other theme colours the plots use.
const PLOT_VARS: &[&str] = &[
    "--p-1", "--p-2", "--p-3", "--p-4", "--p-5", "--p-6", "--p-band", "--c-text", "--c-grid",
    "--muted",
];

const ROLE_VARS: &[(Role, &str)] = &[
    (Role::Grid, "--c-grid"),
    (Role::Bound, "--c-bound"),
    (Role::Link, "--c-link"),
    (Role::Joint, "--c-joint"),
    (Role::Base, "--c-base"),
    (Role::Tip, "--c-tip"),
    (Role::Target, "--c-target"),
    (Role::Ghost, "--c-ghost"),
    (Role::Sample, "--c-sample"),
    (Role::Accent, "--c-accent"),
    (Role::Warning, "--c-warning"),
    (Role::Text, "--c-text"),
    (Role::Robot, "--c-robot"),
    (Role::Obstacle, "--c-obstacle"),
    (Role::Path, "--c-path"),
    (Role::Estimate, "--c-estimate"),
    (Role::Visited, "--c-visited"),
];

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
        Self {
            colours: ROLE_VARS
                .iter()
                .map(|(role, var)| (*role, read(var, "#888")))
                .collect(),
            vars: PLOT_VARS.iter().map(|v| (*v, read(v, "#888"))).collect(),
            background: read("--c-canvas", "#fff"),
            focus: read("--focus", "#E69F00"),
            reading: PALETTE_READINGS.with(|n| {
                n.set(n.get() + 1);
                n.get()
            }),
        }
    }

    /// A theme colour by its CSS custom property name (see [`PLOT_VARS`]).
    pub fn var(&self, name: &str) -> String {
        self.vars
            .iter()
            .find(|(v, _)| *v == name)
            .map_or_else(|| "#888".to_owned(), |(_, c)| c.clone())
    }

    pub fn colour(&self, role: Role) -> &str {
        self.colours
            .iter()
            .find(|(r, _)| *r == role)
            .map_or("#888", |(_, c)| c.as_str())
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

/// The world → CSS-pixel mapping of one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewport {
    pub scale_px_per_m: f64,
    pub center_world: DVec2,
    pub center_px: DVec2,
}

impl Viewport {
    /// Fits `view` into a `width_px` × `height_px` canvas, uniform scale.
    #[must_use]
    pub fn fit(view: ViewBox, width_px: f64, height_px: f64) -> Self {
        let size = (view.max - view.min).max(DVec2::splat(1e-9));
        let scale = (width_px / size.x).min(height_px / size.y).max(1e-9);
        Self {
            scale_px_per_m: scale,
            center_world: (view.min + view.max) * 0.5,
            center_px: DVec2::new(width_px, height_px) * 0.5,
        }
    }

    #[must_use]
    pub fn to_px(&self, p: DVec2) -> DVec2 {
        let d = (p - self.center_world) * self.scale_px_per_m;
        DVec2::new(self.center_px.x + d.x, self.center_px.y - d.y)
    }

    #[must_use]
    pub fn to_world(&self, px: DVec2) -> DVec2 {
        let d = px - self.center_px;
        self.center_world + DVec2::new(d.x, -d.y) / self.scale_px_per_m
    }
}

fn set_dash(ctx: &CanvasRenderingContext2d, dashed: bool) {
    let pattern = js_sys::Array::new();
    if dashed {
        pattern.push(&JsValue::from_f64(6.0));
        pattern.push(&JsValue::from_f64(5.0));
    }
    let _ = ctx.set_line_dash(&pattern);
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
    let width_px_canvas = width_px;
    let _ = ctx.set_transform(dpr, 0.0, 0.0, dpr, 0.0, 0.0);
    if background {
        ctx.set_fill_style_str(&palette.background);
        ctx.fill_rect(0.0, 0.0, width_px, height_px);
    }
    ctx.set_line_cap("round");
    ctx.set_line_join("round");
    // Whether the context's font and baseline are the labels' (the scale
    // bar and the off-view marks set their own).
    let mut label_font = false;
    for item in items {
        ctx.set_global_alpha(1.0);
        match item {
            Item::Line {
                from,
                to,
                width_px,
                role,
                dashed,
            } => {
                let (a, b) = (viewport.to_px(*from), viewport.to_px(*to));
                ctx.set_stroke_style_str(palette.colour(*role));
                ctx.set_line_width(*width_px);
                set_dash(ctx, *dashed);
                if *role == Role::Ghost {
                    ctx.set_global_alpha(0.7);
                }
                ctx.begin_path();
                ctx.move_to(a.x, a.y);
                ctx.line_to(b.x, b.y);
                ctx.stroke();
            }
            Item::Circle {
                center,
                radius_m,
                role,
                fill,
                dashed,
            } => {
                let c = viewport.to_px(*center);
                let r = radius_m * viewport.scale_px_per_m;
                ctx.begin_path();
                let _ = ctx.arc(c.x, c.y, r.max(0.0), 0.0, TAU);
                if *fill {
                    ctx.set_fill_style_str(palette.colour(*role));
                    ctx.set_global_alpha(0.18);
                    ctx.fill();
                } else {
                    ctx.set_stroke_style_str(palette.colour(*role));
                    ctx.set_line_width(2.0);
                    set_dash(ctx, *dashed);
                    ctx.stroke();
                }
            }
            Item::Dot {
                center,
                radius_px,
                role,
            } => {
                let c = viewport.to_px(*center);
                ctx.begin_path();
                let _ = ctx.arc(c.x, c.y, *radius_px, 0.0, TAU);
                ctx.set_fill_style_str(palette.colour(*role));
                ctx.fill();
                ctx.set_line_width(2.0);
                ctx.set_stroke_style_str(&palette.background);
                set_dash(ctx, false);
                ctx.stroke();
            }
            Item::Points {
                points,
                radius_px,
                role,
            } if points.len() >= RASTER_SEGMENTS_MIN => paint_points_raster(
                ctx,
                viewport,
                palette.colour(*role),
                points,
                *radius_px,
                (width_px_canvas, height_px),
            ),
            Item::Points {
                points,
                radius_px,
                role,
            } => {
                ctx.set_fill_style_str(palette.colour(*role));
                ctx.set_global_alpha(0.55);
                ctx.begin_path();
                let d = radius_px * 2.0;
                for p in points {
                    let c = viewport.to_px(*p);
                    ctx.rect(c.x - radius_px, c.y - radius_px, d, d);
                }
                ctx.fill();
            }
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
                palette.colour(*role),
                *min,
                *cell_m,
                *cols,
                *rows,
                values,
            ),
            Item::Ellipse {
                center,
                semi_axis_a,
                semi_axis_b,
                role,
            } => {
                let c = viewport.to_px(*center);
                let ra = semi_axis_a.length() * viewport.scale_px_per_m;
                let rb = semi_axis_b.length() * viewport.scale_px_per_m;
                // Screen y is flipped, so the rotation angle changes sign.
                let rotation = -semi_axis_a.y.atan2(semi_axis_a.x);
                ctx.begin_path();
                let _ = ctx.ellipse(c.x, c.y, ra.max(0.5), rb.max(0.5), rotation, 0.0, TAU);
                ctx.set_fill_style_str(palette.colour(*role));
                ctx.set_global_alpha(0.18);
                ctx.fill();
                ctx.set_global_alpha(1.0);
                ctx.set_stroke_style_str(palette.colour(*role));
                ctx.set_line_width(2.0);
                set_dash(ctx, false);
                ctx.stroke();
            }
            Item::Label {
                pos,
                text,
                role,
                offset_px,
            } => {
                let c = viewport.to_px(*pos) + *offset_px;
                // The font is set once a paint (setting it parses it).
                if !label_font {
                    ctx.set_font(LABEL_FONT);
                    ctx.set_text_baseline("middle");
                    label_font = true;
                }
                let text_w = crate::text::width(ctx, LABEL_FONT, text);
                // Keep labels inside the canvas.
                let x = c.x.min(width_px - text_w - 4.0).max(4.0);
                let y = c.y.clamp(10.0, height_px - 10.0);
                ctx.set_line_width(4.0);
                ctx.set_stroke_style_str(&palette.background);
                set_dash(ctx, false);
                let _ = ctx.stroke_text(text, x, y);
                ctx.set_fill_style_str(palette.colour(*role));
                let _ = ctx.fill_text(text, x, y);
            }
            Item::Polyline {
                points,
                width_px,
                role,
                dashed,
                closed,
            } => {
                if points.len() < 2 {
                    continue;
                }
                trace_polyline(ctx, viewport, points, *closed);
                ctx.set_stroke_style_str(palette.colour(*role));
                ctx.set_line_width(*width_px);
                set_dash(ctx, *dashed);
                ctx.stroke();
            }
            Item::Polygon { points, role } => {
                if points.len() < 3 {
                    continue;
                }
                trace_polyline(ctx, viewport, points, true);
                fill_and_outline(ctx, palette.colour(*role));
            }
            Item::Rect {
                min,
                max,
                role,
                fill,
            } => {
                let (a, b) = (viewport.to_px(*min), viewport.to_px(*max));
                ctx.begin_path();
                ctx.rect(
                    a.x.min(b.x),
                    a.y.min(b.y),
                    (b.x - a.x).abs(),
                    (b.y - a.y).abs(),
                );
                if *fill {
                    fill_and_outline(ctx, palette.colour(*role));
                } else {
                    ctx.set_stroke_style_str(palette.colour(*role));
                    ctx.set_line_width(2.0);
                    set_dash(ctx, false);
                    ctx.stroke();
                }
            }
            Item::Arrow {
                from,
                to,
                width_px,
                role,
            } => {
                ctx.begin_path();
                trace_arrow(ctx, viewport.to_px(*from), viewport.to_px(*to), *width_px);
                ctx.set_stroke_style_str(palette.colour(*role));
                ctx.set_line_width(*width_px);
                set_dash(ctx, false);
                ctx.stroke();
            }
            Item::Arrows {
                arrows,
                width_px,
                role,
            } => {
                ctx.begin_path();
                for (from, to) in arrows {
                    trace_arrow(ctx, viewport.to_px(*from), viewport.to_px(*to), *width_px);
                }
                ctx.set_stroke_style_str(palette.colour(*role));
                ctx.set_line_width(*width_px);
                set_dash(ctx, false);
                ctx.stroke();
            }
            Item::Segments {
                segments,
                width_px,
                role,
            } if segments.len() >= RASTER_SEGMENTS_MIN => paint_segments_raster(
                ctx,
                viewport,
                palette.colour(*role),
                segments,
                *width_px,
                (width_px_canvas, height_px),
                dpr,
            ),
            Item::Segments {
                segments,
                width_px,
                role,
            } => stroke_segments(ctx, viewport, palette.colour(*role), segments, *width_px),
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
                palette.colour(*role),
                layer,
                *width_px,
                (width_px_canvas, height_px),
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
            Item::ScaleBar => {
                paint_scale_bar(ctx, viewport, palette, height_px);
                label_font = false;
            }
            Item::OffView { at, label, role } => {
                paint_off_view(
                    ctx,
                    viewport,
                    palette,
                    (width_px, height_px),
                    *at,
                    label,
                    *role,
                );
                label_font = false;
            }
            Item::FocusRing { center, radius_px } => {
                let c = viewport.to_px(*center);
                set_dash(ctx, false);
                // A 3 px ring in the focus colour between two thin lines of
                // the background, so it shows on any colour under it.
                for (colour, width, r) in [
                    (palette.background.as_str(), 1.5, radius_px - 2.25),
                    (palette.background.as_str(), 1.5, radius_px + 2.25),
                    (palette.focus.as_str(), 3.0, *radius_px),
                ] {
                    ctx.set_stroke_style_str(colour);
                    ctx.set_line_width(width);
                    ctx.begin_path();
                    let _ = ctx.arc(c.x, c.y, r, 0.0, std::f64::consts::TAU);
                    ctx.stroke();
                }
            }
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
        }
    }
    ctx.set_global_alpha(1.0);
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

/// Longest a scale bar may be, CSS pixels.
const SCALE_BAR_MAX_PX: f64 = 120.0;
/// Distance of edge marks and the scale bar from the canvas edge, CSS pixels.
const EDGE_INSET_PX: f64 = 14.0;

/// The scale bar's length: the largest round length (1, 2 or 5 × 10ᵏ m)
/// that is at most `max_px` long at `scale_px_per_m`.
#[must_use]
pub fn scale_bar_m(scale_px_per_m: f64, max_px: f64) -> f64 {
    let limit_m = max_px / scale_px_per_m.max(1e-12);
    let decade = 10f64.powf(limit_m.log10().floor());
    [5.0, 2.0, 1.0]
        .iter()
        .map(|f| f * decade)
        .find(|len| *len <= limit_m * (1.0 + 1e-9))
        .unwrap_or(decade)
}

/// The scale bar's label: "1 m", "0.5 m", "20 m".
#[must_use]
pub fn scale_bar_label(length_m: f64) -> String {
    format!("{} m", labcore::units::format_number(length_m, 3))
}

/// A metre scale bar in the lower-left corner, on a plate of the background.
fn paint_scale_bar(
    ctx: &CanvasRenderingContext2d,
    viewport: &Viewport,
    palette: &Palette,
    height_px: f64,
) {
    let len_m = scale_bar_m(viewport.scale_px_per_m, SCALE_BAR_MAX_PX);
    let len_px = len_m * viewport.scale_px_per_m;
    let label = scale_bar_label(len_m);
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
    Some((c + d * t, d.y.atan2(d.x)))
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
    let u = DVec2::new(angle.cos(), angle.sin());
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
    ctx.set_global_alpha(0.35);
    ctx.fill();
    ctx.set_global_alpha(1.0);
    ctx.set_stroke_style_str(colour);
    ctx.set_line_width(2.0);
    set_dash(ctx, false);
    ctx.stroke();
}

/// Adds a shaft and a two-stroke head (sized in pixels) to the current path.
fn trace_arrow(ctx: &CanvasRenderingContext2d, a: DVec2, b: DVec2, width_px: f64) {
    let d = b - a;
    let len = d.length();
    if len.is_nan() || len <= 0.5 {
        return;
    }
    ctx.move_to(a.x, a.y);
    ctx.line_to(b.x, b.y);
    let head = (4.0 + 2.5 * width_px).min(len * 0.5);
    let u = d / len;
    let n = DVec2::new(-u.y, u.x);
    let back = b - u * head;
    ctx.move_to(back.x + n.x * head * 0.5, back.y + n.y * head * 0.5);
    ctx.line_to(b.x, b.y);
    ctx.line_to(back.x - n.x * head * 0.5, back.y - n.y * head * 0.5);
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
        let mut plot = |x: i64, y: i64| {
            if x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h {
                let i = (y as usize * w + x as usize) * 4;
                rgba[i..i + 4].copy_from_slice(&pixel);
            }
        };
        for (a, b) in segments {
            let (a, b) = (viewport.to_px(*a) * dpr, viewport.to_px(*b) * dpr);
            let Some((a, b)) = clip_segment(a, b, w as f64 - 1.0, h as f64 - 1.0) else {
                continue;
            };
            bresenham(a, b, |x, y| {
                plot(x, y);
                if thick {
                    plot(x + 1, y);
                    plot(x, y + 1);
                }
            });
        }
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
    // The dots' bounding box in whole CSS pixels, within the canvas.
    let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
    for p in points {
        let q = viewport.to_px(*p);
        if q.is_finite() {
            let (cx, cy) = (q.x.round() as i64, q.y.round() as i64);
            x0 = x0.min(cx - half + 1);
            y0 = y0.min(cy - half + 1);
            x1 = x1.max(cx + half);
            y1 = y1.max(cy + half);
        }
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
        for p in points {
            let q = viewport.to_px(*p);
            if !q.is_finite() {
                continue;
            }
            let (cx, cy) = (q.x.round() as i64 - x0, q.y.round() as i64 - y0);
            for y in (cy - half + 1).max(0)..(cy + half).min(h as i64) {
                for x in (cx - half + 1).max(0)..(cx + half).min(w as i64) {
                    let i = (y as usize * w + x as usize) * 4;
                    rgba[i..i + 4].copy_from_slice(&pixel);
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

/// Liang–Barsky clipping of segment `a`–`b` to `[0, max_x] × [0, max_y]`.
pub(crate) fn clip_segment(a: DVec2, b: DVec2, max_x: f64, max_y: f64) -> Option<(DVec2, DVec2)> {
    if !(a.is_finite() && b.is_finite()) {
        return None;
    }
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-d.x, a.x),
        (d.x, max_x - a.x),
        (-d.y, a.y),
        (d.y, max_y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return None;
            }
        }
    }
    Some((a + d * t0, a + d * t1))
}

/// Integer Bresenham line from `a` to `b` (both already clipped).
pub(crate) fn bresenham(a: DVec2, b: DVec2, mut plot: impl FnMut(i64, i64)) {
    let (mut x, mut y) = (a.x.round() as i64, a.y.round() as i64);
    let (x1, y1) = (b.x.round() as i64, b.y.round() as i64);
    let (dx, dy) = ((x1 - x).abs(), -(y1 - y).abs());
    let (sx, sy) = (if x < x1 { 1 } else { -1 }, if y < y1 { 1 } else { -1 });
    let mut err = dx + dy;
    loop {
        plot(x, y);
        if x == x1 && y == y1 {
            break;
        }
        let e2 = 2 * err;
        if e2 >= dy {
            err += dy;
            x += sx;
        }
        if e2 <= dx {
            err += dx;
            y += sy;
        }
    }
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

thread_local! {
    /// A small off-screen canvas reused for heatmaps.
    static HEATMAP_CANVAS: Option<web_sys::HtmlCanvasElement> = crate::dom::document()
        .create_element("canvas")
        .ok()
        .and_then(|c| wasm_bindgen::JsCast::dyn_into(c).ok());
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
    for row in 0..rows {
        for col in 0..cols {
            let v = values[row * cols + col];
            if v > 0.0 {
                let i = ((rows - 1 - row) * cols + col) * 4;
                rgba[i..i + 4].copy_from_slice(&[r, g, b, (40.0 + 200.0 * v.min(1.0)) as u8]);
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

/// Puts `rgba` (`w` × `h` pixels) on the reused off-screen canvas and draws
/// it into `(x, y, width, height)` (CSS pixels) with one `drawImage`.
fn blit_to(
    ctx: &CanvasRenderingContext2d,
    rgba: &[u8],
    (w, h): (usize, usize),
    (x, y, width, height): (f64, f64, f64, f64),
    smooth: bool,
) {
    HEATMAP_CANVAS.with(|offscreen| {
        let Some(offscreen) = offscreen else { return };
        if offscreen.width() != w as u32 || offscreen.height() != h as u32 {
            offscreen.set_width(w as u32);
            offscreen.set_height(h as u32);
        }
        let Some(octx) = offscreen
            .get_context("2d")
            .ok()
            .flatten()
            .and_then(|c| wasm_bindgen::JsCast::dyn_into::<CanvasRenderingContext2d>(c).ok())
        else {
            return;
        };
        let Ok(image) = web_sys::ImageData::new_with_u8_clamped_array_and_sh(
            wasm_bindgen::Clamped(rgba),
            w as u32,
            h as u32,
        ) else {
            return;
        };
        let _ = octx.put_image_data(&image, 0.0, 0.0);
        ctx.set_image_smoothing_enabled(smooth);
        let _ =
            ctx.draw_image_with_html_canvas_element_and_dw_and_dh(offscreen, x, y, width, height);
    });
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

    #[test]
    fn the_scale_bar_takes_the_longest_round_length_that_fits() {
        // 100 px per metre, at most 120 px: 1 m.
        assert_eq!(scale_bar_m(100.0, 120.0), 1.0);
        // 50 px/m: 2 m (100 px); 20 px/m: 5 m (100 px); 400 px/m: 0.2 m (80 px).
        assert_eq!(scale_bar_m(50.0, 120.0), 2.0);
        assert_eq!(scale_bar_m(20.0, 120.0), 5.0);
        assert!((scale_bar_m(400.0, 120.0) - 0.2).abs() < 1e-12);
        for scale in [0.7, 3.0, 13.0, 77.0, 640.0] {
            let len = scale_bar_m(scale, 120.0);
            assert!(
                len * scale <= 120.0 + 1e-9 && len * scale > 120.0 / 5.0,
                "{scale}"
            );
        }
        assert_eq!(scale_bar_label(0.5), "0.5 m");
        assert_eq!(scale_bar_label(2.0), "2 m");
    }

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

    #[test]
    fn clipping_keeps_inside_parts_only() {
        let c =
            |a: (f64, f64), b: (f64, f64)| clip_segment(DVec2::from(a), DVec2::from(b), 10.0, 10.0);
        assert_eq!(
            c((1.0, 1.0), (5.0, 5.0)),
            Some((DVec2::new(1.0, 1.0), DVec2::new(5.0, 5.0)))
        );
        assert_eq!(
            c((-10.0, 5.0), (20.0, 5.0)),
            Some((DVec2::new(0.0, 5.0), DVec2::new(10.0, 5.0)))
        );
        assert_eq!(c((-5.0, -5.0), (-1.0, 20.0)), None);
        assert_eq!(c((f64::NAN, 0.0), (1.0, 1.0)), None);
        // A far-away endpoint is clipped, not walked pixel by pixel.
        let (a, b) = c((5.0, 5.0), (1e300, 5.0)).expect("crosses the canvas");
        assert_eq!((a.x, b.x), (5.0, 10.0));
    }

    #[test]
    fn bresenham_visits_every_pixel_once_from_end_to_end() {
        let mut seen = Vec::new();
        bresenham(DVec2::new(0.0, 0.0), DVec2::new(5.0, 2.0), |x, y| {
            seen.push((x, y))
        });
        assert_eq!(seen.first(), Some(&(0, 0)));
        assert_eq!(seen.last(), Some(&(5, 2)));
        assert_eq!(seen.len(), 6, "one pixel per column of an x-major line");
        let mut steep = Vec::new();
        bresenham(DVec2::new(3.0, 7.0), DVec2::new(2.0, 0.0), |x, y| {
            steep.push((x, y))
        });
        assert_eq!(steep.len(), 8);
        assert!(steep
            .windows(2)
            .all(|w| (w[0].0 - w[1].0).abs() <= 1 && (w[0].1 - w[1].1).abs() == 1));
    }
}
