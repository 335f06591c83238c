//! Live plots as data: an experiment describes what to plot the way it
//! describes its scene; the page draws it, shows the nearest sample, offers a
//! data table and exports CSV.
//!
//! A [`Plot`] keeps its full data ([`Series`] are never decimated here); the
//! page draws a dense series as one rectangle per pixel column with
//! [`column_spans`], the lab report's SVG at most a few points per column
//! with [`decimate_min_max`], and both export everything with
//! [`Plot::to_csv`].

mod columns;

pub use columns::{column_spans, dash_is_on};

use crate::units::format_number;

/// What a series means; the page maps each role to a theme colour *and* a
/// dash pattern, so two series differ even without colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SeriesRole {
    /// The main measured quantity (solid, blue).
    Primary,
    /// A second quantity (long dashes, vermilion).
    Secondary,
    /// A third quantity (dots, green).
    Tertiary,
    /// A fourth quantity (dash-dot, purple).
    Quaternary,
    /// A reference or model curve (short dashes, grey).
    Reference,
    /// A bound such as ±3σ (fine dashes, amber).
    Bound,
}

impl SeriesRole {
    /// Every role, in legend order.
    pub const ALL: [SeriesRole; 6] = [
        SeriesRole::Primary,
        SeriesRole::Secondary,
        SeriesRole::Tertiary,
        SeriesRole::Quaternary,
        SeriesRole::Reference,
        SeriesRole::Bound,
    ];
}

/// One curve: samples `(x[i], y[i])` in the plot's units.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend label, also the CSV column name.
    pub label: String,
    /// Unit of the y values (may differ between series of one plot only when
    /// the axis label says so; usually the plot's `y_unit`).
    pub unit: &'static str,
    pub role: SeriesRole,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// A run kept for comparison (a pinned run, an overlay): the page can fit
    /// the x axis to the other series only ("fit the latest run").
    pub comparison: bool,
}

impl Series {
    #[must_use]
    pub fn new(label: impl Into<String>, unit: &'static str, role: SeriesRole) -> Self {
        Self {
            label: label.into(),
            unit,
            role,
            x: Vec::new(),
            y: Vec::new(),
            comparison: false,
        }
    }

    /// Marks the series as a run kept for comparison (see [`Series::comparison`]).
    #[must_use]
    pub fn for_comparison(mut self) -> Self {
        self.comparison = true;
        self
    }

    /// Appends a sample; non-finite samples are skipped (they would poison
    /// the axis range), so every stored value is finite.
    pub fn push(&mut self, x: f64, y: f64) {
        if x.is_finite() && y.is_finite() {
            self.x.push(x);
            self.y.push(y);
        }
    }

    #[must_use]
    pub fn len(&self) -> usize {
        self.x.len()
    }

    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// The index of the sample whose x is nearest `x` (x need not be sorted).
    #[must_use]
    pub fn nearest(&self, x: f64) -> Option<usize> {
        let mut best: Option<(usize, f64)> = None;
        for (i, xi) in self.x.iter().enumerate() {
            let d = (xi - x).abs();
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
        best.map(|(i, _)| i)
    }
}

/// Which axis a reference line is perpendicular to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// A vertical line at an x value.
    X,
    /// A horizontal line at a y value.
    Y,
}

/// A straight reference line (a setpoint, a theoretical radius).
#[derive(Clone, Debug, PartialEq)]
pub struct RefLine {
    pub axis: Axis,
    pub value: f64,
    pub label: String,
}

/// A shaded band: `lo ≤ y ≤ hi` across the plot when `axis` is [`Axis::Y`]
/// (a ±2 % band, χ² bounds), or `lo ≤ x ≤ hi` top to bottom when it is
/// [`Axis::X`] (an interval of time at a saturation limit).
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    pub axis: Axis,
    pub lo: f64,
    pub hi: f64,
    pub label: String,
}

/// A marked event on a curve (a peak, a settling time).
#[derive(Clone, Debug, PartialEq)]
pub struct Marker {
    pub x: f64,
    pub y: f64,
    pub label: String,
}

/// The x range a plot shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum XWindow {
    /// Everything, auto-scaled.
    All,
    /// The last `width` units of x (a rolling time window).
    Rolling(f64),
    /// A fixed range.
    Fixed(f64, f64),
}

/// Most samples a series keeps under [`Plot::push_bounded`] (the oldest
/// quarter is dropped past it).
pub const BOUNDED_SAMPLES: usize = 3000;

