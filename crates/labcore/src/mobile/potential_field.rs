//! Artificial potential-field navigation around circular obstacles.
//!
//! The robot (a point; inflate each obstacle's radius by the robot's radius to
//! plan in configuration space) descends a potential `U = U_att + Σ U_rep`.
//! The lab spec (experiment 5) uses a constant-magnitude ("conic") attraction
//! and a repulsion that grows linearly inside an influence distance `d₀`:
//!
//! ```text
//! F_att = k_a · (goal − p)/|goal − p|                 U_att = k_a |goal − p|
//! F_rep = k_r · (d₀ − d)/d₀ · ∇d,   d < d₀            U_rep = k_r (d₀ − d)² / (2 d₀)
//! ```
//!
//! where `d = |p − c| − r` is the clearance to a circle of centre `c`, radius
//! `r`, and `∇d = (p − c)/|p − c|`. Khatib's original laws (Khatib,
//! "Real-time obstacle avoidance for manipulators and mobile robots",
//! *IJRR* 5(1), 1986, pp. 90–98, eq. 6 and 17–19) are selectable:
//!
//! ```text
//! F_att = k_a (goal − p)                              U_att = ½ k_a |goal − p|²
//! F_rep = k_r (1/d − 1/d₀)(1/d²) ∇d,   d < d₀         U_rep = ½ k_r (1/d − 1/d₀)²
//! ```
//!
//! In every case `F = −∇U`, and each repulsion vanishes with its gradient at
//! `d = d₀`, so `U` is continuously differentiable away from the goal.
//! (Choset et al., *Principles of Robot Motion*, MIT Press 2005, §4.1–4.2,
//! discusses both families.)
//!
//! **Steering.** The net force's direction is the desired heading for the
//! same proportional controller as [`super::go_to_goal`], with the distance
//! to the goal scaling the speed: `ω = Kω·wrap(∠F − θ)`,
//! `v = Kv·|goal − p|·max(0, cos eθ)`.
//!
//! **Local minima.** Where attraction and repulsion cancel away from the goal
//! the robot stalls or oscillates (Koren & Borenstein, "Potential field
//! methods and their inherent limitations for mobile robot navigation",
//! *IEEE ICRA* 1991, pp. 1398–1404, §III: trap situations due to local
//! minima, oscillations in narrow passages). [`TrapDetection`] declares a run
//! [`RunStatus::Trapped`] only on the trap's own evidence, held over a window
//! of `window_s` seconds: the best distance to the goal has not improved by
//! `min_progress_m`, *and* the robot has stayed within `hold_radius_m` of one
//! spot (it stalls, or rocks in place, where the forces balance). A robot
//! that keeps driving without getting closer is not trapped; it runs on
//! until it arrives, collides, leaves the field ([`FieldRunConfig::bounds`])
//! or reaches `max_time_s`, so a run stops in bounded time whatever the field.
//!
//! **Bounded repulsion.** With the linear law each obstacle pushes with at
//! most `k_r`, so `N` obstacles push with at most `N·k_r` in total, while the
//! conic pull is `k_a` everywhere. When `N·k_r < k_a` the net force never
//! vanishes away from the goal: no trap can exist, but neither is a robot
//! heading straight at an obstacle stopped before the surface (that needs
//! `k_r > k_a`). See `no_trap_when_the_pull_beats_every_push` below.
//!
//! **Basins.** [`BasinMap`] classifies the start cells of a grid — reaches the
//! goal, trapped, inside an obstacle, … — a few cells per call, so a page can
//! spread the work over frames.

use glam::DVec2;

use super::go_to_goal::{Command, GoToGoal};
use super::unicycle::{integrate, Integrator, Pose};

/// Attractive law.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Attraction {
    /// The spec's constant-magnitude pull `k_a (goal − p)/|goal − p|`.
    #[default]
    Conic,
    /// Khatib's spring `k_a (goal − p)`.
    Quadratic,
}

/// Repulsive law.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Repulsion {
    /// The spec's `k_r (d₀ − d)/d₀ ∇d`: at most `k_r`, at the surface.
    #[default]
    Linear,
    /// Khatib's `k_r (1/d − 1/d₀)(1/d²) ∇d`: unbounded as `d → 0`.
    Khatib,
}

/// A circular obstacle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircleObstacle {
    /// Centre, metres.
    pub centre: DVec2,
    /// Radius, metres (negative counts as 0).
    pub radius_m: f64,
}

impl CircleObstacle {
    /// An obstacle from centre and radius.
    #[must_use]
    pub const fn new(centre: DVec2, radius_m: f64) -> Self {
        Self { centre, radius_m }
    }

    /// Clearance `d = |p − c| − r`, metres (negative inside).
    #[must_use]
    pub fn clearance_m(&self, p: DVec2) -> f64 {
        (p - self.centre).length() - self.radius_m.max(0.0)
    }
}

