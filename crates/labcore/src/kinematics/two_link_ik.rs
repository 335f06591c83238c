//! Closed-form inverse kinematics of a planar 2-link arm (law of cosines).
//!
//! For a target `(x, y)` and links `L1`, `L2`:
//!
//! ```text
//! cos θ2 = (x² + y² − L1² − L2²) / (2 L1 L2)
//! θ2     = ± atan2(√(1 − cos²θ2), cos θ2)
//! θ1     = atan2(y, x) − atan2(L2 sin θ2, L1 + L2 cos θ2)
//! ```
//!
//! (Spong, Hutchinson & Vidyasagar, *Robot Modeling and Control*, 2006, Ch. 3 (inverse kinematics);
//! Craig, *Introduction to Robotics*, Ch. 4.) The target is unreachable when
//! `|cos θ2| > 1`; this module reports that as a value and never lets a NaN out.
//!
//! **Branches.** *Elbow up* takes `θ2 ≤ 0`: the elbow sits on the
//! counter-clockwise (left) side of the base→target line, which is "up" for a
//! target to the right of the base. *Elbow down* takes `θ2 ≥ 0`. The two are
//! mirror images about the base→target line and coincide on the boundary.
//!
//! **Optional wrist.** A third link `L3` held at a fixed absolute orientation
//! `φ` (a wrist offset) is solved by placing the wrist at
//! `w = p − L3 (cos φ, sin φ)`, solving the 2-link problem for `w`, and
//! setting `θ3 = φ − θ1 − θ2`.

use glam::DVec2;
use std::f64::consts::PI;

/// Which of the two closed-form solutions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Elbow {
    /// `θ2 ≤ 0`.
    Up,
    /// `θ2 ≥ 0`.
    Down,
}

impl Elbow {
    /// The other branch.
    #[must_use]
    pub fn other(self) -> Self {
        match self {
            Elbow::Up => Elbow::Down,
            Elbow::Down => Elbow::Up,
        }
    }
}

/// Joint angles of a 2-link arm, radians, `θ1` in `[-π, π]`, `θ2` in `[-π, π]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoLinkAngles {
    pub theta1_rad: f64,
    pub theta2_rad: f64,
}

/// Where a reachable target sits with respect to the singular configurations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Singularity {
    /// Strictly inside the annulus: two distinct solutions.
    Regular,
    /// On the outer circle `|p| = L1 + L2`: the arm is straight, the branches merge.
    OuterBoundary,
    /// On the inner circle `|p| = |L1 − L2|`: the arm is folded, the branches merge.
    InnerBoundary,
    /// `L1 = L2` and the target is the base itself: `θ2 = π` and every `θ1` works.
    AtBase,
}

/// Both solutions for a reachable target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoLinkSolution {
    pub elbow_up: TwoLinkAngles,
    pub elbow_down: TwoLinkAngles,
    /// `cos θ2` before clamping (in `[-1, 1]` up to the tolerance).
    pub cos_theta2: f64,
    pub singularity: Singularity,
}

impl TwoLinkSolution {
    /// The solution of one branch.
    #[must_use]
    pub fn branch(&self, elbow: Elbow) -> TwoLinkAngles {
        match elbow {
            Elbow::Up => self.elbow_up,
            Elbow::Down => self.elbow_down,
        }
    }
}

/// Why no solution exists.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum IkError {
    /// The target lies outside the annulus `[inner_m, outer_m]`.
    Unreachable {
        distance_m: f64,
        inner_m: f64,
        outer_m: f64,
    },
    /// A length or coordinate was NaN or infinite, or a link length not positive.
    InvalidInput,
}

/// Relative tolerance on `|cos θ2| − 1` inside which a target counts as on a
/// boundary (and is snapped onto it rather than rejected).
pub const BOUNDARY_TOLERANCE: f64 = 1e-9;

