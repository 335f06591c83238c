//! The machine part of a Procedure step, played on a [`Page`]: each item of
//! a step's `play` is one thing the student does or one thing the text says
//! they will see, in the words the page shows (docs/authoring.md,
//! "Procedure steps", lists the vocabulary).

use super::page::{Page, Value as Control};
use glam::DVec2;
use labcore::experiment::Modifiers;
use labcore::testkit::leading_number;
use serde_json::{Map, Value};
use std::collections::HashMap;

/// Why a step does not hold: the experiment, the step, its prose, the claim
/// (or action) and what the page showed.
#[derive(Debug)]
pub struct Failure {
    pub id: String,
    /// From 1.
    pub step: usize,
    pub prose: String,
    pub item: String,
    pub shown: String,
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} step {}: “{}”\n    claim: {}\n    the page showed: {}",
            self.id, self.step, self.prose, self.item, self.shown
        )
    }
}

/// What an item does or checks, by the key that names it (the first of
/// these an item has).
pub const VERBS: [&str; 21] = [
    "set",
    "press",
    "click",
    "drag",
    "move",
    "key",
    "wait",
    "until",
    "scrub",
    "scrub_back_until",
    "scrub_to_largest",
    "reopen",
    "note",
    "see",
    "watch",
    "status",
    "notice",
    "time",
    "plot",
    "table",
    "scene",
];

/// Plot properties (`of`) the native runner reads from the model and the
/// page never puts into its CSV: the time a plot's bands shade. A claim
/// beyond the Procedure may use them (only the native runner plays those);
/// a Procedure step may not, since the browser runner could not read them.
/// (A scene property is read in the browser from Describe's `words`.)
pub const BROWSER_UNREAD: [&str; 1] = ["x_banded"];

/// The keys of a claim about a number ([`Student::compare`]).
const CLAIMS: [&str; 9] = [
    "is",
    "between",
    "above",
    "below",
    "larger_than",
    "smaller_than",
    "about",
    "times",
    "opposite_sign_to",
];

/// A student working through one experiment's Procedure: the page and the
/// values they noted down.
pub struct Student {
    pub page: Page,
    notes: HashMap<String, (f64, String)>,
    /// The scene's numbers as drawn, noted beside the words that say them
    /// (a `scene` item with `words`: the claim holds on both).
    drawn: HashMap<String, (f64, String)>,
}

/// Plays experiment `id`'s Procedure `steps` (the content file's
/// `procedure` array) in order on a freshly opened page, through step
/// `last` (from 1) or all of them; the first step that does not hold.
pub fn play(id: &str, steps: &[Value], last: Option<usize>) -> Result<(), Failure> {
    play_to(id, steps, last).map(|_| ())
}

/// As [`play`], and the page as the steps left it.
pub fn play_to(id: &str, steps: &[Value], last: Option<usize>) -> Result<Page, Failure> {
    let mut student = Student {
        page: Page::open(id),
        notes: HashMap::new(),
        drawn: HashMap::new(),
    };
    let last = last.unwrap_or(steps.len());
    // `LAB_PLAY_TRACE=<id>`: what the page shows after each item, for
    // whoever writes that experiment's Procedure.
    let trace = std::env::var("LAB_PLAY_TRACE").is_ok_and(|t| t == id) && last == steps.len();
    for (k, step) in steps.iter().enumerate().take(last) {
        let prose = step["text"].as_str().unwrap_or_default().to_owned();
        let items = step["play"].as_array().cloned().unwrap_or_default();
        let fail = |item: String, shown: String| Failure {
            id: id.to_owned(),
            step: k + 1,
            prose: prose.clone(),
            item,
            shown,
        };
        if items.is_empty() {
            return Err(fail("(none)".into(), "the step has no machine part".into()));
        }
        for item in &items {
            let done = student.item(item);
            if trace {
                student.trace(k + 1, item);
            }
            done.map_err(|shown| fail(item.to_string(), shown))?;
        }
    }
    Ok(student.page)
}

