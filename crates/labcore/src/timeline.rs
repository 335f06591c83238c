//! The timeline of a run: go back to any step of it, exactly, in bounded
//! memory and bounded work.
//!
//! A run is a function of its starting state and the inputs it was given
//! (every experiment is deterministic and fixed-step), so the timeline keeps
//! copies of the whole experiment ([`crate::Lab::snapshot`]) and steps a copy
//! on to reach any step between them:
//!
//! - a **periodic** snapshot every [`Timeline::interval`] steps of the run;
//! - a **pinned** snapshot at each step where an input (a parameter, an
//!   action, a drag, a file, a link) changed the state, taken once the input
//!   is done ([`Timeline::input_at`], [`Timeline::commit`]): the state after
//!   the input is the log of that input, whatever its kind, with no replay
//!   of the input itself (a pointer's modifiers, a file's text) to go wrong;
//! - a snapshot kept as a pinned one where the run's work phase changes (A*'s
//!   search ends), which is no input: the run goes on as its start stepped
//!   on, and a link of a later moment still names it.
//!
//! Between two snapshots the run only stepped, so the state at step `n` is
//! the latest snapshot at or before `n`, stepped `n − s` times: at most
//! `interval − 1` steps ([`Timeline::last_replay`] counts them).
//!
//! Memory stays within [`Timeline::BUDGET_BYTES`] (as each snapshot's
//! [`crate::Experiment::state_bytes`] estimates it): when the snapshots
//! outgrow it, the interval doubles and every other periodic snapshot goes;
//! if pinned snapshots alone outgrow it, the oldest part of the run is
//! forgotten ([`Timeline::first`] moves on). A long run costs a longer
//! replay, never more memory.
//!
//! A link of a moment reproduces it when every input on the way is one a
//! link can carry ([`crate::run_input`]): the timeline keeps the inputs made
//! after the start, each with its step ([`Timeline::linked`]); an input it
//! was not told how to carry (a file, a reset) breaks the link of every
//! moment from its step on ([`Timeline::unbroken_to`]).
//!
//! Steps are counted as the shell's clock counts them
//! ([`crate::clock::Clock::steps`]): one [`crate::Experiment::step`] of
//! [`crate::clock::Clock::DT_S`] each.

use crate::experiment::{ParamKind, ParamSpec};
use crate::plot::{Plot, Series, SeriesRole};
use crate::run_input::RunInput;
use crate::scene::{Item, Role, Scene};
use crate::units::{format_fixed, format_number, with_unit};
use crate::Lab;
use glam::DVec2;

/// A kept copy of the experiment at one step.
struct Snapshot {
    step: u64,
    lab: Box<dyn Lab>,
    /// Taken after an input (or at the start), or where the work phase
    /// changed: never thinned out.
    pinned: bool,
    /// Taken after an input (or at the start): from here on the state is
    /// no longer the run's start stepped on (a link of the start and a
    /// time does not reach it). A work phase's snapshot is none.
    input: bool,
    /// Its estimated size, bytes.
    bytes: usize,
}

impl Snapshot {
    fn of(exp: &dyn Lab, step: u64, pinned: bool) -> Self {
        let lab = exp.snapshot();
        let bytes = std::mem::size_of_val(&*lab) + lab.state_bytes();
        Self {
            step,
            lab,
            pinned,
            input: pinned,
            bytes,
        }
    }
}

// The doubling keeps snapshots at multiples of the interval: both bounds of
// the first interval are powers of two, so every interval is one.
const _: () = assert!(
    Timeline::FIRST_INTERVAL.is_power_of_two() && Timeline::MIN_FIRST_INTERVAL.is_power_of_two()
);

