//! Estimation errors and filter-consistency tests.
//!
//! **NEES** (normalised estimation error squared; Bar-Shalom, Li &
//! Kirubarajan, *Estimation with Applications to Tracking and Navigation*,
//! Wiley 2001, §5.4.2, eq. 5.4.2-1):
//!
//! ```text
//! ε = (x − x̂)ᵀ P⁻¹ (x − x̂)         (heading difference wrapped to [−π, π))
//! ```
//!
//! For a consistent filter `ε ~ χ²(n)`, `n = 3` here. Averaged over `N`
//! independent Monte-Carlo runs, `N·ε̄ ~ χ²(N n)`, so the two-sided
//! `(1 − α)` acceptance region of the average is (eq. 5.4.2-5/-6)
//!
//! ```text
//! [ χ²_{α/2}(N n) / N ,  χ²_{1−α/2}(N n) / N ]      (n = 3, N = 50, α = 5 %: [2.36, 3.72])
//! ```
//!
//! χ² quantiles come from the Wilson–Hilferty cube-root approximation
//! (Wilson & Hilferty, "The distribution of chi-square", *PNAS* 17, 1931;
//! Johnson, Kotz & Balakrishnan, *Continuous Univariate Distributions* Vol. 1,
//! 1994, eq. 18.24): `χ²_p(k) ≈ k (1 − 2/(9k) + z_p √(2/(9k)))³`, within
//! 0.1 % of the tabulated values for `k ≥ 30` (the Monte-Carlo case: `k = N n`)
//! but rough for a single run of a small state — at `k = 3` the 97.5 % point
//! is 0.3 % low and the 2.5 % point 16 % low (0.181 vs 0.216) — with the normal
//! quantile `z_p` from Acklam's rational approximation (relative error
//! < 1.2·10⁻⁹).

use glam::{DMat2, DMat3, DVec2, DVec3};

use super::wrap_angle;

/// Estimation error `x − x̂` with the heading difference wrapped to `[−π, π)`.
#[must_use]
pub fn pose_error(truth: DVec3, estimate: DVec3) -> DVec3 {
    let mut e = truth - estimate;
    e.z = wrap_angle(e.z);
    e
}

/// Position error `|(x, y) − (x̂, ŷ)|`, metres.
#[must_use]
pub fn position_error_m(truth: DVec3, estimate: DVec3) -> f64 {
    (truth.truncate() - estimate.truncate()).length()
}

/// Heading error `wrap(θ − θ̂)`, radians in `[−π, π)`.
#[must_use]
pub fn heading_error_rad(truth: DVec3, estimate: DVec3) -> f64 {
    wrap_angle(truth.z - estimate.z)
}

/// NEES `eᵀ P⁻¹ e` of a pose estimate; `None` when `P` is not invertible
/// (or not finite).
///
/// # Example
/// ```
/// use labcore::estimation::consistency::nees;
/// use glam::{DMat3, DVec3};
/// let p = DMat3::from_diagonal(DVec3::new(0.04, 0.04, 0.01));
/// // One σ off in x only: NEES = 1.
/// assert!((nees(DVec3::new(0.2, 0.0, 0.0), DVec3::ZERO, p).unwrap() - 1.0).abs() < 1e-12);
/// ```
#[must_use]
pub fn nees(truth: DVec3, estimate: DVec3, cov: DMat3) -> Option<f64> {
    let det = cov.determinant();
    if !(det.is_finite() && det > 0.0) {
        return None;
    }
    let e = pose_error(truth, estimate);
    let v = e.dot(cov.inverse() * e);
    v.is_finite().then_some(v)
}

