//! Experiment 4 — a differential-drive robot driven to clicked waypoints.
//!
//! The robot is a unicycle ([`crate::mobile::unicycle`]):
//! `ẋ = v cos θ, ẏ = v sin θ, θ̇ = ω`, integrated with explicit Euler (the
//! lab description's default) or RK4 in [`SUBSTEPS`] sub-steps of each fixed
//! frame step. The proportional controller of [`GoToGoal`] steers it:
//!
//! ```text
//! eθ = wrap(atan2(dy, dx) − θ) ∈ [−π, π]    ω = clamp(Kω·eθ, ±ω_max)
//! v  = clamp(Kv·d·max(0, cos eθ), 0, v_max)
//! ```
//!
//! so it turns on the spot while the goal is behind it, then drives in
//! (Siegwart, Nourbakhsh & Scaramuzza, *Introduction to Autonomous Mobile
//! Robots*, 2nd ed., 2011, §3.6.2). Wheel rim speeds follow from the track
//! `b`: `v_L = v − ωb/2`, `v_R = v + ωb/2` (ibid. §3.2.2).
//!
//! Clicks queue up to [`MAX_WAYPOINTS`] numbered waypoints; they are
//! parameters (`w1x`, `w1y`, … `w6y`), so a link reproduces the route and the
//! run. A [`WaypointFollower`] visits them in order and keeps one
//! [`RunStats`] "run card" per waypoint reached. The robot starts in the
//! middle of the field facing +x ([`START`]), so the left half of the field
//! is behind it.
//!
//! This file is the model (parameters, state, step, input, actions, link
//! state); `view.rs` draws it and words its readouts and status, `quiz.rs`
//! holds the generated questions and `tests.rs` its tests.

use crate::experiment::{
    check_param, with_coordinate, ActionSpec, Experiment, Input, Notices, ParamError, ParamSpec,
    Sanitized, Tone,
};
use crate::mobile::field::{push_trail, snap_into};
use crate::mobile::go_to_goal::{Command, GoToGoal, RunStats, WaypointFollower};
use crate::mobile::unicycle::{wheel_speeds, Integrator, Pose};
use crate::plot::{Axis, Band, Marker, Plot, Series, SeriesRole, XWindow};
use glam::DVec2;

/// Most waypoints queued at once (each is two URL parameters).
pub const MAX_WAYPOINTS: usize = 6;
/// The field shown, metres: `[0, FIELD_W_M] × [0, FIELD_H_M]`.
pub const FIELD_W_M: f64 = 8.0;
pub const FIELD_H_M: f64 = 6.0;
/// The start pose: the middle of the field, facing +x, so that the whole
/// left half of the field lies behind the robot (`|eθ| > 90°`: it turns on
/// the spot before it rolls) and the right half in front of it.
pub const START: Pose = Pose::new(0.5 * FIELD_W_M, 0.5 * FIELD_H_M, 0.0);
/// Integration sub-steps per fixed step (the controller is sampled once per step).
pub const SUBSTEPS: usize = 4;
/// Arrival radius, metres.
pub const TOLERANCE_M: f64 = 0.05;
/// A press within this distance of a waypoint grabs it, metres.
const GRAB_M: f64 = 0.25;
/// A press that moves less than this before release is a tap, metres.
const TAP_SLOP_M: f64 = 0.08;
/// Plot samples are taken every this many steps (30 Hz at 60 steps/s).
const PLOT_EVERY: u64 = 2;
/// Most shaded "at a limit" intervals kept on the plot.
const MAX_BANDS: usize = 60;

const INTEGRATORS: &[&str] = &["Euler", "RK4"];

