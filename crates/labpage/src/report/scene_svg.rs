//! The simulation's display list ([`Scene`]) as an SVG picture for the
//! report: the world rectangle [`crate::Experiment::view`] scaled to the page,
//! y up, in the site's light colours, with the same fills, dashes and arrow
//! heads as the canvas (labweb's `draw.rs`).
//!
//! Very large batches are thinned so a report stays small: at most the first
//! [`MAX_SEGMENTS`] tree edges, [`MAX_POINTS`] evenly spaced sample points
//! and [`MAX_RASTER_RUNS`] runs of grid cells are drawn, and the caption says
//! when that happened.

use super::n;
use crate::content_html::escape;
use crate::math;
use crate::scene::style::{self, CANVAS};
use crate::scene::{Item, RasterColour, Role, Scene, ViewBox};
use crate::units::format_number;
use glam::DVec2;
use labcore::layout::arrow::arrow_head;
use labcore::layout::map::WorldMap;
use labcore::layout::scale_bar::{ScaleBar, SCALE_BAR_MAX_PX};
use std::fmt::Write as _;

/// Most segments of one [`Item::Segments`] batch drawn (the first ones: a
/// tree's edges come in the order they grew, so its trunk is kept). About
/// ten bytes each in the file.
pub const MAX_SEGMENTS: usize = 16_000;
/// Most points of one [`Item::Points`] cloud drawn.
pub const MAX_POINTS: usize = 4_000;
/// Most horizontal runs of equal cells drawn for one [`Item::Raster`].
pub const MAX_RASTER_RUNS: usize = 12_000;
/// Largest picture side, SVG user units (CSS pixels).
const MAX_W: f64 = 640.0;
const MAX_H: f64 = 520.0;

/// The light theme's colour of each role (the style table's).
fn colour(role: Role) -> &'static str {
    role.style().light()
}

/// World → picture coordinates: the canvas's map ([`WorldMap`]) of the
/// view into a picture of the view's own proportions.
struct Map {
    world: WorldMap,
}

impl Map {
    fn p(&self, w: DVec2) -> (f64, f64) {
        let p = self.world.to_px(w);
        (p.x, p.y)
    }
    fn xy(&self, w: DVec2) -> String {
        let (x, y) = self.p(w);
        format!("{},{}", n1(x), n1(y))
    }
}

/// One decimal: a tenth of a CSS pixel.
fn n1(v: f64) -> String {
    format_number(v, 1)
}

/// An opacity or a stroke: two decimals at most (`0.18`, `2`).
fn n2(v: f64) -> String {
    format_number(v, 2)
}

fn dash(dashed: bool) -> String {
    if dashed {
        let [on, off] = style::DASH_PX;
        format!(" stroke-dasharray=\"{} {}\"", n2(on), n2(off))
    } else {
        String::new()
    }
}

/// Indices of at most `max` of `len` items, evenly spaced.
fn thin(len: usize, max: usize) -> impl Iterator<Item = usize> {
    let stride = len.div_ceil(max.max(1)).max(1);
    (0..len).step_by(stride)
}

/// The picture, and what was thinned (empty when everything is drawn).
/// The picture's map and size: the view at the largest scale that fits
/// [`MAX_W`] × [`MAX_H`], in a picture of the view's own proportions.
fn picture(view: ViewBox) -> (Map, (f64, f64)) {
    let size = view.max - view.min;
    let scale = if size.x > 0.0 && size.y > 0.0 && size.is_finite() {
        (MAX_W / size.x).min(MAX_H / size.y)
    } else {
        1.0
    };
    let (w, h) = (size.x.max(0.0) * scale, size.y.max(0.0) * scale);
    let world = WorldMap::fit(view, w, h);
    (Map { world }, (w, h))
}

pub(super) fn scene_svg(scene: &Scene, view: ViewBox) -> (String, Vec<String>) {
    let (m, (w, h)) = picture(view);
    let mut notes = Vec::new();
    let mut s = String::new();
    let _ = write!(
        s,
        "<svg class=\"scene\" viewBox=\"0 0 {w} {h}\" width=\"{w}\" height=\"{h}\" role=\"img\" \
         aria-label=\"The simulation\" font-family=\"system-ui, sans-serif\" font-size=\"13\" \
         stroke-linecap=\"round\" stroke-linejoin=\"round\">\
         <rect width=\"{w}\" height=\"{h}\" fill=\"{bg}\"/>",
        w = n(w),
        h = n(h),
        bg = CANVAS.light
    );
    for item in &scene.items {
        item_svg(&mut s, item, &m, (w, h), &mut notes);
    }
    let _ = write!(
        s,
        "<rect width=\"{w}\" height=\"{h}\" fill=\"none\" stroke=\"{frame}\"/></svg>",
        w = n(w),
        h = n(h),
        frame = colour(Role::Bound)
    );
    (s, notes)
}

