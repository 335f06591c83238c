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
//! Robots*, 2nd ed., 2011, §3.6.2.4). Wheel rim speeds follow from the track
//! `b`: `v_L = v − ωb/2`, `v_R = v + ωb/2` (ibid. §3.2.1).
//!
//! Clicks queue up to [`MAX_WAYPOINTS`] numbered waypoints; they are
//! parameters (`w1x`, `w1y`, … `w6y`), so a link reproduces the route and the
//! run. A [`WaypointFollower`] visits them in order and keeps one
//! [`RunStats`] "run card" per waypoint reached.

use crate::experiment::{
    check_param, format_degrees, format_fixed, format_metres, with_coordinate, ActionSpec,
    Experiment, Input, ParamError, ParamSpec, Readout, Sanitized, Status, Tone,
};
use crate::mobile::go_to_goal::{Command, GoToGoal, RunStats, WaypointFollower};
use crate::mobile::unicycle::{wheel_speeds, Integrator, Pose};
use crate::plot::{Axis, Band, Marker, Plot, Series, SeriesRole, XWindow};
use crate::quiz::{format_number, Draw, Generator};
use crate::rng::Lcg64;
use crate::scene::{Item, Role, Scene, ViewBox};
use glam::DVec2;

/// Most waypoints queued at once (each is two URL parameters).
pub const MAX_WAYPOINTS: usize = 6;
/// The field shown, metres: `[0, FIELD_W_M] × [0, FIELD_H_M]`.
pub const FIELD_W_M: f64 = 8.0;
pub const FIELD_H_M: f64 = 6.0;
/// The start pose: the lower-left corner, facing +x.
pub const START: Pose = Pose::new(0.6, 0.6, 0.0);
/// Integration sub-steps per fixed step (the controller is sampled once per step).
pub const SUBSTEPS: usize = 4;
/// Arrival radius, metres.
pub const TOLERANCE_M: f64 = 0.05;
/// A press within this distance of a waypoint grabs it, metres.
const GRAB_M: f64 = 0.25;
/// A press that moves less than this before release is a tap, metres.
const TAP_SLOP_M: f64 = 0.08;
/// Drawn body radius of the robot, metres.
pub const BODY_RADIUS_M: f64 = 0.18;
/// Plots keep at most this many samples per series (older ones are dropped).
pub const MAX_PLOT_SAMPLES: usize = 3000;
/// The trail keeps at most this many points (older ones are dropped).
pub const MAX_TRAIL_POINTS: usize = 6000;
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
    ParamSpec::optional_number("w1x", "Waypoint 1 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("w1y", "Waypoint 1 y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("w2x", "Waypoint 2 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("w2y", "Waypoint 2 y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("w3x", "Waypoint 3 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("w3y", "Waypoint 3 y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("w4x", "Waypoint 4 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("w4y", "Waypoint 4 y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("w5x", "Waypoint 5 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("w5y", "Waypoint 5 y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("w6x", "Waypoint 6 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("w6y", "Waypoint 6 y", "m", 0.0, FIELD_H_M),
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
    let rest = key.strip_prefix('w')?;
    let (digits, is_x) = match rest.strip_suffix('x') {
        Some(d) => (d, true),
        None => (rest.strip_suffix('y')?, false),
    };
    let n: usize = digits.parse().ok()?;
    n.checked_sub(1)
        .filter(|i| *i < MAX_WAYPOINTS)
        .map(|i| (i, is_x))
}

/// Rounds a clicked coordinate to whole centimetres, so the link (three
/// decimals) reproduces it exactly.
#[must_use]
pub(crate) fn snap_cm(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

/// A clicked point snapped to centimetres and clamped into `[0, w] × [0, h]`.
#[must_use]
pub(crate) fn snap_into(p: DVec2, w: f64, h: f64) -> DVec2 {
    DVec2::new(snap_cm(p.x.clamp(0.0, w)), snap_cm(p.y.clamp(0.0, h)))
}

/// Appends one sample per series at `x` and drops the oldest quarter once a
/// series holds more than [`MAX_PLOT_SAMPLES`], so a long run stays bounded.
pub(crate) fn push_bounded(plot: &mut Plot, x: f64, ys: &[f64]) {
    for (s, y) in plot.series.iter_mut().zip(ys) {
        s.push(x, *y);
    }
    for s in &mut plot.series {
        if s.len() > MAX_PLOT_SAMPLES {
            let n = MAX_PLOT_SAMPLES / 4;
            s.x.drain(..n);
            s.y.drain(..n);
        }
    }
    if let Some(first) = plot.series.first().and_then(|s| s.x.first()).copied() {
        plot.markers.retain(|m| m.x >= first);
        plot.bands.retain(|b| b.hi >= first);
    }
    plot.touch();
}

/// Appends `p` to a trail unless it is within 5 mm of the last point; keeps
/// at most [`MAX_TRAIL_POINTS`].
pub(crate) fn push_trail(trail: &mut Vec<DVec2>, p: DVec2) {
    if !p.is_finite() || trail.last().is_some_and(|q| (*q - p).length() < 0.005) {
        return;
    }
    trail.push(p);
    if trail.len() > MAX_TRAIL_POINTS {
        trail.drain(..MAX_TRAIL_POINTS / 4);
    }
}

/// Draws a differential-drive robot at `pose`: a round body with a nose
/// showing the heading and two wheels `track_m` apart.
pub(crate) fn draw_robot(out: &mut Scene, pose: Pose, track_m: f64) {
    if !pose.is_finite() {
        return;
    }
    let c = pose.position();
    let f = pose.heading();
    let left = f.perp();
    let body: Vec<DVec2> = (0..20)
        .map(|i| {
            let a = pose.theta_rad + std::f64::consts::TAU * f64::from(i) / 20.0;
            let (s, co) = crate::math::sin_cos(a);
            c + DVec2::new(co, s) * BODY_RADIUS_M
        })
        .collect();
    out.push(Item::Polygon {
        points: body,
        role: Role::Robot,
    });
    let half = 0.5 * track_m.clamp(0.05, 1.0);
    for side in [1.0, -1.0] {
        let w = c + left * side * half;
        let (along, across) = (f * 0.09, left * 0.025);
        out.push(Item::Polygon {
            points: vec![
                w - along - across,
                w + along - across,
                w + along + across,
                w - along + across,
            ],
            role: Role::Base,
        });
    }
    out.push(Item::Line {
        from: c,
        to: c + f * BODY_RADIUS_M * 1.35,
        width_px: 3.0,
        role: Role::Base,
        dashed: false,
    });
}

/// A light 1 m grid over `[0, w] × [0, h]` as one batch of segments.
pub(crate) fn draw_field(out: &mut Scene, w: f64, h: f64) {
    let mut segments = Vec::new();
    let mut x = 0.0;
    while x <= w + 1e-9 {
        segments.push((DVec2::new(x, 0.0), DVec2::new(x, h)));
        x += 1.0;
    }
    let mut y = 0.0;
    while y <= h + 1e-9 {
        segments.push((DVec2::new(0.0, y), DVec2::new(w, y)));
        y += 1.0;
    }
    out.push(Item::Segments {
        segments,
        width_px: 1.0,
        role: Role::Grid,
    });
}

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
    notice: Option<&'static str>,
    /// v, ω, vL, vR against time.
    plots: [Plot; 1],
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
            notice: None,
            plots: new_plots(),
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

    /// Back to the corner with the whole route to drive again.
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
                self.notice =
                    Some("all 6 waypoints are queued: tap one to remove it, or Clear waypoints");
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
        self.notice = None;
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
        self.notice = None;
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
            push_bounded(plot, t, &[cmd.v_mps, cmd.omega_radps, vl, vr]);
        }
    }

    /// The run card shown in the readouts: the active run, else the last one
    /// finished; with its 1-based waypoint number and whether it is done.
    fn shown_card(&self) -> Option<(usize, RunStats, bool)> {
        let reached = self.reached();
        if !self.follower.queue.is_empty() {
            Some((reached + 1, self.follower.current, false))
        } else {
            self.follower.completed.last().map(|s| (reached, *s, true))
        }
    }
}

impl Experiment for DiffDrive {
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
                self.notice = None;
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

    /// The robot back to the corner, driving the same route again.
    fn reset(&mut self) {
        self.restart();
    }

    fn plots(&self) -> &[Plot] {
        &self.plots
    }

    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        self.waypoint_near(p, tolerance_m.max(0.0)).is_some()
    }

    fn view(&self) -> ViewBox {
        ViewBox {
            min: DVec2::ZERO,
            max: DVec2::new(FIELD_W_M, FIELD_H_M),
        }
    }

    fn scene(&self, out: &mut Scene) {
        draw_field(out, FIELD_W_M, FIELD_H_M);
        out.push(Item::Circle {
            center: START.position(),
            radius_m: BODY_RADIUS_M,
            role: Role::Ghost,
            fill: false,
            dashed: true,
        });
        if self.trail.len() > 1 {
            out.push(Item::Polyline {
                points: self.trail.clone(),
                width_px: 2.5,
                role: Role::Path,
                dashed: false,
                closed: false,
            });
        }
        // The route still to drive, dashed.
        if !self.follower.queue.is_empty() {
            let mut route = vec![self.pose().position()];
            route.extend(self.follower.queue.iter().copied());
            out.push(Item::Polyline {
                points: route,
                width_px: 1.5,
                role: Role::Target,
                dashed: true,
                closed: false,
            });
        }
        let reached = self.reached();
        for (k, (slot, w)) in self
            .slots
            .iter()
            .enumerate()
            .filter_map(|(i, w)| w.map(|w| (i, w)))
            .enumerate()
        {
            let done = k < reached;
            let role = if done { Role::Visited } else { Role::Target };
            out.push(Item::Dot {
                center: w,
                radius_px: if k == reached { 8.0 } else { 6.0 },
                role,
            });
            out.push(Item::Label {
                pos: w,
                text: (slot + 1).to_string(),
                role: Role::Text,
                offset_px: DVec2::new(-4.0, 18.0),
            });
            if let Some(card) = self.follower.completed.get(k) {
                out.push(Item::Label {
                    pos: w,
                    text: format!(
                        "{} m · {} s",
                        format_fixed(card.path_length_m, 2),
                        format_fixed(card.time_to_goal_s.unwrap_or(card.elapsed_s), 1)
                    ),
                    role: Role::Text,
                    offset_px: DVec2::new(10.0, -10.0),
                });
            }
        }
        let pose = self.pose();
        draw_robot(out, pose, self.track_m);
        let cmd = self.command();
        if cmd.v_mps > 1e-3 {
            out.push(Item::Arrow {
                from: pose.position(),
                to: pose.position() + pose.heading() * cmd.v_mps,
                width_px: 2.0,
                role: Role::Accent,
            });
        }
    }

    fn readouts(&self) -> Vec<Readout> {
        let cmd = self.command();
        let (vl, vr) = self.wheels();
        let pose = self.pose();
        let speed = |v: f64| format!("{} m/s", format_fixed(v, 3));
        let goal = self.follower.goal().map_or("--".into(), |g| {
            format_metres((g - pose.position()).length())
        });
        let mut out = vec![
            Readout::new("v", "Speed v", speed(cmd.v_mps)),
            Readout::new(
                "omega",
                "Turn rate ω",
                format!("{} rad/s", format_fixed(cmd.omega_radps, 3)),
            ),
            Readout::degrees("heading", "Heading θ", pose.theta_rad.to_degrees()),
            Readout::new("goal", "Goal distance", goal),
            Readout::new("vl", "Left wheel vL", speed(vl)),
            Readout::new("vr", "Right wheel vR", speed(vr)),
            Readout::new(
                "waypoints",
                "Waypoints reached",
                format!("{} of {}", self.reached(), self.waypoints().len()),
            ),
        ];
        let card = self.shown_card();
        let value = |f: &dyn Fn(&RunStats, bool) -> String| {
            card.as_ref()
                .map_or("--".into(), |(_, s, done)| f(s, *done))
        };
        out.extend([
            Readout::new(
                "card",
                "Run card",
                card.as_ref().map_or("--".into(), |(n, _, done)| {
                    format!(
                        "waypoint {n}{}",
                        if *done { " (reached)" } else { " (driving)" }
                    )
                }),
            ),
            Readout::new(
                "path",
                "Path length",
                value(&|s, _| format_metres(s.path_length_m)),
            ),
            Readout::new(
                "time",
                "Time to goal",
                value(&|s, done| match (done, s.time_to_goal_s) {
                    (true, Some(t)) => format!("{} s", format_fixed(t, 2)),
                    _ => format!("{} s so far", format_fixed(s.elapsed_s, 2)),
                }),
            ),
            Readout::new(
                "max_error",
                "Largest heading error",
                value(&|s, _| format_degrees(s.max_heading_error_rad.to_degrees())),
            ),
            Readout::new(
                "at_limit",
                "Time at a limit",
                value(&|s, _| {
                    format!(
                        "v {}%, ω {}%",
                        format_fixed(100.0 * s.v_limit_share(), 1),
                        format_fixed(100.0 * s.omega_limit_share(), 1)
                    )
                }),
            ),
        ]);
        out
    }

    fn status(&self) -> Status {
        if let Some(notice) = self.notice {
            return Status::new(notice, Tone::Warning);
        }
        let total = self.waypoints().len();
        if total == 0 {
            return Status::new("idle: click to drop a goal", Tone::Neutral);
        }
        let reached = self.reached();
        if self.follower.queue.is_empty() {
            return Status::new(
                if total == 1 {
                    "reached the goal".to_owned()
                } else {
                    format!("reached all {total} waypoints")
                },
                Tone::Good,
            );
        }
        let cmd = self.command();
        let doing = if cmd.v_mps < 1e-3 && cmd.heading_error_rad.abs() > 0.1 {
            "turning on the spot"
        } else {
            "driving"
        };
        Status::new(
            format!("waypoint {} of {total}: {doing}", reached + 1),
            Tone::Neutral,
        )
    }

    fn hint(&self) -> &'static str {
        "Click or tap to drop a goal; click again to queue more waypoints. Drag a waypoint to move it, tap it to remove it."
    }

    fn preview(&mut self) {
        for p in [
            DVec2::new(3.2, 4.6),
            DVec2::new(6.4, 4.2),
            DVec2::new(6.8, 1.2),
        ] {
            self.add_waypoint(p);
        }
        for _ in 0..60 * 14 {
            self.step(crate::clock::Clock::DT_S);
        }
    }

    fn animating(&self) -> bool {
        self.follower.goal().is_some()
    }
}

/// A random speed in m/s with two decimals.
fn draw_speed(rng: &mut Lcg64, lo: i64, hi: i64) -> f64 {
    rng.int(lo, hi) as f64 / 100.0
}

/// `v_R = v + ω b/2` for drawn `v`, `ω` and track `b`.
fn quiz_right_wheel(rng: &mut Lcg64) -> Draw {
    let v = draw_speed(rng, 10, 150);
    let w = rng.int(-30, 30) as f64 / 10.0;
    let b = rng.int(20, 60) as f64 / 100.0;
    Draw {
        vars: vec![
            ("v", format_number(v, 2)),
            ("w", format_number(w, 1)),
            ("b", format_number(b, 2)),
        ],
        answer: wheel_speeds(v, w, b).1,
    }
}

/// The wrapped heading error in degrees for a robot at the origin facing
/// `θ` and a goal at `(x, y)` (often across ±180°).
fn quiz_heading_error(rng: &mut Lcg64) -> Draw {
    let theta = rng.int(-179, 179) as f64;
    let x = rng.int(-40, 40) as f64 / 10.0;
    let mut y = rng.int(-40, 40) as f64 / 10.0;
    if x == 0.0 && y == 0.0 {
        y = 1.0;
    }
    let cmd =
        GoToGoal::default().command(Pose::new(0.0, 0.0, theta.to_radians()), DVec2::new(x, y));
    Draw {
        vars: vec![
            ("theta", format_number(theta, 0)),
            ("x", format_number(x, 1)),
            ("y", format_number(y, 1)),
        ],
        answer: cmd.heading_error_rad.to_degrees(),
    }
}

/// The commanded speed `v = min(Kv d max(0, cos eθ), v_max)`.
fn quiz_forward_speed(rng: &mut Lcg64) -> Draw {
    let kv = rng.int(5, 20) as f64 / 10.0;
    let d = rng.int(2, 30) as f64 / 10.0;
    let e = rng.int(-80, 80) as f64;
    let vmax = rng.int(8, 15) as f64 / 10.0;
    let controller = GoToGoal {
        k_v_per_s: kv,
        max_v_mps: vmax,
        ..GoToGoal::default()
    };
    let cmd = controller.command_for_heading(Pose::default(), e.to_radians(), d);
    Draw {
        vars: vec![
            ("kv", format_number(kv, 1)),
            ("d", format_number(d, 1)),
            ("e", format_number(e, 0)),
            ("vmax", format_number(vmax, 1)),
        ],
        answer: cmd.v_mps,
    }
}

/// The quiz generators of experiment 4, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "right_wheel" => Some(quiz_right_wheel),
        "heading_error" => Some(quiz_heading_error),
        "forward_speed" => Some(quiz_forward_speed),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::route::{format, restore, Tab};
    use std::f64::consts::PI;

    const DT: f64 = crate::clock::Clock::DT_S;

    fn run(d: &mut DiffDrive, max_s: f64) -> f64 {
        let mut t = 0.0;
        while d.animating() && t < max_s {
            d.step(DT);
            t += DT;
        }
        t
    }

    fn readout(d: &DiffDrive, key: &str) -> String {
        crate::experiment::readout_value(d, key).unwrap_or_else(|| panic!("no readout {key}"))
    }

    fn click(d: &mut DiffDrive, p: DVec2) {
        d.input(Input::PointerDown(p));
        d.input(Input::PointerUp(p));
    }

    #[test]
    fn idle_robot_waits_in_the_corner() {
        let mut d = DiffDrive::default();
        assert!(!d.animating());
        d.step(DT);
        assert_eq!(d.pose(), START);
        assert_eq!(d.status().text, "idle: click to drop a goal");
        assert_eq!(readout(&d, "goal"), "--");
        assert_eq!(readout(&d, "card"), "--");
    }

    /// The first step toward a goal straight up from the corner, by hand:
    /// eθ = π/2, ω = clamp(3.5·π/2, ±1.4) = 1.4 rad/s, v = Kv·d·max(0, cos eθ) ≈ 0,
    /// so vL = −ωb/2 = −0.21 m/s and vR = +0.21 m/s (b = 0.3 m).
    #[test]
    fn readouts_and_wheel_speeds_match_a_hand_computation() {
        let mut d = DiffDrive::default();
        click(&mut d, DVec2::new(0.6, 3.6));
        d.step(DT);
        assert_eq!(readout(&d, "omega"), "1.400 rad/s");
        assert_eq!(readout(&d, "v"), "0.000 m/s");
        assert_eq!(readout(&d, "vl"), "-0.210 m/s");
        assert_eq!(readout(&d, "vr"), "0.210 m/s");
        assert_eq!(
            readout(&d, "heading"),
            format_degrees((1.4 * DT).to_degrees())
        );
        assert_eq!(readout(&d, "goal"), "3.000 m");
        assert_eq!(d.status().text, "waypoint 1 of 1: turning on the spot");
        // Once aligned it drives at the speed limit: 1.2 · 3 m > 1.1 m/s.
        for _ in 0..90 {
            d.step(DT);
        }
        assert_eq!(readout(&d, "v"), "1.100 m/s");
        let (vl, vr) = d.wheels();
        let c = d.command();
        assert!((vr - vl - c.omega_radps * 0.3).abs() < 1e-12);
        assert!((0.5 * (vl + vr) - c.v_mps).abs() < 1e-12);
    }

    #[test]
    fn reaches_each_waypoint_in_order_with_a_run_card_each() {
        let mut d = DiffDrive::default();
        let goals = [
            DVec2::new(4.0, 0.6),
            DVec2::new(4.0, 4.0),
            DVec2::new(1.0, 5.0),
        ];
        for g in goals {
            click(&mut d, g);
        }
        assert_eq!(d.waypoints(), goals.to_vec());
        assert_eq!(d.param("w3x"), Some(1.0));
        let t = run(&mut d, 60.0);
        assert!(!d.animating(), "arrived after {t} s");
        assert_eq!(d.reached(), 3);
        assert!((d.pose().position() - goals[2]).length() <= TOLERANCE_M);
        assert_eq!(d.status().text, "reached all 3 waypoints");
        // Card 1: straight ahead along +x, 3.4 m: path ≈ 3.4 m, no heading error.
        let c1 = d.run_cards()[0];
        assert!((c1.path_length_m - 3.4).abs() < 0.06, "{c1:?}");
        assert!(c1.max_heading_error_rad < 1e-9);
        assert!(c1.v_limit_share() > 0.3 && c1.omega_limit_share() == 0.0);
        // Card 2: a quarter turn left first.
        let c2 = d.run_cards()[1];
        assert!((c2.max_heading_error_rad - PI / 2.0).abs() < 0.05, "{c2:?}");
        assert!(c2.omega_limit_share() > 0.0);
        // Times add up to the run's time.
        let sum: f64 = d
            .run_cards()
            .iter()
            .map(|c| c.time_to_goal_s.unwrap())
            .sum();
        assert!((sum - d.time_s).abs() < 4.0 * DT, "{sum} vs {}", d.time_s);
        assert_eq!(readout(&d, "card"), "waypoint 3 (reached)");
        assert_eq!(
            readout(&d, "time"),
            format!(
                "{} s",
                format_fixed(d.run_cards()[2].time_to_goal_s.unwrap(), 2)
            )
        );
        assert!(readout(&d, "at_limit").starts_with("v "));
        // The plot shows v, ω, vL, vR with a marker per arrival.
        let plot = &d.plots()[0];
        assert_eq!(plot.series.len(), 4);
        assert!(plot.sample_count() > 100);
        assert_eq!(plot.markers.len(), 3);
        assert!(!plot.bands.is_empty(), "time at a limit is shaded");
        assert!(plot
            .to_csv()
            .starts_with("Time (s),v (m/s),ω (rad/s),vL (m/s),vR (m/s)"));
    }

    #[test]
    fn tapping_a_waypoint_removes_it_and_dragging_moves_it() {
        let mut d = DiffDrive::default();
        for p in [
            DVec2::new(3.0, 3.0),
            DVec2::new(5.0, 3.0),
            DVec2::new(7.0, 3.0),
        ] {
            click(&mut d, p);
        }
        // Tap on waypoint 2: removed, 3 becomes 2.
        click(&mut d, DVec2::new(5.05, 3.0));
        assert_eq!(
            d.waypoints(),
            vec![DVec2::new(3.0, 3.0), DVec2::new(7.0, 3.0)]
        );
        assert_eq!(d.param("w2x"), Some(7.0));
        assert_eq!(d.param("w3x"), None);
        // Drag waypoint 1 to (2, 5).
        d.input(Input::PointerDown(DVec2::new(3.0, 3.1)));
        d.input(Input::PointerMove {
            pos: DVec2::new(2.5, 4.0),
            pressed: true,
        });
        d.input(Input::PointerMove {
            pos: DVec2::new(2.0, 5.0),
            pressed: true,
        });
        d.input(Input::PointerUp(DVec2::new(2.0, 5.0)));
        assert_eq!(d.waypoints()[0], DVec2::new(2.0, 5.0));
        assert_eq!(d.follower.queue.len(), 2);
        assert_eq!(d.follower.goal(), Some(DVec2::new(2.0, 5.0)));
        // The arrow keys move the waypoint last grabbed.
        d.input(Input::Nudge(DVec2::new(0.16, 0.0)));
        assert_eq!(d.waypoints()[0], DVec2::new(2.16, 5.0));
        d.action("clear").unwrap();
        assert!(d.waypoints().is_empty() && !d.animating());
    }

    /// On a touch screen a swipe that starts off every waypoint scrolls the
    /// page; the page still reports it as a press and a move, so a press
    /// only queues a waypoint when it is released where it started.
    #[test]
    fn a_swipe_off_the_waypoints_queues_nothing() {
        let mut d = DiffDrive::default();
        d.input(Input::PointerDown(DVec2::new(4.0, 1.0)));
        d.input(Input::PointerMove {
            pos: DVec2::new(4.0, 1.6),
            pressed: true,
        });
        d.input(Input::PointerUp(DVec2::new(4.0, 1.6)));
        assert!(d.waypoints().is_empty());
        // A click with a little jitter still counts as a tap.
        d.input(Input::PointerDown(DVec2::new(4.0, 1.0)));
        d.input(Input::PointerMove {
            pos: DVec2::new(4.02, 1.01),
            pressed: true,
        });
        d.input(Input::PointerUp(DVec2::new(4.02, 1.01)));
        assert_eq!(d.waypoints(), vec![DVec2::new(4.0, 1.0)]);
    }

    #[test]
    fn removing_a_reached_waypoint_drops_its_card() {
        let mut d = DiffDrive::default();
        click(&mut d, DVec2::new(2.0, 0.6));
        click(&mut d, DVec2::new(3.0, 0.6));
        run(&mut d, 30.0);
        assert_eq!(d.reached(), 2);
        let second = d.run_cards()[1];
        click(&mut d, DVec2::new(2.0, 0.6));
        assert_eq!(d.reached(), 1);
        assert_eq!(d.run_cards()[0], second);
        assert!(!d.animating());
        // A new click continues from where the robot stands.
        click(&mut d, DVec2::new(3.0, 2.0));
        assert!(d.animating());
        assert_eq!(readout(&d, "card"), "waypoint 2 (driving)");
        run(&mut d, 30.0);
        assert_eq!(d.reached(), 2);
    }

    #[test]
    fn a_full_queue_recycles_reached_waypoints_or_says_why() {
        let mut d = DiffDrive::default();
        for i in 0..MAX_WAYPOINTS {
            click(&mut d, DVec2::new(1.0 + i as f64, 2.0 + (i % 2) as f64));
        }
        click(&mut d, DVec2::new(7.5, 5.5));
        assert_eq!(d.waypoints().len(), MAX_WAYPOINTS);
        assert_eq!(d.status().tone, Tone::Warning);
        assert!(d.status().text.contains("all 6 waypoints"));
        // Once the first is reached it makes room.
        while d.reached() == 0 {
            d.step(DT);
        }
        click(&mut d, DVec2::new(7.5, 5.5));
        assert_eq!(d.waypoints().len(), MAX_WAYPOINTS);
        assert_eq!(d.waypoints()[MAX_WAYPOINTS - 1], DVec2::new(7.5, 5.5));
        assert_eq!(d.reached(), 0);
        assert_ne!(d.status().tone, Tone::Warning);
    }

    #[test]
    fn waypoints_round_trip_through_the_link() {
        let mut d = DiffDrive::default();
        click(&mut d, DVec2::new(3.333_333, 2.0));
        click(&mut d, DVec2::new(9.0, -1.0));
        d.set_param("kw", 5.0).unwrap();
        d.set_param("integ", 1.0).unwrap();
        let link = format(&d, Tab::Simulation);
        assert_eq!(
            link,
            "#/diffdrive/simulation?kw=5&kv=1.2&vmax=1.1&wmax=1.4&track=0.3&integ=1&w1x=3.33&w1y=2&w2x=8&w2y=0"
        );
        let (mut fresh, notices) = restore(&link, DiffDrive::default());
        assert!(notices.is_empty(), "{notices:?}");
        assert_eq!(fresh.waypoints(), d.waypoints());
        assert_eq!(format(&fresh, Tab::Simulation), link);
        // The loaded route drives the same run as the clicked one, after a reset.
        d.reset();
        for _ in 0..300 {
            d.step(DT);
            fresh.step(DT);
        }
        assert_eq!(d.pose(), fresh.pose());
    }

    #[test]
    fn typed_waypoint_fields_create_and_move_waypoints() {
        let mut d = DiffDrive::default();
        d.set_param("w2x", 4.0).unwrap();
        assert_eq!(d.waypoints(), vec![DVec2::new(4.0, START.y_m)]);
        d.set_param("w2y", 5.0).unwrap();
        assert_eq!(d.follower.goal(), Some(DVec2::new(4.0, 5.0)));
        assert_eq!(d.set_param("w1y", 99.0), Ok(Sanitized::Clamped(FIELD_H_M)));
        assert_eq!(d.waypoints()[0], DVec2::new(START.x_m, FIELD_H_M));
        assert!(d.set_param("w7x", 1.0).is_err());
        assert!(d.set_param("w1x", f64::NAN).is_err());
    }

    #[test]
    fn rk4_and_euler_both_arrive_and_differ_slightly() {
        let mut a = DiffDrive::default();
        let mut b = DiffDrive::default();
        b.set_param("integ", 1.0).unwrap();
        for d in [&mut a, &mut b] {
            click(d, DVec2::new(5.0, 5.0));
            run(d, 30.0);
            assert_eq!(d.reached(), 1);
        }
        let (ca, cb) = (a.run_cards()[0], b.run_cards()[0]);
        assert!((ca.path_length_m - cb.path_length_m).abs() < 0.05);
    }

    #[test]
    fn hostile_values_keep_the_state_finite() {
        let mut d = DiffDrive::default();
        click(&mut d, DVec2::new(f64::NAN, 1.0));
        click(&mut d, DVec2::new(1e300, -1e300));
        assert_eq!(d.waypoints(), vec![DVec2::new(FIELD_W_M, 0.0)]);
        d.input(Input::Nudge(DVec2::new(f64::INFINITY, 0.0)));
        d.set_param("kw", 1e9).unwrap();
        d.set_param("wmax", 1e9).unwrap();
        run(&mut d, 60.0);
        assert!(d.pose().is_finite());
        let mut scene = Scene::default();
        d.scene(&mut scene);
        assert!(scene.is_finite());
    }

    #[test]
    fn plots_and_trail_stay_bounded() {
        let mut d = DiffDrive::default();
        d.set_param("vmax", 0.1).unwrap();
        click(&mut d, DVec2::new(7.9, 5.9));
        click(&mut d, DVec2::new(0.1, 0.1));
        for _ in 0..60 * 400 {
            d.step(DT);
        }
        assert!(d.plots[0]
            .series
            .iter()
            .all(|s| s.len() <= MAX_PLOT_SAMPLES));
        assert!(d.trail.len() <= MAX_TRAIL_POINTS);
        assert!(d.plots[0].bands.len() <= MAX_BANDS);
    }

    #[test]
    fn waypoint_keys_parse_and_odd_keys_are_refused() {
        assert_eq!(slot_of("w1x"), Some((0, true)));
        assert_eq!(slot_of("w6y"), Some((5, false)));
        for bad in ["w7x", "w0y", "w1z", "wé", "w", "wx", "x1w", "w1xx", "w-1x"] {
            assert_eq!(slot_of(bad), None, "{bad}");
        }
        let d = DiffDrive::default();
        assert_eq!(d.param("wé"), None);
    }

    #[test]
    fn generators_agree_with_hand_formulas() {
        let mut rng = Lcg64::new(3);
        for _ in 0..50 {
            let w = quiz_right_wheel(&mut rng);
            let expected = w.var("v").unwrap() + w.var("w").unwrap() * w.var("b").unwrap() / 2.0;
            assert!((w.answer - expected).abs() < 1e-12);
            let h = quiz_heading_error(&mut rng);
            assert!(h.answer.abs() <= 180.0);
            let raw = h.var("y").unwrap().atan2(h.var("x").unwrap()).to_degrees()
                - h.var("theta").unwrap();
            let wrapped = (raw + 540.0).rem_euclid(360.0) - 180.0;
            assert!((h.answer - wrapped).abs() < 1e-9, "{h:?}");
            let f = quiz_forward_speed(&mut rng);
            let v = (f.var("kv").unwrap()
                * f.var("d").unwrap()
                * f.var("e").unwrap().to_radians().cos().max(0.0))
            .min(f.var("vmax").unwrap());
            assert!((f.answer - v).abs() < 1e-12);
        }
    }
}
