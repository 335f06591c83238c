//! Experiment 5 — potential-field obstacle avoidance, with a basin map.
//!
//! The robot descends `U = U_att + Σ U_rep` ([`PotentialField`], the lab
//! description's laws):
//!
//! ```text
//! F_att = k_a (goal − p)/|goal − p|
//! F_rep = k_r (d₀ − d)/d₀ · (p − c)/|p − c|,   d = |p − c| − r < d₀
//! ```
//!
//! and the direction of `F = F_att + Σ F_rep` is the desired heading of the
//! same proportional unicycle controller as experiment 4 (Khatib, IJRR 5(1),
//! 1986; Choset et al., *Principles of Robot Motion*, 2005, §4.1–4.2). A run
//! ([`FieldRun`]) stops as *trapped* only on the trap's evidence: for 5 s its
//! best distance to the goal has not improved by 5 cm and it has stayed
//! within 0.3 m of one spot (Koren & Borenstein, ICRA 1991, §III). A run also
//! ends when the robot touches an obstacle, is pushed off the field, or at
//! 120 s. With `N·k_r < k_a` no trap exists, and no obstacle stops a robot
//! aimed at it ([`crate::mobile::potential_field::FieldParams::trap_free`]).
//!
//! **Basin map** (the "Basin map" action): every start cell of a
//! [`BASIN_COLS`] × [`BASIN_ROWS`] grid over the field is classified by a
//! whole run from its centre ([`BasinMap`]) — reaches the goal, trapped,
//! collided, pushed off the field, timed out — [`BASIN_CELLS_PER_STEP`]
//! cells per fixed step, so
//! the map fills in over about two seconds without a long frame. The share of
//! free starts that reach the goal is a readout.
//!
//! Everything a student places is a parameter: the goal (`gx`, `gy`), the
//! start (`sx`, `sy`), the obstacle count (`nobs`) and the obstacle centres
//! (`o1x` … `o6y`); a shown basin map is `map=1`. So a link reproduces the
//! field, the map and the run. Prompts and refusals are notices; the status
//! is the run's state.

use crate::experiment::{
    check_param, with_coordinate, ActionSpec, Experiment, Input, Notices, ParamError, ParamSpec,
    Sanitized, Tone,
};
use crate::mobile::field::{push_trail, snap_into};
use crate::mobile::go_to_goal::GoToGoal;
use crate::mobile::potential_field::{
    BasinMap, CircleObstacle, FieldRun, FieldRunConfig, PotentialField, RunStatus, TrapDetection,
};
use crate::mobile::unicycle::{Integrator, Pose};
use crate::plot::{Marker, Plot, Series, SeriesRole, XWindow};
use glam::DVec2;

mod quiz;
#[cfg(test)]
mod tests;
mod view;

/// Most obstacles at once (each centre is two URL parameters).
pub const MAX_OBSTACLES: usize = 6;
/// The field shown, metres: `[0, FIELD_W_M] × [0, FIELD_H_M]`.
pub const FIELD_W_M: f64 = 8.0;
pub const FIELD_H_M: f64 = 6.0;
/// Basin map resolution: 0.2 m cells over the field.
pub const BASIN_COLS: usize = 40;
pub const BASIN_ROWS: usize = 30;
/// Basin cells classified per fixed step (see `basin_step_cost_is_bounded`).
pub const BASIN_CELLS_PER_STEP: usize = 10;
/// Step of the basin map's runs, seconds (the live run steps at 1/60 s).
pub const BASIN_DT_S: f64 = 0.05;
/// Longest basin run, seconds (a live run may take 120 s).
pub const BASIN_MAX_TIME_S: f64 = 60.0;
/// A press within this distance of the goal or the start grabs it, metres.
const GRAB_M: f64 = 0.3;
/// A press that moves less than this before release is a tap, metres.
const TAP_SLOP_M: f64 = 0.08;
/// Plot samples every this many steps.
const PLOT_EVERY: u64 = 2;
/// Where obstacle slots 1–6 sit until placed elsewhere (the first two are
/// pre-placed).
const DEFAULT_OBSTACLES: [DVec2; MAX_OBSTACLES] = [
    DVec2::new(3.0, 3.4),
    DVec2::new(5.2, 2.2),
    DVec2::new(4.2, 4.8),
    DVec2::new(2.0, 1.4),
    DVec2::new(6.4, 4.4),
    DVec2::new(4.0, 1.0),
];
const DEFAULT_GOAL: DVec2 = DVec2::new(7.2, 3.0);
/// Most steps [`Presentation::preview`] takes: one live run's hard limit
/// (120 s at 60 steps per second) and a little more.
pub const MAX_PREVIEW_STEPS: usize = 7300;

