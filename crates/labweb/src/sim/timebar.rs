//! The shell's time bar: play/pause (or Replay once a run has ended), one
//! step, playback speed, reset and the simulated time.

use super::SimState;
use crate::dom::{self, query};
use labcore::clock::{Clock, SPEEDS};
use labcore::Phase;
use wasm_bindgen::JsCast;
use web_sys::HtmlSelectElement;

/// Time-control icons (inline SVG: no icon font, no emoji fallback boxes).
const ICON_PAUSE: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M3 2h3.5v12H3zM9.5 2H13v12H9.5z\"/></svg>";
const ICON_PLAY: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M3 1.5v13l11-6.5z\"/></svg>";
const ICON_STEP: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M2 2v12l8-6zM11 2h3v12h-3z\"/></svg>";
const ICON_REPLAY: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"none\" stroke=\"currentColor\" stroke-width=\"2\" d=\"M12.5 6A5 5 0 1 0 13 9.5\"/><path fill=\"currentColor\" d=\"M15 2.5l-5 .5 3 4zM6 5.5v5l4-2.5z\"/></svg>";
const ICON_RESET: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"none\" stroke=\"currentColor\" stroke-width=\"2\" d=\"M3.5 6A5 5 0 1 1 3 9.5\"/><path fill=\"currentColor\" d=\"M1 2.5l5 .5-3 4z\"/></svg>";

/// The shell's time controls: the same widget, place and keys in every
/// animated experiment.
///
/// `step_s` is the model's own step ([`labcore::Experiment::natural_step_s`]):
/// the Step button says what one press takes.
pub(super) fn timebar_html(step_s: f64) -> String {
    let speeds: String = SPEEDS
        .iter()
        .map(|v| {
            let sel = if *v == 1.0 { " selected" } else { "" };
            format!("<option value=\"{v}\"{sel}>{}×</option>", speed_label(*v))
        })
        .collect();
    format!(
        "<div class=\"timebar\" role=\"group\" aria-label=\"Time controls\">\
         <button type=\"button\" class=\"tb-play\" data-time=\"play\" data-offer=\"pause\" aria-pressed=\"true\" aria-keyshortcuts=\"Space\">\
         <span class=\"tb-icon\">{ICON_PAUSE}</span> <span class=\"tb-label\">Pause</span></button>\
         <button type=\"button\" data-time=\"step\" aria-keyshortcuts=\".\" title=\"One step: {step} s (key .)\">{ICON_STEP} <span class=\"tb-text\">Step</span></button>\
         {back_end}{mark}\
         <label class=\"tb-speed\"><span class=\"tb-speed-text\">Playback</span> <select data-time=\"speed\">{speeds}</select></label>\
         <button type=\"button\" data-time=\"reset\">{ICON_RESET} <span class=\"tb-text\">Reset</span></button>\
         <output class=\"tb-time\" aria-label=\"Simulated time\">t = 0.00 s</output>{marks}{slider}</div>",
        step = step_text(step_s),
        back_end = super::scrub::BUTTONS_HTML,
        mark = super::marks::BUTTON_HTML,
        marks = super::marks::LIST_HTML,
        slider = super::scrub::SLIDER_HTML,
    )
}

/// A step's length as the Step button's title says it: `0.05`, `0.017`.
fn step_text(step_s: f64) -> String {
    let text = format!("{step_s:.3}");
    text.trim_end_matches('0').trim_end_matches('.').to_owned()
}

/// What the shell's time controls make of a live or ended run, shown on the
/// status badge and the time bar (`data-clock`): the model's status says
/// what the run is; this says whether simulated time goes on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ClockState {
    /// Playing, and the model moves: t goes on.
    Running,
    /// The student paused a live run: the badge starts "paused ·".
    Paused,
    /// Playing, but nothing moves (a balanced pole at rest, an arm at its
    /// target): t holds until something moves again; the time bar says so.
    Held,
    /// The run is over (the badge adds "· ended"; the time bar offers Replay).
    Ended,
}

impl ClockState {
    /// The pure rule: `animated` (the experiment has time controls),
    /// `running` (the clock plays), `ended` (the model's phase),
    /// `animating` (the model still moves).
    pub(super) fn of(animated: bool, running: bool, ended: bool, animating: bool) -> Self {
        if ended {
            Self::Ended
        } else if animated && !running {
            Self::Paused
        } else if animated && !animating {
            Self::Held
        } else {
            Self::Running
        }
    }

    pub(super) fn name(self) -> &'static str {
        match self {
            Self::Running => "running",
            Self::Paused => "paused",
            Self::Held => "held",
            Self::Ended => "ended",
        }
    }
}

