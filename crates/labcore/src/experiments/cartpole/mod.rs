//! Experiment 8 — balancing the cart-pole with state feedback, and LQR.
//!
//! The nonlinear cart-pole of Barto, Sutton & Anderson (1983) ([`CartPole`],
//! benchmark constants: g = 9.8 m/s², cart 1.0 kg, pole 0.1 kg, half-length
//! 0.5 m, control period [`CONTROL_PERIOD_S`] = 0.02 s) is balanced by the
//! linear state feedback
//!
//! ```text
//! F = kθ·θ + kω·θ̇ + kx·x + kv·ẋ
//! ```
//!
//! with `θ = 0` upright and `θ > 0` leaning toward `+x` (a positive force
//! pushes the cart toward `+x`, under a pole leaning that way). The force is
//! computed once per control period and held (zero-order hold), clipped to
//! the force limit, while the equations are integrated in [`SUBSTEPS`]
//! sub-steps of explicit Euler (the CartPole-v1 update rule, here with four
//! sub-steps per period and end stops, so not the benchmark step for step)
//! or RK4.
//!
//! **Linear against nonlinear.** Beside the real pole, the linearised model
//! `ṡ = A s + B F` ([`LinearModel`]) runs from the same start under the same
//! feedback, the same force limit, the same integrator and the same nudges,
//! so the only difference between the two is the plant's nonlinearity
//! (`sin θ ≈ θ`, `cos θ ≈ 1`, no `θ̇²` term, no end stops). Once it leans
//! past 90° it is held where it fell (and the gap no longer grows). Its θ and x are
//! overlaid on the plots; they agree for small start angles and part as
//! the start angle grows.
//!
//! **LQR.** "LQR gains" solves the continuous algebraic Riccati equation for
//! the chosen diagonal `Q` and `R` ([`lqr_feedback`]) and puts the resulting
//! gains (rounded to 0.01) on the sliders; the proposal is shown before it
//! is applied.
//!
//! **Energy** `E = ½(M + m)ẋ² + m l ẋ θ̇ cos θ + ⅔ m l² θ̇² + m g l cos θ`
//! is plotted as its relative change `(E − E₀)/E₀` in percent; with control
//! off (and the "never" fall rule, so the pole swings through) it stays flat
//! under RK4 and climbs under Euler.
//!
//! **Rest.** A run is at rest when stepping cannot change it visibly: control
//! on, the linear closed loop stable and every state variable within
//! [`QUIET`] of zero, or control off with the pole exactly upright and still.
//! A step at rest changes nothing, so the Step button and Play agree.

use crate::control::cartpole::{
    closed_loop_eigenvalues, lqr_feedback, open_loop_eigenvalues, CartPole, CartPoleParams,
    CartPoleState, FallCriterion, Integrator, LinearModel, LqrWeights, PoleStatus, StateFeedback,
    NUDGE_RAD_S,
};
use crate::experiment::{
    check_param, ActionSpec, Experiment, Input, Notices, ParamError, ParamSpec, Sanitized, Tone,
};
use crate::memo::Memo;
use crate::plot::{Axis, Band, Plot, RefLine, Series, SeriesRole, XWindow};
use crate::quiz::{Draw, Generator};
use crate::rng::Lcg64;
use crate::units::{format_fixed, format_number};
use glam::DVec2;

const INTEGRATORS: &[&str] = &["Euler (4 sub-steps)", "RK4 (4 sub-steps)"];
const CRITERIA: &[&str] = &[
    "|θ| > 90°",
    "|θ| > 12° or |x| > 2.4 m (CartPole-v1)",
    "never (the pole swings through)",
];

