//! The planar geometric Jacobian (position rows only) and manipulability.
//!
//! For an n-link planar chain with relative joint angles `θ₁ … θₙ`, link `k`
//! points along the cumulative angle `Θₖ = θ₁ + … + θₖ`, and the tip velocity
//! is `ṗ = J(θ) θ̇` with the 2×n Jacobian
//!
//! ```text
//! J[0][j] = −Σ_{k≥j} Lₖ sin Θₖ,   J[1][j] = Σ_{k≥j} Lₖ cos Θₖ
//! ```
//!
//! Geometrically, column `j` is the vector from joint `j` to the tip turned by
//! +90°: `Jⱼ = perp(p_tip − p_j) = (−(y_tip − y_j), x_tip − x_j)` — a revolute
//! joint about z moves the tip perpendicular to the line joining them
//! (Siciliano, Sciavicco, Villani & Oriolo, *Robotics: Modelling, Planning and
//! Control*, Ch. 3, §3.1; Lynch & Park, *Modern Robotics*, Ch. 5).
//!
//! **Manipulability.** The velocity ellipse `{J θ̇ : |θ̇| ≤ 1}` has semi-axes
//! `σ_max u_max` and `σ_min u_min`, where `σ² ` are the eigenvalues of `J Jᵀ` and
//! `u` its unit eigenvectors (the left singular vectors of `J`). Yoshikawa's
//! measure is its area over π:
//!
//! ```text
//! w = √det(J Jᵀ) = σ_max · σ_min
//! ```
//!
//! (Yoshikawa, "Manipulability of robotic mechanisms", *IJRR* 4(2), 1985, pp. 3–9;
//! Siciliano et al., Ch. 3, §3.9). For two links `w = L1 L2 |sin θ2|`: the arm is
//! singular when straight or folded.
//!
//! Chains of [`MAX_JOINTS`] = 8 links or fewer are supported; anything else
//! (no links, too many, mismatched slices, non-finite values) gives an empty
//! Jacobian and a tip at the origin, never a NaN.

use glam::{DMat2, DVec2};

/// The most joints a chain may have here (the stack buffers of the solvers hold 8 columns).
pub const MAX_JOINTS: usize = 8;

/// Relative threshold under which `σ_min / σ_max` counts as exactly singular
/// (`σ_min` and `w` snap to 0, the condition number to infinity).
pub const SINGULAR_RATIO: f64 = 1e-12;

/// True when `lengths_m` and `angles_rad` describe a chain this module accepts:
/// 1 to [`MAX_JOINTS`] joints, equal lengths, every value finite.
#[must_use]
pub fn is_valid_chain(lengths_m: &[f64], angles_rad: &[f64]) -> bool {
    let n = lengths_m.len();
    (1..=MAX_JOINTS).contains(&n)
        && angles_rad.len() == n
        && lengths_m.iter().all(|l| l.is_finite())
        && angles_rad.iter().all(|a| a.is_finite())
}

/// Fills `cols[..n]` with the Jacobian columns and returns the tip. The caller
/// guarantees `lengths_m.len() == angles_rad.len() <= MAX_JOINTS`.
///
/// One pass forward for the link vectors `Lₖ (cos Θₖ, sin Θₖ)`, one pass
/// backward for the suffix sums `p_tip − p_j`; the tip is the suffix sum at 0.
#[inline]
pub(crate) fn columns_into_array(
    lengths_m: &[f64],
    angles_rad: &[f64],
    cols: &mut [DVec2; MAX_JOINTS],
) -> DVec2 {
    let n = lengths_m.len().min(angles_rad.len()).min(MAX_JOINTS);
    let mut heading = 0.0;
    for k in 0..n {
        heading += angles_rad[k];
        let (s, c) = crate::math::sin_cos(heading);
        cols[k] = DVec2::new(c * lengths_m[k], s * lengths_m[k]);
    }
    let mut suffix = DVec2::ZERO;
    for k in (0..n).rev() {
        suffix += cols[k];
        cols[k] = suffix.perp();
    }
    suffix
}

