//! The Simulation tab as a student has it, natively: an experiment behind
//! its controls (found by their visible labels), its readouts and status (as
//! displayed text), and the shell's time bar (Pause, Step, Back, Run to end,
//! Reset, the timeline slider) on a stopped clock the runner steps.
//!
//! It does what `labweb/src/sim` does with the same labcore pieces: a run
//! is recorded on a [`Timeline`]; an input while the slider shows the past
//! starts a new run from there; stepping stops while nothing moves or once
//! the run has ended; Run to end steps until either, at most
//! [`RUN_TO_END_MAX_STEPS`].

use glam::DVec2;
use labcore::clock::Clock;
use labcore::experiment::{Input, Lab, Modifiers, ParamKind, Phase};
use labcore::plot::Plot;
use labcore::testkit;
use labcore::timeline::{self, KeptRun, Timeline};

/// Run to end's cap, as the page's (`labweb/src/sim/scrub.rs`): ten
/// simulated minutes.
pub const RUN_TO_END_MAX_STEPS: u64 = 10 * 60 * 60;

/// One experiment's Simulation tab, opened fresh.
pub struct Page {
    pub exp: Box<dyn Lab>,
    timeline: Timeline,
    /// The step the page shows (the clock's count): the timeline's end
    /// unless the student went back.
    at: u64,
    /// The time bar's Play/Pause: a paused page steps only on Step.
    pub playing: bool,
    /// A pointer still pressed at the end of a drag (`hold`), released at
    /// the student's next input.
    held: Option<DVec2>,
    /// The step of the student's last input: where the run shown began.
    last_input: u64,
    /// The runs a change in the past or a restart left behind, kept on the
    /// plots.
    kept: Vec<KeptRun>,
    /// The timeline paused the run (a scrub, Run to end), not the student:
    /// the next change that branches or restarts plays, as the page's
    /// (`labweb/src/sim/scrub.rs`, `finish_branch`).
    timeline_paused: bool,
    /// The run's last state while the page shows a past moment of it, as
    /// the page keeps it (`record_end`): its plots are the ones drawn, its
    /// pinned runs the ones shown.
    record_end: Option<Box<dyn Lab>>,
}

/// A run ended by a restart is kept for comparison when it lasted at least
/// this many steps (half a second), as on the page (`KEEP_MIN_STEPS`).
const KEEP_MIN_STEPS: u64 = 30;

/// The main plot's progress ([`timeline::plot_x`]): where it goes back, an
/// input started the run again.
fn main_x(exp: &dyn Lab) -> Option<f64> {
    exp.plots().first().and_then(timeline::plot_x)
}

impl Page {
    /// The experiment `id` as a freshly opened Simulation tab shows it.
    pub fn open(id: &str) -> Self {
        let exp = testkit::open(id);
        let timeline = Timeline::new(exp.as_ref(), 0);
        Self {
            exp,
            timeline,
            at: 0,
            playing: true,
            held: None,
            last_input: 0,
            kept: Vec::new(),
            timeline_paused: false,
            record_end: None,
        }
    }

    /// The simulated time the time bar shows, in seconds.
    pub fn time_s(&self) -> f64 {
        self.at as f64 * Clock::DT_S
    }

    /// A change by the student (a control, a button, a click): from the
    /// moment shown, the run is a new one. Made in the past, it leaves the
    /// old run's future on the plots, named after the change (`cause`
    /// when no parameter changed), as the page keeps it.
    fn input(
        &mut self,
        change: impl FnOnce(&mut dyn Lab) -> Result<(), String>,
    ) -> Result<(), String> {
        self.input_because(None, change)
    }

