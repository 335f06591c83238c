//! Experiment 7 — PID position control of a mass with viscous drag.
//!
//! A cart of mass `m` on a level track, with drag `c` and an optional
//! constant disturbance force `d`, is driven toward the setpoint `r` by the
//! PID law of [`crate::control::pid`]:
//!
//! ```text
//! m·ẍ = u + d − c·ẋ,    u = Kp·e + Ki·∫e dt + Kd·de/dt,    e = r − x
//! ```
//!
//! **The run.** Each run is one step response: the controller has been
//! holding the cart at rest at `x = 0` with setpoint 0, and at `t = 0` the
//! setpoint steps to `r`. The controller samples every [`CONTROL_PERIOD_S`]
//! (600 Hz, ten updates per frame of the shell's 60 Hz clock) and the plant
//! is integrated over each period with the force held (RK4). Because the
//! controller already has a previous sample when the step arrives, a
//! derivative taken on the error sees the jump: the *derivative kick*
//! (an impulse `Kd·r`), which the derivative-on-measurement option removes
//! (Åström & Hägglund, *Advanced PID Control*, 2006, §3.4).
//!
//! **Metrics** follow python-control's `step_info` ([`step_info`]): 10→90 %
//! rise time, ±2 % settling time, overshoot in percent of the step, peak and
//! peak time, all measured on the recorded samples (every
//! [`RECORD_PERIOD_S`]), so times are exact to one record period. The
//! steady-state value is the linear loop's final value (see
//! [`PidControl::final_value_m`]), not the last sample, so the metrics are
//! meaningful while the run is still going.
//!
//! **Closed-loop poles** are the roots of `m s³ + (c + Kd) s² + Kp s + Ki`
//! ([`closed_loop_poles`]); with `Ki = 0` the loop is second order with
//! `ωn = √(Kp/m)` and `ζ = (c + Kd)/(2√(m·Kp))` ([`SecondOrder`]; Åström &
//! Murray, *Feedback Systems*, 2nd ed., 2021, §7.3).
//!
//! **Pinned runs.** "Pin run" keeps the current response, its gains and
//! its metrics; up to [`MAX_PINS`] pinned responses are overlaid on the
//! response plot (the oldest is replaced by a fifth) and listed as readouts,
//! one per slot A–D. The plot always holds the four slot series (empty
//! until used): the page draws a plot's legend once, from the series it
//! starts with, so the series set of a plot never changes.

use crate::control::pid::{
    closed_loop_poles, MassDragPlant, Pid, PidConfig, PidGains, PidLoop, SecondOrder,
};
use crate::control::step_info::{step_info, StepInfo, SETTLING_THRESHOLD};
use crate::control::{Complex, Stability};
use crate::experiment::{
    check_param, format_fixed, format_metres, ActionSpec, Experiment, Input, ParamError, ParamSpec,
    Readout, Sanitized, Status, Tone,
};
use crate::plot::{Axis, Band, Marker, Plot, RefLine, Series, SeriesRole, XWindow};
use crate::quiz::{format_number, Draw, Generator};
use crate::rng::Lcg64;
use crate::scene::{Item, Role, Scene, ViewBox};
use glam::DVec2;

const PARAMS: &[ParamSpec] = &[
    ParamSpec::slider("kp", "Kp", "N/m", 0.0, 100.0, 0.5, 12.0),
    ParamSpec::slider("ki", "Ki", "N/(m·s)", 0.0, 50.0, 0.1, 2.0),
    ParamSpec::slider("kd", "Kd", "N·s/m", 0.0, 40.0, 0.1, 6.0),
    ParamSpec::slider("r", "Setpoint r", "m", -2.0, 2.0, 0.01, 1.0),
    ParamSpec::slider("c", "Drag c", "N·s/m", 0.0, 10.0, 0.1, 1.0),
    ParamSpec::slider("m", "Mass m", "kg", 0.2, 10.0, 0.1, 1.0),
    ParamSpec::slider("d", "Disturbance d", "N", -10.0, 10.0, 0.1, 0.0),
    ParamSpec::toggle("dmeas", "Derivative on", "error", "measurement", true),
    ParamSpec::toggle("sat", "Actuator limit", "off", "on", false),
    ParamSpec::slider("umax", "Force limit", "N", 1.0, 100.0, 1.0, 20.0),
    ParamSpec::slider("ilim", "Integral clamp", "m·s", 0.1, 20.0, 0.1, 5.0),
    ParamSpec::slider("noise", "Sensor noise σ", "m", 0.0, 0.05, 0.001, 0.0),
    ParamSpec::slider("tf", "D filter T_f", "s", 0.0, 0.5, 0.01, 0.0),
    ParamSpec::number("seed", "Noise seed", 0.0, 999_999.0, 1.0),
];

const ACTIONS: &[ActionSpec] = &[
    ActionSpec {
        key: "step",
        label: "Step setpoint",
    },
    ActionSpec {
        key: "pin",
        label: "Pin run",
    },
    ActionSpec {
        key: "clear_pins",
        label: "Clear pins",
    },
];

/// Controller sample period and plant integration step, seconds (600 Hz).
pub const CONTROL_PERIOD_S: f64 = 1.0 / 600.0;
/// Control updates per recorded sample.
const UPDATES_PER_RECORD: u64 = 6;
/// Recorded sample period, seconds (100 Hz).
pub const RECORD_PERIOD_S: f64 = CONTROL_PERIOD_S * UPDATES_PER_RECORD as f64;
/// Longest recorded response, seconds; the run ends there.
pub const RECORD_S: f64 = 30.0;
/// The run ends early once the cart has been this close to its final value
/// (fraction of the step, and at least [`QUIET_MIN_M`]) and this slow for
/// [`QUIET_S`] seconds, with no sensor noise.
const QUIET_FRACTION: f64 = 1e-3;
const QUIET_MIN_M: f64 = 1e-4;
const QUIET_S: f64 = 1.0;
/// The run is stopped as diverged when the cart is this far out, metres.
pub const DIVERGED_M: f64 = 20.0;
/// At most this many pinned runs.
pub const MAX_PINS: usize = 4;
/// The roles pinned runs are drawn with, in order of use.
const PIN_ROLES: [SeriesRole; MAX_PINS] = [
    SeriesRole::Secondary,
    SeriesRole::Tertiary,
    SeriesRole::Quaternary,
    SeriesRole::Reference,
];

/// The series names of the four pin slots.
const PIN_NAMES: [&str; MAX_PINS] = [
    "pinned run A",
    "pinned run B",
    "pinned run C",
    "pinned run D",
];

/// World rectangle of the canvas (metres): the track from −2.6 m to 2.6 m.
const VIEW_MIN: DVec2 = DVec2::new(-2.6, -0.7);
const VIEW_MAX: DVec2 = DVec2::new(2.6, 1.3);
/// Cart body half-width and height, metres.
const CART_HALF_W_M: f64 = 0.22;
const CART_BOTTOM_M: f64 = 0.08;
const CART_TOP_M: f64 = 0.34;
/// Height of the setpoint marker's handle, metres.
const MARKER_TOP_M: f64 = 0.85;
/// Force arrow length per newton, metres, and its longest drawn length.
const ARROW_M_PER_N: f64 = 0.04;
const ARROW_MAX_M: f64 = 1.2;

