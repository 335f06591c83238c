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
                let (n, said) = self.scene_value(o)?;
                self.noted_or_compared(o, n, said)
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
    /// sample's x), `first_x_above` (where y first exceeds `level`) or
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
            "x_at_max" => at_max().map(|i| x[i]),
            "first_x_above" => {
                let level = number(o, "level")?;
                y.iter().position(|v| *v > level).map(|i| x[i])
            }
            "swing_growth" => swing_growth(y, number(o, "level")?),
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
    /// circles, metres), `max_semi_axis` (of its ellipses, metres).
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
        let value = match of {
            "count" => Some(items.len() as f64),
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
        let within = o.get("within").and_then(Value::as_f64).unwrap_or(precision) + 1e-9;
        let fail = |why: String| Err(format!("{said}{why}"));
        if let Some(r) = o.get("times") {
            let (base, base_said) = self.reference(r)?;
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
                let (base, base_said) = self.reference(r)?;
                let holds = if wants_larger { n > base } else { n < base };
                return if holds {
                    Ok(())
                } else {
                    fail(format!(" ({base_said})"))
                };
            }
        }
        if let Some(r) = o.get("about") {
            let (base, base_said) = self.reference(r)?;
            return if (n - base).abs() <= within {
                Ok(())
            } else {
                fail(format!(" ({base_said})"))
            };
        }
        if let Some(r) = o.get("opposite_sign_to") {
            let (base, base_said) = self.reference(r)?;
            return if n * base < 0.0 {
                Ok(())
            } else {
                fail(format!(" ({base_said})"))
            };
        }
        Err("no claim: give is, between, above, below, larger_than, smaller_than, about, times or opposite_sign_to".into())
    }

    /// What a comparison is against: a number, a value noted earlier (by
    /// its name) or another readout (by its label).
    fn reference(&self, r: &Value) -> Result<(f64, String), String> {
        match r {
            Value::Number(n) => Ok((n.as_f64().unwrap_or(f64::NAN), format!("against {n}"))),
            Value::String(name) => {
                if let Some((n, said)) = self.notes.get(name) {
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
