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
//! **The track** runs from −[`TRACK_END_M`] to +[`TRACK_END_M`], drawn with
//! an end stop at each end inside the view; the run stops when the cart's
//! centre passes an end ("off the track", [`crate::experiment::Phase::Ended`]). Every run that
//! stops (settled, recorded in full, off the track) has ended.
//!
//! **Metrics of a tiny step.** Overshoot, rise and settling are fractions
//! of the step, so below [`MIN_STEP_M`] they are not shown ("— (step under
//! 1 mm)"): a nanometre step with sensor noise would read 10⁸ %.
//!
//! **Pinned runs.** "Pin run" keeps the current response, its gains and
//! its metrics; up to [`MAX_PINS`] pinned responses are overlaid on the
//! response plot (the oldest is replaced by a fifth, with a notice) and
//! listed as readouts, one per slot A–D. The plot always holds the four
//! slot series (empty until used, marked [`Series::for_comparison`]); a
//! pinned series is named after its slot and gains, `A: Kp 25, Kd 5`.
//!
//! **Layout.** This file holds the model; `view.rs` the scene, readouts and
//! status; `quiz.rs` the generated questions; `tests.rs` the tests (the
//! Procedure is played by `tests/procedures/`).

use crate::control::pid::{
    closed_loop_poles, MassDragPlant, Pid, PidConfig, PidGains, PidLoop, SecondOrder,
};
use crate::control::step_info::{step_info, StepInfo, SETTLING_THRESHOLD};
use crate::control::{Complex, Stability};
use crate::experiment::{
    check_param, ActionSpec, Experiment, Input, Notices, ParamError, ParamSpec, Sanitized, Tone,
};
use crate::memo::Memo;
use crate::plot::{Axis, Band, Marker, Plot, RefLine, Series, SeriesRole, XWindow};
use crate::quiz::{Draw, Generator};
use crate::rng::Lcg64;
use crate::units::{format_fixed, format_magnitude, format_metres, format_number};
use glam::DVec2;

mod quiz;
mod view;
mod words;

use words::{at_setpoint, percent, seconds};

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
/// Recorded samples per second: sample `k` is at `k / 100` s, computed as a
/// division so the times read 0.07, not 0.07000000000000001.
const RECORDS_PER_S: f64 = 100.0;
/// Recorded sample period, seconds (100 Hz).
pub const RECORD_PERIOD_S: f64 = 1.0 / RECORDS_PER_S;
/// Longest recorded response, seconds; the run ends there.
pub const RECORD_S: f64 = 30.0;
/// The run ends early once the cart has been this close to its final value
/// (fraction of the step, and at least [`QUIET_MIN_M`]) and this slow for
/// [`QUIET_S`] seconds, with no sensor noise.
const QUIET_FRACTION: f64 = 1e-3;
const QUIET_MIN_M: f64 = 1e-4;
const QUIET_S: f64 = 1.0;
/// While the run goes on, a settling time is shown (readout, marker, badge)
/// only once the response has stayed inside its ±2 % band this long
/// (seconds): a response that crosses the band on its way to an overshoot
/// is inside it for a moment and has not settled.
pub const SETTLE_DWELL_S: f64 = 1.0;
/// The track runs from `−TRACK_END_M` to `+TRACK_END_M` (metres); the run
/// stops when the cart's centre passes an end.
pub const TRACK_END_M: f64 = 2.5;
/// Below this final value (metres) the step is too small to measure: the
/// overshoot, rise and settling are fractions of the step, so a step of a
/// nanometre (or of `5·10⁻³²⁴` m) would turn sensor noise into
/// percentages of 10⁹ or infinity. One millimetre is the readouts' resolution.
pub const MIN_STEP_M: f64 = 1e-3;
/// At most this many pinned runs.
pub const MAX_PINS: usize = 4;
/// The roles pinned runs are drawn with, in order of use.
const PIN_ROLES: [SeriesRole; MAX_PINS] = [
    SeriesRole::Secondary,
    SeriesRole::Tertiary,
    SeriesRole::Quaternary,
    SeriesRole::Reference,
];

