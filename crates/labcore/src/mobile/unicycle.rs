//! The unicycle (differential-drive) kinematic model.
//!
//! A differential-drive robot with pose `(x, y, θ)`, forward speed `v` and
//! turn rate `ω` moves as
//!
//! ```text
//! ẋ = v cos θ     ẏ = v sin θ     θ̇ = ω
//! ```
//!
//! (Siegwart, Nourbakhsh & Scaramuzza, *Introduction to Autonomous Mobile
//! Robots*, 2nd ed., MIT Press 2011, §3.2.1, eq. 3.9 and §3.3 on the
//! nonholonomic constraint; LaValle, *Planning Algorithms*, 2006, §13.1.2.3.)
//! The robot cannot move sideways: `ẋ sin θ − ẏ cos θ = 0` (the rolling
//! constraint of Siegwart et al. §3.2.3, eq. 3.12).
//!
//! With wheels `b` apart (the track), the wheel rim speeds are
//!
//! ```text
//! v_L = v − ω b/2     v_R = v + ω b/2     ⇔     v = (v_R + v_L)/2,   ω = (v_R − v_L)/b
//! ```
//!
//! (Siegwart et al. §3.2.1, eq. 3.6–3.8).
//!
//! **Integration.** [`integrate`] splits a frame's `dt` into fixed sub-steps of
//! explicit Euler (the spec's default: every step is a straight segment along
//! the current heading, so the nonholonomic constraint holds exactly step by
//! step) or classical fourth-order Runge–Kutta. For constant `v, ω` the exact
//! motion is a circular arc, [`exact_arc`]; the Euler position error is `O(dt)`
//! and RK4's `O(dt⁴)`.

use glam::DVec2;

use crate::kinematics::two_link_ik::wrap_pi;

/// Pose of a planar mobile robot: position in metres, heading in radians
/// (counter-clockwise from +x, kept in `[-π, π]` by this module).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pose {
    pub x_m: f64,
    pub y_m: f64,
    pub theta_rad: f64,
}

impl Pose {
    /// A pose from its parts.
    #[must_use]
    pub const fn new(x_m: f64, y_m: f64, theta_rad: f64) -> Self {
        Self {
            x_m,
            y_m,
            theta_rad,
        }
    }

    /// The position `(x, y)`, metres.
    #[must_use]
    pub fn position(&self) -> DVec2 {
        DVec2::new(self.x_m, self.y_m)
    }

    /// Unit vector along the heading, `(cos θ, sin θ)`.
    #[must_use]
    pub fn heading(&self) -> DVec2 {
        let (s, c) = crate::math::sin_cos(self.theta_rad);
        DVec2::new(c, s)
    }

    /// Every component finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.x_m.is_finite() && self.y_m.is_finite() && self.theta_rad.is_finite()
    }
}

/// Numerical integrator of [`integrate`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Integrator {
    /// Explicit Euler, `x ← x + dt · f(x)`: first order; each step is a
    /// straight segment along the heading at its start.
    #[default]
    Euler,
    /// Classical fourth-order Runge–Kutta: fourth order.
    Rk4,
}

/// Largest number of sub-steps [`integrate`] takes per call.
pub const MAX_SUBSTEPS: usize = 10_000;

/// The right-hand side `(ẋ, ẏ, θ̇) = (v cos θ, v sin θ, ω)`.
#[must_use]
pub fn derivative(theta_rad: f64, v_mps: f64, omega_radps: f64) -> (f64, f64, f64) {
    let (s, c) = crate::math::sin_cos(theta_rad);
    (v_mps * c, v_mps * s, omega_radps)
}

/// One integration step of length `dt_s` with constant `v, ω`; the heading is
/// wrapped to `[-π, π]`. Non-finite input or `dt_s < 0` returns `pose`
/// unchanged.
#[must_use]
pub fn step(pose: Pose, v_mps: f64, omega_radps: f64, dt_s: f64, integrator: Integrator) -> Pose {
    if !(pose.is_finite() && v_mps.is_finite() && omega_radps.is_finite() && dt_s.is_finite())
        || dt_s < 0.0
    {
        return pose;
    }
    let next = match integrator {
        Integrator::Euler => {
            let (dx, dy, dth) = derivative(pose.theta_rad, v_mps, omega_radps);
            Pose::new(
                pose.x_m + dt_s * dx,
                pose.y_m + dt_s * dy,
                pose.theta_rad + dt_s * dth,
            )
        }
        Integrator::Rk4 => {
            let f = |th: f64| derivative(th, v_mps, omega_radps);
            let th = pose.theta_rad;
            let k1 = f(th);
            let k2 = f(th + 0.5 * dt_s * k1.2);
            let k3 = f(th + 0.5 * dt_s * k2.2);
            let k4 = f(th + dt_s * k3.2);
            let w = dt_s / 6.0;
            Pose::new(
                pose.x_m + w * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
                pose.y_m + w * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
                th + w * (k1.2 + 2.0 * k2.2 + 2.0 * k3.2 + k4.2),
            )
        }
    };
    if next.is_finite() {
        Pose {
            theta_rad: wrap_pi(next.theta_rad),
            ..next
        }
    } else {
        pose
    }
}