/// Allocation-free Jacobian: clears `columns`, fills the `n` columns of the
/// 2×n Jacobian (column `j` = `perp(p_tip − p_j)`, metres per radian) and
/// returns the tip position in metres.
///
/// Invalid input (no joints, more than [`MAX_JOINTS`], slices of different
/// lengths, a NaN or infinite value) leaves `columns` empty and returns
/// `DVec2::ZERO`.
///
/// # Example
/// ```
/// use labcore::kinematics::jacobian::jacobian_into;
/// use glam::DVec2;
/// let mut cols = Vec::new();
/// // Two unit links, θ = (0, 90°): tip at (1, 1).
/// let tip = jacobian_into(&[1.0, 1.0], &[0.0, std::f64::consts::FRAC_PI_2], &mut cols);
/// assert!((tip - DVec2::new(1.0, 1.0)).length() < 1e-12);
/// assert!((cols[0] - DVec2::new(-1.0, 1.0)).length() < 1e-12);
/// assert!((cols[1] - DVec2::new(-1.0, 0.0)).length() < 1e-12);
/// ```
pub fn jacobian_into(lengths_m: &[f64], angles_rad: &[f64], columns: &mut Vec<DVec2>) -> DVec2 {
    columns.clear();
    if !is_valid_chain(lengths_m, angles_rad) {
        return DVec2::ZERO;
    }
    let mut cols = [DVec2::ZERO; MAX_JOINTS];
    let tip = columns_into_array(lengths_m, angles_rad, &mut cols);
    columns.extend_from_slice(&cols[..lengths_m.len()]);
    tip
}

/// The Jacobian columns as a new vector (see [`jacobian_into`]); empty on invalid input.
///
/// # Example
/// ```
/// use labcore::kinematics::jacobian::jacobian;
/// // A straight 3-link arm along +x: every column points along +y.
/// let cols = jacobian(&[1.0, 1.0, 1.0], &[0.0, 0.0, 0.0]);
/// assert_eq!(cols.len(), 3);
/// assert_eq!((cols[0].y, cols[1].y, cols[2].y), (3.0, 2.0, 1.0));
/// assert!(jacobian(&[1.0], &[]).is_empty());
/// ```
#[must_use]
pub fn jacobian(lengths_m: &[f64], angles_rad: &[f64]) -> Vec<DVec2> {
    let mut columns = Vec::with_capacity(lengths_m.len().min(MAX_JOINTS));
    jacobian_into(lengths_m, angles_rad, &mut columns);
    columns
}

/// `J Jᵀ = Σⱼ Jⱼ Jⱼᵀ` as a symmetric 2×2 (m²/rad²). The zero matrix for no columns.
///
/// # Example
/// ```
/// use labcore::kinematics::jacobian::{jacobian, jjt};
/// let m = jjt(&jacobian(&[1.0, 1.0], &[0.0, std::f64::consts::FRAC_PI_2]));
/// // J = [[-1, -1], [1, 0]] → J Jᵀ = [[2, -1], [-1, 1]].
/// assert!((m.x_axis.x - 2.0).abs() < 1e-12 && (m.y_axis.x + 1.0).abs() < 1e-12);
/// assert!((m.x_axis.y + 1.0).abs() < 1e-12 && (m.y_axis.y - 1.0).abs() < 1e-12);
/// ```
#[must_use]
pub fn jjt(columns: &[DVec2]) -> DMat2 {
    let (a, b, c) = jjt_entries(columns);
    DMat2::from_cols(DVec2::new(a, b), DVec2::new(b, c))
}

/// The three distinct entries `(a, b, c)` of `J Jᵀ = [[a, b], [b, c]]`.
#[inline]
pub(crate) fn jjt_entries(columns: &[DVec2]) -> (f64, f64, f64) {
    let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
    for col in columns {
        a += col.x * col.x;
        b += col.x * col.y;
        c += col.y * col.y;
    }
    (a, b, c)
}

/// `det(J Jᵀ)` by the Cauchy–Binet formula `Σ_{i<j} (Jᵢ × Jⱼ)²`: a sum of
/// squares, so never negative and free of the cancellation in `ac − b²`
/// (relative accuracy near singular poses is that of the cross products).
#[must_use]
pub fn det_jjt(columns: &[DVec2]) -> f64 {
    let mut det = 0.0;
    for (i, ci) in columns.iter().enumerate() {
        for cj in &columns[i + 1..] {
            let cross = ci.perp_dot(*cj);
            det += cross * cross;
        }
    }
    det
}