const VIEWS: &[&str] = &["Off", "Arrows", "Heat map"];

const PARAMS: &[ParamSpec] = &[
    ParamSpec::slider("ka", "Attract gain kₐ", "", 0.1, 3.0, 0.05, 1.0),
    ParamSpec::slider("kr", "Avoid gain kᵣ", "", 0.0, 5.0, 0.05, 1.6),
    ParamSpec::slider("d0", "Influence d₀", "m", 0.1, 3.0, 0.05, 1.0),
    ParamSpec::slider("rad", "Obstacle radius", "m", 0.1, 1.2, 0.05, 0.5),
    ParamSpec::choice("view", "Field view", VIEWS, 1),
    ParamSpec::slider("nobs", "Obstacles", "", 0.0, MAX_OBSTACLES as f64, 1.0, 2.0).whole_numbers(),
    ParamSpec::slider("sx", "Start x", "m", 0.2, FIELD_W_M - 0.2, 0.01, 0.6),
    ParamSpec::slider("sy", "Start y", "m", 0.2, FIELD_H_M - 0.2, 0.01, 3.0),
    ParamSpec::optional_number("gx", "Goal x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("gy", "Goal y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("o1x", "Obstacle 1 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("o1y", "Obstacle 1 y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("o2x", "Obstacle 2 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("o2y", "Obstacle 2 y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("o3x", "Obstacle 3 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("o3y", "Obstacle 3 y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("o4x", "Obstacle 4 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("o4y", "Obstacle 4 y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("o5x", "Obstacle 5 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("o5y", "Obstacle 5 y", "m", 0.0, FIELD_H_M),
    ParamSpec::optional_number("o6x", "Obstacle 6 x", "m", 0.0, FIELD_W_M),
    ParamSpec::optional_number("o6y", "Obstacle 6 y", "m", 0.0, FIELD_H_M),
];

const ACTIONS: &[ActionSpec] = &[
    ActionSpec {
        key: "basin",
        label: "Basin map",
    },
    ActionSpec {
        key: "add",
        label: "Add obstacle",
    },
    ActionSpec {
        key: "remove",
        label: "Remove obstacle",
    },
    ActionSpec {
        key: "clear",
        label: "Hide basin map",
    },
];

/// The slot (0-based) of an obstacle key `o3x` → 2, and whether it is x.
fn slot_of(key: &str) -> Option<(usize, bool)> {
    crate::experiment::point_slot(key, 'o', MAX_OBSTACLES)
}

/// What the next click does after an action button.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Add,
    Remove,
}

/// A press that places something when it is released in place.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Tap {
    at: DVec2,
    moved: bool,
}

/// Something that can be dragged (and moved with the arrow keys).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Handle {
    Goal,
    Start,
    Obstacle(usize),
}

/// State of the potential-field experiment.
#[derive(Clone, Debug)]
pub struct PotentialFieldLab {
    /// Gains, goal and the first `count` obstacles, kept in sync with the parameters.
    field: PotentialField,
    goal: Option<DVec2>,
    start: DVec2,
    radius_m: f64,
    /// Obstacle centres; the first `count` are in the field.
    slots: [DVec2; MAX_OBSTACLES],
    count: usize,
    view: usize,
    run: Option<FieldRun>,
    basin: Option<BasinMap>,
    /// Field steps the basin map's runs took in the last `step` (0 when it
    /// computed nothing): the work of one frame.
    basin_steps: u64,
    trail: Vec<DVec2>,
    steps: u64,
    mode: Option<Mode>,
    dragging: Option<Handle>,
    /// A press off every handle: a goal (or, after Add obstacle, an
    /// obstacle) is placed where it was pressed if it is released without moving.
    tap: Option<Tap>,
    selected: Handle,
    /// Transient messages (a mode's prompt, a refused click).
    notices: Notices,
    /// Goal distance and |F_rep| against time.
    plots: [Plot; 1],
}

fn new_plots() -> [Plot; 1] {
    let mut p = Plot::new(
        "run",
        "Goal distance and repulsion",
        ("Time", "s"),
        ("Goal distance (m), |F_rep|", ""),
        vec![
            Series::new("goal distance", "m", SeriesRole::Primary),
            Series::new("|F_rep|", "", SeriesRole::Secondary),
        ],
    );
    p.window = XWindow::All;
    [p]
}

/// The controller and trap settings of the live run.
fn live_config() -> FieldRunConfig {
    FieldRunConfig {
        controller: GoToGoal::default(),
        trap: TrapDetection::default(),
        integrator: Integrator::Euler,
        substeps: 2,
        dt_s: crate::clock::Clock::DT_S,
        bounds: Some((DVec2::ZERO, DVec2::new(FIELD_W_M, FIELD_H_M))),
    }
}

/// The settings of the basin map's runs: the same controller and trap
/// window, a coarser step and a shorter hard limit.
#[must_use]
pub fn basin_config() -> FieldRunConfig {
    FieldRunConfig {
        trap: TrapDetection {
            max_time_s: BASIN_MAX_TIME_S,
            ..TrapDetection::default()
        },
        substeps: 1,
        dt_s: BASIN_DT_S,
        ..live_config()
    }
}

impl Default for PotentialFieldLab {
    fn default() -> Self {
        let mut s = Self {
            field: PotentialField::default(),
            goal: None,
            start: DVec2::new(PARAMS[6].default, PARAMS[7].default),
            radius_m: PARAMS[3].default,
            slots: DEFAULT_OBSTACLES,
            count: PARAMS[5].default as usize,
            view: PARAMS[4].default as usize,
            run: None,
            basin: None,
            basin_steps: 0,
            trail: Vec::new(),
            steps: 0,
            mode: None,
            dragging: None,
            tap: None,
            selected: Handle::Goal,
            notices: Notices::default(),
            plots: new_plots(),
        };
        s.field.params.k_att = PARAMS[0].default;
        s.field.params.k_rep = PARAMS[1].default;
        s.field.params.influence_m = PARAMS[2].default;
        s.field_changed();
        s
    }
}

impl PotentialFieldLab {
    /// The obstacles in the field.
    #[must_use]
    pub fn obstacles(&self) -> &[CircleObstacle] {
        &self.field.obstacles
    }

    /// The field (gains, goal, obstacles).
    #[must_use]
    pub fn field(&self) -> &PotentialField {
        &self.field
    }

    /// The current run, once a goal is set.
    #[must_use]
    pub fn run(&self) -> Option<&FieldRun> {
        self.run.as_ref()
    }

    /// Field steps the basin map's runs took in the last step (0 when it
    /// computed nothing): the basin map's work in one frame.
    #[must_use]
    pub fn basin_steps_last_step(&self) -> u64 {
        self.basin_steps
    }

    /// The basin map, once requested.
    #[must_use]
    pub fn basin(&self) -> Option<&BasinMap> {
        self.basin.as_ref()
    }

    /// The start pose: at the start point, facing the goal (as the basin map's runs do).
    #[must_use]
    pub fn start_pose(&self) -> Pose {
        let to_goal = self.goal.unwrap_or(self.start + DVec2::X) - self.start;
        Pose::new(
            self.start.x,
            self.start.y,
            crate::math::atan2(to_goal.y, to_goal.x),
        )
    }

    fn goal_inside_obstacle(&self) -> bool {
        self.goal.is_some_and(|g| self.field.inside_obstacle(g))
    }

    /// Rebuilds the field from the parameters and restarts the run from the
    /// start (and the basin map, when one is shown): the picture always
    /// shows the outcome of the field on screen.
    fn field_changed(&mut self) {
        self.field.goal = self.goal.unwrap_or(self.start);
        self.field.obstacles = self.slots[..self.count]
            .iter()
            .map(|c| CircleObstacle::new(*c, self.radius_m))
            .collect();
        self.restart_run();
        if self.basin.is_some() {
            self.start_basin();
        }
    }

    fn restart_run(&mut self) {
        self.run = self
            .goal
            .map(|_| FieldRun::new(self.start_pose(), &self.field));
        self.trail.clear();
        self.trail.push(self.start);
        self.steps = 0;
        for plot in &mut self.plots {
            plot.clear();
        }
        self.record();
    }

    fn start_basin(&mut self) {
        self.basin = BasinMap::new(
            DVec2::ZERO,
            DVec2::new(FIELD_W_M, FIELD_H_M),
            BASIN_COLS,
            BASIN_ROWS,
        );
    }

    fn basin_computing(&self) -> bool {
        self.goal.is_some() && self.basin.as_ref().is_some_and(|m| !m.is_complete())
    }

    fn record(&mut self) {
        let Some(run) = self.run else { return };
        let d = (self.field.goal - run.pose.position()).length();
        let rep = self.field.repulsive_force(run.pose.position()).length();
        self.plots[0].push_bounded(run.time_s, &[d, rep]);
    }

    fn set_goal(&mut self, p: DVec2) {
        if p.is_finite() {
            self.goal = Some(snap_into(p, FIELD_W_M, FIELD_H_M));
            self.field_changed();
        }
    }

    fn set_start(&mut self, p: DVec2) {
        if p.is_finite() {
            let lo = DVec2::splat(0.2);
            let hi = DVec2::new(FIELD_W_M - 0.2, FIELD_H_M - 0.2);
            self.start = snap_into(p, FIELD_W_M, FIELD_H_M).clamp(lo, hi);
            self.field_changed();
        }
    }

    fn set_obstacle(&mut self, slot: usize, p: DVec2) {
        if p.is_finite() && slot < self.count {
            self.slots[slot] = snap_into(p, FIELD_W_M, FIELD_H_M);
            self.field_changed();
        }
    }

    /// Adds an obstacle at `p`; returns its slot, or `None` when all are placed.
    fn add_obstacle(&mut self, p: DVec2) -> Option<usize> {
        if !p.is_finite() {
            return None;
        }
        if self.count >= MAX_OBSTACLES {
            self.notices.post(
                "all 6 obstacles are placed: remove one first",
                Tone::Warning,
            );
            return None;
        }
        let slot = self.count;
        self.count += 1;
        self.slots[slot] = snap_into(p, FIELD_W_M, FIELD_H_M);
        self.field_changed();
        Some(slot)
    }

    /// Removes obstacle `slot`; the later ones move up a number.
    fn remove_obstacle(&mut self, slot: usize) {
        if slot >= self.count {
            return;
        }
        for i in slot..self.count - 1 {
            self.slots[i] = self.slots[i + 1];
        }
        self.count -= 1;
        self.slots[self.count] = DEFAULT_OBSTACLES[self.count];
        self.selected = Handle::Goal;
        self.field_changed();
    }

    /// The obstacle under `p` (within `margin_m` of its surface), nearest centre first.
    fn obstacle_at(&self, p: DVec2, margin_m: f64) -> Option<usize> {
        let mut best: Option<(usize, f64)> = None;
        for (i, c) in self.slots[..self.count].iter().enumerate() {
            let d = (*c - p).length();
            if d <= self.radius_m + margin_m && best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
        best.map(|(i, _)| i)
    }

    fn handle_under(&self, p: DVec2, margin_m: f64) -> Option<Handle> {
        if let Some(g) = self.goal {
            if (g - p).length() <= margin_m.max(0.0) {
                return Some(Handle::Goal);
            }
        }
        if (self.start - p).length() <= margin_m.max(0.0) {
            return Some(Handle::Start);
        }
        self.obstacle_at(p, 0.0).map(Handle::Obstacle)
    }

    fn move_handle(&mut self, handle: Handle, p: DVec2) {
        match handle {
            Handle::Goal => self.set_goal(p),
            Handle::Start => self.set_start(p),
            Handle::Obstacle(i) => self.set_obstacle(i, p),
        }
    }

    fn handle_position(&self, handle: Handle) -> Option<DVec2> {
        match handle {
            Handle::Goal => self.goal,
            Handle::Start => Some(self.start),
            Handle::Obstacle(i) => (i < self.count).then(|| self.slots[i]),
        }
    }
}

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "Two obstacles trap the robot",
        description: "Two obstacles close together in front of the goal: the pushes cancel the pull and the robot stops in a local minimum.",
        query: "rad=0.4&o1x=4&o1y=3.6&o2x=4&o2y=2.4&gx=7.4&gy=3",
    },
    crate::experiment::Preset {
        name: "The pull beats the push",
        description: "A strong attraction and a weak repulsion with an obstacle on the line: the robot drives into it.",
        query: "ka=2&kr=0.8&o1x=3&o1y=3&gx=7.2&gy=3",
    },
    crate::experiment::Preset {
        name: "A wide berth",
        description: "A strong push felt from far away: the robot keeps well clear of the obstacles on its way to the goal.",
        query: "kr=4&d0=2&gx=7.2&gy=3",
    },
];

impl Experiment for PotentialFieldLab {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

    fn id(&self) -> &'static str {
        "potential"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        if let Some((slot, is_x)) = slot_of(key) {
            return (slot < self.count).then(|| {
                let c = self.slots[slot];
                if is_x {
                    c.x
                } else {
                    c.y
                }
            });
        }
        Some(match key {
            "ka" => self.field.params.k_att,
            "kr" => self.field.params.k_rep,
            "d0" => self.field.params.influence_m,
            "rad" => self.radius_m,
            "view" => self.view as f64,
            "nobs" => self.count as f64,
            "sx" => self.start.x,
            "sy" => self.start.y,
            "gx" => return self.goal.map(|g| g.x),
            "gy" => return self.goal.map(|g| g.y),
            _ => return None,
        })
    }

    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        if let Some((slot, _)) = slot_of(key) {
            // Typing a coordinate of obstacle k places obstacles 1…k.
            self.count = self.count.max(slot + 1);
            let c = self.slots[slot];
            self.slots[slot] = with_coordinate(Some(c), c, key, v);
            self.field_changed();
            return Ok(applied);
        }
        match key {
            "ka" => self.field.params.k_att = v,
            "kr" => self.field.params.k_rep = v,
            "d0" => self.field.params.influence_m = v,
            "rad" => self.radius_m = v,
            "view" => {
                self.view = v as usize;
                return Ok(applied);
            }
            "nobs" => {
                let n = v as usize;
                // Obstacles taken away go back to their default spots.
                if n < self.count {
                    self.slots[n..self.count].copy_from_slice(&DEFAULT_OBSTACLES[n..self.count]);
                }
                self.count = n;
            }
            "sx" | "sy" => self.start = with_coordinate(Some(self.start), self.start, key, v),
            "gx" | "gy" => {
                self.goal = Some(with_coordinate(
                    self.goal,
                    DVec2::new(FIELD_W_M, FIELD_H_M) * 0.5,
                    key,
                    v,
                ));
            }
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        self.field_changed();
        Ok(applied)
    }

    fn actions(&self) -> &'static [ActionSpec] {
        ACTIONS
    }

    /// "Hide basin map" is there while a basin map is.
    fn action_shown(&self, key: &str) -> bool {
        key != "clear" || self.basin.is_some()
    }

    fn action(&mut self, key: &str) -> Result<(), ParamError> {
        // A refused action changes nothing: check the key before anything else.
        if !ACTIONS.iter().any(|a| a.key == key) {
            return Err(ParamError::UnknownAction { key: key.into() });
        }
        self.notices.clear();
        self.mode = None;
        match key {
            "basin" => {
                if self.goal.is_none() {
                    self.notices
                        .post("set a goal first: the basin map needs one", Tone::Warning);
                } else {
                    self.start_basin();
                }
            }
            "add" => {
                if self.count >= MAX_OBSTACLES {
                    self.notices.post(
                        "all 6 obstacles are placed: remove one first",
                        Tone::Warning,
                    );
                } else {
                    self.mode = Some(Mode::Add);
                    self.notices
                        .post("click where the new obstacle goes", Tone::Neutral);
                }
            }
            "remove" => {
                if self.count == 0 {
                    self.notices
                        .post("there is no obstacle to remove", Tone::Warning);
                } else {
                    self.mode = Some(Mode::Remove);
                    self.notices
                        .post("click the obstacle to remove", Tone::Neutral);
                }
            }
            _ => self.basin = None, // "clear"
        }
        Ok(())
    }

    fn input(&mut self, input: Input) {
        match input {
            Input::PointerDown(p) => {
                if !p.is_finite() {
                    return;
                }
                self.notices.clear();
                self.tap = None;
                match self.mode {
                    Some(Mode::Add) => {
                        self.tap = Some(Tap {
                            at: p,
                            moved: false,
                        });
                    }
                    Some(Mode::Remove) => {
                        self.mode = None;
                        if let Some(i) = self.obstacle_at(p, 0.1) {
                            self.remove_obstacle(i);
                        } else {
                            self.notices
                                .post("no obstacle there: nothing removed", Tone::Warning);
                        }
                    }
                    None => match self.handle_under(p, GRAB_M) {
                        Some(handle) => {
                            self.dragging = Some(handle);
                            self.selected = handle;
                        }
                        None => {
                            self.tap = Some(Tap {
                                at: p,
                                moved: false,
                            });
                        }
                    },
                }
            }
            Input::PointerMove { pos, pressed: true } => {
                if let Some(h) = self.dragging {
                    self.move_handle(h, pos);
                } else if let Some(tap) = self.tap.as_mut() {
                    if pos.is_finite() && (pos - tap.at).length() > TAP_SLOP_M {
                        tap.moved = true;
                    }
                }
            }
            Input::PointerMove { pressed: false, .. } => {}
            Input::PointerUp(_) => {
                self.dragging = None;
                let Some(tap) = self.tap.take() else { return };
                if tap.moved {
                    // A swipe (it scrolls the page on a touch screen): nothing placed.
                    return;
                }
                if self.mode == Some(Mode::Add) {
                    self.mode = None;
                    if let Some(slot) = self.add_obstacle(tap.at) {
                        self.selected = Handle::Obstacle(slot);
                    }
                } else {
                    self.set_goal(tap.at);
                    self.selected = Handle::Goal;
                }
            }
            Input::Nudge(delta) => {
                if !delta.is_finite() {
                    return;
                }
                let handle = self.selected;
                let from = self
                    .handle_position(handle)
                    .unwrap_or(if handle == Handle::Goal {
                        self.start
                    } else {
                        self.goal.unwrap_or(self.start)
                    });
                let handle = if self.handle_position(handle).is_none() {
                    Handle::Goal
                } else {
                    handle
                };
                self.selected = handle;
                self.move_handle(handle, from + delta);
            }
        }
    }

    fn step(&mut self, dt_s: f64) {
        if !crate::clock::valid_dt(dt_s) {
            return;
        }
        let blocked = self.goal_inside_obstacle();
        if let Some(run) = self.run.as_mut() {
            if !run.status.is_final() && !blocked {
                run.step(&self.field, &live_config(), dt_s);
                self.steps += 1;
                push_trail(&mut self.trail, run.pose.position());
                let status = run.status;
                let t = run.time_s;
                if self.steps.is_multiple_of(PLOT_EVERY) || status.is_final() {
                    self.record();
                }
                if status.is_final() {
                    let label = match status {
                        RunStatus::Reached => "reached",
                        RunStatus::Trapped => "trapped",
                        RunStatus::Collided => "collided",
                        RunStatus::LeftField => "left the field",
                        _ => "stopped",
                    };
                    let y = self.plots[0].series[0].y.last().copied().unwrap_or(0.0);
                    self.plots[0].markers.push(Marker {
                        x: t,
                        y,
                        label: label.into(),
                    });
                }
            }
        }
        self.basin_steps = 0;
        if self.basin_computing() {
            if let Some(map) = self.basin.as_mut() {
                let (_, steps) =
                    map.advance_counted(&self.field, &basin_config(), BASIN_CELLS_PER_STEP);
                self.basin_steps = steps;
            }
        }
    }

    fn animated(&self) -> bool {
        true
    }

    /// The robot back at the start, the same run again (and the basin map
    /// from its first cell).
    fn reset(&mut self) {
        self.restart_run();
        self.mode = None;
        self.notices.clear();
        self.tap = None;
        if self.basin.is_some() {
            self.start_basin();
        }
    }

    fn plots(&self) -> &[Plot] {
        &self.plots
    }

    /// The goal (once set), the start and the obstacles (`o1`…, as in the link).
    fn handles(&self) -> Vec<crate::experiment::Handle> {
        use crate::experiment::Handle as H;
        let mut out = Vec::new();
        if let Some(g) = self.goal {
            out.push(H::new("goal", "Goal", g));
        }
        out.push(H::new("start", "Start", self.start));
        for (i, c) in self.slots[..self.count].iter().enumerate() {
            out.push(H::new(
                format!("o{}", i + 1),
                format!("Obstacle {}", i + 1),
                *c,
            ));
        }
        out
    }

    /// A drag of handle `id`: grabbed by name (a press on it, even where
    /// another handle overlaps), moved to `to`, released.
    fn move_handle(&mut self, id: &str, to: DVec2) -> bool {
        let handle = match id {
            "goal" if self.goal.is_some() => Handle::Goal,
            "start" => Handle::Start,
            _ => match crate::experiment::point_slot(&format!("{id}x"), 'o', self.count) {
                Some((i, _)) => Handle::Obstacle(i),
                None => return false,
            },
        };
        if !to.is_finite() {
            return false;
        }
        self.notices.clear();
        self.tap = None;
        self.dragging = Some(handle);
        self.selected = handle;
        crate::experiment::finish_drag(self, to)
    }

    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        self.handle_under(p, tolerance_m.max(0.0)).is_some()
            || self.obstacle_at(p, tolerance_m.max(0.0)).is_some()
    }

    fn extra_state(&self) -> Vec<(&'static str, String)> {
        if self.basin.is_some() {
            vec![("map", "1".into())]
        } else {
            Vec::new()
        }
    }

    /// `map=1`: the basin map is shown (it is computed once there is a goal).
    fn set_extra_state(&mut self, key: &str, value: &str) -> Result<(), ParamError> {
        if key != "map" {
            return Err(ParamError::UnknownKey { key: key.into() });
        }
        match value.trim() {
            "1" => self.start_basin(),
            "0" => self.basin = None,
            _ => {
                return Err(ParamError::BadText {
                    key: key.into(),
                    reason: format!("“{value}” is not 0 or 1"),
                })
            }
        }
        Ok(())
    }

    fn animating(&self) -> bool {
        let running =
            self.run.is_some_and(|r| !r.status.is_final()) && !self.goal_inside_obstacle();
        running || self.basin_computing()
    }

    /// The plots, the obstacles, the trail driven and the basin map's cells.
    fn state_bytes(&self) -> usize {
        use std::mem::size_of;
        crate::plot::plots_bytes(&self.plots)
            + self.field.obstacles.capacity() * size_of::<CircleObstacle>()
            + self.trail.capacity() * size_of::<DVec2>()
            + self.basin.as_ref().map_or(0, |b| {
                b.cells.capacity() * size_of::<crate::mobile::potential_field::BasinClass>()
            })
    }
}

pub use quiz::quiz_generator;