const PARAMS: &[ParamSpec] = &[
    ParamSpec::slider("kw", "Kω", "1/s", 0.2, 10.0, 0.1, 3.5),
    ParamSpec::slider("kv", "Kv", "1/s", 0.1, 3.0, 0.05, 1.2),
    ParamSpec::slider("vmax", "Max v", "m/s", 0.1, 2.0, 0.05, 1.1),
    ParamSpec::slider("wmax", "Max ω", "rad/s", 0.2, 4.0, 0.1, 1.4),
    ParamSpec::slider("track", "Track width b", "m", 0.1, 0.6, 0.01, 0.3),
    ParamSpec::choice("integ", "Integrator", INTEGRATORS, 0),
    ParamSpec::optional_number("w1x", "Waypoint 1 x", "m", 0.0, FIELD_W_M).in_group("Waypoints"),
    ParamSpec::optional_number("w1y", "Waypoint 1 y", "m", 0.0, FIELD_H_M).in_group("Waypoints"),
    ParamSpec::optional_number("w2x", "Waypoint 2 x", "m", 0.0, FIELD_W_M).in_group("Waypoints"),
    ParamSpec::optional_number("w2y", "Waypoint 2 y", "m", 0.0, FIELD_H_M).in_group("Waypoints"),
    ParamSpec::optional_number("w3x", "Waypoint 3 x", "m", 0.0, FIELD_W_M).in_group("Waypoints"),
    ParamSpec::optional_number("w3y", "Waypoint 3 y", "m", 0.0, FIELD_H_M).in_group("Waypoints"),
    ParamSpec::optional_number("w4x", "Waypoint 4 x", "m", 0.0, FIELD_W_M).in_group("Waypoints"),
    ParamSpec::optional_number("w4y", "Waypoint 4 y", "m", 0.0, FIELD_H_M).in_group("Waypoints"),
    ParamSpec::optional_number("w5x", "Waypoint 5 x", "m", 0.0, FIELD_W_M).in_group("Waypoints"),
    ParamSpec::optional_number("w5y", "Waypoint 5 y", "m", 0.0, FIELD_H_M).in_group("Waypoints"),
    ParamSpec::optional_number("w6x", "Waypoint 6 x", "m", 0.0, FIELD_W_M).in_group("Waypoints"),
    ParamSpec::optional_number("w6y", "Waypoint 6 y", "m", 0.0, FIELD_H_M).in_group("Waypoints"),
];

const ACTIONS: &[ActionSpec] = &[
    ActionSpec {
        key: "reset",
        label: "Reset robot",
    },
    ActionSpec {
        key: "clear",
        label: "Clear waypoints",
    },
];

/// The slot (0-based) of a waypoint key `w3x` → 2, and whether it is x.
fn slot_of(key: &str) -> Option<(usize, bool)> {
    crate::experiment::point_slot(key, 'w', MAX_WAYPOINTS)
}

mod quiz;
#[cfg(test)]
mod tests;
mod view;

pub use quiz::quiz_generator;

/// A press in progress. On a waypoint (`slot`) a tap removes it and a drag
/// moves it; elsewhere a tap queues a new waypoint when it is released, and
/// a drag does nothing (on a touch screen it is a swipe that scrolls the page).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Press {
    slot: Option<usize>,
    at: DVec2,
    moved: bool,
}

/// State of the differential-drive experiment.
#[derive(Clone, Debug)]
pub struct DiffDrive {
    controller: GoToGoal,
    track_m: f64,
    integrator: Integrator,
    /// Waypoint slots (`w1…w6`); the route is the filled ones, in slot order.
    slots: [Option<DVec2>; MAX_WAYPOINTS],
    /// The robot, its queue (the route's waypoints not reached yet) and the
    /// run cards of those reached (`completed[i]` belongs to the i-th filled slot).
    follower: WaypointFollower,
    trail: Vec<DVec2>,
    time_s: f64,
    steps: u64,
    press: Option<Press>,
    /// The waypoint the arrow keys move (the last one placed or grabbed).
    selected: Option<usize>,
    /// "all 6 waypoints are queued" while a click could not queue one.
    notices: Notices,
    /// v, ω, vL, vR against time.
    plots: [Plot; 1],
    /// The canvas's size (CSS px) as the page last told it: the run cards'
    /// labels are placed clear of the robot and the waypoints at its scale.
    /// View state, never in the link.
    viewport_px: Option<DVec2>,
}

fn new_plots() -> [Plot; 1] {
    let mut p = Plot::new(
        "motion",
        "Speeds and turn rate",
        ("Time", "s"),
        ("v, vL, vR (m/s); ω (rad/s)", ""),
        vec![
            Series::new("v", "m/s", SeriesRole::Primary),
            Series::new("ω", "rad/s", SeriesRole::Secondary),
            Series::new("vL", "m/s", SeriesRole::Tertiary),
            Series::new("vR", "m/s", SeriesRole::Quaternary),
        ],
    );
    p.window = XWindow::Rolling(30.0);
    [p]
}

impl Default for DiffDrive {
    fn default() -> Self {
        let mut follower = WaypointFollower::new(START);
        follower.substeps = SUBSTEPS;
        let mut d = Self {
            controller: GoToGoal {
                tolerance_m: TOLERANCE_M,
                ..GoToGoal::default()
            },
            track_m: PARAMS[4].default,
            integrator: Integrator::Euler,
            slots: [None; MAX_WAYPOINTS],
            follower,
            trail: Vec::new(),
            time_s: 0.0,
            steps: 0,
            press: None,
            selected: None,
            notices: Notices::default(),
            plots: new_plots(),
            viewport_px: None,
        };
        d.restart();
        d
    }
}