impl Student {
    /// Prints the item and what the page shows after it.
    fn trace(&self, step: usize, item: &Value) {
        let exp = self.page.exp.as_ref();
        let readouts: Vec<String> = exp
            .readouts()
            .iter()
            .map(|r| format!("{} = {}", r.label, r.value))
            .collect();
        let also = item.get("also").and_then(Value::as_array);
        for i in std::iter::once(item).chain(also.into_iter().flatten()) {
            if let Some((n, said)) = i
                .get("as")
                .and_then(Value::as_str)
                .and_then(|name| self.notes.get(name))
            {
                eprintln!("    noted {n}: {said} ({})", i["as"]);
            }
        }
        let mut roles: Vec<String> = labcore::testkit::scene_of(exp)
            .items
            .iter()
            .filter_map(|i| {
                let d = format!("{i:?}");
                let at = d.find("role: ")? + 6;
                Some(d[at..].split([',', ' ', '}']).next()?.to_owned())
            })
            .collect();
        roles.dedup();
        if item.get("words").is_some() {
            roles.push(format!("\n    Describe: {}", exp.describe()));
        }
        for t in exp.tables() {
            for row in &t.rows {
                roles.push(format!("\n    table row: {}", row.join(" | ")));
            }
        }
        eprintln!(
            "[{step}] {item}\n    t = {:.2} s, status “{}”, notice “{}”\n    {}\n    scene: {}",
            self.page.time_s(),
            exp.status().text,
            labcore::testkit::notice_text(exp),
            readouts.join(" | "),
            roles.join(" ")
        );
    }

