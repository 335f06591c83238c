//! Paints a [`Scene`] on a 2D canvas.
//!
//! World coordinates (metres, y up) map to CSS pixels with one uniform scale
//! that fits the experiment's [`ViewBox`] into the canvas; the backing store
//! is `devicePixelRatio` times larger so lines stay crisp.

use glam::DVec2;
use labcore::{Item, Role, Scene, ViewBox};
use std::f64::consts::TAU;
use wasm_bindgen::JsValue;
use web_sys::{CanvasRenderingContext2d, Element};

/// Theme colours per role, read from CSS custom properties (`--c-link`, …).
#[derive(Clone, Debug)]
pub struct Palette {
    colours: Vec<(Role, String)>,
    pub background: String,
}

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
                .unwrap_or_else(|| fallback.to_owned())
        };
        Self {
            colours: ROLE_VARS
                .iter()
                .map(|(role, var)| (*role, read(var, "#888")))
                .collect(),
            background: read("--c-canvas", "#fff"),
        }
    }

    fn colour(&self, role: Role) -> &str {
        self.colours
            .iter()
            .find(|(r, _)| *r == role)
            .map_or("#888", |(_, c)| c.as_str())
    }
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
    let _ = ctx.set_transform(dpr, 0.0, 0.0, dpr, 0.0, 0.0);
    ctx.set_fill_style_str(&palette.background);
    ctx.fill_rect(0.0, 0.0, width_px, height_px);
    ctx.set_line_cap("round");
    ctx.set_line_join("round");
    for item in &scene.items {
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
                ctx.set_font("600 13px system-ui, sans-serif");
                ctx.set_text_baseline("middle");
                let text_w = ctx.measure_text(text).map_or(0.0, |m| m.width());
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
        }
    }
    ctx.set_global_alpha(1.0);
}

/// `#rrggbb` → RGB; anything else gives a mid grey.
fn hex_rgb(colour: &str) -> [u8; 3] {
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
    HEATMAP_CANVAS.with(|offscreen| {
        let Some(offscreen) = offscreen else { return };
        offscreen.set_width(cols as u32);
        offscreen.set_height(rows as u32);
        let Some(octx) = offscreen
            .get_context("2d")
            .ok()
            .flatten()
            .and_then(|c| wasm_bindgen::JsCast::dyn_into::<CanvasRenderingContext2d>(c).ok())
        else {
            return;
        };
        let Ok(image) = web_sys::ImageData::new_with_u8_clamped_array_and_sh(
            wasm_bindgen::Clamped(&rgba),
            cols as u32,
            rows as u32,
        ) else {
            return;
        };
        let _ = octx.put_image_data(&image, 0.0, 0.0);
        let top_left = viewport.to_px(min + DVec2::new(0.0, rows as f64 * cell_m));
        let size = cell_m * viewport.scale_px_per_m;
        // Crisp cells: smoothing would smear density outside the reachable annulus.
        ctx.set_image_smoothing_enabled(false);
        let _ = ctx.draw_image_with_html_canvas_element_and_dw_and_dh(
            offscreen,
            top_left.x,
            top_left.y,
            cols as f64 * size,
            rows as f64 * size,
        );
    });
}
