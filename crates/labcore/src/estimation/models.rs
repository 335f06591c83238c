//! Motion and measurement models of the EKF (lab spec, experiment 11).
//!
//! **Velocity motion model**, control `u = (v, ω)` held over `dt`:
//!
//! ```text
//! g(x, u) = ( x + v cos θ dt,  y + v sin θ dt,  θ + ω dt )
//! F = ∂g/∂x = [ 1 0 −v sin θ dt ; 0 1 v cos θ dt ; 0 0 1 ]
//! V = ∂g/∂u = [ cos θ dt 0 ; sin θ dt 0 ; 0 dt ]
//! Q = V M Vᵀ,   M = diag(σ_v², σ_ω²)
//! ```
//!
//! This is the spec's first-order form of the velocity model (Thrun, Burgard
//! & Fox, *Probabilistic Robotics*, MIT Press 2005, §5.3 and Table 7.2, whose
//! exact-arc version differs by `O(ω dt²)`); noise enters through the
//! controls, mapped to state space by `V` (Table 7.2, lines 4–6). The
//! simulated robot moves by the same `g` with noisy controls
//! ([`sample_motion`], after Table 5.3), so a filter told the true `σ_v, σ_ω`
//! is consistent up to linearisation.
//!
//! **Range-bearing measurement** of a landmark `m = (mx, my)`, with
//! `dx = mx − x`, `dy = my − y`, `q = dx² + dy²` (Thrun et al. §6.6, eq. 6.40
//! and Table 7.2, lines 12–16):
//!
//! ```text
//! h(x) = ( √q,  atan2(dy, dx) − θ )
//! H    = [ −dx/√q  −dy/√q  0 ;  dy/q  −dx/q  −1 ]
//! ```
//!
//! The sensor sees a landmark when `√q ≤ max range` and the bearing lies in
//! the field of view, then adds independent Gaussian noise to range and
//! bearing (`R = diag(σ_r², σ_φ²)`).

use glam::{DMat2, DMat3, DVec2, DVec3};

use super::{wrap_angle, EstimationError};
use crate::rng::Lcg64;

/// Control input: forward speed and turn rate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Control {
    pub v_mps: f64,
    pub omega_radps: f64,
}

impl Control {
    #[must_use]
    pub const fn new(v_mps: f64, omega_radps: f64) -> Self {
        Self { v_mps, omega_radps }
    }

    pub(crate) fn is_finite(&self) -> bool {
        self.v_mps.is_finite() && self.omega_radps.is_finite()
    }
}

/// Odometry (control) noise: standard deviations of the executed `v` and `ω`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionNoise {
    pub sigma_v_mps: f64,
    pub sigma_omega_radps: f64,
}

impl Default for MotionNoise {
    /// `σ_v = 0.1 m/s`, `σ_ω = 0.05 rad/s` (≈ 2.9 °/s).
    fn default() -> Self {
        Self {
            sigma_v_mps: 0.1,
            sigma_omega_radps: 0.05,
        }
    }
}

impl MotionNoise {
    /// Both standard deviations finite and non-negative.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        [self.sigma_v_mps, self.sigma_omega_radps]
            .iter()
            .all(|s| s.is_finite() && *s >= 0.0)
    }
}

/// Range-bearing measurement noise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorNoise {
    pub sigma_range_m: f64,
    pub sigma_bearing_rad: f64,
}

impl Default for SensorNoise {
    /// `σ_r = 0.1 m`, `σ_φ = 2°`.
    fn default() -> Self {
        Self {
            sigma_range_m: 0.1,
            sigma_bearing_rad: 2f64.to_radians(),
        }
    }
}

impl SensorNoise {
    /// `R = diag(σ_r², σ_φ²)`.
    #[must_use]
    pub fn r(&self) -> DMat2 {
        DMat2::from_diagonal(DVec2::new(
            self.sigma_range_m * self.sigma_range_m,
            self.sigma_bearing_rad * self.sigma_bearing_rad,
        ))
    }
}

/// One range-bearing observation of landmark `id`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observation {
    /// Landmark identity (index into the known map; known data association).
    pub id: usize,
    pub range_m: f64,
    /// Bearing relative to the robot's heading, radians in `[−π, π)`.
    pub bearing_rad: f64,
}

impl Observation {
    /// `(range, bearing)` as a vector.
    #[must_use]
    pub fn z(&self) -> DVec2 {
        DVec2::new(self.range_m, self.bearing_rad)
    }
}

/// The motion model `g(x, u)` over `dt_s`; the heading is wrapped to `[−π, π)`.
#[must_use]
pub fn motion_model(x: DVec3, u: Control, dt_s: f64) -> DVec3 {
    let (s, c) = crate::math::sin_cos(x.z);
    DVec3::new(
        x.x + u.v_mps * c * dt_s,
        x.y + u.v_mps * s * dt_s,
        wrap_angle(x.z + u.omega_radps * dt_s),
    )
}