fn finite(p: &DVec2) -> bool {
    p.is_finite()
}

/// One item of the display list, by its kind.
fn item_svg(s: &mut String, item: &Item, m: &Map, (w, h): (f64, f64), notes: &mut Vec<String>) {
    match item {
        Item::Line {
            from,
            to,
            width_px,
            role,
            dashed,
        } if finite(from) && finite(to) => line_svg(s, m, (*from, *to), *width_px, *role, *dashed),
        Item::Circle {
            center,
            radius_m,
            role,
            fill,
            dashed,
        } if finite(center) && radius_m.is_finite() => {
            circle_svg(s, m, *center, *radius_m, *role, (*fill, *dashed));
        }
        Item::Dot {
            center,
            radius_px,
            role,
        } if finite(center) => dot_svg(s, m, *center, *radius_px, *role),
        Item::Points {
            points,
            radius_px,
            role,
        } => points_svg(s, m, points, *radius_px, *role, notes),
        Item::Heatmap {
            min,
            cell_m,
            cols,
            rows,
            values,
            role,
        } => heatmap_svg(s, m, *min, *cell_m, (*cols, *rows), values, *role),
        Item::Ellipse {
            center,
            semi_axis_a,
            semi_axis_b,
            role,
        } if finite(center) && finite(semi_axis_a) && finite(semi_axis_b) => {
            ellipse_svg(s, m, *center, (*semi_axis_a, *semi_axis_b), *role);
        }
        Item::Label {
            pos,
            text,
            role,
            offset_px,
        } if finite(pos) => label_svg(s, m, (w, h), *pos, *offset_px, text, *role),
        Item::Polyline {
            points,
            width_px,
            role,
            dashed,
            closed,
        } if points.len() >= 2 => polyline_svg(s, m, points, *width_px, *role, (*dashed, *closed)),
        Item::Polygon { points, role } if points.len() >= 3 => polygon_svg(s, m, points, *role),
        Item::Rect {
            min,
            max,
            role,
            fill,
        } if finite(min) && finite(max) => rect_svg(s, m, (*min, *max), *role, *fill),
        Item::Arrow {
            from,
            to,
            width_px,
            role,
        } => arrows_svg(s, m, std::slice::from_ref(&(*from, *to)), *width_px, *role),
        Item::Arrows {
            arrows,
            width_px,
            role,
        } => arrows_svg(s, m, arrows, *width_px, *role),
        Item::Segments {
            segments,
            width_px,
            role,
        } => segments_svg(s, segments, *width_px, *role, m, notes),
        // A kept tree is drawn in full, as the canvas shows it.
        Item::SegmentLayer {
            layer,
            width_px,
            role,
        } => segments_svg(s, layer.segments(), *width_px, *role, m, notes),
        Item::ScaleBar => scale_bar(s, m.world.scale_px_per_m, h),
        Item::Raster {
            min,
            cell_m,
            cols,
            rows,
            cells,
            palette,
        }
        | Item::VersionedRaster {
            min,
            cell_m,
            cols,
            rows,
            cells,
            palette,
            ..
        } => raster_svg(s, *min, *cell_m, (*cols, *rows), cells, palette, m, notes),
        Item::OffView { at, label, role } => off_view_svg(s, m, (w, h), *at, label, *role),
        // The keyboard's focus ring (the page adds it), and items with
        // non-finite or too few points, are left out.
        _ => {}
    }
}

fn line_svg(
    s: &mut String,
    m: &Map,
    (from, to): (DVec2, DVec2),
    width_px: f64,
    role: Role,
    dashed: bool,
) {
    let (a, b) = (m.p(from), m.p(to));
    let opacity = role.style().line_opacity;
    let _ = write!(
        s,
        "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"{}\"{}{}/>",
        n1(a.0),
        n1(a.1),
        n1(b.0),
        n1(b.1),
        colour(role),
        n1(width_px),
        dash(dashed),
        if opacity < 1.0 {
            format!(" stroke-opacity=\"{}\"", n2(opacity))
        } else {
            String::new()
        }
    );
}