/// Why the current run stopped, if it did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum RunState {
    Running,
    /// Near the final value and at rest: nothing more to see.
    Quiet,
    /// The full [`RECORD_S`] recorded.
    Complete,
    /// Ran off the track or produced non-finite numbers.
    Diverged,
}

/// Sums over one record period of the controller's terms.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct TermSums {
    u: f64,
    p: f64,
    i: f64,
    d: f64,
    count: u32,
    saturated: bool,
}

/// One pinned response: the gains it ran with and its metrics.
#[derive(Clone, Debug, PartialEq)]
pub struct Pin {
    /// Its slot, 0–3: the series "pinned run A"–"D" of the response plot.
    pub slot: usize,
    /// 1, 2, 3, … in the order pinned.
    pub number: usize,
    pub gains: PidGains,
    /// The metrics when it was pinned (`None` when undefined, e.g. unstable).
    pub info: Option<StepInfo>,
    /// Time since the step when it was pinned (s).
    pub time_s: f64,
    /// Whether the run had ended (settled, complete or diverged) when pinned;
    /// otherwise its metrics are those of the response so far.
    pub finished: bool,
}

impl Pin {
    /// `Kp 12 · Ki 2 · Kd 6`.
    #[must_use]
    pub fn gains_text(&self) -> String {
        gains_text(&self.gains)
    }
}

fn gains_text(g: &PidGains) -> String {
    format!(
        "Kp {} · Ki {} · Kd {}",
        format_number(g.kp, 2),
        format_number(g.ki, 2),
        format_number(g.kd, 2)
    )
}

/// State of the PID experiment.
#[derive(Clone, Debug)]
pub struct PidControl {
    gains: PidGains,
    setpoint_m: f64,
    plant: MassDragPlant,
    disturbance_n: f64,
    derivative_on_measurement: bool,
    saturation: bool,
    force_limit_n: f64,
    integral_limit_m_s: f64,
    noise_std_m: f64,
    filter_s: f64,
    seed: u64,
    run: PidLoop,
    /// Shell time not yet spent on control updates, seconds.
    pending_s: f64,
    /// Control updates since the step.
    updates: u64,
    sums: TermSums,
    state: RunState,
    quiet_samples: u32,
    info: Option<StepInfo>,
    pins: Vec<Pin>,
    pins_made: usize,
    /// Response (position and pinned runs) and control effort.
    plots: [Plot; 2],
}

fn new_plots() -> [Plot; 2] {
    let response = Plot {
        window: XWindow::All,
        ..Plot::new(
            "response",
            "Step response",
            ("Time since step", "s"),
            ("Position", "m"),
            std::iter::once(Series::new("position x", "m", SeriesRole::Primary))
                .chain(
                    PIN_NAMES
                        .iter()
                        .zip(PIN_ROLES)
                        .map(|(name, role)| Series::new(*name, "m", role)),
                )
                .collect(),
        )
    };
    let effort = Plot {
        window: XWindow::All,
        ..Plot::new(
            "effort",
            "Control effort and its terms",
            ("Time since step", "s"),
            ("Force", "N"),
            vec![
                Series::new("u (applied)", "N", SeriesRole::Primary),
                Series::new("P = Kp·e", "N", SeriesRole::Secondary),
                Series::new("I = Ki·∫e", "N", SeriesRole::Tertiary),
                Series::new("D = Kd·de/dt", "N", SeriesRole::Quaternary),
            ],
        )
    };
    [response, effort]
}

impl Default for PidControl {
    fn default() -> Self {
        let mut exp = Self {
            gains: PidGains {
                kp: PARAMS[0].default,
                ki: PARAMS[1].default,
                kd: PARAMS[2].default,
            },
            setpoint_m: PARAMS[3].default,
            plant: MassDragPlant {
                mass_kg: PARAMS[5].default,
                drag_n_s_per_m: PARAMS[4].default,
            },
            disturbance_n: PARAMS[6].default,
            derivative_on_measurement: PARAMS[7].default >= 0.5,
            saturation: PARAMS[8].default >= 0.5,
            force_limit_n: PARAMS[9].default,
            integral_limit_m_s: PARAMS[10].default,
            noise_std_m: PARAMS[11].default,
            filter_s: PARAMS[12].default,
            seed: PARAMS[13].default as u64,
            run: PidLoop::new(MassDragPlant::default(), Pid::default(), 0.0, 0),
            pending_s: 0.0,
            updates: 0,
            sums: TermSums::default(),
            state: RunState::Running,
            quiet_samples: 0,
            info: None,
            pins: Vec::new(),
            pins_made: 0,
            plots: new_plots(),
        };
        exp.restart();
        exp
    }
}

impl PidControl {
    /// The controller settings the sliders describe.
    #[must_use]
    pub fn config(&self) -> PidConfig {
        PidConfig {
            gains: self.gains,
            integral_limit_m_s: self.integral_limit_m_s,
            derivative_on_measurement: self.derivative_on_measurement,
            derivative_filter_s: self.filter_s,
            output_limit_n: if self.saturation {
                self.force_limit_n
            } else {
                f64::INFINITY
            },
        }
    }

    /// The cart's position, metres.
    #[must_use]
    pub fn position_m(&self) -> f64 {
        self.run.state.x_m
    }

    /// Time since the step, seconds.
    #[must_use]
    pub fn time_s(&self) -> f64 {
        self.updates as f64 * CONTROL_PERIOD_S
    }

    /// The step-response metrics so far (`None` while undefined).
    #[must_use]
    pub fn metrics(&self) -> Option<StepInfo> {
        self.info
    }

    /// The pinned runs, oldest first.
    #[must_use]
    pub fn pins(&self) -> &[Pin] {
        &self.pins
    }

    /// The steady-state position of the linear loop (no saturation), or
    /// `None` when it has none: an unstable or marginal loop, no
    /// proportional or integral action to hold the cart, or a disturbance
    /// the force limit cannot balance.
    ///
    /// At rest the drag vanishes, so the controller's force must cancel the
    /// disturbance: `Kp·e + Ki·I + d = 0`. With integral action and
    /// `|d/Ki| ≤ I_max` the integral does it alone and `y∞ = r`; when the
    /// clamp stops it at `I = ∓I_max` the rest is left to `Kp`:
    /// `y∞ = r + (d + Ki·I)/Kp`. Without integral action `y∞ = r + d/Kp`.
    #[must_use]
    pub fn final_value_m(&self) -> Option<f64> {
        let g = self.gains;
        let poles = closed_loop_poles(&self.plant, &g).ok()?;
        if poles.stability != Stability::Stable {
            return None;
        }
        if self.saturation && self.disturbance_n.abs() > self.force_limit_n {
            return None;
        }
        let i_term = if g.ki > 0.0 {
            let lim = self.integral_limit_m_s;
            g.ki * (-self.disturbance_n / g.ki).clamp(-lim, lim)
        } else {
            0.0
        };
        let residual = self.disturbance_n + i_term;
        if residual.abs() <= 1e-12 * self.disturbance_n.abs().max(1.0) {
            Some(self.setpoint_m)
        } else if g.kp > 0.0 {
            Some(self.setpoint_m + residual / g.kp)
        } else {
            None
        }
    }