const PARAMS: &[ParamSpec] = &[
    ParamSpec::slider("kth", "kθ", "N/rad", 0.0, 600.0, 0.1, 120.0),
    ParamSpec::slider("kom", "kω", "N·s/rad", 0.0, 150.0, 0.1, 18.0),
    ParamSpec::slider("kx", "kx", "N/m", -50.0, 150.0, 0.1, 3.0),
    ParamSpec::slider("kv", "kv", "N·s/m", -50.0, 150.0, 0.1, 6.0),
    ParamSpec::slider("th0", "Start angle θ₀", "°", -60.0, 60.0, 0.1, 6.0),
    ParamSpec::toggle("ctl", "Control", "off", "on", true).with_actions(),
    ParamSpec::choice("integ", "Integrator", INTEGRATORS, 0),
    ParamSpec::choice("fall", "Fallen when", CRITERIA, 0),
    ParamSpec::slider("flim", "Force limit", "N", 1.0, 100.0, 1.0, 30.0),
    // q_x > 0: with the cart position unweighted, (A, Q^½) is not detectable
    // and the Riccati equation has no stabilising solution.
    ParamSpec::slider("qx", "LQR weight q_x", "", 0.1, 100.0, 0.1, 1.0).in_group("LQR weights"),
    ParamSpec::slider("qv", "LQR weight q_ẋ", "", 0.0, 100.0, 0.1, 1.0).in_group("LQR weights"),
    ParamSpec::slider("qth", "LQR weight q_θ", "", 0.0, 100.0, 0.1, 10.0).in_group("LQR weights"),
    ParamSpec::slider("qom", "LQR weight q_θ̇", "", 0.0, 100.0, 0.1, 1.0).in_group("LQR weights"),
    ParamSpec::slider("r", "LQR weight R", "", 0.01, 10.0, 0.01, 0.1).in_group("LQR weights"),
];

const ACTIONS: &[ActionSpec] = &[
    ActionSpec {
        key: "nudge",
        label: "Nudge pole",
    },
    ActionSpec {
        key: "drop",
        label: "Drop pole (control off)",
    },
    ActionSpec {
        key: "lqr",
        label: "LQR gains",
    },
];

/// Control period: the force is recomputed and held this long (s), as in CartPole-v1.
pub const CONTROL_PERIOD_S: f64 = 0.02;
/// Integration sub-steps per control period.
pub const SUBSTEPS: u32 = 4;
/// The plots show the last 20 s and keep the last [`KEEP_S`].
const WINDOW_S: f64 = 20.0;
/// Seconds of samples kept for the plots and their CSV.
pub const KEEP_S: f64 = 60.0;
/// Balanced: everything this close to zero (rad, rad/s, m, m/s) with control on.
const QUIET: f64 = 1e-4;
/// The status judges the last this many seconds of the run.
const STATUS_WINDOW_S: f64 = 3.0;
/// "Balancing" needs |θ| within this over [`STATUS_WINDOW_S`] (°)…
const SWING_DEG: f64 = 8.0;
/// …and |x| within this (m).
const DRIFT_M: f64 = 1.0;
/// The energy plot spans at least ± this (%), so round-off never fills it.
const ENERGY_MIN_SPAN_PCT: f64 = 0.1;

/// Height of the pole's pivot above the track, metres (where the pole
/// tip is found for a grab, and where the view draws the cart's top).
const PIVOT_Y_M: f64 = 0.3;
/// A pointer this close to the pole tip grabs it (m).
const GRAB_M: f64 = 0.2;

/// Whether the run is going on or has ended.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Run {
    Going,
    /// Fallen or off the track at this time (s).
    Ended {
        status: PoleStatus,
        time_s: f64,
    },
}

/// State of the cart-pole experiment.
#[derive(Clone, Debug)]
pub struct CartPoleBalance {
    sim: CartPole,
    /// The linearised model from the same start.
    linear: CartPoleState,
    linear_force_n: f64,
    model: LinearModel,
    start_deg: f64,
    fall_choice: usize,
    weights: LqrWeights,
    run: Run,
    pending_s: f64,
    /// Largest |θ_linear − θ| so far (rad).
    max_gap_rad: f64,
    /// Energy at the start of the run (J).
    start_energy_j: f64,
    dragging: bool,
    notices: Notices,
    /// θ (nonlinear and linear), x (both), force, energy change.
    plots: [Plot; 4],
    /// Whether the closed loop is stable, for the last parameters and gains
    /// asked: a step at rest needs it and they rarely change.
    stable: Memo<(CartPoleParams, StateFeedback), bool>,
}