impl DiffDrive {
    /// The route: the filled slots' indices, in order.
    fn route(&self) -> Vec<usize> {
        (0..MAX_WAYPOINTS)
            .filter(|&i| self.slots[i].is_some())
            .collect()
    }

    /// The waypoints in visiting order, metres.
    #[must_use]
    pub fn waypoints(&self) -> Vec<DVec2> {
        self.slots.iter().flatten().copied().collect()
    }

    /// How many waypoints of the route have been reached in this run.
    #[must_use]
    pub fn reached(&self) -> usize {
        self.follower.completed.len()
    }

    /// The run cards of the waypoints reached, in order.
    #[must_use]
    pub fn run_cards(&self) -> &[RunStats] {
        &self.follower.completed
    }

    /// The robot's pose.
    #[must_use]
    pub fn pose(&self) -> Pose {
        self.follower.pose
    }

    /// The last command applied.
    #[must_use]
    pub fn command(&self) -> Command {
        self.follower.last_command
    }

    /// `(v_L, v_R)` of the last command, m/s.
    #[must_use]
    pub fn wheels(&self) -> (f64, f64) {
        let c = self.command();
        wheel_speeds(c.v_mps, c.omega_radps, self.track_m)
    }

    /// Back to the start pose with the whole route to drive again.
    fn restart(&mut self) {
        self.follower.reset(START);
        self.sync_follower();
        for g in self.waypoints() {
            self.follower.push_goal(g);
        }
        self.trail.clear();
        self.trail.push(START.position());
        self.time_s = 0.0;
        self.steps = 0;
        self.press = None;
        for plot in &mut self.plots {
            plot.clear();
            plot.bands.clear();
        }
    }

    fn sync_follower(&mut self) {
        self.follower.controller = self.controller;
        self.follower.integrator = self.integrator;
        self.follower.substeps = SUBSTEPS;
    }

    /// Rebuilds the queue from the route after waypoints changed: the
    /// waypoints not reached yet, in order.
    fn rebuild_queue(&mut self) {
        let reached = self.reached().min(self.waypoints().len());
        self.follower.completed.truncate(reached);
        self.follower.queue = self.waypoints().into_iter().skip(reached).collect();
    }

    /// Moves every filled slot to the front, keeping the order.
    fn compact(&mut self) {
        let filled: Vec<DVec2> = self.waypoints();
        self.slots = [None; MAX_WAYPOINTS];
        for (i, p) in filled.into_iter().enumerate() {
            self.slots[i] = Some(p);
        }
        self.selected = None;
    }

    /// Queues a waypoint at `p` (snapped, clamped into the field). When every
    /// slot is used, the oldest waypoint already reached makes room; when
    /// none has been reached, nothing is queued and the status says why.
    /// Returns the slot used.
    fn add_waypoint(&mut self, p: DVec2) -> Option<usize> {
        if !p.is_finite() {
            return None;
        }
        let p = snap_into(p, FIELD_W_M, FIELD_H_M);
        let last = self.slots.iter().rposition(Option::is_some);
        let mut slot = last.map_or(0, |i| i + 1);
        if slot >= MAX_WAYPOINTS {
            if self.route().len() < MAX_WAYPOINTS {
                self.compact();
            } else if self.reached() > 0 {
                self.follower.completed.remove(0);
                self.slots[0] = None;
                self.compact();
            } else {
                self.notices.post(
                    "all 6 waypoints are queued: tap one to remove it, or Clear waypoints",
                    Tone::Warning,
                );
                return None;
            }
            slot = self.route().len();
        }
        let was_idle = self.follower.queue.is_empty();
        self.slots[slot] = Some(p);
        self.follower.push_goal(p);
        if was_idle {
            self.follower.current = RunStats::default();
        }
        self.notices.clear();
        self.selected = Some(slot);
        Some(slot)
    }

    /// Removes the waypoint in `slot` (the later ones move up a number).
    fn remove_waypoint(&mut self, slot: usize) {
        let route = self.route();
        let Some(pos) = route.iter().position(|&s| s == slot) else {
            return;
        };
        let reached = self.reached();
        if pos < reached {
            self.follower.completed.remove(pos);
        } else if pos == reached {
            // The active goal is gone: a fresh run card for the next one.
            self.follower.current = RunStats::default();
        }
        self.slots[slot] = None;
        self.compact();
        self.rebuild_queue();
        self.notices.clear();
    }

