//! Forward kinematics of a planar serial chain of revolute joints.
//!
//! Joint angles are relative (each measured from the previous link), so link
//! `k` points along the cumulative angle `Θₖ = θ₁ + … + θₖ` and
//!
//! ```text
//! x = Σₖ Lₖ cos Θₖ,   y = Σₖ Lₖ sin Θₖ
//! ```
//!
//! For two links: `x = L1 cos θ1 + L2 cos(θ1+θ2)`, `y = L1 sin θ1 + L2 sin(θ1+θ2)`
//! (Spong, Hutchinson & Vidyasagar, *Robot Modeling and Control*, Ch. 3;
//! Craig, *Introduction to Robotics*, Ch. 3).

use glam::DVec2;

/// Every joint position of a chain, base first, tip last (`n + 1` points), and
/// the end-effector orientation.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainPose {
    /// Base (origin), each joint, then the tip, in metres.
    pub points: Vec<DVec2>,
    /// Orientation of the last link, `Θₙ = Σ θₖ`, in radians, wrapped to
    /// `[-π, π]` like every angle labcore returns.
    pub tip_angle_rad: f64,
}

impl ChainPose {
    /// The end-effector position.
    #[must_use]
    pub fn tip(&self) -> DVec2 {
        *self.points.last().unwrap_or(&DVec2::ZERO)
    }
}

/// Forward kinematics of a chain with its base at the origin.
///
/// `lengths_m` and `angles_rad` pair up; extra entries of the longer slice are
/// ignored.
///
/// # Example
/// ```
/// use labcore::kinematics::chain::forward;
/// let pose = forward(&[1.0, 1.0], &[0.0, std::f64::consts::FRAC_PI_2]);
/// assert!((pose.tip() - glam::DVec2::new(1.0, 1.0)).length() < 1e-12);
/// ```
#[must_use]
pub fn forward(lengths_m: &[f64], angles_rad: &[f64]) -> ChainPose {
    let mut points = Vec::with_capacity(lengths_m.len() + 1);
    let tip_angle_rad = forward_into(lengths_m, angles_rad, &mut points);
    ChainPose {
        points,
        tip_angle_rad,
    }
}

/// Allocation-free form of [`forward`]: clears `points`, fills base..tip and
/// returns the tip orientation in radians, wrapped to `[-π, π]`.
pub fn forward_into(lengths_m: &[f64], angles_rad: &[f64], points: &mut Vec<DVec2>) -> f64 {
    points.clear();
    let mut p = DVec2::ZERO;
    let mut heading = 0.0;
    points.push(p);
    for (length, angle) in lengths_m.iter().zip(angles_rad) {
        heading += angle;
        let (s, c) = crate::math::sin_cos(heading);
        p += DVec2::new(c, s) * *length;
        points.push(p);
    }
    super::two_link_ik::wrap_pi(heading)
}

/// Only the tip position (no allocation).
#[must_use]
pub fn tip(lengths_m: &[f64], angles_rad: &[f64]) -> DVec2 {
    let mut p = DVec2::ZERO;
    let mut heading = 0.0;
    for (length, angle) in lengths_m.iter().zip(angles_rad) {
        heading += angle;
        let (s, c) = crate::math::sin_cos(heading);
        p += DVec2::new(c, s) * *length;
    }
    p
}

/// The reachable annulus of a planar chain with unlimited joints.
///
/// Outer radius `R = Σ Lₖ`; inner radius `r = max(0, L_max − (R − L_max))`
/// (the hole left when one link is longer than all the others together). For
/// two links `r = |L1 − L2|`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Annulus {
    pub inner_m: f64,
    pub outer_m: f64,
}

impl Annulus {
    /// The annulus of a chain with these link lengths (metres, non-negative).
    #[must_use]
    pub fn of_chain(lengths_m: &[f64]) -> Self {
        let outer_m: f64 = lengths_m.iter().sum();
        let longest = lengths_m.iter().copied().fold(0.0, f64::max);
        Self {
            inner_m: (2.0 * longest - outer_m).max(0.0),
            outer_m,
        }
    }