fn new_plots() -> [Plot; 4] {
    let time = ("Time", "s");
    let live = |p: Plot| Plot {
        window: XWindow::Rolling(WINDOW_S),
        ..p
    };
    [
        live(Plot::new(
            "angle",
            "Pole angle",
            time,
            ("θ", "°"),
            vec![
                Series::new("θ (nonlinear)", "°", SeriesRole::Primary),
                Series::new("θ (linear model)", "°", SeriesRole::Reference),
            ],
        )),
        live(Plot::new(
            "position",
            "Cart position",
            time,
            ("x", "m"),
            vec![
                Series::new("x (nonlinear)", "m", SeriesRole::Secondary),
                Series::new("x (linear model)", "m", SeriesRole::Reference),
            ],
        )),
        live(Plot::new(
            "force",
            "Force on the cart",
            time,
            ("F", "N"),
            vec![Series::new("F", "N", SeriesRole::Tertiary)],
        )),
        live(Plot::new(
            "energy",
            "Energy change (E − E₀)/E₀",
            time,
            ("ΔE/E₀", "%"),
            vec![Series::new("(E − E₀)/E₀", "%", SeriesRole::Quaternary)],
        )),
    ]
}

impl Default for CartPoleBalance {
    fn default() -> Self {
        let mut sim = CartPole::new(CartPoleState::default());
        sim.substeps = SUBSTEPS;
        let mut exp = Self {
            model: LinearModel::of(&sim.params),
            sim,
            linear: CartPoleState::default(),
            linear_force_n: 0.0,
            start_deg: PARAMS[4].default,
            fall_choice: PARAMS[7].default as usize,
            weights: LqrWeights {
                q: [
                    PARAMS[9].default,
                    PARAMS[10].default,
                    PARAMS[11].default,
                    PARAMS[12].default,
                ],
                r: PARAMS[13].default,
            },
            run: Run::Going,
            pending_s: 0.0,
            max_gap_rad: 0.0,
            start_energy_j: 0.0,
            dragging: false,
            notices: Notices::default(),
            plots: new_plots(),
            stable: Memo::default(),
        };
        exp.sim.gains = StateFeedback {
            k_theta: PARAMS[0].default,
            k_omega: PARAMS[1].default,
            k_x: PARAMS[2].default,
            k_v: PARAMS[3].default,
        };
        exp.sim.params.force_limit_n = PARAMS[8].default;
        exp.restart();
        exp
    }
}

/// The linear model is still up (|θ| ≤ 90°); past that it is held.
fn linear_up(s: &CartPoleState) -> bool {
    s.theta_rad.abs() <= std::f64::consts::FRAC_PI_2
}

/// Rounds a gain to the sliders' 0.01 and keeps it in its range.
fn slider_value(key: &str, v: f64) -> f64 {
    let rounded = (v * 100.0).round() / 100.0;
    crate::experiment::find_spec(PARAMS, key).map_or(rounded, |s| rounded.clamp(s.min, s.max))
}

impl CartPoleBalance {
    /// The start state: the pole at θ₀, everything else at rest.
    fn initial(&self) -> CartPoleState {
        CartPoleState {
            theta_rad: self.start_deg.to_radians(),
            ..CartPoleState::default()
        }
    }

    /// The nonlinear state.
    #[must_use]
    pub fn state(&self) -> CartPoleState {
        self.sim.state
    }

    /// The linear model's state.
    #[must_use]
    pub fn linear_state(&self) -> CartPoleState {
        self.linear
    }

    /// Simulated time of the run (s).
    #[must_use]
    pub fn time_s(&self) -> f64 {
        self.sim.time_s
    }

    /// The feedback gains in use.
    #[must_use]
    pub fn gains(&self) -> StateFeedback {
        self.sim.gains
    }