/// Integrates constant `v, ω` over `dt_s` in `substeps` equal sub-steps
/// (clamped to `1..=`[`MAX_SUBSTEPS`]). Non-finite input or `dt_s < 0`
/// returns `pose` unchanged.
///
/// # Example
/// ```
/// use labcore::mobile::unicycle::{integrate, Integrator, Pose};
/// // Straight ahead at 1 m/s for 2 s.
/// let p = integrate(Pose::new(0.0, 0.0, 0.0), 1.0, 0.0, 2.0, 10, Integrator::Euler);
/// assert!((p.x_m - 2.0).abs() < 1e-12 && p.y_m == 0.0);
/// ```
#[must_use]
pub fn integrate(
    pose: Pose,
    v_mps: f64,
    omega_radps: f64,
    dt_s: f64,
    substeps: usize,
    integrator: Integrator,
) -> Pose {
    let n = substeps.clamp(1, MAX_SUBSTEPS);
    let h = dt_s / n as f64;
    let mut p = pose;
    for _ in 0..n {
        p = step(p, v_mps, omega_radps, h, integrator);
    }
    p
}

/// The exact pose after `t_s` seconds of constant `v, ω` (a circular arc of
/// radius `v/ω`, or a straight line when `ω = 0`):
///
/// ```text
/// x(t) = x + (v/ω)(sin(θ + ωt) − sin θ)     y(t) = y − (v/ω)(cos(θ + ωt) − cos θ)
/// ```
///
/// (Thrun, Burgard & Fox, *Probabilistic Robotics*, 2005, §5.3.3, eq. 5.9).
/// Written with `sin(ωt/2)` so it stays accurate as `ω → 0`.
#[must_use]
pub fn exact_arc(pose: Pose, v_mps: f64, omega_radps: f64, t_s: f64) -> Pose {
    let half = 0.5 * omega_radps * t_s;
    // Chord length 2 (v/ω) sin(ωt/2) = v t · sinc(ωt/2), along the mean heading.
    let chord = if half.abs() < 1e-8 {
        v_mps * t_s * (1.0 - half * half / 6.0)
    } else {
        v_mps * t_s * crate::math::sin(half) / half
    };
    let (s, c) = crate::math::sin_cos(pose.theta_rad + half);
    Pose::new(
        pose.x_m + chord * c,
        pose.y_m + chord * s,
        wrap_pi(pose.theta_rad + omega_radps * t_s),
    )
}

/// Wheel rim speeds `(v_L, v_R)` in m/s for body speeds `v, ω` and a track
/// (wheel separation) `track_m`: `v_L = v − ω b/2`, `v_R = v + ω b/2`.
///
/// # Example
/// ```
/// use labcore::mobile::unicycle::wheel_speeds;
/// // Turning on the spot at 1 rad/s with wheels 0.5 m apart.
/// assert_eq!(wheel_speeds(0.0, 1.0, 0.5), (-0.25, 0.25));
/// ```
#[must_use]
pub fn wheel_speeds(v_mps: f64, omega_radps: f64, track_m: f64) -> (f64, f64) {
    let half = 0.5 * omega_radps * track_m;
    (v_mps - half, v_mps + half)
}

