//! Draws the experiment's [`Plot`]s: axes with readable ticks (linear or
//! log), shaded bands, reference lines, decimated series with a colour *and*
//! a dash per role, event markers, the nearest sample under the pointer, a
//! text summary for screen readers, a data table on request and CSV export.

use crate::dom::{self, escape, query, query_all};
use crate::draw::Palette;
use crate::viewport::clip_segment;
use labcore::layout::ticks::tick_labels;
use labcore::math;
use labcore::plot::{axis_ticks, column_spans, dash_is_on, log_ticks, Axis, Plot, SeriesRole};
use labcore::scene::style::{BAND_OPACITY, PLOT_BAND, REF_LINE_DASH_PX};
use labcore::units::{format_number, power_of_ten};
use labcore::Role;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{
    CanvasRenderingContext2d, Element, HtmlCanvasElement, HtmlElement, ImageBitmapRenderingContext,
    OffscreenCanvas,
};

/// Most rows shown in a plot's data table (the CSV always has every row).
const TABLE_ROWS_MAX: usize = 500;
/// Plot margins, CSS pixels: left (y tick labels), right, top, bottom (x ticks and label).
const MARGIN: (f64, f64, f64, f64) = (58.0, 12.0, 10.0, 37.0);
/// Width of a series' line, CSS pixels.
const SERIES_LINE_PX: f64 = 2.0;

/// CSS custom property and dash pattern of each series role (the style
/// table's): every pair of roles differs in dash as well as colour.
fn role_style(role: SeriesRole) -> (&'static str, &'static [f64]) {
    let style = role.style();
    (style.colour.var, style.dash_px)
}

fn dash_attr(dash: &[f64]) -> String {
    dash.iter()
        .map(|d| format!("{d}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A series' legend entry: its line style and its label (a pinned run's
/// label names its gains, so it changes with the run).
fn legend_entry_html(s: &labcore::Series) -> String {
    let (var, dash) = role_style(s.role);
    // `.p-1 { color: var(--p-1) }` in web/style.css: a class, not a `style`
    // attribute, which the Content-Security-Policy forbids.
    let class = var.trim_start_matches('-');
    format!(
        "<svg width=\"26\" height=\"10\" aria-hidden=\"true\">\
         <line x1=\"1\" y1=\"5\" x2=\"25\" y2=\"5\" class=\"{class}\" stroke=\"currentColor\" stroke-width=\"2.5\" stroke-dasharray=\"{}\"/></svg>{}",
        dash_attr(dash),
        escape(&s.label),
    )
}

/// The HTML of one plot (empty canvas; [`PlotView::draw`] fills it).
#[must_use]
pub fn render(plot: &Plot) -> String {
    let legend: String = plot
        .series
        .iter()
        .enumerate()
        .map(|(i, s)| {
            format!(
                "<span class=\"legend-item\" data-series=\"{i}\"{hidden}>{}</span>",
                legend_entry_html(s),
                hidden = if s.is_empty() { " hidden" } else { "" },
            )
        })
        .collect();
    let key = plot.key;
    let fit = if plot.series.iter().any(|s| s.comparison) {
        format!(
            "<button type=\"button\" class=\"mini\" data-plot-fit=\"{key}\" aria-pressed=\"false\" \
             title=\"Fit the time axis to the latest run, not the longest kept one\">Fit latest run</button>"
        )
    } else {
        String::new()
    };
    let extra = legend_extra_html(plot);
    format!(
        "<figure class=\"plot\" data-plot=\"{key}\">\
         <figcaption><span class=\"plot-title\">{title}</span>\
         <span class=\"plot-tools\">{fit}<button type=\"button\" class=\"mini\" data-plot-csv=\"{key}\">CSV</button>\
         <button type=\"button\" class=\"mini\" data-plot-table=\"{key}\" aria-expanded=\"false\">Table</button></span></figcaption>\
         <div class=\"plot-legend\">{legend}<span class=\"legend-extra\">{extra}</span></div>\
         <div class=\"plot-box\"><canvas class=\"plot-canvas\" role=\"img\" aria-label=\"{title}\"></canvas>\
         <span class=\"plot-cursor\" aria-hidden=\"true\" hidden></span>\
         <output class=\"plot-tip\" hidden></output></div>\
         <p class=\"sr-only plot-summary\"></p>\
         <div class=\"plot-table\" hidden></div></figure>",
        title = escape(plot.title),
    )
}

/// Legend entries for the shaded bands and the reference lines (one per
/// distinct label), so every mark on the plot is named.
#[must_use]
pub fn legend_extra_html(plot: &Plot) -> String {
    let mut seen: Vec<&str> = Vec::new();
    let mut html = String::new();
    for band in &plot.bands {
        if band.label.is_empty() || seen.contains(&band.label.as_str()) {
            continue;
        }
        seen.push(&band.label);
        html.push_str(&format!(
            "<span class=\"legend-item\" data-legend=\"band\"><svg width=\"26\" height=\"12\" aria-hidden=\"true\">\
             <rect x=\"1\" y=\"1\" width=\"24\" height=\"10\" class=\"p-band\" fill=\"currentColor\" fill-opacity=\"0.3\"/></svg>{}</span>",
            escape(&band.label)
        ));
    }
    for line in &plot.ref_lines {
        if line.label.is_empty() || seen.contains(&line.label.as_str()) {
            continue;
        }
        seen.push(&line.label);
        html.push_str(&format!(
            "<span class=\"legend-item\" data-legend=\"line\"><svg width=\"26\" height=\"10\" aria-hidden=\"true\">\
             <line x1=\"1\" y1=\"5\" x2=\"25\" y2=\"5\" class=\"p-5\" stroke=\"currentColor\" stroke-width=\"1.5\" stroke-dasharray=\"{}\"/></svg>{}</span>",
            dash_attr(&REF_LINE_DASH_PX),
            escape(&line.label)
        ));
    }
    html
}

/// The x range to show: with `fit_latest`, only the series that are not kept
/// for comparison count (the latest run), when they have samples.
#[must_use]
pub fn x_range_for(plot: &Plot, fit_latest: bool) -> Option<(f64, f64)> {
    let all = plot.x_range()?;
    if !fit_latest || !matches!(plot.window, labcore::plot::XWindow::All) {
        return Some(all);
    }
    let (lo, hi) = plot
        .series
        .iter()
        .filter(|s| !s.comparison)
        .flat_map(|s| s.x.iter().copied())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
    Some(if lo <= hi { (lo, hi) } else { all })
}

/// A rectangle in CSS pixels: top-left corner and size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub x: f64,
    pub y: f64,
    pub w: f64,
    pub h: f64,
}

impl Rect {
    #[must_use]
    pub fn intersects(&self, o: &Rect) -> bool {
        self.x < o.x + o.w && o.x < self.x + self.w && self.y < o.y + o.h && o.y < self.y + self.h
    }

    #[must_use]
    pub fn inside(&self, outer: &Rect) -> bool {
        self.x >= outer.x
            && self.y >= outer.y
            && self.x + self.w <= outer.x + outer.w
            && self.y + self.h <= outer.y + outer.h
    }

    fn grown(&self, by: f64) -> Rect {
        Rect {
            x: self.x - by,
            y: self.y - by,
            w: self.w + 2.0 * by,
            h: self.h + 2.0 * by,
        }
    }

    /// Distance from `p` to the nearest point of the rectangle.
    fn distance_to(&self, p: (f64, f64)) -> f64 {
        let dx = (self.x - p.0).max(p.0 - (self.x + self.w)).max(0.0);
        let dy = (self.y - p.1).max(p.1 - (self.y + self.h)).max(0.0);
        (dx * dx + dy * dy).sqrt()
    }
}

/// Whether the segment `a`–`b` passes through `r`: its Liang–Barsky clip
/// to the rectangle ([`clip_segment`], moved to the rectangle's corner) is
/// not empty.
#[must_use]
pub fn segment_hits_rect(a: (f64, f64), b: (f64, f64), r: &Rect) -> bool {
    let corner = glam::DVec2::new(r.x, r.y);
    clip_segment(
        glam::DVec2::from(a) - corner,
        glam::DVec2::from(b) - corner,
        r.w,
        r.h,
    )
    .is_some()
}

/// How many things `r` would cover: curve segments and labels already placed.
fn collisions(r: &Rect, curves: &[Vec<(f64, f64)>], taken: &[Rect]) -> usize {
    let pad = r.grown(2.0);
    let labels = taken.iter().filter(|t| t.intersects(&pad)).count();
    let segments: usize = curves
        .iter()
        .map(|c| {
            if c.len() == 1 {
                usize::from(pad.distance_to(c[0]) <= 0.0)
            } else {
                c.windows(2)
                    .filter(|w| segment_hits_rect(w[0], w[1], &pad))
                    .count()
            }
        })
        .sum();
    labels * 1000 + segments
}

/// Places a `size` label near `anchor` inside `bounds`, off the `curves` and
/// the labels already `taken`: the first of `preferred` that is free, else
/// the free spot nearest the anchor, else the spot covering least.
#[must_use]
pub fn place_label(
    anchor: (f64, f64),
    size: (f64, f64),
    preferred: &[(f64, f64)],
    bounds: &Rect,
    curves: &[Vec<(f64, f64)>],
    taken: &[Rect],
) -> Rect {
    let (w, h) = size;
    let at = |x: f64, y: f64| Rect { x, y, w, h };
    let clamp = |r: Rect| Rect {
        x: r.x.clamp(bounds.x, (bounds.x + bounds.w - w).max(bounds.x)),
        y: r.y.clamp(bounds.y, (bounds.y + bounds.h - h).max(bounds.y)),
        w,
        h,
    };
    let score = |r: &Rect| collisions(r, curves, taken);
    let mut best: Option<(usize, f64, Rect)> = None;
    let keep = |best: &mut Option<(usize, f64, Rect)>, r: Rect, rank: f64| -> usize {
        let r = clamp(r);
        let hits = score(&r);
        if best.is_none_or(|(bh, br, _)| (hits, rank) < (bh, br)) {
            *best = Some((hits, rank, r));
        }
        hits
    };
    for (i, (x, y)) in preferred.iter().enumerate() {
        if keep(&mut best, at(*x, *y), -1.0 + i as f64 * 1e-3) == 0 {
            return best.map_or(at(anchor.0, anchor.1), |b| b.2);
        }
    }
    // A ring search: spots around the anchor, nearest first.
    RING_SPOTS.with(|cache| {
        let mut cache = cache.borrow_mut();
        let key = (w.to_bits(), h.to_bits());
        let at_key = match cache.iter().position(|(k, _)| *k == key) {
            Some(i) => i,
            None => {
                if cache.len() >= RING_SIZES_KEPT {
                    cache.remove(0);
                }
                cache.push((key, ring_spots(w, h)));
                cache.len() - 1
            }
        };
        for &(d, dx, dy) in &cache[at_key].1 {
            if d < 4.0 {
                continue; // never on the anchor itself
            }
            if keep(&mut best, at(anchor.0 + dx, anchor.1 + dy), d) == 0 {
                break;
            }
        }
    });
    best.map_or(clamp(at(anchor.0, anchor.1)), |b| b.2)
}

/// The ring search's spots for a `w` × `h` label: (distance to the anchor,
/// offset of the label's corner from it), nearest first, ties by x then y.
/// The order does not depend on where the anchor is, so one sort serves
/// every label of that size (a streaming plot places its labels at every
/// paint).
fn ring_spots(w: f64, h: f64) -> Vec<(f64, f64, f64)> {
    let (step_x, step_y) = (8.0, (h * 0.5).max(6.0));
    let mut spots = Vec::new();
    for i in -24..=24 {
        for j in -16..=16 {
            let (dx, dy) = (
                f64::from(i) * step_x - w / 2.0,
                f64::from(j) * step_y - h / 2.0,
            );
            let r = Rect { x: dx, y: dy, w, h };
            spots.push((r.distance_to((0.0, 0.0)), dx, dy));
        }
    }
    spots.sort_unstable_by(|a, b| {
        a.0.total_cmp(&b.0)
            .then(a.1.total_cmp(&b.1))
            .then(a.2.total_cmp(&b.2))
    });
    spots
}

/// Label sizes (as bits) with their [`ring_spots`], oldest first.
type RingCache = Vec<((u64, u64), Vec<(f64, f64, f64)>)>;

/// How many label sizes keep their ring: a plot has a few labels at most.
const RING_SIZES_KEPT: usize = 16;

thread_local! {
    static RING_SPOTS: std::cell::RefCell<RingCache> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Where the labels, ticks and titles of a drawn plot went (published on the
/// canvas as `data-layout` for tests).
#[derive(Clone, Debug, Default)]
pub struct Layout {
    pub labels: Vec<Rect>,
    pub x_ticks: Vec<(String, Rect)>,
    pub y_ticks: Vec<(String, Rect)>,
    pub x_title: Option<Rect>,
    pub y_title: Option<Rect>,
}

impl Layout {
    /// The layout as JSON, one decimal per coordinate. Built with integer
    /// formatting into one string: `{:.1}` takes the exact (and slow)
    /// float-formatting path, and this runs at every plot paint.
    fn json(&self) -> String {
        use std::fmt::Write as _;
        fn num(out: &mut String, v: f64) {
            let tenths = (v * 10.0).round();
            if !tenths.is_finite() || tenths.abs() >= 1e15 {
                out.push('0');
                return;
            }
            let n = tenths as i64;
            if n < 0 {
                out.push('-');
            }
            let a = n.unsigned_abs();
            let _ = write!(out, "{}.{}", a / 10, a % 10);
        }
        fn rect(out: &mut String, r: &Rect) {
            out.push('[');
            for (i, v) in [r.x, r.y, r.w, r.h].into_iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                num(out, v);
            }
            out.push(']');
        }
        fn ticks(out: &mut String, v: &[(String, Rect)]) {
            for (i, (t, r)) in v.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                out.push_str("[\"");
                out.extend(t.chars().filter(|c| *c != '"'));
                out.push_str("\",");
                rect(out, r);
                out.push(']');
            }
        }
        fn opt(out: &mut String, o: Option<&Rect>) {
            match o {
                Some(r) => rect(out, r),
                None => out.push_str("null"),
            }
        }
        let mut out = String::with_capacity(
            64 + 40 * (self.labels.len() + self.x_ticks.len() + self.y_ticks.len()),
        );
        out.push_str("{\"labels\":[");
        for (i, r) in self.labels.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            rect(&mut out, r);
        }
        out.push_str("],\"xticks\":[");
        ticks(&mut out, &self.x_ticks);
        out.push_str("],\"yticks\":[");
        ticks(&mut out, &self.y_ticks);
        out.push_str("],\"xtitle\":");
        opt(&mut out, self.x_title.as_ref());
        out.push_str(",\"ytitle\":");
        opt(&mut out, self.y_title.as_ref());
        out.push('}');
        out
    }
}

/// The pixel mapping of the last drawing, for the hover read-out.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Frame {
    x: (f64, f64),
    y: (f64, f64),
    log: bool,
    rect: (f64, f64, f64, f64),
}