    /// Largest `|θ_linear − θ|` since the start (rad).
    #[must_use]
    pub fn max_gap_rad(&self) -> f64 {
        self.max_gap_rad
    }

    /// The LQR gains for the current weights, rounded and clamped as the
    /// sliders hold them, or `None` when the Riccati solver fails.
    #[must_use]
    pub fn lqr_proposal(&self) -> Option<StateFeedback> {
        let (k, _) = lqr_feedback(&self.sim.params, &self.weights).ok()?;
        Some(StateFeedback {
            k_theta: slider_value("kth", k.k_theta),
            k_omega: slider_value("kom", k.k_omega),
            k_x: slider_value("kx", k.k_x),
            k_v: slider_value("kv", k.k_v),
        })
    }

    fn criterion(&self) -> FallCriterion {
        match self.fall_choice {
            1 => FallCriterion::benchmark(),
            2 => FallCriterion {
                angle_limit_rad: f64::INFINITY,
                x_limit_m: f64::INFINITY,
            },
            _ => FallCriterion::horizontal(),
        }
    }

    /// Back to θ₀ at rest, time 0, plots cleared.
    fn restart(&mut self) {
        let s0 = self.initial();
        self.sim.reset(s0);
        self.sim.criterion = self.criterion();
        self.linear = s0;
        self.linear_force_n = 0.0;
        self.run = Run::Going;
        self.pending_s = 0.0;
        self.max_gap_rad = 0.0;
        self.start_energy_j = self.sim.energy_j();
        self.plots.iter_mut().for_each(|p| {
            p.clear();
            p.bands.clear();
        });
        let lim = self.sim.params.force_limit_n;
        self.plots[2].ref_lines = vec![
            RefLine {
                axis: Axis::Y,
                value: lim,
                label: "+F_max".into(),
            },
            RefLine {
                axis: Axis::Y,
                value: -lim,
                label: "−F_max".into(),
            },
        ];
        self.plots[3].ref_lines = vec![RefLine {
            axis: Axis::Y,
            value: 0.0,
            label: "E = E₀".into(),
        }];
        self.plots[3].bands = vec![Band {
            axis: Axis::Y,
            lo: -ENERGY_MIN_SPAN_PCT,
            hi: ENERGY_MIN_SPAN_PCT,
            label: format!("within ±{ENERGY_MIN_SPAN_PCT} % of E₀"),
        }];
        self.notices.clear();
        self.record(false);
        self.check_status();
    }

    /// Appends the current sample to every plot and drops samples older than [`KEEP_S`].
    fn record(&mut self, saturated: bool) {
        let t = self.sim.time_s;
        let s = self.sim.state;
        let energy_pct = self.energy_change_pct();
        let [angle, position, force, energy] = &mut self.plots;
        angle.series[0].push(t, s.theta_rad.to_degrees());
        angle.series[1].push(t, self.linear.theta_rad.to_degrees());
        position.series[0].push(t, s.x_m);
        position.series[1].push(t, self.linear.x_m);
        force.series[0].push(t, self.sim.last_force_n());
        energy.series[0].push(t, energy_pct);
        if saturated {
            let from = t - CONTROL_PERIOD_S;
            match force.bands.last_mut() {
                Some(b) if (b.hi - from).abs() < 1e-9 => b.hi = t,
                _ => force.bands.push(Band {
                    axis: Axis::X,
                    lo: from,
                    hi: t,
                    label: "at the force limit".into(),
                }),
            }
        }
        let oldest = t - KEEP_S;
        for plot in &mut self.plots {
            // Trim in batches of a second, so each sample moves rarely.
            plot.forget_before(oldest, 1.0);
            plot.touch();
        }
    }

    fn check_status(&mut self) {
        if self.run != Run::Going {
            return;
        }
        let status = self.sim.status();
        if status != PoleStatus::Up {
            self.run = Run::Ended {
                status,
                time_s: self.sim.time_s,
            };
        }
    }

