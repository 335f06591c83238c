//! The timeline in the time bar (issue 26 §1): a slider over the run so
//! far, Step back (`,`) and Run to end (`End`), for every experiment with
//! time controls.
//!
//! The run's record is a [`Timeline`] (labcore): every input is reported to
//! it before it changes the model ([`SimState::timeline_input`]) and every
//! step after it is taken, and going to a step swaps in the state the
//! timeline rebuilds, bit for bit the one the run had there. An input while
//! the timeline shows the past starts a new run from that moment (the old
//! future is dropped). Scrubbing pauses the run; Play from the past replays
//! the record up to its end, then the run goes on live.
//!
//! While the scene shows the past, the plots show the whole record with a
//! cursor at the moment shown; a point clicked on a plot (or chosen with
//! its arrow keys) moves the timeline there. An input in the past keeps the
//! old future as a comparison run ([`KeptRun`]) named after the change,
//! on the plots and, where the scene has a trail, as a ghost.

use super::SimState;
use crate::dom::{self, query, Listener};
use labcore::clock::Clock;
use labcore::plot::{Plot, XWindow};
use labcore::run_input::RunInput;
use labcore::timeline::{self, plot_x, KeptRun, Timeline};
use labcore::{Lab, Phase};
use std::borrow::Cow;
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::JsCast;
use web_sys::{Element, Event, HtmlInputElement, KeyboardEvent};

/// The longest a frame of Run to end may step, milliseconds: the run is
/// finished over as many frames as it takes, each well under a 50 ms task.
pub(super) const RUN_TO_END_BUDGET_MS: f64 = 30.0;

/// Run to end stops after this many steps (10 simulated minutes) if the run
/// has not ended by then: a run that never ends is not run forever.
pub(super) const RUN_TO_END_MAX_STEPS: u64 = 10 * 60 * 60;

/// How long a dragged timeline slider must rest before the plots whose
/// picture changed are repainted, milliseconds ([`SimState::scrub_moving`]).
pub(super) const SCRUB_REST_MS: f64 = 150.0;

/// How long the rehearsal of a scrub ([`SimState::rehearse_scrub`]) waits
/// for the browser to be idle, milliseconds.
pub(super) const REHEARSAL_TIMEOUT_MS: u32 = 2000;

/// Step back and Run to end (beside Step).
pub(super) const BUTTONS_HTML: &str = "<button type=\"button\" data-time=\"back\" aria-keyshortcuts=\",\" title=\"One step back (key ,)\">\
     <svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M14 2v12l-8-6zM2 2h3v12H2z\"/></svg> <span class=\"tb-text\">Back</span></button>\
     <button type=\"button\" data-time=\"end\" aria-keyshortcuts=\"End\" title=\"Finish the run at once; a run with no end goes 10 minutes on (key End)\">\
     <svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M1 2v12l6-6zM7 2v12l6-6zM13 2h2v12h-2z\"/></svg> <span class=\"tb-text\">Run to end</span></button>";

/// The timeline slider, named on its own row of the time bar: from the oldest
/// step kept to the run's last step, in fixed steps. Its keys are its own
/// ([`SimState::scrub_key`]): an arrow moves one model step, Page Up and
/// Page Down one second (a tenth of the run where the plots count
/// iterations), Home and End to its ends.
pub(super) const SLIDER_HTML: &str = "<label class=\"tb-tl\">Timeline <input type=\"range\" class=\"tb-scrub\" data-time=\"scrub\" min=\"0\" max=\"0\" value=\"0\" step=\"1\" \
     aria-valuetext=\"t = 0.00 s\" title=\"Drag to show any moment of this run\"></label>";

/// One fixed step of a replay.
fn step_once(exp: &mut dyn Lab) {
    exp.step(Clock::DT_S);
}

/// An input on its way: what the run was before it, settled once the
/// input has been applied ([`SimState::finish_branch`]): a change that
/// started the run again begins a new run (its own clock and timeline),
/// one made in the past a branch.
pub(super) struct PendingBranch {
    /// The moment it came at, seconds.
    t_s: f64,
    /// The parameters before the input.
    before: Vec<Option<f64>>,
    /// The main plot's progress before it ([`plot_x`]).
    x_before: Option<f64>,
    /// The run it may leave behind, unnamed: the old future from the past
    /// (with its trails), the run so far from its end (one that lasted
    /// [`KEEP_MIN_STEPS`]; its plots only, taken before every such input).
    left: Option<KeptRun>,
    /// It came while the past was shown.
    from_past: bool,
    /// What the input was, when the page knows (an action).
    cause: Option<&'static labcore::ActionSpec>,
}