    /// Does or checks one item.
    fn item(&mut self, item: &Value) -> Result<(), String> {
        let o = item.as_object().ok_or("an item is an object")?;
        let verb = VERBS
            .iter()
            .find(|v| o.contains_key(**v))
            .ok_or_else(|| format!("no verb: an item is one of {}", VERBS.join(", ")))?;
        // `touch`: the finger's way where the mouse's needs Shift or Ctrl,
        // an item or a list, played by the browser runner at a phone size;
        // here (no touch screen) the mouse's way is played, and the
        // alternative need only name its verbs.
        if let Some(touch) = o.get("touch") {
            let alternative = match touch {
                Value::Array(items) => items.iter().collect(),
                item => vec![item],
            };
            for t in alternative {
                if !t
                    .as_object()
                    .is_some_and(|t| VERBS.iter().any(|v| t.contains_key(*v)))
                {
                    return Err(format!("`touch` is an item or a list of items, not {t}"));
                }
            }
        }
        match *verb {
            "set" => {
                let to = match &o["to"] {
                    // `clamped`: a number typed beyond the control's range,
                    // which the page takes as the nearest end (and says so).
                    Value::Number(n) if o.get("clamped").is_some_and(|c| c == true) => {
                        let label = text(o, "set")?;
                        let params = self.page.exp.params();
                        let spec = params
                            .iter()
                            .find(|s| s.label == label)
                            .ok_or_else(|| format!("no control labelled “{label}”"))?;
                        let n = n.as_f64().unwrap_or(f64::NAN);
                        if (spec.min..=spec.max).contains(&n) {
                            return Err(format!("“{label}” takes {n}: nothing to clamp"));
                        }
                        Control::Number(n.clamp(spec.min, spec.max))
                    }
                    Value::Number(n) => Control::Number(n.as_f64().unwrap_or(f64::NAN)),
                    Value::String(s) => Control::Text(s.clone()),
                    other => return Err(format!("`to` is a number or a label, not {other}")),
                };
                self.page.set(text(o, "set")?, &to)
            }
            "press" => {
                let times = o.get("times").and_then(Value::as_u64).unwrap_or(1);
                for _ in 0..times {
                    self.page.press(text(o, "press")?)?;
                }
                Ok(())
            }
            "click" => {
                let modifiers = match o.get("with").and_then(Value::as_str) {
                    None => Modifiers::default(),
                    Some("shift") => labcore::testkit::SHIFT,
                    Some("ctrl") => labcore::testkit::CTRL,
                    Some(other) => return Err(format!("no key “{other}”")),
                };
                self.page.click(point(&o["click"])?, modifiers)
            }
            "drag" => {
                let from = match &o["drag"] {
                    Value::String(label) => self.page.handle(label)?.1,
                    p => point(p)?,
                };
                let path = match (o.get("to"), o.get("through")) {
                    (Some(to), _) => vec![point(to)?],
                    (None, Some(Value::Array(ps))) => {
                        ps.iter().map(point).collect::<Result<_, _>>()?
                    }
                    _ => return Err("a drag goes `to` a point or `through` points".into()),
                };
                let hold = o.get("hold").is_some_and(|h| h == true);
                self.page.drag(from, &path, hold)
            }
            "key" => {
                let shift = o.get("shift").is_some_and(|s| s == true);
                let times = o.get("times").and_then(Value::as_u64).unwrap_or(1);
                for _ in 0..times {
                    self.page.arrow_key(text(o, "key")?, shift)?;
                }
                Ok(())
            }
            "move" => self.page.move_handle(text(o, "move")?, point(&o["to"])?),
            "wait" => match &o["wait"] {
                Value::String(s) if s == "rest" => self.page.wait_for_rest(),
                v => self
                    .page
                    .wait_s(v.as_f64().ok_or("`wait` is seconds or \"rest\"")?),
            },
            "until" => self
                .page
                .wait_for_text(text(o, "until")?, o.get("readout").and_then(Value::as_str)),
            "scrub" => self.page.scrub_to(number(o, "scrub")?),
            "scrub_back_until" => self.page.scrub_back_until(text(o, "scrub_back_until")?),
            "scrub_to_largest" => {
                let label = text(o, "scrub_to_largest")?.to_owned();
                self.page.scrub_to_largest(|exp| {
                    exp.readouts()
                        .iter()
                        .find(|r| r.label == label)
                        .and_then(|r| shown_number(&r.value))
                })
            }
            "reopen" => self.page.reopen_link(),
            "note" => {
                let label = text(o, "note")?;
                let shown = self.page.readout(label)?;
                let n = shown_number(&shown)
                    .ok_or_else(|| format!("{label} = “{shown}” has no number"))?;
                let name = o.get("as").and_then(Value::as_str).unwrap_or(label);
                self.notes
                    .insert(name.to_owned(), (n, format!("{label} = {shown}")));
                Ok(())
            }
            "see" => {
                let label = text(o, "see")?;
                let shown = self.page.readout(label)?;
                let said = format!("{label} = {shown}");
                if let Some(words) = o.get("says") {
                    let words = words.as_str().ok_or("`says` is a text")?;
                    return if shown.contains(words) {
                        Ok(())
                    } else {
                        Err(said)
                    };
                }
                let n = shown_number(&shown).ok_or_else(|| format!("{said}: no number"))?;
                // As displayed: without `within`, the claim's number is the
                // one the page shows, digit for digit.
                self.compare(o, n, &said, 1e-9 * n.abs())
            }
            "watch" => self.watch(o),
            "status" => {
                let shown = self.page.exp.status().text;
                let words = text(o, "status")?;
                let holds = shown.contains(words) != o.get("not").is_some_and(|n| n == true);
                if holds {
                    Ok(())
                } else {
                    Err(format!("the status “{shown}”"))
                }
            }
            "notice" => {
                let shown = labcore::testkit::notice_text(self.page.exp.as_ref());
                if shown.contains(text(o, "notice")?) {
                    Ok(())
                } else {
                    Err(format!("the notice “{shown}”"))
                }
            }
            "time" => {
                let t = self.page.time_s();
                self.noted_or_compared(o, t, format!("t = {t:.2} s"))
            }
            "plot" => {
                let (n, said) = self.plot_value(o)?;
                self.noted_or_compared(o, n, said)
            }
            "scene" => {
                let (drawn, said) = self.scene_value(o)?;
                let Some(words) = o.get("words") else {
                    return self.noted_or_compared(o, drawn, said);
                };
                // What Describe says of it, as a student reads it: the claim
                // holds on those words, and on the scene as drawn.
                let words = words.as_str().ok_or("`words` is a text")?;
                let text = self.page.exp.describe();
                let n = described_number(&text, words)
                    .ok_or_else(|| format!("Describe does not say “{words}”: “{text}”"))?;
                if CLAIMS.iter().any(|k| o.contains_key(*k)) {
                    compare(&self.drawn, self, o, drawn, &said, 0.0)?;
                }
                if let Some(name) = o.get("as").and_then(Value::as_str) {
                    self.drawn.insert(name.to_owned(), (drawn, said));
                }
                self.noted_or_compared(o, n, format!("{words} = {n} in Describe: “{text}”"))
            }
            "table" => {
                let caption = text(o, "table")?;
                let tables = self.page.exp.tables();
                let table = tables
                    .iter()
                    .find(|t| t.caption.contains(caption))
                    .ok_or_else(|| format!("no table “{caption}”"))?;
                let row = o["row"].as_u64().ok_or("`row` counts from 1")? as usize;
                let cells = table
                    .rows
                    .get(row - 1)
                    .ok_or_else(|| format!("“{caption}” has {} rows", table.rows.len()))?;
                let line = cells.join(" | ");
                if line.contains(text(o, "says")?) {
                    Ok(())
                } else {
                    let all: Vec<String> = table.rows.iter().map(|r| r.join(" | ")).collect();
                    Err(format!(
                        "row {row} of “{caption}”: {line} (its rows: {})",
                        all.join("; ")
                    ))
                }
            }
            other => Err(format!("no verb “{other}” in the step vocabulary")),
        }
    }