    /// One control period of both models.
    fn control_step(&mut self) {
        let before = self.sim.clone();
        if !self.sim.step(CONTROL_PERIOD_S) {
            self.sim = before;
            self.run = Run::Ended {
                status: PoleStatus::Fallen,
                time_s: self.sim.time_s,
            };
            return;
        }
        let lim = self.sim.params.force_limit_n;
        let force = if self.sim.control_enabled {
            self.sim.gains.force_n(&self.linear).clamp(-lim, lim)
        } else {
            0.0
        };
        // The linear model stops where it has fallen: past 90° its
        // small-angle picture means nothing (and it would grow without bound).
        if linear_up(&self.linear) {
            let mut linear = self.linear;
            if self.model.integrate(
                &mut linear,
                force,
                CONTROL_PERIOD_S,
                self.sim.integrator,
                SUBSTEPS,
            ) {
                self.linear = linear;
                self.linear_force_n = force;
            }
            let gap = (self.linear.theta_rad - self.sim.state.theta_rad).abs();
            if gap.is_finite() {
                self.max_gap_rad = self.max_gap_rad.max(gap);
            }
        }
        self.record(self.sim.last_saturated());
        self.check_status();
    }

    /// A push on the pole: `±`[`NUDGE_RAD_S`] added to θ̇ of both models.
    fn nudge(&mut self, direction: f64) {
        if direction == 0.0 || !direction.is_finite() {
            return;
        }
        if self.run != Run::Going {
            self.notices.post(
                "the run has ended: press Reset to start again",
                Tone::Warning,
            );
            return;
        }
        let dw = NUDGE_RAD_S.copysign(direction);
        self.sim.nudge(dw);
        self.linear.omega_rad_s += dw;
    }

    fn pivot(&self) -> DVec2 {
        DVec2::new(self.sim.state.x_m, PIVOT_Y_M)
    }

    fn tip_of(&self, s: &CartPoleState) -> DVec2 {
        let (sin, cos) = crate::math::sin_cos(s.theta_rad);
        let len = 2.0 * self.sim.params.half_length_m;
        DVec2::new(s.x_m + len * sin, PIVOT_Y_M + len * cos)
    }

    /// Sets the start angle from a pointer dragging the tip (0.1° steps, in range).
    fn drag_tip(&mut self, p: DVec2) {
        let d = p - self.pivot();
        if !d.is_finite() || d.length() < 1e-6 {
            return;
        }
        let deg = crate::math::atan2(d.x, d.y).to_degrees();
        let spec = &PARAMS[4];
        let deg = ((deg * 10.0).round() / 10.0).clamp(spec.min, spec.max);
        let _ = self.set_param("th0", deg);
    }

    /// `(E − E₀)/E₀` in percent (E₀ = m g l cos θ₀ > 0 for |θ₀| ≤ 60°).
    fn energy_change_pct(&self) -> f64 {
        let e0 = self.start_energy_j;
        if e0.abs() < 1e-12 {
            return 0.0;
        }
        100.0 * (self.sim.energy_j() - e0) / e0
    }

    /// Nothing can change visibly: control on, a stable linear closed loop and
    /// both models within [`QUIET`] of upright at the centre; or control off
    /// with the pole exactly upright and everything still (an unstable
    /// equilibrium that only a nudge disturbs).
    fn at_rest(&self) -> bool {
        let s = self.sim.state;
        if !self.sim.control_enabled {
            let l = self.linear;
            return s.theta_rad == 0.0
                && s.omega_rad_s == 0.0
                && s.v_m_s == 0.0
                && l.theta_rad == 0.0
                && l.omega_rad_s == 0.0
                && l.v_m_s == 0.0;
        }
        let small = |c: &CartPoleState| c.to_array().iter().all(|v| v.abs() < QUIET);
        // A linear model held where it fell does not move either.
        small(&s)
            && (small(&self.linear) || !linear_up(&self.linear))
            && self
                .stable
                .get((self.sim.params, self.sim.gains), |(params, gains)| {
                    closed_loop_eigenvalues(&params, &gains)
                        .is_ok_and(|z| z.iter().all(|p| p.re < 0.0))
                })
    }

