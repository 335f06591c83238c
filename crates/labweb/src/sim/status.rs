//! Status and notices: the badge shows the run's state ([`labcore::Status`]),
//! a transient notice line under it shows [`labcore::Notice`]s and the shell's
//! own messages, and a live region tells screen-reader users what changed.

use super::SimState;
use crate::dom::{self, escape, query};
use labcore::{Notice, Phase, Status};

/// How long a notice stays up when nothing else hides it, milliseconds.
pub(super) const NOTICE_MS: f64 = 6000.0;

/// The strip under the canvas: the status badge (the run's state) and the
/// notice line beside it. Outside the canvas, so it never covers a handle.
pub(super) fn statusbar_html(status: &Status) -> String {
    format!(
        "<div class=\"sim-statusbar\">\
         <p class=\"sim-status\" data-tone=\"{tone}\" data-phase=\"{phase}\">{text}</p>\
         <p class=\"sim-notice\" aria-live=\"polite\" data-tone=\"neutral\" hidden></p></div>",
        tone = tone_name(status.tone),
        phase = phase_name(status.phase),
        text = escape(&status.text),
    )
}

pub(super) fn phase_name(phase: Phase) -> &'static str {
    match phase {
        Phase::Live => "live",
        Phase::Ended => "ended",
    }
}

/// Which notice is up and which the student has seen off: a pure state
/// machine, so its rules are tested without a browser.
///
/// A notice shows when its serial is new; it goes after [`NOTICE_MS`], or
/// at the student's next input, action or parameter change
/// ([`NoticeShelf::student_acted`]) unless that input posted a newer one.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct NoticeShelf {
    /// The notice on screen and when it went up (ms).
    shown: Option<(Notice, f64)>,
    /// Every serial up to this one has been seen off.
    dismissed: u64,
}

impl NoticeShelf {
    /// Call before handling an input: whatever is posted now is old news.
    pub(super) fn student_acted(&mut self, current: Option<&Notice>) {
        if let Some(n) = current {
            self.dismissed = self.dismissed.max(n.serial);
        }
    }

    /// The notice to show now, given the experiment's current notice.
    pub(super) fn update(&mut self, current: Option<Notice>, now_ms: f64) -> Option<&Notice> {
        let current = current.filter(|n| n.serial > self.dismissed);
        match current {
            None => self.shown = None,
            Some(n) => {
                let fresh = self
                    .shown
                    .as_ref()
                    .is_none_or(|(s, _)| s.serial != n.serial);
                if fresh {
                    self.shown = Some((n, now_ms));
                } else if let Some((s, since)) = &self.shown {
                    if now_ms - since >= NOTICE_MS {
                        self.dismissed = self.dismissed.max(s.serial);
                        self.shown = None;
                    }
                }
            }
        }
        self.shown.as_ref().map(|(n, _)| n)
    }
}

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
        let mut status = self.exp.status();
        if self.touch_input {
            status.text = labcore::experiment::for_touch(&status.text);
        }
        if Some(&status) != self.shown_status.as_ref() {
            if let Some(badge) = query(&self.panel, ".sim-status") {
                // A scrub changes the text at each jump; the tone and phase,
                // which the style sheet selects on, seldom: an attribute
                // written re-styles the badge even with the same value.
                let was = self.shown_status.as_ref();
                dom::set_text(&badge, &status.text);
                if was.map(|s| s.tone) != Some(status.tone) {
                    let _ = badge.set_attribute("data-tone", tone_name(status.tone));
                }
                if was.map(|s| s.phase) != Some(status.phase) {
                    let _ = badge.set_attribute("data-phase", phase_name(status.phase));
                }
            }
            self.shown_status = Some(status);
        }
    }

    /// The badge during a stream of input (a drag, a held arrow key): a new
    /// tone shows at once ("in reach" turning "out of reach: target 1.71 m
    /// away"); the rest follows at the text's pace, like the readouts. Under
    /// a held key each press starts and ends a motion, and the badge would
    /// flicker between live and ended.
    pub(super) fn sync_status_during_stream(&mut self) {
        let tone = self.exp.status().tone;
        if self.shown_status.as_ref().is_some_and(|s| s.tone == tone) {
            return;
        }
        self.sync_status();
    }

    /// The caption: the touch hint while the last pointer was a finger.
    pub(super) fn sync_hint(&mut self) {
        let hint = if self.touch_input {
            self.exp.touch_hint()
        } else {
            self.exp.hint()
        };
        if Some((hint, self.touch_input)) != self.shown_hint {
            if let Some(caption) = query(&self.panel, ".sim-caption") {
                caption.set_text_content(Some(hint));
                let _ = caption.set_attribute(
                    "data-input",
                    if self.touch_input { "touch" } else { "mouse" },
                );
                // Texts for keys or for a finger (the Move form's help):
                // the style sheet shows the ones for the input in use.
                let _ = self.panel.set_attribute(
                    "data-input",
                    if self.touch_input { "touch" } else { "mouse" },
                );
            }
            self.shown_hint = Some((hint, self.touch_input));
        }
    }

    /// Shows, keeps or hides the notice line (every frame: notices expire).
    pub(super) fn sync_notice(&mut self, now_ms: f64) {
        let current = self.exp.notice();
        let shown = self.notices.update(current, now_ms).cloned();
        let serial = shown.as_ref().map(|n| n.serial);
        if serial == self.shown_notice {
            return;
        }
        self.shown_notice = serial;
        if let Some(line) = query(&self.panel, ".sim-notice") {
            match shown {
                Some(n) => {
                    let text = if self.touch_input {
                        labcore::experiment::for_touch(&n.text)
                    } else {
                        n.text.clone()
                    };
                    line.set_text_content(Some(&text));
                    let _ = line.set_attribute("data-tone", tone_name(n.tone));
                    let _ = line.set_attribute("data-serial", &n.serial.to_string());
                    dom::set_hidden(&line, false);
                }
                None => {
                    line.set_text_content(None);
                    dom::set_hidden(&line, true);
                }
            }
        }
    }

    /// The student did something (pressed on the canvas, a key, a button, a
    /// control): the notice up now goes, unless the input posts a new one.
    pub(super) fn student_acted(&mut self) {
        let current = self.exp.notice();
        self.notices.student_acted(current.as_ref());
    }

    /// After a pointer release or a keyboard nudge: repaint, put the new state
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