    /// Back to the start of the step: cart at rest at 0, controller primed
    /// with one sample at setpoint 0 (so a derivative on the error sees the
    /// step), plots of the run cleared (pins kept).
    fn restart(&mut self) {
        let controller = match Pid::new(self.config()) {
            Ok(c) => c,
            // Every slider value gives a valid configuration; keep the old one otherwise.
            Err(_) => self.run.controller.clone(),
        };
        let mut run = PidLoop::new(self.plant, controller, self.setpoint_m, self.seed);
        run.disturbance_n = self.disturbance_n;
        run.noise_std_m = self.noise_std_m;
        run.controller.reset();
        let _ = run.controller.update(0.0, 0.0, CONTROL_PERIOD_S);
        self.run = run;
        self.pending_s = 0.0;
        self.updates = 0;
        self.sums = TermSums::default();
        self.state = RunState::Running;
        self.quiet_samples = 0;
        self.info = None;
        let y_final = self.final_value_m();
        let [response, effort] = &mut self.plots;
        let position = &mut response.series[0];
        position.x.clear();
        position.y.clear();
        position.push(0.0, 0.0);
        response.markers.clear();
        response.ref_lines = vec![RefLine {
            axis: Axis::Y,
            value: self.setpoint_m,
            label: "setpoint r".into(),
        }];
        let span = y_final.map(|y| y.abs()).unwrap_or(0.0);
        response.bands = match y_final {
            Some(y) if span > 0.0 => vec![Band {
                axis: Axis::Y,
                lo: y - SETTLING_THRESHOLD * span,
                hi: y + SETTLING_THRESHOLD * span,
                label: "±2 % band".into(),
            }],
            _ => Vec::new(),
        };
        response.touch();
        effort.clear();
        effort.bands.clear();
        effort.ref_lines = if self.saturation {
            vec![
                RefLine {
                    axis: Axis::Y,
                    value: self.force_limit_n,
                    label: "+u_max".into(),
                },
                RefLine {
                    axis: Axis::Y,
                    value: -self.force_limit_n,
                    label: "−u_max".into(),
                },
            ]
        } else {
            Vec::new()
        };
    }

    /// One control update; records a sample every [`UPDATES_PER_RECORD`].
    fn update(&mut self) {
        if !self.run.step(CONTROL_PERIOD_S) || !self.run.state.x_m.is_finite() {
            self.state = RunState::Diverged;
            return;
        }
        self.updates += 1;
        let terms = self.run.last_terms();
        let s = &mut self.sums;
        s.u += terms.output;
        s.p += terms.p;
        s.i += terms.i;
        s.d += terms.d;
        s.count += 1;
        s.saturated |= terms.saturated;
        if u64::from(s.count) == UPDATES_PER_RECORD {
            self.record();
        }
        if self.run.state.x_m.abs() > DIVERGED_M {
            self.state = RunState::Diverged;
        } else if self.time_s() >= RECORD_S - 1e-9 {
            self.state = RunState::Complete;
        }
    }

    /// Appends the position and the period's mean force terms (a mean keeps
    /// the impulse of a derivative kick visible however short it is).
    fn record(&mut self) {
        let t = self.time_s();
        let x = self.run.state.x_m;
        let sums = std::mem::take(&mut self.sums);
        let n = f64::from(sums.count.max(1));
        let [response, effort] = &mut self.plots;
        response.series[0].push(t, x);
        for (series, v) in effort
            .series
            .iter_mut()
            .zip([sums.u, sums.p, sums.i, sums.d])
        {
            series.push(t, v / n);
        }
        if sums.saturated {
            let from = t - RECORD_PERIOD_S;
            match effort.bands.last_mut() {
                Some(band) if (band.hi - from).abs() < 1e-9 => band.hi = t,
                _ => effort.bands.push(Band {
                    axis: Axis::X,
                    lo: from,
                    hi: t,
                    label: "saturated".into(),
                }),
            }
        }
        // Quiet: at rest near the final value, no noise to keep it moving.
        let quiet = self.noise_std_m == 0.0
            && self.final_value_m().is_some_and(|y| {
                let tol = (QUIET_FRACTION * y.abs()).max(QUIET_MIN_M);
                (x - y).abs() <= tol && self.run.state.v_m_s.abs() <= tol
            });
        self.quiet_samples = if quiet { self.quiet_samples + 1 } else { 0 };
        if f64::from(self.quiet_samples) * RECORD_PERIOD_S >= QUIET_S - 1e-9 {
            self.state = RunState::Quiet;
        }
    }

    /// Recomputes the metrics and the markers on the response curve.
    fn update_metrics(&mut self) {
        let y_final = self.final_value_m();
        let response = &mut self.plots[0];
        let series = &response.series[0];
        self.info =
            y_final.and_then(|y| step_info(&series.x, &series.y, 0.0, self.setpoint_m, Some(y)));
        response.markers.clear();
        let (Some(info), Some(y_inf)) = (self.info, y_final) else {
            return;
        };
        // Rise: where the curve first reaches 90 % of the step.
        if let Some(rise) = info.rise_time_s {
            if let Some(k) = series.y.iter().position(|y| y / y_inf >= 0.9) {
                response.markers.push(Marker {
                    x: series.x[k],
                    y: series.y[k],
                    label: format!("rise {} s", format_fixed(rise, 2)),
                });
            }
        }
        if info.overshoot_pct > 0.0 {
            response.markers.push(Marker {
                x: info.peak_time_s,
                y: info.peak,
                label: format!("peak {}%", format_fixed(info.overshoot_pct, 1)),
            });
        }
        if let Some(ts) = info.settling_time_s {
            if let Some(k) = series.nearest(ts) {
                response.markers.push(Marker {
                    x: series.x[k],
                    y: series.y[k],
                    label: format!("settled {} s", format_fixed(ts, 2)),
                });
            }
        }
    }

    /// Keeps the current response as a pinned run in the first free slot,
    /// or in the oldest pin's slot when all [`MAX_PINS`] are taken.
    fn pin(&mut self) {
        let slot = (0..MAX_PINS)
            .find(|k| self.pins.iter().all(|p| p.slot != *k))
            .unwrap_or_else(|| self.pins.remove(0).slot);
        self.pins_made += 1;
        self.pins.push(Pin {
            slot,
            number: self.pins_made,
            gains: self.gains,
            info: self.info,
            time_s: self.time_s(),
            finished: self.state != RunState::Running,
        });
        let response = &mut self.plots[0];
        let (x, y) = (response.series[0].x.clone(), response.series[0].y.clone());
        let series = &mut response.series[1 + slot];
        series.x = x;
        series.y = y;
        response.touch();
    }

    fn clear_pins(&mut self) {
        self.pins.clear();
        for series in &mut self.plots[0].series[1..] {
            series.x.clear();
            series.y.clear();
        }
        self.plots[0].touch();
    }