/// `F = ∂g/∂x` at `x`.
#[must_use]
pub fn jacob_f(x: DVec3, u: Control, dt_s: f64) -> DMat3 {
    let (s, c) = crate::math::sin_cos(x.z);
    // glam matrices are built from columns.
    DMat3::from_cols(
        DVec3::X,
        DVec3::Y,
        DVec3::new(-u.v_mps * s * dt_s, u.v_mps * c * dt_s, 1.0),
    )
}

/// Process noise `Q = V M Vᵀ` in state space, `V = ∂g/∂u`.
#[must_use]
pub fn process_noise(x: DVec3, dt_s: f64, noise: &MotionNoise) -> DMat3 {
    let (s, c) = crate::math::sin_cos(x.z);
    let sv2 = noise.sigma_v_mps * noise.sigma_v_mps * dt_s * dt_s;
    let sw2 = noise.sigma_omega_radps * noise.sigma_omega_radps * dt_s * dt_s;
    let (xx, xy, yy) = (sv2 * c * c, sv2 * c * s, sv2 * s * s);
    DMat3::from_cols(
        DVec3::new(xx, xy, 0.0),
        DVec3::new(xy, yy, 0.0),
        DVec3::new(0.0, 0.0, sw2),
    )
}

/// The true robot's motion: `g(x, u + ε)`, `ε ~ N(0, M)` drawn from `rng`
/// (`v` first, then `ω`). Returns the new pose and the executed control.
/// Invalid `dt` or non-finite input leaves the pose unchanged.
pub fn sample_motion(
    x: DVec3,
    u: Control,
    dt_s: f64,
    noise: &MotionNoise,
    rng: &mut Lcg64,
) -> (DVec3, Control) {
    if !(dt_s.is_finite() && dt_s >= 0.0 && x.is_finite() && u.is_finite() && noise.is_valid()) {
        return (x, Control::default());
    }
    let executed = Control::new(
        rng.normal(u.v_mps, noise.sigma_v_mps),
        rng.normal(u.omega_radps, noise.sigma_omega_radps),
    );
    (motion_model(x, executed, dt_s), executed)
}

/// Expected measurement `h(x) = (√q, wrap(atan2(dy, dx) − θ))` of `landmark`.
#[must_use]
pub fn observation_model(x: DVec3, landmark: DVec2) -> DVec2 {
    let d = landmark - x.truncate();
    DVec2::new(d.length(), wrap_angle(crate::math::atan2(d.y, d.x) - x.z))
}

/// `H = ∂h/∂x` as its two rows (range row, bearing row). `None` when the
/// landmark is within `1e-9` m of the robot (the bearing is undefined).
#[must_use]
pub fn jacob_h(x: DVec3, landmark: DVec2) -> Option<(DVec3, DVec3)> {
    let d = landmark - x.truncate();
    let q = d.length_squared();
    let r = q.sqrt();
    if r.is_nan() || r <= 1e-9 || !q.is_finite() {
        return None;
    }
    Some((
        DVec3::new(-d.x / r, -d.y / r, 0.0),
        DVec3::new(d.y / q, -d.x / q, -1.0),
    ))
}

/// A range-bearing sensor with limited range and field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RangeBearingSensor {
    /// Largest range at which a landmark is seen, metres.
    pub max_range_m: f64,
    /// Full field of view centred on the heading, radians (≥ 2π: all round).
    pub fov_rad: f64,
    pub noise: SensorNoise,
}

impl Default for RangeBearingSensor {
    /// 3 m range, 180° field of view, [`SensorNoise::default`].
    fn default() -> Self {
        Self {
            max_range_m: 3.0,
            fov_rad: std::f64::consts::PI,
            noise: SensorNoise::default(),
        }
    }
}

impl RangeBearingSensor {
    /// Whether the noise-free measurement `z` of a landmark lies within range
    /// and field of view.
    #[must_use]
    pub fn sees(&self, z: DVec2) -> bool {
        z.x <= self.max_range_m && z.y.abs() <= 0.5 * self.fov_rad
    }

    /// Noisy observations of every landmark in view from the true pose `x`
    /// (landmark `i` of the slice has id `i`), in id order. Draws range then
    /// bearing noise per seen landmark. The bearing is wrapped to `[−π, π)`;
    /// the range is kept non-negative.
    pub fn observe(&self, x: DVec3, landmarks: &[DVec2], rng: &mut Lcg64) -> Vec<Observation> {
        let mut out = Vec::new();
        self.observe_into(x, landmarks, rng, &mut out);
        out
    }