    /// Largest `|θ|` (°, judged within (−180°, 180°]) and `|x|` (m) over the
    /// last [`STATUS_WINDOW_S`], and whether the pole is still being caught
    /// from its start angle. The catch lasts from the start of the run until
    /// `|θ|` first comes within [`SWING_DEG`], as long as the pole leans no
    /// further than it started; the leaning of the catch does not count as
    /// swinging afterwards.
    fn recent_peaks(&self) -> (f64, f64, bool) {
        let (angle, position) = (&self.plots[0].series[0], &self.plots[1].series[0]);
        let lean = |v: &f64| wrap_deg(*v).abs();
        let mut from = self.sim.time_s - STATUS_WINDOW_S - 1e-9;
        let mut catching = false;
        if angle.x.first() == Some(&0.0) {
            match angle.y.iter().position(|v| lean(v) <= SWING_DEG) {
                Some(i) => from = from.max(angle.x[i]),
                None => {
                    let start = self.start_deg.abs() + 1e-6;
                    catching = angle.y.iter().all(|v| lean(v) <= start);
                }
            }
        }
        let peak = |series: &Series, f: &dyn Fn(&f64) -> f64| {
            series
                .x
                .iter()
                .zip(&series.y)
                .rev()
                .take_while(|(t, _)| **t >= from)
                .fold(0.0_f64, |m, (_, v)| m.max(f(v)))
        };
        (
            peak(angle, &lean),
            peak(position, &|v: &f64| v.abs()),
            catching,
        )
    }
}

/// The four gains as a notice and the LQR readout word them:
/// `kθ 12.00, kω 3.00, kx 1.00, kv 2.00`.
fn gains_text(k: &StateFeedback) -> String {
    format!(
        "kθ {}, kω {}, kx {}, kv {}",
        format_fixed(k.k_theta, 2),
        format_fixed(k.k_omega, 2),
        format_fixed(k.k_x, 2),
        format_fixed(k.k_v, 2)
    )
}

/// An angle in degrees wrapped into `(−180°, 180°]`.
fn wrap_deg(deg: f64) -> f64 {
    let w = deg.rem_euclid(360.0);
    if w > 180.0 {
        w - 360.0
    } else {
        w
    }
}

mod quiz;
#[cfg(test)]
mod tests;
mod view;

pub use quiz::quiz_generator;

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "Too soft: the pole is lost",
        description: "kθ = 15, below the stability limit: the pole swings wider each time and falls within seconds.",
        query: "kth=15",
    },
    crate::experiment::Preset {
        name: "Control off",
        description: "No controller: the pole, started 6° off upright, falls over.",
        query: "ctl=0",
    },
];

impl Experiment for CartPoleBalance {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