/// Quantile `z_p` of the standard normal distribution (Acklam's algorithm,
/// relative error below 1.2·10⁻⁹). `None` unless `0 < p < 1`.
///
/// # Example
/// ```
/// use labcore::estimation::consistency::normal_quantile;
/// assert!((normal_quantile(0.975).unwrap() - 1.959964).abs() < 1e-6);
/// ```
#[must_use]
pub fn normal_quantile(p: f64) -> Option<f64> {
    if !(p > 0.0 && p < 1.0) {
        return None;
    }
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    const P_LOW: f64 = 0.024_25;
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    let z = if p < P_LOW {
        tail((-2.0 * crate::math::ln(p)).sqrt())
    } else if p > 1.0 - P_LOW {
        -tail((-2.0 * crate::math::ln(1.0 - p)).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    };
    Some(z)
}

/// Quantile `χ²_p(k)` by Wilson–Hilferty. `None` unless `0 < p < 1` and
/// `dof ≥ 1`.
#[must_use]
pub fn chi_square_quantile(p: f64, dof: usize) -> Option<f64> {
    if dof == 0 {
        return None;
    }
    let z = normal_quantile(p)?;
    let k = dof as f64;
    let a = 2.0 / (9.0 * k);
    let t = 1.0 - a + z * a.sqrt();
    Some((k * t * t * t).max(0.0))
}

/// Two-sided acceptance region of the NEES averaged over `runs` independent
/// runs of a filter with `dof` states, at `confidence` (e.g. 0.95).
///
/// # Example
/// ```
/// use labcore::estimation::consistency::nees_bounds;
/// let (lo, hi) = nees_bounds(3, 50, 0.95).unwrap();
/// assert_eq!(((lo * 100.0).round() / 100.0, (hi * 100.0).round() / 100.0), (2.36, 3.72));
/// ```
#[must_use]
pub fn nees_bounds(dof: usize, runs: usize, confidence: f64) -> Option<(f64, f64)> {
    if runs == 0 || !(confidence > 0.0 && confidence < 1.0) {
        return None;
    }
    let alpha = 1.0 - confidence;
    let k = dof.checked_mul(runs)?;
    let n = runs as f64;
    Some((
        chi_square_quantile(0.5 * alpha, k)? / n,
        chi_square_quantile(1.0 - 0.5 * alpha, k)? / n,
    ))
}

/// Semi-axes and orientation of the `n_sigma` ellipse of a 2×2 covariance:
/// `(a, b, φ)` with `a ≥ b ≥ 0` metres and the major axis at angle `φ`
/// (radians, in `(−π/2, π/2]`) from +x. From the closed-form eigen-
/// decomposition of a symmetric 2×2 matrix; negative eigenvalues (rounding)
/// count as 0, non-finite input gives zeros.
///
/// # Example
/// ```
/// use labcore::estimation::consistency::covariance_ellipse;
/// use glam::{DMat2, DVec2};
/// let (a, b, phi) = covariance_ellipse(DMat2::from_diagonal(DVec2::new(0.01, 0.04)), 3.0);
/// assert!((a - 0.6).abs() < 1e-12 && (b - 0.3).abs() < 1e-12);
/// assert!((phi - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
/// ```
#[must_use]
pub fn covariance_ellipse(cov: DMat2, n_sigma: f64) -> (f64, f64, f64) {
    if !(cov.is_finite() && n_sigma.is_finite()) {
        return (0.0, 0.0, 0.0);
    }
    let (sxx, syy) = (cov.x_axis.x, cov.y_axis.y);
    let sxy = 0.5 * (cov.x_axis.y + cov.y_axis.x);
    let mean = 0.5 * (sxx + syy);
    let half_diff = 0.5 * (sxx - syy);
    let rad = crate::math::hypot(half_diff, sxy);
    let l1 = (mean + rad).max(0.0);
    let l2 = (mean - rad).max(0.0);
    let mut phi = 0.5 * crate::math::atan2(2.0 * sxy, sxx - syy);
    if phi <= -std::f64::consts::FRAC_PI_2 {
        phi += std::f64::consts::PI;
    }
    let k = n_sigma.abs();
    (k * l1.sqrt(), k * l2.sqrt(), phi)
}

/// The position block (upper-left 2×2) of a pose covariance.
#[must_use]
pub fn position_block(cov: DMat3) -> DMat2 {
    DMat2::from_cols(
        DVec2::new(cov.x_axis.x, cov.x_axis.y),
        DVec2::new(cov.y_axis.x, cov.y_axis.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nees_bounds_for_50_runs_of_3_states() {
        let (lo, hi) = nees_bounds(3, 50, 0.95).unwrap();
        assert!((lo - 2.36).abs() < 0.005, "{lo}");
        assert!((hi - 3.72).abs() < 0.005, "{hi}");
        // Tabulated χ²(150): 0.025 → 117.985, 0.975 → 185.800.
        assert!((chi_square_quantile(0.025, 150).unwrap() - 117.985).abs() < 0.05);
        assert!((chi_square_quantile(0.975, 150).unwrap() - 185.800).abs() < 0.05);
        // Single run, 3 states: tabulated [0.2158, 9.3484]; Wilson–Hilferty
        // is close at the upper end, 16 % low at the lower (documented).
        let (lo, hi) = nees_bounds(3, 1, 0.95).unwrap();
        assert!((hi / 9.3484 - 1.0).abs() < 0.005, "{hi}");
        assert!((lo - 0.1814).abs() < 0.001, "{lo}");
        // k = 30: within 0.1 % of the table (16.791, 46.979).
        assert!((chi_square_quantile(0.025, 30).unwrap() / 16.791 - 1.0).abs() < 1e-3);
        assert!((chi_square_quantile(0.975, 30).unwrap() / 46.979 - 1.0).abs() < 1e-3);
        assert_eq!(nees_bounds(3, 0, 0.95), None);
        assert_eq!(nees_bounds(3, 50, 1.0), None);
        assert_eq!(chi_square_quantile(0.5, 0), None);
    }

    #[test]
    fn normal_quantile_matches_table() {
        for (p, z) in [
            (0.5, 0.0),
            (0.8413447460685429, 1.0),
            (0.975, 1.959963984540054),
            (0.001, -3.090232306167813),
            (1e-10, -6.361340902404056),
        ] {
            let got = normal_quantile(p).unwrap();
            assert!(
                (got - z).abs() < 1e-8 * (1.0 + z.abs()),
                "p={p}: {got} vs {z}"
            );
            assert!((normal_quantile(1.0 - p).unwrap() + z).abs() < 1e-8 * (1.0 + z.abs()));
        }
        assert_eq!(normal_quantile(0.0), None);
        assert_eq!(normal_quantile(f64::NAN), None);
    }

    #[test]
    fn errors_wrap_heading_and_nees_refuses_singular_covariance() {
        use std::f64::consts::PI;
        let t = DVec3::new(1.0, 1.0, PI - 0.1);
        let e = DVec3::new(1.0, 4.0, -PI + 0.1);
        assert!((heading_error_rad(t, e) + 0.2).abs() < 1e-12);
        assert_eq!(position_error_m(t, e), 3.0);
        assert_eq!(nees(t, e, DMat3::ZERO), None);
        let p = DMat3::from_diagonal(DVec3::new(1.0, 4.0, 0.04));
        assert!((nees(t, e, p).unwrap() - (9.0 / 4.0 + 1.0)).abs() < 1e-12);
    }

    #[test]
    fn ellipse_of_a_rotated_covariance() {
        // Variances 4 and 1 along axes rotated by 30°.
        let phi: f64 = 30f64.to_radians();
        let (s, c) = phi.sin_cos();
        let rot = DMat2::from_cols(DVec2::new(c, s), DVec2::new(-s, c));
        let cov = rot * DMat2::from_diagonal(DVec2::new(4.0, 1.0)) * rot.transpose();
        let (a, b, ang) = covariance_ellipse(cov, 1.0);
        assert!((a - 2.0).abs() < 1e-12 && (b - 1.0).abs() < 1e-12);
        assert!((ang - phi).abs() < 1e-12);
        assert_eq!(covariance_ellipse(DMat2::NAN, 3.0), (0.0, 0.0, 0.0));
    }
}
