//! PID position control of a mass with viscous drag.
//!
//! **Plant.** A mass `m` (kg) on a line with viscous drag `c` (N·s/m), control force `u`
//! and an optional constant disturbance force `d` (N):
//!
//! ```text
//! m·ẍ = u + d − c·ẋ
//! ```
//!
//! integrated over each fixed step with the force held constant (zero-order hold) by
//! classical RK4, which for this linear plant is accurate to `O(dt⁵)` per step.
//!
//! **Controller** (Åström & Murray, *Feedback Systems*, 2nd ed., 2021, §11.1, eq. 11.1;
//! Åström & Hägglund, *Advanced PID Control*, 2006, §3.2–3.5), with `e = r − y`:
//!
//! ```text
//! u = Kp·e + Ki·∫e dt + Kd·de/dt
//! ```
//!
//! discretised with step `h`:
//!
//! - integral: `I ← clamp(I + e·h, −I_max, I_max)` — clamping the integral state is the
//!   simplest anti-windup (Åström & Hägglund 2006, §3.5);
//! - derivative: the backward difference `(e − e_prev)/h`, or with *derivative on
//!   measurement* `−(y − y_prev)/h`, which equals `de/dt` while the setpoint is constant
//!   but gives no impulse ("derivative kick") when the setpoint steps
//!   (Åström & Hägglund 2006, §3.4, "set-point weighting" with `γ = 0`);
//!   on the very first update there is no previous sample and the derivative is 0;
//! - derivative filter: the first-order low-pass `D_f/D = 1/(T_f s + 1)` discretised by
//!   backward Euler, `D_f ← D_f + h/(T_f + h)·(D − D_f)` (Åström & Murray 2021, §11.5);
//!   it tames the amplification of sensor noise by the difference `1/h`;
//! - saturation: `u = clamp(u_PID, −u_max, u_max)`; [`PidTerms::saturated`] reports when
//!   it was active.
//!
//! **Closed-loop poles.** With `P(s) = 1/(m s² + c s)` and `C(s) = Kp + Ki/s + Kd s`, the
//! characteristic equation `1 + C P = 0` is
//!
//! ```text
//! m·s³ + (c + Kd)·s² + Kp·s + Ki = 0
//! ```
//!
//! (derivative on measurement moves zeros, not poles). With `Ki = 0` the loop is second
//! order, `m s² + (c + Kd) s + Kp`, with `ωn = √(Kp/m)` and `ζ = (c + Kd)/(2√(m·Kp))`
//! (Åström & Murray 2021, §7.3 / Table 7.1).

use super::poly::{roots, Complex, RootError};
use super::Stability;
use crate::rng::Lcg64;

/// The three gains. Units: `Kp` N/m, `Ki` N/(m·s), `Kd` N·s/m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PidGains {
    pub kp: f64,
    pub ki: f64,
    pub kd: f64,
}

impl Default for PidGains {
    /// The lab description's starting tuning: `Kp = 12`, `Ki = 2`, `Kd = 6`.
    fn default() -> Self {
        Self {
            kp: 12.0,
            ki: 2.0,
            kd: 6.0,
        }
    }
}

/// Controller settings: gains plus the practical modifications.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PidConfig {
    pub gains: PidGains,
    /// Anti-windup clamp on the integral state, `|∫e dt| ≤` this (m·s).
    /// `f64::INFINITY` disables the clamp.
    pub integral_limit_m_s: f64,
    /// Differentiate `−y` instead of `e` (no derivative kick on setpoint steps).
    pub derivative_on_measurement: bool,
    /// Derivative filter time constant `T_f` (s); 0 differentiates the raw samples.
    pub derivative_filter_s: f64,
    /// Actuator limit, `|u| ≤` this (N). `f64::INFINITY` means no saturation.
    pub output_limit_n: f64,
}

impl Default for PidConfig {
    fn default() -> Self {
        Self {
            gains: PidGains::default(),
            integral_limit_m_s: 5.0,
            derivative_on_measurement: false,
            derivative_filter_s: 0.0,
            output_limit_n: f64::INFINITY,
        }
    }
}

/// Why a configuration or plant was refused.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PidError {
    /// A gain was NaN or infinite.
    NonFiniteGain,
    /// The integral or output limit was NaN, zero or negative.
    BadLimit,
    /// The derivative filter constant was NaN, infinite or negative.
    BadFilter,
    /// Mass not finite and positive, or drag not finite and non-negative.
    BadPlant,
    /// The pole computation failed.
    Roots(RootError),
}