    fn input_because(
        &mut self,
        cause: Option<&str>,
        change: impl FnOnce(&mut dyn Lab) -> Result<(), String>,
    ) -> Result<(), String> {
        let values = |exp: &dyn Lab| -> Vec<Option<f64>> {
            exp.params().iter().map(|s| exp.param(s.key)).collect()
        };
        let from_past = self.at < self.timeline.end();
        let before = values(self.exp.as_ref());
        let (t_s, x_before) = (self.time_s(), main_x(self.exp.as_ref()));
        // What the run leaves if the change branches or restarts it: the
        // old future from the past, else the run so far (its plots) once
        // it lasted half a second.
        let left = if let Some(abandoned) = self.record_end.take() {
            Some(KeptRun::of(abandoned.as_ref(), String::new()))
        } else if self.at - self.timeline.first() >= KEEP_MIN_STEPS && !self.exp.plots().is_empty()
        {
            Some(KeptRun::plots_of(self.exp.as_ref(), String::new()))
        } else {
            None
        };
        self.timeline.input_at(self.at);
        self.last_input = self.at;
        if let Some(p) = self.held.take() {
            self.exp.input(Input::PointerUp(p));
        }
        let done = change(self.exp.as_mut());
        self.timeline.commit(self.exp.as_ref());
        let restarted = timeline::restarted(x_before, main_x(self.exp.as_ref()));
        if let Some(mut left) = left.filter(|_| restarted || from_past) {
            let (specs, after) = (self.exp.params(), values(self.exp.as_ref()));
            left.label = if restarted {
                timeline::restart_label(specs, &before, &after, cause)
            } else {
                timeline::branch_label(specs, &before, &after, cause, t_s)
            };
            timeline::keep(&mut self.kept, left);
        }
        if restarted {
            // A new run: the clock and the timeline count from its start.
            self.timeline = Timeline::new(self.exp.as_ref(), 0);
            self.at = 0;
            self.last_input = 0;
        }
        if (restarted || from_past) && std::mem::take(&mut self.timeline_paused) {
            self.playing = true;
        }
        done
    }

    /// The plots as the page draws them: the run's, whole (its last
    /// state's, while the slider shows a past moment of it), with the runs
    /// kept by changes in the past.
    pub fn plots(&self) -> Vec<Plot> {
        let run = self.record_end.as_deref().unwrap_or(&*self.exp);
        timeline::with_kept(run.plots(), &self.kept, 0)
    }

    /// Where the cursor of the plot titled `title` is (plot x): the moment
    /// shown while the slider is in the past; `None` when the page shows
    /// the run's end.
    pub fn cursor(&self, title: &str) -> Option<f64> {
        self.record_end.as_ref()?;
        let plot = self.exp.plots().iter().find(|p| p.title == title)?;
        timeline::plot_x(plot)
    }

    /// One frame of the playing clock: the run steps, unless it has ended
    /// or nothing moves (the page idles then); in the past, the record
    /// plays on.
    fn frame(&mut self) {
        if self.at < self.timeline.end() {
            self.seek(self.at + 1);
            return;
        }
        if self.exp.status().phase == Phase::Ended || !self.exp.animating() {
            return;
        }
        self.step_live();
    }

    fn step_live(&mut self) {
        self.timeline.commit(self.exp.as_ref());
        self.exp.step(Clock::DT_S);
        self.timeline.stepped(self.exp.as_ref());
        self.at += 1;
    }

    /// Goes to step `to` of the record (the slider, Back): in the past the
    /// run's last state is kept aside, and the moment shown has its pinned
    /// runs, as on the page.
    fn seek(&mut self, to: u64) {
        let (at, lab) = self
            .timeline
            .state_at(to, &mut |lab: &mut dyn Lab| lab.step(Clock::DT_S));
        let shown = std::mem::replace(&mut self.exp, lab);
        if self.record_end.is_none() {
            self.record_end = Some(shown);
        }
        if at == self.timeline.end() {
            self.record_end = None;
        }
        if let Some(end) = &self.record_end {
            self.exp.take_comparisons(end.as_any());
        }
        self.at = at;
    }

    /// Lets the playing clock run for `seconds` of simulated time.
    pub fn wait_s(&mut self, seconds: f64) -> Result<(), String> {
        if !self.playing {
            return Err("the time bar is paused: waiting changes nothing".into());
        }
        for _ in 0..(seconds / Clock::DT_S).round() as u64 {
            self.frame();
        }
        Ok(())
    }

    /// Lets the clock run until nothing moves or the run has ended.
    pub fn wait_for_rest(&mut self) -> Result<(), String> {
        if !self.playing {
            return Err("the time bar is paused: waiting changes nothing".into());
        }
        for _ in 0..RUN_TO_END_MAX_STEPS {
            if self.at >= self.timeline.end()
                && (self.exp.status().phase == Phase::Ended || !self.exp.animating())
            {
                return Ok(());
            }
            self.frame();
        }
        Err(format!(
            "still moving after {} s",
            RUN_TO_END_MAX_STEPS as f64 * Clock::DT_S
        ))
    }