fn circle_svg(
    s: &mut String,
    m: &Map,
    center: DVec2,
    radius_m: f64,
    role: Role,
    (fill, dashed): (bool, bool),
) {
    let (x, y) = m.p(center);
    let r = (radius_m * m.world.scale_px_per_m).max(0.0);
    let paint = if fill {
        format!(
            "fill=\"{}\" fill-opacity=\"{}\"",
            colour(role),
            n2(style::FILL_OPACITY_LIGHT)
        )
    } else {
        format!(
            "fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"{}",
            colour(role),
            n2(style::OUTLINE_PX),
            dash(dashed)
        )
    };
    let _ = write!(
        s,
        "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" {paint}/>",
        n1(x),
        n1(y),
        n1(r)
    );
}

fn dot_svg(s: &mut String, m: &Map, center: DVec2, radius_px: f64, role: Role) {
    let (x, y) = m.p(center);
    let _ = write!(
        s,
        "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\"/>",
        n1(x),
        n1(y),
        n1(radius_px),
        colour(role),
        CANVAS.light,
        n2(style::OUTLINE_PX)
    );
}

fn points_svg(
    s: &mut String,
    m: &Map,
    points: &[DVec2],
    radius_px: f64,
    role: Role,
    notes: &mut Vec<String>,
) {
    if points.len() > MAX_POINTS {
        notes.push(format!(
            "{} of {} sample points drawn",
            points.len().div_ceil(points.len().div_ceil(MAX_POINTS)),
            points.len()
        ));
    }
    let d = n1(radius_px * 2.0);
    let mut path = String::new();
    for i in thin(points.len(), MAX_POINTS) {
        let p = points[i];
        if finite(&p) {
            let (x, y) = m.p(p);
            let _ = write!(
                path,
                "M{},{}h{d}v{d}h-{d}z",
                n1(x - radius_px),
                n1(y - radius_px)
            );
        }
    }
    if !path.is_empty() {
        let _ = write!(
            s,
            "<path d=\"{path}\" fill=\"{}\" fill-opacity=\"{}\"/>",
            colour(role),
            n2(style::POINTS_OPACITY)
        );
    }
}

/// Densities as ten opacity levels, one path each: a fine heat map stays small.
fn heatmap_svg(
    s: &mut String,
    m: &Map,
    min: DVec2,
    cell_m: f64,
    (cols, rows): (usize, usize),
    values: &[f32],
    role: Role,
) {
    let c = m.world.scale_px_per_m * cell_m;
    let mut levels: Vec<String> = vec![String::new(); 10];
    for row in 0..rows {
        for col in 0..cols {
            let Some(v) = values.get(row * cols + col) else {
                continue;
            };
            if v.is_nan() || *v <= 0.0 {
                continue;
            }
            let level = ((f64::from(v.min(1.0)) * 10.0).ceil() as usize).clamp(1, 10);
            let corner = min + DVec2::new(col as f64, (row + 1) as f64) * cell_m;
            let (x, y) = m.p(corner);
            let _ = write!(
                levels[level - 1],
                "M{},{}h{c}v{c}h-{c}z",
                n1(x),
                n1(y),
                c = n1(c)
            );
        }
    }
    for (i, path) in levels.iter().enumerate() {
        if !path.is_empty() {
            let _ = write!(
                s,
                "<path d=\"{path}\" fill=\"{}\" fill-opacity=\"{}\"/>",
                colour(role),
                format_number((i + 1) as f64 * 0.06, 2)
            );
        }
    }
}

fn ellipse_svg(
    s: &mut String,
    m: &Map,
    center: DVec2,
    (semi_axis_a, semi_axis_b): (DVec2, DVec2),
    role: Role,
) {
    let (x, y) = m.p(center);
    let ra = (semi_axis_a.length() * m.world.scale_px_per_m).max(0.5);
    let rb = (semi_axis_b.length() * m.world.scale_px_per_m).max(0.5);
    // Picture y points down, so the angle changes sign.
    let deg = -math::atan2(semi_axis_a.y, semi_axis_a.x).to_degrees();
    let _ = write!(
        s,
        "<ellipse cx=\"0\" cy=\"0\" rx=\"{}\" ry=\"{}\" transform=\"translate({} {}) rotate({})\" \
         fill=\"{c}\" fill-opacity=\"{}\" stroke=\"{c}\" stroke-width=\"{}\"/>",
        n1(ra),
        n1(rb),
        n1(x),
        n1(y),
        n1(deg),
        n2(style::FILL_OPACITY_LIGHT),
        n2(style::OUTLINE_PX),
        c = colour(role)
    );
}