/// The recorded run: snapshots from [`Timeline::first`] to [`Timeline::end`]
/// (see the module's documentation).
pub struct Timeline {
    /// Sorted by step, never empty; the first is the oldest step kept.
    snaps: Vec<Snapshot>,
    /// The run's last step (the live state's).
    end: u64,
    interval: u64,
    /// An input changed the state at `end`; not yet snapshot.
    dirty: bool,
    /// The snapshots' estimated size, bytes.
    bytes: usize,
    budget_bytes: usize,
    last_replay: u64,
    worst_replay: u64,
    /// The actions pressed at the start (step 0), in order, after its
    /// parameters: a link of the start carries them (`do=`).
    start_actions: Vec<&'static str>,
    /// An input at the start that may not be an action (until
    /// [`Timeline::acted`] says it was).
    start_pending: bool,
    /// Another input followed an action at the start: no link reproduces
    /// that order (a link's parameters come before its actions).
    start_unlinked: bool,
    /// The live state's [`crate::Experiment::work_phase`].
    work_phase: u8,
    /// The inputs after the start, in order, with their steps: each as a
    /// link carries it, or `None` for one no link carries.
    later: Vec<(u64, Option<RunInput>)>,
}

impl Timeline {
    /// The first snapshot interval of an experiment whose step weighs 1
    /// ([`Timeline::first_interval`]), steps (0.53 s at 60 steps a second).
    pub const FIRST_INTERVAL: u64 = 32;
    /// What the snapshots may hold, bytes (estimated; see the module).
    pub const BUDGET_BYTES: usize = 16 << 20;

    /// The shortest first interval, steps: a scrub of the heaviest steps
    /// (RRT*'s batches) replays at most one. Measured on the 4×-throttled
    /// phone stand-in (issue 53 §9), RRT*'s default run at 4 steps replayed
    /// up to 3 batches of 24 iterations, and its scrub frame p95 read
    /// 7.9–9.3 ms against a budget of 8; at 2 its 84 snapshots hold
    /// 15.8 MB, within [`Self::BUDGET_BYTES`].
    pub const MIN_FIRST_INTERVAL: u64 = 2;

    /// The first snapshot interval for `exp`, steps: [`Self::FIRST_INTERVAL`]
    /// divided by its [`crate::Experiment::step_weight`] (rounded up to a
    /// power of two), at least [`Self::MIN_FIRST_INTERVAL`]. A power of two,
    /// as the doubling needs.
    #[must_use]
    pub fn first_interval(exp: &dyn Lab) -> u64 {
        let weight = exp.step_weight().clamp(1, Self::FIRST_INTERVAL);
        (Self::FIRST_INTERVAL / weight.next_power_of_two()).max(Self::MIN_FIRST_INTERVAL)
    }

    /// A timeline starting at `exp`, which shows step `step` (0 after a
    /// reset).
    #[must_use]
    pub fn new(exp: &dyn Lab, step: u64) -> Self {
        Self::with_budget(exp, step, Self::BUDGET_BYTES)
    }

    /// [`Timeline::new`] with another memory budget, bytes (tests).
    #[must_use]
    pub fn with_budget(exp: &dyn Lab, step: u64, budget_bytes: usize) -> Self {
        let first = Snapshot::of(exp, step, true);
        Self {
            bytes: first.bytes,
            snaps: vec![first],
            end: step,
            interval: Self::first_interval(exp),
            dirty: false,
            budget_bytes,
            last_replay: 0,
            worst_replay: 0,
            start_actions: Vec::new(),
            start_pending: false,
            start_unlinked: false,
            work_phase: exp.work_phase(),
            later: Vec::new(),
        }
    }

    /// The oldest step the timeline can go back to.
    #[must_use]
    pub fn first(&self) -> u64 {
        self.snaps[0].step
    }

    /// The run's last step.
    #[must_use]
    pub fn end(&self) -> u64 {
        self.end
    }

    /// Steps between periodic snapshots now: no step is further than this
    /// less one from a snapshot.
    #[must_use]
    pub fn interval(&self) -> u64 {
        self.interval
    }

