//! The moments a student marks in a run (issue 26 §3): "Mark this moment"
//! keeps the step shown; each mark is a point on every plot, a section of
//! the lab report, and travels in the link as `marks=1.20,3.45` (seconds of
//! the shell's clock, two decimals, as `at=`).
//!
//! Marks belong to the run: a reset (or a new run from a link or a file)
//! clears them; an input that starts a new run from a moment (a parameter,
//! an action, a drag at the step shown) drops the marks after that step,
//! whose states the new run no longer has, and keeps the others
//! ([`Marks::drop_after`]); a mark at the input's own step then shows the
//! state the input left.
//!
//! Times round-trip exactly: a step `n` is written as `n·Δt` to 0.01 s and
//! read back as the nearest step, and Δt = 1/60 s is wider than two
//! hundredths, so every step reads back as itself.

use crate::clock::Clock;
use crate::plot::Plot;

/// The link key of the marks.
pub const MARKS_KEY: &str = "marks";

/// Most marks a run keeps (and a link carries): a report section each.
pub const MAX_MARKS: usize = 12;

/// The latest time a mark may name, seconds (10 simulated minutes, the
/// longest run the shell steps to at once).
pub const MAX_MARK_S: f64 = 600.0;

/// The marked steps of a run, sorted, each once.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Marks {
    steps: Vec<u64>,
}

impl Marks {
    /// The marked steps (steps of [`Clock::DT_S`]), in order.
    #[must_use]
    pub fn steps(&self) -> &[u64] {
        &self.steps
    }

    /// Whether no moment is marked.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }

    /// Marks `step`; false if it was marked already or [`MAX_MARKS`] are
    /// kept.
    pub fn add(&mut self, step: u64) -> bool {
        match self.steps.binary_search(&step) {
            Ok(_) => false,
            Err(_) if self.steps.len() >= MAX_MARKS => false,
            Err(i) => {
                self.steps.insert(i, step);
                true
            }
        }
    }

    /// Unmarks `step`; false if it was not marked.
    pub fn remove(&mut self, step: u64) -> bool {
        match self.steps.binary_search(&step) {
            Ok(i) => {
                self.steps.remove(i);
                true
            }
            Err(_) => false,
        }
    }

    /// Forgets every mark (a reset, a new run).
    pub fn clear(&mut self) {
        self.steps.clear();
    }

    /// A new run starts from `step` (an input there): the marks after it
    /// go, the others stay. Returns whether any went.
    pub fn drop_after(&mut self, step: u64) -> bool {
        let keep = self.steps.partition_point(|&s| s <= step);
        let dropped = keep < self.steps.len();
        self.steps.truncate(keep);
        dropped
    }

    /// The link's value: each mark's time in seconds to 0.01 s, joined by
    /// commas (`1.20,3.45`); empty without marks.
    #[must_use]
    pub fn link_value(&self) -> String {
        self.steps
            .iter()
            .map(|&s| time_text(s))
            .collect::<Vec<_>>()
            .join(",")
    }

    /// Reads a link's value ([`Marks::link_value`]): times in seconds, ≥ 0,
    /// separated by commas, at most [`MAX_MARKS`]. A value that is not that
    /// gives the message to show, and no marks.
    pub fn parse(value: &str) -> Result<Self, String> {
        let mut marks = Self::default();
        let value = value.trim();
        if value.is_empty() {
            return Ok(marks);
        }
        for part in value.split(',') {
            let t_s = part
                .trim()
                .parse::<f64>()
                .ok()
                .filter(|t| t.is_finite() && *t >= 0.0 && *t <= MAX_MARK_S);
            let Some(t_s) = t_s else {
                let shown: String = part.trim().chars().take(12).collect();
                return Err(format!(
                    "Marks: “{shown}” is not a time in seconds from 0 to 600 (e.g. marks=1.20,3.45); no marks were set."
                ));
            };
            let step = (t_s / Clock::DT_S).round() as u64;
            if !marks.add(step) && marks.steps.len() >= MAX_MARKS {
                return Err(format!(
                    "Marks: a run keeps at most {MAX_MARKS} marks; no marks were set."
                ));
            }
        }
        Ok(marks)
    }
}

/// A step's time as marks show it and links carry it: seconds to 0.01
/// (`1.20`).
#[must_use]
pub fn time_text(step: u64) -> String {
    format!("{:.2}", step as f64 * Clock::DT_S)
}