    /// The dashed circles a scene draws for it, in words (Describe): how
    /// many, and their radii; `centre` where it is not the base
    /// ("2 dashed circles bound the reach: outer radius 1.700 m, inner
    /// radius 0.300 m").
    #[must_use]
    pub fn words(&self, centre: Option<DVec2>) -> String {
        let at = centre.map_or(String::new(), |c| {
            format!(", centred on {}", crate::units::format_point(c))
        });
        let outer = crate::units::format_metres(self.outer_m);
        if self.inner_m > 1e-9 {
            format!(
                "2 dashed circles bound the reach{at}: outer radius {outer}, inner radius {}",
                crate::units::format_metres(self.inner_m)
            )
        } else {
            format!("1 dashed circle bounds the reach{at}: outer radius {outer}, no hole")
        }
    }

    /// True when `p` lies in the closed annulus (with `eps_m` slack).
    #[must_use]
    pub fn contains(&self, p: DVec2, eps_m: f64) -> bool {
        let d = crate::math::hypot(p.x, p.y);
        d >= self.inner_m - eps_m && d <= self.outer_m + eps_m
    }

    /// The reachable point nearest to `p`: `p` itself inside the annulus,
    /// otherwise its radial projection onto the nearer boundary. At the origin
    /// with a hole, the point on the inner circle along +x. `|p|` is computed
    /// with `hypot`, so far points (|p| up to `f64::MAX`) keep their direction.
    #[must_use]
    pub fn nearest(&self, p: DVec2) -> DVec2 {
        let d = crate::math::hypot(p.x, p.y);
        if d < 1e-12 || !p.is_finite() {
            return DVec2::new(self.inner_m, 0.0);
        }
        if d >= self.inner_m && d <= self.outer_m {
            return p;
        }
        // The direction from p scaled by its largest component: a unit vector
        // even when |p| overflows (|p| may reach √2 · f64::MAX).
        let scaled = p / p.x.abs().max(p.y.abs());
        scaled.normalize() * d.clamp(self.inner_m, self.outer_m)
    }