    /// A property of a plot's series: `of` is `max`, `min`, `final`,
    /// `max_abs`, `mean`, `x_at_max` (where the maximum is), `x_end` (the last
    /// sample's x), `cursor` (the x of the moment the slider shows),
    /// `first_x_above` (where y first exceeds `level`) or
    /// `swing_growth` (how much wider each swing about `level` is than the
    /// one before, a ratio), `share_in_band` (the % of samples inside the
    /// plot's band) or `share_within` (the % no farther from 0 than the
    /// series `bound`).
    fn plot_value(&self, o: &Map<String, Value>) -> Result<(f64, String), String> {
        let title = text(o, "plot")?;
        let plots = self.page.plots();
        let plot = plots.iter().find(|p| p.title == title).ok_or_else(|| {
            let titles: Vec<&str> = plots.iter().map(|p| p.title).collect();
            format!("no plot “{title}” (the plots: {})", titles.join(", "))
        })?;
        let series = match o.get("series").and_then(Value::as_str) {
            Some(label) => plot.series.iter().find(|s| s.label == label),
            None => plot.series.iter().find(|s| !s.comparison),
        }
        .ok_or_else(|| {
            let labels: Vec<&str> = plot.series.iter().map(|s| s.label.as_str()).collect();
            format!("“{title}” has the series {}", labels.join(", "))
        })?;
        let of = text(o, "of")?;
        let (x, y) = (&series.x, &series.y);
        let at_max = || {
            (0..y.len()).fold(None::<usize>, |best, i| match best {
                Some(b) if y[b] >= y[i] => Some(b),
                _ => Some(i),
            })
        };
        let value = match of {
            "max" => y.iter().copied().reduce(f64::max),
            "min" => y.iter().copied().reduce(f64::min),
            "max_abs" => y.iter().map(|v| v.abs()).reduce(f64::max),
            "final" => y.last().copied(),
            "mean" => (!y.is_empty()).then(|| y.iter().sum::<f64>() / y.len() as f64),
            "x_end" => x.last().copied(),
            // The moment shown on the plot, while the slider is in the past.
            "cursor" => Some(self.page.cursor(title).ok_or_else(|| {
                format!("“{title}” shows no cursor: the page shows the run's end")
            })?),
            "x_at_max" => at_max().map(|i| x[i]),
            "first_x_above" => {
                let level = number(o, "level")?;
                y.iter().position(|v| *v > level).map(|i| x[i])
            }
            "swing_growth" => swing_growth(y, number(o, "level")?),
            // The time (x) the plot's bands across x shade, in all.
            "x_banded" => Some(
                plot.bands
                    .iter()
                    .filter(|b| b.axis == labcore::plot::Axis::X)
                    .map(|b| b.hi - b.lo)
                    .sum(),
            ),
            // The share of samples, in %, inside the plot's shaded band.
            "share_in_band" => {
                let band = plot
                    .bands
                    .iter()
                    .find(|b| b.axis == labcore::plot::Axis::Y)
                    .ok_or_else(|| format!("“{title}” has no band across y"))?;
                share(y.iter().map(|v| band.lo <= *v && *v <= band.hi))
            }
            // The share of samples, in %, no farther from 0 than the series
            // `bound` at the same moment (an error inside its ±3σ).
            "share_within" => {
                let bound = text(o, "bound")?;
                let b = plot
                    .series
                    .iter()
                    .find(|s| s.label == bound)
                    .ok_or_else(|| format!("“{title}” has no series “{bound}”"))?;
                share(y.iter().zip(&b.y).map(|(v, b)| v.abs() <= b.abs()))
            }
            other => return Err(format!("no plot property “{of}”: {other}")),
        }
        .ok_or_else(|| format!("“{}” of plot “{title}” has no samples", series.label))?;
        Ok((
            value,
            format!("{of} of “{}” on “{title}” = {value:.4}", series.label),
        ))
    }