/// What the page says when a link's time (`at=`, `written_s` as the link
/// wrote it, `raw`) is not the time of the step it opened, `step`: the run
/// moves in steps of 1/60 s, so most hundredths of a second are no step's
/// time (`at=0.66` opens step 40, t = 0.67 s). `None` when the time bar
/// reads the time written (every link the page writes: [`time_text`]).
/// A time past the run's end opens its end, and says so the same way.
#[must_use]
pub fn link_time_notice(raw: &str, written_s: f64, step: u64) -> Option<String> {
    // The hundredths the bar reads: step k is at 5k/3 hundredths, a whole
    // number of them or a third or two thirds past one, never half-way.
    let same = (step as f64 * Clock::DT_S * 100.0).round() == (written_s * 100.0).round();
    (!same).then(|| {
        let shown = time_text(step);
        let raw: String = raw.trim().chars().take(12).collect();
        format!(
            "The link's t = {raw} s is no step of the run (one every 1/60 s, up to its end): it opened at t = {shown} s, the nearest."
        )
    })
}

/// A mark's points on each plot: the plot's key, then a point per series
/// (in the plot's units).
pub type PlotPoints = Vec<(&'static str, Vec<(f64, f64)>)>;

/// Where a mark sits on each plot: for each of `plots` (the plots of the
/// state at the marked step), the last sample of each of its series that
/// is not kept for comparison (the run's own curves at that moment).
#[must_use]
pub fn plot_points(plots: &[Plot]) -> PlotPoints {
    plots
        .iter()
        .map(|p| {
            let points = p
                .series
                .iter()
                .filter(|s| !s.comparison)
                .filter_map(|s| Some((*s.x.last()?, *s.y.last()?)))
                .collect();
            (p.key, points)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 53 §7: `at=0.66` opened at 0.67 s and said nothing. A time
    /// the bar can read opens as written; another says where it opened.
    #[test]
    fn link_times_between_steps_say_where_they_opened() {
        assert_eq!(link_time_notice("0.65", 0.65, 39), None);
        assert_eq!(link_time_notice("0.67", 0.67, 40), None);
        assert_eq!(link_time_notice("0.6667", 0.6667, 40), None);
        assert_eq!(
            link_time_notice("0.66", 0.66, 40).as_deref(),
            Some("The link's t = 0.66 s is no step of the run (one every 1/60 s, up to its end): it opened at t = 0.67 s, the nearest.")
        );
        assert_eq!(
            link_time_notice("5", 5.0, 192).as_deref(),
            Some("The link's t = 5 s is no step of the run (one every 1/60 s, up to its end): it opened at t = 3.20 s, the nearest.")
        );
        // Every step's own text reads back as itself and says nothing.
        for step in 0..3600 {
            let text = time_text(step);
            let t: f64 = text.parse().unwrap();
            assert_eq!((t / Clock::DT_S).round() as u64, step);
            assert_eq!(link_time_notice(&text, t, step), None, "{text}");
        }
    }

    #[test]
    fn marks_round_trip_exactly_through_their_link_value() {
        let mut rng = crate::Lcg64::new(26);
        for _ in 0..2000 {
            let mut marks = Marks::default();
            for _ in 0..rng.int(0, MAX_MARKS as i64) {
                marks.add(rng.int(0, 36_000) as u64);
            }
            let text = marks.link_value();
            assert_eq!(Marks::parse(&text), Ok(marks.clone()), "{text}");
        }
    }

    #[test]
    fn malformed_marks_say_what_is_wrong_and_set_none() {
        for bad in ["abc", "1.2,x", "-1", "NaN", "inf", "1e9", "1,,2"] {
            let err = Marks::parse(bad).unwrap_err();
            assert!(err.starts_with("Marks: "), "{bad}: {err}");
        }
        let many = (0..=MAX_MARKS).map(|i| format!("{i}")).collect::<Vec<_>>();
        assert!(Marks::parse(&many.join(",")).is_err());
        assert_eq!(Marks::parse(" 1.00 , 0.50 ").unwrap().steps(), &[30, 60]);
        assert!(Marks::parse("").unwrap().is_empty());
    }

    #[test]
    fn marks_stay_sorted_and_a_new_run_drops_those_after_its_start() {
        let mut marks = Marks::default();
        assert!(marks.add(90));
        assert!(marks.add(30));
        assert!(!marks.add(30), "once");
        assert!(marks.add(60));
        assert_eq!(marks.steps(), &[30, 60, 90]);
        assert!(marks.drop_after(59));
        assert_eq!(marks.steps(), &[30]);
        assert!(!marks.drop_after(30));
        assert!(marks.remove(30));
        assert!(marks.is_empty());
    }
}