/// A run ended by a restart is kept for comparison when it lasted at least
/// this many steps (half a second): the runs a dragged slider starts one a
/// frame are not.
const KEEP_MIN_STEPS: u64 = 30;

fn main_x(exp: &dyn Lab) -> Option<f64> {
    exp.plots().first().and_then(plot_x)
}

fn param_values(exp: &dyn Lab) -> Vec<Option<f64>> {
    exp.params().iter().map(|s| exp.param(s.key)).collect()
}

/// The plots as drawn: the record's (its last state's) while the scene
/// shows the past, with a rolling window moved to keep the moment shown in
/// view; each with the places of the kept runs (an experiment with a
/// timeline). Borrowed, not copied, while there is nothing to add.
pub(super) fn shown_plots<'a>(
    exp: &'a dyn Lab,
    record_end: Option<&'a dyn Lab>,
    kept: &[KeptRun],
    kept_serial: u64,
) -> Cow<'a, [Plot]> {
    if record_end.is_none() && kept.is_empty() {
        return Cow::Borrowed(exp.plots());
    }
    let base = record_end.map_or(exp.plots(), |end| end.plots());
    let mut plots = timeline::with_kept(base, kept, kept_serial);
    if record_end.is_some() {
        for (i, (plot, now)) in plots.iter_mut().zip(exp.plots()).enumerate() {
            let (XWindow::Rolling(w), Some(x), Some((_, hi))) =
                (plot.window, plot_x(now), plot.x_range())
            else {
                continue;
            };
            let w = w.abs();
            if x >= hi - 0.9 * w && x <= hi {
                continue;
            }
            let first = plot
                .series
                .iter()
                .filter(|s| !s.comparison)
                .filter_map(|s| s.x.first().copied())
                .reduce(f64::min);
            match first {
                // The record still holds that moment: a window around it.
                Some(first) if x >= first => {
                    let lo = (x - 0.5 * w).max(first);
                    plot.window = XWindow::Fixed(lo, lo + w);
                    // Another window is another picture; the cursor alone
                    // moving is not ([`crate::plot_view::PlotView::set_cursor`]).
                    // The low bit set, a window from 0 changes it too (it
                    // was taken for the record's own picture).
                    plot.revision ^= (lo.to_bits() | 1).rotate_left(29);
                }
                // The record has let that moment go (a long run keeps a
                // window's worth of samples): the plot as the run showed it
                // then, ending at the moment.
                _ => *plot = timeline::plot_with_kept(now, i, kept, kept_serial),
            }
        }
    }
    Cow::Owned(plots)
}

/// Makes each plot canvas focusable, its arrow keys moving the timeline
/// along the plot, for an experiment with a timeline.
pub(super) fn focusable_plots(panel: &Element) {
    for canvas in dom::query_all(panel, ".plot-canvas") {
        let _ = canvas.set_attribute("tabindex", "0");
        let _ = canvas.set_attribute("aria-keyshortcuts", "ArrowLeft ArrowRight Home End");
        let title = canvas.get_attribute("aria-label").unwrap_or_default();
        let _ = canvas.set_attribute(
            "aria-label",
            &format!("{title}: click a point, or use the Left and Right arrows, to show the scene at that moment"),
        );
    }
}