    fn id(&self) -> &'static str {
        "cartpole"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        let g = self.sim.gains;
        Some(match key {
            "kth" => g.k_theta,
            "kom" => g.k_omega,
            "kx" => g.k_x,
            "kv" => g.k_v,
            "th0" => self.start_deg,
            "ctl" => f64::from(u8::from(self.sim.control_enabled)),
            "integ" => match self.sim.integrator {
                Integrator::Euler => 0.0,
                Integrator::Rk4 => 1.0,
            },
            "fall" => self.fall_choice as f64,
            "flim" => self.sim.params.force_limit_n,
            "qx" => self.weights.q[0],
            "qv" => self.weights.q[1],
            "qth" => self.weights.q[2],
            "qom" => self.weights.q[3],
            "r" => self.weights.r,
            _ => return None,
        })
    }

    /// Gains, control, criterion and force limit act on the running pole;
    /// the start angle and the integrator restart the run; the LQR weights
    /// only change the proposal until "LQR gains" is pressed.
    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        match key {
            "kth" => self.sim.gains.k_theta = v,
            "kom" => self.sim.gains.k_omega = v,
            "kx" => self.sim.gains.k_x = v,
            "kv" => self.sim.gains.k_v = v,
            "th0" => {
                self.start_deg = v;
                self.restart();
            }
            "ctl" => self.sim.control_enabled = v >= 0.5,
            "integ" => {
                self.sim.integrator = if v >= 0.5 {
                    Integrator::Rk4
                } else {
                    Integrator::Euler
                };
                self.restart();
            }
            "fall" => {
                self.fall_choice = v as usize;
                self.sim.criterion = self.criterion();
                self.check_status();
            }
            "flim" => {
                self.sim.params.force_limit_n = v;
                for line in &mut self.plots[2].ref_lines {
                    line.value = v.copysign(line.value);
                }
                self.plots[2].touch();
            }
            "qx" => self.weights.q[0] = v,
            "qv" => self.weights.q[1] = v,
            "qth" => self.weights.q[2] = v,
            "qom" => self.weights.q[3] = v,
            "r" => self.weights.r = v,
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        Ok(applied)
    }

    fn actions(&self) -> &'static [ActionSpec] {
        ACTIONS
    }

    fn action(&mut self, key: &str) -> Result<(), ParamError> {
        match key {
            "nudge" => self.nudge(1.0),
            "drop" => self.sim.control_enabled = false,
            "lqr" => match self.lqr_proposal() {
                Some(k) => {
                    self.sim.gains = k;
                    self.notices
                        .post(format!("LQR gains applied: {}", gains_text(&k)), Tone::Good);
                }
                None => self.notices.post(
                    "no stabilising LQR solution for these weights: weight the cart position",
                    Tone::Warning,
                ),
            },
            _ => return Err(ParamError::UnknownAction { key: key.into() }),
        }
        Ok(())
    }

    /// Press on the pole tip and drag to set the start angle; a tap
    /// elsewhere nudges the pole toward the tap's side; arrow keys nudge it.
    fn input(&mut self, input: Input) {
        match input {
            Input::PointerDown(p) => {
                if !p.is_finite() {
                    return;
                }
                if self.handle_at(p, GRAB_M) {
                    self.dragging = true;
                    self.drag_tip(p);
                } else {
                    self.nudge(p.x - self.pivot().x);
                }
            }
            Input::PointerMove { pos, pressed: true } if self.dragging => self.drag_tip(pos),
            Input::PointerMove { .. } => {}
            Input::PointerUp(_) => self.dragging = false,
            Input::Nudge(d) => self.nudge(d.x),
        }
    }

    /// A step at rest changes nothing (see [`CartPoleBalance::animating`]), so
    /// single steps and a running clock agree.
    fn step(&mut self, dt_s: f64) {
        if !crate::clock::valid_dt(dt_s) || self.run != Run::Going || self.at_rest() {
            return;
        }
        self.pending_s += dt_s;
        let n = ((self.pending_s + 1e-9) / CONTROL_PERIOD_S).floor();
        self.pending_s = (self.pending_s - n * CONTROL_PERIOD_S).max(0.0);
        for _ in 0..n as u64 {
            self.control_step();
            if self.run != Run::Going {
                break;
            }
        }
    }

    fn animated(&self) -> bool {
        true
    }

    /// The pole back at θ₀, at rest (parameters and gains kept).
    fn reset(&mut self) {
        self.restart();
    }

    fn plots(&self) -> &[Plot] {
        &self.plots
    }

    /// The pole's tip (drag it to set the start angle).
    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        (self.tip_of(&self.sim.state) - p).length() <= tolerance_m
    }

    /// The pole's tip (dragging it sets the start angle).
    fn handles(&self) -> Vec<crate::experiment::Handle> {
        vec![crate::experiment::Handle::new(
            "tip",
            "Pole tip",
            self.tip_of(&self.sim.state),
        )]
    }

    fn animating(&self) -> bool {
        self.run == Run::Going && !self.at_rest()
    }
}
