//! EKF localisation of a unicycle against known landmarks.
//!
//! **Predict** (Thrun, Burgard & Fox, *Probabilistic Robotics*, 2005,
//! Table 3.3 lines 2–3 and Table 7.2 lines 3–7):
//!
//! ```text
//! μ̄ = g(μ, u)        P̄ = F P Fᵀ + Q,     F = ∂g/∂x (μ, u),  Q = V M Vᵀ
//! ```
//!
//! `g` here is the straight step of [`motion_model`] with a fixed
//! `M = diag(σv², σω²)`; Table 7.2 uses the exact-arc velocity model with
//! `M` scaled by the speeds (α₁ … α₄), so its `G` and `V` differ. A process
//! noise given directly in state space goes to [`ekf_predict_with_q`].
//!
//! **Update** with one range-bearing observation `z` of landmark `m`
//! (Table 3.3 lines 4–6, Table 7.2 lines 10–18):
//!
//! ```text
//! ν = z − h(μ̄)  (bearing wrapped to [−π, π))      S = H P̄ Hᵀ + R
//! K = P̄ Hᵀ S⁻¹       μ = μ̄ + K ν
//! P = (I − K H) P̄ (I − K H)ᵀ + K R Kᵀ
//! ```
//!
//! The covariance uses the Joseph form (Bucy & Joseph, *Filtering for
//! Stochastic Processes with Applications to Guidance*, 1968; Bar-Shalom, Li &
//! Kirubarajan, *Estimation with Applications to Tracking and Navigation*,
//! 2001, §5.2.3, eq. 5.2.3-18): it equals `(I − K H) P̄` for the optimal gain
//! but, as a sum of two positive semi-definite terms, stays symmetric
//! positive semi-definite under rounding. The result is symmetrised,
//! `P ← (P + Pᵀ)/2`. Several landmarks in one step are folded in one after
//! another ([`ekf_update_sequential`]), re-linearising about the updated mean
//! each time — valid because the measurement noises are independent.
//!
//! Everything is 3×3 and 2×2 glam arithmetic: no allocation, no matrix
//! library.

use glam::{DMat2, DMat3, DVec2, DVec3};

use super::models::{
    check_dt, check_motion, jacob_f, jacob_h, motion_model, observation_model, process_noise,
    sample_motion, Control, MotionNoise, Observation, RangeBearingSensor, SensorNoise,
};
use super::{check_cov3, wrap_angle, EstimationError};
use crate::rng::Lcg64;

/// A Gaussian belief over the pose: mean `(x, y, θ)` and covariance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Belief {
    pub mean: DVec3,
    pub cov: DMat3,
}

impl Belief {
    /// Mean and covariance finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.mean.is_finite() && self.cov.is_finite()
    }
}

/// The result of one update.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Update {
    pub belief: Belief,
    /// Innovation `ν = z − h(μ̄)`, bearing in `[−π, π)`.
    pub innovation: DVec2,
    /// The predicted observation `ẑ = h(μ̄)`: range (m), bearing (rad).
    pub predicted: DVec2,
    /// Normalised innovation squared `νᵀ S⁻¹ ν` (χ² with 2 degrees of
    /// freedom for a consistent filter).
    pub nis: f64,
}

/// Symmetric part `(A + Aᵀ)/2`.
#[must_use]
pub fn symmetrize(a: DMat3) -> DMat3 {
    (a + a.transpose()) * 0.5
}