    /// How many snapshots are kept.
    #[must_use]
    pub fn snapshots(&self) -> usize {
        self.snaps.len()
    }

    /// The snapshots' estimated size, bytes.
    #[must_use]
    pub fn bytes(&self) -> usize {
        self.bytes
    }

    /// Whether the state at `step` is the run's start stepped `step` times,
    /// with only inputs a link carries on the way ([`Timeline::inputs_link`]),
    /// so that a link of the start, those inputs and the time reproduces
    /// it. An input not yet committed ([`Timeline::input_at`]) counts: it
    /// changed the state at the run's end.
    #[must_use]
    pub fn unbroken_to(&self, step: u64) -> bool {
        self.first() == 0
            && !self.start_unlinked
            && (!self.start_pending || self.start_actions.is_empty())
            && self
                .later
                .iter()
                .take_while(|(s, _)| *s <= step)
                .all(|(_, input)| input.is_some())
    }

    /// The inputs after the start up to `step` (inclusive), in order, as a
    /// link of that moment carries them ([`crate::run_input::link_value`]):
    /// empty where there are none or [`Timeline::unbroken_to`] is false.
    #[must_use]
    pub fn inputs_link(&self, step: u64) -> String {
        let mut out = String::new();
        if self.unbroken_to(step) {
            for (s, input) in self.later.iter().take_while(|(s, _)| *s <= step) {
                if let Some(input) = input {
                    crate::run_input::push_entry(&mut out, *s, input);
                }
            }
        }
        out
    }

    /// The input just given ([`Timeline::input_at`]) after the start is
    /// `input`, which a link carries. Without this call the input breaks
    /// the link of every moment from its step on.
    pub fn linked(&mut self, input: RunInput) {
        if let Some((step, slot @ None)) = self.later.last_mut() {
            if *step == self.end {
                *slot = Some(input);
            }
        }
    }

    /// The state whose parameters and set-up a link that names moments of
    /// the run up to `step` (`at=`, `marks=`) carries: the run's start, as
    /// the moments are it stepped on; `None` when no link of the start
    /// reproduces them ([`Timeline::unbroken_to`]). A run moves some
    /// parameters (ik's joint angles): the state shown has the moment's.
    /// `live` is the state shown: the start itself while an input at the
    /// start is not yet committed.
    #[must_use]
    pub fn link_start<'a>(&'a self, live: &'a dyn Lab, step: u64) -> Option<&'a dyn Lab> {
        if !self.unbroken_to(step) {
            return None;
        }
        Some(if self.dirty && self.end == 0 {
            live
        } else {
            &*self.snaps[0].lab
        })
    }

    /// Steps replayed by the last [`Timeline::state_at`] or
    /// [`Timeline::step_on_to`].
    #[must_use]
    pub fn last_replay(&self) -> u64 {
        self.last_replay
    }

    /// The most steps any [`Timeline::state_at`] or [`Timeline::step_on_to`]
    /// replayed.
    #[must_use]
    pub fn worst_replay(&self) -> u64 {
        self.worst_replay
    }

    /// An input is about to change the state shown at `step`: from there on
    /// the run is a new one. The recorded future after `step` is dropped
    /// (the run now ends at `step`), and the state the input leaves is
    /// snapshot by the next [`Timeline::commit`].
    pub fn input_at(&mut self, step: u64) {
        self.settle_start();
        let step = step.max(self.first()).min(self.end);
        self.start_pending = step == 0;
        while self.snaps.len() > 1 && self.snaps[self.snaps.len() - 1].step > step {
            self.pop();
        }
        // The inputs of the dropped future go with it.
        while self.later.last().is_some_and(|(s, _)| *s > step) {
            self.later.pop();
        }
        if step > 0 {
            // No link carries it until it is said to ([`Timeline::linked`]).
            self.later.push((step, None));
        }
        self.end = step;
        self.dirty = true;
    }

