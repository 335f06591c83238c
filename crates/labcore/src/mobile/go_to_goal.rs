//! Proportional go-to-goal controller for a unicycle, and a waypoint follower.
//!
//! With the goal `d` metres away along bearing `atan2(dy, dx)`, the heading
//! error, the commanded turn rate and the forward speed are (lab spec,
//! experiment 4; Siegwart, Nourbakhsh & Scaramuzza, *Introduction to
//! Autonomous Mobile Robots*, 2nd ed., 2011, §3.6.2 "Feedback control"):
//!
//! ```text
//! eθ = wrap(atan2(dy, dx) − θ)  ∈ [−π, π]
//! ω  = clamp(Kω · eθ, ±ω_max)
//! v  = clamp(Kv · d · max(0, cos eθ), 0, v_max)
//! ```
//!
//! so the robot turns on the spot while the goal is behind it (`|eθ| ≥ π/2`),
//! then drives in, slowing as the distance shrinks. It has arrived once
//! `d ≤ tolerance`.
//!
//! **Why it always arrives** (continuous time): `ḋ = −v cos eθ =
//! −Kv d max(0, cos eθ)·cos eθ ≤ 0`, so the distance never grows, and
//! `ėθ = −ω + (v/d) sin eθ`, where `|(v/d) sin eθ| ≤ Kv/2`. With the
//! defaults `Kv/2 = 0.6 < ω_max = 1.4` and `Kω = 3.5`, the heading error
//! decays whenever it is not already small, and then `d` decays
//! exponentially. Keeping `Kv < 2 ω_max` preserves that argument; the speed
//! limit only slows the approach.

use std::collections::VecDeque;

use glam::DVec2;

use super::unicycle::{integrate, Integrator, Pose};
use crate::kinematics::two_link_ik::wrap_pi;

/// Gains and limits of the proportional controller (SI units).
///
/// The lab page shows the spec's figures: `Kω = 3.5`, `Kv = 1.2`,
/// max v = 110 px/s (here 1.1 m/s at 100 px per metre), max ω 1.4 rad/s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GoToGoal {
    /// Heading gain `Kω`, 1/s.
    pub k_omega_per_s: f64,
    /// Speed gain `Kv`, 1/s (speed per metre of remaining distance).
    pub k_v_per_s: f64,
    /// Largest forward speed, m/s.
    pub max_v_mps: f64,
    /// Largest turn rate magnitude, rad/s.
    pub max_omega_radps: f64,
    /// Arrival radius, metres.
    pub tolerance_m: f64,
}

impl Default for GoToGoal {
    fn default() -> Self {
        Self {
            k_omega_per_s: 3.5,
            k_v_per_s: 1.2,
            max_v_mps: 1.1,
            max_omega_radps: 1.4,
            tolerance_m: 0.05,
        }
    }
}

/// One controller output, with what produced it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Command {
    /// Forward speed, m/s, in `[0, max_v]`.
    pub v_mps: f64,
    /// Turn rate, rad/s, in `[−ω_max, ω_max]`.
    pub omega_radps: f64,
    /// Heading error `eθ`, radians in `[−π, π]`.
    pub heading_error_rad: f64,
    /// Distance to the goal, metres.
    pub distance_m: f64,
    /// The speed limit clipped `v`.
    pub v_limited: bool,
    /// The turn-rate limit clipped `ω`.
    pub omega_limited: bool,
    /// `distance ≤ tolerance`: the command is zero.
    pub arrived: bool,
    /// The heading `θ` of the pose the command was computed from, radians
    /// (what the unicycle moves along while the command holds).
    pub heading_rad: f64,
}