/// Yoshikawa manipulability and the velocity ellipse of a planar arm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Manipulability {
    /// `w = √det(J Jᵀ) = σ_max σ_min`, m²/rad (≥ 0).
    pub w: f64,
    /// Largest singular value of `J`, m/rad: the longest semi-axis of the velocity ellipse.
    pub sigma_max: f64,
    /// Smallest singular value of `J`, m/rad (0 at a singularity).
    pub sigma_min: f64,
    /// `σ_max / σ_min`; `f64::INFINITY` when `σ_min ≈ 0` (see [`SINGULAR_RATIO`]).
    pub condition: f64,
    /// Unit direction of the long axis (left singular vector for `σ_max`).
    pub u_max: DVec2,
    /// Unit direction of the short axis, `u_max` turned by +90°.
    pub u_min: DVec2,
}

/// Singular values and axes of `J` from the closed-form eigen-decomposition
/// of the symmetric 2×2 `J Jᵀ = [[a, b], [b, c]]`:
///
/// ```text
/// σ_max² = (a + c)/2 + √(((a − c)/2)² + b²),   σ_min² = det(J Jᵀ) / σ_max²
/// u_max  = (cos φ, sin φ),  φ = ½ atan2(2b, a − c),   u_min = perp(u_max)
/// ```
///
/// `det` comes from [`det_jjt`] (Cauchy–Binet) so `σ_min` stays accurate near a
/// singularity. When `σ_min ≤ 1e-12 σ_max` the pose counts as singular:
/// `σ_min = w = 0`, `condition = ∞`. No columns (or all zero): everything 0,
/// `condition = ∞`, axes along x and y. Never NaN for finite columns.
///
/// # Example
/// ```
/// use labcore::kinematics::jacobian::{jacobian, manipulability};
/// let t2 = 1.0_f64; // rad
/// let m = manipulability(&jacobian(&[1.0, 0.5], &[0.3, t2]));
/// assert!((m.w - 1.0 * 0.5 * t2.sin().abs()).abs() < 1e-12);
/// let straight = manipulability(&jacobian(&[1.0, 1.0], &[0.0, 0.0]));
/// assert_eq!((straight.w, straight.sigma_min, straight.condition), (0.0, 0.0, f64::INFINITY));
/// ```
#[must_use]
pub fn manipulability(columns: &[DVec2]) -> Manipulability {
    let (a, b, c) = jjt_entries(columns);
    let half_diff = 0.5 * (a - c);
    let radius = crate::math::hypot(half_diff, b);
    let lambda_max = (0.5 * (a + c) + radius).max(0.0);
    let phi = 0.5 * crate::math::atan2(2.0 * b, a - c);
    let u_max = DVec2::new(crate::math::cos(phi), crate::math::sin(phi));
    let u_min = u_max.perp();
    let sigma_max = lambda_max.sqrt();
    if !sigma_max.is_finite() || sigma_max <= 0.0 {
        return Manipulability {
            w: 0.0,
            sigma_max: if sigma_max.is_finite() {
                sigma_max
            } else {
                0.0
            },
            sigma_min: 0.0,
            condition: f64::INFINITY,
            u_max: DVec2::X,
            u_min: DVec2::Y,
        };
    }
    let det = det_jjt(columns);
    let mut sigma_min = (det / lambda_max).max(0.0).sqrt().min(sigma_max);
    if sigma_min.is_nan() || sigma_min <= SINGULAR_RATIO * sigma_max {
        sigma_min = 0.0;
    }
    let condition = if sigma_min > 0.0 {
        sigma_max / sigma_min
    } else {
        f64::INFINITY
    };
    Manipulability {
        w: sigma_max * sigma_min,
        sigma_max,
        sigma_min,
        condition,
        u_max,
        u_min,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::chain::{forward, tip};
    use crate::rng::Lcg64;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn close(a: DVec2, b: DVec2, tol: f64) -> bool {
        (a - b).length() < tol
    }

    #[test]
    fn hand_computed_two_link_jacobian() {
        // L = (1, 1), θ = (0, 90°): J = [[-1, -1], [1, 0]], tip (1, 1).
        let mut cols = Vec::new();
        let p = jacobian_into(&[1.0, 1.0], &[0.0, FRAC_PI_2], &mut cols);
        assert!(close(p, DVec2::new(1.0, 1.0), 1e-12));
        assert_eq!(cols.len(), 2);
        assert!(close(cols[0], DVec2::new(-1.0, 1.0), 1e-12));
        assert!(close(cols[1], DVec2::new(-1.0, 0.0), 1e-12));
        // L = (2, 1), θ = (90°, 0): straight up, J = [[-3, -1], [0, 0]].
        let cols = jacobian(&[2.0, 1.0], &[FRAC_PI_2, 0.0]);
        assert!(close(cols[0], DVec2::new(-3.0, 0.0), 1e-12));
        assert!(close(cols[1], DVec2::new(-1.0, 0.0), 1e-12));
        // One link of 0.5 m at 180°: J = [[0], [-0.5]].
        let cols = jacobian(&[0.5], &[PI]);
        assert!(close(cols[0], DVec2::new(0.0, -0.5), 1e-12));
    }

    #[test]
    fn columns_are_perp_of_joint_to_tip() {
        let mut rng = Lcg64::new(11);
        for n in 1..=MAX_JOINTS {
            let lengths: Vec<f64> = (0..n).map(|_| rng.range(0.1, 2.0)).collect();
            let angles: Vec<f64> = (0..n).map(|_| rng.range(-PI, PI)).collect();
            let pose = forward(&lengths, &angles);
            let mut cols = Vec::new();
            let p = jacobian_into(&lengths, &angles, &mut cols);
            assert!(close(p, pose.tip(), 1e-12));
            for (j, col) in cols.iter().enumerate() {
                assert!(close(*col, (pose.tip() - pose.points[j]).perp(), 1e-12));
            }
        }
    }

    /// Property: J equals central finite differences of the tip, n = 2..8.
    #[test]
    fn jacobian_matches_central_finite_differences() {
        let mut rng = Lcg64::new(314);
        let h = 1e-6;
        for _ in 0..500 {
            let n = rng.int(2, MAX_JOINTS as i64) as usize;
            let lengths: Vec<f64> = (0..n).map(|_| rng.range(0.2, 1.5)).collect();
            let angles: Vec<f64> = (0..n).map(|_| rng.range(-PI, PI)).collect();
            let cols = jacobian(&lengths, &angles);
            assert_eq!(cols.len(), n);
            for j in 0..n {
                let mut plus = angles.clone();
                let mut minus = angles.clone();
                plus[j] += h;
                minus[j] -= h;
                let fd = (tip(&lengths, &plus) - tip(&lengths, &minus)) / (2.0 * h);
                assert!(close(cols[j], fd, 1e-6), "n={n} j={j} {} vs {fd}", cols[j]);
            }
        }
    }

    #[test]
    fn invalid_input_gives_empty_jacobian_and_no_nan() {
        let mut cols = vec![DVec2::ONE; 3];
        assert_eq!(jacobian_into(&[], &[], &mut cols), DVec2::ZERO);
        assert!(cols.is_empty());
        assert!(jacobian(&[1.0, 1.0], &[0.0]).is_empty());
        assert!(jacobian(&[1.0; 9], &[0.0; 9]).is_empty());
        assert!(jacobian(&[1.0, f64::NAN], &[0.0, 0.0]).is_empty());
        assert!(jacobian(&[1.0, 1.0], &[f64::INFINITY, 0.0]).is_empty());
        assert_eq!(jacobian(&[1.0; 8], &[0.1; 8]).len(), 8);
        let m = manipulability(&[]);
        assert_eq!((m.w, m.sigma_max, m.sigma_min), (0.0, 0.0, 0.0));
        assert_eq!(m.condition, f64::INFINITY);
        assert!(m.u_max.is_finite() && m.u_min.is_finite());
        assert_eq!(jjt(&[]), DMat2::ZERO);
    }

    /// Property: for two links, w = L1 L2 |sin θ2| and w² = det(J Jᵀ).
    #[test]
    fn two_link_manipulability_is_l1_l2_abs_sin_theta2() {
        let mut rng = Lcg64::new(7);
        for _ in 0..10_000 {
            let (l1, l2) = (rng.range(0.1, 2.0), rng.range(0.1, 2.0));
            let (t1, t2) = (rng.range(-PI, PI), rng.range(-PI, PI));
            let cols = jacobian(&[l1, l2], &[t1, t2]);
            let m = manipulability(&cols);
            let expected = l1 * l2 * t2.sin().abs();
            assert!(
                (m.w - expected).abs() < 1e-12,
                "w={} expected {expected}",
                m.w
            );
            let det = jjt(&cols).determinant();
            assert!((m.w * m.w - det).abs() < 1e-9);
        }
    }

    /// Property: σ² are the eigenvalues of J Jᵀ with eigenvectors u (J Jᵀ u = σ² u),
    /// u_max ⟂ u_min, both unit; σ_max ≥ σ_min ≥ 0; w = σ_max σ_min.
    #[test]
    fn ellipse_axes_are_the_singular_values_and_vectors() {
        let mut rng = Lcg64::new(2718);
        for _ in 0..5_000 {
            let n = rng.int(1, MAX_JOINTS as i64) as usize;
            let lengths: Vec<f64> = (0..n).map(|_| rng.range(0.1, 2.0)).collect();
            let angles: Vec<f64> = (0..n).map(|_| rng.range(-PI, PI)).collect();
            let cols = jacobian(&lengths, &angles);
            let m = manipulability(&cols);
            let a = jjt(&cols);
            let scale = a.x_axis.x + a.y_axis.y; // trace: sets the tolerance
            assert!((m.u_max.length() - 1.0).abs() < 1e-12);
            assert!((m.u_min.length() - 1.0).abs() < 1e-12);
            assert!(m.u_max.dot(m.u_min).abs() < 1e-12);
            assert!(m.sigma_max >= m.sigma_min && m.sigma_min >= 0.0);
            let res_max = a * m.u_max - m.u_max * (m.sigma_max * m.sigma_max);
            let res_min = a * m.u_min - m.u_min * (m.sigma_min * m.sigma_min);
            assert!(res_max.length() < 1e-10 * scale, "n={n} {res_max}");
            assert!(res_min.length() < 1e-10 * scale, "n={n} {res_min}");
            assert!((m.w - m.sigma_max * m.sigma_min).abs() < 1e-12 * scale);
            // Trace and determinant invariants.
            let s2 = m.sigma_max.powi(2) + m.sigma_min.powi(2);
            assert!((s2 - scale).abs() < 1e-10 * scale);
            if n == 1 {
                assert_eq!(m.sigma_min, 0.0);
                assert_eq!(m.condition, f64::INFINITY);
            } else if m.sigma_min > 0.0 {
                assert!((m.condition - m.sigma_max / m.sigma_min).abs() <= 1e-9 * m.condition);
            }
        }
    }

    #[test]
    fn hand_computed_ellipse_for_two_link_right_angle() {
        // J Jᵀ = [[2, -1], [-1, 1]]: eigenvalues (3 ± √5)/2.
        let m = manipulability(&jacobian(&[1.0, 1.0], &[0.0, FRAC_PI_2]));
        let s5 = 5f64.sqrt();
        assert!((m.sigma_max.powi(2) - (3.0 + s5) / 2.0).abs() < 1e-12);
        assert!((m.sigma_min.powi(2) - (3.0 - s5) / 2.0).abs() < 1e-12);
        assert!((m.w - 1.0).abs() < 1e-12); // L1 L2 |sin 90°|
                                            // Long axis tilts into the second/fourth quadrant (b < 0).
        assert!(m.u_max.x * m.u_max.y < 0.0);
    }

    #[test]
    fn straight_and_folded_arms_are_singular_without_nan() {
        for angles in [
            vec![0.0, 0.0, 0.0],
            vec![0.7, 0.0, 0.0],
            vec![-2.0, 0.0, 0.0],
            vec![1.0, PI, 0.0],
        ] {
            let cols = jacobian(&[1.0, 0.8, 0.5], &angles);
            let m = manipulability(&cols);
            assert_eq!(m.sigma_min, 0.0, "{angles:?}");
            assert_eq!(m.w, 0.0);
            assert_eq!(m.condition, f64::INFINITY);
            assert!(m.sigma_max > 0.0 && m.sigma_max.is_finite());
            assert!(m.u_max.is_finite() && m.u_min.is_finite());
            // The short axis is along the arm (radial): no instantaneous radial motion.
            let radial = DVec2::new(angles[0].cos(), angles[0].sin());
            assert!(m.u_min.dot(radial).abs() > 1.0 - 1e-9);
        }
        // Nearly straight is not snapped: tiny but positive.
        let m = manipulability(&jacobian(&[1.0, 1.0], &[0.3, 1e-6]));
        assert!((m.w - 1e-6).abs() < 1e-12);
        assert!(m.condition.is_finite() && m.condition > 1e5);
    }

    #[test]
    fn isotropic_jacobian_has_equal_singular_values() {
        // Columns (1,0) and (0,1): J Jᵀ = I, a circle.
        let m = manipulability(&[DVec2::X, DVec2::Y]);
        assert!((m.sigma_max - 1.0).abs() < 1e-15 && (m.sigma_min - 1.0).abs() < 1e-15);
        assert_eq!(m.condition, 1.0);
        assert!(m.u_max.is_finite());
    }
}