    /// The input just given ([`Timeline::input_at`]) was the action `key`
    /// (or the run started again with it): at the start, a link of the
    /// start carries it ([`Timeline::start_actions`]); later, among the
    /// run's inputs ([`Timeline::linked`]).
    pub fn acted(&mut self, key: &'static str) {
        if self.first() == 0 && self.end == 0 {
            self.start_pending = false;
            self.start_actions.push(key);
        } else {
            self.linked(RunInput::Action(key.to_owned()));
        }
    }

    /// The actions pressed at the start, in order (see
    /// [`Timeline::acted`]): a link of the start presses them after setting
    /// its parameters.
    #[must_use]
    pub fn start_actions(&self) -> &[&'static str] {
        &self.start_actions
    }

    /// An input at the start that was no action, after one, breaks the
    /// link of the start.
    fn settle_start(&mut self) {
        if std::mem::take(&mut self.start_pending) && !self.start_actions.is_empty() {
            self.start_unlinked = true;
        }
    }

    /// Takes the snapshot an input asked for ([`Timeline::input_at`]), if
    /// any, of `exp` as the input left it. Call it before the next step and
    /// before going to another step.
    pub fn commit(&mut self, exp: &dyn Lab) {
        self.settle_start();
        if !self.dirty {
            return;
        }
        self.dirty = false;
        self.work_phase = exp.work_phase();
        // The snapshots are in step order: one at this step is the last.
        if self.snaps.len() > 1 && self.snaps[self.snaps.len() - 1].step == self.end {
            self.pop();
        }
        if self.snaps.len() == 1 && self.snaps[0].step == self.end {
            // The input changed the first state kept: it is the start now.
            self.bytes = 0;
            self.snaps.clear();
        }
        self.push(Snapshot::of(exp, self.end, true));
    }

    /// The live run took one step (after [`Timeline::commit`]): `exp` is
    /// the state at the new end. Snapshots it every [`Timeline::interval`]
    /// steps, and keeps one where its [`crate::Experiment::work_phase`]
    /// changed (a search ended), so that a jump past that step never
    /// replays the work before it; otherwise it costs nothing.
    pub fn stepped(&mut self, exp: &dyn Lab) {
        debug_assert!(!self.dirty, "Timeline::stepped before Timeline::commit");
        self.end += 1;
        let phase = exp.work_phase();
        if phase != self.work_phase {
            self.work_phase = phase;
            // Kept, but no input: the run goes on as its start stepped on,
            // and a link of a moment after it still names the moment.
            let mut snap = Snapshot::of(exp, self.end, true);
            snap.input = false;
            self.push(snap);
        } else if self.end.is_multiple_of(self.interval) {
            self.push(Snapshot::of(exp, self.end, false));
        }
    }

    /// The state at `step` (clamped to [`Timeline::first`]..=
    /// [`Timeline::end`]) and the step it is at: a copy of the latest
    /// snapshot at or before it, stepped on by `step_once` (one fixed step;
    /// the shell's keeps the instructor's locks) at most
    /// [`Timeline::interval`] − 1 times, between
    /// [`crate::Experiment::begin_replay`] and `end_replay`. `step_once`
    /// must only step: what a step derives from the state (pid's metrics)
    /// may be put off until the replay ends.
    pub fn state_at(
        &mut self,
        step: u64,
        step_once: &mut dyn FnMut(&mut dyn Lab),
    ) -> (u64, Box<dyn Lab>) {
        let (step, replay, lab) = self.rebuild(step, step_once);
        self.last_replay = replay;
        self.worst_replay = self.worst_replay.max(replay);
        (step, lab)
    }

    /// [`Timeline::state_at`] without counting its replay: the page's
    /// rehearsal of a scrub, in idle time before the first one, so the
    /// browser has compiled the code a scrub runs (WebAssembly functions
    /// are compiled on their first call) before a student drags.
    pub fn peek_at(&self, step: u64, step_once: &mut dyn FnMut(&mut dyn Lab)) -> Box<dyn Lab> {
        self.rebuild(step, step_once).2
    }