#[cfg(test)]
mod tests {
    use super::*;
    use labcore::Tone;

    fn notice(serial: u64) -> Notice {
        Notice {
            serial,
            text: format!("notice {serial}"),
            tone: Tone::Warning,
        }
    }

    #[test]
    fn a_notice_shows_then_expires_after_its_time() {
        let mut shelf = NoticeShelf::default();
        assert_eq!(
            shelf.update(Some(notice(1)), 0.0).map(|n| n.serial),
            Some(1)
        );
        assert!(shelf.update(Some(notice(1)), NOTICE_MS - 1.0).is_some());
        assert!(shelf.update(Some(notice(1)), NOTICE_MS).is_none());
        // Still posted by the experiment, but seen off: it stays hidden.
        assert!(shelf.update(Some(notice(1)), NOTICE_MS * 3.0).is_none());
    }

    #[test]
    fn the_next_input_hides_a_notice_unless_it_posts_a_new_one() {
        let mut shelf = NoticeShelf::default();
        assert!(shelf.update(Some(notice(4)), 0.0).is_some());
        // An input that posts nothing: the old notice goes at once.
        shelf.student_acted(Some(&notice(4)));
        assert!(shelf.update(Some(notice(4)), 10.0).is_none());
        // An input that posts a new notice: the new one shows, with its own time.
        shelf.student_acted(Some(&notice(4)));
        assert_eq!(
            shelf.update(Some(notice(5)), 20.0).map(|n| n.serial),
            Some(5)
        );
        assert!(shelf
            .update(Some(notice(5)), 20.0 + NOTICE_MS - 1.0)
            .is_some());
    }

    #[test]
    fn a_withdrawn_notice_disappears() {
        let mut shelf = NoticeShelf::default();
        assert!(shelf.update(Some(notice(2)), 0.0).is_some());
        assert!(shelf.update(None, 5.0).is_none());
    }

    #[test]
    fn the_badge_carries_the_phase_and_no_notice_text() {
        let html = statusbar_html(&Status::ended("reached the goal", Tone::Good));
        assert!(html.contains("data-phase=\"ended\""));
        assert!(html.contains(">reached the goal</p>"));
        assert!(html.contains("class=\"sim-notice\" aria-live=\"polite\""));
    }
}