/// EKF prediction with the velocity motion model over `dt_s`.
///
/// Refuses a NaN, infinite or negative `dt` and non-finite input; `dt = 0`
/// returns the belief unchanged.
///
/// # Example
/// ```
/// use labcore::estimation::ekf::ekf_predict;
/// use labcore::estimation::models::{Control, MotionNoise};
/// use glam::{DMat3, DVec3};
/// let b = ekf_predict(DVec3::ZERO, DMat3::ZERO, Control::new(1.0, 0.0), 0.5, &MotionNoise::default()).unwrap();
/// assert_eq!(b.mean, DVec3::new(0.5, 0.0, 0.0));
/// assert!(b.cov.x_axis.x > 0.0); // σ_v² dt² along the heading
/// assert!(ekf_predict(DVec3::ZERO, DMat3::ZERO, Control::new(1.0, 0.0), -0.1, &MotionNoise::default()).is_err());
/// ```
pub fn ekf_predict(
    mean: DVec3,
    cov: DMat3,
    u: Control,
    dt_s: f64,
    noise: &MotionNoise,
) -> Result<Belief, EstimationError> {
    check_dt(dt_s)?;
    check_motion(u, noise)?;
    if !(mean.is_finite() && cov.is_finite()) {
        return Err(EstimationError::NonFinite);
    }
    predict_with(mean, cov, u, dt_s, process_noise(mean, dt_s, noise))
}

/// EKF prediction with a process noise `q` given directly in state space
/// (the form filterpy's `predict(Q=…)` and most texts use):
/// `μ̄ = g(μ, u)`, `P̄ = F P Fᵀ + Q`, with `F = ∂g/∂x` at `μ`. [`ekf_predict`]
/// is this with `Q = V M Vᵀ` ([`process_noise`]).
///
/// Refuses a NaN, infinite or negative `dt`, non-finite input, and a `q`
/// that is not a covariance (symmetric positive semi-definite,
/// [`EstimationError::NotCovariance`]).
///
/// # Example
/// ```
/// use labcore::estimation::ekf::ekf_predict_with_q;
/// use labcore::estimation::models::Control;
/// use glam::{DMat3, DVec3};
/// let q = DMat3::from_diagonal(DVec3::new(1e-4, 1e-4, 1e-5));
/// let b = ekf_predict_with_q(DVec3::ZERO, DMat3::ZERO, Control::new(1.0, 0.0), 0.5, q).unwrap();
/// assert_eq!(b.mean, DVec3::new(0.5, 0.0, 0.0));
/// assert_eq!(b.cov, q); // nothing to carry forward: P̄ = Q
/// let bad = DMat3::from_diagonal(DVec3::new(1e-4, -1e-4, 1e-5));
/// assert!(ekf_predict_with_q(DVec3::ZERO, DMat3::ZERO, Control::new(1.0, 0.0), 0.5, bad).is_err());
/// ```
pub fn ekf_predict_with_q(
    mean: DVec3,
    cov: DMat3,
    u: Control,
    dt_s: f64,
    q: DMat3,
) -> Result<Belief, EstimationError> {
    check_dt(dt_s)?;
    if !(u.is_finite() && mean.is_finite() && cov.is_finite()) {
        return Err(EstimationError::NonFinite);
    }
    check_cov3(q)?;
    predict_with(mean, cov, u, dt_s, q)
}

/// `μ̄ = g(μ, u)`, `P̄ = sym(F P Fᵀ + Q)`, checked inputs.
fn predict_with(
    mean: DVec3,
    cov: DMat3,
    u: Control,
    dt_s: f64,
    q: DMat3,
) -> Result<Belief, EstimationError> {
    let f = jacob_f(mean, u, dt_s);
    let belief = Belief {
        mean: motion_model(mean, u, dt_s),
        cov: symmetrize(f * cov * f.transpose() + q),
    };
    if belief.is_finite() {
        Ok(belief)
    } else {
        Err(EstimationError::NonFinite)
    }
}