/// Gains and shape of the field.
///
/// Defaults: `k_a = 1`, `k_r = 1.6` (the spec's avoid gain), `d₀ = 1 m`, the
/// spec's laws. With the linear law a robot cannot be pushed into an obstacle
/// head-on as long as `k_r > k_a` (the largest repulsion, `k_r`, beats the
/// conic pull `k_a`); with `N` obstacles and `N·k_r < k_a` the net force never
/// vanishes away from the goal, so no trap exists ([`FieldParams::trap_free`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldParams {
    /// Attractive gain `k_a` (force units; per metre for the quadratic law).
    pub k_att: f64,
    /// Repulsive gain `k_r`.
    pub k_rep: f64,
    /// Influence distance `d₀` beyond which an obstacle exerts no force, metres.
    pub influence_m: f64,
    pub attraction: Attraction,
    pub repulsion: Repulsion,
}

impl FieldParams {
    /// With the conic attraction and the linear repulsion, `n` obstacles can
    /// never cancel the pull: `n·k_r < k_a`, so `|F| ≥ k_a − n·k_r > 0` away
    /// from the goal and no local minimum (no trap) exists. The price: no
    /// obstacle can then stop a robot heading straight at it.
    #[must_use]
    pub fn trap_free(&self, n: usize) -> bool {
        self.attraction == Attraction::Conic
            && self.repulsion == Repulsion::Linear
            && (n as f64) * self.k_rep.max(0.0) < self.k_att
    }
}

impl Default for FieldParams {
    fn default() -> Self {
        Self {
            k_att: 1.0,
            k_rep: 1.6,
            influence_m: 1.0,
            attraction: Attraction::Conic,
            repulsion: Repulsion::Linear,
        }
    }
}

/// Smallest clearance used inside the repulsive laws, metres: keeps Khatib's
/// `1/d` finite on and inside an obstacle's surface.
pub const MIN_CLEARANCE_M: f64 = 1e-3;

/// A goal and obstacles under one set of [`FieldParams`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PotentialField {
    pub params: FieldParams,
    pub goal: DVec2,
    pub obstacles: Vec<CircleObstacle>,
}

impl PotentialField {
    /// A field toward `goal` around `obstacles` with default parameters.
    #[must_use]
    pub fn new(goal: DVec2, obstacles: Vec<CircleObstacle>) -> Self {
        Self {
            params: FieldParams::default(),
            goal,
            obstacles,
        }
    }

    /// Attractive force at `p` (zero at the goal itself).
    #[must_use]
    pub fn attractive_force(&self, p: DVec2) -> DVec2 {
        let to_goal = self.goal - p;
        let k = finite_or_zero(self.params.k_att);
        match self.params.attraction {
            Attraction::Conic => to_goal.normalize_or_zero() * k,
            Attraction::Quadratic => to_goal * k,
        }
    }

    /// Sum of the repulsive forces at `p`. An obstacle whose centre is exactly
    /// `p` has no defined direction and contributes nothing.
    #[must_use]
    pub fn repulsive_force(&self, p: DVec2) -> DVec2 {
        self.obstacles
            .iter()
            .map(|o| {
                let grad_d = (p - o.centre).normalize_or_zero();
                grad_d * self.repulsion_magnitude(o.clearance_m(p))
            })
            .sum()
    }

    /// Net force `F = −∇U` at `p`; zero for a non-finite `p`.
    ///
    /// # Example
    /// ```
    /// use labcore::mobile::potential_field::{CircleObstacle, PotentialField};
    /// use glam::DVec2;
    /// let field = PotentialField::new(DVec2::new(5.0, 0.0), vec![CircleObstacle::new(DVec2::ZERO, 0.5)]);
    /// // 0.25 m from the surface, goal straight through the obstacle:
    /// // pull 1 toward +x, push 1.6·(1 − 0.25)/1 = 1.2 toward −x.
    /// let f = field.force(DVec2::new(-0.75, 0.0));
    /// assert!((f.x + 0.2).abs() < 1e-12 && f.y == 0.0);
    /// ```
    #[must_use]
    pub fn force(&self, p: DVec2) -> DVec2 {
        if !p.is_finite() {
            return DVec2::ZERO;
        }
        let f = self.attractive_force(p) + self.repulsive_force(p);
        if f.is_finite() {
            f
        } else {
            DVec2::ZERO
        }
    }

    /// Potential `U(p) = U_att + Σ U_rep` (for a heat map). Inside an
    /// obstacle the repulsive term takes its value at the clearance
    /// [`MIN_CLEARANCE_M`] (linear law: at the surface), so `U` stays finite.
    #[must_use]
    pub fn potential(&self, p: DVec2) -> f64 {
        let dist = (self.goal - p).length();
        let k_a = finite_or_zero(self.params.k_att);
        let att = match self.params.attraction {
            Attraction::Conic => k_a * dist,
            Attraction::Quadratic => 0.5 * k_a * dist * dist,
        };
        let rep: f64 = self
            .obstacles
            .iter()
            .map(|o| self.repulsive_potential(o.clearance_m(p)))
            .sum();
        let u = att + rep;
        if u.is_nan() {
            0.0
        } else {
            u
        }
    }

    /// Samples [`PotentialField::potential`] at the centres of a `cols × rows`
    /// grid over `[min, max]`, row-major from `min.y` upward.
    #[must_use]
    pub fn potential_map(&self, min: DVec2, max: DVec2, cols: usize, rows: usize) -> Vec<f64> {
        let (cols, rows) = (cols.min(MAX_GRID_SIDE), rows.min(MAX_GRID_SIDE));
        let cell = (max - min) / DVec2::new(cols.max(1) as f64, rows.max(1) as f64);
        let mut out = Vec::with_capacity(cols * rows);
        for r in 0..rows {
            for c in 0..cols {
                out.push(self.potential(min + cell * DVec2::new(c as f64 + 0.5, r as f64 + 0.5)));
            }
        }
        out
    }