/// Wires the slider: dragging it (or its arrow, Page, Home and End keys)
/// goes to that step.
pub(super) fn listen(
    state: &Rc<RefCell<SimState>>,
    panel: &Element,
    listeners: &mut Vec<Listener>,
) {
    let Some(slider) = query(panel, ".tb-scrub") else {
        return;
    };
    let s = state.clone();
    listeners.push(Listener::new(slider.as_ref(), "input", move |e: Event| {
        let Some(input) = e
            .target()
            .and_then(|t| t.dyn_into::<HtmlInputElement>().ok())
        else {
            return;
        };
        let Ok(step) = input.value().parse::<u64>() else {
            return;
        };
        let mut st = s.borrow_mut();
        st.student_acted();
        st.seek(step);
        // The slider already shows the step it moved to: the frame does not
        // write it back (a range input given a value lays its thumb out
        // again; 0.3 ms of a 4×-throttled scrub frame in RRT*'s profile).
        if st.clock.steps() == step {
            st.shown_scrub.2 = step;
        }
        // A drag is a stream of inputs: the page's text follows it at the
        // text's pace, the link is written once it stops (a link a frame
        // costs Chromium 10–17 ms each, and Safari refuses more than 100 in
        // 30 s), and the plots whose picture changed (a rolling window that
        // moved) keep it while the drag moves, then are repainted at the
        // plots' pace, one a frame, once it rests for SCRUB_REST_MS (a plot
        // paint is 12–16 ms on the 4×-throttled phone: a drag painting them
        // moved in jerks); the scene, the cursors and the time follow every
        // frame. A single move (a tap on the track, a value typed by a
        // test) writes everything at once.
        if st.scrub_dragging {
            st.text_paced = true;
            st.plots_stale = false;
            st.scrub_moved = true;
        }
    }));
    let s = state.clone();
    listeners.push(Listener::new(
        slider.as_ref(),
        "pointerdown",
        move |_: Event| {
            s.borrow_mut().scrub_dragging = true;
        },
    ));
    // The drag ends with `change` (the value committed on release), or
    // with the pointer let go or taken by the browser.
    for kind in ["change", "pointerup", "pointercancel"] {
        let s = state.clone();
        listeners.push(Listener::new(slider.as_ref(), kind, move |_: Event| {
            let mut st = s.borrow_mut();
            if st.scrub_dragging {
                st.scrub_dragging = false;
                // The moment it stopped at, written at once (also when the
                // last move came in the same frame).
                st.needs_paint = true;
                st.text_paced = false;
                st.plots_stale = true;
            }
        }));
    }
    let s = state.clone();
    listeners.push(Listener::new(
        slider.as_ref(),
        "keydown",
        move |e: Event| {
            let Some(key) = e.dyn_ref::<KeyboardEvent>().map(KeyboardEvent::key) else {
                return;
            };
            let mut st = s.borrow_mut();
            if st.scrub_key(&key) {
                e.prevent_default();
            }
        },
    ));
    if state.borrow().timeline.is_some() {
        focusable_plots(panel);
        let s = state.clone();
        listeners.push(Listener::new(panel.as_ref(), "keydown", move |e: Event| {
            let (Some(ke), Some(canvas)) = (
                e.dyn_ref::<KeyboardEvent>(),
                e.target()
                    .and_then(|t| t.dyn_into::<Element>().ok())
                    .filter(|el| el.class_list().contains("plot-canvas")),
            ) else {
                return;
            };
            let mut st = s.borrow_mut();
            if st.plot_key(&canvas, &ke.key()) {
                e.prevent_default();
            }
        }));
    }
}

impl SimState {
    /// Whether the scene shows a step before the run's last.
    pub(super) fn in_past(&self) -> bool {
        self.timeline
            .as_ref()
            .is_some_and(|t| self.clock.steps() < t.end())
    }

    /// The plots of the run shown, whole: the record's end's while the
    /// scene shows a past moment of it (the plots drawn, their CSV and
    /// their tables: one run, its moment a cursor on them).
    pub(super) fn run_plots(&self) -> &[Plot] {
        self.record_end.as_deref().unwrap_or(&*self.exp).plots()
    }

    /// A new record from the state now (mount, Reset, a file loaded, a
    /// new run): the clock's steps are the run's own from here.
    pub(super) fn restart_timeline(&mut self) {
        self.record_end = None;
        self.pending_branch = None;
        if self.exp.animated() {
            self.timeline = Some(Timeline::new(self.exp.as_ref(), self.clock.steps()));
        }
        self.run_to_end = None;
        self.clear_marks();
    }