    /// Readouts watched while the clock runs for `for` seconds: the item's
    /// own (`watch`) and those of `also` (items of the same form, without
    /// `for`), each checked or noted as a plot's number is. `of` is
    /// `max_abs` (the largest size it showed) or `last_above` (how long
    /// after the start of the watch its size last exceeded `level`).
    fn watch(&mut self, o: &Map<String, Value>) -> Result<(), String> {
        let seconds = number(o, "for")?;
        let mut watched: Vec<&Map<String, Value>> = vec![o];
        if let Some(also) = o.get("also").and_then(Value::as_array) {
            for a in also {
                watched.push(a.as_object().ok_or("`also` holds watch items")?);
            }
        }
        let frames = (seconds / labcore::clock::Clock::DT_S).round() as usize;
        let mut seen = vec![(0.0_f64, 0.0_f64); watched.len()];
        for k in 0..=frames {
            for (w, (largest, last_above)) in watched.iter().zip(seen.iter_mut()) {
                let shown = self.page.readout(text(w, "watch")?)?;
                let v = shown_number(&shown).unwrap_or(0.0).abs();
                *largest = largest.max(v);
                if w.get("level")
                    .and_then(Value::as_f64)
                    .is_some_and(|l| v > l)
                {
                    *last_above = k as f64 * labcore::clock::Clock::DT_S;
                }
            }
            if k < frames {
                self.page.wait_s(labcore::clock::Clock::DT_S)?;
            }
        }
        for (w, (largest, last_above)) in watched.into_iter().zip(seen) {
            let label = text(w, "watch")?;
            let of = text(w, "of")?;
            let value = match of {
                "max_abs" => largest,
                "last_above" if w.contains_key("level") => last_above,
                other => {
                    return Err(format!(
                        "no watch property “{other}” (max_abs, last_above with a level)"
                    ))
                }
            };
            self.noted_or_compared(
                w,
                value,
                format!("{of} of {label} over {seconds} s = {value:.4}"),
            )?;
        }
        Ok(())
    }

    /// A plot's, the scene's or a watched number: checked against the
    /// item's claim, if it makes one, and noted down with `as`.
    fn noted_or_compared(
        &mut self,
        o: &Map<String, Value>,
        n: f64,
        said: String,
    ) -> Result<(), String> {
        if CLAIMS.iter().any(|k| o.contains_key(*k)) {
            self.compare(o, n, &said, 0.0)?;
        }
        if let Some(name) = o.get("as").and_then(Value::as_str) {
            self.notes.insert(name.to_owned(), (n, said));
        }
        Ok(())
    }