    /// Smallest clearance to any obstacle, metres (`+∞` with none).
    #[must_use]
    pub fn clearance_m(&self, p: DVec2) -> f64 {
        self.obstacles
            .iter()
            .map(|o| o.clearance_m(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// `p` lies inside (or on) an obstacle.
    #[must_use]
    pub fn inside_obstacle(&self, p: DVec2) -> bool {
        self.clearance_m(p) <= 0.0
    }

    fn influence(&self) -> f64 {
        let d0 = self.params.influence_m;
        if d0.is_finite() && d0 > 0.0 {
            d0
        } else {
            0.0
        }
    }

    fn repulsion_magnitude(&self, d: f64) -> f64 {
        let d0 = self.influence();
        if d.is_nan() || d >= d0 {
            return 0.0;
        }
        let k = finite_or_zero(self.params.k_rep);
        match self.params.repulsion {
            Repulsion::Linear => k * (d0 - d.max(0.0)) / d0,
            Repulsion::Khatib => {
                let d = d.max(MIN_CLEARANCE_M.min(0.5 * d0));
                k * (1.0 / d - 1.0 / d0) / (d * d)
            }
        }
    }

    fn repulsive_potential(&self, d: f64) -> f64 {
        let d0 = self.influence();
        if d.is_nan() || d >= d0 {
            return 0.0;
        }
        let k = finite_or_zero(self.params.k_rep);
        match self.params.repulsion {
            Repulsion::Linear => {
                let g = d0 - d.max(0.0);
                k * g * g / (2.0 * d0)
            }
            Repulsion::Khatib => {
                let d = d.max(MIN_CLEARANCE_M.min(0.5 * d0));
                let g = 1.0 / d - 1.0 / d0;
                0.5 * k * g * g
            }
        }
    }
}

fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() {
        x
    } else {
        0.0
    }
}

/// Stall detection and the time bound of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrapDetection {
    /// Progress window `T`, seconds.
    pub window_s: f64,
    /// Improvement `ε` of the best distance to the goal that counts as
    /// progress, metres.
    pub min_progress_m: f64,
    /// Hard limit on a run's duration, seconds.
    pub max_time_s: f64,
    /// A trapped robot stays within this distance of one spot for the whole
    /// window, metres (a robot that keeps driving is not trapped).
    pub hold_radius_m: f64,
}

impl Default for TrapDetection {
    fn default() -> Self {
        Self {
            window_s: 5.0,
            min_progress_m: 0.05,
            max_time_s: 120.0,
            hold_radius_m: 0.3,
        }
    }
}

/// Everything that drives a run besides the field.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldRunConfig {
    pub controller: GoToGoal,
    pub trap: TrapDetection,
    pub integrator: Integrator,
    /// Sub-steps per step, at least 1.
    pub substeps: usize,
    /// Step used by [`run_to_end`] and [`BasinMap`], seconds.
    pub dt_s: f64,
    /// The field's rectangle `(min, max)`, metres: a robot that ends a step
    /// outside it has been pushed off the field ([`RunStatus::LeftField`]).
    /// `None`: the plane is unbounded.
    pub bounds: Option<(DVec2, DVec2)>,
}

impl Default for FieldRunConfig {
    fn default() -> Self {
        Self {
            controller: GoToGoal::default(),
            trap: TrapDetection::default(),
            integrator: Integrator::Euler,
            substeps: 1,
            dt_s: 0.02,
            bounds: None,
        }
    }
}

/// Where a run stands.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RunStatus {
    #[default]
    Running,
    /// Within the controller's tolerance of the goal.
    Reached,
    /// No progress over the detection window while staying within
    /// [`TrapDetection::hold_radius_m`] of one spot, away from the goal.
    Trapped,
    /// The robot ended a step outside [`FieldRunConfig::bounds`]: the
    /// repulsion pushed it off the field.
    LeftField,
    /// The robot ended a step inside an obstacle.
    Collided,
    /// The start pose lies inside an obstacle.
    StartInsideObstacle,
    /// `max_time_s` elapsed.
    TimedOut,
}

impl RunStatus {
    /// The run has ended.
    #[must_use]
    pub fn is_final(self) -> bool {
        self != RunStatus::Running
    }
}

/// State of one potential-field run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldRun {
    pub pose: Pose,
    pub status: RunStatus,
    /// Time since the start, seconds.
    pub time_s: f64,
    /// Distance travelled, metres.
    pub path_length_m: f64,
    /// Smallest distance to the goal so far, metres.
    pub best_distance_m: f64,
    /// When `best_distance_m` last improved by at least `min_progress_m`, seconds.
    pub last_progress_s: f64,
    /// The spot the robot has stayed near (within
    /// [`TrapDetection::hold_radius_m`]) since `anchor_s`.
    pub anchor: DVec2,
    /// Since when the robot has stayed near `anchor`, seconds.
    pub anchor_s: f64,
    /// Smallest clearance to an obstacle so far, metres.
    pub min_clearance_m: f64,
    /// Net force at the pose of the last step.
    pub last_force: DVec2,
    /// Repulsive part of that force.
    pub last_repulsion: DVec2,
    /// The last command applied.
    pub last_command: Command,
}