    /// An input is about to change the model at the step shown: the record
    /// keeps the state it leaves (from the past: a new run from there), and
    /// what the run was is noted for [`SimState::finish_branch`].
    pub(super) fn timeline_input(&mut self) {
        let cause = self.branch_cause.take();
        if self.record_end.is_some() {
            self.finish_branch();
        }
        if self.pending_branch.is_none() {
            let steps = self.timeline.as_ref().map_or(0, |t| t.end() - t.first());
            let from_past = self.record_end.is_some();
            let left = match self.record_end.take() {
                Some(end) => Some(KeptRun::of(end.as_ref(), String::new())),
                None if steps >= KEEP_MIN_STEPS && !self.exp.plots().is_empty() => {
                    Some(KeptRun::plots_of(self.exp.as_ref(), String::new()))
                }
                None => None,
            };
            self.pending_branch = Some(PendingBranch {
                t_s: self.clock.time_s(),
                before: param_values(self.exp.as_ref()),
                x_before: main_x(self.exp.as_ref()),
                left,
                from_past,
                cause,
            });
        }
        if let Some(tl) = &mut self.timeline {
            tl.input_at(self.clock.steps());
            if let Some(action) = cause {
                tl.acted(action.key);
            }
        }
        self.marks_new_run_from(self.clock.steps());
    }

    /// The input just given ([`SimState::timeline_input`]) is `input`: a
    /// link of a later moment carries it (`then=`, issue 53). An input not
    /// said to be one breaks the link of the moments after it.
    pub(super) fn timeline_linked(&mut self, input: labcore::run_input::RunInput) {
        if let Some(tl) = &mut self.timeline {
            tl.linked(input);
        }
    }

    /// Settles an input once it has been applied. One that started the run
    /// again (the main plot went back: [`timeline::restarted`]) begins a
    /// new run: the clock and the timeline count from its start, as its
    /// plots, status and marks do, and the run it ended is kept for
    /// comparison, named as the restart it is. One made in the past keeps
    /// the old future, named after the change and its moment. Either plays
    /// on where the timeline had paused the run (a scrub, Run to end).
    pub(super) fn finish_branch(&mut self) {
        let Some(branch) = self.pending_branch.take() else {
            return;
        };
        let restarted = timeline::restarted(branch.x_before, main_x(self.exp.as_ref()));
        let cause = branch.cause.map(|a| a.label);
        if let Some(mut left) = branch.left.filter(|_| restarted || branch.from_past) {
            let (specs, after) = (self.exp.params(), param_values(self.exp.as_ref()));
            left.label = if restarted {
                timeline::restart_label(specs, &branch.before, &after, cause)
            } else {
                timeline::branch_label(specs, &branch.before, &after, cause, branch.t_s)
            };
            timeline::keep(&mut self.kept, left);
            self.kept_serial += 1;
            self.plots_force = true;
        }
        if restarted {
            self.clock.reset();
            self.restart_timeline();
            // An action that started the run again is part of its start.
            if let (Some(tl), Some(action)) = (&mut self.timeline, branch.cause) {
                tl.acted(action.key);
            }
            self.plots_force = true;
            self.jumped = true;
            self.hash_dirty = true;
        }
        if (restarted || branch.from_past) && std::mem::take(&mut self.timeline_paused) {
            self.clock.set_running(true);
            self.last_time_ms = None;
        }
        self.needs_paint = true;
    }

    /// Puts the cursor on every plot at the moment shown while it is in
    /// the past; none when the run is shown live at its end.
    pub(super) fn sync_cursors(&mut self) {
        let past = self.record_end.is_some();
        for plot in self.exp.plots() {
            self.plots
                .set_cursor(plot.key, if past { plot_x(plot) } else { None });
        }
    }

    /// The moment shown in words: the time and the main readout
    /// (`t = 3.20 s, x = 0.950 m`), as the slider speaks it.
    pub(super) fn moment_text(&self) -> String {
        let main = self
            .exp
            .readouts()
            .into_iter()
            .next()
            .map_or(String::new(), |r| format!(", {} = {}", r.label, r.value));
        format!("t = {:.2} s{main}", self.clock.time_s())
    }

    /// The timeline slider's keys: an arrow moves one model step, Page Up
    /// and Page Down one second (a tenth of the run where the main plot
    /// counts iterations, not seconds), Home and End to the record's ends.
    /// Returns whether the key was one of them.
    pub(super) fn scrub_key(&mut self, key: &str) -> bool {
        let Some(tl) = &self.timeline else {
            return false;
        };
        let (first, end, now) = (tl.first(), tl.end(), self.clock.steps());
        let model = u64::from(Clock::fixed_steps_in(self.exp.natural_step_s())).max(1);
        let in_seconds = self.exp.plots().first().is_none_or(|p| p.x_unit == "s");
        let page = if in_seconds {
            (1.0 / Clock::DT_S).round() as u64
        } else {
            ((end - first) / 10).max(1)
        };
        let target = match key {
            "ArrowLeft" | "ArrowDown" => now.saturating_sub(model),
            "ArrowRight" | "ArrowUp" => now + model,
            "PageDown" => now.saturating_sub(page),
            "PageUp" => now + page,
            "Home" => first,
            "End" => end,
            _ => return false,
        };
        self.student_acted();
        self.seek(target.clamp(first, end));
        true
    }