impl Frame {
    fn px_x(&self, x: f64) -> f64 {
        let (l, _, w, _) = self.rect;
        l + (x - self.x.0) / (self.x.1 - self.x.0).max(f64::MIN_POSITIVE) * w
    }

    fn px_y(&self, y: f64) -> f64 {
        let (_, t, _, h) = self.rect;
        let (a, b, v) = if self.log {
            (
                math::log10(self.y.0),
                math::log10(self.y.1),
                math::log10(y.max(f64::MIN_POSITIVE)),
            )
        } else {
            (self.y.0, self.y.1, y)
        };
        t + h - (v - a) / (b - a).max(f64::MIN_POSITIVE) * h
    }

    fn world_x(&self, px: f64) -> f64 {
        let (l, _, w, _) = self.rect;
        self.x.0 + (px - l) / w.max(1.0) * (self.x.1 - self.x.0)
    }
}

/// One drawn plot: its canvas, the elements around it, and what was last
/// drawn or written there (so an unchanged value is never written again).
struct Drawn {
    key: &'static str,
    figure: Element,
    canvas: HtmlCanvasElement,
    /// The context painted on: the canvas's own, or the off-screen one.
    ctx: CanvasRenderingContext2d,
    surface: Surface,
    revision: Option<u64>,
    size: (f64, f64, f64),
    /// The canvas size (CSS px) and pixel ratio read by [`PlotView::measure`].
    measured: (f64, f64, f64),
    /// When it was last painted (animation-frame time, ms).
    painted_ms: f64,
    frame: Frame,
    hover_x: Option<f64>,
    /// Whether the x axis fits the latest run (the comparison runs ignored).
    fit_latest: bool,
    /// Where the timeline's cursor is drawn (plot x), while the timeline
    /// shows a past moment ([`PlotView::set_cursor`]).
    cursor_x: Option<f64>,
    /// What the canvas's `data-cursor` says ([`PlotView::sync_cursor_attrs`]).
    cursor_attr: Option<f64>,
    /// Where its labels went at the last paint.
    labels: LabelMemory,
    /// Whether its canvas was in the window at the last
    /// [`PlotView::measure`].
    on_screen: bool,
    /// The browser's observers watching its canvas (size, in the window).
    watch: Option<dom::BoxWatch>,
    parts: Parts,
    shown: Shown,
    /// The run's marked moments on this plot, in its units (see
    /// [`PlotView::set_marks`]).
    marks: Vec<(f64, f64)>,
}

/// Where a plot is painted.
///
/// Off screen where the browser can: the page then shows each finished
/// picture through a `bitmaprenderer` context. A 2D canvas on the page costs
/// the browser a copy of its whole bitmap at every frame the page changes,
/// whether the canvas changed or not (measured in Chromium with software
/// compositing: each 780 × 400 canvas adds about 1.7 ms a frame at a 4× CPU
/// throttle); a bitmap shown this way costs nothing until it is replaced.
enum Surface {
    Offscreen {
        offscreen: OffscreenCanvas,
        shown: ImageBitmapRenderingContext,
    },
    /// The canvas's own 2D context (browsers without `OffscreenCanvas`).
    Direct,
}