    /// A property of the scene's items of one role (its name in the style
    /// table, as `Debug` writes it): `of` is `count`, `cells` (of a raster,
    /// painted in the role's colour), `max_radius` or `min_radius` (of its
    /// circles, metres), `centre_x` or `centre_y` (the one centre its
    /// circles share, metres), `max_semi_axis` or `min_semi_axis` (the longest
    /// and the shortest semi-axis of its ellipses, metres), `width_px` (its
    /// widest stroke, CSS pixels), `shade_at` a point `at` (its heat map's
    /// shade there, 0 to 1).
    fn scene_value(&self, o: &Map<String, Value>) -> Result<(f64, String), String> {
        use labcore::scene::Item;
        let role = text(o, "scene")?;
        let scene = labcore::testkit::scene_of(self.page.exp.as_ref());
        let items: Vec<&Item> = scene
            .items
            .iter()
            .filter(|i| {
                format!("{i:?}").contains(&format!("role: {role},"))
                    || format!("{i:?}").contains(&format!("role: {role} "))
            })
            .collect();
        let radii = || {
            items.iter().filter_map(|i| match i {
                Item::Circle { radius_m, .. } => Some(*radius_m),
                _ => None,
            })
        };
        let of = text(o, "of")?;
        // Cells of a raster (a basin map) painted in the role's colour.
        let cells = || {
            scene
                .items
                .iter()
                .map(|i| match i {
                    Item::Raster { cells, palette, .. } => cells
                        .iter()
                        .filter(|c| {
                            **c > 0
                                && palette
                                    .get(usize::from(**c) - 1)
                                    .is_some_and(|p| format!("{:?}", p.role) == role)
                        })
                        .count(),
                    _ => 0,
                })
                .sum::<usize>() as f64
        };
        // The one centre its circles share (concentric bounds), metres.
        let centre = || -> Result<Option<DVec2>, String> {
            let mut centres = items.iter().filter_map(|i| match i {
                Item::Circle { center, .. } => Some(*center),
                _ => None,
            });
            let first = centres.next();
            match first {
                Some(c) if centres.all(|d| (d - c).length() < 1e-12) => Ok(Some(c)),
                Some(_) => Err(format!(
                    "the circles of role {role} have more than one centre"
                )),
                None => Ok(None),
            }
        };
        let value = match of {
            "count" => Some(items.len() as f64),
            "centre_x" => centre()?.map(|c| c.x),
            "centre_y" => centre()?.map(|c| c.y),
            "cells" => Some(cells()),
            "max_radius" => radii().reduce(f64::max),
            "min_radius" => radii().reduce(f64::min),
            "max_semi_axis" => items
                .iter()
                .filter_map(|i| match i {
                    Item::Ellipse {
                        semi_axis_a,
                        semi_axis_b,
                        ..
                    } => Some(semi_axis_a.length().max(semi_axis_b.length())),
                    _ => None,
                })
                .reduce(f64::max),
            "min_semi_axis" => items
                .iter()
                .filter_map(|i| match i {
                    Item::Ellipse {
                        semi_axis_a,
                        semi_axis_b,
                        ..
                    } => Some(semi_axis_a.length().min(semi_axis_b.length())),
                    _ => None,
                })
                .reduce(f64::min),
            // The widest stroke among its lines and arrows, CSS pixels.
            "width_px" => items
                .iter()
                .filter_map(|i| match i {
                    Item::Line { width_px, .. }
                    | Item::Polyline { width_px, .. }
                    | Item::Arrow { width_px, .. }
                    | Item::Arrows { width_px, .. }
                    | Item::Segments { width_px, .. } => Some(*width_px),
                    _ => None,
                })
                .reduce(f64::max),
            // The shade of its heat map at the point `at` (0 to 1: the
            // strength of the colour; 0 outside the map).
            "shade_at" => {
                let p = point(o.get("at").ok_or("`shade_at` needs a point `at`")?)?;
                items
                    .iter()
                    .filter_map(|i| match i {
                        Item::Heatmap {
                            min,
                            cell_m,
                            cols,
                            rows,
                            values,
                            ..
                        } => {
                            let cell = ((p - *min) / *cell_m).floor();
                            let inside = cell.x >= 0.0
                                && cell.y >= 0.0
                                && (cell.x as usize) < *cols
                                && (cell.y as usize) < *rows;
                            Some(if inside {
                                f64::from(values[cell.y as usize * cols + cell.x as usize])
                            } else {
                                0.0
                            })
                        }
                        _ => None,
                    })
                    .reduce(f64::max)
            }
            other => return Err(format!("no scene property “{other}”")),
        }
        .ok_or_else(|| format!("the scene has no {of} of role {role}"))?;
        Ok((
            value,
            format!("{of} of the scene's {role} items = {value:.4}"),
        ))
    }

    /// The claim of `o` about the number `n` shown as `said`: `is` (within
    /// `within`, by default `precision`), `between`,
    /// `above`, `below`, `larger_than`, `smaller_than`, `about` (a noted
    /// value or another readout, within `within`), `times` (the ratio to
    /// one, `is` within `within`), `opposite_sign_to`.
    fn compare(
        &self,
        o: &Map<String, Value>,
        n: f64,
        said: &str,
        precision: f64,
    ) -> Result<(), String> {
        compare(&self.notes, self, o, n, said, precision)
    }
}