    /// A click or tap at client x `client_x` on a plot's canvas: the
    /// timeline goes to the moment of that point and pauses there.
    pub(super) fn go_to_plot_point(&mut self, canvas: &Element, client_x: f64) {
        if let Some((key, x)) = self.plots.point_at(canvas, client_x) {
            self.go_to_plot_x(key, x, None);
        }
    }

    /// Goes to the step of the run whose plot `key` reached nearest plot x
    /// `x`, past `not` (a step the keys must leave), and says the moment.
    /// Returns the step gone to.
    fn go_to_plot_x(&mut self, key: &str, x: f64, not: Option<u64>) -> Option<u64> {
        let index = self.exp.plots().iter().position(|p| p.key == key)?;
        self.timeline_commit();
        let step = self
            .timeline
            .as_ref()?
            .step_at_plot_x(index, x, &mut step_once)?;
        if Some(step) == not {
            return None;
        }
        self.student_acted();
        self.seek(step);
        let text = self.moment_text();
        self.say(&text);
        Some(step)
    }

    /// A key on a focused plot: Left and Right move the timeline to the
    /// plot's previous or next point, Home and End to its first and last.
    /// Returns whether the key was one of them.
    pub(super) fn plot_key(&mut self, canvas: &Element, key: &str) -> bool {
        let Some(plot_key) = self.plots.key_of(canvas) else {
            return false;
        };
        let (xs, now) = {
            let plots = shown_plots(
                self.exp.as_ref(),
                self.record_end.as_deref(),
                &self.kept,
                self.kept_serial,
            );
            let Some(main) = plots
                .iter()
                .find(|p| p.key == plot_key)
                .and_then(|p| p.series.iter().find(|s| !s.comparison && !s.is_empty()))
            else {
                return false;
            };
            let now = self
                .exp
                .plots()
                .iter()
                .find(|p| p.key == plot_key)
                .and_then(plot_x)
                .and_then(|x| main.nearest(x))
                .unwrap_or(main.len() - 1);
            (main.x.clone(), now)
        };
        let last = xs.len() - 1;
        let step_now = self.clock.steps();
        let order: Vec<usize> = match key {
            "ArrowLeft" => (0..now).rev().collect(),
            "ArrowRight" => (now + 1..=last).collect(),
            "Home" => vec![0],
            "End" => vec![last],
            _ => return false,
        };
        // The next point that is another step (a step may add several).
        for i in order {
            if self.go_to_plot_x(plot_key, xs[i], Some(step_now)).is_some() {
                break;
            }
        }
        true
    }

    /// Before the live run steps: the record takes the state an input left.
    /// An input on its way is settled first ([`SimState::finish_branch`]).
    pub(super) fn timeline_commit(&mut self) {
        self.finish_branch();
        if let Some(tl) = &mut self.timeline {
            tl.commit(self.exp.as_ref());
        }
    }

    /// Asks for a rehearsal of a scrub in the browser's idle time
    /// ([`SimState::rehearse_scrub`]), once, when the record first holds a
    /// replay to go back to.
    pub(super) fn ask_for_scrub_rehearsal(&mut self) {
        if self.scrub_rehearsed || self.rehearse_asked {
            return;
        }
        let Some(tl) = &self.timeline else {
            return;
        };
        if tl.end() - tl.first() < 2 * tl.interval() {
            return;
        }
        // Where the browser has no idle callbacks, nothing is rehearsed.
        self.rehearse_asked = dom::when_idle(&self.panel, REHEARSAL_TIMEOUT_MS);
        self.scrub_rehearsed = !self.rehearse_asked;
    }

