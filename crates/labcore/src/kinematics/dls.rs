//! Damped-least-squares (DLS) inverse kinematics of a planar chain, position only.
//!
//! With the tip error `e = p_target − p_tip` (metres) and the 2×n Jacobian `J`
//! of [`super::jacobian`], one DLS step is
//!
//! ```text
//! Δθ = Jᵀ (J Jᵀ + λ² I)⁻¹ e
//! ```
//!
//! the minimiser of `|J Δθ − e|² + λ² |Δθ|²` (Wampler, "Manipulator inverse
//! kinematic solutions based on vector formulations and damped least-squares
//! methods", *IEEE Trans. SMC* 16(1), 1986; Nakamura & Hanafusa, "Inverse
//! kinematic solutions with singularity robustness for robot manipulator
//! control", *ASME J. Dyn. Sys. Meas. Control* 108, 1986, pp. 163–171; Buss,
//! "Introduction to Inverse Kinematics with Jacobian Transpose, Pseudoinverse
//! and Damped Least Squares methods", 2004, §5, eq. (11)).
//!
//! In the plane `J Jᵀ + λ² I = [[a + λ², b], [b, c + λ²]]` is 2×2, so the
//! system is solved in closed form, `y = M⁻¹ e`, then `Δθ = Jᵀ y`: no matrix
//! library, no heap allocation (chains of up to [`MAX_JOINTS`] = 8 joints live
//! in stack arrays).
//!
//! **Why damping.** Along a singular direction with singular value `σ` the
//! pseudo-inverse multiplies the error by `1/σ`, which explodes as `σ → 0`
//! (straight or folded arm). DLS multiplies it by `σ / (σ² + λ²) ≤ 1/(2λ)`, so
//! every step obeys `|Δθ| ≤ |e| / (2λ)` (Buss 2004, §5). The price is a small
//! lag: far from singularities the error still shrinks by about
//! `λ² / (σ² + λ²)` per step.
//!
//! **Adaptive damping** ([`AdaptiveDamping`], after Nakamura & Hanafusa 1986):
//! damping is only needed near singularities, so with manipulability
//! `w = √det(J Jᵀ)` below a threshold `w₀`
//!
//! ```text
//! λ² = λ_base² + λ_max² (1 − w/w₀)²     (w < w₀),     λ² = λ_base²   (w ≥ w₀)
//! ```
//!
//! which is continuous at `w = w₀` and reduces to Nakamura & Hanafusa's
//! `λ_max² (1 − w/w₀)²` when the base damping is 0.
//!
//! **One step** ([`DlsSolver::step`]) is that update with two guards: `|Δθ|`
//! is clamped to [`DlsSolver::max_step_rad`], and with
//! [`DlsSolver::reject_uphill_steps`] a step that would raise the error is
//! retried with λ² × 10 (Levenberg–Marquardt's rule: Marquardt, *J. SIAM*
//! 11(2), 1963). Without that rule the bare update overshoots around an
//! out-of-reach target and can oscillate — the behaviour damping is meant to
//! tame.
//!
//! **The iteration** ([`DlsSolver::solve`]) repeats the step from the current
//! pose and adapts the damping between steps as a Levenberg–Marquardt method:
//! λ² is multiplied by a factor `μ` that shrinks after a good step and grows
//! after a rejected one, by Nielsen's gain-ratio rule (Madsen, Nielsen &
//! Tingleff, *Methods for Non-Linear Least Squares Problems*, DTU 2004, §3.2,
//! eq. 3.16): with `ρ` = actual / predicted decrease of `|e|²`,
//! `μ ← μ · max(1/3, 1 − (2ρ − 1)³)` on acceptance, `μ ← μ · ν, ν ← 2ν` on
//! rejection, `μ` kept between [`MIN_BOOST`] and [`MAX_BOOST`]. So the damping you set
//! bounds the first steps and fades (down to λ/100) as the pose nears a
//! solution, which keeps convergence fast even at a singular solution.
//!
//! **Unreachable targets** are not an error. [`DlsSolver::solve`] aims at the
//! closest reachable point — the target's radial projection onto the
//! reachable annulus ([`Annulus::nearest`]) — so the arm settles straight
//! towards a target beyond its reach, or folded towards one inside the inner
//! hole; the reported error is measured to the real target, i.e. the distance
//! to the annulus (plus at most the tolerance).

use glam::DVec2;
use std::fmt;

use super::chain::{tip, Annulus};
use super::jacobian::{columns_into_array, det_jjt, jjt_entries, MAX_JOINTS};
use super::two_link_ik::wrap_pi;

/// Largest total reach `Σ Lₖ` accepted, metres: keeps every product in the
/// 2×2 solve (≈ reach⁴) far from overflow.
pub const MAX_REACH_M: f64 = 1e50;

/// λ² is never below this fraction of `tr(J Jᵀ)`, so `J Jᵀ + λ² I` stays
/// invertible even with `damping = 0` (the undamped pseudo-inverse step).
pub const LAMBDA_SQ_FLOOR_REL: f64 = 1e-12;

/// The iteration stops (not converged) when a step would move the joints by less than this, radians.
pub const STALL_STEP_RAD: f64 = 1e-13;

/// Largest factor by which uphill retries may multiply λ² (see [`DlsSolver::reject_uphill_steps`]).
pub const MAX_BOOST: f64 = 1e16;

/// Smallest factor on λ² that [`DlsSolver::solve`] relaxes to after a run of
/// accepted steps (λ down to λ/100), when [`DlsSolver::reject_uphill_steps`] is on.
pub const MIN_BOOST: f64 = 1e-4;

/// Singularity-dependent damping after Nakamura & Hanafusa (1986):
/// `λ² = λ_base² + λ_max² (1 − w/w₀)²` while `w < w₀`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveDamping {
    /// `w₀`, m²/rad: manipulability below which extra damping starts (≥ 0).
    pub w_threshold: f64,
    /// `λ_max`, metres: the extra damping reached at `w = 0` (≥ 0).
    pub lambda_max: f64,
}