fn speed_label(v: f64) -> &'static str {
    if v == 0.25 {
        "¼"
    } else if v == 0.5 {
        "½"
    } else if v == 2.0 {
        "2"
    } else if v == 4.0 {
        "4"
    } else {
        "1"
    }
}
/// What the play button offers: (label, icon, aria-pressed), for `running`
/// (the clock plays and something moves: not held) and `ended`. A run that
/// has ended offers Replay (reset, then play), never Pause; one that waits
/// for something to move offers Play, as its time bar says it is held.
pub(super) fn play_button(running: bool, ended: bool) -> (&'static str, &'static str, bool) {
    if ended {
        ("Replay", ICON_REPLAY, false)
    } else if running {
        ("Pause", ICON_PAUSE, true)
    } else {
        ("Play", ICON_PLAY, false)
    }
}

/// What the clock does when the run's phase is `ended` (a pure rule, tested
/// below): `Some(false)` stops it (the run just ended while playing),
/// `Some(true)` resumes it (a run the end had stopped is live again, e.g.
/// after a new goal or a reset), `None` leaves it. `hold` is whether the end
/// stopped the clock; the new `hold` is returned with the action.
pub(super) fn clock_rule(running: bool, hold: bool, ended: bool) -> (Option<bool>, bool) {
    match (ended, running, hold) {
        (true, true, _) => (Some(false), true),
        (false, false, true) => (Some(true), false),
        (false, true, _) => (None, false),
        _ => (None, hold),
    }
}

impl SimState {
    /// Reads the run's phase after stepping: an ended run stops the clock
    /// (t stops too), a live one the end had stopped plays again.
    pub(super) fn follow_phase(&mut self) {
        self.phase = self.exp.status().phase;
        let (action, hold) = clock_rule(
            self.clock.running(),
            self.ended_hold,
            self.phase == Phase::Ended,
        );
        self.ended_hold = hold;
        if let Some(run) = action {
            self.clock.set_running(run);
            self.last_time_ms = None;
            self.hash_dirty = true;
        }
    }

    /// The play button (and Space): Pause/Play, or Replay once the run ended.
    pub(super) fn play_pressed(&mut self) {
        self.run_to_end = None;
        self.phase = self.exp.status().phase;
        if self.phase == Phase::Ended {
            self.reset_run();
            self.phase = self.exp.status().phase;
            self.ended_hold = false;
            self.set_running(true);
        } else if self.clock_state() == ClockState::Held {
            // Play is on already: time starts when something moves.
            self.say("Nothing moves yet: time starts when something does.");
        } else {
            let running = !self.clock.running();
            self.ended_hold = false;
            self.set_running(running);
        }
    }

    fn clock_state(&self) -> ClockState {
        ClockState::of(
            self.exp.animated(),
            self.clock.running(),
            self.phase == Phase::Ended,
            self.exp.animating(),
        )
    }

    /// One model step from a pause (the Step button and the `.` key): the
    /// fixed steps that make the model's own step (one filter cycle of the
    /// EKF), fewer if the run ends on the way.
    pub(super) fn single_step(&mut self) {
        let was_animating = self.exp.animating();
        let steps = Clock::fixed_steps_in(self.exp.natural_step_s());
        self.run_to_end = None;
        self.timeline_paused = false;
        if self.in_past() {
            // Along the record, as it went.
            self.clock.set_running(false);
            self.forward_in_past(self.clock.steps(), u64::from(steps));
        } else {
            self.timeline_commit();
            let clock = &mut self.clock;
            let timeline = &mut self.timeline;
            let _ = labcore::route::keep_locked(self.exp.as_mut(), &self.instructor, |exp| {
                clock.single_step(steps, || {
                    exp.step(Clock::DT_S);
                    if let Some(tl) = timeline.as_mut() {
                        tl.stepped(exp);
                    }
                    exp.status().phase != Phase::Ended
                });
            });
        }
        self.phase = self.exp.status().phase;
        self.needs_paint = true;
        self.hash_dirty = true;
        self.plots_force = true;
        self.sync_timebar(true);
        if was_animating && !self.exp.animating() {
            self.announce();
        }
    }

    pub(super) fn set_running(&mut self, running: bool) {
        self.timeline_paused = false;
        self.clock.set_running(running);
        self.last_time_ms = None;
        self.hash_dirty = true;
        // The next frame shows the readouts of the moment it stopped (or
        // started), not those of up to TEXT_INTERVAL_MS before.
        self.needs_paint = true;
        // The button says so at once, not at the next frame.
        self.sync_timebar(true);
    }

    pub(super) fn reset_run(&mut self) {
        // Reset keeps the parameters, locked ones above all; it starts the
        // run again rather than branching from the moment shown.
        self.record_end = None;
        self.guarded(|exp| exp.reset());
        self.clock.reset();
        self.restart_timeline();
        self.phase = self.exp.status().phase;
        self.needs_paint = true;
        self.hash_dirty = true;
        self.plots_force = true;
    }

