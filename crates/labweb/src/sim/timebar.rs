//! The shell's time bar: play/pause (or Replay once a run has ended), one
//! step, playback speed, reset and the simulated time.

use super::SimState;
use crate::dom::query;
use labcore::clock::{Clock, SPEEDS};
use wasm_bindgen::JsCast;
use web_sys::HtmlSelectElement;

/// Time-control icons (inline SVG: no icon font, no emoji fallback boxes).
const ICON_PAUSE: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M3 2h3.5v12H3zM9.5 2H13v12H9.5z\"/></svg>";
const ICON_PLAY: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M3 1.5v13l11-6.5z\"/></svg>";
const ICON_STEP: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M2 2v12l8-6zM11 2h3v12h-3z\"/></svg>";
const ICON_RESET: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"none\" stroke=\"currentColor\" stroke-width=\"2\" d=\"M3.5 6A5 5 0 1 1 3 9.5\"/><path fill=\"currentColor\" d=\"M1 2.5l5 .5-3 4z\"/></svg>";

/// The shell's time controls: the same widget, place and keys in every
/// animated experiment.
pub(super) fn timebar_html() -> String {
    let speeds: String = SPEEDS
        .iter()
        .map(|v| {
            let sel = if *v == 1.0 { " selected" } else { "" };
            format!("<option value=\"{v}\"{sel}>{}×</option>", speed_label(*v))
        })
        .collect();
    format!(
        "<div class=\"timebar\" role=\"group\" aria-label=\"Time controls\">\
         <button type=\"button\" class=\"tb-play\" data-time=\"play\" aria-pressed=\"true\" aria-keyshortcuts=\"Space\">\
         <span class=\"tb-icon\">{ICON_PAUSE}</span> <span class=\"tb-label\">Pause</span></button>\
         <button type=\"button\" data-time=\"step\" aria-keyshortcuts=\".\" title=\"One step (key .)\">{ICON_STEP} Step</button>\
         <label class=\"tb-speed\">Playback <select data-time=\"speed\">{speeds}</select></label>\
         <button type=\"button\" data-time=\"reset\">{ICON_RESET} Reset</button>\
         <output class=\"tb-time\" aria-label=\"Simulated time\">t = 0.00 s</output></div>"
    )
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
impl SimState {
    /// One fixed step from a pause (the Step button and the `.` key).
    pub(super) fn single_step(&mut self) {
        let was_animating = self.exp.animating();
        for _ in 0..self.clock.single_step() {
            self.exp.step(Clock::DT_S);
        }
        self.needs_paint = true;
        self.hash_dirty = true;
        self.plots_force = true;
        self.sync_timebar();
        if was_animating && !self.exp.animating() {
            self.announce();
        }
    }

    pub(super) fn set_running(&mut self, running: bool) {
        self.clock.set_running(running);
        self.last_time_ms = None;
        self.hash_dirty = true;
        // The button says so at once, not at the next frame.
        self.sync_timebar();
    }

    pub(super) fn reset_run(&mut self) {
        self.exp.reset();
        self.clock.reset();
        self.needs_paint = true;
        self.hash_dirty = true;
        self.plots_force = true;
    }

    /// Brings the play button, the speed and the time read-out up to date.
    pub(super) fn sync_timebar(&mut self) {
        let now = (self.clock.running(), self.clock.speed(), self.clock.steps());
        if now == self.shown_time {
            return;
        }
        let _ = self.canvas.set_attribute("data-steps", &now.2.to_string());
        if let Some(bar) = query(&self.panel, ".timebar") {
            if now.0 != self.shown_time.0 {
                if let Some(play) = query(&bar, ".tb-play") {
                    let _ =
                        play.set_attribute("aria-pressed", if now.0 { "true" } else { "false" });
                    if let Some(icon) = query(&play, ".tb-icon") {
                        icon.set_inner_html(if now.0 { ICON_PAUSE } else { ICON_PLAY });
                    }
                    if let Some(label) = query(&play, ".tb-label") {
                        label.set_text_content(Some(if now.0 { "Pause" } else { "Play" }));
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
            if let Some(out) = query(&bar, ".tb-time") {
                out.set_text_content(Some(&format!("t = {:.2} s", self.clock.time_s())));
            }
        }
        self.shown_time = now;
    }
}