    /// Rehearses a scrub, once, in the browser's idle time: rebuilds a past
    /// state ([`Timeline::peek_at`]: a snapshot copied, one interval less one
    /// step replayed), its display list, text and plots, and drops them.
    /// Nothing the student sees changes (the canvas says
    /// `data-scrub-rehearsed`, for tests). A WebAssembly function is compiled on
    /// its first call: on the 4×-throttled phone stand-in, the first frame of
    /// a student's first drag spent about 9 of its 23 ms compiling (RRT*);
    /// after the rehearsal, that frame's compiling took 1.1 ms. (The next
    /// few frames, which the browser runs while it optimises the code, stay
    /// as they were.)
    pub(super) fn rehearse_scrub(&mut self) {
        self.rehearse_asked = false;
        // A scrub came first (the idle time waits up to 2 s): nothing to do.
        if std::mem::replace(&mut self.scrub_rehearsed, true) {
            return;
        }
        let Some(tl) = &self.timeline else {
            return;
        };
        let (first, end, k) = (tl.first(), tl.end(), tl.interval());
        // Periodic snapshots fall on multiples of the interval: a step just
        // before one replays the most.
        let middle = first + (end - first) / 2;
        let step = (middle - middle % k + k - 1).clamp(first, end);
        let lab = tl.peek_at(step, &mut step_once);
        let mut scene = labcore::scene::Scene::default();
        lab.scene(&mut scene);
        std::hint::black_box((lab.readouts(), lab.status(), lab.tables(), scene));
        let plots = shown_plots(
            lab.as_ref(),
            Some(self.record_end.as_deref().unwrap_or(self.exp.as_ref())),
            &self.kept,
            self.kept_serial,
        );
        std::hint::black_box(plots);
        // For tests (like `data-steps`): the student sees nothing of it.
        let _ = self.canvas.set_attribute("data-scrub-rehearsed", "");
    }

    /// Goes to step `step` of the run (clamped to the record) and pauses
    /// there: the scene, readouts, status, tables and plots as they were.
    pub(super) fn seek(&mut self, step: u64) {
        self.timeline_commit();
        let Some(tl) = self.timeline.as_mut() else {
            return;
        };
        let end = tl.end();
        // A scrub's code has run: no rehearsal is wanted.
        self.scrub_rehearsed = true;
        // A drag forward through the past steps the state shown on, when
        // no snapshot lies between (the run's last state is kept aside).
        let stepped_on = if self.record_end.is_some() {
            tl.step_on_to(self.exp.as_mut(), self.clock.steps(), step, &mut step_once)
        } else {
            None
        };
        let at = if let Some(at) = stepped_on {
            at
        } else {
            let (at, lab) = tl.state_at(step, &mut step_once);
            let shown = std::mem::replace(&mut self.exp, lab);
            // The run's last state is kept while the past is shown (its
            // plots are drawn; an input there keeps it as the run left
            // behind).
            if self.record_end.is_none() {
                self.record_end = Some(shown);
            }
            at
        };
        if at == end {
            self.record_end = None;
        }
        self.keep_end_comparisons();
        if self.css_size.0 >= 1.0 {
            self.exp.viewport_px(self.css_size.0, self.css_size.1);
        }
        self.clock.set_running(false);
        self.timeline_paused = true;
        self.clock.seek(at);
        self.ended_hold = false;
        self.run_to_end = None;
        self.phase = self.exp.status().phase;
        self.last_time_ms = None;
        self.after_jump();
    }

    /// The past moment shown keeps the runs the record's end compares
    /// with (PID's pins), as the plots drawn are the end's: a run pinned
    /// after the moment stays in the readouts too (issue 53 §2).
    fn keep_end_comparisons(&mut self) {
        if let Some(end) = &self.record_end {
            self.exp.take_comparisons(end.as_any());
        }
    }

    /// What a jump in time redraws: the scene, the plots' cursors (a plot
    /// itself only where its picture changed: a rolling window that moved,
    /// the record's end shown again), the controls whose parameter was
    /// another then (the next text write compares each with what it shows),
    /// the text and the link.
    ///
    /// Nothing is written to the page here, in the input's handler: the
    /// next frame writes it all after reading the layout (a write here
    /// would make that read lay the page out again, mid-frame).
    fn after_jump(&mut self) {
        self.needs_paint = true;
        self.plots_stale = true;
        self.jumped = true;
        self.hash_dirty = true;
    }

    /// Step back (the button and `,`): one model step earlier.
    pub(super) fn step_back(&mut self) {
        let n = u64::from(Clock::fixed_steps_in(self.exp.natural_step_s()));
        self.seek(self.clock.steps().saturating_sub(n));
    }