    /// The step `step` clamped to the record, the steps replayed to reach
    /// it, and the state there (see [`Timeline::state_at`]). One function
    /// for both callers: the code a rehearsal compiles is the scrub's own.
    #[inline(never)]
    fn rebuild(
        &self,
        step: u64,
        step_once: &mut dyn FnMut(&mut dyn Lab),
    ) -> (u64, u64, Box<dyn Lab>) {
        let step = step.max(self.first()).min(self.end);
        let i = self.snaps.partition_point(|s| s.step <= step).max(1) - 1;
        let snap = &self.snaps[i];
        let mut lab = snap.lab.snapshot();
        let replay = step - snap.step;
        if replay > 0 {
            lab.begin_replay();
            for _ in 0..replay {
                step_once(lab.as_mut());
            }
            lab.end_replay();
        }
        (step, replay, lab)
    }

    /// A scrub forward from a past state: steps `exp`, which shows step
    /// `from` of the record, on to `to` and returns `Some(to)` when no
    /// snapshot lies between the two (so no input either): the steps are
    /// then no more than [`Timeline::state_at`] would replay, and no copy
    /// is made. It counts them as [`Timeline::last_replay`]. Otherwise
    /// leaves `exp` as it is and returns `None`.
    ///
    /// A drag of the slider moves a few steps a frame: going forward it
    /// then costs those steps, with no copy of a snapshot (5 MB for A* on a
    /// 512 × 512 maze) and no replay from it.
    pub fn step_on_to(
        &mut self,
        exp: &mut dyn Lab,
        from: u64,
        to: u64,
        step_once: &mut dyn FnMut(&mut dyn Lab),
    ) -> Option<u64> {
        if from < self.first() || to <= from || to > self.end {
            return None;
        }
        let i = self.snaps.partition_point(|s| s.step <= to).max(1) - 1;
        let snap = &self.snaps[i];
        // A snapshot after `from` is either an input's (the state changed
        // there) or nearer `to`: the scrub rebuilds from it.
        if snap.step > from {
            return None;
        }
        for _ in from..to {
            step_once(exp);
        }
        self.last_replay = to - from;
        self.worst_replay = self.worst_replay.max(self.last_replay);
        Some(to)
    }

    /// Moves `exp`, which shows step `from`, on to step `to` along the
    /// recorded run (a replay's frame, the Step button in the past): steps
    /// it on when no input happened in between, else goes there through
    /// [`Timeline::state_at`]. Returns the step reached.
    pub fn forward(
        &mut self,
        exp: &mut Box<dyn Lab>,
        from: u64,
        to: u64,
        step_once: &mut dyn FnMut(&mut dyn Lab),
    ) -> u64 {
        let to = to.min(self.end);
        if to <= from {
            return from;
        }
        let input_between = self
            .snaps
            .iter()
            .any(|s| s.input && s.step > from && s.step <= to);
        if input_between {
            let (at, lab) = self.state_at(to, step_once);
            *exp = lab;
            at
        } else {
            for _ in from..to {
                step_once(exp.as_mut());
            }
            to
        }
    }

    fn pop(&mut self) {
        if let Some(s) = self.snaps.pop() {
            self.bytes -= s.bytes;
        }
    }

    /// Keeps `snap` (the latest step), then doubles the interval (dropping
    /// every other periodic snapshot) until the snapshots fit the budget; if
    /// pinned ones alone do not, forgets the oldest.
    fn push(&mut self, snap: Snapshot) {
        self.bytes += snap.bytes;
        self.snaps.push(snap);
        while self.bytes > self.budget_bytes && self.snaps.len() > 1 {
            let doubled = self.interval * 2;
            let mut i = 1;
            let mut dropped = false;
            while i < self.snaps.len() {
                let s = &self.snaps[i];
                if self.interval <= self.end && !s.pinned && !s.step.is_multiple_of(doubled) {
                    self.bytes -= self.snaps.remove(i).bytes;
                    dropped = true;
                } else {
                    i += 1;
                }
            }
            if self.interval <= self.end {
                self.interval = doubled;
            } else if !dropped {
                self.bytes -= self.snaps.remove(0).bytes;
            }
        }
    }
}