impl Surface {
    /// The off-screen surface for `canvas` and its 2D context, if the
    /// browser has one; `None` leaves the canvas free for a 2D context.
    fn offscreen(canvas: &HtmlCanvasElement) -> Option<(Self, CanvasRenderingContext2d)> {
        let offscreen = OffscreenCanvas::new(1, 1).ok()?;
        // An `OffscreenCanvasRenderingContext2D` has every method and
        // property of `CanvasRenderingContext2D` the plots use, and
        // wasm-bindgen calls them by name, so one set of bindings serves both.
        let ctx: CanvasRenderingContext2d =
            offscreen.get_context("2d").ok().flatten()?.unchecked_into();
        let shown = canvas
            .get_context("bitmaprenderer")
            .ok()
            .flatten()?
            .dyn_into::<ImageBitmapRenderingContext>()
            .ok()?;
        Some((Self::Offscreen { offscreen, shown }, ctx))
    }

    /// Sizes the surface's bitmap (and the canvas's) in device pixels.
    fn set_size(&self, canvas: &HtmlCanvasElement, w: u32, h: u32) {
        canvas.set_width(w);
        canvas.set_height(h);
        if let Self::Offscreen { offscreen, .. } = self {
            offscreen.set_width(w);
            offscreen.set_height(h);
        }
    }

    /// Shows what was painted since the last call.
    fn present(&self) {
        if let Self::Offscreen { offscreen, shown } = self {
            if let Ok(bitmap) = offscreen.transfer_to_image_bitmap() {
                shown.transfer_from_image_bitmap(&bitmap);
            }
        }
    }
}

/// The elements of a plot figure the drawing updates, found once at mount.
struct Parts {
    legend_extra: Option<Element>,
    fit: Option<Element>,
    summary: Option<Element>,
    table: Option<Element>,
    tip: Option<Element>,
    /// The timeline's cursor, laid over the canvas ([`Drawn::place_cursor`]).
    cursor: Option<HtmlElement>,
    /// The series' legend entries with their series index.
    legend: Vec<(usize, Element)>,
}

/// What the figure's elements show now.
#[derive(Default)]
struct Shown {
    legend_extra: String,
    layout: String,
    summary: Option<String>,
    fit_hidden: Option<bool>,
    /// Per legend entry: hidden, and the label it shows.
    legend: Vec<Option<(bool, String)>>,
    /// Where the cursor is laid (CSS px: x, top, height); `None` hidden
    /// (as the page starts it).
    cursor: Option<(f64, f64, f64)>,
}

/// Every plot of the mounted simulation.
pub struct PlotView {
    plots: Vec<Drawn>,
    /// When the summaries were last written (animation-frame time, ms).
    summaries_ms: f64,
}

/// Shortest time between two paints of one plot while its data streams,
/// milliseconds: a curve needs no 60 Hz, and the frame keeps its budget for
/// the simulation.
pub const PLOT_INTERVAL_MS: f64 = 66.0;

/// The same for a plot scrolled out of view: it is kept roughly up to date
/// (for a glance, a test or a screen reader's table) without costing the
/// frames of the plots a student is watching. On a phone most plots are
/// below the fold.
pub const HIDDEN_PLOT_INTERVAL_MS: f64 = 1000.0;

/// Shortest time between two writes of the plots' text summaries while a
/// run streams, milliseconds.
pub const SUMMARY_INTERVAL_MS: f64 = 1000.0;

impl PlotView {
    /// Finds the plot figures rendered by [`render`] inside `root`.
    pub fn mount(root: &Element) -> Self {
        let plots = query_all(root, "figure.plot")
            .into_iter()
            .filter_map(|figure| {
                let key = figure.get_attribute("data-plot")?;
                let canvas: HtmlCanvasElement = query(&figure, "canvas")?.dyn_into().ok()?;
                let (surface, ctx) = match Surface::offscreen(&canvas) {
                    Some(s) => s,
                    None => (
                        Surface::Direct,
                        canvas
                            .get_context("2d")
                            .ok()
                            .flatten()?
                            .dyn_into::<CanvasRenderingContext2d>()
                            .ok()?,
                    ),
                };
                let legend: Vec<(usize, Element)> = query_all(&figure, ".legend-item[data-series]")
                    .into_iter()
                    .filter_map(|item| {
                        let i = item.get_attribute("data-series")?.parse().ok()?;
                        Some((i, item))
                    })
                    .collect();
                let parts = Parts {
                    legend_extra: query(&figure, ".legend-extra"),
                    fit: query(&figure, "[data-plot-fit]"),
                    summary: query(&figure, ".plot-summary"),
                    table: query(&figure, ".plot-table"),
                    tip: query(&figure, ".plot-tip"),
                    cursor: query(&figure, ".plot-cursor").and_then(|e| e.dyn_into().ok()),
                    legend,
                };
                let shown = Shown {
                    legend: vec![None; parts.legend.len()],
                    ..Shown::default()
                };
                let watch = dom::watch_box(canvas.as_ref());
                Some(Drawn {
                    key: Box::leak(key.into_boxed_str()),
                    figure,
                    canvas,
                    ctx,
                    surface,
                    revision: None,
                    size: (0.0, 0.0, 0.0),
                    measured: (0.0, 0.0, 0.0),
                    painted_ms: f64::NEG_INFINITY,
                    frame: Frame::default(),
                    hover_x: None,
                    fit_latest: false,
                    cursor_x: None,
                    cursor_attr: None,
                    labels: LabelMemory::default(),
                    on_screen: true,
                    watch,
                    parts,
                    shown,
                    marks: Vec::new(),
                })
            })
            .collect::<Vec<Drawn>>();
        Self {
            plots,
            summaries_ms: f64::NEG_INFINITY,
        }
    }

    /// The shortest time between two paints of each plot now, ms.
    fn intervals(&self) -> Vec<f64> {
        self.plots
            .iter()
            .map(|d| {
                if d.on_screen {
                    PLOT_INTERVAL_MS
                } else {
                    HIDDEN_PLOT_INTERVAL_MS
                }
            })
            .collect()
    }

    /// Takes every plot canvas's size and whether it is in the window from
    /// what the browser's observers last told ([`dom::watch_box`]); it reads
    /// them only for a canvas not seen with a size yet (just mounted, or
    /// shown again). Call it before the frame writes to the page: reading a
    /// size after a write forces the browser to lay the page out again in
    /// the middle of the frame.
    pub fn measure(&mut self) {
        if self.plots.is_empty() {
            return;
        }
        let dpr = dom::window().device_pixel_ratio().max(1.0);
        for drawn in &mut self.plots {
            let seen = drawn.watch.as_ref().and_then(|w| w.seen.get());
            let seen = seen
                .filter(|s| s.width >= 1.0 && s.height >= 1.0)
                .unwrap_or_else(|| dom::read_box(drawn.canvas.as_ref()));
            drawn.measured = (seen.width, seen.height, dpr);
            // Scrolled out of view (or in a hidden panel: no size).
            drawn.on_screen = seen.on_screen();
        }
    }

    /// Whether some plot may be painted at `now_ms` (its last paint is at
    /// least [`PLOT_INTERVAL_MS`] old, [`HIDDEN_PLOT_INTERVAL_MS`] if it is
    /// out of view).
    #[must_use]
    pub fn due(&self, now_ms: f64) -> bool {
        self.plots
            .iter()
            .zip(self.intervals())
            .any(|(d, interval)| now_ms - d.painted_ms >= interval)
    }

    /// Repaints the plots whose data, size or theme changed (every plot with
    /// `force`), at the sizes of the last [`PlotView::measure`].
    pub fn draw(&mut self, plots: &[Plot], palette: &Palette, force: bool) {
        for drawn in &mut self.plots {
            if let Some(plot) = plots.iter().find(|p| p.key == drawn.key) {
                if force || drawn.stale(plot) {
                    drawn.paint(plot, palette);
                }
            }
        }
    }

    /// Writes every plot's text summary that changed. The frame loop calls it
    /// with the rest of the page's text, not at every plot paint: at once
    /// with `now` (an input, the end of a motion), else at most every
    /// [`SUMMARY_INTERVAL_MS`]. Summaries are read on demand by a screen
    /// reader, not watched; every text written costs the page a layout.
    pub fn sync_text(&mut self, plots: &[Plot], now_ms: f64, now: bool) {
        if !now && now_ms - self.summaries_ms < SUMMARY_INTERVAL_MS {
            return;
        }
        self.summaries_ms = now_ms;
        for drawn in &mut self.plots {
            if let Some(plot) = plots.iter().find(|p| p.key == drawn.key) {
                drawn.sync_summary(plot);
            }
        }
    }

    /// Paints at most one plot at animation-frame time `now_ms`: of those
    /// whose data or size changed and whose last paint is at least
    /// [`PLOT_INTERVAL_MS`] old ([`HIDDEN_PLOT_INTERVAL_MS`] out of view),
    /// the one painted longest ago. Several plots
    /// streaming together thus take turns, one a frame, each still about
    /// every [`PLOT_INTERVAL_MS`]. Uses the sizes of the last
    /// [`PlotView::measure`]. Returns whether a plot was painted.
    pub fn draw_next(&mut self, plots: &[Plot], palette: &Palette, now_ms: f64) -> bool {
        let intervals = self.intervals();
        let next = self
            .plots
            .iter_mut()
            .zip(intervals)
            .filter(|(d, interval)| now_ms - d.painted_ms >= *interval)
            .map(|(d, _)| d)
            .filter_map(|d| {
                let plot = plots.iter().find(|p| p.key == d.key)?;
                d.stale(plot).then_some((d, plot))
            })
            .min_by(|a, b| a.0.painted_ms.total_cmp(&b.0.painted_ms));
        match next {
            Some((drawn, plot)) => {
                drawn.paint(plot, palette);
                drawn.painted_ms = now_ms;
                true
            }
            None => false,
        }
    }