/// EKF update with one observation `z` of a landmark at `landmark` (metres),
/// measurement noise covariance `r` (use [`SensorNoise::r`]). Joseph-form
/// covariance; the heading of the new mean is wrapped to `[−π, π)`.
///
/// # Example
/// ```
/// use labcore::estimation::ekf::ekf_update;
/// use labcore::estimation::models::{Observation, SensorNoise};
/// use glam::{DMat3, DVec2, DVec3};
/// let p = DMat3::from_diagonal(DVec3::new(0.1, 0.1, 0.01));
/// let z = Observation { id: 0, range_m: 2.1, bearing_rad: 0.0 };
/// let up = ekf_update(DVec3::ZERO, p, &z, DVec2::new(2.0, 0.0), SensorNoise::default().r()).unwrap();
/// // Measured farther than predicted: the robot must be further back.
/// assert!(up.belief.mean.x < 0.0);
/// assert!(up.belief.cov.x_axis.x < 0.1);
/// ```
pub fn ekf_update(
    mean: DVec3,
    cov: DMat3,
    z: &Observation,
    landmark: DVec2,
    r: DMat2,
) -> Result<Update, EstimationError> {
    let finite = mean.is_finite() && cov.is_finite() && z.z().is_finite();
    if !(finite && landmark.is_finite() && r.is_finite()) {
        return Err(EstimationError::NonFinite);
    }
    let (h0, h1) = jacob_h(mean, landmark).ok_or(EstimationError::LandmarkTooClose {
        range_m: (landmark - mean.truncate()).length(),
    })?;
    // P Hᵀ as two columns (P symmetric).
    let w0 = cov * h0;
    let w1 = cov * h1;
    let s00 = h0.dot(w0) + r.x_axis.x;
    let s11 = h1.dot(w1) + r.y_axis.y;
    let s01 = 0.5 * (h0.dot(w1) + h1.dot(w0) + r.y_axis.x + r.x_axis.y);
    let det = s00 * s11 - s01 * s01;
    if !(s00 > 0.0 && det > 0.0 && det.is_finite()) {
        return Err(EstimationError::SingularInnovation);
    }
    let (i00, i01, i11) = (s11 / det, -s01 / det, s00 / det);
    // K = P Hᵀ S⁻¹: columns k0, k1.
    let k0 = w0 * i00 + w1 * i01;
    let k1 = w0 * i01 + w1 * i11;
    let zhat = observation_model(mean, landmark);
    let nu = DVec2::new(z.range_m - zhat.x, wrap_angle(z.bearing_rad - zhat.y));
    let mut new_mean = mean + k0 * nu.x + k1 * nu.y;
    new_mean.z = wrap_angle(new_mean.z);
    // Joseph form: (I − K H) P (I − K H)ᵀ + K R Kᵀ.
    let kh = outer(k0, h0) + outer(k1, h1);
    let a = DMat3::IDENTITY - kh;
    let krk = outer(k0, k0) * r.x_axis.x
        + outer(k1, k1) * r.y_axis.y
        + (outer(k0, k1) * r.y_axis.x + outer(k1, k0) * r.x_axis.y);
    let new_cov = symmetrize(a * cov * a.transpose() + krk);
    let nis = nu.x * (i00 * nu.x + i01 * nu.y) + nu.y * (i01 * nu.x + i11 * nu.y);
    let belief = Belief {
        mean: new_mean,
        cov: new_cov,
    };
    if !belief.is_finite() {
        return Err(EstimationError::NonFinite);
    }
    Ok(Update {
        belief,
        innovation: nu,
        predicted: zhat,
        nis,
    })
}

/// `a bᵀ`.
fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// Result of [`ekf_update_sequential`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SequentialUpdate {
    pub belief: Belief,
    /// Observations folded in.
    pub applied: usize,
    /// Observations refused (unknown id, landmark at the robot, …); each
    /// left the belief as it was.
    pub rejected: usize,
    /// Sum of the applied updates' NIS.
    pub nis_sum: f64,
    /// The last applied observation `z` (range m, bearing rad) and its
    /// update, if any was applied.
    pub last: Option<(DVec2, Update)>,
}