/// [`Student::compare`] against the values in `notes` (a noted name), or
/// the readouts `student`'s page shows.
fn compare(
    notes: &HashMap<String, (f64, String)>,
    student: &Student,
    o: &Map<String, Value>,
    n: f64,
    said: &str,
    precision: f64,
) -> Result<(), String> {
    let reference = |r: &Value| student.reference(notes, r);
    {
        let within = o.get("within").and_then(Value::as_f64).unwrap_or(precision) + 1e-9;
        let fail = |why: String| Err(format!("{said}{why}"));
        if let Some(r) = o.get("times") {
            let (base, base_said) = reference(r)?;
            let ratio = n / base;
            let k = number(o, "is")?;
            return if (ratio - k).abs() <= within {
                Ok(())
            } else {
                fail(format!(" ({base_said}; ratio {ratio:.3})"))
            };
        }
        if let Some(is) = o.get("is") {
            let k = is.as_f64().ok_or("`is` is a number")?;
            return if (n - k).abs() <= within {
                Ok(())
            } else {
                fail(String::new())
            };
        }
        if let Some(range) = o.get("between") {
            let (a, b) = (
                range[0].as_f64().ok_or("`between` is [low, high]")?,
                range[1].as_f64().ok_or("`between` is [low, high]")?,
            );
            return if a <= n && n <= b {
                Ok(())
            } else {
                fail(String::new())
            };
        }
        for (key, wants_larger) in [
            ("above", true),
            ("larger_than", true),
            ("below", false),
            ("smaller_than", false),
        ] {
            if let Some(r) = o.get(key) {
                let (base, base_said) = reference(r)?;
                let holds = if wants_larger { n > base } else { n < base };
                return if holds {
                    Ok(())
                } else {
                    fail(format!(" ({base_said})"))
                };
            }
        }
        if let Some(r) = o.get("about") {
            let (base, base_said) = reference(r)?;
            return if (n - base).abs() <= within {
                Ok(())
            } else {
                fail(format!(" ({base_said})"))
            };
        }
        if let Some(r) = o.get("opposite_sign_to") {
            let (base, base_said) = reference(r)?;
            return if n * base < 0.0 {
                Ok(())
            } else {
                fail(format!(" ({base_said})"))
            };
        }
        Err("no claim: give is, between, above, below, larger_than, smaller_than, about, times or opposite_sign_to".into())
    }
}

impl Student {
    /// What a comparison is against: a number, a value noted earlier (by
    /// its name, in `notes`) or another readout (by its label).
    fn reference(
        &self,
        notes: &HashMap<String, (f64, String)>,
        r: &Value,
    ) -> Result<(f64, String), String> {
        match r {
            Value::Number(n) => Ok((n.as_f64().unwrap_or(f64::NAN), format!("against {n}"))),
            Value::String(name) => {
                if let Some((n, said)) = notes.get(name) {
                    return Ok((*n, format!("noted as {name}: {said}")));
                }
                let shown = self.page.readout(name)?;
                let n = shown_number(&shown)
                    .ok_or_else(|| format!("{name} = “{shown}” has no number"))?;
                Ok((n, format!("{name} = {shown}")))
            }
            other => Err(format!(
                "compare with a number, a note or a readout, not {other}"
            )),
        }
    }
}

/// The share, in %, of the samples for which `inside` holds.
fn share(inside: impl Iterator<Item = bool>) -> Option<f64> {
    let (mut n, mut k) = (0_usize, 0_usize);
    for i in inside {
        n += 1;
        k += usize::from(i);
    }
    (n > 0).then(|| 100.0 * k as f64 / n as f64)
}

/// How much wider each swing about `level` is than the one before: the
/// median ratio of the largest distances from `level` in successive half
/// swings (between crossings), leaving out the first (the approach) and
/// the last (cut short by the end of the record).
fn swing_growth(y: &[f64], level: f64) -> Option<f64> {
    let mut halves: Vec<f64> = Vec::new();
    let mut current = 0.0_f64;
    let mut side = 0.0_f64;
    for v in y {
        let d = v - level;
        if d == 0.0 {
            continue;
        }
        if side != 0.0 && d.signum() != side {
            halves.push(current);
            current = 0.0;
        }
        side = d.signum();
        current = current.max(d.abs());
    }
    if halves.len() < 3 {
        return None;
    }
    let mut ratios: Vec<f64> = halves[1..].windows(2).map(|w| w[1] / w[0]).collect();
    ratios.sort_by(f64::total_cmp);
    Some(ratios[ratios.len() / 2])
}