    /// Sets the setpoint from a pointer or key, rounded to 1 cm and kept in
    /// the slider's range, so the link reproduces it; restarts the step.
    fn drag_setpoint(&mut self, x_m: f64) {
        if !x_m.is_finite() {
            return;
        }
        let spec = &PARAMS[3];
        let r = ((x_m * 100.0).round() / 100.0).clamp(spec.min, spec.max);
        if r != self.setpoint_m {
            self.setpoint_m = r;
            self.restart();
        }
    }

    fn poles(&self) -> Option<(Vec<Complex>, Stability)> {
        closed_loop_poles(&self.plant, &self.gains)
            .ok()
            .map(|p| (p.poles, p.stability))
    }
}

/// `-0.187` or `-1.000 ± 2.000i` (one entry per conjugate pair).
fn format_poles(poles: &[Complex]) -> String {
    let mut parts = Vec::new();
    // Dominant (slowest) pole first.
    for p in poles.iter().rev() {
        if p.im < 0.0 {
            continue;
        }
        if p.im == 0.0 {
            parts.push(format_fixed(p.re, 3));
        } else {
            parts.push(format!(
                "{} ± {}i",
                format_fixed(p.re, 3),
                format_fixed(p.im, 3)
            ));
        }
    }
    parts.join(", ")
}

fn seconds(v: Option<f64>) -> String {
    v.map_or("--".into(), |t| format!("{} s", format_fixed(t, 2)))
}

fn percent(v: f64) -> String {
    format!("{}%", format_fixed(v, 1))
}