    /// [`RangeBearingSensor::observe`] into a reused buffer (cleared first).
    pub fn observe_into(
        &self,
        x: DVec3,
        landmarks: &[DVec2],
        rng: &mut Lcg64,
        out: &mut Vec<Observation>,
    ) {
        out.clear();
        if !x.is_finite() {
            return;
        }
        for (id, &m) in landmarks.iter().enumerate() {
            if !m.is_finite() {
                continue;
            }
            let z = observation_model(x, m);
            if !self.sees(z) {
                continue;
            }
            let range_m = rng.normal(z.x, self.noise.sigma_range_m).max(0.0);
            let bearing_rad = wrap_angle(rng.normal(z.y, self.noise.sigma_bearing_rad));
            out.push(Observation {
                id,
                range_m,
                bearing_rad,
            });
        }
    }
}

/// Checks a `dt`: finite and non-negative.
pub(crate) fn check_dt(dt_s: f64) -> Result<(), EstimationError> {
    if dt_s.is_finite() && dt_s >= 0.0 {
        Ok(())
    } else {
        Err(EstimationError::InvalidDt { dt_s })
    }
}

/// Checks a control and its noise for finiteness.
pub(crate) fn check_motion(u: Control, noise: &MotionNoise) -> Result<(), EstimationError> {
    if u.is_finite() && noise.is_valid() {
        Ok(())
    } else {
        Err(EstimationError::NonFinite)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central finite differences of `g` and `h` match `F` and `H`.
    #[test]
    fn jacobians_match_finite_differences() {
        let mut rng = Lcg64::new(12);
        for _ in 0..500 {
            let x = DVec3::new(
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
            );
            let u = Control::new(rng.range(-1.0, 2.0), rng.range(-1.0, 1.0));
            let dt = rng.range(0.0, 0.5);
            let m = DVec2::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0));
            let f = jacob_f(x, u, dt);
            let (h0, h1) = match jacob_h(x, m) {
                Some(h) => h,
                None => continue,
            };
            if observation_model(x, m).y.abs() > 3.0 {
                continue; // keep the differences away from the ±π cut
            }
            let eps = 1e-6;
            for k in 0..3 {
                let mut dx = DVec3::ZERO;
                dx[k] = eps;
                let dg = (motion_model(x + dx, u, dt) - motion_model(x - dx, u, dt)) / (2.0 * eps);
                let mut dg = dg;
                dg.z = wrap_angle(dg.z * 2.0 * eps) / (2.0 * eps);
                assert!((dg - f.col(k)).length() < 1e-7, "F col {k}");
                let dh =
                    (observation_model(x + dx, m) - observation_model(x - dx, m)) / (2.0 * eps);
                assert!(
                    (dh.x - h0[k]).abs() < 1e-6 && (dh.y - h1[k]).abs() < 1e-6,
                    "H col {k}"
                );
            }
        }
        assert!(jacob_h(DVec3::new(1.0, 1.0, 0.0), DVec2::new(1.0, 1.0)).is_none());
    }

    #[test]
    fn sensor_respects_range_and_field_of_view() {
        let sensor = RangeBearingSensor {
            max_range_m: 2.0,
            fov_rad: std::f64::consts::FRAC_PI_2,
            noise: SensorNoise {
                sigma_range_m: 0.0,
                sigma_bearing_rad: 0.0,
            },
        };
        let landmarks = [
            DVec2::new(1.0, 0.0),  // ahead, seen
            DVec2::new(1.0, 0.9),  // 42° left, seen
            DVec2::new(0.5, 1.0),  // 63° left: outside ±45°
            DVec2::new(-1.0, 0.0), // behind
            DVec2::new(2.5, 0.0),  // too far
            DVec2::new(f64::NAN, 0.0),
        ];
        let mut rng = Lcg64::new(1);
        let obs = sensor.observe(DVec3::ZERO, &landmarks, &mut rng);
        assert_eq!(obs.iter().map(|o| o.id).collect::<Vec<_>>(), vec![0, 1]);
        assert!((obs[1].bearing_rad - crate::math::atan2(0.9, 1.0)).abs() < 1e-15);
        assert!(sensor
            .observe(DVec3::new(f64::NAN, 0.0, 0.0), &landmarks, &mut rng)
            .is_empty());
    }

    #[test]
    fn sampled_motion_has_the_told_spread() {
        let noise = MotionNoise::default();
        let mut rng = Lcg64::new(77);
        let u = Control::new(1.0, 0.3);
        let n = 20_000;
        let mut sum_sq = DVec2::ZERO;
        for _ in 0..n {
            let (_, executed) = sample_motion(DVec3::ZERO, u, 0.1, &noise, &mut rng);
            let e = DVec2::new(
                executed.v_mps - u.v_mps,
                executed.omega_radps - u.omega_radps,
            );
            sum_sq += e * e;
        }
        let std = (sum_sq / n as f64).to_array().map(f64::sqrt);
        assert!((std[0] / noise.sigma_v_mps - 1.0).abs() < 0.03);
        assert!((std[1] / noise.sigma_omega_radps - 1.0).abs() < 0.03);
        let (x, _) = sample_motion(DVec3::ONE, u, f64::NAN, &noise, &mut rng);
        assert_eq!(x, DVec3::ONE);
    }
}