/// Folds in every observation in order, each about the mean left by the
/// previous one; `landmarks[id]` is landmark `id`. A refused observation is
/// counted and skipped.
pub fn ekf_update_sequential(
    mean: DVec3,
    cov: DMat3,
    observations: &[Observation],
    landmarks: &[DVec2],
    r: DMat2,
) -> SequentialUpdate {
    let mut out = SequentialUpdate {
        belief: Belief { mean, cov },
        applied: 0,
        rejected: 0,
        nis_sum: 0.0,
        last: None,
    };
    for z in observations {
        let Some(&m) = landmarks.get(z.id) else {
            out.rejected += 1;
            continue;
        };
        match ekf_update(out.belief.mean, out.belief.cov, z, m, r) {
            Ok(up) => {
                out.belief = up.belief;
                out.applied += 1;
                out.nis_sum += up.nis;
                out.last = Some((z.z(), up));
            }
            Err(_) => out.rejected += 1,
        }
    }
    out
}

/// A seeded simulation of EKF localisation: a true robot driven by noisy
/// controls, a range-bearing sensor over known landmarks, and the filter.
///
/// The truth uses `true_motion_noise` and `sensor.noise`; the filter is told
/// `filter_motion_noise` and `filter_sensor_noise` (equal by default; make
/// them differ to show an over- or under-confident filter).
#[derive(Clone, Debug, PartialEq)]
pub struct EkfLocalisation {
    /// True pose.
    pub truth: DVec3,
    /// The filter's belief.
    pub belief: Belief,
    /// Known map: landmark `i` has id `i`.
    pub landmarks: Vec<DVec2>,
    pub true_motion_noise: MotionNoise,
    pub filter_motion_noise: MotionNoise,
    pub sensor: RangeBearingSensor,
    pub filter_sensor_noise: SensorNoise,
    pub rng: Lcg64,
    /// Simulated time, seconds.
    pub time_s: f64,
    /// Observations of the last step.
    pub last_observations: Vec<Observation>,
    /// NIS sum and counts of the last step's updates.
    pub last_update: Option<SequentialUpdate>,
}

impl EkfLocalisation {
    /// Truth and belief start at `start` with covariance `initial_cov`;
    /// default noises and sensor.
    #[must_use]
    pub fn new(start: DVec3, initial_cov: DMat3, landmarks: Vec<DVec2>, seed: u64) -> Self {
        let sensor = RangeBearingSensor::default();
        Self {
            truth: start,
            belief: Belief {
                mean: start,
                cov: initial_cov,
            },
            landmarks,
            true_motion_noise: MotionNoise::default(),
            filter_motion_noise: MotionNoise::default(),
            sensor,
            filter_sensor_noise: sensor.noise,
            rng: Lcg64::new(seed),
            time_s: 0.0,
            last_observations: Vec::new(),
            last_update: None,
        }
    }