    /// Moves on `n` steps along the record while the scene shows the past
    /// (Play or Step there); returns the steps taken (fewer at its end).
    pub(super) fn forward_in_past(&mut self, from: u64, n: u64) -> u64 {
        let Some(tl) = self.timeline.as_mut() else {
            return 0;
        };
        let at = tl.forward(&mut self.exp, from, from + n, &mut step_once);
        if at == tl.end() {
            self.record_end = None;
        }
        self.keep_end_comparisons();
        self.clock.seek(at);
        // The plots' cursors follow the replay.
        self.plots_stale = true;
        self.jumped = true;
        at - from
    }

    /// Run to end (the button and `End`): pauses, goes to the run's last
    /// step, then finishes the run over the next frames.
    pub(super) fn start_run_to_end(&mut self) {
        if self.timeline.is_none() {
            return;
        }
        self.timeline_commit();
        if self.in_past() {
            let end = self.timeline.as_ref().map_or(0, Timeline::end);
            self.seek(end);
        }
        self.clock.set_running(false);
        self.timeline_paused = true;
        self.ended_hold = false;
        self.run_to_end = Some(self.clock.steps());
        self.needs_paint = true;
        self.sync_timebar(true);
    }

    /// One frame of Run to end: steps until the run ends or stops moving,
    /// for at most [`RUN_TO_END_BUDGET_MS`] since `start_ms`. Returns the
    /// steps taken.
    pub(super) fn run_to_end_frame(&mut self, start_ms: f64) -> u64 {
        let Some(from) = self.run_to_end else {
            return 0;
        };
        let left = (from + RUN_TO_END_MAX_STEPS).saturating_sub(self.clock.steps());
        let (taken, done) = self.step_recorded(left, true, start_ms, RUN_TO_END_BUDGET_MS);
        self.needs_paint = true;
        if done {
            self.run_to_end = None;
            self.plots_force = true;
            self.hash_dirty = true;
            self.announce();
            if self.exp.animating() && self.exp.status().phase != Phase::Ended {
                // Stopped by the limit, not by an end: say so.
                self.show_message(Some(&format!(
                    "Run to end: this run has no end, so it went 10 minutes on, to t = {:.2} s.",
                    self.clock.time_s()
                )));
            }
        }
        taken
    }

    /// Opens the run at `t_s` seconds (a link's `at=`): the link's state is
    /// its start; the run is stepped there (at most
    /// [`RUN_TO_END_MAX_STEPS`], fewer if it ends first) and paused. A
    /// link's marks after that moment (`last_mark`, a step) are part of the
    /// run it names: the run is stepped on to the last of them and shown at
    /// the moment, the marks on its plots (issue 53 §2: a report's link
    /// reopens the moment and the marks).
    pub(super) fn open_at(
        &mut self,
        t_s: f64,
        last_mark: Option<u64>,
        inputs: &[(u64, RunInput)],
    ) -> Vec<String> {
        let at = ((t_s / Clock::DT_S).round() as u64).min(RUN_TO_END_MAX_STEPS);
        let steps = at.max(last_mark.unwrap_or(0)).min(RUN_TO_END_MAX_STEPS);
        let actions = self.timeline.as_ref().map(|t| t.start_actions().to_vec());
        self.clock.reset();
        self.restart_timeline();
        // The link's actions (`do=`) are part of its start.
        if let Some(tl) = &mut self.timeline {
            actions.into_iter().flatten().for_each(|a| tl.acted(a));
        }
        // The inputs during the run (`then=`), each given at its step as
        // the page gave it; one the run does not reach (it ended first, or
        // the link's last moment is before it) is left out, and said.
        let mut notices = Vec::new();
        let mut left_out = false;
        for (step, input) in inputs {
            let to_go = step.saturating_sub(self.clock.steps());
            self.step_recorded(
                to_go.min(steps - self.clock.steps().min(steps)),
                false,
                0.0,
                f64::INFINITY,
            );
            if self.clock.steps() != *step {
                left_out = true;
                continue;
            }
            notices.extend(self.give_run_input(input));
        }
        if left_out {
            notices.push("Some of the link's inputs during the run come after the run or the link's moment; they were left out.".to_owned());
        }
        let to_go = steps.saturating_sub(self.clock.steps());
        self.step_recorded(to_go, false, 0.0, f64::INFINITY);
        if at < self.clock.steps() {
            self.seek(at);
            // Paused by the link (`run=0`), as at its end, not by a scrub.
            self.timeline_paused = false;
        }
        self.clock.set_running(false);
        self.phase = self.exp.status().phase;
        self.plots_force = true;
        notices
    }