    /// Moves the waypoint in `slot` to `p` (snapped, clamped).
    fn move_waypoint(&mut self, slot: usize, p: DVec2) {
        if !p.is_finite() || self.slots[slot].is_none() {
            return;
        }
        self.slots[slot] = Some(snap_into(p, FIELD_W_M, FIELD_H_M));
        self.rebuild_queue();
    }

    /// The waypoint slot nearest `p` within `radius_m`.
    fn waypoint_near(&self, p: DVec2, radius_m: f64) -> Option<usize> {
        let mut best: Option<(usize, f64)> = None;
        for (i, w) in self.slots.iter().enumerate() {
            if let Some(w) = w {
                let d = (*w - p).length();
                if d <= radius_m && best.is_none_or(|(_, bd)| d < bd) {
                    best = Some((i, d));
                }
            }
        }
        best.map(|(i, _)| i)
    }

    fn record(&mut self, cmd: &Command) {
        let (vl, vr) = wheel_speeds(cmd.v_mps, cmd.omega_radps, self.track_m);
        let t = self.time_s;
        let plot = &mut self.plots[0];
        if cmd.v_limited || cmd.omega_limited {
            let dt = crate::clock::Clock::DT_S;
            match plot.bands.last_mut() {
                Some(b) if (t - dt - b.hi).abs() < 1e-9 => b.hi = t,
                _ => {
                    plot.bands.push(Band {
                        axis: Axis::X,
                        lo: t - dt,
                        hi: t,
                        label: "v or ω at its limit".into(),
                    });
                    if plot.bands.len() > MAX_BANDS {
                        plot.bands.remove(0);
                    }
                }
            }
        }
        // The page redraws a plot when it is touched: only when a sample is added.
        if self.steps.is_multiple_of(PLOT_EVERY) || cmd.arrived {
            plot.push_bounded(t, &[cmd.v_mps, cmd.omega_radps, vl, vr]);
        }
    }
}

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "A goal behind the robot",
        description: "The goal is straight behind: the robot first turns on the spot at its turn limit, then drives.",
        query: "w1x=1&w1y=3",
    },
    crate::experiment::Preset {
        name: "Lazy steering: wide arcs",
        description: "A low Kω on a two-waypoint route: the robot turns late and drives a longer path than with the default gain.",
        query: "kw=0.5&w1x=7&w1y=5&w2x=1&w2y=5",
    },
];

impl Experiment for DiffDrive {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