/// How far along its run a plot is: the largest x of the last samples of
/// its series that are not kept for comparison (the time, the iteration);
/// `None` before any sample. The plot cursor of a past moment is drawn
/// there, and [`Timeline::step_at_plot_x`] looks for it.
#[must_use]
pub fn plot_x(plot: &Plot) -> Option<f64> {
    plot.series
        .iter()
        .filter(|s| !s.comparison)
        .filter_map(|s| s.x.last().copied())
        .reduce(f64::max)
}

impl Timeline {
    /// The step of the recorded run whose plot `plot` (an index into
    /// [`crate::Experiment::plots`]) has got nearest to `x` (see
    /// [`plot_x`]): a point clicked on a plot of the run, as a step to go
    /// to. Only the stretch of the run since the plot last restarted (an
    /// input that cleared it) is searched, as that is what the plot at the
    /// run's end shows. Steps on a copy of one snapshot, at most
    /// [`Timeline::interval`] steps. `None` when the plot has no samples.
    pub fn step_at_plot_x(
        &self,
        plot: usize,
        x: f64,
        step_once: &mut dyn FnMut(&mut dyn Lab),
    ) -> Option<u64> {
        let key = |lab: &dyn Lab| lab.plots().get(plot).and_then(plot_x);
        // The stretch: from the last snapshot after which the plot went back.
        let mut lo = 0;
        for i in 1..self.snaps.len() {
            let (before, now) = (key(&*self.snaps[i - 1].lab), key(&*self.snaps[i].lab));
            if now.is_none() || before.is_some_and(|b| now.is_some_and(|n| n < b)) {
                lo = i;
            }
        }
        // The last snapshot of the stretch at or before x, stepped on.
        let i = (lo..self.snaps.len())
            .rev()
            .find(|&i| key(&*self.snaps[i].lab).is_some_and(|k| k <= x))
            .unwrap_or(lo);
        let limit = self.snaps.get(i + 1).map_or(self.end, |s| s.step);
        let mut lab = self.snaps[i].lab.snapshot();
        let mut step = self.snaps[i].step;
        let mut prev: Option<(u64, f64)> = None;
        let mut now = key(&*lab);
        while step < limit && now.is_none_or(|k| k < x) {
            if let Some(k) = now {
                prev = Some((step, k));
            }
            step_once(lab.as_mut());
            step += 1;
            now = key(&*lab);
        }
        let here = now.map(|k| (step, k));
        match (prev, here) {
            (Some(p), Some(h)) => Some(if (x - p.1).abs() < (h.1 - x).abs() {
                p.0
            } else {
                h.0
            }),
            (p, h) => h.or(p).map(|(s, _)| s),
        }
    }
}

/// At most this many runs left behind by branches are kept on the plots.
pub const MAX_KEPT: usize = 2;

/// The roles a kept run may be drawn with, in order of preference: each
/// plot gives its kept runs roles its own series do not have
/// ([`kept_roles`]), so a kept run differs from every live curve by its
/// dash as well as its colour.
pub const KEPT_ROLES: [SeriesRole; 6] = [
    SeriesRole::Quaternary,
    SeriesRole::Bound,
    SeriesRole::Reference,
    SeriesRole::Tertiary,
    SeriesRole::Secondary,
    SeriesRole::Primary,
];