/// One plot: series, axes, reference lines, bands and markers.
#[derive(Clone, Debug, PartialEq)]
pub struct Plot {
    /// Stable key: DOM id, CSV file name.
    pub key: &'static str,
    pub title: &'static str,
    pub x_label: &'static str,
    pub x_unit: &'static str,
    pub y_label: &'static str,
    pub y_unit: &'static str,
    /// A logarithmic y axis (non-positive values are not drawn).
    pub log_y: bool,
    pub window: XWindow,
    pub series: Vec<Series>,
    pub ref_lines: Vec<RefLine>,
    pub bands: Vec<Band>,
    pub markers: Vec<Marker>,
    /// Bumped by [`Plot::touch`] whenever the data changes, so the page
    /// redraws only changed plots.
    pub revision: u64,
}

impl Plot {
    /// An empty plot with the given axes and series (no samples yet).
    #[must_use]
    pub fn new(
        key: &'static str,
        title: &'static str,
        (x_label, x_unit): (&'static str, &'static str),
        (y_label, y_unit): (&'static str, &'static str),
        series: Vec<Series>,
    ) -> Self {
        Self {
            key,
            title,
            x_label,
            x_unit,
            y_label,
            y_unit,
            log_y: false,
            window: XWindow::All,
            series,
            ref_lines: Vec::new(),
            bands: Vec::new(),
            markers: Vec::new(),
            revision: 0,
        }
    }

    /// Marks the data as changed.
    pub fn touch(&mut self) {
        self.revision = self.revision.wrapping_add(1);
    }

    /// Appends one sample per series at `x` (`ys[i]` to series `i`) and
    /// drops the oldest quarter of a series once it holds more than
    /// [`BOUNDED_SAMPLES`], with the markers and bands left before the
    /// first sample kept; so a long run stays bounded. Marks the data as
    /// changed.
    pub fn push_bounded(&mut self, x: f64, ys: &[f64]) {
        for (s, y) in self.series.iter_mut().zip(ys) {
            s.push(x, *y);
        }
        for s in &mut self.series {
            if s.len() > BOUNDED_SAMPLES {
                let n = BOUNDED_SAMPLES / 4;
                s.x.drain(..n);
                s.y.drain(..n);
            }
        }
        if let Some(first) = self.series.first().and_then(|s| s.x.first()).copied() {
            self.markers.retain(|m| m.x >= first);
            self.bands.retain(|b| b.hi >= first);
        }
        self.touch();
    }

    /// Removes every sample and marker (keeps series, lines and bands).
    pub fn clear(&mut self) {
        for s in &mut self.series {
            s.x.clear();
            s.y.clear();
        }
        self.markers.clear();
        self.touch();
    }

    /// Forgets what lies wholly before `x_min` (a rolling window's left
    /// edge): the samples with `x < x_min` and the x bands that end before
    /// it. In batches: only once some series' oldest sample is `batch` or
    /// more older than `x_min`, so each sample is moved about once per
    /// `batch` of x rather than at every push (a drain per step moves the
    /// whole window each step, which a long replay multiplies). Returns
    /// whether anything was forgotten.
    pub fn forget_before(&mut self, x_min: f64, batch: f64) -> bool {
        let due = self
            .series
            .iter()
            .any(|s| s.x.first().is_some_and(|x0| *x0 < x_min - batch));
        if due {
            for s in &mut self.series {
                let cut = s.x.iter().take_while(|x| **x < x_min).count();
                s.x.drain(..cut);
                s.y.drain(..cut);
            }
            self.bands.retain(|b| b.axis == Axis::Y || b.hi >= x_min);
        }
        due
    }

    /// Total number of samples over all series.
    #[must_use]
    pub fn sample_count(&self) -> usize {
        self.series.iter().map(Series::len).sum()
    }

    /// The x range shown, or `None` with no samples.
    #[must_use]
    pub fn x_range(&self) -> Option<(f64, f64)> {
        let (lo, hi) = fold_range(self.series.iter().flat_map(|s| s.x.iter().copied()))?;
        Some(match self.window {
            XWindow::All => (lo, hi),
            XWindow::Rolling(w) => ((hi - w.abs()).max(lo).min(hi), hi),
            XWindow::Fixed(a, b) => (a.min(b), a.max(b)),
        })
    }