    /// One step: the truth moves under `u` with control noise, the filter
    /// predicts with `u`, the sensor observes from the true pose, the filter
    /// folds the observations in. On error nothing changes.
    pub fn step(&mut self, u: Control, dt_s: f64) -> Result<(), EstimationError> {
        let predicted = ekf_predict(
            self.belief.mean,
            self.belief.cov,
            u,
            dt_s,
            &self.filter_motion_noise,
        )?;
        let (truth, _) = sample_motion(self.truth, u, dt_s, &self.true_motion_noise, &mut self.rng);
        self.truth = truth;
        let mut obs = std::mem::take(&mut self.last_observations);
        self.sensor
            .observe_into(truth, &self.landmarks, &mut self.rng, &mut obs);
        let up = ekf_update_sequential(
            predicted.mean,
            predicted.cov,
            &obs,
            &self.landmarks,
            self.filter_sensor_noise.r(),
        );
        self.belief = up.belief;
        self.last_observations = obs;
        self.last_update = Some(up);
        self.time_s += dt_s;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimation::consistency::{nees, nees_bounds, position_error_m};
    use std::f64::consts::PI;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    /// One predict by hand: μ = (1, 2, 0.5), u = (1 m/s, 0.2 rad/s), dt = 0.1.
    #[test]
    fn predict_matches_a_hand_computed_step() {
        let (s, c) = (0.5f64.sin(), 0.5f64.cos());
        let p0 = DMat3::from_diagonal(DVec3::new(0.04, 0.09, 0.01));
        let noise = MotionNoise {
            sigma_v_mps: 0.2,
            sigma_omega_radps: 0.1,
        };
        let b = ekf_predict(
            DVec3::new(1.0, 2.0, 0.5),
            p0,
            Control::new(1.0, 0.2),
            0.1,
            &noise,
        )
        .unwrap();
        assert!(close(b.mean.x, 1.0 + 0.1 * c, 1e-15));
        assert!(close(b.mean.y, 2.0 + 0.1 * s, 1e-15));
        assert!(close(b.mean.z, 0.52, 1e-15));
        // F = [1 0 a; 0 1 b; 0 0 1], a = −0.1 s, b = 0.1 c; P = diag(p1, p2, p3).
        let (a, bb) = (-0.1 * s, 0.1 * c);
        let (qv, qw) = (0.04 * 0.01, 0.01 * 0.01);
        let expected = [
            [
                0.04 + a * a * 0.01 + qv * c * c,
                a * bb * 0.01 + qv * c * s,
                a * 0.01,
            ],
            [
                a * bb * 0.01 + qv * c * s,
                0.09 + bb * bb * 0.01 + qv * s * s,
                bb * 0.01,
            ],
            [a * 0.01, bb * 0.01, 0.01 + qw],
        ];
        for (i, row) in expected.iter().enumerate() {
            for (j, e) in row.iter().enumerate() {
                assert!(close(b.cov.col(j)[i], *e, 1e-15), "P[{i}][{j}]");
            }
        }
        // dt = 0 changes nothing; bad dt is refused.
        let same = ekf_predict(DVec3::ONE, p0, Control::new(3.0, 1.0), 0.0, &noise).unwrap();
        assert_eq!((same.mean, same.cov), (DVec3::ONE, p0));
        for dt in [f64::NAN, -1e-3, f64::INFINITY] {
            assert!(matches!(
                ekf_predict(DVec3::ONE, p0, Control::new(1.0, 0.0), dt, &noise),
                Err(EstimationError::InvalidDt { .. })
            ));
        }
        let bad_noise = MotionNoise {
            sigma_v_mps: -1.0,
            ..noise
        };
        assert_eq!(
            ekf_predict(DVec3::ONE, p0, Control::new(1.0, 0.0), 0.1, &bad_noise),
            Err(EstimationError::NonFinite)
        );
    }

    /// One update by hand: robot at the origin facing +x, P = diag(0.1, 0.1,
    /// 0.01), landmark (2, 0), z = (2.1, 0.05), R = diag(0.01, 0.001).
    /// H = [−1 0 0; 0 −½ −1], S = diag(0.11, 0.036).
    #[test]
    fn update_matches_a_hand_computed_step() {
        let p = DMat3::from_diagonal(DVec3::new(0.1, 0.1, 0.01));
        let r = DMat2::from_diagonal(DVec2::new(0.01, 0.001));
        let z = Observation {
            id: 0,
            range_m: 2.1,
            bearing_rad: 0.05,
        };
        let up = ekf_update(DVec3::ZERO, p, &z, DVec2::new(2.0, 0.0), r).unwrap();
        let m = up.belief.mean;
        assert!(close(m.x, -0.1 / 0.11 * 0.1, 1e-15));
        assert!(close(m.y, -0.05 / 0.036 * 0.05, 1e-15));
        assert!(close(m.z, -0.01 / 0.036 * 0.05, 1e-15));
        let c = up.belief.cov;
        assert!(close(c.col(0)[0], 0.1 - 0.01 / 0.11, 1e-15));
        assert!(close(c.col(1)[1], 0.1 - 0.0025 / 0.036, 1e-15));
        assert!(close(c.col(2)[2], 0.01 - 0.0001 / 0.036, 1e-15));
        assert!(close(c.col(2)[1], -0.0005 / 0.036, 1e-15));
        assert!(close(c.col(1)[0], 0.0, 1e-15) && close(c.col(2)[0], 0.0, 1e-15));
        assert_eq!(c, c.transpose());
        assert!(close(up.nis, 0.01 / 0.11 + 0.0025 / 0.036, 1e-12));
        assert_eq!(up.innovation, DVec2::new(2.1 - 2.0, 0.05));
    }

    #[test]
    fn bearing_innovation_wraps_across_pi() {
        // Landmark straight behind: predicted bearing −π (wrapped), measured
        // just under +π: the innovation is tiny, not ≈ 2π.
        let p = DMat3::from_diagonal(DVec3::splat(0.01));
        let z = Observation {
            id: 0,
            range_m: 1.0,
            bearing_rad: PI - 0.01,
        };
        let up = ekf_update(
            DVec3::ZERO,
            p,
            &z,
            DVec2::new(-1.0, 0.0),
            SensorNoise::default().r(),
        )
        .unwrap();
        assert!(close(up.innovation.y, -0.01, 1e-12), "{}", up.innovation.y);
        assert!(up.belief.mean.z.abs() < 0.01);
    }

    #[test]
    fn refuses_degenerate_updates_and_leaves_state() {
        let p = DMat3::from_diagonal(DVec3::splat(0.01));
        let z = Observation {
            id: 0,
            range_m: 1.0,
            bearing_rad: 0.0,
        };
        let r = SensorNoise::default().r();
        assert!(matches!(
            ekf_update(DVec3::ONE, p, &z, DVec2::ONE, r),
            Err(EstimationError::LandmarkTooClose { .. })
        ));
        assert_eq!(
            ekf_update(DVec3::ZERO, DMat3::ZERO, &z, DVec2::X, DMat2::ZERO),
            Err(EstimationError::SingularInnovation)
        );
        let nan = Observation {
            range_m: f64::NAN,
            ..z
        };
        assert_eq!(
            ekf_update(DVec3::ZERO, p, &nan, DVec2::X, r),
            Err(EstimationError::NonFinite)
        );
        let seq = ekf_update_sequential(
            DVec3::ZERO,
            p,
            &[z, Observation { id: 7, ..z }, Observation { id: 1, ..z }],
            &[DVec2::X, DVec2::ZERO],
            r,
        );
        assert_eq!((seq.applied, seq.rejected), (1, 2));
    }

    /// Starting from a wide prior, every update shrinks trace(P), and on
    /// average over seeded trials the position error falls after the updates.
    #[test]
    fn error_and_covariance_shrink_after_updates() {
        let landmarks = vec![
            DVec2::new(2.0, 1.0),
            DVec2::new(1.0, -2.0),
            DVec2::new(-2.0, 0.5),
        ];
        let sensor = RangeBearingSensor {
            max_range_m: 10.0,
            fov_rad: 2.0 * PI,
            noise: SensorNoise::default(),
        };
        let prior = DMat3::from_diagonal(DVec3::new(0.25, 0.25, 0.05));
        let mut rng = Lcg64::new(31);
        let (mut before, mut after) = (0.0, 0.0);
        for _ in 0..500 {
            let truth = DVec3::ZERO;
            let mean = DVec3::new(
                rng.normal(0.0, 0.5),
                rng.normal(0.0, 0.5),
                rng.normal(0.0, 0.22),
            );
            let obs = sensor.observe(truth, &landmarks, &mut rng);
            let mut b = Belief { mean, cov: prior };
            for z in &obs {
                let up = ekf_update(b.mean, b.cov, z, landmarks[z.id], sensor.noise.r()).unwrap();
                let tr = |m: DMat3| m.x_axis.x + m.y_axis.y + m.z_axis.z;
                assert!(tr(up.belief.cov) < tr(b.cov));
                b = up.belief;
            }
            before += position_error_m(truth, mean);
            after += position_error_m(truth, b.mean);
        }
        assert!(after < 0.5 * before, "before {before}, after {after}");
    }

    /// 100,000 predict + update steps on a loop: P stays exactly symmetric
    /// and positive-definite (all leading minors > 0) and finite.
    #[test]
    fn covariance_stays_symmetric_positive_definite_over_100k_steps() {
        let landmarks = vec![
            DVec2::new(3.0, 0.0),
            DVec2::new(0.0, 3.0),
            DVec2::new(-3.0, 0.0),
            DVec2::new(0.0, -3.0),
        ];
        let mut sim = EkfLocalisation::new(
            DVec3::new(2.0, 0.0, PI / 2.0),
            DMat3::from_diagonal(DVec3::splat(1e-4)),
            landmarks,
            2026,
        );
        for k in 0..100_000 {
            // Stretches of dead reckoning (sensor off) between fixes.
            sim.sensor.max_range_m = if (k / 500) % 2 == 0 { 3.0 } else { 0.0 };
            sim.step(Control::new(1.0, 0.5), 0.05).unwrap();
            let p = sim.belief.cov;
            assert_eq!(p, p.transpose(), "step {k}");
            let m1 = p.x_axis.x;
            let m2 = p.x_axis.x * p.y_axis.y - p.x_axis.y * p.y_axis.x;
            assert!(
                m1 > 0.0 && m2 > 0.0 && p.determinant() > 0.0,
                "step {k}: {p:?}"
            );
        }
        assert!(sim.belief.is_finite());
        assert!(position_error_m(sim.truth, sim.belief.mean) < 1.0);
    }

    /// Filter consistency (Bar-Shalom et al. 2001, §5.4.2): over 50 seeded
    /// Monte-Carlo runs the average NEES at each time step lies inside the
    /// two-sided 95 % χ² bounds [2.36, 3.72] at (about) 95 % of the steps,
    /// and its time average is close to the state dimension 3.
    #[test]
    fn average_nees_stays_inside_chi_square_bounds() {
        const RUNS: usize = 50;
        const STEPS: usize = 200;
        let landmarks = vec![
            DVec2::new(4.0, 2.0),
            DVec2::new(-1.0, 5.0),
            DVec2::new(-4.0, -1.0),
            DVec2::new(2.0, -4.0),
        ];
        let p0 = DMat3::from_diagonal(DVec3::new(0.01, 0.01, 0.0025));
        let mut sum = vec![0.0; STEPS];
        for run in 0..RUNS {
            let start = DVec3::new(2.0, 0.0, PI / 2.0);
            let mut sim = EkfLocalisation::new(start, p0, landmarks.clone(), 1000 + run as u64);
            sim.sensor.fov_rad = 2.0 * PI;
            sim.sensor.max_range_m = 6.0;
            // Start the filter at a draw from its own prior, so the initial
            // error matches P0 (σ 0.1 m, 0.05 rad).
            sim.belief.mean += DVec3::new(
                sim.rng.normal(0.0, 0.1),
                sim.rng.normal(0.0, 0.1),
                sim.rng.normal(0.0, 0.05),
            );
            for s in sum.iter_mut() {
                // Fixes only every fifth step, so the filter spends time in
                // prediction too.
                let k = (sim.time_s / 0.1).round() as usize;
                sim.sensor.max_range_m = if matches!(k % 5, 0) { 6.0 } else { 0.0 };
                sim.step(Control::new(1.0, 0.5), 0.1).unwrap();
                *s += nees(sim.truth, sim.belief.mean, sim.belief.cov).unwrap();
            }
        }
        let (lo, hi) = nees_bounds(3, RUNS, 0.95).unwrap();
        let avg: Vec<f64> = sum.iter().map(|s| s / RUNS as f64).collect();
        let inside = avg.iter().filter(|a| (lo..=hi).contains(*a)).count();
        let mean = avg.iter().sum::<f64>() / STEPS as f64;
        assert!(
            inside as f64 >= 0.9 * STEPS as f64,
            "{inside}/{STEPS} inside [{lo}, {hi}]"
        );
        assert!((mean - 3.0).abs() < 0.3, "time-averaged ANEES {mean}");
    }

    /// Issue 15: a state-space `Q`, against one step computed by hand with
    /// `F = I + a e₀e₂ᵀ + b e₁e₂ᵀ`, `a = −v sin θ Δt`, `b = v cos θ Δt`.
    #[test]
    fn predict_with_a_state_space_q_matches_a_hand_computed_step() {
        let (v, w, dt, th) = (0.8, 0.2, 0.1, 0.3f64);
        let mean = DVec3::new(1.0, 2.0, th);
        let p = DMat3::from_cols(
            DVec3::new(0.04, 0.01, 0.002),
            DVec3::new(0.01, 0.09, -0.003),
            DVec3::new(0.002, -0.003, 0.01),
        );
        let q = DMat3::from_cols(
            DVec3::new(4e-4, 1e-4, 0.0),
            DVec3::new(1e-4, 9e-4, 2e-5),
            DVec3::new(0.0, 2e-5, 1e-4),
        );
        let b = ekf_predict_with_q(mean, p, Control::new(v, w), dt, q).unwrap();
        let (a, bb) = (-v * th.sin() * dt, v * th.cos() * dt);
        let m = |i: usize, j: usize| p.col(j)[i];
        let qq = |i: usize, j: usize| q.col(j)[i];
        let hand = [
            [
                m(0, 0) + 2.0 * a * m(0, 2) + a * a * m(2, 2) + qq(0, 0),
                m(0, 1) + a * m(1, 2) + bb * m(0, 2) + a * bb * m(2, 2) + qq(0, 1),
                m(0, 2) + a * m(2, 2) + qq(0, 2),
            ],
            [
                0.0,
                m(1, 1) + 2.0 * bb * m(1, 2) + bb * bb * m(2, 2) + qq(1, 1),
                m(1, 2) + bb * m(2, 2) + qq(1, 2),
            ],
            [0.0, 0.0, m(2, 2) + qq(2, 2)],
        ];
        for (i, row) in hand.iter().enumerate() {
            for (j, want) in row.iter().enumerate().skip(i) {
                let got = b.cov.col(j)[i];
                assert!((got - want).abs() < 1e-15, "P̄[{i}][{j}] {got} vs {want}");
                assert_eq!(got, b.cov.col(i)[j]);
            }
        }
        let mean_hand = DVec3::new(
            1.0 + v * th.cos() * dt,
            2.0 + v * th.sin() * dt,
            th + w * dt,
        );
        assert!((b.mean - mean_hand).length() < 1e-15);
        // The control-space predict is the same with Q = V M Vᵀ.
        let noise = MotionNoise::default();
        assert_eq!(
            ekf_predict(mean, p, Control::new(v, w), dt, &noise),
            ekf_predict_with_q(
                mean,
                p,
                Control::new(v, w),
                dt,
                process_noise(mean, dt, &noise)
            )
        );
        // A Q that is not a covariance is refused.
        let u = Control::new(v, w);
        let skew = DMat3::from_cols(
            DVec3::new(1e-4, 1e-5, 0.0),
            DVec3::new(0.0, 1e-4, 0.0),
            DVec3::Z * 1e-4,
        );
        let negative = DMat3::from_diagonal(DVec3::new(1e-4, -1e-6, 1e-4));
        let indefinite = DMat3::from_cols(
            DVec3::new(1e-4, 2e-4, 0.0),
            DVec3::new(2e-4, 1e-4, 0.0),
            DVec3::Z * 1e-4,
        );
        for bad in [skew, negative, indefinite] {
            assert_eq!(
                ekf_predict_with_q(mean, p, u, dt, bad),
                Err(EstimationError::NotCovariance),
                "{bad:?}"
            );
        }
        assert_eq!(
            ekf_predict_with_q(mean, p, u, dt, DMat3::from_diagonal(DVec3::splat(f64::NAN))),
            Err(EstimationError::NonFinite)
        );
        assert!(ekf_predict_with_q(mean, p, u, -1.0, q).is_err());
        assert_eq!(
            ekf_predict_with_q(mean, p, u, 0.0, DMat3::ZERO).unwrap(),
            Belief { mean, cov: p }
        );
    }
}