/// The series names of the four pin slots while empty; a pinned run is named
/// after its slot and gains instead ("A: Kp 25, Kd 5").
const PIN_NAMES: [&str; MAX_PINS] = [
    "pinned run A",
    "pinned run B",
    "pinned run C",
    "pinned run D",
];
/// The slot letters.
const PIN_LETTERS: [&str; MAX_PINS] = ["A", "B", "C", "D"];

/// Height of the setpoint marker's handle, metres.
const MARKER_TOP_M: f64 = 0.85;

/// Why the current run stopped, if it did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum RunState {
    Running,
    /// Near the final value and at rest: nothing more to see.
    Quiet,
    /// The full [`RECORD_S`] recorded.
    Complete,
    /// The cart's centre passed an end of the track.
    OffTrack,
    /// The numbers stopped being finite.
    Diverged,
}

/// Why there are no step-response metrics.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoMetrics {
    /// The linear loop has no final value (unstable, marginal, nothing to
    /// hold the cart, or a push the force limit cannot balance).
    NoFinalValue,
    /// The step to the final value is under [`MIN_STEP_M`].
    StepTooSmall,
    /// Not enough samples yet.
    NotYet,
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
    /// The metrics when it was pinned, or why there were none.
    pub info: Result<StepInfo, NoMetrics>,
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
        format!(
            "Kp {} · Ki {} · Kd {}",
            gain_text(self.gains.kp),
            gain_text(self.gains.ki),
            gain_text(self.gains.kd)
        )
    }

    /// The legend name of the pinned curve: its slot and the gains, the zero
    /// Ki and Kd left out, `A: Kp 25, Kd 5`.
    #[must_use]
    pub fn legend(&self) -> String {
        let g = self.gains;
        let mut parts = vec![format!("Kp {}", gain_text(g.kp))];
        for (name, v) in [("Ki", g.ki), ("Kd", g.kd)] {
            if v != 0.0 {
                parts.push(format!("{name} {}", gain_text(v)));
            }
        }
        format!("{}: {}", PIN_LETTERS[self.slot], parts.join(", "))
    }
}