    /// The pointer is over a plot canvas at client x `client_x` (or left it: `None`).
    pub fn hover(
        &mut self,
        canvas: &Element,
        client_x: Option<f64>,
        plots: &[Plot],
        palette: &Palette,
    ) {
        let Some(drawn) = self
            .plots
            .iter_mut()
            .find(|d| d.canvas.unchecked_ref::<Element>() == canvas)
        else {
            return;
        };
        let Some(plot) = plots.iter().find(|p| p.key == drawn.key) else {
            return;
        };
        drawn.hover_x = client_x.map(|cx| {
            let left = drawn.canvas.get_bounding_client_rect().left();
            drawn.frame.world_x(cx - left)
        });
        drawn.frame = paint_plot_layout(
            &drawn.ctx,
            plot,
            palette,
            drawn.size,
            drawn.fit_latest,
            &mut drawn.labels,
        )
        .0;
        paint_marks(&drawn.ctx, &drawn.frame, &drawn.marks, palette);
        match drawn.hover_x {
            Some(x) => show_nearest(drawn, plot, palette, x),
            None => {
                if let Some(tip) = &drawn.parts.tip {
                    dom::set_hidden(tip, true);
                }
            }
        }
        drawn.surface.present();
    }

    /// The run's marked moments (issue 26 §3): for each mark, its points on
    /// each plot (plot key, points in the plot's units). A plot whose points
    /// changed is painted again.
    pub fn set_marks(&mut self, marks: &[(u64, labcore::marks::PlotPoints)]) {
        for drawn in &mut self.plots {
            let points: Vec<(f64, f64)> = marks
                .iter()
                .flat_map(|(_, plots)| plots.iter().filter(|(k, _)| *k == drawn.key))
                .flat_map(|(_, p)| p.iter().copied())
                .collect();
            if points != drawn.marks {
                drawn.marks = points;
                drawn.revision = None;
                let text: Vec<String> = drawn
                    .marks
                    .iter()
                    .map(|(x, y)| format!("{x},{y}"))
                    .collect();
                let _ = drawn.canvas.set_attribute("data-marks", &text.join(" "));
            }
        }
    }

    /// Puts the timeline's cursor on plot `key` at plot x `x` (`None`: no
    /// cursor, the run shown live). The cursor is an element laid over the
    /// canvas, so moving it repaints nothing: a scrub costs the plots only
    /// a style change while the record they show stays the same. The
    /// canvas's `data-cursor` follows at the text's pace
    /// ([`PlotView::sync_cursor_attrs`]).
    pub fn set_cursor(&mut self, key: &str, x: Option<f64>) {
        if let Some(drawn) = self.plots.iter_mut().find(|d| d.key == key) {
            if drawn.cursor_x != x {
                drawn.cursor_x = x;
                drawn.place_cursor();
            }
        }
    }

    /// Writes each canvas's `data-cursor` (the cursor's plot x, for tests
    /// and tools) where it differs from the cursor. Written with the page's
    /// text, not at every move of a drag: an attribute write re-styles the
    /// canvas (0.4 ms of a cartpole scrub frame with three plots).
    pub fn sync_cursor_attrs(&mut self) {
        for drawn in &mut self.plots {
            if drawn.cursor_attr == drawn.cursor_x {
                continue;
            }
            drawn.cursor_attr = drawn.cursor_x;
            match drawn.cursor_x {
                Some(x) => {
                    let _ = drawn.canvas.set_attribute("data-cursor", &format!("{x}"));
                }
                None => {
                    let _ = drawn.canvas.remove_attribute("data-cursor");
                }
            }
        }
    }

    /// The plot whose canvas is `canvas` and the plot x under client x
    /// `client_x` (as last drawn): a point clicked on the plot.
    #[must_use]
    pub fn point_at(&self, canvas: &Element, client_x: f64) -> Option<(&'static str, f64)> {
        let drawn = self
            .plots
            .iter()
            .find(|d| d.canvas.unchecked_ref::<Element>() == canvas)?;
        let left = drawn.canvas.get_bounding_client_rect().left();
        let x = drawn.frame.world_x(client_x - left);
        x.is_finite().then_some((drawn.key, x))
    }

    /// The key of the plot drawn on `canvas`.
    #[must_use]
    pub fn key_of(&self, canvas: &Element) -> Option<&'static str> {
        self.plots
            .iter()
            .find(|d| d.canvas.unchecked_ref::<Element>() == canvas)
            .map(|d| d.key)
    }

    /// Switches a plot between fitting the latest run and every run (the
    /// "Fit latest run" button); returns whether it now fits the latest.
    pub fn toggle_fit(&mut self, key: &str) -> bool {
        let Some(drawn) = self.plots.iter_mut().find(|d| d.key == key) else {
            return false;
        };
        drawn.fit_latest = !drawn.fit_latest;
        drawn.revision = None;
        if let Some(button) = &drawn.parts.fit {
            let _ = button.set_attribute(
                "aria-pressed",
                if drawn.fit_latest { "true" } else { "false" },
            );
        }
        drawn.fit_latest
    }

    /// Shows or hides a plot's data table; returns whether it is now shown.
    pub fn toggle_table(&self, key: &str, plots: &[Plot]) -> bool {
        let (Some(drawn), Some(plot)) = (
            self.plots.iter().find(|d| d.key == key),
            plots.iter().find(|p| p.key == key),
        ) else {
            return false;
        };
        let Some(table) = &drawn.parts.table else {
            return false;
        };
        let show = table.has_attribute("hidden");
        if show {
            table.set_inner_html(&table_html(plot));
        }
        dom::set_hidden(table, !show);
        if let Some(button) = query(&drawn.figure, "[data-plot-table]") {
            let _ = button.set_attribute("aria-expanded", if show { "true" } else { "false" });
        }
        show
    }
}

impl Drawn {
    /// Lays the timeline's cursor over the canvas at [`Drawn::cursor_x`]
    /// as last painted (CSS px, the canvas's frame): a solid vertical line
    /// in the text colour with a small triangle on top, unlike the dashed
    /// reference lines (the style sheet's `.plot-cursor`). Hidden with no
    /// cursor or outside the plot's x range. Writes only what changed.
    fn place_cursor(&mut self) {
        let Some(el) = &self.parts.cursor else {
            return;
        };
        let (l, t, w, h) = self.frame.rect;
        let px = self.cursor_x.map(|x| self.frame.px_x(x));
        let place = px
            .filter(|px| w > 0.0 && (l - 0.5..=l + w + 0.5).contains(px))
            .map(|px| (px, t, h));
        if self.shown.cursor == place {
            return;
        }
        // Hidden by `visibility` once first shown, not by the `hidden`
        // attribute: the style sheet's `:has()` rules name `hidden`, so each
        // toggle would re-style the page's sections above it. Hidden, it
        // still takes room: at the box's corner with no height, where no
        // resize pushes it past the plot. A scrub moves it; its height is
        // written only when it changes (shown or hidden, a resized plot).
        let style = el.style();
        let transform = place.map_or("none".into(), |(px, t, _)| {
            format!("translate({px:.1}px,{t:.1}px)")
        });
        let _ = style.set_property("transform", &transform);
        let height = |p: Option<(f64, f64, f64)>| p.map_or(0.0, |c| c.2);
        if self.shown.cursor.is_none() || height(self.shown.cursor) != height(place) {
            let _ = style.set_property("height", &format!("{:.1}px", height(place)));
        }
        if self.shown.cursor.is_some() != place.is_some() {
            el.set_hidden(false);
            let _ = style.set_property("visibility", if place.is_some() { "" } else { "hidden" });
        }
        self.shown.cursor = place;
    }

    /// Writes the plot's text summary (read by screen readers) if it changed.
    fn sync_summary(&mut self, plot: &Plot) {
        if let Some(summary) = &self.parts.summary {
            let text = plot.summary();
            if self.shown.summary.as_deref() != Some(text.as_str()) {
                dom::set_text(summary, &text);
                self.shown.summary = Some(text);
            }
        }
    }

    /// Whether the plot's data or the measured size differ from what is drawn.
    fn stale(&self, plot: &Plot) -> bool {
        self.measured.0 >= 1.0
            && (self.revision != Some(plot.revision) || self.size != self.measured)
    }