impl GoToGoal {
    /// Every field finite, gains and limits non-negative.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        [
            self.k_omega_per_s,
            self.k_v_per_s,
            self.max_v_mps,
            self.max_omega_radps,
            self.tolerance_m,
        ]
        .iter()
        .all(|x| x.is_finite() && *x >= 0.0)
    }

    /// The controller's command toward `goal` from `pose`. Zero (and
    /// `arrived`) within the tolerance; zero with `arrived == false` on
    /// non-finite input or invalid settings.
    ///
    /// # Example
    /// ```
    /// use labcore::mobile::go_to_goal::GoToGoal;
    /// use labcore::mobile::unicycle::Pose;
    /// let c = GoToGoal::default().command(Pose::new(0.0, 0.0, 0.0), glam::DVec2::new(0.0, 2.0));
    /// // Goal to the left: turn left at the rate limit; cos(π/2) = 0 so barely any speed.
    /// assert!((c.heading_error_rad - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    /// assert_eq!(c.omega_radps, 1.4);
    /// assert!(c.v_mps < 1e-12);
    /// ```
    #[must_use]
    pub fn command(&self, pose: Pose, goal: DVec2) -> Command {
        let d = goal - pose.position();
        let distance_m = d.length();
        if !distance_m.is_finite() || !pose.is_finite() || !self.is_valid() {
            return Command::default();
        }
        if distance_m <= self.tolerance_m {
            return Command {
                distance_m,
                arrived: true,
                heading_rad: pose.theta_rad,
                ..Command::default()
            };
        }
        let bearing = crate::math::atan2(d.y, d.x);
        self.command_for_heading(pose, bearing, distance_m)
    }

    /// The same control law with the desired heading given directly (the
    /// potential field passes its force direction) and `distance_m` as the
    /// distance that scales the speed. No arrival test.
    #[must_use]
    pub fn command_for_heading(
        &self,
        pose: Pose,
        desired_heading_rad: f64,
        distance_m: f64,
    ) -> Command {
        let finite = pose.is_finite() && desired_heading_rad.is_finite() && distance_m.is_finite();
        if !(finite && self.is_valid()) {
            return Command::default();
        }
        let e = wrap_pi(desired_heading_rad - pose.theta_rad);
        let omega_raw = self.k_omega_per_s * e;
        let omega = omega_raw.clamp(-self.max_omega_radps, self.max_omega_radps);
        let v_raw = self.k_v_per_s * distance_m.max(0.0) * crate::math::cos(e).max(0.0);
        let v = v_raw.min(self.max_v_mps);
        Command {
            v_mps: v,
            omega_radps: omega,
            heading_error_rad: e,
            distance_m,
            v_limited: v_raw > self.max_v_mps,
            omega_limited: omega_raw.abs() > self.max_omega_radps,
            arrived: false,
            heading_rad: pose.theta_rad,
        }
    }
}

/// Statistics of one run toward one goal.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RunStats {
    /// Distance travelled, metres.
    pub path_length_m: f64,
    /// Time since the run started, seconds.
    pub elapsed_s: f64,
    /// Time at which the goal was reached, seconds from the start of the run.
    pub time_to_goal_s: Option<f64>,
    /// Largest `|eθ|` seen, radians.
    pub max_heading_error_rad: f64,
    /// Time spent with `v` at its limit, seconds.
    pub time_at_v_limit_s: f64,
    /// Time spent with `ω` at its limit, seconds.
    pub time_at_omega_limit_s: f64,
}

impl RunStats {
    /// Share of the run's time spent at the speed limit, in `[0, 1]`.
    #[must_use]
    pub fn v_limit_share(&self) -> f64 {
        share(self.time_at_v_limit_s, self.elapsed_s)
    }

    /// Share of the run's time spent at the turn-rate limit, in `[0, 1]`.
    #[must_use]
    pub fn omega_limit_share(&self) -> f64 {
        share(self.time_at_omega_limit_s, self.elapsed_s)
    }

    /// Accounts for one step of `dt_s` under `cmd` that moved `moved_m`.
    pub fn record(&mut self, cmd: &Command, dt_s: f64, moved_m: f64) {
        self.elapsed_s += dt_s;
        self.path_length_m += moved_m;
        self.max_heading_error_rad = self.max_heading_error_rad.max(cmd.heading_error_rad.abs());
        if cmd.v_limited {
            self.time_at_v_limit_s += dt_s;
        }
        if cmd.omega_limited {
            self.time_at_omega_limit_s += dt_s;
        }
    }
}