impl PidConfig {
    /// Checks every field; a [`Pid`] built from a refused configuration is never made.
    pub fn validate(&self) -> Result<(), PidError> {
        let g = self.gains;
        if !(g.kp.is_finite() && g.ki.is_finite() && g.kd.is_finite()) {
            return Err(PidError::NonFiniteGain);
        }
        let limit_ok = |v: f64| !v.is_nan() && v > 0.0;
        if !limit_ok(self.integral_limit_m_s) || !limit_ok(self.output_limit_n) {
            return Err(PidError::BadLimit);
        }
        if !(self.derivative_filter_s.is_finite() && self.derivative_filter_s >= 0.0) {
            return Err(PidError::BadFilter);
        }
        Ok(())
    }
}

/// One controller update, term by term (N).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PidTerms {
    /// `e = r − y` used by this update (m).
    pub error_m: f64,
    /// `Kp·e`.
    pub p: f64,
    /// `Ki·∫e dt` (after the clamp).
    pub i: f64,
    /// `Kd·(filtered derivative)`.
    pub d: f64,
    /// `p + i + d` before saturation.
    pub unsaturated: f64,
    /// The force actually applied, `clamp(p + i + d, ±u_max)`.
    pub output: f64,
    /// `true` when the actuator limit cut the output.
    pub saturated: bool,
    /// `true` when the integral clamp was active in this update.
    pub integral_clamped: bool,
}

/// A discrete PID controller with its memory (integral, previous samples, filter).
#[derive(Clone, Debug, PartialEq)]
pub struct Pid {
    config: PidConfig,
    integral_m_s: f64,
    prev_error_m: f64,
    prev_measurement_m: f64,
    derivative_filtered: f64,
    has_previous: bool,
}

impl Default for Pid {
    /// A controller at rest with [`PidConfig::default`] (which always validates).
    fn default() -> Self {
        Self {
            config: PidConfig::default(),
            integral_m_s: 0.0,
            prev_error_m: 0.0,
            prev_measurement_m: 0.0,
            derivative_filtered: 0.0,
            has_previous: false,
        }
    }
}

impl Pid {
    /// A controller at rest, or the reason the configuration is refused.
    pub fn new(config: PidConfig) -> Result<Self, PidError> {
        config.validate()?;
        Ok(Self {
            config,
            integral_m_s: 0.0,
            prev_error_m: 0.0,
            prev_measurement_m: 0.0,
            derivative_filtered: 0.0,
            has_previous: false,
        })
    }

    /// The configuration in use.
    #[must_use]
    pub fn config(&self) -> &PidConfig {
        &self.config
    }

    /// Replaces the configuration, keeping the controller's memory (bumpless for gain
    /// changes); the integral is re-clamped to a new limit. A refused configuration
    /// leaves everything unchanged.
    pub fn set_config(&mut self, config: PidConfig) -> Result<(), PidError> {
        config.validate()?;
        self.config = config;
        let lim = config.integral_limit_m_s;
        self.integral_m_s = self.integral_m_s.clamp(-lim, lim);
        Ok(())
    }

    /// The (filtered) derivative the last update used (m/s): `ė`, or with
    /// derivative on measurement `−ẏ`.
    #[must_use]
    pub fn derivative_m_s(&self) -> f64 {
        self.derivative_filtered
    }

    /// The integral state `∫e dt` (m·s).
    #[must_use]
    pub fn integral_m_s(&self) -> f64 {
        self.integral_m_s
    }

    /// Forgets the integral, previous samples and filter state.
    pub fn reset(&mut self) {
        self.integral_m_s = 0.0;
        self.prev_error_m = 0.0;
        self.prev_measurement_m = 0.0;
        self.derivative_filtered = 0.0;
        self.has_previous = false;
    }