    /// Paints the plot at the measured size and brings the figure's legend,
    /// summary and table up to date, writing only what changed.
    fn paint(&mut self, plot: &Plot, palette: &Palette) {
        let size = self.measured;
        if size.0 < 1.0 {
            return;
        }
        if self.size != size {
            self.surface.set_size(
                &self.canvas,
                (size.0 * size.2).round() as u32,
                (size.1 * size.2).round() as u32,
            );
            self.size = size;
        }
        self.revision = Some(plot.revision);
        let (frame, layout) = paint_plot_layout(
            &self.ctx,
            plot,
            palette,
            size,
            self.fit_latest,
            &mut self.labels,
        );
        self.frame = frame;
        paint_marks(&self.ctx, &self.frame, &self.marks, palette);
        self.place_cursor();
        let json = layout.json();
        if json != self.shown.layout {
            let _ = self.canvas.set_attribute("data-layout", &json);
            self.shown.layout = json;
        }
        let extra = legend_extra_html(plot);
        if extra != self.shown.legend_extra {
            if let Some(span) = &self.parts.legend_extra {
                span.set_inner_html(&extra);
            }
            self.shown.legend_extra = extra;
        }
        if let Some(x) = self.hover_x {
            show_nearest(self, plot, palette, x);
        }
        self.surface.present();
        // "Fit latest run" only means something once a run is kept.
        if let Some(button) = &self.parts.fit {
            let hide = !plot.series.iter().any(|s| s.comparison && !s.is_empty());
            if self.shown.fit_hidden != Some(hide) {
                dom::set_hidden(button, hide);
                self.shown.fit_hidden = Some(hide);
            }
        }
        // A series with no samples yet (an empty slot for a pinned run) has
        // no legend entry; a label that changed (a pin named after its
        // gains) is rewritten.
        for ((i, item), shown) in self.parts.legend.iter().zip(self.shown.legend.iter_mut()) {
            let series = plot.series.get(*i);
            let hide = series.is_none_or(labcore::Series::is_empty);
            let label = series.map_or("", |s| s.label.as_str());
            match shown {
                Some((h, l)) if *h == hide && l == label => continue,
                _ => {}
            }
            if shown.as_ref().is_none_or(|(h, _)| *h != hide) {
                dom::set_hidden(item, hide);
            }
            if let Some(s) = series {
                if item.text_content().as_deref() != Some(s.label.as_str()) {
                    item.set_inner_html(&legend_entry_html(s));
                }
            }
            *shown = Some((hide, label.to_owned()));
        }
        if let Some(table) = &self.parts.table {
            if !table.has_attribute("hidden") {
                table.set_inner_html(&table_html(plot));
            }
        }
    }
}

/// Draws the run's marked moments: a downward triangle at each point, in
/// the text colour with a background outline (a shape, not a colour, tells
/// a mark from the curves and the event diamonds).
fn paint_marks(
    ctx: &CanvasRenderingContext2d,
    frame: &Frame,
    marks: &[(f64, f64)],
    palette: &Palette,
) {
    if marks.is_empty() || frame.rect.2 <= 0.0 {
        return;
    }
    let (l, t, w, h) = frame.rect;
    ctx.save();
    ctx.begin_path();
    ctx.rect(l - 6.0, t - 6.0, w + 12.0, h + 12.0);
    ctx.clip();
    set_dash(ctx, &[]);
    ctx.set_line_width(2.0);
    ctx.set_stroke_style_str(&palette.background);
    ctx.set_fill_style_str(palette.colour(Role::Text));
    for &(x, y) in marks {
        let (px, py) = (frame.px_x(x), frame.px_y(y));
        ctx.begin_path();
        ctx.move_to(px - 6.0, py - 10.0);
        ctx.line_to(px + 6.0, py - 10.0);
        ctx.line_to(px, py);
        ctx.close_path();
        ctx.stroke();
        ctx.fill();
    }
    ctx.restore();
}

fn axis_title(label: &str, unit: &str) -> String {
    if unit.is_empty() {
        label.to_owned()
    } else {
        format!("{label} ({unit})")
    }
}

fn set_dash(ctx: &CanvasRenderingContext2d, dash: &[f64]) {
    let pattern = js_sys::Array::new();
    for d in dash {
        pattern.push(&JsValue::from_f64(*d));
    }
    let _ = ctx.set_line_dash(&pattern);
}

/// Paints one plot; returns the mapping used.
#[cfg(feature = "bench-exports")]
pub(crate) fn paint_plot(
    ctx: &CanvasRenderingContext2d,
    plot: &Plot,
    palette: &Palette,
    size: (f64, f64, f64),
) -> Frame {
    paint_plot_layout(ctx, plot, palette, size, false, &mut LabelMemory::default()).0
}

/// Where each label of a plot went at its last paint: the label's text and
/// its corner's offset from its anchor. A streaming plot is repainted many
/// times a second; a label keeps its place while that place stays free,
/// rather than being searched for again (and jumping about) at every paint.
#[derive(Default)]
pub(crate) struct LabelMemory(Vec<(String, (f64, f64))>);

impl LabelMemory {
    /// The spot `label` had, moved with its `anchor`, if it had one.
    fn spot(&self, label: &str, anchor: (f64, f64)) -> Option<(f64, f64)> {
        self.0
            .iter()
            .find(|(l, _)| l == label)
            .map(|(_, (dx, dy))| (anchor.0 + dx, anchor.1 + dy))
    }
}

/// The font of every text on a plot.
const PLOT_FONT: &str = "12px system-ui, sans-serif";

/// Width of the band at the left edge that holds the rotated y-axis title.
const Y_TITLE_BAND: f64 = 20.0;
/// Height of one tick label line, CSS pixels (12 px font).
const TICK_H: f64 = 14.0;

/// Paints one plot (x axis fitted to the latest run with `fit_latest`);
/// returns the mapping used and where every label went.
pub(crate) fn paint_plot_layout(
    ctx: &CanvasRenderingContext2d,
    plot: &Plot,
    palette: &Palette,
    (w, h, dpr): (f64, f64, f64),
    fit_latest: bool,
    labels: &mut LabelMemory,
) -> (Frame, Layout) {
    let mut layout = Layout::default();
    let _ = ctx.set_transform(dpr, 0.0, 0.0, dpr, 0.0, 0.0);
    ctx.set_fill_style_str(&palette.background);
    ctx.fill_rect(0.0, 0.0, w, h);
    let (_, mr, mt, mb) = MARGIN;
    let text = palette.colour(Role::Text).to_owned();
    ctx.set_font(PLOT_FONT);
    ctx.set_fill_style_str(&text);
    let Some(x_range) = x_range_for(plot, fit_latest) else {
        ctx.set_text_align("center");
        ctx.set_text_baseline("middle");
        let _ = ctx.fill_text("No data yet", w / 2.0, h / 2.0);
        return (Frame::default(), layout);
    };
    let (mut y0, mut y1) = plot.y_range(x_range).unwrap_or((0.0, 1.0));
    let log = plot.log_y && y0 > 0.0;
    if log {
        y0 = power_of_ten(math::log10(y0).floor() as i32);
        y1 = power_of_ten(math::log10(y1).ceil().max(math::log10(y0) + 1.0) as i32);
    } else {
        let pad = ((y1 - y0) * 0.08).max(if y1 == y0 {
            y0.abs().max(1.0) * 0.1
        } else {
            0.0
        });
        y0 -= pad;
        y1 += pad;
    }
    let (x0, x1) = if x_range.1 > x_range.0 {
        x_range
    } else {
        (x_range.0 - 1.0, x_range.1 + 1.0)
    };
    // The y ticks first: their widest label sets the left margin, so no
    // label reaches into the band of the y-axis title. Each axis has two
    // labelled ticks at least (`axis_ticks` widens it where its range
    // holds fewer).
    let ph = (h - mt - mb).max(10.0);
    let max_y_ticks = ((ph / 34.0) as usize).clamp(2, 8);
    let y_ticks = if log {
        log_ticks(y0, y1, max_y_ticks)
    } else {
        axis_ticks(y0, y1, max_y_ticks).map_or_else(Vec::new, |(a, b, ticks)| {
            (y0, y1) = (a, b);
            ticks
        })
    };
    let y_labels = tick_labels(&y_ticks, log);
    let widest_y = y_labels.iter().map(|t| measure(ctx, t)).fold(0.0, f64::max);
    let ml = left_margin(widest_y);
    let pw = (w - ml - mr).max(10.0);
    let (x0, x1, x_ticks, x_labels) = x_axis(ctx, (x0, x1), pw);
    let frame = Frame {
        x: (x0, x1),
        y: (y0, y1),
        log,
        rect: (ml, mt, pw, ph),
    };
    let paint = PlotPaint {
        ctx,
        plot,
        palette,
        frame,
        text,
        dpr,
    };
    paint.bands();
    paint.axes(
        &mut layout,
        (&x_ticks, &x_labels),
        (&y_ticks, &y_labels),
        (w, h),
    );
    // Clip the data to the plot rectangle.
    let (l, t, pw, ph) = frame.rect;
    ctx.save();
    ctx.begin_path();
    ctx.rect(l, t, pw, ph);
    ctx.clip();
    let ref_px = paint.ref_lines();
    let curves = paint.series();
    // Marker diamonds are obstacles for every label.
    let diamonds = paint.diamonds();
    let mut taken: Vec<Rect> = diamonds
        .iter()
        .map(|(px, py)| Rect {
            x: px - 7.0,
            y: py - 7.0,
            w: 14.0,
            h: 14.0,
        })
        .collect();
    let diamond_count = taken.len();
    let to_draw = paint.place_labels(&ref_px, &curves, &diamonds, &mut taken, labels);
    paint.labels(&to_draw);
    ctx.restore();
    layout.labels = taken[diamond_count..].to_vec();
    (frame, layout)
}

/// The width of `text` in the plot font, CSS pixels.
fn measure(ctx: &CanvasRenderingContext2d, text: &str) -> f64 {
    crate::text::width(ctx, PLOT_FONT, text)
}

/// A reference line as drawn: the line and its ends, CSS pixels.
type RefLinePx<'a> = (&'a labcore::plot::RefLine, (f64, f64), (f64, f64));

/// One paint of one plot: the parts of [`paint_plot_layout`], in order.
struct PlotPaint<'a> {
    ctx: &'a CanvasRenderingContext2d,
    plot: &'a Plot,
    palette: &'a Palette,
    frame: Frame,
    /// The text colour.
    text: String,
    /// Device pixels per CSS pixel.
    dpr: f64,
}