fn label_svg(
    s: &mut String,
    m: &Map,
    (w, h): (f64, f64),
    pos: DVec2,
    offset_px: DVec2,
    text: &str,
    role: Role,
) {
    let (x, y) = m.p(pos);
    let x = (x + offset_px.x).clamp(4.0, (w - 4.0).max(4.0));
    let y = (y + offset_px.y).clamp(10.0, (h - 10.0).max(10.0));
    let _ = write!(
        s,
        "<text x=\"{}\" y=\"{}\" dominant-baseline=\"middle\" font-weight=\"600\" fill=\"{}\" \
         stroke=\"{}\" stroke-width=\"{}\" paint-order=\"stroke\">{}</text>",
        n1(x),
        n1(y),
        colour(role),
        CANVAS.light,
        n2(style::LABEL_HALO_PX),
        escape(text)
    );
}

/// The finite points as an SVG `points` list.
fn points_attr(m: &Map, points: &[DVec2]) -> String {
    let pts: Vec<String> = points
        .iter()
        .filter(|p| finite(p))
        .map(|p| m.xy(*p))
        .collect();
    pts.join(" ")
}

fn polyline_svg(
    s: &mut String,
    m: &Map,
    points: &[DVec2],
    width_px: f64,
    role: Role,
    (dashed, closed): (bool, bool),
) {
    let _ = write!(
        s,
        "<{tag} points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"{}/>",
        points_attr(m, points),
        colour(role),
        n1(width_px),
        dash(dashed),
        tag = if closed { "polygon" } else { "polyline" }
    );
}

/// Fill and outline of a filled polygon or rectangle.
fn filled_paint(role: Role) -> String {
    format!(
        "fill=\"{c}\" fill-opacity=\"{}\" stroke=\"{c}\" stroke-width=\"{}\"",
        n2(style::FILL_OPACITY),
        n2(style::OUTLINE_PX),
        c = colour(role)
    )
}

fn polygon_svg(s: &mut String, m: &Map, points: &[DVec2], role: Role) {
    let _ = write!(
        s,
        "<polygon points=\"{}\" {}/>",
        points_attr(m, points),
        filled_paint(role)
    );
}

fn rect_svg(s: &mut String, m: &Map, (min, max): (DVec2, DVec2), role: Role, fill: bool) {
    let (a, b) = (m.p(min), m.p(max));
    let paint = if fill {
        filled_paint(role)
    } else {
        format!(
            "fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"",
            colour(role),
            n2(style::OUTLINE_PX)
        )
    };
    let _ = write!(
        s,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" {paint}/>",
        n1(a.0.min(b.0)),
        n1(a.1.min(b.1)),
        n1((b.0 - a.0).abs()),
        n1((b.1 - a.1).abs())
    );
}

/// Arrows of one role as one path (at most [`MAX_POINTS`] of them).
fn arrows_svg(s: &mut String, m: &Map, arrows: &[(DVec2, DVec2)], width_px: f64, role: Role) {
    let d: String = thin(arrows.len(), MAX_POINTS)
        .map(|i| arrow_path(m, arrows[i].0, arrows[i].1, width_px))
        .collect();
    if !d.is_empty() {
        let _ = write!(
            s,
            "<path d=\"{d}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"/>",
            colour(role),
            n1(width_px)
        );
    }
}

/// A batch of segments as one path: at most the first [`MAX_SEGMENTS`].
fn segments_svg(
    s: &mut String,
    segments: &[(DVec2, DVec2)],
    width_px: f64,
    role: Role,
    m: &Map,
    notes: &mut Vec<String>,
) {
    if segments.len() > MAX_SEGMENTS {
        notes.push(format!(
            "the first {MAX_SEGMENTS} of {} edges drawn",
            segments.len()
        ));
    }
    // Whole units and a relative end point: about ten bytes an edge.
    let mut d = String::new();
    for (a, b) in segments.iter().take(MAX_SEGMENTS) {
        if finite(a) && finite(b) {
            let (pa, pb) = (m.p(*a), m.p(*b));
            let (ax, ay) = (pa.0.round(), pa.1.round());
            let _ = write!(
                d,
                "M{} {}l{} {}",
                format_number(ax, 0),
                format_number(ay, 0),
                format_number(pb.0 - ax, 1),
                format_number(pb.1 - ay, 1)
            );
        }
    }
    if !d.is_empty() {
        let _ = write!(
            s,
            "<path d=\"{d}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"/>",
            colour(role),
            n1(width_px)
        );
    }
}