    /// One update for setpoint `r` and measurement `y` (m) after `dt_s` seconds.
    /// Returns `None`, and changes nothing, when `dt_s` is not finite and positive or
    /// `r`/`y` is not finite.
    ///
    /// # Example
    /// ```
    /// use labcore::control::pid::{Pid, PidConfig, PidGains};
    /// let config = PidConfig {
    ///     gains: PidGains { kp: 2.0, ki: 1.0, kd: 0.5 },
    ///     ..PidConfig::default()
    /// };
    /// let mut pid = Pid::new(config).unwrap();
    /// // e = 1 − 0 = 1; I = 1·0.1; D = 0 on the first update.
    /// let t = pid.update(1.0, 0.0, 0.1).unwrap();
    /// assert_eq!((t.p, t.d), (2.0, 0.0));
    /// assert!((t.i - 0.1).abs() < 1e-15);
    /// ```
    pub fn update(&mut self, setpoint_m: f64, measurement_m: f64, dt_s: f64) -> Option<PidTerms> {
        if !(dt_s.is_finite() && dt_s > 0.0 && setpoint_m.is_finite() && measurement_m.is_finite())
        {
            return None;
        }
        let c = &self.config;
        let e = setpoint_m - measurement_m;
        let lim = c.integral_limit_m_s;
        let integral_raw = self.integral_m_s + e * dt_s;
        let integral = integral_raw.clamp(-lim, lim);
        let raw_derivative = if !self.has_previous {
            0.0
        } else if c.derivative_on_measurement {
            -(measurement_m - self.prev_measurement_m) / dt_s
        } else {
            (e - self.prev_error_m) / dt_s
        };
        let tf = c.derivative_filter_s;
        let derivative = if tf > 0.0 && self.has_previous {
            self.derivative_filtered
                + dt_s / (tf + dt_s) * (raw_derivative - self.derivative_filtered)
        } else {
            raw_derivative
        };
        let p = c.gains.kp * e;
        let i = c.gains.ki * integral;
        let d = c.gains.kd * derivative;
        let unsaturated = p + i + d;
        let umax = c.output_limit_n;
        let output = unsaturated.clamp(-umax, umax);
        if !output.is_finite() {
            return None;
        }
        self.integral_m_s = integral;
        self.prev_error_m = e;
        self.prev_measurement_m = measurement_m;
        self.derivative_filtered = derivative;
        self.has_previous = true;
        Some(PidTerms {
            error_m: e,
            p,
            i,
            d,
            unsaturated,
            output,
            saturated: output != unsaturated,
            integral_clamped: integral != integral_raw,
        })
    }
}

/// Mass with viscous drag, `m·ẍ = u + d − c·ẋ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassDragPlant {
    /// `m` (kg), finite and positive.
    pub mass_kg: f64,
    /// `c` (N·s/m), finite and non-negative.
    pub drag_n_s_per_m: f64,
}

impl Default for MassDragPlant {
    /// Unit mass, drag 1 N·s/m (the lab description's defaults).
    fn default() -> Self {
        Self {
            mass_kg: 1.0,
            drag_n_s_per_m: 1.0,
        }
    }
}

/// Position and velocity of the mass.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PlantState {
    pub x_m: f64,
    pub v_m_s: f64,
}

impl MassDragPlant {
    /// `true` when the mass is finite and positive and the drag finite and `≥ 0`.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        self.mass_kg.is_finite()
            && self.mass_kg > 0.0
            && self.drag_n_s_per_m.is_finite()
            && self.drag_n_s_per_m >= 0.0
    }

    /// Acceleration `(F − c·v)/m` (m/s²) under total force `force_n`.
    #[must_use]
    pub fn acceleration(&self, v_m_s: f64, force_n: f64) -> f64 {
        (force_n - self.drag_n_s_per_m * v_m_s) / self.mass_kg
    }

    /// Advances `state` by `dt_s` with the total force held constant, by RK4.
    /// Returns `false` and leaves `state` unchanged for a bad `dt_s`, force or plant.
    pub fn step(&self, state: &mut PlantState, force_n: f64, dt_s: f64) -> bool {
        if !(self.is_valid() && dt_s.is_finite() && dt_s > 0.0 && force_n.is_finite()) {
            return false;
        }
        let f = |v: f64| (v, self.acceleration(v, force_n));
        let (k1x, k1v) = f(state.v_m_s);
        let (k2x, k2v) = f(state.v_m_s + 0.5 * dt_s * k1v);
        let (k3x, k3v) = f(state.v_m_s + 0.5 * dt_s * k2v);
        let (k4x, k4v) = f(state.v_m_s + dt_s * k3v);
        let x = state.x_m + dt_s / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        let v = state.v_m_s + dt_s / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if !(x.is_finite() && v.is_finite()) {
            return false;
        }
        *state = PlantState { x_m: x, v_m_s: v };
        true
    }
}

/// The closed loop: plant, controller, setpoint, disturbance and seeded sensor noise.
#[derive(Clone, Debug, PartialEq)]
pub struct PidLoop {
    pub plant: MassDragPlant,
    pub state: PlantState,
    pub controller: Pid,
    /// `r` (m).
    pub setpoint_m: f64,
    /// Constant disturbance force `d` (N) added to the control force.
    pub disturbance_n: f64,
    /// Standard deviation of the Gaussian sensor noise on `y` (m); 0 for none.
    pub noise_std_m: f64,
    /// Simulated time (s).
    pub time_s: f64,
    rng: Lcg64,
    seed: u64,
    last: PidTerms,
    last_measurement_m: f64,
}

impl PidLoop {
    /// The mass at rest at `x = 0`, setpoint `setpoint_m`, no disturbance or noise.
    #[must_use]
    pub fn new(plant: MassDragPlant, controller: Pid, setpoint_m: f64, seed: u64) -> Self {
        Self {
            plant,
            state: PlantState::default(),
            controller,
            setpoint_m,
            disturbance_n: 0.0,
            noise_std_m: 0.0,
            time_s: 0.0,
            rng: Lcg64::new(seed),
            seed,
            last: PidTerms::default(),
            last_measurement_m: 0.0,
        }
    }