impl FieldRun {
    /// A run starting at `pose` (status [`RunStatus::StartInsideObstacle`]
    /// when the start is inside an obstacle or not finite).
    #[must_use]
    pub fn new(pose: Pose, field: &PotentialField) -> Self {
        let p = pose.position();
        let clearance = field.clearance_m(p);
        let status = if !pose.is_finite() || clearance <= 0.0 {
            RunStatus::StartInsideObstacle
        } else {
            RunStatus::Running
        };
        let d = (field.goal - p).length();
        Self {
            pose,
            status,
            time_s: 0.0,
            path_length_m: 0.0,
            best_distance_m: d,
            last_progress_s: 0.0,
            anchor: p,
            anchor_s: 0.0,
            min_clearance_m: clearance,
            last_force: DVec2::ZERO,
            last_repulsion: DVec2::ZERO,
            last_command: Command::default(),
        }
    }

    /// One step of `dt_s` (ignored when not positive and finite, or when the
    /// run has ended). Returns the status afterwards.
    pub fn step(
        &mut self,
        field: &PotentialField,
        config: &FieldRunConfig,
        dt_s: f64,
    ) -> RunStatus {
        if self.status.is_final() || !(dt_s.is_finite() && dt_s > 0.0) {
            return self.status;
        }
        let p = self.pose.position();
        let distance = (field.goal - p).length();
        if distance <= config.controller.tolerance_m {
            self.status = RunStatus::Reached;
            self.last_command = Command {
                distance_m: distance,
                arrived: true,
                ..Command::default()
            };
            return self.status;
        }
        let force = field.force(p);
        self.last_force = force;
        self.last_repulsion = field.repulsive_force(p);
        let heading = if force.length_squared() > 0.0 {
            crate::math::atan2(force.y, force.x)
        } else {
            self.pose.theta_rad
        };
        let cmd = config
            .controller
            .command_for_heading(self.pose, heading, distance);
        self.pose = integrate(
            self.pose,
            cmd.v_mps,
            cmd.omega_radps,
            dt_s,
            config.substeps,
            config.integrator,
        );
        self.last_command = cmd;
        let q = self.pose.position();
        self.path_length_m += (q - p).length();
        self.time_s += dt_s;
        let clearance = field.clearance_m(q);
        self.min_clearance_m = self.min_clearance_m.min(clearance);
        let d = (field.goal - q).length();
        let trap = config.trap;
        if d < self.best_distance_m - trap.min_progress_m.max(0.0) {
            self.best_distance_m = d;
            self.last_progress_s = self.time_s;
        }
        let held = (q - self.anchor).length() <= trap.hold_radius_m; // false for NaN
        if !held {
            self.anchor = q;
            self.anchor_s = self.time_s;
        }
        let outside = config
            .bounds
            .is_some_and(|(lo, hi)| !(q.x >= lo.x && q.x <= hi.x && q.y >= lo.y && q.y <= hi.y));
        self.status = if clearance <= 0.0 {
            RunStatus::Collided
        } else if d <= config.controller.tolerance_m {
            RunStatus::Reached
        } else if outside {
            RunStatus::LeftField
        } else if self.time_s - self.last_progress_s >= trap.window_s
            && self.time_s - self.anchor_s >= trap.window_s
        {
            RunStatus::Trapped
        } else if self.time_s >= trap.max_time_s {
            RunStatus::TimedOut
        } else {
            RunStatus::Running
        };
        self.status
    }
}

/// Largest number of steps [`run_to_end`] takes.
pub const MAX_RUN_STEPS: u64 = 1_000_000;

/// Runs from `start` until the run ends, with `config.dt_s` steps; at most
/// `max_time_s / dt_s` steps (and [`MAX_RUN_STEPS`]), so it always returns.
///
/// # Example
/// ```
/// use labcore::mobile::potential_field::{run_to_end, CircleObstacle, FieldRunConfig, PotentialField, RunStatus};
/// use labcore::mobile::unicycle::Pose;
/// use glam::DVec2;
/// let field = PotentialField::new(DVec2::new(4.0, 0.0), vec![CircleObstacle::new(DVec2::new(0.0, 0.4), 0.5)]);
/// let run = run_to_end(&field, &FieldRunConfig::default(), Pose::new(-4.0, 0.0, 0.0));
/// assert_eq!(run.status, RunStatus::Reached);
/// assert!(run.min_clearance_m > 0.0);
/// ```
#[must_use]
pub fn run_to_end(field: &PotentialField, config: &FieldRunConfig, start: Pose) -> FieldRun {
    run_to_end_counted(field, config, start).0
}

/// [`run_to_end`], and how many steps of `config.dt_s` the run took.
#[must_use]
pub fn run_to_end_counted(
    field: &PotentialField,
    config: &FieldRunConfig,
    start: Pose,
) -> (FieldRun, u64) {
    let mut run = FieldRun::new(start, field);
    let dt = if config.dt_s.is_finite() && config.dt_s > 0.0 {
        config.dt_s
    } else {
        FieldRunConfig::default().dt_s
    };
    let max_time = if config.trap.max_time_s.is_finite() {
        config.trap.max_time_s.max(0.0)
    } else {
        TrapDetection::default().max_time_s
    };
    let steps = ((max_time / dt).ceil() as u64)
        .saturating_add(2)
        .min(MAX_RUN_STEPS);
    let mut taken = 0;
    for _ in 0..steps {
        taken += 1;
        if run.step(field, config, dt).is_final() {
            break;
        }
    }
    if run.status == RunStatus::Running {
        run.status = RunStatus::TimedOut;
    }
    (run, taken)
}