impl PlotPaint<'_> {
    /// The shaded bands, under everything else.
    fn bands(&self) {
        let (ctx, frame) = (self.ctx, &self.frame);
        let (l, t, pw, ph) = frame.rect;
        let ((x0, x1), (y0, y1)) = (frame.x, frame.y);
        ctx.set_fill_style_str(&self.palette.var(PLOT_BAND.var));
        ctx.set_global_alpha(BAND_OPACITY);
        for band in &self.plot.bands {
            match band.axis {
                Axis::Y => {
                    let (a, b) = (frame.px_y(band.hi.min(y1)), frame.px_y(band.lo.max(y0)));
                    ctx.fill_rect(l, a, pw, (b - a).max(0.0));
                }
                Axis::X => {
                    let (a, b) = (frame.px_x(band.lo.max(x0)), frame.px_x(band.hi.min(x1)));
                    ctx.fill_rect(a, t, (b - a).max(0.0), ph);
                }
            }
        }
        ctx.set_global_alpha(1.0);
    }

    /// Grid lines, tick labels, the frame and the axis titles; writes where
    /// the labels and titles went into `layout`.
    fn axes(
        &self,
        layout: &mut Layout,
        (x_ticks, x_labels): (&[f64], &[String]),
        (y_ticks, y_labels): (&[f64], &[String]),
        (w, h): (f64, f64),
    ) {
        let (ctx, frame) = (self.ctx, &self.frame);
        let (l, t, pw, ph) = frame.rect;
        ctx.set_line_width(1.0);
        set_dash(ctx, &[]);
        ctx.set_stroke_style_str(self.palette.colour(Role::Grid));
        ctx.set_fill_style_str(&self.text);
        ctx.set_text_align("center");
        ctx.set_text_baseline("top");
        for (x, label) in x_ticks.iter().zip(x_labels) {
            let px = frame.px_x(*x);
            ctx.begin_path();
            ctx.move_to(px, t);
            ctx.line_to(px, t + ph);
            ctx.stroke();
            let lw = measure(ctx, label);
            // A label under the last tick would stand past the canvas' edge
            // (RRT*'s "4000" showed as "400"): it moves in, off its tick.
            let centre = label_centre(px, lw, w);
            let _ = ctx.fill_text(label, centre, t + ph + 4.0);
            layout.x_ticks.push((
                label.clone(),
                Rect {
                    x: centre - lw / 2.0,
                    y: t + ph + 4.0,
                    w: lw,
                    h: TICK_H,
                },
            ));
        }
        ctx.set_text_align("right");
        ctx.set_text_baseline("middle");
        for (y, label) in y_ticks.iter().zip(y_labels) {
            let py = frame.px_y(*y);
            ctx.begin_path();
            ctx.move_to(l, py);
            ctx.line_to(l + pw, py);
            ctx.stroke();
            let _ = ctx.fill_text(label, l - 6.0, py);
            let lw = measure(ctx, label);
            layout.y_ticks.push((
                label.clone(),
                Rect {
                    x: l - 6.0 - lw,
                    y: py - TICK_H / 2.0,
                    w: lw,
                    h: TICK_H,
                },
            ));
        }
        ctx.set_stroke_style_str(&self.palette.var("--muted"));
        ctx.stroke_rect(l, t, pw, ph);
        self.axis_titles(layout, h);
    }

    fn axis_titles(&self, layout: &mut Layout, h: f64) {
        let ctx = self.ctx;
        let (l, t, pw, ph) = self.frame.rect;
        ctx.set_text_align("center");
        ctx.set_text_baseline("bottom");
        let x_title = axis_title(self.plot.x_label, self.plot.x_unit);
        let _ = ctx.fill_text(&x_title, l + pw / 2.0, h - 1.0);
        let xw = measure(ctx, &x_title);
        layout.x_title = Some(Rect {
            x: l + pw / 2.0 - xw / 2.0,
            y: h - 1.0 - TICK_H,
            w: xw,
            h: TICK_H,
        });
        let y_title = axis_title(self.plot.y_label, self.plot.y_unit);
        ctx.save();
        let _ = ctx.translate(Y_TITLE_BAND / 2.0 + 1.0, t + ph / 2.0);
        let _ = ctx.rotate(-std::f64::consts::FRAC_PI_2);
        ctx.set_text_baseline("middle");
        let _ = ctx.fill_text(&y_title, 0.0, 0.0);
        ctx.restore();
        let yw = measure(ctx, &y_title);
        layout.y_title = Some(Rect {
            x: Y_TITLE_BAND / 2.0 + 1.0 - TICK_H / 2.0,
            y: t + ph / 2.0 - yw / 2.0,
            w: TICK_H,
            h: yw,
        });
    }

    /// The dashed reference lines; returns where each went.
    fn ref_lines(&self) -> Vec<RefLinePx<'_>> {
        let (ctx, frame) = (self.ctx, &self.frame);
        let (l, t, pw, ph) = frame.rect;
        let (reference, _) = role_style(SeriesRole::Reference);
        let mut ref_px = Vec::new();
        for line in &self.plot.ref_lines {
            ctx.set_stroke_style_str(&self.palette.var(reference));
            set_dash(ctx, &REF_LINE_DASH_PX);
            ctx.set_line_width(1.5);
            ctx.begin_path();
            let (a, b) = match line.axis {
                Axis::Y => {
                    let py = frame.px_y(line.value);
                    ((l, py), (l + pw, py))
                }
                Axis::X => {
                    let px = frame.px_x(line.value);
                    ((px, t), (px, t + ph))
                }
            };
            ctx.move_to(a.0, a.1);
            ctx.line_to(b.0, b.1);
            ctx.stroke();
            ref_px.push((line, a, b));
        }
        ref_px
    }

    /// Every series; returns each drawn curve in CSS pixels. A series with
    /// more samples in view than the plot has device-pixel columns is drawn
    /// as a rectangle a column over what its line covers there
    /// ([`column_spans`]: a thick stroke through a dense zigzag rasterised
    /// 5–10 times slower in Chromium's software canvas), its dashes along x.
    fn series(&self) -> Vec<Vec<(f64, f64)>> {
        let (ctx, frame) = (self.ctx, &self.frame);
        let (l, _, pw, _) = frame.rect;
        // Device-pixel columns: a steep smooth curve steps by one device
        // pixel, as its anti-aliased stroke would.
        let columns = ((pw * self.dpr) as usize).max(1);
        let column = pw / columns as f64;
        // Column edges on device pixels: neighbours meet without a seam.
        let snap = |x: f64| (x * self.dpr + 0.5).floor() / self.dpr;
        let mut curves: Vec<Vec<(f64, f64)>> = Vec::new();
        for s in &self.plot.series {
            let (var, dash) = role_style(s.role);
            let colour = self.palette.var(var);
            // The samples in view, in CSS pixels.
            let px = || {
                s.x.iter()
                    .zip(&s.y)
                    .filter(|(x, y)| {
                        (frame.x.0..=frame.x.1).contains(*x) && (!frame.log || **y > 0.0)
                    })
                    .map(|(x, y)| (frame.px_x(*x), frame.px_y(*y)))
            };
            let dense = px().count() > columns;
            if let Some(spans) = dense.then(|| column_spans(px(), l, pw, columns)).flatten() {
                ctx.set_fill_style_str(&colour);
                let mut curve = Vec::with_capacity(2 * columns);
                for (c, &(top, bottom)) in spans.iter().enumerate() {
                    let along = c as f64 * column;
                    if top > bottom {
                        continue;
                    }
                    curve.extend([(l + along, top), (l + along, bottom)]);
                    if dash_is_on(dash, along) {
                        let (a, b) = (snap(l + along), snap(l + along + column));
                        let half = SERIES_LINE_PX / 2.0;
                        ctx.fill_rect(a, top - half, b - a, bottom - top + SERIES_LINE_PX);
                    }
                }
                curves.push(curve);
                continue;
            }
            let px: Vec<(f64, f64)> = px().collect();
            ctx.set_stroke_style_str(&colour);
            set_dash(ctx, dash);
            ctx.set_line_width(SERIES_LINE_PX);
            ctx.begin_path();
            for (i, (x, y)) in px.iter().enumerate() {
                if i == 0 {
                    ctx.move_to(*x, *y);
                } else {
                    ctx.line_to(*x, *y);
                }
            }
            if px.len() == 1 {
                let _ = ctx.arc(px[0].0, px[0].1, 2.0, 0.0, std::f64::consts::TAU);
            }
            ctx.stroke();
            if !px.is_empty() {
                curves.push(px);
            }
        }
        set_dash(ctx, &[]);
        curves
    }

    /// A diamond at each event marker (its shape tells it from the lines);
    /// returns their centres.
    fn diamonds(&self) -> Vec<(f64, f64)> {
        let ctx = self.ctx;
        let diamonds: Vec<(f64, f64)> = self
            .plot
            .markers
            .iter()
            .map(|m| (self.frame.px_x(m.x), self.frame.px_y(m.y)))
            .collect();
        let (bound, _) = role_style(SeriesRole::Bound);
        for (px, py) in &diamonds {
            ctx.set_fill_style_str(&self.palette.var(bound));
            ctx.set_stroke_style_str(&self.palette.background);
            ctx.begin_path();
            ctx.move_to(*px, py - 6.0);
            ctx.line_to(px + 6.0, *py);
            ctx.line_to(*px, py + 6.0);
            ctx.line_to(px - 6.0, *py);
            ctx.close_path();
            ctx.fill();
            ctx.stroke();
        }
        diamonds
    }

    /// Places the reference-line and marker labels clear of each other, the
    /// curves and `taken`, each where it was last time if still free
    /// (`memory`); adds their boxes to `taken`.
    fn place_labels(
        &self,
        ref_px: &[RefLinePx<'_>],
        curves: &[Vec<(f64, f64)>],
        diamonds: &[(f64, f64)],
        taken: &mut Vec<Rect>,
        memory: &mut LabelMemory,
    ) -> Vec<PlacedLabel> {
        let (l, t, pw, ph) = self.frame.rect;
        let plot_rect = Rect {
            x: l,
            y: t,
            w: pw,
            h: ph,
        };
        let mut to_draw: Vec<PlacedLabel> = Vec::new();
        let mut placed = Vec::new();
        // Reference-line labels: at an end of their line, where no series is.
        for (line, a, b) in ref_px {
            if line.label.is_empty() {
                continue;
            }
            let size = (measure(self.ctx, &line.label) + 6.0, TICK_H + 2.0);
            let anchor = (b.0, b.1);
            let preferred: Vec<(f64, f64)> = memory
                .spot(&line.label, anchor)
                .into_iter()
                .chain(ref_label_spots(line.axis, *a, *b, size, &self.frame))
                .collect();
            let r = place_label(anchor, size, &preferred, &plot_rect, curves, taken);
            taken.push(r);
            placed.push((line.label.clone(), (r.x - anchor.0, r.y - anchor.1)));
            to_draw.push((line.label.clone(), r, None));
        }
        // Marker labels: beside their diamond if free, else in free space with a
        // leader line; never on each other, on a curve or on a reference line.
        let mut marker_obstacles = curves.to_vec();
        marker_obstacles.extend(ref_px.iter().map(|(_, a, b)| vec![*a, *b]));
        for (m, (px, py)) in self.plot.markers.iter().zip(diamonds) {
            if m.label.is_empty() {
                continue;
            }
            let size = (measure(self.ctx, &m.label) + 6.0, TICK_H + 2.0);
            let preferred: Vec<(f64, f64)> = memory
                .spot(&m.label, (*px, *py))
                .into_iter()
                .chain([
                    (px + 8.0, py - size.1 - 4.0),
                    (px - size.0 - 8.0, py - size.1 - 4.0),
                    (px + 8.0, py + 4.0),
                    (px - size.0 - 8.0, py + 4.0),
                ])
                .collect();
            let r = place_label(
                (*px, *py),
                size,
                &preferred,
                &plot_rect,
                &marker_obstacles,
                taken,
            );
            taken.push(r);
            placed.push((m.label.clone(), (r.x - px, r.y - py)));
            let far = r.distance_to((*px, *py)) > 12.0;
            to_draw.push((m.label.clone(), r, far.then_some((*px, *py))));
        }
        memory.0 = placed;
        to_draw
    }

    /// The placed labels on a plate of the background, with their leader lines.
    fn labels(&self, to_draw: &[PlacedLabel]) {
        let ctx = self.ctx;
        ctx.set_text_align("left");
        ctx.set_text_baseline("middle");
        for (label, r, leader) in to_draw {
            if let Some((ax, ay)) = leader {
                let cx = ax.clamp(r.x, r.x + r.w);
                let cy = ay.clamp(r.y, r.y + r.h);
                ctx.set_stroke_style_str(&self.palette.var("--muted"));
                ctx.set_line_width(1.0);
                ctx.begin_path();
                ctx.move_to(*ax, *ay);
                ctx.line_to(cx, cy);
                ctx.stroke();
            }
            ctx.set_fill_style_str(&self.palette.background);
            ctx.set_global_alpha(0.85);
            ctx.fill_rect(r.x, r.y, r.w, r.h);
            ctx.set_global_alpha(1.0);
            ctx.set_fill_style_str(&self.text);
            let _ = ctx.fill_text(label, r.x + 3.0, r.y + r.h / 2.0);
        }
    }
}