    /// The last update's terms (all zero before the first step).
    #[must_use]
    pub fn last_terms(&self) -> PidTerms {
        self.last
    }

    /// The last (possibly noisy) measurement fed to the controller (m).
    #[must_use]
    pub fn last_measurement_m(&self) -> f64 {
        self.last_measurement_m
    }

    /// Back to rest at `x = 0`, time 0, controller memory cleared, noise generator
    /// re-seeded (so a reset run repeats exactly).
    pub fn reset(&mut self) {
        self.state = PlantState::default();
        self.controller.reset();
        self.time_s = 0.0;
        self.rng = Lcg64::new(self.seed);
        self.last = PidTerms::default();
        self.last_measurement_m = 0.0;
    }

    /// Measure (with noise), update the controller, then integrate the plant over
    /// `dt_s` with that force held. Returns `false` and changes nothing on a bad `dt_s`
    /// or a non-finite result.
    pub fn step(&mut self, dt_s: f64) -> bool {
        if !(dt_s.is_finite() && dt_s > 0.0) {
            return false;
        }
        let mut rng = self.rng.clone();
        let noise = if self.noise_std_m > 0.0 && self.noise_std_m.is_finite() {
            self.noise_std_m * standard_normal(&mut rng)
        } else {
            0.0
        };
        let y = self.state.x_m + noise;
        let mut controller = self.controller.clone();
        let Some(terms) = controller.update(self.setpoint_m, y, dt_s) else {
            return false;
        };
        let mut state = self.state;
        if !self
            .plant
            .step(&mut state, terms.output + self.disturbance_n, dt_s)
        {
            return false;
        }
        self.state = state;
        self.controller = controller;
        self.rng = rng;
        self.last = terms;
        self.last_measurement_m = y;
        self.time_s += dt_s;
        true
    }
}

/// A standard normal draw by the Box–Muller transform (Box & Muller, *Ann. Math.
/// Statist.* 29, 1958): `√(−2 ln u₁)·cos(2π u₂)`, `u₁` in `(0, 1]`.
pub fn standard_normal(rng: &mut Lcg64) -> f64 {
    let u1 = 1.0 - rng.next_f64();
    let u2 = rng.next_f64();
    (-2.0 * crate::math::ln(u1)).sqrt() * crate::math::cos(2.0 * std::f64::consts::PI * u2)
}

/// Simulates a step from rest at `x = 0` toward `setpoint_m` for `duration_s` with
/// fixed step `dt_s`, no noise; returns the sample times and positions, including
/// `t = 0`. `None` for a bad configuration, plant, `dt_s` or duration.
///
/// # Example
/// ```
/// use labcore::control::pid::{simulate_step, MassDragPlant, PidConfig};
/// use labcore::control::step_info::step_info;
/// let (t, y) = simulate_step(&MassDragPlant::default(), &PidConfig::default(), 1.0, 0.0, 20.0, 1e-3).unwrap();
/// let info = step_info(&t, &y, 0.0, 1.0, Some(1.0)).unwrap();
/// assert!(info.settling_time_s.unwrap() < 20.0);
/// ```
#[must_use]
pub fn simulate_step(
    plant: &MassDragPlant,
    config: &PidConfig,
    setpoint_m: f64,
    disturbance_n: f64,
    duration_s: f64,
    dt_s: f64,
) -> Option<(Vec<f64>, Vec<f64>)> {
    if !(plant.is_valid()
        && duration_s.is_finite()
        && duration_s >= 0.0
        && dt_s.is_finite()
        && dt_s > 0.0
        && setpoint_m.is_finite()
        && disturbance_n.is_finite())
    {
        return None;
    }
    let steps = (duration_s / dt_s).round();
    if steps > 10_000_000.0 {
        return None;
    }
    let mut lp = PidLoop::new(*plant, Pid::new(*config).ok()?, setpoint_m, 0);
    lp.disturbance_n = disturbance_n;
    let n = steps as usize;
    let mut t = Vec::with_capacity(n + 1);
    let mut y = Vec::with_capacity(n + 1);
    t.push(0.0);
    y.push(0.0);
    for k in 1..=n {
        if !lp.step(dt_s) {
            return None;
        }
        t.push(k as f64 * dt_s);
        y.push(lp.state.x_m);
    }
    Some((t, y))
}

/// Poles of the linear closed loop and the stability verdict.
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedLoopPoles {
    /// Characteristic polynomial, highest power first: `[m, c + Kd, Kp, Ki]`, or
    /// `[m, c + Kd, Kp]` when `Ki = 0`.
    pub characteristic: Vec<f64>,
    /// Its roots, sorted by real part (complex pairs are exact conjugates).
    pub poles: Vec<Complex>,
    pub stability: Stability,
}

