//! Status and notices: the badge shows the run's state ([`labcore::Status`]),
//! a transient notice line under it shows [`labcore::Notice`]s and the shell's
//! own messages, and a live region tells screen-reader users what changed.

use super::SimState;
use crate::dom::{self, query};

pub(super) fn tone_name(tone: labcore::Tone) -> &'static str {
    match tone {
        labcore::Tone::Neutral => "neutral",
        labcore::Tone::Good => "good",
        labcore::Tone::Warning => "warning",
        labcore::Tone::Bad => "bad",
    }
}
impl SimState {
    /// Brings the status badge up to date with the run's state.
    pub(super) fn sync_status(&mut self) {
        let status = self.exp.status();
        if status.text != self.shown_status {
            if let Some(badge) = query(&self.panel, ".sim-status") {
                badge.set_text_content(Some(&status.text));
                let _ = badge.set_attribute("data-tone", tone_name(status.tone));
            }
            self.shown_status = status.text;
        }
    }

    /// in the link, and announce it (once any motion has settled).
    pub(super) fn interaction_ended(&mut self) {
        self.needs_paint = true;
        self.hash_dirty = true;
        self.announce_when_settled();
    }

    /// Tells screen-reader users the new readouts after an interaction ends;
    /// while the simulation is still moving, waits until it stops (the frame
    /// loop announces then).
    pub(super) fn announce_when_settled(&self) {
        if !self.exp.animating() {
            self.announce();
        }
    }

    /// Tells screen-reader users the current status and readouts.
    pub(super) fn announce(&self) {
        let text: Vec<String> = self
            .exp
            .readouts()
            .iter()
            .map(|r| format!("{}: {}", r.label, r.value))
            .collect();
        if let Some(live) = query(&self.panel, ".sim-live") {
            live.set_text_content(Some(&format!(
                "{}. {}",
                self.exp.status().text,
                text.join(", ")
            )));
        }
    }

    pub(super) fn show_message(&self, text: Option<&str>) {
        if let Some(m) = query(&self.panel, ".sim-message") {
            m.set_text_content(text);
            dom::set_hidden(&m, text.is_none());
        }
    }
}