    /// Gives the live run an input a link carries ([`RunInput`]) as the
    /// page's own controls give it: through the instructor's locks, recorded
    /// as one. Returns what the page would say of a value or a button it
    /// does not take.
    fn give_run_input(&mut self, input: &RunInput) -> Option<String> {
        let mut result = Ok(());
        if let RunInput::Action(key) = input {
            self.branch_cause = self.exp.actions().iter().find(|a| a.key == key);
        }
        self.guarded(|exp| result = input.apply(exp));
        if !matches!(input, RunInput::Action(_)) {
            self.timeline_linked(input.clone());
        }
        self.finish_branch();
        self.hash_dirty = true;
        result
            .err()
            .map(|e| format!("The link's inputs during the run: {e}"))
    }

    /// Takes up to `steps` steps of the live run, recorded, as a run takes
    /// them (the instructor's locks held); stops at the run's end (with
    /// `until_still`, also when nothing moves) or once the time since
    /// `start_ms` reaches `budget_ms`. Returns the steps taken and whether
    /// it is done (not stopped by the budget).
    fn step_recorded(
        &mut self,
        steps: u64,
        until_still: bool,
        start_ms: f64,
        budget_ms: f64,
    ) -> (u64, bool) {
        self.timeline_commit();
        let timeline = &mut self.timeline;
        let (mut taken, mut done) = (0, false);
        let _ = labcore::route::keep_locked(self.exp.as_mut(), &self.instructor, |exp| loop {
            if taken >= steps
                || exp.status().phase == Phase::Ended
                || (until_still && !exp.animating())
            {
                done = true;
                break;
            }
            if dom::now_ms() - start_ms >= budget_ms {
                break;
            }
            exp.step(Clock::DT_S);
            if let Some(tl) = timeline.as_mut() {
                tl.stepped(exp);
            }
            taken += 1;
        });
        self.clock.seek(self.clock.steps() + taken);
        (taken, done)
    }

    /// Brings the slider up to date: its range (the record), its value (the
    /// step shown) and its spoken value, the time and the main readout.
    ///
    /// While a pointer drags the slider its `aria-valuetext` (which reads
    /// the main readout: every readout computed) waits for the page's text
    /// ([`SimState::sync_valuetext`], at the text's pace and when the drag
    /// ends); its range and value follow every frame, each written only
    /// when it changed.
    pub(super) fn sync_scrub(&mut self) {
        let Some(tl) = &self.timeline else {
            return;
        };
        let now = (tl.first(), tl.end(), self.clock.steps());
        if now != self.shown_scrub {
            let shown = std::mem::replace(&mut self.shown_scrub, now);
            let Some(slider) = self
                .scrub_slider
                .as_ref()
                .and_then(|s| s.dyn_ref::<HtmlInputElement>())
            else {
                return;
            };
            if (now.0, now.1) != (shown.0, shown.1) {
                let _ = slider.set_attribute("min", &now.0.to_string());
                let _ = slider.set_attribute("max", &now.1.to_string());
            }
            slider.set_value(&now.2.to_string());
        }
        if !self.scrub_dragging {
            self.sync_valuetext();
        }
    }

    /// Writes the slider's `aria-valuetext` ([`SimState::moment_text`]) if
    /// the moment it names, or the record around it, changed since.
    pub(super) fn sync_valuetext(&mut self) {
        if self.shown_valuetext == self.shown_scrub {
            return;
        }
        self.shown_valuetext = self.shown_scrub;
        if let Some(slider) = &self.scrub_slider {
            let _ = slider.set_attribute("aria-valuetext", &self.moment_text());
        }
    }

    /// Whether a pointer drags the timeline slider and moved it less than
    /// [`SCRUB_REST_MS`] before `now_ms`: the plots keep their pictures
    /// (their cursors move over them) until it rests or lets go.
    pub(super) fn scrub_moving(&self, now_ms: f64) -> bool {
        self.scrub_dragging && now_ms - self.scrub_moved_ms < SCRUB_REST_MS
    }
}