    /// Lets the clock run until the status badge, or the readout labelled
    /// `readout`, shows `text`.
    pub fn wait_for_text(&mut self, text: &str, readout: Option<&str>) -> Result<(), String> {
        let shows = |page: &Page| match readout {
            None => Ok(page.exp.status().text.contains(text)),
            Some(label) => page.readout(label).map(|r| r.contains(text)),
        };
        for _ in 0..RUN_TO_END_MAX_STEPS {
            if shows(self)? {
                return Ok(());
            }
            if !self.playing {
                return Err("the time bar is paused".into());
            }
            let before = self.at;
            self.frame();
            if self.at == before && !shows(self)? {
                return Err(format!(
                    "the run came to rest at t = {:.2} s",
                    self.time_s()
                ));
            }
        }
        Err("ten simulated minutes passed".into())
    }

    /// A button of the time bar, by its label.
    pub fn time_bar(&mut self, label: &str) -> Result<bool, String> {
        match label {
            "Pause" => {
                self.playing = false;
                self.timeline_paused = false;
            }
            // Play on an ended run is Replay: the run starts again.
            "Play" if self.exp.status().phase == Phase::Ended && self.at >= self.timeline.end() => {
                self.time_bar("Reset")?;
                self.playing = true;
            }
            "Play" => {
                self.playing = true;
                self.timeline_paused = false;
            }
            "Step" => {
                self.playing = false;
                self.timeline_paused = false;
                for _ in 0..Clock::fixed_steps_in(self.exp.natural_step_s()) {
                    if self.at < self.timeline.end() {
                        self.seek(self.at + 1);
                    } else {
                        self.step_live();
                    }
                }
            }
            "Back" => {
                self.playing = false;
                self.timeline_paused = false;
                let n = u64::from(Clock::fixed_steps_in(self.exp.natural_step_s()));
                self.seek(self.at.saturating_sub(n));
            }
            "Run to end" => {
                self.playing = false;
                self.timeline_paused = true;
                if self.at < self.timeline.end() {
                    self.seek(self.timeline.end());
                }
                for _ in 0..RUN_TO_END_MAX_STEPS {
                    if self.exp.status().phase == Phase::Ended || !self.exp.animating() {
                        break;
                    }
                    self.step_live();
                }
            }
            "Reset" => {
                // The moment shown starts again (with the pins it shows).
                self.record_end = None;
                self.exp.reset();
                self.timeline = Timeline::new(self.exp.as_ref(), 0);
                self.at = 0;
                self.last_input = 0;
            }
            // The lab report's copy of the moment: nothing on the tab changes.
            "Mark" => {}
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// The timeline slider dragged to `t_s` seconds (paused there).
    pub fn scrub_to(&mut self, t_s: f64) -> Result<(), String> {
        let to = (t_s / Clock::DT_S).round() as u64;
        if to > self.timeline.end() || to < self.timeline.first() {
            return Err(format!(
                "the timeline runs from {:.2} s to {:.2} s",
                self.timeline.first() as f64 * Clock::DT_S,
                self.timeline.end() as f64 * Clock::DT_S
            ));
        }
        self.playing = false;
        self.timeline_paused = true;
        self.seek(to);
        Ok(())
    }

    /// The timeline slider dragged back along the run shown (since the
    /// student's last input) and left where `value` (of the page, as
    /// shown) is largest: its first such moment.
    pub fn scrub_to_largest(
        &mut self,
        value: impl Fn(&dyn Lab) -> Option<f64>,
    ) -> Result<(), String> {
        let (first, end) = (
            self.last_input.max(self.timeline.first()),
            self.timeline.end(),
        );
        let mut best: Option<(u64, f64)> = None;
        for step in first..=end {
            self.seek(step);
            if let Some(v) = value(self.exp.as_ref()) {
                if best.is_none_or(|(_, b)| v > b) {
                    best = Some((step, v));
                }
            }
        }
        let (step, _) = best.ok_or("the value shows no number on the timeline")?;
        self.playing = false;
        self.timeline_paused = true;
        self.seek(step);
        Ok(())
    }

    /// The timeline slider dragged back, a step at a time, until the status
    /// shows `text`.
    pub fn scrub_back_until(&mut self, text: &str) -> Result<(), String> {
        self.playing = false;
        self.timeline_paused = true;
        while !self.exp.status().text.contains(text) {
            if self.at <= self.timeline.first() {
                return Err(format!(
                    "the start of the timeline, and the status never showed “{text}”"
                ));
            }
            self.seek(self.at - 1);
        }
        Ok(())
    }

    /// Sets the control labelled `label` to `value`: a number (display
    /// units) for a slider or number field, an option's or a switch
    /// state's label for a choice or a toggle.
    pub fn set(&mut self, label: &str, value: &Value) -> Result<(), String> {
        let spec = *self
            .exp
            .params()
            .iter()
            .find(|s| s.label == label)
            .ok_or_else(|| {
                let labels: Vec<&str> = self.exp.params().iter().map(|s| s.label).collect();
                format!(
                    "no control labelled “{label}” (the controls: {})",
                    labels.join(", ")
                )
            })?;
        let number = match (spec.kind, value) {
            (_, Value::Number(n)) => *n,
            (ParamKind::Toggle { off, on }, Value::Text(t)) => {
                if t == on {
                    1.0
                } else if t == off {
                    0.0
                } else {
                    return Err(format!("“{label}” switches between “{off}” and “{on}”"));
                }
            }
            (ParamKind::Choice(options), Value::Text(t)) => options
                .iter()
                .position(|o| o == t)
                .ok_or_else(|| format!("“{label}” offers {}", options.join(", ")))?
                as f64,
            (_, Value::Text(t)) => return Err(format!("“{label}” takes a number, not “{t}”")),
        };
        if number < spec.min || number > spec.max {
            return Err(format!(
                "“{label}” goes from {} to {}, not {number}",
                spec.min, spec.max
            ));
        }
        self.input(|exp| {
            exp.set_param(spec.key, number)
                .map(|_| ())
                .map_err(|e| format!("“{label}” = {number}: {e}"))
        })
    }

    /// Presses the button labelled `label`: an experiment's action or one of
    /// the time bar's.
    pub fn press(&mut self, label: &str) -> Result<(), String> {
        if let Some(action) = self.exp.actions().iter().find(|a| a.label == label) {
            let key = action.key;
            if !self.exp.action_shown(key) {
                return Err(format!(
                    "the button “{label}” is hidden now: it has nothing to act on"
                ));
            }
            return self.input_because(Some(label), |exp| {
                exp.action(key).map_err(|e| e.to_string())
            });
        }
        if self.time_bar(label)? {
            return Ok(());
        }
        let labels: Vec<&str> = self.exp.actions().iter().map(|a| a.label).collect();
        Err(format!(
            "no button labelled “{label}” (the experiment's: {}; the time bar's: Pause, Play, Step, Back, Run to end, Reset, Mark)",
            labels.join(", ")
        ))
    }

    /// A click or tap at a world point, with a key held.
    pub fn click(&mut self, p: DVec2, modifiers: Modifiers) -> Result<(), String> {
        self.input(|exp| {
            exp.input_with(Input::PointerDown(p), modifiers);
            exp.input_with(Input::PointerUp(p), modifiers);
            Ok(())
        })
    }

    /// A press at `from`, a drag through `path`, a release at its end
    /// (with `hold`, at the student's next input).
    pub fn drag(&mut self, from: DVec2, path: &[DVec2], hold: bool) -> Result<(), String> {
        let end = path.last().copied().unwrap_or(from);
        self.input(|exp| {
            exp.input(Input::PointerDown(from));
            let mut last = from;
            for &pos in path {
                // The pointer moves in small steps, as a hand does.
                let n = ((pos - last).length() / 0.05).ceil().max(1.0) as usize;
                for k in 1..=n {
                    let p = last + (pos - last) * (k as f64 / n as f64);
                    exp.input(Input::PointerMove {
                        pos: p,
                        pressed: true,
                    });
                }
                last = pos;
            }
            if !hold {
                exp.input(Input::PointerUp(last));
            }
            Ok(())
        })?;
        if hold {
            self.held = Some(end);
        }
        Ok(())
    }

    /// An arrow key pressed on the canvas (`ArrowLeft`…`ArrowDown`), with
    /// Shift for a fine step: the page nudges the dragged point by 2 % of the
    /// view's width, 0.2 % with Shift (`labweb/src/sim/canvas_input.rs`).
    pub fn arrow_key(&mut self, key: &str, shift: bool) -> Result<(), String> {
        let dir = match key {
            "ArrowLeft" => DVec2::NEG_X,
            "ArrowRight" => DVec2::X,
            "ArrowUp" => DVec2::Y,
            "ArrowDown" => DVec2::NEG_Y,
            other => return Err(format!("no arrow key “{other}”")),
        };
        let view = self.exp.view();
        let fraction = if shift { 0.002 } else { 0.02 };
        let delta = dir * (view.max.x - view.min.x) * fraction;
        self.input(|exp| {
            exp.input(Input::Nudge(delta));
            Ok(())
        })
    }

    /// Where the handle labelled `label` is now.
    pub fn handle(&self, label: &str) -> Result<(String, DVec2), String> {
        let handles = self.exp.handles();
        handles
            .iter()
            .find(|h| h.label == label)
            .map(|h| (h.id.clone(), h.at))
            .ok_or_else(|| {
                let labels: Vec<&str> = handles.iter().map(|h| h.label.as_str()).collect();
                format!("no handle “{label}” (the handles: {})", labels.join(", "))
            })
    }

    /// The handle labelled `label` moved to `to` with the Move form (typed
    /// coordinates).
    pub fn move_handle(&mut self, label: &str, to: DVec2) -> Result<(), String> {
        let (id, _) = self.handle(label)?;
        self.input(|exp| {
            if exp.move_handle(&id, to) {
                Ok(())
            } else {
                Err(format!("“{label}” cannot go to {to}"))
            }
        })
    }

    /// The page reopened from its own link, as a classmate would open it.
    pub fn reopen_link(&mut self) -> Result<(), String> {
        let link = labcore::route::format(self.exp.as_ref(), labcore::route::Tab::Simulation);
        let mut fresh = testkit::open(self.exp.id());
        let notices = testkit::apply_link(fresh.as_mut(), &link);
        if !notices.is_empty() {
            return Err(format!("{link} gave the notices {notices:?}"));
        }
        // A paused page's link names its moment (`run=0&at=`, the run's own
        // time): it reopens there, paused, as the page does; a playing
        // page's link opens the run from its start, playing.
        let (moment, playing) = (self.at, self.playing);
        self.exp = fresh;
        self.timeline = Timeline::new(self.exp.as_ref(), 0);
        self.at = 0;
        self.last_input = 0;
        self.kept.clear();
        self.timeline_paused = false;
        self.record_end = None;
        self.playing = true;
        if !playing {
            for _ in 0..moment {
                self.step_live();
            }
            self.playing = false;
        }
        Ok(())
    }

    /// The text of the readout labelled `label`, as displayed, or else the
    /// value of the control labelled so, as its number box shows it (an
    /// option's or a switch state's label for a choice or a toggle).
    pub fn readout(&self, label: &str) -> Result<String, String> {
        let readouts = self.exp.readouts();
        if let Some(r) = readouts.iter().find(|r| r.label == label) {
            return Ok(r.value.clone());
        }
        if let Some(spec) = self.exp.params().iter().find(|s| s.label == label) {
            let value = self.exp.param(spec.key);
            return Ok(match (spec.kind, value) {
                (_, None) => String::new(),
                (ParamKind::Toggle { off, on }, Some(v)) => {
                    (if v > 0.5 { on } else { off }).to_owned()
                }
                (ParamKind::Choice(options), Some(v)) => options[v as usize].to_owned(),
                // As the control's number box writes it (labweb's
                // `set_control_value`): a digit more than the step's, at
                // most 3 (an LQR gain of 49.5104 shows 49.51 on a 0.1 step).
                (_, Some(v)) => {
                    let step_digits = (0..4)
                        .find(|&d| (spec.step * 10f64.powi(d)).fract().abs() < 1e-9)
                        .unwrap_or(4) as usize;
                    let number = labcore::units::format_number(v, (step_digits + 1).min(3));
                    format!("{number} {}", spec.unit).trim_end().to_owned()
                }
            });
        }
        let labels: Vec<&str> = readouts.iter().map(|r| r.label).collect();
        Err(format!(
            "no readout or control “{label}” (the readouts: {})",
            labels.join(", ")
        ))
    }
}

/// A control's value as a step writes it.
#[derive(Clone, Debug)]
pub enum Value {
    Number(f64),
    Text(String),
}
