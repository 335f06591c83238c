//! Draws the experiment's [`Plot`]s: axes with readable ticks (linear or
//! log), shaded bands, reference lines, decimated series with a colour *and*
//! a dash per role, event markers, the nearest sample under the pointer, a
//! text summary for screen readers, a data table on request and CSV export.

use crate::dom::{self, escape, query, query_all};
use crate::draw::Palette;
use labcore::plot::{decimate_min_max, log_ticks, nice_ticks, Axis, Plot, SeriesRole};
use labcore::quiz::format_number;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{CanvasRenderingContext2d, Element, HtmlCanvasElement};

/// Most rows shown in a plot's data table (the CSV always has every row).
const TABLE_ROWS_MAX: usize = 500;
/// Plot margins, CSS pixels: left (y tick labels), right, top, bottom (x ticks and label).
const MARGIN: (f64, f64, f64, f64) = (58.0, 12.0, 10.0, 34.0);

/// CSS custom property and dash pattern of each series role: every pair of
/// roles differs in dash as well as colour.
fn role_style(role: SeriesRole) -> (&'static str, &'static [f64]) {
    match role {
        SeriesRole::Primary => ("--p-1", &[]),
        SeriesRole::Secondary => ("--p-2", &[9.0, 4.0]),
        SeriesRole::Tertiary => ("--p-3", &[2.0, 3.0]),
        SeriesRole::Quaternary => ("--p-4", &[9.0, 3.0, 2.0, 3.0]),
        SeriesRole::Reference => ("--p-5", &[5.0, 5.0]),
        SeriesRole::Bound => ("--p-6", &[2.0, 2.0]),
    }
}