/// The roles of the [`MAX_KEPT`] kept runs on `plot`: the first of
/// [`KEPT_ROLES`] that none of its series has, else one only its other
/// runs kept for comparison (a PID pin) have.
#[must_use]
pub fn kept_roles(plot: &Plot) -> [SeriesRole; MAX_KEPT] {
    let mut taken: Vec<SeriesRole> = plot.series.iter().map(|s| s.role).collect();
    let live: Vec<SeriesRole> = plot
        .series
        .iter()
        .filter(|s| !s.comparison)
        .map(|s| s.role)
        .collect();
    let mut roles = [SeriesRole::Bound; MAX_KEPT];
    for role in &mut roles {
        let free = KEPT_ROLES.iter().find(|r| !taken.contains(r));
        let shared = KEPT_ROLES.iter().find(|r| !live.contains(r));
        *role = *free.or(shared).unwrap_or(&SeriesRole::Bound);
        taken.push(*role);
    }
    roles
}

/// A run a branch left behind (issue 26 §2): changing something while the
/// timeline shows the past starts a new run from there, and the future
/// the old run had is kept for comparison, as PID's pinned runs are, on
/// every experiment's plots: the main series of each plot (its first not
/// already kept for comparison) and the trails of its scene (solid
/// [`Role::Path`] lines), named after the change.
#[derive(Clone, Debug, PartialEq)]
pub struct KeptRun {
    /// The legend name, e.g. `before Kp 20 → 60 at t = 2.10 s`.
    pub label: String,
    /// Per plot of the experiment, its main series at the old run's end.
    pub series: Vec<Option<Series>>,
    /// The old run's trails, world coordinates (drawn as ghosts).
    pub trails: Vec<Vec<DVec2>>,
}

impl KeptRun {
    /// What `abandoned` (the state at the old run's end) leaves to compare
    /// with, under `label`.
    #[must_use]
    pub fn of(abandoned: &dyn Lab, label: String) -> Self {
        let mut run = Self::plots_of(abandoned, label);
        let mut scene = Scene::default();
        abandoned.scene(&mut scene);
        run.trails = scene
            .items
            .iter()
            .filter_map(|item| match item {
                Item::Polyline {
                    points,
                    role: Role::Path,
                    dashed: false,
                    closed: false,
                    ..
                } if points.len() > 1 => Some(points.clone()),
                _ => None,
            })
            .collect();
        run
    }

    /// [`KeptRun::of`] without the trails (no scene is built): the plots'
    /// main series alone, cheap enough to take before every input in case
    /// it starts the run again.
    #[must_use]
    pub fn plots_of(run: &dyn Lab, label: String) -> Self {
        let series = run
            .plots()
            .iter()
            .map(|p| p.series.iter().find(|s| !s.comparison).cloned())
            .collect();
        Self {
            label,
            series,
            trails: Vec::new(),
        }
    }

    /// The trails as ghosts: dimmed and dashed, so they differ from the
    /// live run's by more than colour.
    pub fn ghosts(&self, out: &mut Scene) {
        for points in &self.trails {
            out.push(Item::Polyline {
                points: points.clone(),
                width_px: 2.0,
                role: Role::Ghost,
                dashed: true,
                closed: false,
            });
        }
    }
}

/// Keeps `run`, the newest, dropping the oldest beyond [`MAX_KEPT`].
pub fn keep(kept: &mut Vec<KeptRun>, run: KeptRun) {
    if kept.len() == MAX_KEPT {
        kept.remove(0);
    }
    kept.push(run);
}

/// The plots as the page shows them: each of `plots` followed by
/// [`MAX_KEPT`] comparison series, empty until a run is kept (so the
/// legend has their places from the start), filled from `kept`, oldest
/// first. `serial` (bumped whenever `kept` changes) goes into each
/// plot's [`Plot::revision`], so a new kept run redraws the plots.
#[must_use]
pub fn with_kept(plots: &[Plot], kept: &[KeptRun], serial: u64) -> Vec<Plot> {
    plots
        .iter()
        .enumerate()
        .map(|(i, plot)| plot_with_kept(plot, i, kept, serial))
        .collect()
}