/// A grid of cells as horizontal runs of one state, one path per state; at
/// most [`MAX_RASTER_RUNS`] runs.
#[allow(clippy::too_many_arguments)]
fn raster_svg(
    s: &mut String,
    min: DVec2,
    cell_m: f64,
    (cols, rows): (usize, usize),
    cells: &[u8],
    palette: &[RasterColour],
    m: &Map,
    notes: &mut Vec<String>,
) {
    if cols == 0 || rows == 0 || cells.len() < cols * rows {
        return;
    }
    let mut paths: Vec<String> = vec![String::new(); palette.len()];
    let c = m.world.scale_px_per_m * cell_m;
    let mut runs = 0usize;
    let mut skipped = false;
    'rows: for row in 0..rows {
        let line = &cells[row * cols..(row + 1) * cols];
        let mut col = 0;
        while col < cols {
            let state = line[col];
            let start = col;
            while col < cols && line[col] == state {
                col += 1;
            }
            let Some(path) = (state as usize)
                .checked_sub(1)
                .and_then(|i| paths.get_mut(i))
            else {
                continue;
            };
            if runs >= MAX_RASTER_RUNS {
                skipped = true;
                break 'rows;
            }
            runs += 1;
            let corner = min + DVec2::new(start as f64, (row + 1) as f64) * cell_m;
            let (x, y) = m.p(corner);
            let _ = write!(
                path,
                "M{},{}h{}v{}h-{}z",
                n1(x),
                n1(y),
                n1(c * (col - start) as f64),
                n1(c),
                n1(c * (col - start) as f64)
            );
        }
    }
    for (path, state) in paths.iter().zip(palette) {
        if !path.is_empty() {
            let _ = write!(
                s,
                "<path d=\"{path}\" fill=\"{}\" fill-opacity=\"{}\"/>",
                colour(state.role),
                format_number(f64::from(state.alpha.clamp(0.0, 1.0)), 2)
            );
        }
    }
    if skipped {
        notes.push(format!(
            "the grid ({cols} × {rows} cells) is too detailed to draw here in full: open the link to see it"
        ));
    }
}

/// A point outside the picture: an arrowhead on the edge pointing at it,
/// with its label toward the inside (as on the canvas).
fn off_view_svg(s: &mut String, m: &Map, (w, h): (f64, f64), at: DVec2, label: &str, role: Role) {
    let (px, py) = m.p(at);
    let p = DVec2::new(px, py);
    if !p.is_finite() || (px >= 0.0 && px <= w && py >= 0.0 && py <= h) {
        return;
    }
    let c = DVec2::new(w, h) * 0.5;
    let d = p - c;
    let half = (c - DVec2::splat(6.0)).max(DVec2::splat(1.0));
    let t = (half.x / d.x.abs()).min(half.y / d.y.abs());
    let tip = c + d * t;
    let u = d.normalize_or_zero();
    let nrm = DVec2::new(-u.y, u.x) * 8.0;
    let back = tip - u * 14.0;
    let (l, r) = (back + nrm, back - nrm);
    let at_text = back - u * 6.0;
    let _ = write!(
        s,
        "<path d=\"M{},{}L{},{}L{},{}z\" fill=\"{c}\" stroke=\"{bg}\" stroke-width=\"1.5\"/>\
         <text x=\"{}\" y=\"{}\" text-anchor=\"middle\" dominant-baseline=\"middle\" font-weight=\"600\" \
         fill=\"{c}\" stroke=\"{bg}\" stroke-width=\"{halo}\" paint-order=\"stroke\">{}</text>",
        n1(tip.x),
        n1(tip.y),
        n1(l.x),
        n1(l.y),
        n1(r.x),
        n1(r.y),
        n1(at_text.x.clamp(40.0, (w - 40.0).max(40.0))),
        n1(at_text.y.clamp(14.0, (h - 6.0).max(14.0))),
        escape(label),
        c = colour(role),
        bg = CANVAS.light,
        halo = n2(style::LABEL_HALO_PX)
    );
}

/// A shaft and a two-stroke head sized in pixels (as on the canvas).
fn arrow_path(m: &Map, from: DVec2, to: DVec2, width_px: f64) -> String {
    if !(finite(&from) && finite(&to)) {
        return String::new();
    }
    let (a, b) = (m.world.to_px(from), m.world.to_px(to));
    let Some([l, b, r]) = arrow_head(a, b, width_px) else {
        return String::new();
    };
    format!(
        "M{},{}L{},{}M{},{}L{},{}L{},{}",
        n1(a.x),
        n1(a.y),
        n1(b.x),
        n1(b.y),
        n1(l.x),
        n1(l.y),
        n1(b.x),
        n1(b.y),
        n1(r.x),
        n1(r.y)
    )
}