fn share(part: f64, whole: f64) -> f64 {
    if whole > 0.0 {
        (part / whole).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// A robot that drives through a queue of waypoints with [`GoToGoal`].
///
/// Each [`WaypointFollower::step`] computes one command from the current pose
/// (held for the whole step, as a controller sampled once per frame would),
/// then integrates the unicycle over `dt` in `substeps` sub-steps.
#[derive(Clone, Debug, PartialEq)]
pub struct WaypointFollower {
    pub controller: GoToGoal,
    pub integrator: Integrator,
    /// Sub-steps per [`WaypointFollower::step`], at least 1.
    pub substeps: usize,
    /// Current pose.
    pub pose: Pose,
    /// Goals still to reach; the front one is active.
    pub queue: VecDeque<DVec2>,
    /// Statistics of the run toward the active goal.
    pub current: RunStats,
    /// Statistics of every goal reached, oldest first.
    pub completed: Vec<RunStats>,
    /// The last command applied.
    pub last_command: Command,
    /// The gains and limits [`WaypointFollower::last_command`] was computed
    /// with (the controller may have changed since).
    pub last_controller: GoToGoal,
}

impl WaypointFollower {
    /// A follower at `pose` with an empty queue, the default controller,
    /// Euler integration and one sub-step.
    #[must_use]
    pub fn new(pose: Pose) -> Self {
        Self {
            controller: GoToGoal::default(),
            integrator: Integrator::Euler,
            substeps: 1,
            pose,
            queue: VecDeque::new(),
            current: RunStats::default(),
            completed: Vec::new(),
            last_command: Command::default(),
            last_controller: GoToGoal::default(),
        }
    }

    /// Appends a goal (ignored when not finite). Returns whether it was queued.
    pub fn push_goal(&mut self, goal: DVec2) -> bool {
        if !goal.is_finite() {
            return false;
        }
        if self.queue.is_empty() {
            self.current = RunStats::default();
        }
        self.queue.push_back(goal);
        true
    }

    /// The active goal.
    #[must_use]
    pub fn goal(&self) -> Option<DVec2> {
        self.queue.front().copied()
    }

    /// Forgets all goals and statistics and moves the robot to `pose`.
    pub fn reset(&mut self, pose: Pose) {
        *self = Self {
            controller: self.controller,
            integrator: self.integrator,
            substeps: self.substeps,
            ..Self::new(pose)
        };
    }

    /// Advances by `dt_s` (ignored when negative or not finite). Returns the
    /// command applied; with no goal the robot stands still.
    pub fn step(&mut self, dt_s: f64) -> Command {
        if !(dt_s.is_finite() && dt_s >= 0.0) {
            return self.last_command;
        }
        let Some(goal) = self.goal() else {
            self.last_command = Command::default();
            return self.last_command;
        };
        let cmd = self.controller.command(self.pose, goal);
        self.last_controller = self.controller;
        if cmd.arrived {
            self.current.time_to_goal_s = Some(self.current.elapsed_s);
            self.completed.push(self.current);
            self.current = RunStats::default();
            self.queue.pop_front();
            self.last_command = cmd;
            return cmd;
        }
        let before = self.pose.position();
        self.pose = integrate(
            self.pose,
            cmd.v_mps,
            cmd.omega_radps,
            dt_s,
            self.substeps,
            self.integrator,
        );
        self.current
            .record(&cmd, dt_s, (self.pose.position() - before).length());
        self.last_command = cmd;
        cmd
    }

    /// Steps until the queue is empty or `max_time_s` has elapsed; returns
    /// whether every goal was reached.
    pub fn run(&mut self, dt_s: f64, max_time_s: f64) -> bool {
        if !(dt_s.is_finite() && dt_s > 0.0 && max_time_s.is_finite()) {
            return self.queue.is_empty();
        }
        let steps = (max_time_s / dt_s).ceil().clamp(0.0, 1e9) as u64;
        for _ in 0..steps {
            if self.queue.is_empty() {
                break;
            }
            self.step(dt_s);
        }
        self.queue.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Lcg64;
    use std::f64::consts::PI;

    /// Default gains reach every goal from every start pose (seeded sweep over
    /// a 10 m × 10 m field, random headings), within the tolerance and in
    /// bounded time, with Euler and RK4.
    #[test]
    fn default_gains_reach_any_goal_from_any_pose() {
        let mut rng = Lcg64::new(2024);
        for trial in 0..300 {
            let start = Pose::new(
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
                rng.range(-PI, PI),
            );
            let goal = DVec2::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0));
            let mut f = WaypointFollower::new(start);
            if trial % 2 == 1 {
                f.integrator = Integrator::Rk4;
                f.substeps = 4;
            }
            f.push_goal(goal);
            assert!(f.run(0.02, 40.0), "trial {trial}: {start:?} → {goal}");
            assert!((f.pose.position() - goal).length() <= f.controller.tolerance_m);
            let stats = f.completed[0];
            assert!(stats.time_to_goal_s.unwrap() < 40.0);
            assert!(stats.path_length_m + 1e-9 >= (goal - start.position()).length() - 0.05);
        }
    }

    #[test]
    fn heading_error_wraps_across_pi() {
        let c = GoToGoal::default();
        // Facing almost −π, goal just above the −x axis (bearing ≈ +π):
        // the error is small and positive, not ≈ 2π.
        let pose = Pose::new(0.0, 0.0, -PI + 0.05);
        let cmd = c.command(pose, DVec2::new(-3.0, 0.1));
        let bearing = crate::math::atan2(0.1, -3.0);
        let expected = bearing - (-PI + 0.05) - 2.0 * PI;
        assert!((cmd.heading_error_rad - expected).abs() < 1e-12);
        assert!(cmd.heading_error_rad.abs() < 0.1);
        assert!(cmd.v_mps > 1.0);
        // Goal straight behind: |eθ| = π, no forward speed, turn at the limit.
        let cmd = c.command(Pose::new(0.0, 0.0, 0.0), DVec2::new(-2.0, 0.0));
        assert!((cmd.heading_error_rad.abs() - PI).abs() < 1e-12);
        assert_eq!(cmd.v_mps, 0.0);
        assert!(cmd.omega_limited && cmd.omega_radps.abs() == 1.4);
    }

    #[test]
    fn limits_hold_and_are_counted() {
        let c = GoToGoal::default();
        let mut rng = Lcg64::new(8);
        for _ in 0..2000 {
            let pose = Pose::new(
                rng.range(-9.0, 9.0),
                rng.range(-9.0, 9.0),
                rng.range(-PI, PI),
            );
            let cmd = c.command(pose, DVec2::new(rng.range(-9.0, 9.0), rng.range(-9.0, 9.0)));
            assert!((0.0..=c.max_v_mps).contains(&cmd.v_mps));
            assert!(cmd.omega_radps.abs() <= c.max_omega_radps);
        }
        // A far goal straight ahead: speed pinned at the limit most of the way.
        let mut f = WaypointFollower::new(Pose::default());
        f.push_goal(DVec2::new(8.0, 0.0));
        assert!(f.run(0.01, 30.0));
        let s = f.completed[0];
        assert!(s.v_limit_share() > 0.5 && s.v_limit_share() < 1.0, "{s:?}");
        assert_eq!(s.omega_limit_share(), 0.0);
        assert!((s.path_length_m - 8.0).abs() < 0.06);
        assert!(s.max_heading_error_rad < 1e-12);
    }

    #[test]
    fn waypoint_queue_runs_in_order_with_statistics_per_goal() {
        let mut f = WaypointFollower::new(Pose::new(0.0, 0.0, PI));
        for g in [
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(0.0, 2.0),
        ] {
            assert!(f.push_goal(g));
        }
        assert!(!f.push_goal(DVec2::new(f64::NAN, 0.0)));
        assert_eq!(f.queue.len(), 3);
        assert!(f.run(0.02, 60.0));
        assert_eq!(f.completed.len(), 3);
        // The first goal is behind the start heading: a big initial error,
        // and the turn happened at the rate limit.
        assert!(f.completed[0].max_heading_error_rad > 3.0);
        assert!(f.completed[0].omega_limit_share() > 0.0);
        for s in &f.completed {
            assert!(s.time_to_goal_s.unwrap() > 0.0 && s.path_length_m > 1.9);
        }
        assert!((f.pose.position() - DVec2::new(0.0, 2.0)).length() <= 0.05);
        // With no goal the robot stands still.
        let before = f.pose;
        let cmd = f.step(0.1);
        assert_eq!((cmd.v_mps, cmd.omega_radps), (0.0, 0.0));
        assert_eq!(f.pose, before);
        f.reset(Pose::default());
        assert!(f.completed.is_empty() && f.pose == Pose::default());
    }

    #[test]
    fn invalid_settings_and_inputs_give_zero_commands() {
        let bad = GoToGoal {
            k_v_per_s: f64::NAN,
            ..GoToGoal::default()
        };
        let cmd = bad.command(Pose::default(), DVec2::new(1.0, 1.0));
        assert_eq!(cmd, Command::default());
        let cmd = GoToGoal::default().command(Pose::new(f64::NAN, 0.0, 0.0), DVec2::ONE);
        assert_eq!(cmd, Command::default());
        let mut f = WaypointFollower::new(Pose::default());
        f.push_goal(DVec2::ONE);
        f.step(f64::NAN);
        f.step(-1.0);
        assert_eq!(f.pose, Pose::default());
        assert!(!f.run(0.0, 10.0));
    }
}