/// Where a reference line's label may go, best first: at an end of the
/// line, above or below it (a horizontal line), or beside it at the top or
/// the bottom (a vertical one).
fn ref_label_spots(
    axis: Axis,
    a: (f64, f64),
    b: (f64, f64),
    size: (f64, f64),
    frame: &Frame,
) -> Vec<(f64, f64)> {
    let (_, t, pw, ph) = frame.rect;
    match axis {
        Axis::Y => vec![
            (b.0 - size.0 - 4.0, a.1 - size.1 - 1.0),
            (b.0 - size.0 - 4.0, a.1 + 2.0),
            (a.0 + 4.0, a.1 - size.1 - 1.0),
            (a.0 + 4.0, a.1 + 2.0),
            (a.0 + (pw - size.0) / 2.0, a.1 - size.1 - 1.0),
            (a.0 + (pw - size.0) / 2.0, a.1 + 2.0),
        ],
        Axis::X => vec![
            (a.0 + 3.0, t + 2.0),
            (a.0 - size.0 - 3.0, t + 2.0),
            (a.0 + 3.0, t + ph - size.1 - 2.0),
            (a.0 - size.0 - 3.0, t + ph - size.1 - 2.0),
        ],
    }
}

/// A label to draw: its text, its box and the anchor of its leader line.
type PlacedLabel = (String, Rect, Option<(f64, f64)>);

/// The left margin that keeps the widest y tick label (`widest_px`) clear of
/// the y-axis title band.
#[must_use]
pub fn left_margin(widest_px: f64) -> f64 {
    (Y_TITLE_BAND + 4.0 + widest_px + 6.0).max(MARGIN.0)
}

/// Where a tick label `width_px` wide is centred for a tick at `px` on a
/// canvas `canvas_px` wide: under the tick, or moved in just enough to
/// stand wholly on the canvas.
#[must_use]
pub fn label_centre(px: f64, width_px: f64, canvas_px: f64) -> f64 {
    let half = width_px / 2.0;
    px.min(canvas_px - half - 1.0).max(half + 1.0)
}

/// The x axis over at least `(x0, x1)` and its ticks with their labels: as
/// many as fit side by side with a gap between their labels on a plot
/// `pw` pixels wide, and two at least (`axis_ticks`, which may widen the
/// axis).
fn x_axis(
    ctx: &CanvasRenderingContext2d,
    (x0, x1): (f64, f64),
    pw: f64,
) -> (f64, f64, Vec<f64>, Vec<String>) {
    let mut max_x_ticks = ((pw / 70.0) as usize).clamp(2, 10);
    loop {
        let (a, b, ticks) = axis_ticks(x0, x1, max_x_ticks).unwrap_or((x0, x1, Vec::new()));
        let labels = tick_labels(&ticks, false);
        let widest = labels.iter().map(|t| measure(ctx, t)).fold(0.0, f64::max);
        if max_x_ticks <= 2 || (widest + 12.0) * labels.len() as f64 <= pw {
            return (a, b, ticks, labels);
        }
        max_x_ticks -= 1;
    }
}

/// Draws a cursor at the sample nearest `x` and fills the tooltip.
fn show_nearest(drawn: &Drawn, plot: &Plot, palette: &Palette, x: f64) {
    let frame = drawn.frame;
    let ctx = &drawn.ctx;
    let mut lines = Vec::new();
    let mut cursor_x = None;
    for s in &plot.series {
        let Some(i) = s.nearest(x) else { continue };
        let (sx, sy) = (s.x[i], s.y[i]);
        cursor_x.get_or_insert(sx);
        let (px, py) = (frame.px_x(sx), frame.px_y(sy));
        let (var, _) = role_style(s.role);
        ctx.set_fill_style_str(&palette.var(var));
        ctx.begin_path();
        let _ = ctx.arc(px, py, 4.0, 0.0, std::f64::consts::TAU);
        ctx.fill();
        lines.push(format!(
            "{}: {}{}",
            s.label,
            format_number(sy, 5),
            if s.unit.is_empty() {
                String::new()
            } else {
                format!(" {}", s.unit)
            }
        ));
    }
    let Some(cx) = cursor_x else { return };
    let (_, t, _, ph) = frame.rect;
    let px = frame.px_x(cx);
    ctx.set_stroke_style_str(&palette.var("--muted"));
    set_dash(ctx, &[3.0, 3.0]);
    ctx.begin_path();
    ctx.move_to(px, t);
    ctx.line_to(px, t + ph);
    ctx.stroke();
    set_dash(ctx, &[]);
    if let Some(tip) = &drawn.parts.tip {
        tip.set_text_content(Some(&format!(
            "{} = {}{} · {}",
            plot.x_label,
            format_number(cx, 5),
            if plot.x_unit.is_empty() {
                String::new()
            } else {
                format!(" {}", plot.x_unit)
            },
            lines.join(" · ")
        )));
        dom::set_hidden(tip, false);
    }
}