    /// Brings the time bar up to date: its buttons at once, the time's text
    /// only with `text` (a frame that writes the page's text).
    pub(super) fn sync_timebar(&mut self, text: bool) {
        let clock = self.clock_state();
        let now = (
            self.clock.running() && clock != ClockState::Held,
            self.clock.speed(),
            self.clock.steps(),
            self.phase == Phase::Ended,
        );
        if now != self.shown_time {
            self.sync_time_controls(now);
        }
        if Some(clock) != self.shown_clock {
            // The badge says "paused" (CSS adds it), the time bar "held".
            for el in [".sim-status", ".timebar"] {
                if let Some(el) = query(&self.panel, el) {
                    let _ = el.set_attribute("data-clock", clock.name());
                }
            }
            self.shown_clock = Some(clock);
        }
        if text {
            self.sync_scrub();
            // The time is written only when its text changes.
            let held = if clock == ClockState::Held {
                " · held"
            } else {
                ""
            };
            let text = format!("t = {:.2} s{held}", self.clock.time_s());
            if text != self.shown_time_text {
                if let Some(out) = &self.time_output {
                    dom::set_text(out, &text);
                }
                self.shown_time_text = text;
            }
        }
    }

    /// The step count (`data-steps` on the canvas, for tests), the play
    /// button and the speed, for `now` = (running, speed, steps, ended).
    fn sync_time_controls(&mut self, now: (bool, f64, u64, bool)) {
        let _ = self.canvas.set_attribute("data-steps", &now.2.to_string());
        let controls_changed =
            (now.0, now.1, now.3) != (self.shown_time.0, self.shown_time.1, self.shown_time.3);
        if let Some(bar) = controls_changed
            .then(|| query(&self.panel, ".timebar"))
            .flatten()
        {
            if (now.0, now.3) != (self.shown_time.0, self.shown_time.3) {
                if let Some(play) = query(&bar, ".tb-play") {
                    let (label, icon, pressed) = play_button(now.0, now.3);
                    let _ =
                        play.set_attribute("aria-pressed", if pressed { "true" } else { "false" });
                    let _ = play.set_attribute("data-offer", &label.to_ascii_lowercase());
                    if let Some(el) = query(&play, ".tb-icon") {
                        el.set_inner_html(icon);
                    }
                    if let Some(el) = query(&play, ".tb-label") {
                        el.set_text_content(Some(label));
                    }
                }
            }
            if now.1 != self.shown_time.1 {
                if let Some(select) = query(&bar, "select[data-time=speed]")
                    .and_then(|e| e.dyn_into::<HtmlSelectElement>().ok())
                {
                    select.set_value(&format!("{}", now.1));
                }
            }
        }
        self.shown_time = now;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_ended_run_offers_replay_never_pause() {
        assert_eq!(play_button(true, true).0, "Replay");
        assert_eq!(play_button(false, true).0, "Replay");
        assert_eq!(play_button(true, false).0, "Pause");
        assert_eq!(play_button(false, false).0, "Play");
        assert!(!play_button(true, true).2, "Replay is not a pressed toggle");
    }

    #[test]
    fn the_clock_state_joins_the_models_phase_and_the_time_controls() {
        // (animated, running, ended, animating)
        assert_eq!(ClockState::of(true, true, false, true), ClockState::Running);
        assert_eq!(ClockState::of(true, false, false, true), ClockState::Paused);
        assert_eq!(
            ClockState::of(true, false, false, false),
            ClockState::Paused
        );
        assert_eq!(ClockState::of(true, true, false, false), ClockState::Held);
        assert_eq!(ClockState::of(true, false, true, false), ClockState::Ended);
        // Without time controls nothing is paused or held.
        assert_eq!(
            ClockState::of(false, true, false, false),
            ClockState::Running
        );
        assert_eq!(step_text(0.05), "0.05");
        assert_eq!(step_text(1.0 / 60.0), "0.017");
    }

    #[test]
    fn the_clock_stops_when_the_run_ends_and_resumes_only_if_the_end_stopped_it() {
        // Playing, the run ends: stop, and remember why.
        assert_eq!(clock_rule(true, false, true), (Some(false), true));
        // Stopped by the end, still ended: nothing.
        assert_eq!(clock_rule(false, true, true), (None, true));
        // Stopped by the end, live again (new goal, reset): play on.
        assert_eq!(clock_rule(false, true, false), (Some(true), false));
        // Paused by the student: stays paused whatever the phase.
        assert_eq!(clock_rule(false, false, false), (None, false));
        assert_eq!(clock_rule(false, false, true), (None, false));
    }
}