/// Solves both branches for a target `p` (metres).
///
/// # Example
/// ```
/// use labcore::kinematics::two_link_ik::{solve, Elbow};
/// use labcore::kinematics::chain::tip;
/// let sol = solve(1.0, 1.0, glam::DVec2::new(1.0, 1.0)).unwrap();
/// let a = sol.branch(Elbow::Down);
/// assert!((tip(&[1.0, 1.0], &[a.theta1_rad, a.theta2_rad]) - glam::DVec2::new(1.0, 1.0)).length() < 1e-12);
/// ```
pub fn solve(l1_m: f64, l2_m: f64, p: DVec2) -> Result<TwoLinkSolution, IkError> {
    if !(l1_m.is_finite() && l2_m.is_finite() && p.is_finite()) || l1_m <= 0.0 || l2_m <= 0.0 {
        return Err(IkError::InvalidInput);
    }
    let d2 = p.length_squared();
    let cos_theta2 = (d2 - l1_m * l1_m - l2_m * l2_m) / (2.0 * l1_m * l2_m);
    if cos_theta2.abs() > 1.0 + BOUNDARY_TOLERANCE {
        return Err(IkError::Unreachable {
            distance_m: d2.sqrt(),
            inner_m: (l1_m - l2_m).abs(),
            outer_m: l1_m + l2_m,
        });
    }
    let c = cos_theta2.clamp(-1.0, 1.0);
    let s = (1.0 - c * c).max(0.0).sqrt();
    let singularity = if d2.sqrt() <= BOUNDARY_TOLERANCE * (l1_m + l2_m) && c <= -1.0 + 1e-12 {
        Singularity::AtBase
    } else if 1.0 - c <= BOUNDARY_TOLERANCE {
        Singularity::OuterBoundary
    } else if 1.0 + c <= BOUNDARY_TOLERANCE {
        Singularity::InnerBoundary
    } else {
        Singularity::Regular
    };
    let base_angle = if singularity == Singularity::AtBase {
        0.0
    } else {
        crate::math::atan2(p.y, p.x)
    };
    let branch = |sign: f64| {
        let theta2 = sign * crate::math::atan2(s, c);
        let theta1 = base_angle
            - crate::math::atan2(
                l2_m * crate::math::sin(theta2),
                l1_m + l2_m * crate::math::cos(theta2),
            );
        TwoLinkAngles {
            theta1_rad: wrap_pi(theta1),
            theta2_rad: theta2,
        }
    };
    Ok(TwoLinkSolution {
        elbow_up: branch(-1.0),
        elbow_down: branch(1.0),
        cos_theta2,
        singularity,
    })
}

/// Joint angles of a 3-link arm whose last link holds a fixed absolute
/// orientation, radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WristAngles {
    pub theta1_rad: f64,
    pub theta2_rad: f64,
    pub theta3_rad: f64,
}

/// Solves a 2-link arm plus a wrist link `l3_m` held at absolute orientation
/// `phi_rad`: the wrist centre `p − L3 (cos φ, sin φ)` is solved in closed
/// form, then `θ3 = φ − θ1 − θ2` (wrapped to `[-π, π]`).
pub fn solve_with_wrist(
    l1_m: f64,
    l2_m: f64,
    l3_m: f64,
    phi_rad: f64,
    p: DVec2,
    elbow: Elbow,
) -> Result<WristAngles, IkError> {
    if !(l3_m.is_finite() && phi_rad.is_finite()) || l3_m < 0.0 {
        return Err(IkError::InvalidInput);
    }
    let wrist = p - DVec2::new(crate::math::cos(phi_rad), crate::math::sin(phi_rad)) * l3_m;
    let a = solve(l1_m, l2_m, wrist)?.branch(elbow);
    Ok(WristAngles {
        theta1_rad: a.theta1_rad,
        theta2_rad: a.theta2_rad,
        theta3_rad: wrap_pi(phi_rad - a.theta1_rad - a.theta2_rad),
    })
}

/// Wraps an angle to `[-π, π]`: the one convention for every angle labcore
/// returns (`-π` stays `-π`, an angle above `π` maps into `(-π, π]`).
#[must_use]
pub fn wrap_pi(angle_rad: f64) -> f64 {
    if (-PI..=PI).contains(&angle_rad) {
        return angle_rad;
    }
    let wrapped = (angle_rad + PI).rem_euclid(2.0 * PI) - PI;
    if wrapped == -PI && angle_rad > 0.0 {
        PI
    } else {
        wrapped
    }
}