    fn id(&self) -> &'static str {
        "diffdrive"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        if let Some((slot, is_x)) = slot_of(key) {
            return self.slots[slot].map(|p| if is_x { p.x } else { p.y });
        }
        Some(match key {
            "kw" => self.controller.k_omega_per_s,
            "kv" => self.controller.k_v_per_s,
            "vmax" => self.controller.max_v_mps,
            "wmax" => self.controller.max_omega_radps,
            "track" => self.track_m,
            "integ" => match self.integrator {
                Integrator::Euler => 0.0,
                Integrator::Rk4 => 1.0,
            },
            _ => return None,
        })
    }

    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        if let Some((slot, _)) = slot_of(key) {
            match self.slots[slot] {
                Some(p) => {
                    self.slots[slot] = Some(with_coordinate(Some(p), p, key, v));
                    self.rebuild_queue();
                }
                None => {
                    let from = snap_into(self.pose().position(), FIELD_W_M, FIELD_H_M);
                    self.slots[slot] = Some(with_coordinate(None, from, key, v));
                    let pos = self.route().iter().position(|&s| s == slot).unwrap_or(0);
                    if pos < self.reached() {
                        // Inserted before a waypoint already reached: drive the route again.
                        self.restart();
                    } else {
                        if pos == self.reached() {
                            self.follower.current = RunStats::default();
                        }
                        self.rebuild_queue();
                    }
                }
            }
            return Ok(applied);
        }
        match key {
            "kw" => self.controller.k_omega_per_s = v,
            "kv" => self.controller.k_v_per_s = v,
            "vmax" => self.controller.max_v_mps = v,
            "wmax" => self.controller.max_omega_radps = v,
            "track" => self.track_m = v,
            "integ" => {
                self.integrator = if v >= 0.5 {
                    Integrator::Rk4
                } else {
                    Integrator::Euler
                }
            }
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        self.sync_follower();
        Ok(applied)
    }

    fn actions(&self) -> &'static [ActionSpec] {
        ACTIONS
    }

    fn action(&mut self, key: &str) -> Result<(), ParamError> {
        match key {
            "reset" => self.restart(),
            "clear" => {
                self.slots = [None; MAX_WAYPOINTS];
                self.selected = None;
                self.notices.clear();
                self.follower.queue.clear();
                self.follower.completed.clear();
                self.follower.current = RunStats::default();
                self.follower.last_command = Command::default();
            }
            _ => return Err(ParamError::UnknownAction { key: key.into() }),
        }
        Ok(())
    }

    fn input(&mut self, input: Input) {
        match input {
            Input::PointerDown(p) => {
                if !p.is_finite() {
                    return;
                }
                let slot = self.waypoint_near(p, GRAB_M);
                if slot.is_some() {
                    self.selected = slot;
                }
                self.press = Some(Press {
                    slot,
                    at: p,
                    moved: false,
                });
            }
            Input::PointerMove { pos, pressed: true } => {
                let Some(mut press) = self.press else { return };
                if !pos.is_finite() {
                    return;
                }
                if (pos - press.at).length() > TAP_SLOP_M {
                    press.moved = true;
                }
                self.press = Some(press);
                if let (Some(slot), true) = (press.slot, press.moved) {
                    self.move_waypoint(slot, pos);
                }
            }
            Input::PointerMove { pressed: false, .. } => {}
            Input::PointerUp(_) => match self.press.take() {
                Some(Press {
                    slot: Some(slot),
                    moved: false,
                    ..
                }) => self.remove_waypoint(slot),
                Some(Press {
                    slot: None,
                    moved: false,
                    at,
                }) => {
                    self.add_waypoint(at);
                }
                _ => {}
            },
            Input::Nudge(delta) => {
                if !delta.is_finite() {
                    return;
                }
                let target = self
                    .selected
                    .filter(|&s| self.slots[s].is_some())
                    .or_else(|| self.route().last().copied());
                match target {
                    Some(slot) => {
                        let p = self.slots[slot].unwrap_or(DVec2::ZERO) + delta;
                        self.move_waypoint(slot, p);
                        self.selected = Some(slot);
                    }
                    None => {
                        self.add_waypoint(self.pose().position() + delta);
                    }
                }
            }
        }
    }

    fn step(&mut self, dt_s: f64) {
        if !crate::clock::valid_dt(dt_s) {
            return;
        }
        if self.follower.goal().is_none() {
            return;
        }
        self.sync_follower();
        let cmd = self.follower.step(dt_s);
        self.time_s += dt_s;
        self.steps += 1;
        let p = self.pose().position();
        push_trail(&mut self.trail, p);
        self.record(&cmd);
        if cmd.arrived {
            // A reached waypoint makes room for a new one.
            self.notices.clear();
            let n = self.reached();
            let t = self.time_s;
            self.plots[0].markers.push(Marker {
                x: t,
                y: 0.0,
                label: format!("reached {n}"),
            });
        }
    }

    fn animated(&self) -> bool {
        true
    }

    /// The robot back to the start pose, driving the same route again.
    fn reset(&mut self) {
        self.restart();
    }

    fn plots(&self) -> &[Plot] {
        &self.plots
    }

    /// The waypoints, by slot (`w2` is the one the link keys `w2x`, `w2y` hold).
    fn handles(&self) -> Vec<crate::experiment::Handle> {
        self.route()
            .into_iter()
            .filter_map(|i| {
                let at = self.slots[i]?;
                Some(crate::experiment::Handle::new(
                    format!("w{}", i + 1),
                    format!("Waypoint {}", i + 1),
                    at,
                ))
            })
            .collect()
    }

    /// A drag of waypoint `id` to `to`: grabbed (a press on it), moved, released.
    /// Grabbed by slot, so a waypoint on top of another is still the one moved,
    /// and a short move is never taken for a tap (which removes it).
    fn move_handle(&mut self, id: &str, to: DVec2) -> bool {
        let Some((slot, _)) = crate::experiment::point_slot(&format!("{id}x"), 'w', MAX_WAYPOINTS)
        else {
            return false;
        };
        let Some(at) = self.slots[slot] else {
            return false;
        };
        if !to.is_finite() {
            return false;
        }
        self.selected = Some(slot);
        self.press = Some(Press {
            slot: Some(slot),
            at,
            moved: true,
        });
        crate::experiment::finish_drag(self, to)
    }

    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        self.waypoint_near(p, tolerance_m.max(0.0)).is_some()
    }

    fn animating(&self) -> bool {
        self.follower.goal().is_some()
    }
}