    /// The y range of the samples inside `x_range`, with reference lines and
    /// bands included; for a log axis only positive values count.
    #[must_use]
    pub fn y_range(&self, (x0, x1): (f64, f64)) -> Option<(f64, f64)> {
        let log = self.log_y;
        let keep = |y: f64| !log || y > 0.0;
        let samples = self.series.iter().flat_map(|s| {
            s.x.iter()
                .zip(&s.y)
                .filter(move |(x, _)| **x >= x0 && **x <= x1)
                .map(|(_, y)| *y)
        });
        let lines = self
            .ref_lines
            .iter()
            .filter(|l| l.axis == Axis::Y)
            .map(|l| l.value);
        let bands = self
            .bands
            .iter()
            .filter(|b| b.axis == Axis::Y)
            .flat_map(|b| [b.lo, b.hi]);
        fold_range(samples.chain(lines).chain(bands).filter(|y| keep(*y)))
    }

    /// A short text description for screen readers: what is plotted and the
    /// latest, smallest and largest value of each series. An empty slot for
    /// a run kept for comparison (a pin not made yet, or cleared) is left
    /// out, as the legend leaves it out: it is no run.
    #[must_use]
    pub fn summary(&self) -> String {
        let mut parts = vec![format!(
            "{}: {} against {}.",
            self.title,
            self.y_label,
            self.x_label.to_ascii_lowercase()
        )];
        for s in self
            .series
            .iter()
            .filter(|s| !(s.comparison && s.is_empty()))
        {
            let Some((lo, hi)) = fold_range(s.y.iter().copied()) else {
                parts.push(format!("{}: no data yet.", s.label));
                continue;
            };
            let last = s.y.last().copied().unwrap_or(0.0);
            parts.push(format!(
                "{}: {} sample{}, latest {}, range {} to {}.",
                s.label,
                s.len(),
                if s.len() == 1 { "" } else { "s" },
                with_unit(last, s.unit),
                with_unit(lo, s.unit),
                with_unit(hi, s.unit)
            ));
        }
        for m in &self.markers {
            parts.push(format!(
                "{} at {} = {}.",
                m.label,
                self.x_label.to_ascii_lowercase(),
                with_unit(m.x, self.x_unit)
            ));
        }
        parts.join(" ")
    }

    /// The full data as CSV (RFC 4180): a header row naming every column with
    /// its unit, then one row per sample. When every series shares the same x
    /// values the x column is written once; otherwise each series gets its own
    /// x and y columns and shorter columns are left empty.
    #[must_use]
    pub fn to_csv(&self) -> String {
        let header_of = |label: &str, unit: &str| {
            if unit.is_empty() {
                csv_field(label)
            } else {
                csv_field(&format!("{label} ({unit})"))
            }
        };
        let shared_x = self.series.windows(2).all(|w| w[0].x == w[1].x);
        let mut out = String::new();
        let rows = self.series.iter().map(Series::len).max().unwrap_or(0);
        if shared_x {
            let mut head = vec![header_of(self.x_label, self.x_unit)];
            head.extend(self.series.iter().map(|s| header_of(&s.label, s.unit)));
            out.push_str(&head.join(","));
            out.push_str("\r\n");
            let xs = self.series.first().map_or(&[][..], |s| &s.x[..]);
            for (i, x) in xs.iter().enumerate() {
                let mut row = vec![csv_x(*x)];
                row.extend(self.series.iter().map(|s| csv_number(s.y[i])));
                out.push_str(&row.join(","));
                out.push_str("\r\n");
            }
        } else {
            let mut head = Vec::new();
            for s in &self.series {
                head.push(header_of(
                    &format!("{} {}", s.label, self.x_label),
                    self.x_unit,
                ));
                head.push(header_of(&s.label, s.unit));
            }
            out.push_str(&head.join(","));
            out.push_str("\r\n");
            for i in 0..rows {
                let mut row = Vec::new();
                for s in &self.series {
                    match (s.x.get(i), s.y.get(i)) {
                        (Some(x), Some(y)) => {
                            row.push(csv_x(*x));
                            row.push(csv_number(*y));
                        }
                        _ => {
                            row.push(String::new());
                            row.push(String::new());
                        }
                    }
                }
                out.push_str(&row.join(","));
                out.push_str("\r\n");
            }
        }
        out
    }
}

fn with_unit(v: f64, unit: &str) -> String {
    let n = format_number(v, 4);
    if unit.is_empty() {
        n
    } else {
        format!("{n} {unit}")
    }
}

/// Full precision, shortest round-trip form (Rust's `Display` for f64).
fn csv_number(v: f64) -> String {
    format!("{v}")
}