impl Experiment for PidControl {
    fn id(&self) -> &'static str {
        "pid"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        let flag = |b: bool| f64::from(u8::from(b));
        Some(match key {
            "kp" => self.gains.kp,
            "ki" => self.gains.ki,
            "kd" => self.gains.kd,
            "r" => self.setpoint_m,
            "c" => self.plant.drag_n_s_per_m,
            "m" => self.plant.mass_kg,
            "d" => self.disturbance_n,
            "dmeas" => flag(self.derivative_on_measurement),
            "sat" => flag(self.saturation),
            "umax" => self.force_limit_n,
            "ilim" => self.integral_limit_m_s,
            "noise" => self.noise_std_m,
            "tf" => self.filter_s,
            "seed" => self.seed as f64,
            _ => return None,
        })
    }

    /// Every parameter defines the run, so every change replays the step
    /// from the start with the new settings (pins are kept).
    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        match key {
            "kp" => self.gains.kp = v,
            "ki" => self.gains.ki = v,
            "kd" => self.gains.kd = v,
            "r" => self.setpoint_m = v,
            "c" => self.plant.drag_n_s_per_m = v,
            "m" => self.plant.mass_kg = v,
            "d" => self.disturbance_n = v,
            "dmeas" => self.derivative_on_measurement = v >= 0.5,
            "sat" => self.saturation = v >= 0.5,
            "umax" => self.force_limit_n = v,
            "ilim" => self.integral_limit_m_s = v,
            "noise" => self.noise_std_m = v,
            "tf" => self.filter_s = v,
            "seed" => self.seed = v as u64,
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        self.restart();
        Ok(applied)
    }

    fn actions(&self) -> &'static [ActionSpec] {
        ACTIONS
    }

    fn action(&mut self, key: &str) -> Result<(), ParamError> {
        match key {
            "step" => self.restart(),
            "pin" => self.pin(),
            "clear_pins" => self.clear_pins(),
            _ => return Err(ParamError::UnknownAction { key: key.into() }),
        }
        Ok(())
    }

    /// Pressing or dragging anywhere moves the setpoint marker there; arrow
    /// keys move it by the nudge's x.
    fn input(&mut self, input: Input) {
        if let Some(p) = input.drag_point(|| DVec2::new(self.setpoint_m, MARKER_TOP_M)) {
            self.drag_setpoint(p.x);
        }
    }

    fn step(&mut self, dt_s: f64) {
        if !crate::clock::valid_dt(dt_s) || self.state != RunState::Running {
            return;
        }
        self.pending_s += dt_s;
        let n = ((self.pending_s + 1e-9) / CONTROL_PERIOD_S).floor();
        self.pending_s = (self.pending_s - n * CONTROL_PERIOD_S).max(0.0);
        for _ in 0..n as u64 {
            self.update();
            if self.state != RunState::Running {
                break;
            }
        }
        self.update_metrics();
        self.plots.iter_mut().for_each(Plot::touch);
    }

    fn animated(&self) -> bool {
        true
    }

    /// The step again from rest (pins kept).
    fn reset(&mut self) {
        self.restart();
    }

    fn plots(&self) -> &[Plot] {
        &self.plots
    }

    /// The setpoint marker: its vertical line and its handle.
    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        (p.x - self.setpoint_m).abs() <= tolerance_m
            && p.y >= -tolerance_m
            && p.y <= MARKER_TOP_M + tolerance_m
    }

    fn view(&self) -> ViewBox {
        ViewBox {
            min: VIEW_MIN,
            max: VIEW_MAX,
        }
    }

    fn scene(&self, out: &mut Scene) {
        // Track with a tick every 0.5 m and labels at whole metres.
        out.push(Item::Line {
            from: DVec2::new(VIEW_MIN.x, 0.0),
            to: DVec2::new(VIEW_MAX.x, 0.0),
            width_px: 2.0,
            role: Role::Bound,
            dashed: false,
        });
        for k in -5..=5 {
            let x = f64::from(k) * 0.5;
            out.push(Item::Line {
                from: DVec2::new(x, 0.0),
                to: DVec2::new(x, -0.08),
                width_px: 1.0,
                role: Role::Grid,
                dashed: false,
            });
            if k % 2 == 0 {
                out.push(Item::Label {
                    pos: DVec2::new(x, -0.08),
                    text: format!("{} m", k / 2),
                    role: Role::Text,
                    offset_px: DVec2::new(-8.0, 12.0),
                });
            }
        }
        // The ±2 % band around the final value, on the track.
        if let Some(band) = self.plots[0].bands.first() {
            out.push(Item::Rect {
                min: DVec2::new(band.lo, -0.02),
                max: DVec2::new(band.hi, 0.02),
                role: Role::Accent,
                fill: true,
            });
        }
        // Setpoint marker (the draggable handle).
        let r = self.setpoint_m;
        out.push(Item::Line {
            from: DVec2::new(r, 0.0),
            to: DVec2::new(r, MARKER_TOP_M),
            width_px: 2.0,
            role: Role::Target,
            dashed: true,
        });
        out.push(Item::Polygon {
            points: vec![
                DVec2::new(r, MARKER_TOP_M - 0.12),
                DVec2::new(r - 0.08, MARKER_TOP_M),
                DVec2::new(r + 0.08, MARKER_TOP_M),
            ],
            role: Role::Target,
        });
        out.push(Item::Label {
            pos: DVec2::new(r, MARKER_TOP_M),
            text: format!("r = {}", format_metres(r)),
            role: Role::Target,
            offset_px: DVec2::new(10.0, -12.0),
        });
        // The cart, its wheels and the control force.
        let x = self.run.state.x_m.clamp(-1e3, 1e3);
        out.push(Item::Rect {
            min: DVec2::new(x - CART_HALF_W_M, CART_BOTTOM_M),
            max: DVec2::new(x + CART_HALF_W_M, CART_TOP_M),
            role: Role::Robot,
            fill: true,
        });
        for dx in [-0.13, 0.13] {
            out.push(Item::Circle {
                center: DVec2::new(x + dx, 0.045),
                radius_m: 0.045,
                role: Role::Joint,
                fill: true,
                dashed: false,
            });
        }
        let u = self.run.last_terms().output;
        let len = (u * ARROW_M_PER_N).clamp(-ARROW_MAX_M, ARROW_MAX_M);
        if len.abs() > 0.01 {
            let y = 0.5 * (CART_BOTTOM_M + CART_TOP_M);
            let start = x + CART_HALF_W_M.copysign(len);
            out.push(Item::Arrow {
                from: DVec2::new(start, y),
                to: DVec2::new(start + len, y),
                width_px: 3.0,
                role: Role::Accent,
            });
        }
        out.push(Item::Label {
            pos: DVec2::new(x, CART_TOP_M),
            text: format!("u = {} N", format_fixed(u, 1)),
            role: Role::Text,
            offset_px: DVec2::new(-24.0, -14.0),
        });
    }

    fn readouts(&self) -> Vec<Readout> {
        let x = self.run.state.x_m;
        let info = self.info;
        let y_final = self.final_value_m();
        let (poles, stability) = match self.poles() {
            Some((p, s)) => (
                format_poles(&p),
                match s {
                    Stability::Stable => "stable",
                    Stability::MarginallyStable => "marginally stable",
                    Stability::Unstable => "unstable",
                },
            ),
            None => ("--".into(), "--"),
        };
        let second = SecondOrder::of(&self.plant, &self.gains).map_or("--".into(), |s| {
            format!(
                "ωn {} rad/s · ζ {}",
                format_fixed(s.natural_frequency_rad_s, 3),
                format_fixed(s.damping_ratio, 3)
            )
        });
        let mut out = vec![
            Readout::metres("x", "Position x", x),
            Readout::metres("error", "Error e = r − x", self.setpoint_m - x),
            Readout::new(
                "force",
                "Force u",
                format!("{} N", format_fixed(self.run.last_terms().output, 2)),
            ),
            Readout::new(
                "overshoot",
                "Overshoot",
                info.map_or("--".into(), |i| percent(i.overshoot_pct)),
            ),
            Readout::new(
                "rise",
                "Rise time (10–90 %)",
                seconds(info.and_then(|i| i.rise_time_s)),
            ),
            Readout::new(
                "settling",
                "Settling time (±2 %)",
                seconds(info.and_then(|i| i.settling_time_s)),
            ),
            Readout::new(
                "peak",
                "Peak",
                info.map_or("--".into(), |i| {
                    format!(
                        "{} at {} s",
                        format_metres(i.peak),
                        format_fixed(i.peak_time_s, 2)
                    )
                }),
            ),
            Readout::new(
                "sse",
                "Steady-state error",
                y_final.map_or("--".into(), |y| format_metres(self.setpoint_m - y)),
            ),
            Readout::new("poles", "Closed-loop poles (1/s)", poles),
            Readout::new("stability", "Linear loop", stability),
            Readout::new("second_order", "Second order (Ki = 0)", second),
        ];
        const PIN_KEYS: [&str; MAX_PINS] = ["pinA", "pinB", "pinC", "pinD"];
        const PIN_LABELS: [&str; MAX_PINS] = [
            "Pinned run A",
            "Pinned run B",
            "Pinned run C",
            "Pinned run D",
        ];
        let mut pins: Vec<&Pin> = self.pins.iter().collect();
        pins.sort_by_key(|p| p.slot);
        for pin in pins {
            let none = if pin.finished {
                "no metrics (no final value)"
            } else {
                "no metrics yet"
            };
            let metrics = pin.info.map_or(none.into(), |i| {
                format!(
                    "overshoot {}, rise {}, settling {}",
                    percent(i.overshoot_pct),
                    seconds(i.rise_time_s),
                    seconds(i.settling_time_s)
                )
            });
            let partial = if pin.finished {
                String::new()
            } else {
                format!(", so far (pinned at {})", seconds(Some(pin.time_s)))
            };
            out.push(Readout::new(
                PIN_KEYS[pin.slot],
                PIN_LABELS[pin.slot],
                format!("{}, {metrics}{partial}", pin.gains_text()),
            ));
        }
        out
    }

    fn status(&self) -> Status {
        let settled = self.info.and_then(|i| i.settling_time_s);
        match self.state {
            RunState::Running => Status::new(
                format!("stepping to {}", format_metres(self.setpoint_m)),
                Tone::Neutral,
            ),
            RunState::Diverged => Status::new("diverged: the loop is unstable", Tone::Bad),
            RunState::Quiet | RunState::Complete => match (settled, self.final_value_m()) {
                (Some(ts), Some(_)) => Status::new(
                    format!("settled within 2 % after {}", seconds(Some(ts))),
                    Tone::Good,
                ),
                (None, Some(_)) => Status::new(
                    format!("not settled after {} s", format_fixed(self.time_s(), 0)),
                    Tone::Warning,
                ),
                (_, None) => Status::new("at rest", Tone::Neutral),
            },
        }
    }

    fn hint(&self) -> &'static str {
        "Drag the setpoint marker or use the sliders; each change replays the step. Pin run keeps a response to compare gains."
    }

    /// A finished default step response with one pinned run for comparison.
    fn preview(&mut self) {
        self.gains.kd = 2.0;
        self.restart();
        while self.state == RunState::Running {
            self.step(0.1);
        }
        self.pin();
        self.gains.kd = PARAMS[2].default;
        self.restart();
        for _ in 0..30 {
            self.step(0.1);
        }
    }

    fn animating(&self) -> bool {
        self.state == RunState::Running
    }
}

/// Draws a mass and gains giving a stable, underdamped `Ki = 0` loop.
fn draw_second_order(rng: &mut Lcg64) -> (f64, PidGains, f64) {
    let m = rng.int(1, 8) as f64 * 0.5;
    let c = rng.int(0, 10) as f64 * 0.2;
    let kp = rng.int(4, 40) as f64;
    // ζ between about 0.15 and 0.8.
    let zeta = rng.range(0.15, 0.8);
    let kd = ((zeta * 2.0 * (m * kp).sqrt() - c) * 10.0).round().max(0.0) / 10.0;
    (m, PidGains { kp, ki: 0.0, kd }, c)
}

fn second_order_vars(m: f64, g: &PidGains, c: f64) -> Vec<(&'static str, String)> {
    vec![
        ("m", format_number(m, 2)),
        ("c", format_number(c, 2)),
        ("kp", format_number(g.kp, 2)),
        ("kd", format_number(g.kd, 2)),
    ]
}