/// Class of a start cell in a [`BasinMap`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BasinClass {
    /// Not classified yet.
    #[default]
    Pending,
    ReachesGoal,
    Trapped,
    InsideObstacle,
    Collided,
    TimedOut,
    /// Pushed off the field ([`RunStatus::LeftField`]).
    LeftField,
}

impl From<RunStatus> for BasinClass {
    fn from(s: RunStatus) -> Self {
        match s {
            RunStatus::Running => BasinClass::Pending,
            RunStatus::Reached => BasinClass::ReachesGoal,
            RunStatus::Trapped => BasinClass::Trapped,
            RunStatus::Collided => BasinClass::Collided,
            RunStatus::StartInsideObstacle => BasinClass::InsideObstacle,
            RunStatus::TimedOut => BasinClass::TimedOut,
            RunStatus::LeftField => BasinClass::LeftField,
        }
    }
}

/// Largest side of a [`BasinMap`] or [`PotentialField::potential_map`], cells.
pub const MAX_GRID_SIDE: usize = 1024;

/// Cell counts of a [`BasinMap`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BasinCounts {
    pub pending: usize,
    pub reaches_goal: usize,
    pub trapped: usize,
    pub inside_obstacle: usize,
    pub collided: usize,
    pub timed_out: usize,
    pub left_field: usize,
}

/// Basin-of-attraction map: for each cell centre of a grid over
/// `[min, max]`, where a run started there (heading toward the goal) ends.
/// Built progressively by [`BasinMap::advance`], row-major from `min.y` up.
#[derive(Clone, Debug, PartialEq)]
pub struct BasinMap {
    pub min: DVec2,
    pub max: DVec2,
    pub cols: usize,
    pub rows: usize,
    /// `cols × rows` classes, row-major.
    pub cells: Vec<BasinClass>,
    next: usize,
}

impl BasinMap {
    /// An empty map; `None` unless `min < max` (finite) and both sides are in
    /// `1..=`[`MAX_GRID_SIDE`].
    #[must_use]
    pub fn new(min: DVec2, max: DVec2, cols: usize, rows: usize) -> Option<Self> {
        let ok = min.is_finite()
            && max.is_finite()
            && min.x < max.x
            && min.y < max.y
            && (1..=MAX_GRID_SIDE).contains(&cols)
            && (1..=MAX_GRID_SIDE).contains(&rows);
        ok.then(|| Self {
            min,
            max,
            cols,
            rows,
            cells: vec![BasinClass::Pending; cols * rows],
            next: 0,
        })
    }

    /// Centre of cell `(col, row)`, metres.
    #[must_use]
    pub fn cell_centre(&self, col: usize, row: usize) -> DVec2 {
        let cell = (self.max - self.min) / DVec2::new(self.cols as f64, self.rows as f64);
        self.min + cell * DVec2::new(col as f64 + 0.5, row as f64 + 0.5)
    }

    /// The start pose used for a cell: its centre, heading toward the goal.
    #[must_use]
    pub fn start_pose(&self, field: &PotentialField, col: usize, row: usize) -> Pose {
        let p = self.cell_centre(col, row);
        let d = field.goal - p;
        Pose::new(p.x, p.y, crate::math::atan2(d.y, d.x))
    }

    /// Classifies one start pose with a full run.
    #[must_use]
    pub fn classify(field: &PotentialField, config: &FieldRunConfig, start: Pose) -> BasinClass {
        run_to_end(field, config, start).status.into()
    }

    /// Classifies up to `cell_budget` more cells; returns how many it did.
    /// Call again (e.g. once per frame) until [`BasinMap::is_complete`]. Pass
    /// the same field and config every time, or [`BasinMap::restart`].
    pub fn advance(
        &mut self,
        field: &PotentialField,
        config: &FieldRunConfig,
        cell_budget: usize,
    ) -> usize {
        self.advance_counted(field, config, cell_budget).0
    }

    /// [`BasinMap::advance`], also counting the field steps its runs took
    /// (the work done): `(cells classified, steps)`.
    pub fn advance_counted(
        &mut self,
        field: &PotentialField,
        config: &FieldRunConfig,
        cell_budget: usize,
    ) -> (usize, u64) {
        let mut done = 0;
        let mut steps = 0;
        while done < cell_budget && self.next < self.cells.len() {
            let (col, row) = (self.next % self.cols, self.next / self.cols);
            let start = self.start_pose(field, col, row);
            let (run, taken) = run_to_end_counted(field, config, start);
            self.cells[self.next] = run.status.into();
            steps += taken;
            self.next += 1;
            done += 1;
        }
        (done, steps)
    }

    /// Forgets every classification.
    pub fn restart(&mut self) {
        self.cells.fill(BasinClass::Pending);
        self.next = 0;
    }