/// Closed-loop poles, roots of `m s³ + (c + Kd) s² + Kp s + Ki` (second order when
/// `Ki = 0`).
///
/// # Example
/// ```
/// use labcore::control::{pid::{closed_loop_poles, MassDragPlant, PidGains}, Stability};
/// let plant = MassDragPlant { mass_kg: 1.0, drag_n_s_per_m: 0.0 };
/// // s² + 2s + 5 → −1 ± 2i
/// let cl = closed_loop_poles(&plant, &PidGains { kp: 5.0, ki: 0.0, kd: 2.0 }).unwrap();
/// assert_eq!(cl.poles.len(), 2);
/// assert!((cl.poles[1].im - 2.0).abs() < 1e-12);
/// assert_eq!(cl.stability, Stability::Stable);
/// ```
pub fn closed_loop_poles(
    plant: &MassDragPlant,
    gains: &PidGains,
) -> Result<ClosedLoopPoles, PidError> {
    if !plant.is_valid() {
        return Err(PidError::BadPlant);
    }
    if !(gains.kp.is_finite() && gains.ki.is_finite() && gains.kd.is_finite()) {
        return Err(PidError::NonFiniteGain);
    }
    let mut characteristic = vec![
        plant.mass_kg,
        plant.drag_n_s_per_m + gains.kd,
        gains.kp,
        gains.ki,
    ];
    if gains.ki == 0.0 {
        characteristic.pop();
    }
    let poles = roots(&characteristic).map_err(PidError::Roots)?;
    let stability = Stability::of(&poles);
    Ok(ClosedLoopPoles {
        characteristic,
        poles,
        stability,
    })
}

/// Natural frequency and damping ratio of the `Ki = 0` loop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SecondOrder {
    /// `ωn = √(Kp/m)` (rad/s).
    pub natural_frequency_rad_s: f64,
    /// `ζ = (c + Kd)/(2√(m·Kp))`.
    pub damping_ratio: f64,
}

impl SecondOrder {
    /// `ωn` and `ζ` for `Ki = 0` and `Kp > 0`; `None` otherwise or for a bad plant.
    #[must_use]
    pub fn of(plant: &MassDragPlant, gains: &PidGains) -> Option<Self> {
        if !plant.is_valid() || gains.ki != 0.0 || !(gains.kp > 0.0 && gains.kp.is_finite()) {
            return None;
        }
        let wn = (gains.kp / plant.mass_kg).sqrt();
        let zeta = (plant.drag_n_s_per_m + gains.kd) / (2.0 * (plant.mass_kg * gains.kp).sqrt());
        zeta.is_finite().then_some(Self {
            natural_frequency_rad_s: wn,
            damping_ratio: zeta,
        })
    }

    /// Step overshoot `100·exp(−ζπ/√(1 − ζ²))` percent for `0 ≤ ζ < 1`, else 0
    /// (Åström & Murray 2021, §7.3, eq. 7.17). Valid for the loop without a zero, i.e.
    /// `Kd = 0` or derivative on measurement.
    #[must_use]
    pub fn overshoot_pct(&self) -> f64 {
        let z = self.damping_ratio;
        if (0.0..1.0).contains(&z) {
            100.0 * crate::math::exp(-z * std::f64::consts::PI / (1.0 - z * z).sqrt())
        } else {
            0.0
        }
    }

    /// Peak time `π/ωd` with `ωd = ωn√(1 − ζ²)` (s); `None` unless `0 ≤ ζ < 1`.
    #[must_use]
    pub fn peak_time_s(&self) -> Option<f64> {
        let z = self.damping_ratio;
        (0.0..1.0)
            .contains(&z)
            .then(|| std::f64::consts::PI / (self.natural_frequency_rad_s * (1.0 - z * z).sqrt()))
    }