/// Body speeds `(v, ω)` from wheel rim speeds: `v = (v_R + v_L)/2`,
/// `ω = (v_R − v_L)/b`. `None` when the track is not positive or any input is
/// not finite.
///
/// # Example
/// ```
/// use labcore::mobile::unicycle::body_velocity;
/// assert_eq!(body_velocity(-0.25, 0.25, 0.5), Some((0.0, 1.0)));
/// assert_eq!(body_velocity(1.0, 1.0, 0.0), None);
/// ```
#[must_use]
pub fn body_velocity(v_left_mps: f64, v_right_mps: f64, track_m: f64) -> Option<(f64, f64)> {
    if !(v_left_mps.is_finite() && v_right_mps.is_finite() && track_m.is_finite()) || track_m <= 0.0
    {
        return None;
    }
    Some((
        0.5 * (v_right_mps + v_left_mps),
        (v_right_mps - v_left_mps) / track_m,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Lcg64;
    use std::f64::consts::PI;

    fn pos_err(a: Pose, b: Pose) -> f64 {
        (a.position() - b.position()).length()
    }

    #[test]
    fn straight_line_and_turn_on_the_spot() {
        let p = integrate(
            Pose::new(1.0, 2.0, PI / 2.0),
            0.5,
            0.0,
            4.0,
            7,
            Integrator::Rk4,
        );
        assert!((p.x_m - 1.0).abs() < 1e-12 && (p.y_m - 4.0).abs() < 1e-12);
        let p = integrate(Pose::default(), 0.0, 1.0, 1.0, 3, Integrator::Euler);
        assert_eq!(p.position(), DVec2::ZERO);
        assert!((p.theta_rad - 1.0).abs() < 1e-15);
    }

    #[test]
    fn heading_stays_wrapped_across_pi() {
        let mut p = Pose::new(0.0, 0.0, 3.0);
        for _ in 0..1000 {
            p = step(p, 1.0, 2.0, 0.05, Integrator::Rk4);
            assert!((-PI..=PI).contains(&p.theta_rad));
        }
        // A quarter turn past +π lands near −π + something.
        let q = step(
            Pose::new(0.0, 0.0, PI - 0.1),
            0.0,
            1.0,
            0.2,
            Integrator::Euler,
        );
        assert!((q.theta_rad - (-PI + 0.1)).abs() < 1e-12);
    }

    #[test]
    fn bad_input_leaves_the_pose_unchanged() {
        let p = Pose::new(1.0, 2.0, 0.3);
        assert_eq!(step(p, f64::NAN, 0.0, 0.1, Integrator::Euler), p);
        assert_eq!(step(p, 1.0, f64::INFINITY, 0.1, Integrator::Rk4), p);
        assert_eq!(step(p, 1.0, 0.0, -0.1, Integrator::Euler), p);
        assert_eq!(step(p, 1.0, 0.0, f64::NAN, Integrator::Euler), p);
        assert_eq!(integrate(p, 1e308, 0.0, 1e308, 1, Integrator::Euler), p);
        assert_eq!(integrate(p, 1.0, 0.0, 0.0, 0, Integrator::Euler), p);
    }

    /// Nonholonomic constraint: the chord of an Euler step has no component
    /// across the heading at the step's start (to rounding); an RK4 step's
    /// chord has a tiny one across the mean heading `θ + ωdt/2` (the exact
    /// arc's chord direction).
    #[test]
    fn no_step_moves_sideways() {
        let mut rng = Lcg64::new(11);
        for _ in 0..5000 {
            let p = Pose::new(
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
                rng.range(-PI, PI),
            );
            let (v, w, dt) = (
                rng.range(-2.0, 2.0),
                rng.range(-3.0, 3.0),
                rng.range(0.0, 0.1),
            );
            let e = step(p, v, w, dt, Integrator::Euler);
            let d = e.position() - p.position();
            let side = d.perp_dot(p.heading());
            assert!(
                side.abs() <= 1e-14 * (1.0 + p.position().length()),
                "Euler {side}"
            );
            let r = step(p, v, w, dt, Integrator::Rk4);
            let d = r.position() - p.position();
            let mean = Pose::new(0.0, 0.0, p.theta_rad + 0.5 * w * dt).heading();
            assert!(d.perp_dot(mean).abs() < 1e-7, "RK4 {}", d.perp_dot(mean));
        }
    }

    /// Halving `dt` divides the end-point error by ≈ 2 for Euler (first
    /// order) and ≈ 16 for RK4 (fourth order), against the exact arc.
    #[test]
    fn rk4_and_euler_convergence_orders() {
        let start = Pose::new(0.3, -0.2, 0.4);
        let (v, w, t) = (1.0, 1.3, 2.0);
        let exact = exact_arc(start, v, w, t);
        for (integrator, expected, n0) in [(Integrator::Euler, 2.0, 64), (Integrator::Rk4, 16.0, 8)]
        {
            let errs: Vec<f64> = (0..4)
                .map(|k| pos_err(integrate(start, v, w, t, n0 << k, integrator), exact))
                .collect();
            for pair in errs.windows(2) {
                let ratio = pair[0] / pair[1];
                assert!(
                    (ratio / expected - 1.0).abs() < 0.1,
                    "{integrator:?} ratio {ratio} errors {errs:?}"
                );
            }
        }
    }

    #[test]
    fn exact_arc_is_a_circle_of_radius_v_over_omega() {
        let start = Pose::new(0.0, 0.0, 0.0);
        // Quarter circle of radius 2: ends at (2, 2) heading π/2.
        let p = exact_arc(start, 2.0, 1.0, PI / 2.0);
        assert!((p.x_m - 2.0).abs() < 1e-12 && (p.y_m - 2.0).abs() < 1e-12);
        assert!((p.theta_rad - PI / 2.0).abs() < 1e-12);
        // Tiny ω agrees with the straight line.
        let p = exact_arc(start, 1.0, 1e-12, 3.0);
        assert!((p.x_m - 3.0).abs() < 1e-12 && p.y_m.abs() < 1e-10);
    }

    #[test]
    fn wheel_speeds_round_trip() {
        let mut rng = Lcg64::new(4);
        for _ in 0..1000 {
            let (v, w, b) = (
                rng.range(-2.0, 2.0),
                rng.range(-4.0, 4.0),
                rng.range(0.1, 1.0),
            );
            let (l, r) = wheel_speeds(v, w, b);
            let (v2, w2) = body_velocity(l, r, b).unwrap();
            assert!((v - v2).abs() < 1e-12 && (w - w2).abs() < 1e-12);
        }
        assert_eq!(body_velocity(1.0, f64::NAN, 0.5), None);
        assert_eq!(body_velocity(1.0, 1.0, -0.5), None);
    }
}