    /// Fraction of the full reach used by a tip at `p`: `|p| / R` (0 when `R = 0`).
    #[must_use]
    pub fn reach_used(&self, p: DVec2) -> f64 {
        if self.outer_m > 0.0 {
            crate::math::hypot(p.x, p.y) / self.outer_m
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Lcg64;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_6, PI};

    fn close(a: DVec2, b: DVec2) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn hand_computed_two_link_poses() {
        // θ1 = 0, θ2 = 0: arm straight along +x.
        let p = forward(&[1.2, 0.8], &[0.0, 0.0]);
        assert_eq!(p.points.len(), 3);
        assert!(close(p.points[1], DVec2::new(1.2, 0.0)));
        assert!(close(p.tip(), DVec2::new(2.0, 0.0)));
        // θ1 = 90°, θ2 = -90°: up, then right.
        let p = forward(&[1.0, 0.5], &[FRAC_PI_2, -FRAC_PI_2]);
        assert!(close(p.tip(), DVec2::new(0.5, 1.0)));
        assert!(p.tip_angle_rad.abs() < 1e-15);
        // θ1 = 30°, θ2 = 60°: x = cos30 + cos90 = √3/2, y = sin30 + sin90 = 1.5.
        let p = forward(&[1.0, 1.0], &[FRAC_PI_6, PI / 3.0]);
        assert!(close(p.tip(), DVec2::new(3f64.sqrt() / 2.0, 1.5)));
        // Folded back: tip at L1 − L2 along θ1.
        let p = forward(&[1.0, 0.4], &[0.0, PI]);
        assert!(close(p.tip(), DVec2::new(0.6, 0.0)));
    }

    #[test]
    fn three_link_hand_value() {
        // 0°, 90°, 90°: (1,0) → (1,1) → (0,1).
        let p = forward(&[1.0, 1.0, 1.0], &[0.0, FRAC_PI_2, FRAC_PI_2]);
        assert!(close(p.tip(), DVec2::new(0.0, 1.0)));
        assert!((p.tip_angle_rad - PI).abs() < 1e-15);
        assert!(close(
            tip(&[1.0, 1.0, 1.0], &[0.0, FRAC_PI_2, FRAC_PI_2]),
            p.tip()
        ));
    }

    /// Every returned angle is wrapped to [-π, π] (the tip angle was not).
    #[test]
    fn tip_angle_is_wrapped() {
        let p = forward(&[1.0, 1.0, 1.0], &[3.0, 3.0, 3.0]);
        assert!((-PI..=PI).contains(&p.tip_angle_rad), "{}", p.tip_angle_rad);
        assert!((p.tip_angle_rad - (9.0 - 2.0 * PI)).abs() < 1e-12);
        let p = forward(&[1.0], &[-7.0]);
        assert!((p.tip_angle_rad - (-7.0 + 2.0 * PI)).abs() < 1e-12);
    }

    #[test]
    fn annulus_radii() {
        let a = Annulus::of_chain(&[1.2, 0.8]);
        assert!((a.inner_m - 0.4).abs() < 1e-12 && (a.outer_m - 2.0).abs() < 1e-12);
        let a = Annulus::of_chain(&[1.0, 1.0, 1.0]);
        assert_eq!(a.inner_m, 0.0);
        let a = Annulus::of_chain(&[3.0, 1.0, 0.5]);
        assert!((a.inner_m - 1.5).abs() < 1e-12 && (a.outer_m - 4.5).abs() < 1e-12);
    }

    #[test]
    fn nearest_projects_onto_the_annulus() {
        let a = Annulus::of_chain(&[1.2, 0.8]);
        assert!(close(a.nearest(DVec2::new(5.0, 0.0)), DVec2::new(2.0, 0.0)));
        assert!(close(a.nearest(DVec2::new(0.0, 0.1)), DVec2::new(0.0, 0.4)));
        assert!(close(a.nearest(DVec2::new(1.0, 0.0)), DVec2::new(1.0, 0.0)));
        assert!(close(a.nearest(DVec2::ZERO), DVec2::new(0.4, 0.0)));
    }

    /// Regression: `length()` overflows for |p| ≥ 1.34e154, which used to
    /// fold the arm onto its base (nearest = (0, 0)).
    #[test]
    fn nearest_keeps_the_direction_of_very_far_points() {
        let a = Annulus::of_chain(&[1.2, 0.8]);
        assert!(close(
            a.nearest(DVec2::new(1e200, 0.0)),
            DVec2::new(2.0, 0.0)
        ));
        assert!(close(
            a.nearest(DVec2::new(0.0, -1e200)),
            DVec2::new(0.0, -2.0)
        ));
        let diag = a.nearest(DVec2::new(1e200, 1e200));
        assert!(close(diag, DVec2::splat(2.0 / 2f64.sqrt())), "{diag}");
        let huge = a.nearest(DVec2::new(f64::MAX, f64::MAX));
        assert!((huge.length() - 2.0).abs() < 1e-12, "{huge}");
        assert!(a.contains(DVec2::new(1.5, 0.0), 0.0));
        assert!(!a.contains(DVec2::new(1e200, 1e200), 0.0));
        assert!((a.reach_used(DVec2::new(1e200, 0.0)) - 5e199).abs() < 1e188);
    }

    /// Property: for any angles, |L1 − L2| ≤ |tip| ≤ L1 + L2, and every link
    /// keeps its length.
    #[test]
    fn reach_stays_in_annulus_for_random_configurations() {
        let mut rng = Lcg64::new(2024);
        for _ in 0..10_000 {
            let l1 = rng.range(0.1, 2.0);
            let l2 = rng.range(0.1, 2.0);
            let t1 = rng.range(-PI, PI);
            let t2 = rng.range(-PI, PI);
            let pose = forward(&[l1, l2], &[t1, t2]);
            let d = pose.tip().length();
            assert!(d <= l1 + l2 + 1e-12);
            assert!(d >= (l1 - l2).abs() - 1e-12);
            assert!(((pose.points[1] - pose.points[0]).length() - l1).abs() < 1e-12);
            assert!(((pose.points[2] - pose.points[1]).length() - l2).abs() < 1e-12);
            assert!(Annulus::of_chain(&[l1, l2]).contains(pose.tip(), 1e-9));
            let used = Annulus::of_chain(&[l1, l2]).reach_used(pose.tip());
            assert!((0.0..=1.0 + 1e-12).contains(&used));
        }
    }
}