/// An x value (time, iteration) as the CSV writes it: rounded to 12
/// significant digits first, so a time accumulated or computed as
/// step × dt reads `0.15`, not `0.15000000000000002`. Twelve digits keep
/// microseconds over a week-long run.
fn csv_x(v: f64) -> String {
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    csv_number(rounded)
}

/// Quotes a CSV field when it holds a comma, quote or line break.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_owned()
    }
}

/// The smallest and largest of finite values, or `None` when there are none.
fn fold_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite())
        .fold(None, |acc, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// "Nice" tick values covering `[lo, hi]`: steps of 1, 2 or 5 × 10ᵏ with at
/// most `max_ticks` ticks, as many as fit (Heckbert, "Nice numbers for graph
/// labels", *Graphics Gems*, 1990). A degenerate range is widened around its
/// value. It may hold a single tick, or none: [`axis_ticks`] widens the
/// range of an axis so that it holds two.
///
/// ```
/// assert_eq!(labcore::plot::nice_ticks(0.0, 1.0, 6), vec![0.0, 0.2, 0.4, 0.6, 0.8, 1.0]);
/// ```
#[must_use]
pub fn nice_ticks(lo: f64, hi: f64, max_ticks: usize) -> Vec<f64> {
    nice_steps(lo, hi, max_ticks).map_or_else(Vec::new, |(lo, hi, step)| ticks_of(lo, hi, step))
}

/// An axis over at least `[lo, hi]` and its ticks, at least two of them:
/// those of [`nice_ticks`] where the range holds two; else those of the
/// next smaller step where they are at most one more than `max_ticks`;
/// else the range is widened to the multiples of the step just outside it
/// (less than a step each way), which puts two or three ticks on it.
/// Returns the axis' ends and its ticks; nothing for a range that is not
/// finite or `max_ticks < 2`.
///
/// ```
/// // ±0.03 with room for two ticks: 0.05 apart only 0 is inside, and
/// // 0.02 apart there are three.
/// let (lo, hi, ticks) = labcore::plot::axis_ticks(-0.03, 0.03, 2).unwrap();
/// assert_eq!((lo, hi, ticks), (-0.03, 0.03, vec![-0.02, 0.0, 0.02]));
/// ```
#[must_use]
pub fn axis_ticks(lo: f64, hi: f64, max_ticks: usize) -> Option<(f64, f64, Vec<f64>)> {
    let (lo, hi, step) = nice_steps(lo, hi, max_ticks)?;
    let ticks = ticks_of(lo, hi, step);
    if ticks.len() >= 2 {
        return Some((lo, hi, ticks));
    }
    // The ladder's step below: 5 → 2, 2 → 1, 1 → 0.5.
    let leading = step / 10f64.powi(crate::math::log10(step).floor() as i32);
    let smaller = if (leading - 5.0).abs() < 0.5 {
        step / 2.5
    } else {
        step / 2.0
    };
    if ticks_in(lo, hi, smaller) <= (max_ticks + 1) as f64 {
        return Some((lo, hi, ticks_of(lo, hi, smaller)));
    }
    let (a, b) = (
        snap(step, (lo / step).floor() * step).min(lo),
        snap(step, (hi / step).ceil() * step).max(hi),
    );
    Some((a, b, ticks_of(a, b, step)))
}

/// The range `[lo, hi]` (a degenerate one widened) and the tick step of
/// [`nice_ticks`]: the smallest of 1, 2 or 5 × 10ᵏ that puts at most
/// `max_ticks` ticks in the range, so as many as fit. `None` for a range
/// that is not finite or `max_ticks < 2`.
fn nice_steps(lo: f64, hi: f64, max_ticks: usize) -> Option<(f64, f64, f64)> {
    if !(lo.is_finite() && hi.is_finite()) || max_ticks < 2 {
        return None;
    }
    let (lo, hi) = if hi - lo > 1e-300 * lo.abs().max(1.0) {
        (lo, hi)
    } else {
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
        (lo - pad, hi + pad)
    };
    let raw = (hi - lo) / (max_ticks - 1) as f64;
    let mag = 10f64.powi(crate::math::log10(raw).floor() as i32);
    // From a decade below: 0.93 to 1.93 with two ticks is 1.0 and 1.5,
    // where steps from 1 up put only 1.0 in it.
    let step = [0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| ticks_in(lo, hi, *s) <= max_ticks as f64)
        .unwrap_or(10.0 * mag);
    Some((lo, hi, step))
}

/// Tolerate float noise at the ends: 0.35 / 0.05 is 6.999….
fn first_multiple(lo: f64, step: f64) -> f64 {
    (lo / step - 1e-9).ceil()
}

fn last_multiple(hi: f64, step: f64) -> f64 {
    (hi / step + 1e-9).floor()
}

/// How many multiples of `step` lie in `[lo, hi]`.
fn ticks_in(lo: f64, hi: f64, step: f64) -> f64 {
    last_multiple(hi, step) - first_multiple(lo, step) + 1.0
}

/// A multiple of `step` with its float noise snapped to the step's decimals
/// (0.30000000000000004 → 0.3).
fn snap(step: f64, v: f64) -> f64 {
    let decimals = (-crate::math::log10(step).floor()).max(0.0) as i32;
    let scale = 10f64.powi(decimals);
    (v * scale).round() / scale
}

/// The multiples of `step` in `[lo, hi]`.
fn ticks_of(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let first = first_multiple(lo, step) as i64;
    let last = last_multiple(hi, step) as i64;
    (first..=last)
        .map(|k| snap(step, k as f64 * step))
        .collect()
}

/// Tick values for a log axis over `[lo, hi]` (both > 0): the powers of ten
/// inside it, thinned to at most `max_ticks`.
#[must_use]
pub fn log_ticks(lo: f64, hi: f64, max_ticks: usize) -> Vec<f64> {
    if !(lo > 0.0 && hi >= lo && hi.is_finite()) || max_ticks == 0 {
        return Vec::new();
    }
    let (a, b) = (
        crate::math::log10(lo).ceil() as i32,
        crate::math::log10(hi).floor() as i32,
    );
    if b < a {
        return vec![lo, hi];
    }
    let count = (b - a + 1) as usize;
    let stride = count.div_ceil(max_ticks).max(1) as i32;
    (a..=b)
        .filter(|k| (k - a) % stride == 0)
        .map(|k| 10f64.powi(k))
        .collect()
}

/// Reduces a series to at most four points per bucket — first, minimum,
/// maximum and last of the samples whose x falls in each of `buckets` equal
/// slices of `[x0, x1]` — keeping their order. A line through the result looks
/// the same as through every sample at one bucket per pixel column, so a
/// 10,000-point series costs a few hundred line segments to draw. Samples
/// outside `[x0, x1]` are dropped; `y` values that `keep` rejects (e.g. ≤ 0 on
/// a log axis) break nothing and are skipped.
#[must_use]
pub fn decimate_min_max(
    x: &[f64],
    y: &[f64],
    (x0, x1): (f64, f64),
    buckets: usize,
    keep: impl Fn(f64) -> bool,
) -> Vec<(f64, f64)> {
    let n = x.len().min(y.len());
    let buckets = buckets.max(1);
    let width = (x1 - x0).max(f64::MIN_POSITIVE);
    if n <= buckets * 4 {
        return (0..n)
            .filter(|&i| x[i] >= x0 && x[i] <= x1 && keep(y[i]))
            .map(|i| (x[i], y[i]))
            .collect();
    }
    let mut out = Vec::with_capacity(buckets * 4);
    let mut current: Option<usize> = None;
    let mut group: Vec<usize> = Vec::new();
    let flush = |group: &mut Vec<usize>, out: &mut Vec<(f64, f64)>| {
        if group.is_empty() {
            return;
        }
        let first = group[0];
        let last = group[group.len() - 1];
        let mut min = first;
        let mut max = first;
        for &i in group.iter() {
            if y[i] < y[min] {
                min = i;
            }
            if y[i] > y[max] {
                max = i;
            }
        }
        let mut picks = [first, min, max, last];
        picks.sort_unstable();
        let mut prev = usize::MAX;
        for i in picks {
            if i != prev {
                out.push((x[i], y[i]));
                prev = i;
            }
        }
        group.clear();
    };
    for i in 0..n {
        if !(x[i] >= x0 && x[i] <= x1 && keep(y[i])) {
            continue;
        }
        let b = (((x[i] - x0) / width) * buckets as f64).floor() as usize;
        let b = b.min(buckets - 1);
        if current != Some(b) {
            flush(&mut group, &mut out);
            current = Some(b);
        }
        group.push(i);
    }
    flush(&mut group, &mut out);
    out
}

/// The heap bytes plots hold (their series, samples, labels, lines, bands
/// and markers; not the `Plot`s themselves, which their owner counts): the
/// default of [`crate::Experiment::state_bytes`], what a timeline snapshot
/// of them costs.
#[must_use]
pub fn plots_bytes(plots: &[Plot]) -> usize {
    use std::mem::size_of;
    plots
        .iter()
        .map(|p| {
            let series: usize = p
                .series
                .iter()
                .map(|s| (s.x.capacity() + s.y.capacity()) * size_of::<f64>() + s.label.capacity())
                .sum();
            let labels: usize = p
                .ref_lines
                .iter()
                .map(|r| r.label.capacity())
                .sum::<usize>()
                + p.bands.iter().map(|b| b.label.capacity()).sum::<usize>()
                + p.markers.iter().map(|m| m.label.capacity()).sum::<usize>();
            series
                + labels
                + p.series.capacity() * size_of::<Series>()
                + p.ref_lines.capacity() * size_of::<RefLine>()
                + p.bands.capacity() * size_of::<Band>()
                + p.markers.capacity() * size_of::<Marker>()
        })
        .sum()
}

#[cfg(test)]
mod tests {

    #[test]
    fn csv_time_column_reads_as_step_times_dt() {
        // Issue 13 §5: 0.05000000000000001 in the time column.
        let mut plot = Plot::new(
            "p",
            "P",
            ("t", "s"),
            ("x", "m"),
            vec![Series::new("x", "m", SeriesRole::Primary)],
        );
        let mut t = 0.0;
        for k in 0..200 {
            plot.series[0].push(t, 0.1 + 0.2 * f64::from(k));
            t += 0.05;
        }
        let csv = plot.to_csv();
        let times: Vec<&str> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').next().unwrap())
            .collect();
        for (k, text) in times.iter().enumerate() {
            let expected = format!("{}", (k as f64 * 5.0).round() / 100.0);
            assert_eq!(*text, expected, "row {k}");
        }
        // y keeps full precision.
        assert!(csv.contains(",0.30000000000000004\r\n"));
    }

    use super::*;

    fn demo() -> Plot {
        let mut p = Plot::new(
            "err",
            "Error",
            ("Iteration", ""),
            ("Error", "m"),
            vec![
                Series::new("error", "m", SeriesRole::Primary),
                Series::new("w", "", SeriesRole::Secondary),
            ],
        );
        for i in 0..3 {
            p.series[0].push(f64::from(i), 1.0 / f64::from(i + 1));
            p.series[1].push(f64::from(i), f64::from(i) * 0.5);
        }
        p
    }

    #[test]
    fn push_bounded_drops_the_oldest_quarter_past_3000_samples_and_what_lay_there() {
        let mut p = demo();
        p.series[0].x.clear();
        p.series[0].y.clear();
        p.series[1].x.clear();
        p.series[1].y.clear();
        p.markers.push(Marker {
            x: 10.0,
            y: 0.0,
            label: "early".into(),
        });
        p.markers.push(Marker {
            x: 2000.0,
            y: 0.0,
            label: "late".into(),
        });
        for k in 0..3000 {
            p.push_bounded(f64::from(k), &[1.0, 2.0]);
        }
        assert_eq!((p.series[0].len(), p.revision), (3000, 3000));
        assert_eq!(p.markers.len(), 2, "nothing dropped yet");
        // Sample 3001 drops 750 (3000 / 4): x = 0 … 749 go; 2251 stay.
        p.push_bounded(3000.0, &[1.0, f64::NAN]);
        assert_eq!(p.series[0].len(), 2251);
        assert_eq!(p.series[0].x[0], 750.0);
        // The NaN was skipped: 3000 samples, none dropped.
        assert_eq!(p.series[1].len(), 3000);
        assert_eq!(p.markers.len(), 1);
        assert_eq!(p.markers[0].label, "late");
        assert_eq!(p.revision, 3001);
    }

    #[test]
    fn csv_has_units_in_the_header_and_every_sample() {
        let csv = demo().to_csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "Iteration,error (m),w");
        assert_eq!(lines[1], "0,1,0");
        assert_eq!(lines[2], "1,0.5,0.5");
        assert_eq!(lines[3], "2,0.3333333333333333,1");
        assert_eq!(lines.len(), 4);
    }

    #[test]
    fn csv_with_different_x_uses_column_pairs_and_quotes() {
        let mut p = demo();
        p.series[1].label = "a, \"b\"".into();
        p.series[1].push(3.0, 9.0);
        let csv = p.to_csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(
            lines[0],
            "error Iteration,error (m),\"a, \"\"b\"\" Iteration\",\"a, \"\"b\"\"\""
        );
        assert_eq!(lines[4], ",,3,9");
    }

    #[test]
    fn non_finite_samples_are_skipped() {
        let mut s = Series::new("s", "", SeriesRole::Primary);
        s.push(0.0, f64::NAN);
        s.push(f64::INFINITY, 1.0);
        s.push(1.0, 2.0);
        assert_eq!((s.x.clone(), s.y.clone()), (vec![1.0], vec![2.0]));
    }

    #[test]
    fn ranges_follow_window_lines_and_log_axis() {
        let mut p = demo();
        assert_eq!(p.x_range(), Some((0.0, 2.0)));
        p.ref_lines.push(RefLine {
            axis: Axis::Y,
            value: 5.0,
            label: "ref".into(),
        });
        assert_eq!(p.y_range((0.0, 2.0)), Some((0.0, 5.0)));
        p.log_y = true;
        // w = 0 is not positive: the log range starts at the smallest positive value.
        assert_eq!(p.y_range((0.0, 2.0)), Some((1.0 / 3.0, 5.0)));
        p.window = XWindow::Rolling(1.0);
        assert_eq!(p.x_range(), Some((1.0, 2.0)));
    }

    #[test]
    fn nice_ticks_by_hand() {
        assert_eq!(nice_ticks(0.0, 1.0, 6), vec![0.0, 0.2, 0.4, 0.6, 0.8, 1.0]);
        assert_eq!(nice_ticks(-3.0, 7.0, 6), vec![-2.0, 0.0, 2.0, 4.0, 6.0]);
        assert_eq!(nice_ticks(0.0, 1000.0, 5), vec![0.0, 500.0, 1000.0]);
        assert_eq!(
            nice_ticks(0.1, 0.35, 6),
            vec![0.1, 0.15, 0.2, 0.25, 0.3, 0.35]
        );
        // A flat series still gets ticks around its value.
        assert!(!nice_ticks(2.0, 2.0, 5).is_empty());
        assert!(nice_ticks(f64::NAN, 1.0, 5).is_empty());
    }

    /// Issue 53 §7: y axes with a single tick label (ekf's position errors,
    /// cart-pole's force). Room for two ticks over 0.93…1.93 put only 1.0
    /// on it (steps of 1, 2, 5); over ±0.03, only 0.
    #[test]
    fn every_axis_has_two_ticks_by_hand() {
        assert_eq!(nice_ticks(0.93, 1.93, 2), vec![1.0, 1.5]);
        assert_eq!(
            axis_ticks(0.93, 1.93, 2),
            Some((0.93, 1.93, vec![1.0, 1.5]))
        );
        // ±0.03 with room for two: 0.05 apart only 0 is inside; 0.02 apart,
        // three, one more than the room, and the axis stays as it is.
        assert_eq!(nice_ticks(-0.03, 0.03, 2), vec![0.0]);
        assert_eq!(
            axis_ticks(-0.03, 0.03, 2),
            Some((-0.03, 0.03, vec![-0.02, 0.0, 0.02]))
        );
        // 1.9…6.1 with room for two: 5 apart only 5; 2 apart, 2, 4 and 6.
        assert_eq!(nice_ticks(1.9, 6.1, 2), vec![5.0]);
        assert_eq!(
            axis_ticks(1.9, 6.1, 2),
            Some((1.9, 6.1, vec![2.0, 4.0, 6.0]))
        );
        // 1.9…8.1 with room for two: 2 apart would be four; the axis widens
        // to 0…10, 5 apart.
        assert_eq!(nice_ticks(1.9, 8.1, 2), vec![5.0]);
        assert_eq!(
            axis_ticks(1.9, 8.1, 2),
            Some((0.0, 10.0, vec![0.0, 5.0, 10.0]))
        );
        assert_eq!(axis_ticks(f64::NAN, 1.0, 5), None);
        assert_eq!(axis_ticks(0.0, 1.0, 1), None);
    }

    #[test]
    fn axis_ticks_are_two_or_more_and_at_most_one_over_the_room() {
        let mut rng = crate::Lcg64::new(11);
        for _ in 0..4000 {
            let a = rng.range(-1e6, 1e6) * 10f64.powi(rng.int(-8, 3) as i32);
            let b = a + rng.range(1e-9, 1e3) * 10f64.powi(rng.int(-3, 3) as i32);
            let n = rng.int(2, 12) as usize;
            let (lo, hi, t) = axis_ticks(a, b, n).unwrap();
            assert!(t.len() >= 2 && t.len() <= n + 1, "{a} {b} {n}: {t:?}");
            assert!(lo <= a && hi >= b, "{a} {b} → {lo} {hi}");
            let step = t[1] - t[0];
            // Widened by less than a step each way, to ticks at its ends.
            assert!(
                a - lo < step * (1.0 + 1e-9) && hi - b < step * (1.0 + 1e-9),
                "{a} {b} → {lo} {hi} {t:?}"
            );
            let eps = (hi - lo) * 1e-9;
            assert!(
                t.iter().all(|v| *v >= lo - eps && *v <= hi + eps),
                "{lo} {hi} {t:?}"
            );
            assert!(t.windows(2).all(|w| w[1] > w[0]));
        }
    }

    #[test]
    fn nice_ticks_stay_within_count_and_range() {
        let mut rng = crate::Lcg64::new(7);
        for _ in 0..2000 {
            let a = rng.range(-1e6, 1e6) * 10f64.powi(rng.int(-8, 3) as i32);
            let b = a + rng.range(1e-9, 1e3) * 10f64.powi(rng.int(-3, 3) as i32);
            let n = rng.int(2, 12) as usize;
            let t = nice_ticks(a, b, n);
            assert!(t.len() <= n, "{a} {b} {n}: {t:?}");
            assert!(!t.is_empty() || b - a < 1e-300, "{a} {b} {n}");
            let eps = (b - a) * 1e-9;
            assert!(
                t.iter().all(|v| *v >= a - eps && *v <= b + eps),
                "{a} {b} {t:?}"
            );
            assert!(t.windows(2).all(|w| w[1] > w[0]));
        }
    }

    #[test]
    fn log_ticks_are_powers_of_ten() {
        assert_eq!(
            log_ticks(1e-6, 10.0, 10),
            vec![1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0]
        );
        assert_eq!(log_ticks(1e-6, 10.0, 4), vec![1e-6, 1e-4, 1e-2, 1.0]);
        assert!(log_ticks(0.0, 1.0, 4).is_empty());
    }

    #[test]
    fn decimation_keeps_extremes_and_bounds_the_count() {
        let n = 10_000;
        let x: Vec<f64> = (0..n).map(f64::from).collect();
        let y: Vec<f64> = (0..n)
            .map(|i| crate::math::sin(f64::from(i) * 0.01))
            .collect();
        let d = decimate_min_max(&x, &y, (0.0, f64::from(n - 1)), 300, |_| true);
        assert!(d.len() <= 1200, "{}", d.len());
        assert!(d.len() >= 300);
        let max = d.iter().map(|p| p.1).fold(f64::MIN, f64::max);
        let min = d.iter().map(|p| p.1).fold(f64::MAX, f64::min);
        let true_max = y.iter().copied().fold(f64::MIN, f64::max);
        let true_min = y.iter().copied().fold(f64::MAX, f64::min);
        assert_eq!((min, max), (true_min, true_max));
        assert!(d.windows(2).all(|w| w[1].0 >= w[0].0), "order kept");
        assert_eq!(d.first().map(|p| p.0), Some(0.0));
        assert_eq!(d.last().map(|p| p.0), Some(f64::from(n - 1)));
    }

    #[test]
    fn summary_names_series_and_markers() {
        let mut p = demo();
        p.markers.push(Marker {
            x: 1.0,
            y: 0.5,
            label: "Peak".into(),
        });
        let s = p.summary();
        assert!(s.starts_with("Error: Error against iteration."), "{s}");
        assert!(
            s.contains("error: 3 samples, latest 0.3333 m, range 0.3333 m to 1 m."),
            "{s}"
        );
        assert!(s.contains("Peak at iteration = 1."), "{s}");
    }

    /// Issue 53 §7: after pid's Clear pins the summary still named the four
    /// pin slots ("pinned run A: no data yet. …"), which the legend hides.
    #[test]
    fn summary_leaves_out_empty_comparison_slots_and_names_kept_runs() {
        let mut p = demo();
        p.series
            .push(Series::new("pinned run A", "m", SeriesRole::Secondary).for_comparison());
        let mut kept = Series::new("A: Kp 12", "m", SeriesRole::Tertiary).for_comparison();
        kept.push(0.0, 2.0);
        p.series.push(kept);
        p.series
            .push(Series::new("live, empty", "m", SeriesRole::Quaternary));
        let s = p.summary();
        assert!(!s.contains("pinned run A"), "{s}");
        assert!(
            s.contains("A: Kp 12: 1 sample, latest 2 m, range 2 m to 2 m."),
            "{s}"
        );
        // The run's own series says it has no data yet.
        assert!(s.contains("live, empty: no data yet."), "{s}");
    }
}