/// Natural frequency `√(Kp/m)` of the `Ki = 0` loop.
fn quiz_natural_frequency(rng: &mut Lcg64) -> Draw {
    let (m, g, c) = draw_second_order(rng);
    let plant = MassDragPlant {
        mass_kg: m,
        drag_n_s_per_m: c,
    };
    Draw {
        vars: second_order_vars(m, &g, c),
        answer: SecondOrder::of(&plant, &g).map_or(0.0, |s| s.natural_frequency_rad_s),
    }
}

/// Damping ratio `(c + Kd)/(2√(m·Kp))`.
fn quiz_damping_ratio(rng: &mut Lcg64) -> Draw {
    let (m, g, c) = draw_second_order(rng);
    let plant = MassDragPlant {
        mass_kg: m,
        drag_n_s_per_m: c,
    };
    Draw {
        vars: second_order_vars(m, &g, c),
        answer: SecondOrder::of(&plant, &g).map_or(0.0, |s| s.damping_ratio),
    }
}

/// Percent overshoot `100·exp(−ζπ/√(1 − ζ²))` for a drawn ζ.
fn quiz_overshoot(rng: &mut Lcg64) -> Draw {
    let zeta = rng.int(10, 85) as f64 / 100.0;
    let s = SecondOrder {
        natural_frequency_rad_s: 1.0,
        damping_ratio: zeta,
    };
    Draw {
        vars: vec![("zeta", format_number(zeta, 2))],
        answer: s.overshoot_pct(),
    }
}

/// Steady-state error `d/Kp` of a P or PD loop pushed back by a force `d`.
fn quiz_offset(rng: &mut Lcg64) -> Draw {
    let kp = rng.int(2, 20) as f64;
    let d = rng.int(4, 40) as f64 * 0.25;
    let mut exp = PidControl::default();
    // The cart is pushed back (toward −x) while the setpoint is ahead.
    for (key, value) in [("kp", kp), ("ki", 0.0), ("kd", 5.0), ("d", -d)] {
        let _ = exp.set_param(key, value);
    }
    let answer = exp.final_value_m().map_or(d / kp, |y| exp.setpoint_m - y);
    Draw {
        vars: vec![("kp", format_number(kp, 2)), ("d", format_number(d, 2))],
        answer,
    }
}