/// A gain as the legend and the readouts name it: `12.5`, or a power of ten
/// for a value a link can carry but two decimals cannot show (`1.0 × 10⁻⁵`).
fn gain_text(v: f64) -> String {
    if v != 0.0 && v.abs() < 0.01 {
        format_magnitude(v)
    } else {
        format_number(v, 2)
    }
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
    /// Samples recorded since the step (the first, at t = 0, not counted).
    records: u64,
    sums: TermSums,
    state: RunState,
    quiet_samples: u32,
    info: Result<StepInfo, NoMetrics>,
    /// When the loop has no final value: the response measured against the
    /// setpoint instead (how far it went past it, its peak), so an unstable
    /// run reports what it reached.
    setpoint_info: Option<StepInfo>,
    /// The timeline replays this copy ([`Experiment::begin_replay`]): its
    /// steps leave the metrics to [`Experiment::end_replay`].
    replaying: bool,
    /// A replayed step left the metrics and markers to compute.
    metrics_stale: bool,
    notices: Notices,
    pins: Vec<Pin>,
    pins_made: usize,
    /// Response (position and pinned runs) and control effort.
    plots: [Plot; 2],
    /// The closed loop's stability for the last plant and gains asked: a
    /// step needs it (the final value) and the gains rarely change.
    stability: Memo<(MassDragPlant, PidGains), Option<Stability>>,
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
                        .map(|(name, role)| Series::new(*name, "m", role).for_comparison()),
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
            records: 0,
            sums: TermSums::default(),
            state: RunState::Running,
            quiet_samples: 0,
            stability: Memo::default(),
            info: Err(NoMetrics::NotYet),
            setpoint_info: None,
            replaying: false,
            metrics_stale: false,
            notices: Notices::default(),
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
        self.info.ok()
    }

    /// The peak so far (metres) and its time (seconds): that of the
    /// recorded samples `info` measured, or the cart's position now when it
    /// is further in the step's direction. The record keeps a sample every
    /// [`RECORD_PERIOD_S`] and a frame ends between samples, so while the
    /// cart rises its position is past the last sample: "Peak" never reads
    /// less than the "Position x" beside it.
    pub(crate) fn peak_so_far(&self, info: &StepInfo) -> (f64, f64) {
        let x = self.run.state.x_m;
        // The step starts at 0: its direction is the sign of y∞.
        if x.is_finite() && (x - info.peak) * info.steady_state_value.signum() > 0.0 {
            (x, self.time_s())
        } else {
            (info.peak, info.peak_time_s)
        }
    }

    /// The final value if the step to it is large enough to measure
    /// ([`MIN_STEP_M`]), or why not.
    fn measurable_final_value(&self) -> Result<f64, NoMetrics> {
        match self.final_value_m() {
            None => Err(NoMetrics::NoFinalValue),
            Some(y) if y.abs() < MIN_STEP_M => Err(NoMetrics::StepTooSmall),
            Some(y) => Ok(y),
        }
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
        let stability = self.stability.get((self.plant, g), |(plant, gains)| {
            closed_loop_poles(&plant, &gains).ok().map(|p| p.stability)
        });
        if stability? != Stability::Stable {
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
        self.records = 0;
        self.sums = TermSums::default();
        self.state = RunState::Running;
        self.quiet_samples = 0;
        self.info = Err(NoMetrics::NotYet);
        self.setpoint_info = None;
        let y_final = self.measurable_final_value().ok();
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
                label: if at_setpoint(y, self.setpoint_m) {
                    "±2 % band".into()
                } else {
                    format!("±2 % band around {}", format_metres(y))
                },
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
        if self.run.state.x_m.abs() > TRACK_END_M {
            self.state = RunState::OffTrack;
        } else if self.time_s() >= RECORD_S - 1e-9 {
            self.state = RunState::Complete;
        }
    }

    /// Appends the position and the period's mean force terms (a mean keeps
    /// the impulse of a derivative kick visible however short it is).
    fn record(&mut self) {
        self.records += 1;
        let t = self.records as f64 / RECORDS_PER_S;
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
            let from = (self.records - 1) as f64 / RECORDS_PER_S;
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
        let y_final = self.measurable_final_value();
        let (running, now_s) = (self.state == RunState::Running, self.time_s());
        let response = &mut self.plots[0];
        let series = &response.series[0];
        self.info = y_final.and_then(|y| {
            step_info(&series.x, &series.y, 0.0, self.setpoint_m, Some(y)).ok_or(NoMetrics::NotYet)
        });
        if let Ok(info) = &mut self.info {
            if running
                && info
                    .settling_time_s
                    .is_some_and(|ts| now_s - ts < SETTLE_DWELL_S - 1e-9)
            {
                info.settling_time_s = None;
            }
        }
        let r = self.setpoint_m;
        self.setpoint_info = match y_final {
            Err(NoMetrics::NoFinalValue) if r.abs() >= MIN_STEP_M => {
                step_info(&series.x, &series.y, 0.0, r, Some(r))
            }
            _ => None,
        };
        response.markers.clear();
        if let Some(info) = self.setpoint_info.filter(|i| i.overshoot_pct > 0.0) {
            response.markers.push(Marker {
                x: info.peak_time_s,
                y: info.peak,
                label: format!("peak {}", percent(info.overshoot_pct)),
            });
        }
        let (Ok(info), Ok(y_inf)) = (self.info, y_final) else {
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
                label: format!("peak {}", percent(info.overshoot_pct)),
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
        let free = (0..MAX_PINS).find(|k| self.pins.iter().all(|p| p.slot != *k));
        let (slot, replaced) = match free {
            Some(k) => (k, false),
            None => (self.pins.remove(0).slot, true),
        };
        self.pins_made += 1;
        let pin = Pin {
            slot,
            number: self.pins_made,
            gains: self.gains,
            info: self.info,
            time_s: self.time_s(),
            finished: self.state != RunState::Running,
        };
        let response = &mut self.plots[0];
        let (x, y) = (response.series[0].x.clone(), response.series[0].y.clone());
        let series = &mut response.series[1 + slot];
        series.x = x;
        series.y = y;
        series.label = pin.legend();
        response.touch();
        if replaced {
            self.notices.post(
                format!(
                    "pinned as run {}: it replaces the oldest pin, in slot {}",
                    PIN_LETTERS[slot], PIN_LETTERS[slot]
                ),
                Tone::Neutral,
            );
        } else if !pin.finished {
            self.notices.post(
                format!(
                    "pinned at {}: its metrics are those of the response so far",
                    seconds(Some(pin.time_s))
                ),
                Tone::Neutral,
            );
        } else {
            self.notices.clear();
        }
        self.pins.push(pin);
    }

    fn clear_pins(&mut self) {
        self.pins.clear();
        for (series, name) in self.plots[0].series[1..].iter_mut().zip(PIN_NAMES) {
            series.x.clear();
            series.y.clear();
            series.label = name.into();
        }
        self.plots[0].touch();
        self.notices.clear();
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

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "Overshoot vs damping: little damping",
        description: "Kp 40 with Kd 1: the cart shoots about 60 % past the setpoint and rings before it settles.",
        query: "kp=40&ki=0&kd=1",
    },
    crate::experiment::Preset {
        name: "Overshoot vs damping: plenty of damping",
        description: "The same Kp 40 with Kd 12: no overshoot at all; compare the two runs.",
        query: "kp=40&ki=0&kd=12",
    },
    crate::experiment::Preset {
        name: "A push leaves an offset",
        description: "A constant push of 5 N and no integral action: the cart stops d / Kp = 0.25 m past the setpoint.",
        query: "kp=20&ki=0&kd=6&d=5",
    },
];

impl Experiment for PidControl {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

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
        // The metrics are a function of the response so far and the run's
        // state alone: a replay computes them once, at its end.
        if self.replaying {
            self.metrics_stale = true;
        } else {
            self.update_metrics();
        }
        self.plots.iter_mut().for_each(Plot::touch);
    }

    fn begin_replay(&mut self) {
        self.replaying = true;
    }

    /// The metrics and markers of the response so far: what the last
    /// replayed step would have computed, since the state has not moved
    /// since (a step after the run went quiet changes nothing).
    fn end_replay(&mut self) {
        self.replaying = false;
        if std::mem::take(&mut self.metrics_stale) {
            self.update_metrics();
        }
    }

    /// The pinned runs of `end` (their slots, numbers and curves) in place
    /// of these: a past moment of the run shows the pins its end has.
    fn take_comparisons(&mut self, end: &dyn std::any::Any) {
        // Pins are only ever added (each numbered) or all cleared: the same
        // count made and kept is the same pins (a replay frame asks again,
        // and copies nothing).
        let Some(end) = end
            .downcast_ref::<Self>()
            .filter(|e| (e.pins_made, e.pins.len()) != (self.pins_made, self.pins.len()))
        else {
            return;
        };
        // A copy of the end (the clone a snapshot takes) hands over its pins.
        let mut end = end.clone();
        std::mem::swap(&mut self.pins, &mut end.pins);
        self.pins_made = end.pins_made;
        let theirs = end.plots[0].series.iter_mut().skip(1);
        for (mine, theirs) in self.plots[0].series.iter_mut().skip(1).zip(theirs) {
            std::mem::swap(mine, theirs);
        }
        self.plots[0].touch();
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

    /// The setpoint marker (it moves along x only).
    fn handles(&self) -> Vec<crate::experiment::Handle> {
        vec![crate::experiment::Handle::along_x(
            "setpoint",
            "Setpoint",
            DVec2::new(self.setpoint_m, MARKER_TOP_M),
        )]
    }

    fn animating(&self) -> bool {
        self.state == RunState::Running
    }
}

pub use quiz::quiz_generator;

#[cfg(test)]
mod tests;