/// [`with_kept`] for one plot, the `index`-th of its experiment's.
#[must_use]
pub fn plot_with_kept(plot: &Plot, index: usize, kept: &[KeptRun], serial: u64) -> Plot {
    let mut plot = plot.clone();
    let unit = plot.y_unit;
    for (k, role) in kept_roles(&plot).iter().enumerate() {
        let run = kept.get(k);
        let mut s = run
            .and_then(|r| r.series.get(index).cloned().flatten())
            .unwrap_or_else(|| Series::new("", unit, *role));
        s.label = run.map_or_else(|| format!("kept run {}", k + 1), |r| r.label.clone());
        s.role = *role;
        s.comparison = true;
        plot.series.push(s);
    }
    plot.revision = plot.revision.wrapping_add(serial << 40);
    plot
}

/// A parameter's value as a branch's name says it: the choice or switch
/// label, or the number with its unit (`60`, `2.5 m`, `12°`).
#[must_use]
pub fn value_text(spec: &ParamSpec, value: f64) -> String {
    match spec.kind {
        ParamKind::Toggle { off, on } => (if value >= 0.5 { on } else { off }).to_owned(),
        ParamKind::Choice(names) => names
            .get(value as usize)
            .map_or_else(|| format_number(value, 0), |n| (*n).to_owned()),
        _ => {
            let decimals = (0..6)
                .find(|&d| (spec.step * 10f64.powi(d)).fract().abs() < 1e-9)
                .unwrap_or(6) as usize;
            with_unit(&format_number(value, decimals), spec.unit)
        }
    }
}

/// Whether an input started the run again: the main plot's progress
/// ([`plot_x`]) went back, or its samples went, where it had some before.
/// The plots, the status and the time count from a run's start, so the
/// page's clock and timeline start again there too.
#[must_use]
pub fn restarted(before: Option<f64>, after: Option<f64>) -> bool {
    before.is_some_and(|b| after.is_none_or(|a| a < b))
}

/// The name of the run a branch leaves behind: what changed and when,
/// `before Kp 20 → 60 at t = 2.10 s`. The first parameter whose value
/// differs between `before` and `after` (values in the order of `specs`)
/// names the change; with none, `cause` does (an action's label, "a
/// drag"), else "the change".
#[must_use]
pub fn branch_label(
    specs: &[ParamSpec],
    before: &[Option<f64>],
    after: &[Option<f64>],
    cause: Option<&str>,
    t_s: f64,
) -> String {
    format!(
        "before {} at t = {} s",
        change_text(specs, before, after, cause),
        format_fixed(t_s, 2)
    )
}

/// The name of a run that a change started again from its start (see
/// [`restarted`]): `before Kd 2 → 10 restarted the run`, named as
/// [`branch_label`] names a change. The runs share no moment after their
/// start, so no time is named.
#[must_use]
pub fn restart_label(
    specs: &[ParamSpec],
    before: &[Option<f64>],
    after: &[Option<f64>],
    cause: Option<&str>,
) -> String {
    format!(
        "before {} restarted the run",
        change_text(specs, before, after, cause)
    )
}

/// What changed, as a branch's name says it (see [`branch_label`]).
fn change_text(
    specs: &[ParamSpec],
    before: &[Option<f64>],
    after: &[Option<f64>],
    cause: Option<&str>,
) -> String {
    let changed = specs
        .iter()
        .zip(before.iter().zip(after))
        .find(|(_, (b, a))| b != a);
    match changed {
        Some((spec, (b, a))) => {
            let text =
                |v: &Option<f64>| v.map_or_else(|| "unset".to_owned(), |v| value_text(spec, v));
            format!("{} {} → {}", spec.label, text(b), text(a))
        }
        None => cause.unwrap_or("the change").to_owned(),
    }
}