impl AdaptiveDamping {
    /// `λ²` (m²) for manipulability `w` (m²/rad) on top of the base damping `base_lambda` (m).
    ///
    /// # Example
    /// ```
    /// use labcore::kinematics::dls::AdaptiveDamping;
    /// let a = AdaptiveDamping { w_threshold: 0.1, lambda_max: 0.5 };
    /// assert_eq!(a.lambda_squared(0.2, 0.01), 0.01 * 0.01);          // w ≥ w₀: base only
    /// assert!((a.lambda_squared(0.0, 0.0) - 0.25).abs() < 1e-15);   // w = 0: λ_max²
    /// ```
    #[must_use]
    pub fn lambda_squared(&self, w: f64, base_lambda: f64) -> f64 {
        let base2 = base_lambda * base_lambda;
        if w < self.w_threshold && self.w_threshold > 0.0 {
            let f = 1.0 - (w / self.w_threshold).max(0.0);
            base2 + self.lambda_max * self.lambda_max * f * f
        } else {
            base2
        }
    }
}

/// Tuning of the damped-least-squares solver; every field is public and documented.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DlsSolver {
    /// Base damping `λ`, metres (finite, ≥ 0). 0 gives the undamped
    /// (pseudo-inverse) step, kept invertible by [`LAMBDA_SQ_FLOOR_REL`].
    pub damping: f64,
    /// Success when the tip error `|e|` is below this, metres (finite, ≥ 0).
    pub tolerance_m: f64,
    /// Most steps [`DlsSolver::solve`] takes (rejected retries count too).
    pub max_iterations: usize,
    /// Extra damping near singularities; `None` keeps `λ` fixed.
    pub adaptive: Option<AdaptiveDamping>,
    /// Clamp on the Euclidean norm of one joint step `|Δθ|`, radians (> 0;
    /// `f64::INFINITY` disables it).
    pub max_step_rad: f64,
    /// Levenberg–Marquardt safeguard. In [`DlsSolver::step`]: a step that does
    /// not lower the error is retried with λ² × 10. In [`DlsSolver::solve`]:
    /// the same, plus λ² relaxing after good steps (module docs). `false`
    /// gives the plain DLS iteration with fixed λ, which can oscillate around
    /// an unreachable target.
    pub reject_uphill_steps: bool,
}

impl Default for DlsSolver {
    /// `λ = 0.05 m`, tolerance `1e-6 m`, 200 iterations, no adaptive damping,
    /// steps clamped to 1 rad, uphill steps rejected.
    ///
    /// With unit-scale links (0.3–2 m) this converges on reachable targets in
    /// about 7 steps (the Planar IK benchmark); λ = 0.05 m keeps a [`DlsSolver::step`]
    /// near a singularity under `|e| / (0.1 m)` radians.
    fn default() -> Self {
        Self {
            damping: 0.05,
            tolerance_m: 1e-6,
            max_iterations: 200,
            adaptive: None,
            max_step_rad: 1.0,
            reject_uphill_steps: true,
        }
    }
}

/// What one [`DlsSolver::step`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DlsStep {
    /// `|e|` before the step, metres.
    pub error_before_m: f64,
    /// `|e|` after the step, metres.
    pub error_after_m: f64,
    /// The damping actually used, metres (adaptive and floor included).
    pub lambda: f64,
    /// `|Δθ|` (Euclidean norm, after the clamp), radians.
    pub step_norm_rad: f64,
}

/// How [`DlsSolver::solve`] ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DlsOutcome {
    /// Steps taken, rejected retries included (0 when the start pose already met the tolerance).
    pub iterations: usize,
    /// Final tip error `|e|`, metres. For an unreachable target, about the
    /// distance from the target to the reachable annulus.
    pub error_m: f64,
    /// `error_m < tolerance_m`.
    pub converged: bool,
}

/// Why the solver refused to run. On any error the joint angles are left unchanged.
#[derive(Clone, Debug, PartialEq)]
pub enum DlsError {
    /// No joints, `lengths_m` and `angles_rad` of different lengths, a NaN or
    /// infinite length, angle or target (or one so far that its distance
    /// overflows `f64`), a length ≤ 0, or a total reach above [`MAX_REACH_M`].
    InvalidInput,
    /// More joints than the solver's stack buffers hold.
    TooManyJoints { joints: usize, max: usize },
    /// A [`DlsSolver`] field out of its documented range; names the field.
    InvalidSettings { field: &'static str },
}

impl fmt::Display for DlsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DlsError::InvalidInput => write!(
                f,
                "invalid input: need 1 to {MAX_JOINTS} finite positive link lengths, as many finite angles, and a finite target"
            ),
            DlsError::TooManyJoints { joints, max } => {
                write!(f, "{joints} joints: at most {max} are supported")
            }
            DlsError::InvalidSettings { field } => write!(f, "solver setting `{field}` out of range"),
        }
    }
}

impl std::error::Error for DlsError {}

/// `|e|` without overflow: the plain norm, or `hypot` if the square overflowed.
#[inline]
fn norm(e: DVec2) -> f64 {
    let d2 = e.length_squared();
    if d2.is_finite() {
        d2.sqrt()
    } else {
        crate::math::hypot(e.x, e.y)
    }
}