    /// The envelope estimate of the 2 % settling time, `4/(ζ ωn)` (s); `None` unless
    /// `ζ > 0`. An approximation (exact settling jumps with the oscillation's phase).
    #[must_use]
    pub fn settling_time_estimate_s(&self) -> Option<f64> {
        (self.damping_ratio > 0.0)
            .then(|| 4.0 / (self.damping_ratio * self.natural_frequency_rad_s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::step_info::step_info;

    fn config(kp: f64, ki: f64, kd: f64) -> PidConfig {
        PidConfig {
            gains: PidGains { kp, ki, kd },
            integral_limit_m_s: f64::INFINITY,
            ..PidConfig::default()
        }
    }

    #[test]
    fn hand_computed_controller_updates() {
        let mut pid = Pid::new(config(2.0, 1.0, 0.5)).unwrap();
        // Update 1: e = 1, I = 0.1, D = 0 (no previous sample).
        let t1 = pid.update(1.0, 0.0, 0.1).unwrap();
        assert_eq!((t1.error_m, t1.p, t1.d), (1.0, 2.0, 0.0));
        assert!((t1.i - 0.1).abs() < 1e-15);
        // Update 2: y = 0.2 → e = 0.8, I = 0.1 + 0.08 = 0.18, de/dt = −0.2/0.1 = −2.
        let t2 = pid.update(1.0, 0.2, 0.1).unwrap();
        assert!((t2.p - 1.6).abs() < 1e-15);
        assert!((t2.i - 0.18).abs() < 1e-15);
        assert!((t2.d - (-1.0)).abs() < 1e-14);
        assert!((t2.output - 0.78).abs() < 1e-14);
        assert!(!t2.saturated);
    }

    #[test]
    fn derivative_on_measurement_has_no_setpoint_kick() {
        for on_measurement in [false, true] {
            let mut cfg = config(1.0, 0.0, 1.0);
            cfg.derivative_on_measurement = on_measurement;
            let mut pid = Pid::new(cfg).unwrap();
            pid.update(0.0, 0.0, 0.01).unwrap();
            // Setpoint jumps 0 → 1 with the measurement still at 0.
            let t = pid.update(1.0, 0.0, 0.01).unwrap();
            if on_measurement {
                assert_eq!(t.d, 0.0);
            } else {
                assert!((t.d - 100.0).abs() < 1e-9, "kick = Kd·Δr/h = 100");
            }
        }
    }

    #[test]
    fn filter_saturation_and_clamp_by_hand() {
        let mut cfg = config(10.0, 100.0, 1.0);
        cfg.derivative_filter_s = 0.1;
        cfg.output_limit_n = 5.0;
        cfg.integral_limit_m_s = 0.05;
        let mut pid = Pid::new(cfg).unwrap();
        let t1 = pid.update(1.0, 0.0, 0.1).unwrap();
        // I = clamp(0.1, ±0.05) = 0.05 → i = 5; p = 10; u = 15 → saturated at 5.
        assert!(t1.integral_clamped && t1.saturated);
        assert_eq!((t1.i, t1.unsaturated, t1.output), (5.0, 15.0, 5.0));
        // Raw de/dt = (0.5 − 1)/0.1 = −5; filtered: 0 + 0.1/0.2·(−5 − 0) = −2.5.
        let t2 = pid.update(1.0, 0.5, 0.1).unwrap();
        assert!((t2.d + 2.5).abs() < 1e-12);
    }

    #[test]
    fn bad_inputs_leave_state_unchanged() {
        let mut pid = Pid::new(config(1.0, 1.0, 1.0)).unwrap();
        pid.update(1.0, 0.0, 0.1).unwrap();
        let before = pid.clone();
        for dt in [0.0, -0.1, f64::NAN, f64::INFINITY] {
            assert!(pid.update(1.0, 0.0, dt).is_none());
        }
        assert!(pid.update(f64::NAN, 0.0, 0.1).is_none());
        assert_eq!(pid, before);

        let mut lp = PidLoop::new(MassDragPlant::default(), pid, 1.0, 1);
        lp.step(0.01);
        let before = lp.clone();
        assert!(!lp.step(-0.01) && !lp.step(f64::NAN));
        assert_eq!(lp, before);

        let mut s = PlantState {
            x_m: 1.0,
            v_m_s: 2.0,
        };
        let bad = MassDragPlant {
            mass_kg: -1.0,
            drag_n_s_per_m: 0.0,
        };
        assert!(!bad.step(&mut s, 1.0, 0.1));
        assert!(!MassDragPlant::default().step(&mut s, f64::NAN, 0.1));
        assert_eq!(
            s,
            PlantState {
                x_m: 1.0,
                v_m_s: 2.0
            }
        );

        assert_eq!(
            Pid::new(PidConfig {
                output_limit_n: 0.0,
                ..PidConfig::default()
            }),
            Err(PidError::BadLimit)
        );
        assert_eq!(
            Pid::new(PidConfig {
                derivative_filter_s: -1.0,
                ..PidConfig::default()
            }),
            Err(PidError::BadFilter)
        );
    }

    #[test]
    fn plant_step_matches_exact_solution() {
        // m = 2, c = 1, F = 3 from rest: v(t) = 3(1 − e^(−t/2)), x(t) = 3t − 6(1 − e^(−t/2)).
        let plant = MassDragPlant {
            mass_kg: 2.0,
            drag_n_s_per_m: 1.0,
        };
        let mut s = PlantState::default();
        for _ in 0..100 {
            assert!(plant.step(&mut s, 3.0, 0.01));
        }
        let e = crate::math::exp(-0.5);
        assert!((s.v_m_s - 3.0 * (1.0 - e)).abs() < 1e-10);
        assert!((s.x_m - (3.0 - 6.0 * (1.0 - e))).abs() < 1e-10);
    }

    /// Exact step response of `ωn²/(s² + 2ζωn s + ωn²)`, `ζ < 1`.
    fn second_order_response(wn: f64, zeta: f64, t: f64) -> f64 {
        let wd = wn * (1.0 - zeta * zeta).sqrt();
        let (s, c) = crate::math::sin_cos(wd * t);
        1.0 - crate::math::exp(-zeta * wn * t) * (c + zeta / (1.0 - zeta * zeta).sqrt() * s)
    }

    #[test]
    fn second_order_metrics_match_analytic_formulas() {
        let plant = MassDragPlant {
            mass_kg: 1.0,
            drag_n_s_per_m: 1.0,
        };
        for (kp, kd) in [(12.0, 1.0), (25.0, 3.0), (4.0, 0.0)] {
            let mut cfg = config(kp, 0.0, kd);
            cfg.derivative_on_measurement = true; // no zero: a pure second-order loop
            let dt = 1e-3;
            let (t, y) = simulate_step(&plant, &cfg, 1.0, 0.0, 15.0, dt).unwrap();
            let sim = step_info(&t, &y, 0.0, 1.0, Some(1.0)).unwrap();
            let so = SecondOrder::of(&plant, &cfg.gains).unwrap();
            let (wn, zeta) = (so.natural_frequency_rad_s, so.damping_ratio);
            assert!((wn - kp.sqrt()).abs() < 1e-12);
            assert!((zeta - (1.0 + kd) / (2.0 * kp.sqrt())).abs() < 1e-12);
            // Overshoot and peak time: closed forms (ZOH at 1 kHz costs < 0.3 points).
            assert!(
                (sim.overshoot_pct - so.overshoot_pct()).abs() < 0.3,
                "{} vs {}",
                sim.overshoot_pct,
                so.overshoot_pct()
            );
            assert!((sim.peak_time_s - so.peak_time_s().unwrap()).abs() < 5.0 * dt);
            // Settling: the exact continuous response's 2 % time, and the 4/(ζωn) rule.
            let exact: Vec<f64> = t
                .iter()
                .map(|&t| second_order_response(wn, zeta, t))
                .collect();
            let ex = step_info(&t, &exact, 0.0, 1.0, Some(1.0)).unwrap();
            let ts = sim.settling_time_s.unwrap();
            assert!(
                (ts - ex.settling_time_s.unwrap()).abs() < 0.05,
                "{ts} vs {ex:?}"
            );
            assert!((ex.rise_time_s.unwrap() - sim.rise_time_s.unwrap()).abs() < 5.0 * dt);
            let estimate = so.settling_time_estimate_s().unwrap();
            assert!((ts / estimate - 1.0).abs() < 0.3, "{ts} vs {estimate}");
        }
    }

    #[test]
    fn integral_action_removes_disturbance_offset() {
        let plant = MassDragPlant::default();
        let d = -2.0; // a constant push back toward the origin (N)
                      // P-D only: offset e_ss = −d/Kp = 2/12.
        let (t, y) = simulate_step(&plant, &config(12.0, 0.0, 6.0), 1.0, d, 30.0, 1e-3).unwrap();
        let pd = step_info(&t, &y, 0.0, 1.0, None).unwrap();
        assert!((pd.steady_state_error - 2.0 / 12.0).abs() < 1e-6);
        // With Ki the offset goes.
        let (t, y) = simulate_step(&plant, &config(12.0, 2.0, 6.0), 1.0, d, 60.0, 1e-3).unwrap();
        let pid = step_info(&t, &y, 0.0, 1.0, None).unwrap();
        assert!(
            pid.steady_state_error.abs() < 1e-4,
            "{}",
            pid.steady_state_error
        );
    }

    #[test]
    fn anti_windup_bounds_the_integral_under_saturation() {
        let plant = MassDragPlant::default();
        let run = |limit: f64| {
            let cfg = PidConfig {
                gains: PidGains {
                    kp: 12.0,
                    ki: 8.0,
                    kd: 6.0,
                },
                integral_limit_m_s: limit,
                output_limit_n: 1.0,
                ..PidConfig::default()
            };
            let mut lp = PidLoop::new(plant, Pid::new(cfg).unwrap(), 5.0, 0);
            let mut max_integral: f64 = 0.0;
            let mut saturated_steps = 0;
            let mut y = Vec::new();
            for _ in 0..40_000 {
                assert!(lp.step(1e-3));
                max_integral = max_integral.max(lp.controller.integral_m_s().abs());
                saturated_steps += usize::from(lp.last_terms().saturated);
                y.push(lp.state.x_m);
            }
            let peak = y.iter().fold(f64::MIN, |m, &v| m.max(v));
            (max_integral, saturated_steps, peak)
        };
        let (i_clamped, sat, peak_clamped) = run(0.5);
        assert!(sat > 1000, "the actuator was saturated for a while");
        assert!(i_clamped <= 0.5);
        let (i_free, _, peak_free) = run(f64::INFINITY);
        assert!(
            i_free > 5.0,
            "without the clamp the integral winds up: {i_free}"
        );
        assert!(peak_free - 5.0 > 2.0 * (peak_clamped - 5.0).max(0.01));
    }

    #[test]
    fn poles_agree_with_simulation() {
        let plant = MassDragPlant {
            mass_kg: 1.0,
            drag_n_s_per_m: 0.5,
        };
        // Hurwitz for a3 s³ + a2 s² + a1 s + a0: all > 0 and a2 a1 > a3 a0.
        for (gains, stable) in [
            (
                PidGains {
                    kp: 12.0,
                    ki: 2.0,
                    kd: 6.0,
                },
                true,
            ), // 6.5·12 > 2
            (
                PidGains {
                    kp: 2.0,
                    ki: 10.0,
                    kd: 0.5,
                },
                false,
            ), // 1·2 < 10
        ] {
            let cl = closed_loop_poles(&plant, &gains).unwrap();
            assert_eq!(cl.poles.len(), 3);
            let hurwitz = (plant.drag_n_s_per_m + gains.kd) * gains.kp > plant.mass_kg * gains.ki;
            assert_eq!(hurwitz, stable);
            assert_eq!(cl.stability == Stability::Stable, stable);
            // Each pole is a root.
            for p in &cl.poles {
                assert!(crate::control::poly::eval(&cl.characteristic, *p).abs() < 1e-9);
            }
            let cfg = config(gains.kp, gains.ki, gains.kd);
            let (_, y) = simulate_step(&plant, &cfg, 1.0, 0.0, 40.0, 1e-3).unwrap();
            let tail = y[y.len() - 2000..]
                .iter()
                .fold(0.0_f64, |m, v| m.max((v - 1.0).abs()));
            if stable {
                assert!(tail < 1e-3, "settles: {tail}");
            } else {
                assert!(tail > 10.0, "diverges: {tail}");
            }
        }
        // Ki = 0 → second order; Kp = Ki = 0 leaves a pole at the origin.
        let cl = closed_loop_poles(
            &plant,
            &PidGains {
                kp: 4.0,
                ki: 0.0,
                kd: 0.0,
            },
        )
        .unwrap();
        assert_eq!(cl.characteristic, vec![1.0, 0.5, 4.0]);
        assert_eq!(cl.stability, Stability::Stable);
        let cl = closed_loop_poles(
            &plant,
            &PidGains {
                kp: 0.0,
                ki: 0.0,
                kd: 1.0,
            },
        )
        .unwrap();
        assert_eq!(cl.stability, Stability::MarginallyStable);
        assert!(closed_loop_poles(
            &MassDragPlant {
                mass_kg: 0.0,
                drag_n_s_per_m: 0.0
            },
            &PidGains::default()
        )
        .is_err());
    }

    #[test]
    fn noise_is_seeded_and_the_filter_calms_the_derivative() {
        let run = |filter_s: f64, seed: u64| {
            let cfg = PidConfig {
                derivative_filter_s: filter_s,
                ..PidConfig::default()
            };
            let mut lp = PidLoop::new(MassDragPlant::default(), Pid::new(cfg).unwrap(), 1.0, seed);
            lp.noise_std_m = 0.01;
            let mut d_sq = 0.0;
            let mut xs = Vec::new();
            for k in 0..5000 {
                assert!(lp.step(1e-3));
                if k >= 1000 {
                    d_sq += lp.last_terms().d * lp.last_terms().d;
                }
                xs.push(lp.state.x_m);
            }
            ((d_sq / 4000.0).sqrt(), xs)
        };
        let (raw_rms, a) = run(0.0, 7);
        let (_, b) = run(0.0, 7);
        assert_eq!(a, b, "same seed, same run");
        let (_, c) = run(0.0, 8);
        assert_ne!(a, c);
        let (filtered_rms, _) = run(0.02, 7);
        assert!(filtered_rms < 0.2 * raw_rms, "{filtered_rms} vs {raw_rms}");
    }

    #[test]
    fn standard_normal_has_unit_moments() {
        let mut rng = Lcg64::new(3);
        let n = 100_000;
        let draws: Vec<f64> = (0..n).map(|_| standard_normal(&mut rng)).collect();
        let mean = draws.iter().sum::<f64>() / n as f64;
        let var = draws.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n as f64;
        assert!(
            mean.abs() < 0.02 && (var - 1.0).abs() < 0.02,
            "{mean} {var}"
        );
    }
}