/// Moves angle `from` towards `to` along the shorter way round, by fraction `t` in `[0, 1]`.
#[must_use]
pub fn lerp_angle(from_rad: f64, to_rad: f64, t: f64) -> f64 {
    from_rad + wrap_pi(to_rad - from_rad) * t.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::chain::tip;
    use crate::rng::Lcg64;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn hand_computed_right_angle() {
        // L1 = L2 = 1, target (1, 1): cos θ2 = 0 → θ2 = ±90°.
        let sol = solve(1.0, 1.0, DVec2::new(1.0, 1.0)).unwrap();
        assert_eq!(sol.singularity, Singularity::Regular);
        // Elbow down (θ2 = +90°): θ1 = 45° − atan2(1, 1) = 0.
        assert!((sol.elbow_down.theta2_rad - FRAC_PI_2).abs() < 1e-12);
        assert!(sol.elbow_down.theta1_rad.abs() < 1e-12);
        // Elbow up (θ2 = −90°): θ1 = 45° + 45° = 90°.
        assert!((sol.elbow_up.theta2_rad + FRAC_PI_2).abs() < 1e-12);
        assert!((sol.elbow_up.theta1_rad - FRAC_PI_2).abs() < 1e-12);
    }

    #[test]
    fn unreachable_targets_are_rejected_without_nan() {
        for p in [
            DVec2::new(3.0, 0.0),
            DVec2::new(0.0, 0.1),
            DVec2::new(1e300, 1e300),
        ] {
            match solve(1.2, 0.8, p) {
                Err(IkError::Unreachable {
                    distance_m,
                    inner_m,
                    outer_m,
                }) => {
                    assert!((inner_m - 0.4).abs() < 1e-12 && (outer_m - 2.0).abs() < 1e-12);
                    assert!(!distance_m.is_nan());
                }
                other => panic!("expected unreachable, got {other:?}"),
            }
        }
        assert_eq!(
            solve(1.0, 1.0, DVec2::new(f64::NAN, 0.0)),
            Err(IkError::InvalidInput)
        );
        assert_eq!(
            solve(0.0, 1.0, DVec2::new(1.0, 0.0)),
            Err(IkError::InvalidInput)
        );
    }

    #[test]
    fn boundary_and_singular_cases() {
        // Outer boundary: straight arm, branches merge.
        let sol = solve(1.2, 0.8, DVec2::new(0.0, 2.0)).unwrap();
        assert_eq!(sol.singularity, Singularity::OuterBoundary);
        assert_eq!(sol.elbow_up, sol.elbow_down);
        assert!(sol.elbow_up.theta2_rad.abs() < 1e-6);
        assert!((sol.elbow_up.theta1_rad - FRAC_PI_2).abs() < 1e-6);
        // Inner boundary: folded arm.
        let sol = solve(1.2, 0.8, DVec2::new(-0.4, 0.0)).unwrap();
        assert_eq!(sol.singularity, Singularity::InnerBoundary);
        assert!((sol.elbow_down.theta2_rad.abs() - PI).abs() < 1e-6);
        // Equal links, target at the base.
        let sol = solve(1.0, 1.0, DVec2::ZERO).unwrap();
        assert_eq!(sol.singularity, Singularity::AtBase);
        let a = sol.elbow_down;
        assert!(tip(&[1.0, 1.0], &[a.theta1_rad, a.theta2_rad]).length() < 1e-12);
        // A hair outside the boundary within tolerance snaps onto it.
        let sol = solve(1.0, 1.0, DVec2::new(2.0 + 1e-12, 0.0)).unwrap();
        assert_eq!(sol.singularity, Singularity::OuterBoundary);
    }

    /// Property: FK(IK(p)) = p within 1e-9 for both branches, and the branches
    /// have opposite elbow signs.
    #[test]
    fn fk_of_ik_returns_the_target_for_random_reachable_points() {
        let mut rng = Lcg64::new(99);
        for _ in 0..20_000 {
            let l1 = rng.range(0.1, 2.0);
            let l2 = rng.range(0.1, 2.0);
            // Draw a reachable point by FK of random angles, plus random points in a box.
            let p = if rng.next_f64() < 0.5 {
                tip(&[l1, l2], &[rng.range(-PI, PI), rng.range(-PI, PI)])
            } else {
                DVec2::new(rng.range(-4.0, 4.0), rng.range(-4.0, 4.0))
            };
            match solve(l1, l2, p) {
                Ok(sol) => {
                    for elbow in [Elbow::Up, Elbow::Down] {
                        let a = sol.branch(elbow);
                        let reached = tip(&[l1, l2], &[a.theta1_rad, a.theta2_rad]);
                        assert!(
                            (reached - p).length() < 1e-9,
                            "{elbow:?} l=({l1},{l2}) p={p} got {reached}"
                        );
                        assert!((-PI..=PI).contains(&a.theta1_rad));
                    }
                    assert!(sol.elbow_up.theta2_rad <= 0.0 && sol.elbow_down.theta2_rad >= 0.0);
                }
                Err(IkError::Unreachable { distance_m, .. }) => {
                    let inside = distance_m <= l1 + l2 && distance_m >= (l1 - l2).abs();
                    let margin = (distance_m - (l1 + l2))
                        .abs()
                        .min((distance_m - (l1 - l2).abs()).abs());
                    assert!(!inside || margin < 1e-6, "rejected reachable point {p}");
                }
                Err(e) => panic!("{e:?}"),
            }
        }
    }

    #[test]
    fn wrist_offset_reaches_target_with_fixed_orientation() {
        let mut rng = Lcg64::new(5);
        for _ in 0..2000 {
            let (l1, l2, l3) = (1.0, 0.8, 0.3);
            let q = [rng.range(-PI, PI), rng.range(-PI, PI), rng.range(-PI, PI)];
            let p = tip(&[l1, l2, l3], &q);
            let phi = q[0] + q[1] + q[2];
            for elbow in [Elbow::Up, Elbow::Down] {
                let a = solve_with_wrist(l1, l2, l3, phi, p, elbow).unwrap();
                let got = tip(&[l1, l2, l3], &[a.theta1_rad, a.theta2_rad, a.theta3_rad]);
                assert!((got - p).length() < 1e-9);
                let orient = wrap_pi(a.theta1_rad + a.theta2_rad + a.theta3_rad - phi);
                assert!(orient.abs() < 1e-9);
            }
        }
    }

    #[test]
    fn wrap_and_lerp() {
        assert!((wrap_pi(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_pi(-3.0 * PI / 2.0) - FRAC_PI_2).abs() < 1e-12);
        assert_eq!(wrap_pi(0.5), 0.5);
        // From 170° to −170° goes through 180°, not through 0.
        let mid = lerp_angle(170f64.to_radians(), (-170f64).to_radians(), 0.5);
        assert!((wrap_pi(mid).abs() - PI).abs() < 1e-12);
    }
}