    /// Every cell is classified.
    #[must_use]
    pub fn is_complete(&self) -> bool {
        self.next >= self.cells.len()
    }

    /// Share of cells classified, in `[0, 1]`.
    #[must_use]
    pub fn progress(&self) -> f64 {
        self.next as f64 / self.cells.len().max(1) as f64
    }

    /// The class of cell `(col, row)`, `None` outside the grid.
    #[must_use]
    pub fn get(&self, col: usize, row: usize) -> Option<BasinClass> {
        (col < self.cols && row < self.rows).then(|| self.cells[row * self.cols + col])
    }

    /// Cell counts by class.
    #[must_use]
    pub fn counts(&self) -> BasinCounts {
        let mut c = BasinCounts::default();
        for cell in &self.cells {
            match cell {
                BasinClass::Pending => c.pending += 1,
                BasinClass::ReachesGoal => c.reaches_goal += 1,
                BasinClass::Trapped => c.trapped += 1,
                BasinClass::InsideObstacle => c.inside_obstacle += 1,
                BasinClass::Collided => c.collided += 1,
                BasinClass::TimedOut => c.timed_out += 1,
                BasinClass::LeftField => c.left_field += 1,
            }
        }
        c
    }

    /// Share of the classified free start cells (not inside an obstacle)
    /// that reach the goal, in `[0, 1]`; 0 before any is classified.
    #[must_use]
    pub fn reach_share(&self) -> f64 {
        let c = self.counts();
        let free = c.reaches_goal + c.trapped + c.collided + c.timed_out + c.left_field;
        if free == 0 {
            0.0
        } else {
            c.reaches_goal as f64 / free as f64
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Lcg64;
    use std::f64::consts::PI;

    fn two_obstacle_trap() -> PotentialField {
        // Two obstacles 0.4 m apart (surface to surface) across the
        // start–goal line: their repulsions' x-components beat the pull in
        // front of the gap, and their y-components cancel on the line and
        // push back toward it off the line — a stable local minimum.
        PotentialField::new(
            DVec2::new(4.0, 0.0),
            vec![
                CircleObstacle::new(DVec2::new(0.0, 0.6), 0.4),
                CircleObstacle::new(DVec2::new(0.0, -0.6), 0.4),
            ],
        )
    }

    #[test]
    fn reaches_the_goal_around_a_single_obstacle() {
        let config = FieldRunConfig::default();
        for law in [Repulsion::Linear, Repulsion::Khatib] {
            for start_y in [-1.0, 0.3, 0.8] {
                let mut field = PotentialField::new(
                    DVec2::new(4.0, 0.0),
                    vec![CircleObstacle::new(DVec2::new(0.0, 0.0), 0.6)],
                );
                field.params.repulsion = law;
                if law == Repulsion::Khatib {
                    field.params.k_rep = 0.05;
                }
                let run = run_to_end(&field, &config, Pose::new(-4.0, start_y, 0.0));
                assert_eq!(
                    run.status,
                    RunStatus::Reached,
                    "{law:?} y={start_y}: {run:?}"
                );
                assert!(run.min_clearance_m > 0.05, "{run:?}");
                assert!(run.path_length_m > 8.0 && run.path_length_m < 12.0);
            }
        }
    }

    /// The two-obstacle trap and a U-shaped cup of three obstacles stop the
    /// run as Trapped, well before the hard time limit, for starts on and off
    /// the symmetry line. A single obstacle dead ahead is only a saddle: the
    /// unicycle's turn on the spot breaks the symmetry and it escapes.
    #[test]
    fn symmetric_traps_are_reported_in_bounded_time() {
        let config = FieldRunConfig::default();
        let cup = PotentialField::new(
            DVec2::new(4.0, 0.0),
            vec![
                CircleObstacle::new(DVec2::new(0.6, 0.0), 0.4),
                CircleObstacle::new(DVec2::new(0.1, 0.75), 0.4),
                CircleObstacle::new(DVec2::new(0.1, -0.75), 0.4),
            ],
        );
        for field in [two_obstacle_trap(), cup] {
            for start in [Pose::new(-4.0, 0.0, 0.0), Pose::new(-4.0, 0.7, -0.3)] {
                let run = run_to_end(&field, &config, start);
                assert_eq!(run.status, RunStatus::Trapped, "{run:?}");
                assert!(run.time_s < 30.0, "took {} s", run.time_s);
                assert!(run.best_distance_m > 3.0);
                assert!(run.min_clearance_m > 0.0);
            }
        }
        let single = PotentialField::new(
            DVec2::new(4.0, 0.0),
            vec![CircleObstacle::new(DVec2::ZERO, 0.6)],
        );
        let run = run_to_end(&single, &config, Pose::new(-4.0, 0.0, 0.0));
        assert_eq!(run.status, RunStatus::Reached, "{run:?}");
        assert!(run.min_clearance_m > 0.0);
    }

    #[test]
    fn gradient_matches_finite_differences_of_the_potential() {
        let mut rng = Lcg64::new(17);
        for attraction in [Attraction::Conic, Attraction::Quadratic] {
            for repulsion in [Repulsion::Linear, Repulsion::Khatib] {
                let mut field = two_obstacle_trap();
                field
                    .obstacles
                    .push(CircleObstacle::new(DVec2::new(2.0, 1.5), 0.7));
                field.params.attraction = attraction;
                field.params.repulsion = repulsion;
                let mut checked = 0;
                while checked < 500 {
                    let p = DVec2::new(rng.range(-3.0, 5.0), rng.range(-3.0, 3.0));
                    let near_kink = field
                        .obstacles
                        .iter()
                        .any(|o| (o.clearance_m(p) - field.params.influence_m).abs() < 1e-3);
                    if field.clearance_m(p) < 0.05 || (p - field.goal).length() < 0.05 || near_kink
                    {
                        continue;
                    }
                    let h = 1e-6;
                    let gx = (field.potential(p + DVec2::X * h)
                        - field.potential(p - DVec2::X * h))
                        / (2.0 * h);
                    let gy = (field.potential(p + DVec2::Y * h)
                        - field.potential(p - DVec2::Y * h))
                        / (2.0 * h);
                    let f = field.force(p);
                    let err = (f + DVec2::new(gx, gy)).length();
                    assert!(
                        err < 1e-5 * (1.0 + f.length()),
                        "{attraction:?}/{repulsion:?} at {p}: F={f}, ∇U=({gx},{gy})"
                    );
                    checked += 1;
                }
            }
        }
    }

    #[test]
    fn potential_and_force_stay_finite_everywhere() {
        let mut field = two_obstacle_trap();
        for repulsion in [Repulsion::Linear, Repulsion::Khatib] {
            field.params.repulsion = repulsion;
            for p in [
                DVec2::new(0.0, 0.6),
                DVec2::new(0.0, 0.2),
                field.goal,
                DVec2::new(f64::NAN, 0.0),
                DVec2::new(1e300, -1e300),
            ] {
                assert!(field.force(p).is_finite(), "{p}");
                assert!(!field.potential(p).is_nan(), "{p}");
            }
        }
        let map = field.potential_map(DVec2::new(-2.0, -2.0), DVec2::new(2.0, 2.0), 8, 4);
        assert_eq!(map.len(), 32);
        assert!(map.iter().all(|u| u.is_finite()));
        // Bad parameters never produce NaN.
        field.params = FieldParams {
            k_att: f64::NAN,
            k_rep: f64::INFINITY,
            influence_m: -1.0,
            ..FieldParams::default()
        };
        assert!(field.force(DVec2::new(0.0, 0.1)).is_finite());
        assert!(field.potential(DVec2::new(0.0, 0.1)).is_finite());
    }

    #[test]
    fn start_inside_an_obstacle_and_bad_steps() {
        let field = two_obstacle_trap();
        let config = FieldRunConfig::default();
        let run = run_to_end(&field, &config, Pose::new(0.0, 0.6, 0.0));
        assert_eq!(run.status, RunStatus::StartInsideObstacle);
        assert_eq!(run.time_s, 0.0);
        let mut run = FieldRun::new(Pose::new(-3.0, 0.0, 0.0), &field);
        assert_eq!(run.step(&field, &config, f64::NAN), RunStatus::Running);
        assert_eq!(run.step(&field, &config, -1.0), RunStatus::Running);
        assert_eq!(run.time_s, 0.0);
        // A zero-length hard limit still ends.
        let cfg = FieldRunConfig {
            trap: TrapDetection {
                max_time_s: 0.0,
                ..TrapDetection::default()
            },
            ..config
        };
        let run = run_to_end(&field, &cfg, Pose::new(-3.0, 0.0, 0.0));
        assert_eq!(run.status, RunStatus::TimedOut);
    }

    /// The map, built over several budgeted calls, agrees with individual
    /// runs from sampled cells; the trap arrangement has both kinds of cell.
    #[test]
    fn basin_map_agrees_with_individual_runs() {
        let field = two_obstacle_trap();
        let config = FieldRunConfig {
            dt_s: 0.05,
            ..FieldRunConfig::default()
        };
        let mut map = BasinMap::new(DVec2::new(-4.0, -3.0), DVec2::new(3.0, 3.0), 14, 12).unwrap();
        let mut calls = 0;
        while !map.is_complete() {
            let did = map.advance(&field, &config, 25);
            assert!(did > 0 && did <= 25);
            calls += 1;
        }
        assert_eq!(calls, (14 * 12 + 24) / 25);
        assert_eq!(map.advance(&field, &config, 25), 0);
        assert_eq!(map.progress(), 1.0);
        let c = map.counts();
        assert_eq!(c.pending, 0);
        assert!(
            c.reaches_goal > 0 && c.trapped > 0 && c.inside_obstacle > 0,
            "{c:?}"
        );
        let share = map.reach_share();
        assert!(share > 0.3 && share < 1.0, "{share}");
        let mut rng = Lcg64::new(5);
        for _ in 0..20 {
            let (col, row) = (rng.int(0, 13) as usize, rng.int(0, 11) as usize);
            let start = map.start_pose(&field, col, row);
            let direct: BasinClass = run_to_end(&field, &config, start).status.into();
            assert_eq!(map.get(col, row), Some(direct));
        }
        // The cell straight in front of the gap, on the line, is trapped.
        let trapped = run_to_end(&field, &config, Pose::new(-2.0, 0.0, 0.0));
        assert_eq!(trapped.status, RunStatus::Trapped);
        assert_eq!(map.get(14, 0), None);
        assert!(BasinMap::new(DVec2::ONE, DVec2::ZERO, 4, 4).is_none());
        assert!(BasinMap::new(DVec2::ZERO, DVec2::ONE, 0, 4).is_none());
        map.restart();
        assert_eq!(map.counts().pending, 14 * 12);
        assert_eq!(map.reach_share(), 0.0);
    }

    /// Issue 15: with `N·k_r < k_a` the pull beats every combination of
    /// pushes, so the force never vanishes away from the goal and no start
    /// ends trapped; but a robot heading at an obstacle is not stopped
    /// before its surface either.
    #[test]
    fn no_trap_when_the_pull_beats_every_push() {
        let mut field = two_obstacle_trap();
        field.params.k_att = 2.0;
        field.params.k_rep = 0.9;
        assert!(field.params.trap_free(2));
        let floor = 2.0 - 2.0 * 0.9;
        let mut rng = Lcg64::new(3);
        for _ in 0..2000 {
            let p = DVec2::new(rng.range(-4.0, 5.0), rng.range(-3.0, 3.0));
            if field.inside_obstacle(p) || (p - field.goal).length() < 1e-9 {
                continue;
            }
            assert!(field.force(p).length() >= floor - 1e-12, "{p}");
        }
        let config = FieldRunConfig {
            dt_s: 0.05,
            ..FieldRunConfig::default()
        };
        let mut map = BasinMap::new(DVec2::new(-4.0, -3.0), DVec2::new(3.0, 3.0), 14, 12).unwrap();
        map.advance(&field, &config, usize::MAX);
        let c = map.counts();
        assert_eq!(c.trapped, 0, "{c:?}");
        assert!(c.collided > 0, "{c:?}");
        // Head-on at the gap's line through obstacle 1's centre: it touches.
        let run = run_to_end(&field, &config, Pose::new(-3.0, 0.6, 0.0));
        assert_eq!(run.status, RunStatus::Collided, "{run:?}");
        // The default gains (k_r > k_a) stop the same robot short of the surface.
        let mut strong = field.clone();
        strong.params = FieldParams::default();
        assert!(!strong.params.trap_free(2));
        let run = run_to_end(&strong, &config, Pose::new(-3.0, 0.6, 0.0));
        assert_ne!(run.status, RunStatus::Collided, "{run:?}");
        assert!(run.min_clearance_m > 0.0);
    }

    /// Issue 13: a robot that keeps driving without getting closer to the
    /// goal is not trapped (it was, after 5 s, at 1.1 m/s); leaving the
    /// field's rectangle is its own outcome.
    #[test]
    fn driving_away_is_not_a_trap_and_leaving_the_field_is_its_own_end() {
        let mut field = PotentialField::new(
            DVec2::new(7.5, 3.0),
            vec![
                CircleObstacle::new(DVec2::new(3.0, 3.4), 1.2),
                CircleObstacle::new(DVec2::new(5.2, 2.2), 1.2),
            ],
        );
        field.params.k_att = 0.1;
        field.params.k_rep = 5.0;
        field.params.influence_m = 3.0;
        let start = Pose::new(0.6, 3.0, 0.0);
        let unbounded = FieldRunConfig::default();
        let mut run = FieldRun::new(start, &field);
        let mut moving_after_window = false;
        while run.time_s < 8.0 && !run.step(&field, &unbounded, 0.02).is_final() {
            if run.time_s > unbounded.trap.window_s && run.last_command.v_mps > 0.5 {
                moving_after_window = true;
            }
        }
        assert!(moving_after_window, "{run:?}");
        assert_ne!(run.status, RunStatus::Trapped, "{run:?}");
        let bounded = FieldRunConfig {
            bounds: Some((DVec2::ZERO, DVec2::new(8.0, 6.0))),
            ..unbounded
        };
        let run = run_to_end(&field, &bounded, start);
        assert_eq!(run.status, RunStatus::LeftField, "{run:?}");
        let q = run.pose.position();
        assert!(q.x < 0.0 || q.y < 0.0 || q.x > 8.0 || q.y > 6.0, "{q}");
        assert_eq!(BasinClass::from(run.status), BasinClass::LeftField);
    }

    /// A trapped run stayed near one spot for the whole window.
    #[test]
    fn a_trap_holds_the_robot_near_one_spot() {
        let field = two_obstacle_trap();
        let config = FieldRunConfig::default();
        let run = run_to_end(&field, &config, Pose::new(-4.0, 0.0, 0.0));
        assert_eq!(run.status, RunStatus::Trapped);
        assert!(run.time_s - run.anchor_s >= config.trap.window_s);
        assert!((run.pose.position() - run.anchor).length() <= config.trap.hold_radius_m);
    }

    #[test]
    fn heading_follows_the_force_direction() {
        let field = two_obstacle_trap();
        let config = FieldRunConfig::default();
        let mut run = FieldRun::new(Pose::new(-3.0, 2.0, PI / 2.0), &field);
        run.step(&field, &config, 0.02);
        let f = run.last_force;
        let expected =
            crate::kinematics::two_link_ik::wrap_pi(crate::math::atan2(f.y, f.x) - PI / 2.0);
        assert!((run.last_command.heading_error_rad - expected).abs() < 1e-12);
        assert!(run.last_command.omega_radps < 0.0);
    }
}