/// A metre scale bar in the lower left corner, the canvas's: the largest
/// round length at most [`SCALE_BAR_MAX_PX`] units long, with the same text.
fn scale_bar(s: &mut String, scale: f64, h: f64) {
    let Some(ScaleBar { length_m, label }) = ScaleBar::fit(scale, SCALE_BAR_MAX_PX) else {
        return;
    };
    let len = length_m * scale;
    let (x, y) = (14.0, h - 14.0);
    let _ = write!(
        s,
        "<path d=\"M{x},{}V{y}H{}V{}\" fill=\"none\" stroke=\"{ink}\" stroke-width=\"{}\"/>\
         <text x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"{ink}\">{label}</text>",
        n1(y - 5.0),
        n1(x + len),
        n1(y - 5.0),
        n2(style::OUTLINE_PX),
        n1(x + len / 2.0),
        n1(y - 8.0),
        x = n1(x),
        y = n1(y),
        ink = colour(Role::Text)
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use labcore::rng::Lcg64;

    /// Random views of every shape and random points, in and out of view:
    /// the report's picture maps a point where the canvas would at the
    /// picture's size (both are [`WorldMap`]) and where the report's own
    /// corner-origin formula did before it shared the map (y up, the view's
    /// top-left corner at the picture's origin); an arrow's path holds the
    /// canvas's head points.
    #[test]
    fn the_report_maps_points_and_arrow_heads_as_the_canvas_does() {
        let mut rng = Lcg64::new(54);
        for _ in 0..500 {
            let min = DVec2::new(rng.range(-50.0, 50.0), rng.range(-50.0, 50.0));
            let size = DVec2::new(rng.range(0.05, 80.0), rng.range(0.05, 80.0));
            let view = ViewBox {
                min,
                max: min + size,
            };
            let (m, (w, h)) = picture(view);
            let canvas = WorldMap::fit(view, w, h);
            let scale = (MAX_W / size.x).min(MAX_H / size.y);
            for _ in 0..4 {
                let p =
                    min + DVec2::new(rng.range(-0.5, 1.5) * size.x, rng.range(-0.5, 1.5) * size.y);
                let (x, y) = m.p(p);
                let c = canvas.to_px(p);
                let corner = ((p.x - min.x) * scale, (view.max.y - p.y) * scale);
                let tol = 1e-9 * (w + h);
                assert!(
                    (x - c.x).abs() < tol && (y - c.y).abs() < tol,
                    "{view:?} {p}"
                );
                assert!(
                    (x - corner.0).abs() < tol && (y - corner.1).abs() < tol,
                    "{view:?} {p}"
                );
            }
            let (a, b) = (
                min + size * 0.2,
                min + size * DVec2::new(rng.next_f64(), rng.next_f64()),
            );
            let width_px = rng.range(0.5, 4.0);
            let path = arrow_path(&m, a, b, width_px);
            match arrow_head(canvas.to_px(a), canvas.to_px(b), width_px) {
                Some([l, tip, r]) => {
                    let head = format!(
                        "M{},{}L{},{}L{},{}",
                        n1(l.x),
                        n1(l.y),
                        n1(tip.x),
                        n1(tip.y),
                        n1(r.x),
                        n1(r.y)
                    );
                    assert!(path.ends_with(&head), "{path} lacks {head}");
                }
                None => assert_eq!(path, ""),
            }
        }
    }

    #[test]
    fn the_scale_bar_reads_in_metres_as_on_the_canvas() {
        // 240 units per metre: 0.5 m is 120 units, the longest that fits.
        let mut s = String::new();
        scale_bar(&mut s, 240.0, 300.0);
        assert!(s.contains(">0.5 m</text>"), "{s}");
        assert!(s.contains("M14,281V286H134V281"), "{s}");
        // 50 units per metre: 2 m, 100 units long.
        let mut s = String::new();
        scale_bar(&mut s, 50.0, 300.0);
        assert!(s.contains(">2 m</text>"), "{s}");
        // No scale, no bar (and no panic).
        let mut s = String::new();
        scale_bar(&mut s, f64::NAN, 300.0);
        assert_eq!(s, "");
    }
}