/// The quiz generators of experiment 7, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "natural_frequency" => Some(quiz_natural_frequency),
        "damping_ratio" => Some(quiz_damping_ratio),
        "overshoot" => Some(quiz_overshoot),
        "offset" => Some(quiz_offset),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::route::{format, restore, Tab};

    fn run_to_end(e: &mut PidControl) -> usize {
        let mut frames = 0;
        while e.animating() && frames < 10_000 {
            e.step(1.0 / 60.0);
            frames += 1;
        }
        frames
    }

    fn readout(e: &PidControl, key: &str) -> String {
        crate::experiment::readout_value(e, key).unwrap_or_else(|| panic!("no readout {key}"))
    }

    /// `Kp = 25, Kd = 5, c = 1, m = 1, Ki = 0`: `s² + 6 s + 25`, poles
    /// `−3 ± 4i`, `ωn = 5`, `ζ = 0.6`.
    fn underdamped() -> PidControl {
        let mut e = PidControl::default();
        e.set_param("kp", 25.0).unwrap();
        e.set_param("ki", 0.0).unwrap();
        e.set_param("kd", 5.0).unwrap();
        e
    }

    #[test]
    fn readouts_by_hand_at_the_start() {
        let e = underdamped();
        assert_eq!(readout(&e, "x"), "0.000 m");
        assert_eq!(readout(&e, "error"), "1.000 m");
        assert_eq!(readout(&e, "poles"), "-3.000 ± 4.000i");
        assert_eq!(readout(&e, "stability"), "stable");
        assert_eq!(readout(&e, "second_order"), "ωn 5.000 rad/s · ζ 0.600");
        assert_eq!(readout(&e, "sse"), "0.000 m");
        // Default gains: m s³ + (c + Kd) s² + Kp s + Ki = s³ + 7 s² + 12 s + 2,
        // three real poles, the slowest near −0.187.
        let d = PidControl::default();
        let poles = readout(&d, "poles");
        assert!(poles.starts_with("-0.18"), "{poles}");
        assert_eq!(poles.split(", ").count(), 3, "{poles}");
        assert_eq!(readout(&d, "second_order"), "--");
    }

    /// With `Ki = 0` and the derivative on the measurement the loop is the
    /// textbook second-order system `ωn²/(s² + 2ζωn s + ωn²)`: its metrics
    /// match the analytic formulas and `step_info` of the exact response.
    #[test]
    fn second_order_metrics_and_markers_match_the_analytic_response() {
        let mut e = underdamped();
        run_to_end(&mut e);
        let info = e.metrics().expect("metrics");
        let (wn, zeta) = (5.0_f64, 0.6_f64);
        let wd = wn * (1.0 - zeta * zeta).sqrt();
        let overshoot = 100.0 * (-zeta * std::f64::consts::PI / (1.0 - zeta * zeta).sqrt()).exp();
        assert!((info.overshoot_pct - overshoot).abs() < 0.1, "{info:?}");
        assert!(
            (info.peak_time_s - std::f64::consts::PI / wd).abs() <= 0.011,
            "{info:?}"
        );
        // The exact response sampled at the record period.
        let t: Vec<f64> = (0..=3000).map(|k| k as f64 * RECORD_PERIOD_S).collect();
        let y: Vec<f64> = t
            .iter()
            .map(|t| {
                1.0 - (-zeta * wn * t).exp()
                    * ((wd * t).cos() + zeta / (1.0 - zeta * zeta).sqrt() * (wd * t).sin())
            })
            .collect();
        let exact = step_info(&t, &y, 0.0, 1.0, Some(1.0)).unwrap();
        let close = |a: Option<f64>, b: Option<f64>| (a.unwrap() - b.unwrap()).abs() <= 0.021;
        assert!(
            close(info.rise_time_s, exact.rise_time_s),
            "{info:?} vs {exact:?}"
        );
        assert!(
            close(info.settling_time_s, exact.settling_time_s),
            "{info:?} vs {exact:?}"
        );
        // Markers sit on the curve at the rise, peak and settling times.
        let markers = &e.plots()[0].markers;
        assert_eq!(markers.len(), 3, "{markers:?}");
        let series = &e.plots()[0].series[0];
        for m in markers {
            let k = series.nearest(m.x).unwrap();
            assert!((series.x[k] - m.x).abs() < 1e-12 && (series.y[k] - m.y).abs() < 1e-12);
        }
        let first_90 = series.y.iter().position(|y| *y >= 0.9).unwrap();
        assert_eq!(markers[0].x, series.x[first_90]);
        assert!(markers[0].label.starts_with("rise "));
        assert_eq!((markers[1].x, markers[1].y), (info.peak_time_s, info.peak));
        assert_eq!(
            markers[1].label,
            format!("peak {}%", format_fixed(info.overshoot_pct, 1))
        );
        assert!((markers[2].x - info.settling_time_s.unwrap()).abs() < 1e-9);
        assert_eq!(
            readout(&e, "overshoot"),
            format!("{}%", format_fixed(info.overshoot_pct, 1))
        );
        assert_eq!(e.status().tone, Tone::Good);
        assert!(e.status().text.starts_with("settled within 2 % after"));
    }

    #[test]
    fn the_cart_reaches_the_setpoint_and_the_run_goes_quiet() {
        let mut e = PidControl::default();
        let frames = run_to_end(&mut e);
        assert!(!e.animating());
        assert!(frames < 10_000);
        assert!((e.position_m() - 1.0).abs() < 2e-3, "{}", e.position_m());
        // Bounded records: at most RECORD_S of samples.
        let n = e.plots()[0].series[0].len();
        assert!(n <= (RECORD_S / RECORD_PERIOD_S) as usize + 1, "{n}");
        // Finished runs ignore further steps.
        let before = e.position_m();
        e.step(1.0 / 60.0);
        assert_eq!(e.position_m(), before);
    }

    #[test]
    fn integral_action_removes_the_offset_of_a_constant_push() {
        let mut p_only = PidControl::default();
        p_only.set_param("ki", 0.0).unwrap();
        p_only.set_param("d", -3.0).unwrap();
        run_to_end(&mut p_only);
        // Kp·e = 3 N → e = 3/12 = 0.25 m.
        assert!(
            (p_only.position_m() - 0.75).abs() < 1e-3,
            "{}",
            p_only.position_m()
        );
        assert_eq!(readout(&p_only, "sse"), "0.250 m");
        let mut pid = PidControl::default();
        pid.set_param("d", -3.0).unwrap();
        run_to_end(&mut pid);
        assert!(
            (pid.position_m() - 1.0).abs() < 2e-3,
            "{}",
            pid.position_m()
        );
        assert_eq!(readout(&pid, "sse"), "0.000 m");
    }

    /// With `Ki = 0.5` a 5 N push needs `∫e = 10 m·s`, but the clamp stops the
    /// integral at 5: the last 2.5 N are left to `Kp`, `e = 2.5/12`.
    #[test]
    fn the_integral_clamp_bounds_the_integral_and_leaves_the_predicted_offset() {
        let mut e = PidControl::default();
        e.set_param("ki", 0.5).unwrap();
        e.set_param("d", -5.0).unwrap();
        let predicted = 1.0 - 2.5 / 12.0;
        assert!((e.final_value_m().unwrap() - predicted).abs() < 1e-12);
        run_to_end(&mut e);
        assert!(e.run.controller.integral_m_s().abs() <= 5.0 + 1e-12);
        assert!(
            (e.position_m() - predicted).abs() < 2e-3,
            "{}",
            e.position_m()
        );
    }

    #[test]
    fn saturation_is_shaded_and_limits_the_force() {
        let mut e = PidControl::default();
        e.set_param("sat", 1.0).unwrap();
        e.set_param("umax", 5.0).unwrap();
        run_to_end(&mut e);
        let effort = &e.plots()[1];
        assert!(effort.series[0].y.iter().all(|u| u.abs() <= 5.0 + 1e-9));
        assert!(!effort.bands.is_empty());
        let band = &effort.bands[0];
        assert_eq!(band.axis, Axis::X);
        // Saturated from the start: a 1 m error asks Kp·e = 12 N > 5 N.
        assert!(band.lo.abs() < 1e-9 && band.hi > 0.1, "{band:?}");
        assert_eq!(effort.ref_lines.len(), 2);
        // The applied force is the sum of the terms wherever it is not cut.
        let s = &effort.series;
        let inside = |t: f64| {
            effort
                .bands
                .iter()
                .any(|b| t >= b.lo - 1e-9 && t <= b.hi + 1e-9)
        };
        for k in 0..s[0].len() {
            if !inside(s[0].x[k]) {
                let sum = s[1].y[k] + s[2].y[k] + s[3].y[k];
                assert!((s[0].y[k] - sum).abs() < 1e-9, "t = {}", s[0].x[k]);
            }
        }
    }

    #[test]
    fn derivative_on_the_error_kicks_and_on_the_measurement_does_not() {
        let mut on_error = PidControl::default();
        on_error.set_param("dmeas", 0.0).unwrap();
        on_error.step(1.0 / 60.0);
        // The first record period holds the impulse Kd·r = 6 N·s, a mean of
        // 6 N·s / 0.01 s = 600 N, less the damping −Kd·ẋ of the five updates
        // after the kick (ẋ ≈ 6 m/s: about −30 N on average).
        let d0 = on_error.plots()[1].series[3].y[0];
        assert!(d0 > 550.0 && d0 < 600.0, "{d0}");
        let mut on_measurement = PidControl::default();
        on_measurement.step(1.0 / 60.0);
        let d0 = on_measurement.plots()[1].series[3].y[0];
        assert!(d0.abs() < 1.0, "{d0}");
    }

    #[test]
    fn unstable_gains_diverge_and_say_so() {
        let mut e = PidControl::default();
        // m s³ + 0·s² + s + 5: no damping at all, poles in the right half-plane.
        for (k, v) in [("c", 0.0), ("kd", 0.0), ("kp", 1.0), ("ki", 5.0)] {
            e.set_param(k, v).unwrap();
        }
        assert_eq!(readout(&e, "stability"), "unstable");
        run_to_end(&mut e);
        assert_eq!(e.status().tone, Tone::Bad);
        assert!(e.position_m().abs() > DIVERGED_M);
        assert_eq!(readout(&e, "overshoot"), "--");
        let mut scene = Scene::default();
        e.scene(&mut scene);
        assert!(scene.is_finite());
    }

    #[test]
    fn pinned_runs_keep_their_gains_and_metrics() {
        let mut e = underdamped();
        // The slot series exist from the start (the page's legend is fixed).
        let labels: Vec<&str> = e.plots()[0]
            .series
            .iter()
            .map(|s| s.label.as_str())
            .collect();
        assert_eq!(
            labels,
            [
                "position x",
                "pinned run A",
                "pinned run B",
                "pinned run C",
                "pinned run D"
            ]
        );
        assert!(e.plots()[0].series[1..].iter().all(Series::is_empty));
        run_to_end(&mut e);
        let first = e.metrics().unwrap();
        let curve = e.plots()[0].series[0].clone();
        e.action("pin").unwrap();
        e.set_param("kd", 10.0).unwrap();
        run_to_end(&mut e);
        e.action("pin").unwrap();
        let response = &e.plots()[0];
        assert_eq!(
            (&response.series[1].x, &response.series[1].y),
            (&curve.x, &curve.y)
        );
        assert_eq!(response.series[2].len(), response.series[0].len());
        assert_eq!(response.series[1].role, SeriesRole::Secondary);
        assert_eq!(response.series[2].role, SeriesRole::Tertiary);
        assert_eq!(e.pins()[0].info, Some(first));
        assert_eq!(
            readout(&e, "pinA"),
            format!(
                "Kp 25 · Ki 0 · Kd 5, overshoot {}, rise {}, settling {}",
                percent(first.overshoot_pct),
                seconds(first.rise_time_s),
                seconds(first.settling_time_s)
            )
        );
        assert!(readout(&e, "pinB").starts_with("Kp 25 · Ki 0 · Kd 10, overshoot "));
        // More damping, less overshoot.
        assert!(e.pins()[1].info.unwrap().overshoot_pct < first.overshoot_pct);
        // A replayed step keeps the pins; the fifth pin replaces the oldest (slot A).
        e.action("step").unwrap();
        assert_eq!(e.plots()[0].series[1].x, curve.x);
        e.set_param("kd", 1.0).unwrap();
        for _ in 0..3 {
            e.action("pin").unwrap();
        }
        assert_eq!(e.pins().len(), MAX_PINS);
        let numbers: Vec<(usize, usize)> = e.pins().iter().map(|p| (p.number, p.slot)).collect();
        assert_eq!(numbers, [(2, 1), (3, 2), (4, 3), (5, 0)]);
        assert!(readout(&e, "pinA").starts_with("Kp 25 · Ki 0 · Kd 1, "));
        // Pinned mid-run: the metrics are marked as those so far.
        assert!(
            readout(&e, "pinA").ends_with(", so far (pinned at 0.00 s)"),
            "{}",
            readout(&e, "pinA")
        );
        assert!(!readout(&e, "pinB").contains("so far"));
        let keys: Vec<&str> = e
            .readouts()
            .iter()
            .map(|r| r.key)
            .filter(|k| k.starts_with("pin"))
            .collect();
        assert_eq!(keys, ["pinA", "pinB", "pinC", "pinD"]);
        e.action("clear_pins").unwrap();
        assert_eq!(e.plots()[0].series.len(), 1 + MAX_PINS);
        assert!(e.plots()[0].series[1..].iter().all(Series::is_empty));
        assert!(e.readouts().iter().all(|r| !r.key.starts_with("pin")));
    }

    #[test]
    fn dragging_the_marker_sets_the_setpoint_to_the_centimetre() {
        let mut e = PidControl::default();
        assert!(e.handle_at(DVec2::new(1.0, 0.5), 0.1));
        assert!(!e.handle_at(DVec2::new(0.0, 0.5), 0.1));
        e.step(0.05);
        e.input(Input::PointerDown(DVec2::new(-1.234, 0.4)));
        assert_eq!(e.param("r"), Some(-1.23));
        assert_eq!(e.time_s(), 0.0, "the step restarts");
        e.input(Input::Nudge(DVec2::new(0.05, 0.0)));
        assert!((e.param("r").unwrap() + 1.18).abs() < 1e-12);
        e.input(Input::PointerMove {
            pos: DVec2::new(9.0, 0.0),
            pressed: true,
        });
        assert_eq!(e.param("r"), Some(2.0), "kept in the slider's range");
        e.input(Input::PointerMove {
            pos: DVec2::new(f64::NAN, 0.0),
            pressed: true,
        });
        assert_eq!(e.param("r"), Some(2.0));
    }

    #[test]
    fn every_parameter_round_trips_through_the_link() {
        let mut e = PidControl::default();
        for (k, v) in [
            ("kp", 30.5),
            ("ki", 0.3),
            ("kd", 2.2),
            ("r", -0.75),
            ("c", 0.4),
            ("m", 2.5),
            ("d", 1.5),
            ("dmeas", 0.0),
            ("sat", 1.0),
            ("umax", 40.0),
            ("ilim", 2.5),
            ("noise", 0.004),
            ("tf", 0.05),
            ("seed", 42.0),
        ] {
            e.set_param(k, v).unwrap();
        }
        let link = format(&e, Tab::Simulation);
        let (mut fresh, notices) = restore(&link, PidControl::default());
        assert!(notices.is_empty(), "{notices:?}");
        assert_eq!(format(&fresh, Tab::Simulation), link);
        for spec in PARAMS {
            assert_eq!(fresh.param(spec.key), e.param(spec.key), "{}", spec.key);
        }
        // The same settings replay the same (noisy) run.
        for _ in 0..120 {
            e.step(1.0 / 60.0);
            fresh.step(1.0 / 60.0);
        }
        assert_eq!(e.position_m(), fresh.position_m());
    }

    #[test]
    fn noise_is_seeded_and_the_filter_calms_the_derivative() {
        let spread = |tf: f64, seed: f64| {
            let mut e = PidControl::default();
            e.set_param("noise", 0.005).unwrap();
            e.set_param("seed", seed).unwrap();
            e.set_param("tf", tf).unwrap();
            for _ in 0..600 {
                e.step(1.0 / 60.0);
            }
            let d = &e.plots()[1].series[3].y;
            let tail = &d[d.len() - 300..];
            let mean = tail.iter().sum::<f64>() / tail.len() as f64;
            (tail.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / tail.len() as f64).sqrt()
        };
        let raw = spread(0.0, 1.0);
        let filtered = spread(0.05, 1.0);
        assert!(filtered < raw / 3.0, "raw {raw}, filtered {filtered}");
        assert_eq!(spread(0.0, 1.0), raw, "same seed, same noise");
        assert_ne!(spread(0.0, 2.0), raw);
    }

    #[test]
    fn bad_steps_and_inputs_change_nothing() {
        let mut e = PidControl::default();
        e.step(0.1);
        let before = (e.position_m(), e.time_s(), e.plots()[0].clone());
        for dt in [f64::NAN, -1.0, 0.0, 0.2, f64::INFINITY] {
            e.step(dt);
        }
        assert_eq!((e.position_m(), e.time_s(), e.plots()[0].clone()), before);
        assert!(e.set_param("kp", f64::NAN).is_err());
        assert!(e.set_param("nope", 1.0).is_err());
        assert!(e.action("nope").is_err());
        assert_eq!(e.time_s(), before.1);
    }

    #[test]
    fn quiz_generators_agree_with_the_formulas() {
        let mut rng = Lcg64::new(5);
        for _ in 0..200 {
            let d = quiz_offset(&mut rng);
            let (kp, push) = (d.var("kp").unwrap(), d.var("d").unwrap());
            assert!((d.answer - push / kp).abs() < 1e-12);
            let d = quiz_damping_ratio(&mut rng);
            let (m, c, kp, kd) = (
                d.var("m").unwrap(),
                d.var("c").unwrap(),
                d.var("kp").unwrap(),
                d.var("kd").unwrap(),
            );
            assert!((d.answer - (c + kd) / (2.0 * (m * kp).sqrt())).abs() < 1e-12);
            assert!(d.answer > 0.0 && d.answer < 1.0, "{}", d.answer);
            let d = quiz_natural_frequency(&mut rng);
            assert!((d.answer - (d.var("kp").unwrap() / d.var("m").unwrap()).sqrt()).abs() < 1e-12);
            let d = quiz_overshoot(&mut rng);
            let z = d.var("zeta").unwrap();
            let expected = 100.0 * (-z * std::f64::consts::PI / (1.0 - z * z).sqrt()).exp();
            assert!((d.answer - expected).abs() < 1e-9);
        }
    }
}
