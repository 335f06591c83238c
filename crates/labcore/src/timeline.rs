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
//!   of the input itself (a pointer's modifiers, a file's text) to go wrong.
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
//! Steps are counted as the shell's clock counts them
//! ([`crate::clock::Clock::steps`]): one [`crate::Experiment::step`] of
//! [`crate::clock::Clock::DT_S`] each.

use crate::plot::Plot;
use crate::Lab;

/// A kept copy of the experiment at one step.
struct Snapshot {
    step: u64,
    lab: Box<dyn Lab>,
    /// Taken after an input (or at the start): never thinned out.
    pinned: bool,
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
            bytes,
        }
    }
}

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
}

impl Timeline {
    /// The first snapshot interval, steps (0.53 s at 60 steps a second).
    pub const FIRST_INTERVAL: u64 = 32;
    /// What the snapshots may hold, bytes (estimated; see the module).
    pub const BUDGET_BYTES: usize = 16 << 20;

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
            interval: Self::FIRST_INTERVAL,
            dirty: false,
            budget_bytes,
            last_replay: 0,
            worst_replay: 0,
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
    /// with no input on the way (so a link of the start and the time
    /// reproduces it).
    #[must_use]
    pub fn unbroken_to(&self, step: u64) -> bool {
        self.first() == 0
            && !self
                .snaps
                .iter()
                .any(|s| s.pinned && s.step > 0 && s.step <= step)
    }

    /// Steps replayed by the last [`Timeline::state_at`].
    #[must_use]
    pub fn last_replay(&self) -> u64 {
        self.last_replay
    }

    /// The most steps any [`Timeline::state_at`] replayed.
    #[must_use]
    pub fn worst_replay(&self) -> u64 {
        self.worst_replay
    }

    /// An input is about to change the state shown at `step`: from there on
    /// the run is a new one. The recorded future after `step` is dropped
    /// (the run now ends at `step`), and the state the input leaves is
    /// snapshot by the next [`Timeline::commit`].
    pub fn input_at(&mut self, step: u64) {
        let step = step.max(self.first()).min(self.end);
        while self.snaps.len() > 1 && self.snaps[self.snaps.len() - 1].step > step {
            self.pop();
        }
        self.end = step;
        self.dirty = true;
    }

    /// Takes the snapshot an input asked for ([`Timeline::input_at`]), if
    /// any, of `exp` as the input left it. Call it before the next step and
    /// before going to another step.
    pub fn commit(&mut self, exp: &dyn Lab) {
        if !self.dirty {
            return;
        }
        self.dirty = false;
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
    /// steps; otherwise it costs nothing.
    pub fn stepped(&mut self, exp: &dyn Lab) {
        debug_assert!(!self.dirty, "Timeline::stepped before Timeline::commit");
        self.end += 1;
        if self.end.is_multiple_of(self.interval) {
            self.push(Snapshot::of(exp, self.end, false));
        }
    }

    /// The state at `step` (clamped to [`Timeline::first`]..=
    /// [`Timeline::end`]) and the step it is at: a copy of the latest
    /// snapshot at or before it, stepped on by `step_once` (one fixed step;
    /// the shell's keeps the instructor's locks) at most
    /// [`Timeline::interval`] − 1 times.
    pub fn state_at(
        &mut self,
        step: u64,
        step_once: &mut dyn FnMut(&mut dyn Lab),
    ) -> (u64, Box<dyn Lab>) {
        let step = step.max(self.first()).min(self.end);
        let i = self.snaps.partition_point(|s| s.step <= step).max(1) - 1;
        let snap = &self.snaps[i];
        let mut lab = snap.lab.snapshot();
        let replay = step - snap.step;
        for _ in 0..replay {
            step_once(lab.as_mut());
        }
        self.last_replay = replay;
        self.worst_replay = self.worst_replay.max(replay);
        (step, lab)
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
            .any(|s| s.pinned && s.step > from && s.step <= to);
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

/// The bytes a plot's samples take: the default of
/// [`crate::Experiment::state_bytes`].
#[must_use]
pub fn plots_bytes(plots: &[Plot]) -> usize {
    plots
        .iter()
        .flat_map(|p| &p.series)
        .map(|s| (s.x.capacity() + s.y.capacity()) * std::mem::size_of::<f64>())
        .sum()
}