/// The number a readout's text shows, read as a student reads it: its
/// leading number, times the power of ten written after it
/// (`2.2 × 10⁻⁸ m` → 2.2e-8).
fn shown_number(text: &str) -> Option<f64> {
    let mantissa = leading_number(text)?;
    let Some((_, rest)) = text.split_once(" × 10") else {
        return Some(mantissa);
    };
    let mut exponent = String::new();
    for c in rest.chars() {
        let digit = match c {
            '⁻' => '-',
            '⁰' => '0',
            '¹' => '1',
            '²' => '2',
            '³' => '3',
            '⁴' => '4',
            '⁵' => '5',
            '⁶' => '6',
            '⁷' => '7',
            '⁸' => '8',
            '⁹' => '9',
            _ => break,
        };
        exponent.push(digit);
    }
    let exponent: i32 = exponent.parse().ok()?;
    Some(mantissa * 10f64.powi(exponent))
}

fn text<'a>(o: &'a Map<String, Value>, key: &str) -> Result<&'a str, String> {
    o.get(key)
        .and_then(Value::as_str)
        .ok_or_else(|| format!("`{key}` is a text"))
}

fn number(o: &Map<String, Value>, key: &str) -> Result<f64, String> {
    o.get(key)
        .and_then(Value::as_f64)
        .ok_or_else(|| format!("`{key}` is a number"))
}

fn point(v: &Value) -> Result<DVec2, String> {
    match v.as_array().map(Vec::as_slice) {
        Some([x, y]) => Ok(DVec2::new(
            x.as_f64().ok_or("a point is [x, y]")?,
            y.as_f64().ok_or("a point is [x, y]")?,
        )),
        _ => Err(format!("a point is [x, y], not {v}")),
    }
}

/// The number Describe's `text` writes where `words` has `#` (the words
/// around it as written; "no" or "No" reads 0): `described_number("2 dashed circles
/// bound", "# dashed circle")` is 2. The first place the words fit.
fn described_number(text: &str, words: &str) -> Option<f64> {
    let (before, after) = words.split_once('#')?;
    let text = text.replace('\u{2212}', "-");
    let places = text
        .char_indices()
        .map(|(i, _)| i)
        .filter(|i| text[*i..].starts_with(before));
    for at in places {
        let rest = &text[at + before.len()..];
        // A number starts here, not inside another one.
        let inside = before.is_empty()
            && text[..at]
                .chars()
                .next_back()
                .is_some_and(|c| c.is_ascii_digit() || c == '.' || c == ',' || c == '-');
        if inside {
            continue;
        }
        let (n, len) = if rest.starts_with("no") || rest.starts_with("No") {
            (Some(0.0), 2)
        } else {
            let len = rest
                .char_indices()
                .take_while(|(i, c)| {
                    c.is_ascii_digit() || (*i == 0 && *c == '-') || *c == '.' || *c == ','
                })
                .count();
            let written = rest[..len].trim_end_matches(['.', ',']);
            (written.replace(',', "").parse().ok(), written.len())
        };
        if let Some(n) = n {
            if rest[len..].starts_with(after) {
                return Some(n);
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::described_number;

    #[test]
    fn described_numbers_are_read_where_the_words_put_them() {
        let text = "Tip at (0.76, 1.27) m. 2 dashed circles bound the reach: outer radius 1.700 m, inner radius 0.300 m. No ghost arm: the branches merge. Basin map: 1,050 starts reach the goal, −3 trapped.";
        assert_eq!(described_number(text, "# dashed circle"), Some(2.0));
        assert_eq!(described_number(text, "outer radius # m"), Some(1.7));
        assert_eq!(described_number(text, "inner radius # m"), Some(0.3));
        assert_eq!(described_number(text, "# ghost arm"), Some(0.0));
        assert_eq!(described_number(text, "# starts reach"), Some(1050.0));
        assert_eq!(described_number(text, "# trapped"), Some(-3.0));
        // A whole number, not a number's tail ("27" of 1.27); words not there.
        assert_eq!(described_number(text, "#) m"), Some(1.27));
        assert_eq!(described_number(text, "# collided"), None);
        assert_eq!(described_number(text, "no number here"), None);
    }
}