impl DlsSolver {
    /// Checks the settings and the chain; returns `n` and the total reach (m).
    fn validate(
        &self,
        lengths_m: &[f64],
        angles_rad: &[f64],
        target: DVec2,
    ) -> Result<(usize, f64), DlsError> {
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return Err(DlsError::InvalidSettings { field: "damping" });
        }
        if !(self.tolerance_m.is_finite() && self.tolerance_m >= 0.0) {
            return Err(DlsError::InvalidSettings {
                field: "tolerance_m",
            });
        }
        if self.max_step_rad.is_nan() || self.max_step_rad <= 0.0 {
            return Err(DlsError::InvalidSettings {
                field: "max_step_rad",
            });
        }
        if let Some(a) = self.adaptive {
            if !(a.w_threshold.is_finite() && a.w_threshold >= 0.0) {
                return Err(DlsError::InvalidSettings {
                    field: "adaptive.w_threshold",
                });
            }
            if !(a.lambda_max.is_finite() && a.lambda_max >= 0.0) {
                return Err(DlsError::InvalidSettings {
                    field: "adaptive.lambda_max",
                });
            }
        }
        let n = lengths_m.len();
        if n == 0 || angles_rad.len() != n {
            return Err(DlsError::InvalidInput);
        }
        if n > MAX_JOINTS {
            return Err(DlsError::TooManyJoints {
                joints: n,
                max: MAX_JOINTS,
            });
        }
        let mut reach = 0.0;
        for &l in lengths_m {
            if !(l.is_finite() && l > 0.0) {
                return Err(DlsError::InvalidInput);
            }
            reach += l;
        }
        if reach.is_nan() || reach > MAX_REACH_M || !norm(target).is_finite() {
            return Err(DlsError::InvalidInput);
        }
        if !angles_rad.iter().all(|a| a.is_finite()) {
            return Err(DlsError::InvalidInput);
        }
        Ok((n, reach))
    }

    /// λ² (m²) for these columns, before the floor and any retry boost.
    #[inline]
    fn lambda_squared(&self, cols: &[DVec2]) -> f64 {
        match self.adaptive {
            None => self.damping * self.damping,
            Some(adaptive) => adaptive.lambda_squared(det_jjt(cols).sqrt(), self.damping),
        }
    }

    /// One DLS step for the Jacobian `cols` and error `e` (already clamped to
    /// the reach): fills `dq[..n]`, returns `(|Δθ|, λ used)`.
    #[inline]
    fn delta(
        &self,
        cols: &[DVec2],
        e: DVec2,
        boost: f64,
        dq: &mut [f64; MAX_JOINTS],
    ) -> (f64, f64) {
        let (a, b, c) = jjt_entries(cols);
        let floor = LAMBDA_SQ_FLOOR_REL * (a + c);
        let lam2 = (self.lambda_squared(cols).max(floor) * boost).max(floor);
        let (ma, mc) = (a + lam2, c + lam2);
        let det = ma * mc - b * b;
        if !(det > 0.0 && det.is_finite()) {
            dq.fill(0.0);
            return (0.0, lam2.sqrt());
        }
        let y = DVec2::new(mc * e.x - b * e.y, ma * e.y - b * e.x) / det;
        let mut norm2 = 0.0;
        for (d, col) in dq.iter_mut().zip(cols) {
            *d = col.dot(y);
            norm2 += *d * *d;
        }
        let mut step = norm2.sqrt();
        if step > self.max_step_rad {
            let scale = self.max_step_rad / step;
            for d in dq.iter_mut().take(cols.len()) {
                *d *= scale;
            }
            step = self.max_step_rad;
        }
        if !step.is_finite() {
            dq.fill(0.0);
            step = 0.0;
        }
        (step, lam2.sqrt())
    }

    /// One DLS iteration `Δθ = Jᵀ (J Jᵀ + λ² I)⁻¹ e`, `e = target − tip`,
    /// applied to `angles_rad` in place (radians, relative joint angles,
    /// written back wrapped to `[-π, π]`;
    /// `lengths_m` in metres, `target` in metres in the base frame).
    ///
    /// The error fed to the step is clamped to the arm's reach `Σ Lₖ` (only far
    /// targets notice) and `|Δθ|` to [`DlsSolver::max_step_rad`].
    ///
    /// With [`DlsSolver::reject_uphill_steps`] (the default) a step that does
    /// not lower the error is retried within this call with λ² × 10, up to
    /// 10¹⁶ × λ²; [`DlsStep::lambda`] reports the damping of the step taken. If
    /// no damping helps (a stationary pose, e.g. a straight arm aimed at a
    /// target beyond its reach) the angles stay as they are and
    /// `step_norm_rad = 0`. With the flag off this is the bare update, which
    /// for an unreachable target can overshoot and oscillate — the classic
    /// reason for damping (Buss 2004, §5). On `Err` the angles are unchanged.
    ///
    /// # Example
    /// ```
    /// use labcore::kinematics::dls::DlsSolver;
    /// use glam::DVec2;
    /// let solver = DlsSolver::default();
    /// let mut q = [0.3, 0.3];
    /// let s = solver.step(&[1.0, 1.0], &mut q, DVec2::new(1.0, 1.0)).unwrap();
    /// assert!(s.error_after_m < s.error_before_m);
    /// assert!(s.step_norm_rad <= s.error_before_m / (2.0 * s.lambda));
    /// ```
    pub fn step(
        &self,
        lengths_m: &[f64],
        angles_rad: &mut [f64],
        target: DVec2,
    ) -> Result<DlsStep, DlsError> {
        let (n, reach) = self.validate(lengths_m, angles_rad, target)?;
        let mut cols = [DVec2::ZERO; MAX_JOINTS];
        let mut trial_cols = [DVec2::ZERO; MAX_JOINTS];
        let tip = columns_into_array(lengths_m, angles_rad, &mut cols);
        let e = target - tip;
        let error_before_m = norm(e);
        let e_used = if error_before_m > reach {
            e * (reach / error_before_m)
        } else {
            e
        };
        let mut dq = [0.0; MAX_JOINTS];
        let mut q = [0.0; MAX_JOINTS];
        let mut boost = 1.0;
        let mut first_lambda = None;
        while boost <= MAX_BOOST {
            let (step_norm_rad, lambda) = self.delta(&cols[..n], e_used, boost, &mut dq);
            first_lambda.get_or_insert(lambda);
            if step_norm_rad < STALL_STEP_RAD && self.reject_uphill_steps {
                break;
            }
            for k in 0..n {
                q[k] = angles_rad[k] + dq[k];
            }
            let after = columns_into_array(lengths_m, &q[..n], &mut trial_cols);
            let error_after_m = norm(target - after);
            if !self.reject_uphill_steps || error_after_m < error_before_m {
                if !(q[..n].iter().all(|a| a.is_finite()) && error_after_m.is_finite()) {
                    // Unreachable with validated input; kept so no NaN can escape.
                    return Err(DlsError::InvalidInput);
                }
                for (a, q) in angles_rad.iter_mut().zip(&q[..n]) {
                    *a = wrap_pi(*q);
                }
                return Ok(DlsStep {
                    error_before_m,
                    error_after_m,
                    lambda,
                    step_norm_rad,
                });
            }
            boost *= 10.0;
        }
        Ok(DlsStep {
            error_before_m,
            error_after_m: error_before_m,
            lambda: first_lambda.unwrap_or(self.damping),
            step_norm_rad: 0.0,
        })
    }

    /// Iterates DLS steps from `angles_rad` until `|e| < tolerance_m` or
    /// [`DlsSolver::max_iterations`] steps, writing the final pose back into
    /// `angles_rad` (radians, each wrapped to `[-π, π]` by
    /// [`wrap_pi`](super::two_link_ik::wrap_pi); wrapping leaves the pose unchanged).
    ///
    /// With [`DlsSolver::reject_uphill_steps`] (the default) this is a
    /// Levenberg–Marquardt iteration on the DLS step: an uphill step is undone
    /// and λ² raised; after an accepted step λ² relaxes by the gain-ratio rule
    /// (module docs), never below `λ² ×` [`MIN_BOOST`]. Without it, the plain
    /// DLS iteration with fixed λ. The loop also ends early (not converged)
    /// when the step falls below [`STALL_STEP_RAD`] or λ² would exceed
    /// `λ² ×` [`MAX_BOOST`].
    ///
    /// An unreachable target is not an error: the iteration aims at the
    /// closest point of the reachable annulus, the arm settles straight (or
    /// folded) towards the target, `converged = false` and `error_m` is the
    /// distance from the target to the annulus, plus at most `tolerance_m`.
    /// On `Err` the angles are left as they were.
    ///
    /// # Example
    /// ```
    /// use labcore::kinematics::{chain::tip, dls::DlsSolver};
    /// use glam::DVec2;
    /// let lengths = [1.0, 1.0, 1.0];
    /// let target = DVec2::new(1.2, 1.5);
    /// let mut q = [0.3; 3];
    /// let out = DlsSolver::default().solve(&lengths, &mut q, target).unwrap();
    /// assert!(out.converged && (tip(&lengths, &q) - target).length() < 1e-6);
    ///
    /// // Out of reach (|p| = 5 > 3): settles straight towards it, 2 m short.
    /// let out = DlsSolver::default().solve(&lengths, &mut q, DVec2::new(3.0, 4.0)).unwrap();
    /// assert!(!out.converged && (out.error_m - 2.0).abs() < 1e-6);
    /// ```
    pub fn solve(
        &self,
        lengths_m: &[f64],
        angles_rad: &mut [f64],
        target: DVec2,
    ) -> Result<DlsOutcome, DlsError> {
        let (n, reach) = self.validate(lengths_m, angles_rad, target)?;
        let lengths = &lengths_m[..n];
        let mut q = [0.0; MAX_JOINTS];
        q[..n].copy_from_slice(angles_rad);
        let mut trial = q;
        let mut cols = [DVec2::ZERO; MAX_JOINTS];
        let mut trial_cols = [DVec2::ZERO; MAX_JOINTS];
        let mut dq = [0.0; MAX_JOINTS];

        // Aim at the closest reachable point: the target itself when it lies in
        // the annulus, else its radial projection onto the nearer boundary.
        let annulus = Annulus::of_chain(lengths);
        let aim = if annulus.contains(target, 0.0) {
            target
        } else {
            annulus.nearest(target)
        };
        let mut e = aim - columns_into_array(lengths, &q[..n], &mut cols);
        let mut err = norm(e);
        let mut boost = 1.0;
        let mut nu = 2.0;
        let mut iterations = 0;
        while err >= self.tolerance_m && iterations < self.max_iterations {
            let e_used = if err > reach { e * (reach / err) } else { e };
            let (step, _) = self.delta(&cols[..n], e_used, boost, &mut dq);
            if step < STALL_STEP_RAD {
                break;
            }
            iterations += 1;
            let mut j_dq = DVec2::ZERO;
            for k in 0..n {
                trial[k] = q[k] + dq[k];
                j_dq += cols[k] * dq[k];
            }
            let e_trial = aim - columns_into_array(lengths, &trial[..n], &mut trial_cols);
            let err_trial = norm(e_trial);
            if !self.reject_uphill_steps {
                q = trial;
                std::mem::swap(&mut cols, &mut trial_cols);
                e = e_trial;
                err = err_trial;
            } else if err_trial < err {
                // Gain ratio: actual over predicted (linear model) decrease of |e|².
                let predicted = err * err - (e - j_dq).length_squared();
                let rho = (err * err - err_trial * err_trial) / predicted;
                let factor = if rho.is_finite() && predicted > 0.0 {
                    (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0)
                } else {
                    1.0 / 3.0
                };
                boost = (boost * factor).max(MIN_BOOST);
                nu = 2.0;
                q = trial;
                std::mem::swap(&mut cols, &mut trial_cols);
                e = e_trial;
                err = err_trial;
            } else {
                boost *= nu;
                nu *= 2.0;
                if boost > MAX_BOOST {
                    break;
                }
            }
        }
        let error_m = if aim == target {
            err
        } else {
            norm(target - tip(lengths, &q[..n]))
        };
        if !q[..n].iter().all(|a| a.is_finite()) || !error_m.is_finite() {
            // Unreachable with validated input; kept so no NaN can escape.
            return Err(DlsError::InvalidInput);
        }
        for (a, q) in angles_rad.iter_mut().zip(&q[..n]) {
            *a = wrap_pi(*q);
        }
        Ok(DlsOutcome {
            iterations,
            error_m,
            converged: error_m < self.tolerance_m,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::jacobian::{jacobian, manipulability};
    use crate::kinematics::two_link_ik::wrap_pi;
    use crate::rng::Lcg64;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn unclamped(damping: f64) -> DlsSolver {
        DlsSolver {
            damping,
            max_step_rad: f64::INFINITY,
            reject_uphill_steps: false,
            ..DlsSolver::default()
        }
    }

    #[test]
    fn hand_computed_single_step_two_link() {
        // L = (1, 1), θ = (0, 90°): tip (1, 1), J = [[-1, -1], [1, 0]],
        // J Jᵀ = [[2, -1], [-1, 1]]. Target (1.1, 1): e = (0.1, 0). λ = 0.1:
        // M = [[2.01, -1], [-1, 1.01]], det M = 1.0301,
        // y = M⁻¹ e = (0.101, 0.1) / 1.0301,
        // Δθ = Jᵀ y = (−y1 + y2, −y1) = (−0.001, −0.101) / 1.0301.
        let solver = unclamped(0.1);
        let mut q = [0.0, FRAC_PI_2];
        let s = solver
            .step(&[1.0, 1.0], &mut q, DVec2::new(1.1, 1.0))
            .unwrap();
        let d1 = -0.001 / 1.0301;
        let d2 = -0.101 / 1.0301;
        assert!((q[0] - d1).abs() < 1e-14, "{}", q[0]);
        assert!((q[1] - (FRAC_PI_2 + d2)).abs() < 1e-14, "{}", q[1]);
        assert!((s.error_before_m - 0.1).abs() < 1e-14);
        assert!((s.lambda - 0.1).abs() < 1e-15);
        assert!((s.step_norm_rad - d1.hypot(d2)).abs() < 1e-14);
        let after = (tip(&[1.0, 1.0], &q) - DVec2::new(1.1, 1.0)).length();
        assert!((s.error_after_m - after).abs() < 1e-15);
        assert!(s.error_after_m < 0.01); // one step removes most of the error
    }

    #[test]
    fn step_is_clamped_to_max_step() {
        let solver = DlsSolver {
            max_step_rad: 0.05,
            ..DlsSolver::default()
        };
        let mut q = [0.3, 0.3, 0.3];
        let s = solver
            .step(&[1.0, 1.0, 1.0], &mut q, DVec2::new(-2.0, -1.0))
            .unwrap();
        assert!((s.step_norm_rad - 0.05).abs() < 1e-15);
        let moved = ((q[0] - 0.3).powi(2) + (q[1] - 0.3).powi(2) + (q[2] - 0.3).powi(2)).sqrt();
        assert!((moved - 0.05).abs() < 1e-12);
    }

    /// Property: targets made by FK of random configurations (n = 2..8, random
    /// lengths, random start pose) converge below the 1e-6 m tolerance.
    #[test]
    fn reachable_targets_converge() {
        let solver = DlsSolver::default();
        let mut rng = Lcg64::new(1986);
        let mut worst_iterations = 0;
        for _ in 0..4000 {
            let n = rng.int(2, MAX_JOINTS as i64) as usize;
            let lengths: Vec<f64> = (0..n).map(|_| rng.range(0.3, 1.5)).collect();
            let goal: Vec<f64> = (0..n).map(|_| rng.range(-PI, PI)).collect();
            let target = tip(&lengths, &goal);
            let mut q: Vec<f64> = (0..n).map(|_| rng.range(-PI, PI)).collect();
            let out = solver.solve(&lengths, &mut q, target).unwrap();
            let reached = (tip(&lengths, &q) - target).length();
            assert!(
                out.converged && out.error_m < 1e-6,
                "n={n} lengths={lengths:?} target={target} {out:?}"
            );
            assert!((reached - out.error_m).abs() < 1e-12);
            worst_iterations = worst_iterations.max(out.iterations);
        }
        assert!(worst_iterations < solver.max_iterations);
    }

    /// The benchmark scenario in miniature: unit links, start 0.3 rad everywhere.
    #[test]
    fn benchmark_style_targets_converge_from_the_fixed_start() {
        let solver = DlsSolver::default();
        let mut rng = Lcg64::new(42);
        for n in [3usize, 7] {
            let lengths = vec![1.0; n];
            for _ in 0..500 {
                let goal: Vec<f64> = (0..n).map(|_| rng.range(-PI, PI)).collect();
                let target = tip(&lengths, &goal);
                let mut q = vec![0.3; n];
                let out = solver.solve(&lengths, &mut q, target).unwrap();
                assert!(out.converged, "n={n} target={target} {out:?}");
                assert!(out.iterations <= 30, "{out:?}");
            }
        }
    }

    #[test]
    fn target_already_reached_takes_no_step() {
        let lengths = [1.0, 0.7, 0.4];
        let mut q = [0.2, -0.5, 1.1];
        let target = tip(&lengths, &q);
        let before = q;
        let out = DlsSolver::default()
            .solve(&lengths, &mut q, target)
            .unwrap();
        assert_eq!(out.iterations, 0);
        assert!(out.converged);
        assert_eq!(q, before);
        // max_iterations = 0 only evaluates the error.
        let solver = DlsSolver {
            max_iterations: 0,
            ..DlsSolver::default()
        };
        let out = solver
            .solve(&lengths, &mut q, DVec2::new(0.5, 0.5))
            .unwrap();
        assert_eq!(out.iterations, 0);
        assert!(!out.converged && out.error_m > 0.0);
        assert_eq!(q, before);
    }

    /// An unreachable target outside the reach: the arm ends (nearly) straight
    /// towards it and the error is |p| − ΣL, up to the tolerance.
    #[test]
    fn unreachable_target_settles_at_the_closest_boundary_pose() {
        let solver = DlsSolver::default();
        let mut rng = Lcg64::new(8);
        for _ in 0..300 {
            let n = rng.int(2, MAX_JOINTS as i64) as usize;
            let lengths: Vec<f64> = (0..n).map(|_| rng.range(0.3, 1.5)).collect();
            let reach: f64 = lengths.iter().sum();
            let heading = rng.range(-PI, PI);
            let distance = reach * rng.range(1.01, 3.0);
            let target = DVec2::new(heading.cos(), heading.sin()) * distance;
            let mut q: Vec<f64> = (0..n).map(|_| rng.range(-PI, PI)).collect();
            let out = solver.solve(&lengths, &mut q, target).unwrap();
            assert!(
                !out.converged && out.iterations < solver.max_iterations,
                "{out:?}"
            );
            assert!(q.iter().all(|a| a.is_finite()));
            let gap = distance - reach;
            assert!(
                out.error_m >= gap - 1e-12 && out.error_m <= gap + solver.tolerance_m,
                "n={n} error {} expected {gap}",
                out.error_m
            );
            // Straight (every relative angle after the first ≈ 0) and aimed at the target.
            for a in &q[1..] {
                assert!(wrap_pi(*a).abs() < 1e-2, "{q:?}");
            }
            let p = tip(&lengths, &q);
            assert!((p.normalize() - target.normalize()).length() < 1e-6);
            assert!((p.length() - reach).abs() <= solver.tolerance_m);
        }
    }

    /// Settling is monotone: with the uphill rule every `step` lowers the error,
    /// and repeated steps straighten the arm towards an out-of-reach target.
    #[test]
    fn repeated_steps_settle_on_an_unreachable_target() {
        let lengths = [0.6; 4];
        let target = DVec2::new(0.0, 2.6); // reach 2.4 m
        let solver = DlsSolver {
            damping: 0.1,
            ..DlsSolver::default()
        };
        let mut q = [0.3; 4];
        let mut last = f64::INFINITY;
        for _ in 0..500 {
            let s = solver.step(&lengths, &mut q, target).unwrap();
            assert!(s.error_after_m <= s.error_before_m && s.error_after_m <= last);
            assert!(s.step_norm_rad <= s.error_before_m / (2.0 * s.lambda) * (1.0 + 1e-12));
            last = s.error_after_m;
        }
        assert!((tip(&lengths, &q) - DVec2::new(0.0, 2.4)).length() < 1e-3);
        assert!((last - 0.2).abs() < 1e-6);
    }

    /// A target inside the inner hole: the arm folds to the inner circle.
    #[test]
    fn target_in_the_inner_hole_settles_on_the_inner_circle() {
        let lengths = [3.0, 1.0, 0.5];
        let annulus = Annulus::of_chain(&lengths); // r = 1.5 m
        for target in [
            DVec2::new(0.5, 0.2),
            DVec2::new(-0.3, -1.0),
            DVec2::new(0.0, 0.1),
        ] {
            let mut q = [0.3, 0.3, 0.3];
            let out = DlsSolver::default()
                .solve(&lengths, &mut q, target)
                .unwrap();
            assert!(!out.converged);
            let expected = (annulus.nearest(target) - target).length();
            assert!(
                (out.error_m - expected).abs() < 1e-6,
                "{target}: {} vs {expected}",
                out.error_m
            );
            assert!(q.iter().all(|a| a.is_finite()));
        }
    }

    #[test]
    fn absurdly_far_targets_stay_finite() {
        // Its distance overflows f64: rejected as input.
        let mut q = [0.3, 0.3, 0.3];
        let far = DVec2::new(f64::MAX, f64::MAX);
        let solver = DlsSolver::default();
        assert_eq!(
            solver.solve(&[1.0; 3], &mut q, far),
            Err(DlsError::InvalidInput)
        );
        assert_eq!(
            solver.step(&[1.0; 3], &mut q, far),
            Err(DlsError::InvalidInput)
        );
        assert_eq!(q, [0.3, 0.3, 0.3]);
        for target in [DVec2::new(1e200, -1e200), DVec2::new(-f64::MAX, 0.0)] {
            let mut q = [0.3, 0.3, 0.3];
            let out = DlsSolver::default()
                .solve(&[1.0, 1.0, 1.0], &mut q, target)
                .unwrap();
            assert!(out.error_m.is_finite() && out.error_m > 1e100);
            assert!(q.iter().all(|a| a.is_finite()));
            let mut q = [0.3, 0.3, 0.3];
            let s = DlsSolver::default()
                .step(&[1.0, 1.0, 1.0], &mut q, target)
                .unwrap();
            assert!(s.error_after_m.is_finite() && s.step_norm_rad.is_finite());
        }
    }

    /// Without the uphill rejection plain DLS may oscillate around an
    /// unreachable target, but it never produces a NaN or beats the annulus.
    #[test]
    fn plain_dls_on_unreachable_target_stays_finite() {
        let solver = DlsSolver {
            reject_uphill_steps: false,
            ..DlsSolver::default()
        };
        let mut q = [0.3, 0.3, 0.3];
        let out = solver
            .solve(&[1.0, 1.0, 1.0], &mut q, DVec2::new(6.0, 0.0))
            .unwrap();
        assert!(!out.converged && out.error_m >= 3.0 - 1e-12);
        assert!(out.error_m.is_finite() && q.iter().all(|a| a.is_finite()));
    }

    /// Property (Buss 2004, §5): each singular direction is scaled by
    /// σ/(σ² + λ²) ≤ 1/(2λ), so |Δθ| ≤ |e|/(2λ) — even at and next to the
    /// straight-arm singularity, where the undamped step explodes.
    #[test]
    fn step_norm_is_bounded_by_error_over_two_lambda_near_singularity() {
        let mut rng = Lcg64::new(123);
        let lengths = [1.0, 0.8, 0.6];
        let mut worst_undamped_ratio: f64 = 0.0;
        for _ in 0..3000 {
            let heading = rng.range(-PI, PI);
            let bend = [0.0, 1e-9, 1e-6, 1e-3][rng.int(0, 3) as usize];
            let q0 = [
                heading,
                bend * rng.range(-1.0, 1.0),
                bend * rng.range(-1.0, 1.0),
            ];
            let tip0 = tip(&lengths, &q0);
            let along = DVec2::new(heading.cos(), heading.sin());
            // Slightly beyond the reach along the arm, sideways, or anything in between.
            let dir = along * rng.range(-1.0, 1.0) + along.perp() * rng.range(-1.0, 1.0);
            let target = tip0 + dir * rng.range(1e-4, 0.5);
            let e = (target - tip0).length();
            for lambda in [0.01, 0.05, 0.2] {
                let mut q = q0;
                let s = unclamped(lambda).step(&lengths, &mut q, target).unwrap();
                assert!(s.step_norm_rad.is_finite() && q.iter().all(|a| a.is_finite()));
                assert!(
                    s.step_norm_rad <= e / (2.0 * lambda) * (1.0 + 1e-9),
                    "λ={lambda} |Δθ|={} bound={}",
                    s.step_norm_rad,
                    e / (2.0 * lambda)
                );
            }
            let mut q = q0;
            let s = unclamped(0.0).step(&lengths, &mut q, target).unwrap();
            assert!(s.step_norm_rad.is_finite());
            worst_undamped_ratio = worst_undamped_ratio.max(s.step_norm_rad / (e / 0.1));
        }
        // The undamped (pseudo-inverse) step exceeds the λ = 0.05 bound by orders of magnitude.
        assert!(worst_undamped_ratio > 1e3, "{worst_undamped_ratio}");
    }

    #[test]
    fn straight_arm_target_along_the_arm_gives_no_nan() {
        // Exactly straight along +x, target beyond the reach on the same line:
        // Jᵀ e = 0, the step is zero and the solver stops without NaN.
        let lengths = [1.0, 1.0, 1.0];
        for damping in [0.0, 0.05] {
            let solver = DlsSolver {
                damping,
                ..DlsSolver::default()
            };
            let mut q = [0.0, 0.0, 0.0];
            let s = solver.step(&lengths, &mut q, DVec2::new(3.5, 0.0)).unwrap();
            assert_eq!(s.step_norm_rad, 0.0);
            assert_eq!(q, [0.0, 0.0, 0.0]);
            let out = solver
                .solve(&lengths, &mut q, DVec2::new(3.5, 0.0))
                .unwrap();
            assert!(!out.converged && (out.error_m - 0.5).abs() < 1e-12);
            // Slightly short of the reach along the arm: must bend, from a singular start.
            let mut q = [0.0, 0.0, 0.0];
            let out = solver
                .solve(&lengths, &mut q, DVec2::new(2.9, 0.0))
                .unwrap();
            assert!(q.iter().all(|a| a.is_finite()));
            assert!(out.error_m.is_finite());
        }
    }

    #[test]
    fn undamped_solver_converges_on_regular_targets() {
        let solver = DlsSolver {
            damping: 0.0,
            ..DlsSolver::default()
        };
        let lengths = [1.0, 0.8, 0.5];
        let mut rng = Lcg64::new(77);
        for _ in 0..300 {
            let goal = [rng.range(-PI, PI), rng.range(-PI, PI), rng.range(-PI, PI)];
            let target = tip(&lengths, &goal);
            let mut q = [0.3, 0.3, 0.3];
            let out = solver.solve(&lengths, &mut q, target).unwrap();
            assert!(out.converged, "{target} {out:?}");
        }
    }

    #[test]
    fn adaptive_damping_raises_lambda_when_w_below_threshold() {
        let adaptive = AdaptiveDamping {
            w_threshold: 0.2,
            lambda_max: 0.3,
        };
        let solver = DlsSolver {
            damping: 0.01,
            adaptive: Some(adaptive),
            ..DlsSolver::default()
        };
        let lengths = [1.0, 1.0];
        let target = DVec2::new(0.5, 0.5);
        let mut last_lambda = 0.0;
        // w = |sin θ2| falls from 1 to 0: λ rises from the base to √(λ_b² + λ_max²).
        for theta2 in [FRAC_PI_2, 0.5, 0.15, 0.1, 0.05, 0.01, 0.0] {
            let q0 = [0.2, theta2];
            let w = manipulability(&jacobian(&lengths, &q0)).w;
            let mut q = q0;
            let s = solver.step(&lengths, &mut q, target).unwrap();
            let expected = adaptive.lambda_squared(w, 0.01).sqrt();
            assert!((s.lambda - expected).abs() < 1e-12);
            if w >= 0.2 {
                assert!((s.lambda - 0.01).abs() < 1e-15, "θ2={theta2}");
            } else {
                assert!(s.lambda > 0.01 && s.lambda >= last_lambda, "θ2={theta2}");
            }
            last_lambda = s.lambda;
        }
        assert!((last_lambda - (0.01f64.powi(2) + 0.09).sqrt()).abs() < 1e-12);
        // Without the adaptive part, λ stays at the base.
        let mut q = [0.2, 0.0];
        let s = DlsSolver {
            damping: 0.01,
            ..DlsSolver::default()
        }
        .step(&lengths, &mut q, target)
        .unwrap();
        assert!((s.lambda - 0.01).abs() < 1e-15);
        // Formula: continuous at w₀, λ_max² at w = 0, base above w₀.
        assert!((adaptive.lambda_squared(0.2 - 1e-12, 0.01) - 1e-4).abs() < 1e-12);
        assert!((adaptive.lambda_squared(0.1, 0.0) - 0.09 * 0.25).abs() < 1e-15);
        assert_eq!(adaptive.lambda_squared(5.0, 0.01), 1e-4);
        // And the adaptive solver still converges on reachable targets.
        let mut rng = Lcg64::new(4);
        for _ in 0..500 {
            let lengths = [1.0, 0.8, 0.5, 0.3];
            let goal: Vec<f64> = (0..4).map(|_| rng.range(-PI, PI)).collect();
            let target = tip(&lengths, &goal);
            let mut q = [0.3; 4];
            assert!(solver.solve(&lengths, &mut q, target).unwrap().converged);
        }
    }

    #[test]
    fn invalid_input_is_an_error_and_leaves_angles_unchanged() {
        let ok = DlsSolver::default();
        let t = DVec2::new(1.0, 0.5);
        // (solver, lengths, angles, target, expected error)
        type Case = (DlsSolver, Vec<f64>, Vec<f64>, DVec2, DlsError);
        let cases: Vec<Case> = vec![
            (ok, vec![], vec![], t, DlsError::InvalidInput),
            (ok, vec![1.0, 1.0], vec![0.3], t, DlsError::InvalidInput),
            (ok, vec![1.0], vec![0.3, 0.3], t, DlsError::InvalidInput),
            (
                ok,
                vec![1.0, f64::NAN],
                vec![0.3, 0.3],
                t,
                DlsError::InvalidInput,
            ),
            (
                ok,
                vec![1.0, 0.0],
                vec![0.3, 0.3],
                t,
                DlsError::InvalidInput,
            ),
            (
                ok,
                vec![1.0, -1.0],
                vec![0.3, 0.3],
                t,
                DlsError::InvalidInput,
            ),
            (
                ok,
                vec![1.0, 1e60],
                vec![0.3, 0.3],
                t,
                DlsError::InvalidInput,
            ),
            (
                ok,
                vec![1.0, 1.0],
                vec![0.3, f64::NAN],
                t,
                DlsError::InvalidInput,
            ),
            (
                ok,
                vec![1.0, 1.0],
                vec![f64::INFINITY, 0.3],
                t,
                DlsError::InvalidInput,
            ),
            (
                ok,
                vec![1.0, 1.0],
                vec![0.3, 0.3],
                DVec2::new(f64::NAN, 0.0),
                DlsError::InvalidInput,
            ),
            (
                ok,
                vec![1.0, 1.0],
                vec![0.3, 0.3],
                DVec2::new(0.0, f64::INFINITY),
                DlsError::InvalidInput,
            ),
            (
                ok,
                vec![1.0; 9],
                vec![0.3; 9],
                t,
                DlsError::TooManyJoints { joints: 9, max: 8 },
            ),
            (
                DlsSolver {
                    damping: -0.1,
                    ..ok
                },
                vec![1.0, 1.0],
                vec![0.3, 0.3],
                t,
                DlsError::InvalidSettings { field: "damping" },
            ),
            (
                DlsSolver {
                    damping: f64::NAN,
                    ..ok
                },
                vec![1.0, 1.0],
                vec![0.3, 0.3],
                t,
                DlsError::InvalidSettings { field: "damping" },
            ),
            (
                DlsSolver {
                    tolerance_m: f64::NAN,
                    ..ok
                },
                vec![1.0, 1.0],
                vec![0.3, 0.3],
                t,
                DlsError::InvalidSettings {
                    field: "tolerance_m",
                },
            ),
            (
                DlsSolver {
                    max_step_rad: 0.0,
                    ..ok
                },
                vec![1.0, 1.0],
                vec![0.3, 0.3],
                t,
                DlsError::InvalidSettings {
                    field: "max_step_rad",
                },
            ),
            (
                DlsSolver {
                    adaptive: Some(AdaptiveDamping {
                        w_threshold: f64::NAN,
                        lambda_max: 0.1,
                    }),
                    ..ok
                },
                vec![1.0, 1.0],
                vec![0.3, 0.3],
                t,
                DlsError::InvalidSettings {
                    field: "adaptive.w_threshold",
                },
            ),
            (
                DlsSolver {
                    adaptive: Some(AdaptiveDamping {
                        w_threshold: 0.1,
                        lambda_max: -1.0,
                    }),
                    ..ok
                },
                vec![1.0, 1.0],
                vec![0.3, 0.3],
                t,
                DlsError::InvalidSettings {
                    field: "adaptive.lambda_max",
                },
            ),
        ];
        for (solver, lengths, angles, target, expected) in cases {
            let mut q = angles.clone();
            let err = solver.solve(&lengths, &mut q, target).unwrap_err();
            assert_eq!(err, expected, "{lengths:?} {angles:?} {target}");
            assert!(!err.to_string().is_empty());
            // Bit-for-bit unchanged (NaN included).
            assert!(q
                .iter()
                .zip(&angles)
                .all(|(a, b)| a.to_bits() == b.to_bits()));
            let err = solver.step(&lengths, &mut q, target).unwrap_err();
            assert_eq!(err, expected);
            assert!(q
                .iter()
                .zip(&angles)
                .all(|(a, b)| a.to_bits() == b.to_bits()));
        }
    }

    #[test]
    fn same_input_same_result() {
        let lengths = [1.0, 0.9, 0.8, 0.7, 0.6];
        let target = DVec2::new(-1.3, 2.2);
        let mut a = [0.3; 5];
        let mut b = [0.3; 5];
        let ra = DlsSolver::default()
            .solve(&lengths, &mut a, target)
            .unwrap();
        let rb = DlsSolver::default()
            .solve(&lengths, &mut b, target)
            .unwrap();
        assert_eq!(ra, rb);
        assert_eq!(a, b);
    }
}