/// The data table: one row per sample (at most [`TABLE_ROWS_MAX`]).
fn table_html(plot: &Plot) -> String {
    let csv = plot.to_csv();
    let mut rows = csv.lines();
    let head = rows.next().unwrap_or("");
    let head_cells: String = split_csv(head)
        .iter()
        .map(|c| format!("<th scope=\"col\">{}</th>", escape(c)))
        .collect();
    let total = plot.series.iter().map(|s| s.len()).max().unwrap_or(0);
    let body: String = rows
        .take(TABLE_ROWS_MAX)
        .map(|r| {
            let cells: String = split_csv(r)
                .iter()
                .map(|c| {
                    let shown = c.parse::<f64>().map_or(c.clone(), |v| format_number(v, 6));
                    format!("<td>{}</td>", escape(&shown))
                })
                .collect();
            format!("<tr>{cells}</tr>")
        })
        .collect();
    let note = if total > TABLE_ROWS_MAX {
        format!(
            "<p class=\"muted\">The first {TABLE_ROWS_MAX} of {total} rows; the CSV has them all.</p>"
        )
    } else {
        String::new()
    };
    format!(
        "<div class=\"table-scroll\" tabindex=\"0\"><table><caption>{}</caption><thead><tr>{head_cells}</tr></thead><tbody>{body}</tbody></table></div>{note}",
        escape(plot.title)
    )
}

/// Splits one CSV row (RFC 4180 quoting).
fn split_csv(row: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = row.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => out.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    out.push(field);
    out
}

/// Offers `bytes` as a download named `file_name`, made in the page from a
/// Blob URL (nothing leaves the browser).
pub fn download(file_name: &str, mime: &str, text: &str) {
    let parts = js_sys::Array::of1(&JsValue::from_str(text));
    let options = web_sys::BlobPropertyBag::new();
    options.set_type(mime);
    let Ok(blob) = web_sys::Blob::new_with_str_sequence_and_options(&parts, &options) else {
        return;
    };
    download_blob(file_name, &blob);
}

/// Clicks a temporary link to a Blob URL, then revokes the URL.
pub fn download_blob(file_name: &str, blob: &web_sys::Blob) {
    let Ok(url) = web_sys::Url::create_object_url_with_blob(blob) else {
        return;
    };
    if let Ok(a) = dom::document().create_element("a") {
        let _ = a.set_attribute("href", &url);
        let _ = a.set_attribute("download", file_name);
        if let Some(a) = a.dyn_ref::<web_sys::HtmlElement>() {
            a.click();
        }
    }
    // Revoke after the click has been handled.
    dom::defer(move || {
        let _ = web_sys::Url::revoke_object_url(&url);
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 53 §7: RRT*'s last x tick, "4000", under the plot's right edge,
    /// stood half past the canvas and showed as "400". A label stays whole
    /// on the canvas, under its tick where it fits.
    #[test]
    fn a_tick_label_at_an_edge_moves_in_to_stay_whole() {
        // A 30 px label under a tick 8 px from the right edge of 300 px.
        assert_eq!(label_centre(292.0, 30.0, 300.0), 284.0);
        assert_eq!(label_centre(3.0, 30.0, 300.0), 16.0);
        assert_eq!(label_centre(150.0, 30.0, 300.0), 150.0);
    }

    #[test]
    fn csv_rows_split_with_quotes() {
        assert_eq!(
            split_csv("a,\"b, c\",\"d\"\"e\""),
            vec!["a", "b, c", "d\"e"]
        );
    }

    use labcore::plot::{Band, Marker, RefLine, Series};

    #[test]
    fn y_tick_labels_stay_clear_of_the_axis_title() {
        for widest in [10.0, 34.0, 60.0, 120.0] {
            let l = left_margin(widest);
            let label_left = l - 6.0 - widest;
            assert!(
                label_left >= Y_TITLE_BAND,
                "{widest}: label from {label_left}"
            );
        }
    }

    fn rising_curve() -> Vec<(f64, f64)> {
        // A step response in pixels: rises from (0, 200) to (100, 40), then flat.
        let mut c: Vec<(f64, f64)> = (0..=100)
            .map(|i| (f64::from(i), 200.0 - 1.6 * f64::from(i)))
            .collect();
        c.extend((101..=400).map(|i| (f64::from(i), 40.0)));
        c
    }

    /// Regression (issue 13 §5): "rise" and "settled" labels drawn on each
    /// other and on the curve.
    #[test]
    fn marker_labels_avoid_each_other_and_the_curves() {
        let bounds = Rect {
            x: 0.0,
            y: 0.0,
            w: 400.0,
            h: 220.0,
        };
        let curves = vec![rising_curve()];
        let mut taken: Vec<Rect> = Vec::new();
        // Two markers close together on the curve, as rise and settling are.
        for anchor in [(90.0, 56.0), (100.0, 40.0), (104.0, 40.0)] {
            let size = (70.0, 16.0);
            let preferred = [
                (anchor.0 + 8.0, anchor.1 - 20.0),
                (anchor.0 - 78.0, anchor.1 - 20.0),
            ];
            let r = place_label(anchor, size, &preferred, &bounds, &curves, &taken);
            assert!(r.inside(&bounds), "{r:?}");
            for t in &taken {
                assert!(!t.intersects(&r), "{r:?} overlaps {t:?}");
            }
            for w in curves[0].windows(2) {
                assert!(!segment_hits_rect(w[0], w[1], &r), "{r:?} covers the curve");
            }
            taken.push(r);
        }
    }

    #[test]
    fn a_reference_label_moves_off_a_series_that_runs_along_its_line() {
        let bounds = Rect {
            x: 0.0,
            y: 0.0,
            w: 300.0,
            h: 200.0,
        };
        // The series lies just above the line at y = 100 on the right half.
        let curve: Vec<(f64, f64)> = (150..=300).map(|x| (f64::from(x), 92.0)).collect();
        let size = (60.0, 16.0);
        let preferred = [(236.0, 83.0), (236.0, 102.0), (4.0, 83.0)];
        let r = place_label(
            (300.0, 100.0),
            size,
            &preferred,
            &bounds,
            std::slice::from_ref(&curve),
            &[],
        );
        for w in curve.windows(2) {
            assert!(!segment_hits_rect(w[0], w[1], &r));
        }
        assert_eq!(
            (r.x, r.y),
            (236.0, 102.0),
            "the second choice: below the line"
        );
    }

    fn comparison_plot() -> Plot {
        let mut plot = Plot::new(
            "r",
            "Response",
            ("Time", "s"),
            ("Position", "m"),
            vec![
                Series::new("now", "m", SeriesRole::Primary),
                Series::new("Kp 25, Kd 5", "m", SeriesRole::Reference).for_comparison(),
            ],
        );
        for i in 0..=20 {
            plot.series[0].push(f64::from(i) * 0.1, 1.0);
        }
        for i in 0..=80 {
            plot.series[1].push(f64::from(i) * 0.1, 1.0);
        }
        plot
    }

    #[test]
    fn fit_latest_run_takes_the_x_range_from_the_runs_not_kept_for_comparison() {
        let plot = comparison_plot();
        assert_eq!(x_range_for(&plot, false), Some((0.0, 8.0)));
        assert_eq!(x_range_for(&plot, true), Some((0.0, 2.0)));
        assert!(render(&plot).contains("data-plot-fit=\"r\""));
        let mut plain = plot.clone();
        plain.series[1].comparison = false;
        assert!(!render(&plain).contains("data-plot-fit"));
    }

    #[test]
    fn every_band_and_reference_line_has_a_legend_entry() {
        let mut plot = comparison_plot();
        plot.bands.push(Band {
            axis: Axis::Y,
            lo: 0.98,
            hi: 1.02,
            label: "±2 % band".into(),
        });
        plot.ref_lines.push(RefLine {
            axis: Axis::Y,
            value: 1.0,
            label: "set-point".into(),
        });
        plot.ref_lines.push(RefLine {
            axis: Axis::Y,
            value: 3.0,
            label: "expected 3".into(),
        });
        plot.markers.push(Marker {
            x: 0.5,
            y: 1.0,
            label: "rise 0.5 s".into(),
        });
        let html = render(&plot);
        assert_eq!(html.matches("data-legend=\"band\"").count(), 1);
        assert_eq!(html.matches("data-legend=\"line\"").count(), 2);
        for name in ["±2 % band", "set-point", "expected 3"] {
            assert!(html.contains(name), "{name}");
        }
    }

    #[test]
    fn layout_json_has_one_decimal_per_coordinate() {
        let r = |x, y, w, h| Rect { x, y, w, h };
        let layout = Layout {
            labels: vec![r(1.04, -2.36, 30.0, 14.0)],
            x_ticks: vec![("0.5".into(), r(10.0, 20.25, 7.5, 14.0))],
            y_ticks: vec![("\"1\"".into(), r(-0.04, 0.0, 1e20, 14.0))],
            x_title: None,
            y_title: Some(r(0.0, 0.0, 14.0, 99.95)),
        };
        assert_eq!(
            layout.json(),
            "{\"labels\":[[1.0,-2.4,30.0,14.0]],\"xticks\":[[\"0.5\",[10.0,20.3,7.5,14.0]]],\
             \"yticks\":[[\"1\",[0.0,0.0,0,14.0]]],\"xtitle\":null,\"ytitle\":[0.0,0.0,14.0,100.0]}"
        );
    }

    #[test]
    fn every_role_has_its_own_dash() {
        let dashes: Vec<_> = SeriesRole::ALL.iter().map(|r| role_style(*r).1).collect();
        for (i, a) in dashes.iter().enumerate() {
            for b in &dashes[i + 1..] {
                assert_ne!(a, b);
            }
        }
    }
}