fn dash_attr(dash: &[f64]) -> String {
    dash.iter()
        .map(|d| format!("{d}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The HTML of one plot (empty canvas; [`PlotView::draw`] fills it).
#[must_use]
pub fn render(plot: &Plot) -> String {
    let legend: String = plot
        .series
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let (var, dash) = role_style(s.role);
            format!(
                "<span class=\"legend-item\" data-series=\"{i}\"{hidden}><svg width=\"26\" height=\"10\" aria-hidden=\"true\">\
                 <line x1=\"1\" y1=\"5\" x2=\"25\" y2=\"5\" style=\"stroke:var({var})\" stroke-width=\"2.5\" stroke-dasharray=\"{}\"/></svg>{}</span>",
                dash_attr(dash),
                escape(&s.label),
                hidden = if s.is_empty() { " hidden" } else { "" },
            )
        })
        .collect();
    let key = plot.key;
    format!(
        "<figure class=\"plot\" data-plot=\"{key}\">\
         <figcaption><span class=\"plot-title\">{title}</span>\
         <span class=\"plot-tools\"><button type=\"button\" class=\"mini\" data-plot-csv=\"{key}\">CSV</button>\
         <button type=\"button\" class=\"mini\" data-plot-table=\"{key}\" aria-expanded=\"false\">Table</button></span></figcaption>\
         <div class=\"plot-legend\">{legend}</div>\
         <div class=\"plot-box\"><canvas class=\"plot-canvas\" role=\"img\" aria-label=\"{title}\"></canvas>\
         <output class=\"plot-tip\" hidden></output></div>\
         <p class=\"sr-only plot-summary\"></p>\
         <div class=\"plot-table\" hidden></div></figure>",
        title = escape(plot.title),
    )
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
                self.y.0.log10(),
                self.y.1.log10(),
                y.max(f64::MIN_POSITIVE).log10(),
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

/// One drawn plot: its canvas and what was last drawn there.
struct Drawn {
    key: &'static str,
    figure: Element,
    canvas: HtmlCanvasElement,
    ctx: CanvasRenderingContext2d,
    revision: Option<u64>,
    size: (f64, f64, f64),
    frame: Frame,
    hover_x: Option<f64>,
}

/// Every plot of the mounted simulation.
pub struct PlotView {
    plots: Vec<Drawn>,
}

impl PlotView {
    /// Finds the plot figures rendered by [`render`] inside `root`.
    pub fn mount(root: &Element) -> Self {
        let plots = query_all(root, "figure.plot")
            .into_iter()
            .filter_map(|figure| {
                let key = figure.get_attribute("data-plot")?;
                let canvas: HtmlCanvasElement = query(&figure, "canvas")?.dyn_into().ok()?;
                let ctx = canvas
                    .get_context("2d")
                    .ok()
                    .flatten()?
                    .dyn_into::<CanvasRenderingContext2d>()
                    .ok()?;
                Some(Drawn {
                    key: Box::leak(key.into_boxed_str()),
                    figure,
                    canvas,
                    ctx,
                    revision: None,
                    size: (0.0, 0.0, 0.0),
                    frame: Frame::default(),
                    hover_x: None,
                })
            })
            .collect();
        Self { plots }
    }

    /// Redraws the plots whose data, size or theme changed.
    pub fn draw(&mut self, plots: &[Plot], palette: &Palette, force: bool) {
        for drawn in &mut self.plots {
            let Some(plot) = plots.iter().find(|p| p.key == drawn.key) else {
                continue;
            };
            let rect = drawn.canvas.get_bounding_client_rect();
            let dpr = dom::window().device_pixel_ratio().max(1.0);
            let size = (rect.width(), rect.height(), dpr);
            if size.0 < 1.0 {
                continue;
            }
            if !force && drawn.revision == Some(plot.revision) && drawn.size == size {
                continue;
            }
            if drawn.size != size {
                drawn.canvas.set_width((size.0 * dpr).round() as u32);
                drawn.canvas.set_height((size.1 * dpr).round() as u32);
                drawn.size = size;
            }
            drawn.revision = Some(plot.revision);
            drawn.frame = paint_plot(&drawn.ctx, plot, palette, size);
            if let Some(x) = drawn.hover_x {
                show_nearest(drawn, plot, palette, x);
            }
            if let Some(summary) = query(&drawn.figure, ".plot-summary") {
                summary.set_text_content(Some(&plot.summary()));
            }
            // A series with no samples yet (an empty slot for a pinned run)
            // has no legend entry.
            for item in query_all(&drawn.figure, ".legend-item[data-series]") {
                let empty = item
                    .get_attribute("data-series")
                    .and_then(|i| i.parse::<usize>().ok())
                    .and_then(|i| plot.series.get(i))
                    .is_none_or(|s| s.is_empty());
                dom::set_hidden(&item, empty);
            }
            if let Some(table) = query(&drawn.figure, ".plot-table") {
                if !table.has_attribute("hidden") {
                    table.set_inner_html(&table_html(plot));
                }
            }
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
        drawn.frame = paint_plot(&drawn.ctx, plot, palette, drawn.size);
        match drawn.hover_x {
            Some(x) => show_nearest(drawn, plot, palette, x),
            None => {
                if let Some(tip) = query(&drawn.figure, ".plot-tip") {
                    dom::set_hidden(&tip, true);
                }
            }
        }
    }

    /// Shows or hides a plot's data table; returns whether it is now shown.
    pub fn toggle_table(&self, key: &str, plots: &[Plot]) -> bool {
        let (Some(drawn), Some(plot)) = (
            self.plots.iter().find(|d| d.key == key),
            plots.iter().find(|p| p.key == key),
        ) else {
            return false;
        };
        let Some(table) = query(&drawn.figure, ".plot-table") else {
            return false;
        };
        let show = table.has_attribute("hidden");
        if show {
            table.set_inner_html(&table_html(plot));
        }
        dom::set_hidden(&table, !show);
        if let Some(button) = query(&drawn.figure, "[data-plot-table]") {
            let _ = button.set_attribute("aria-expanded", if show { "true" } else { "false" });
        }
        show
    }
}

fn axis_title(label: &str, unit: &str) -> String {
    if unit.is_empty() {
        label.to_owned()
    } else {
        format!("{label} ({unit})")
    }
}

fn tick_label(v: f64, log: bool) -> String {
    if log || (v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3)) {
        let exp = v.abs().log10().floor() as i32;
        let mant = v / 10f64.powi(exp);
        if (mant - 1.0).abs() < 1e-9 {
            format!("1e{exp}")
        } else {
            format!("{}e{exp}", format_number(mant, 1))
        }
    } else {
        format_number(v, 4)
    }
}

fn set_dash(ctx: &CanvasRenderingContext2d, dash: &[f64]) {
    let pattern = js_sys::Array::new();
    for d in dash {
        pattern.push(&JsValue::from_f64(*d));
    }
    let _ = ctx.set_line_dash(&pattern);
}

fn css(palette: &Palette, var: &str) -> String {
    palette.var(var)
}

/// Paints one plot; returns the mapping used.
pub(crate) fn paint_plot(
    ctx: &CanvasRenderingContext2d,
    plot: &Plot,
    palette: &Palette,
    (w, h, dpr): (f64, f64, f64),
) -> Frame {
    let _ = ctx.set_transform(dpr, 0.0, 0.0, dpr, 0.0, 0.0);
    ctx.set_fill_style_str(&palette.background);
    ctx.fill_rect(0.0, 0.0, w, h);
    let (ml, mr, mt, mb) = MARGIN;
    let rect = (ml, mt, (w - ml - mr).max(10.0), (h - mt - mb).max(10.0));
    let text = css(palette, "--c-text");
    let grid = css(palette, "--c-grid");
    ctx.set_font("12px system-ui, sans-serif");
    ctx.set_fill_style_str(&text);
    let Some(x_range) = plot.x_range() else {
        ctx.set_text_align("center");
        ctx.set_text_baseline("middle");
        let _ = ctx.fill_text("No data yet", w / 2.0, h / 2.0);
        return Frame::default();
    };
    let (mut y0, mut y1) = plot.y_range(x_range).unwrap_or((0.0, 1.0));
    let log = plot.log_y && y0 > 0.0;
    if log {
        y0 = 10f64.powf(y0.log10().floor());
        y1 = 10f64.powf(y1.log10().ceil().max(y0.log10() + 1.0));
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
    let frame = Frame {
        x: (x0, x1),
        y: (y0, y1),
        log,
        rect,
    };
    let (l, t, pw, ph) = rect;
    // Bands, then grid and ticks.
    ctx.set_fill_style_str(&css(palette, "--p-band"));
    ctx.set_global_alpha(0.22);
    for band in &plot.bands {
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
    ctx.set_line_width(1.0);
    set_dash(ctx, &[]);
    ctx.set_stroke_style_str(&grid);
    ctx.set_fill_style_str(&text);
    let max_x_ticks = ((pw / 70.0) as usize).clamp(2, 10);
    let max_y_ticks = ((ph / 34.0) as usize).clamp(2, 8);
    ctx.set_text_align("center");
    ctx.set_text_baseline("top");
    for x in nice_ticks(x0, x1, max_x_ticks) {
        let px = frame.px_x(x);
        ctx.begin_path();
        ctx.move_to(px, t);
        ctx.line_to(px, t + ph);
        ctx.stroke();
        let _ = ctx.fill_text(&tick_label(x, false), px, t + ph + 4.0);
    }
    ctx.set_text_align("right");
    ctx.set_text_baseline("middle");
    let y_ticks = if log {
        log_ticks(y0, y1, max_y_ticks)
    } else {
        nice_ticks(y0, y1, max_y_ticks)
    };
    for y in y_ticks {
        let py = frame.px_y(y);
        ctx.begin_path();
        ctx.move_to(l, py);
        ctx.line_to(l + pw, py);
        ctx.stroke();
        let _ = ctx.fill_text(&tick_label(y, log), l - 6.0, py);
    }
    ctx.set_stroke_style_str(&css(palette, "--muted"));
    ctx.stroke_rect(l, t, pw, ph);
    ctx.set_text_align("center");
    ctx.set_text_baseline("bottom");
    let _ = ctx.fill_text(
        &axis_title(plot.x_label, plot.x_unit),
        l + pw / 2.0,
        h - 1.0,
    );
    ctx.save();
    let _ = ctx.translate(12.0, t + ph / 2.0);
    let _ = ctx.rotate(-std::f64::consts::FRAC_PI_2);
    ctx.set_text_baseline("middle");
    let _ = ctx.fill_text(&axis_title(plot.y_label, plot.y_unit), 0.0, 0.0);
    ctx.restore();

    // Clip the data to the plot rectangle.
    ctx.save();
    ctx.begin_path();
    ctx.rect(l, t, pw, ph);
    ctx.clip();
    for line in &plot.ref_lines {
        ctx.set_stroke_style_str(&css(palette, "--p-5"));
        set_dash(ctx, &[6.0, 4.0]);
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
        ctx.set_fill_style_str(&text);
        ctx.set_text_align("right");
        ctx.set_text_baseline("bottom");
        let _ = ctx.fill_text(&line.label, b.0 - 4.0, a.1.max(b.1.min(a.1)) - 2.0);
    }
    let buckets = (pw as usize).max(1);
    let keep = move |y: f64| !log || y > 0.0;
    for s in &plot.series {
        let (var, dash) = role_style(s.role);
        let pts = decimate_min_max(&s.x, &s.y, (x0, x1), buckets, keep);
        ctx.set_stroke_style_str(&css(palette, var));
        set_dash(ctx, dash);
        ctx.set_line_width(2.0);
        ctx.begin_path();
        for (i, (x, y)) in pts.iter().enumerate() {
            let (px, py) = (frame.px_x(*x), frame.px_y(*y));
            if i == 0 {
                ctx.move_to(px, py);
            } else {
                ctx.line_to(px, py);
            }
        }
        if pts.len() == 1 {
            let (px, py) = (frame.px_x(pts[0].0), frame.px_y(pts[0].1));
            let _ = ctx.arc(px, py, 2.0, 0.0, std::f64::consts::TAU);
        }
        ctx.stroke();
    }
    set_dash(ctx, &[]);
    for m in &plot.markers {
        let (px, py) = (frame.px_x(m.x), frame.px_y(m.y));
        ctx.set_fill_style_str(&css(palette, "--p-6"));
        ctx.set_stroke_style_str(&palette.background);
        ctx.begin_path();
        // A diamond: its shape tells it from the lines.
        ctx.move_to(px, py - 6.0);
        ctx.line_to(px + 6.0, py);
        ctx.line_to(px, py + 6.0);
        ctx.line_to(px - 6.0, py);
        ctx.close_path();
        ctx.fill();
        ctx.stroke();
        ctx.set_fill_style_str(&text);
        ctx.set_text_align("left");
        ctx.set_text_baseline("bottom");
        let _ = ctx.fill_text(&m.label, (px + 7.0).min(l + pw - 40.0), py - 4.0);
    }
    ctx.restore();
    frame
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
        ctx.set_fill_style_str(&css(palette, var));
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
    ctx.set_stroke_style_str(&css(palette, "--muted"));
    set_dash(ctx, &[3.0, 3.0]);
    ctx.begin_path();
    ctx.move_to(px, t);
    ctx.line_to(px, t + ph);
    ctx.stroke();
    set_dash(ctx, &[]);
    if let Some(tip) = query(&drawn.figure, ".plot-tip") {
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
        dom::set_hidden(&tip, false);
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

    #[test]
    fn csv_rows_split_with_quotes() {
        assert_eq!(
            split_csv("a,\"b, c\",\"d\"\"e\""),
            vec!["a", "b, c", "d\"e"]
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
