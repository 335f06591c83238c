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
//! sub-steps of explicit Euler (the CartPole-v1 update) or RK4.
//!
//! **Linear against nonlinear.** Beside the real pole, the linearised model
//! `ṡ = A s + B F` ([`LinearModel`]) runs from the same start under the same
//! feedback, the same force limit, the same integrator and the same nudges,
//! so the only difference between the two is the plant's nonlinearity
//! (`sin θ ≈ θ`, `cos θ ≈ 1`, no `θ̇²` term, no end stops). Its θ and x are
//! overlaid on the plots; they agree for small start angles and part as
//! the start angle grows.
//!
//! **LQR.** "LQR gains" solves the continuous algebraic Riccati equation for
//! the chosen diagonal `Q` and `R` ([`lqr_feedback`]) and puts the resulting
//! gains (rounded to 0.01) on the sliders; the proposal is shown before it
//! is applied.
//!
//! **Energy** `E = ½(M + m)ẋ² + m l ẋ θ̇ cos θ + ⅔ m l² θ̇² + m g l cos θ`
//! is plotted; with control off it stays flat under RK4 and creeps under
//! Euler.

use crate::control::cartpole::{
    closed_loop_eigenvalues, lqr_feedback, open_loop_eigenvalues, CartPole, CartPoleParams,
    CartPoleState, FallCriterion, Integrator, LinearModel, LqrWeights, PoleStatus, StateFeedback,
    NUDGE_RAD_S,
};
use crate::control::{Complex, Stability};
use crate::experiment::{
    check_param, format_fixed, ActionSpec, Experiment, Input, ParamError, ParamSpec, Readout,
    Sanitized, Status, Tone,
};
use crate::plot::{Axis, Band, Plot, RefLine, Series, SeriesRole, XWindow};
use crate::quiz::{format_number, Draw, Generator};
use crate::rng::Lcg64;
use crate::scene::{Item, Role, Scene, ViewBox};
use glam::DVec2;

const INTEGRATORS: &[&str] = &["Euler (CartPole-v1)", "RK4"];
const CRITERIA: &[&str] = &["|θ| > 90°", "|θ| > 12° or |x| > 2.4 m (CartPole-v1)"];

const PARAMS: &[ParamSpec] = &[
    ParamSpec::slider("kth", "kθ", "N/rad", 0.0, 600.0, 0.1, 120.0),
    ParamSpec::slider("kom", "kω", "N·s/rad", 0.0, 150.0, 0.1, 18.0),
    ParamSpec::slider("kx", "kx", "N/m", -50.0, 150.0, 0.1, 3.0),
    ParamSpec::slider("kv", "kv", "N·s/m", -50.0, 150.0, 0.1, 6.0),
    ParamSpec::slider("th0", "Start angle θ₀", "°", -60.0, 60.0, 0.1, 6.0),
    ParamSpec::toggle("ctl", "Control", "off", "on", true),
    ParamSpec::choice("integ", "Integrator", INTEGRATORS, 0),
    ParamSpec::choice("fall", "Fallen when", CRITERIA, 0),
    ParamSpec::slider("flim", "Force limit", "N", 1.0, 100.0, 1.0, 30.0),
    ParamSpec::slider("qx", "LQR weight q_x", "", 0.0, 100.0, 0.1, 1.0),
    ParamSpec::slider("qv", "LQR weight q_ẋ", "", 0.0, 100.0, 0.1, 1.0),
    ParamSpec::slider("qth", "LQR weight q_θ", "", 0.0, 100.0, 0.1, 10.0),
    ParamSpec::slider("qom", "LQR weight q_θ̇", "", 0.0, 100.0, 0.1, 1.0),
    ParamSpec::slider("r", "LQR weight R", "", 0.01, 10.0, 0.01, 0.1),
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
        key: "catch",
        label: "Control on",
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

/// Drawing: cart body, pivot height and track.
const CART_HALF_W_M: f64 = 0.25;
const CART_BOTTOM_M: f64 = 0.06;
const PIVOT_Y_M: f64 = 0.3;
const VIEW_MIN: DVec2 = DVec2::new(-3.0, -0.5);
const VIEW_MAX: DVec2 = DVec2::new(3.0, 1.5);
/// Force arrow length per newton (m).
const ARROW_M_PER_N: f64 = 0.02;
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
    /// θ (nonlinear and linear), x (both), force, energy.
    plots: [Plot; 4],
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
            "Total mechanical energy",
            time,
            ("E", "J"),
            vec![Series::new("E", "J", SeriesRole::Quaternary)],
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
            plots: new_plots(),
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
        if self.fall_choice == 1 {
            FallCriterion::benchmark()
        } else {
            FallCriterion::horizontal()
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
            value: self.start_energy_j,
            label: "E at start".into(),
        }];
        self.record(false);
        self.check_status();
    }

    /// Appends the current sample to every plot and drops samples older than [`KEEP_S`].
    fn record(&mut self, saturated: bool) {
        let t = self.sim.time_s;
        let s = self.sim.state;
        let [angle, position, force, energy] = &mut self.plots;
        angle.series[0].push(t, s.theta_rad.to_degrees());
        angle.series[1].push(t, self.linear.theta_rad.to_degrees());
        position.series[0].push(t, s.x_m);
        position.series[1].push(t, self.linear.x_m);
        force.series[0].push(t, self.sim.last_force_n());
        energy.series[0].push(t, self.sim.energy_j());
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
            if plot.series[0]
                .x
                .first()
                .is_some_and(|x0| *x0 < oldest - 1.0)
            {
                for series in &mut plot.series {
                    let cut = series.x.iter().take_while(|x| **x < oldest).count();
                    series.x.drain(..cut);
                    series.y.drain(..cut);
                }
                plot.bands.retain(|b| b.hi >= oldest);
            }
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
        self.record(self.sim.last_saturated());
        self.check_status();
    }

    /// A push on the pole: `±`[`NUDGE_RAD_S`] added to θ̇ of both models.
    fn nudge(&mut self, direction: f64) {
        if self.run != Run::Going || direction == 0.0 || !direction.is_finite() {
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

    fn quiet(&self) -> bool {
        let s = self.sim.state;
        self.sim.control_enabled && s.to_array().iter().all(|v| v.abs() < QUIET)
    }
}

/// `3.972, -3.972, 0, 0` or `-1.234 ± 5.678i`, slowest first.
fn format_eigenvalues(z: &[Complex]) -> String {
    let mut sorted: Vec<Complex> = z.iter().copied().filter(|p| p.im >= 0.0).collect();
    sorted.sort_by(|a, b| b.re.total_cmp(&a.re));
    sorted
        .iter()
        .map(|p| {
            if p.im == 0.0 {
                format_fixed(p.re, 3)
            } else {
                format!("{} ± {}i", format_fixed(p.re, 3), format_fixed(p.im, 3))
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn gains_text(k: &StateFeedback) -> String {
    format!(
        "kθ {}, kω {}, kx {}, kv {}",
        format_fixed(k.k_theta, 2),
        format_fixed(k.k_omega, 2),
        format_fixed(k.k_x, 2),
        format_fixed(k.k_v, 2)
    )
}

impl Experiment for CartPoleBalance {
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
            "catch" => self.sim.control_enabled = true,
            "lqr" => {
                if let Some(k) = self.lqr_proposal() {
                    self.sim.gains = k;
                }
            }
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

    fn step(&mut self, dt_s: f64) {
        if !crate::clock::valid_dt(dt_s) || self.run != Run::Going {
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

    fn view(&self) -> ViewBox {
        ViewBox {
            min: VIEW_MIN,
            max: VIEW_MAX,
        }
    }

    fn scene(&self, out: &mut Scene) {
        let track = self.sim.params.track_limit_m;
        out.push(Item::Line {
            from: DVec2::new(VIEW_MIN.x, 0.0),
            to: DVec2::new(VIEW_MAX.x, 0.0),
            width_px: 2.0,
            role: Role::Bound,
            dashed: false,
        });
        if track.is_finite() {
            for side in [-1.0, 1.0] {
                let x = side * (track + CART_HALF_W_M);
                out.push(Item::Rect {
                    min: DVec2::new(x - 0.04, 0.0),
                    max: DVec2::new(x + 0.04, 0.35),
                    role: Role::Obstacle,
                    fill: true,
                });
            }
        }
        for k in -2..=2 {
            let x = f64::from(k);
            out.push(Item::Line {
                from: DVec2::new(x, 0.0),
                to: DVec2::new(x, -0.08),
                width_px: 1.0,
                role: Role::Grid,
                dashed: false,
            });
            out.push(Item::Label {
                pos: DVec2::new(x, -0.08),
                text: format!("{k} m"),
                role: Role::Text,
                offset_px: DVec2::new(-8.0, 12.0),
            });
        }
        // The linear model as a ghost.
        let lin = self.linear;
        let lin_x = lin.x_m.clamp(-100.0, 100.0);
        out.push(Item::Rect {
            min: DVec2::new(lin_x - CART_HALF_W_M, CART_BOTTOM_M),
            max: DVec2::new(lin_x + CART_HALF_W_M, PIVOT_Y_M),
            role: Role::Ghost,
            fill: false,
        });
        let lin_tip = self.tip_of(&CartPoleState { x_m: lin_x, ..lin });
        out.push(Item::Line {
            from: DVec2::new(lin_x, PIVOT_Y_M),
            to: lin_tip,
            width_px: 3.0,
            role: Role::Ghost,
            dashed: true,
        });
        // Where the chosen criterion calls the pole fallen (12°).
        let limit = self.criterion().angle_limit_rad;
        let pivot = self.pivot();
        if limit < 1.0 {
            for side in [-1.0, 1.0] {
                let (sin, cos) = crate::math::sin_cos(side * limit);
                out.push(Item::Line {
                    from: pivot,
                    to: pivot + DVec2::new(sin, cos) * 1.1,
                    width_px: 1.0,
                    role: Role::Warning,
                    dashed: true,
                });
            }
        }
        // The cart, wheels, pole and force.
        let x = pivot.x;
        out.push(Item::Rect {
            min: DVec2::new(x - CART_HALF_W_M, CART_BOTTOM_M),
            max: DVec2::new(x + CART_HALF_W_M, PIVOT_Y_M),
            role: Role::Robot,
            fill: true,
        });
        for dx in [-0.15, 0.15] {
            out.push(Item::Circle {
                center: DVec2::new(x + dx, 0.035),
                radius_m: 0.035,
                role: Role::Joint,
                fill: true,
                dashed: false,
            });
        }
        let tip = self.tip_of(&self.sim.state);
        let fallen = matches!(self.run, Run::Ended { .. });
        out.push(Item::Line {
            from: pivot,
            to: tip,
            width_px: 7.0,
            role: if fallen { Role::Warning } else { Role::Link },
            dashed: false,
        });
        out.push(Item::Dot {
            center: pivot,
            radius_px: 6.0,
            role: Role::Joint,
        });
        out.push(Item::Dot {
            center: tip,
            radius_px: 8.0,
            role: Role::Tip,
        });
        let f = self.sim.last_force_n();
        if f.abs() > 0.05 {
            let y = 0.5 * (CART_BOTTOM_M + PIVOT_Y_M);
            let start = x + CART_HALF_W_M.copysign(f);
            out.push(Item::Arrow {
                from: DVec2::new(start, y),
                to: DVec2::new(start + f * ARROW_M_PER_N, y),
                width_px: 3.0,
                role: Role::Accent,
            });
        }
        out.push(Item::Label {
            pos: DVec2::new(x, 0.0),
            text: format!("F = {} N", format_fixed(f, 1)),
            role: Role::Text,
            offset_px: DVec2::new(-24.0, 44.0),
        });
    }

    fn readouts(&self) -> Vec<Readout> {
        let s = self.sim.state;
        let verdict = |z: &[Complex]| match Stability::of(z) {
            Stability::Stable => "stable",
            Stability::MarginallyStable => "marginally stable",
            Stability::Unstable => "unstable",
        };
        let closed = closed_loop_eigenvalues(&self.sim.params, &self.sim.gains).ok();
        let open = open_loop_eigenvalues(&self.sim.params).ok();
        let status = match self.run {
            Run::Going if !self.sim.control_enabled => "up, control off".to_owned(),
            Run::Going => "up".to_owned(),
            Run::Ended { status, time_s } => format!(
                "{} at {} s",
                if status == PoleStatus::OutOfBounds {
                    "off the track"
                } else {
                    "fallen"
                },
                format_fixed(time_s, 2)
            ),
        };
        vec![
            Readout::degrees("theta", "Pole angle θ", s.theta_rad.to_degrees()),
            Readout::new(
                "omega",
                "Angular velocity θ̇",
                format!("{}°/s", format_fixed(s.omega_rad_s.to_degrees(), 1)),
            ),
            Readout::metres("x", "Cart position x", s.x_m),
            Readout::new(
                "force",
                "Force F",
                format!("{} N", format_fixed(self.sim.last_force_n(), 2)),
            ),
            Readout::new("status", "Status", status),
            Readout::new(
                "energy",
                "Energy E",
                format!("{} J", format_fixed(self.sim.energy_j(), 4)),
            ),
            Readout::new(
                "closed_eig",
                "Closed-loop eigenvalues (1/s)",
                closed.as_deref().map_or("--".into(), format_eigenvalues),
            ),
            Readout::new(
                "closed_verdict",
                "Closed loop (linearised)",
                closed.as_deref().map_or("--", verdict),
            ),
            Readout::new(
                "open_eig",
                "Open-loop eigenvalues (1/s)",
                open.as_deref().map_or("--".into(), format_eigenvalues),
            ),
            Readout::new(
                "lqr",
                "LQR proposal for Q, R",
                self.lqr_proposal()
                    .map_or("no solution".into(), |k| gains_text(&k)),
            ),
            Readout::degrees(
                "gap",
                "Linear model gap, max |Δθ|",
                self.max_gap_rad.to_degrees(),
            ),
        ]
    }

    fn status(&self) -> Status {
        match self.run {
            Run::Ended { status, time_s } => Status::new(
                format!(
                    "{} at t = {} s: press Reset",
                    if status == PoleStatus::OutOfBounds {
                        "cart off the track"
                    } else {
                        "pole fallen"
                    },
                    format_fixed(time_s, 2)
                ),
                Tone::Bad,
            ),
            Run::Going if !self.sim.control_enabled => {
                Status::new("control off: the pole is falling", Tone::Warning)
            }
            Run::Going if self.quiet() => Status::new("balanced", Tone::Good),
            Run::Going => Status::new("up: balancing", Tone::Neutral),
        }
    }

    fn hint(&self) -> &'static str {
        "Tap beside the pole (or use ← →) to nudge it; drag its tip to set the start angle. Drop pole switches control off."
    }

    /// A pole caught from its start angle, a second into the run.
    fn preview(&mut self) {
        for _ in 0..60 {
            self.step(1.0 / 60.0);
        }
    }

    fn animating(&self) -> bool {
        self.run == Run::Going && !self.quiet()
    }
}

/// Draws a cart-pole: cart mass `M`, pole mass `m`, half-length `l`.
fn draw_cart_pole(rng: &mut Lcg64) -> CartPoleParams {
    CartPoleParams {
        cart_mass_kg: rng.int(2, 20) as f64 * 0.25,
        pole_mass_kg: rng.int(1, 10) as f64 * 0.05,
        half_length_m: rng.int(1, 8) as f64 * 0.125,
        ..CartPoleParams::default()
    }
}

/// The unstable open-loop eigenvalue `√(g/D)`, `D = l(4/3 − m/(M + m))`.
fn quiz_unstable_eigenvalue(rng: &mut Lcg64) -> Draw {
    let p = draw_cart_pole(rng);
    let answer = open_loop_eigenvalues(&p)
        .ok()
        .map(|z| z.iter().fold(0.0_f64, |m, e| m.max(e.re)))
        .unwrap_or(0.0);
    Draw {
        vars: vec![
            ("cart", format_number(p.cart_mass_kg, 3)),
            ("pole", format_number(p.pole_mass_kg, 3)),
            ("half", format_number(p.half_length_m, 3)),
        ],
        answer,
    }
}

/// The feedback force `kθ·θ + kω·θ̇ + kx·x + kv·ẋ` for a drawn state.
fn quiz_feedback_force(rng: &mut Lcg64) -> Draw {
    let k = StateFeedback {
        k_theta: rng.int(40, 200) as f64,
        k_omega: rng.int(5, 40) as f64,
        k_x: rng.int(1, 10) as f64,
        k_v: rng.int(1, 12) as f64,
    };
    let theta_deg = rng.int(-10, 10) as f64;
    let omega = rng.int(-20, 20) as f64 / 10.0;
    let x = rng.int(-10, 10) as f64 / 10.0;
    let v = rng.int(-10, 10) as f64 / 10.0;
    let s = CartPoleState {
        x_m: x,
        v_m_s: v,
        theta_rad: theta_deg.to_radians(),
        omega_rad_s: omega,
    };
    Draw {
        vars: vec![
            ("kth", format_number(k.k_theta, 2)),
            ("kom", format_number(k.k_omega, 2)),
            ("kx", format_number(k.k_x, 2)),
            ("kv", format_number(k.k_v, 2)),
            ("theta", format_number(theta_deg, 1)),
            ("omega", format_number(omega, 2)),
            ("x", format_number(x, 2)),
            ("v", format_number(v, 2)),
        ],
        answer: k.force_n(&s),
    }
}

/// How far `sin θ` falls below `θ`, in percent: `100·(θ − sin θ)/sin θ`.
fn quiz_small_angle(rng: &mut Lcg64) -> Draw {
    let deg = rng.int(5, 60) as f64;
    let t = deg.to_radians();
    let sin = crate::math::sin(t);
    Draw {
        vars: vec![("deg", format_number(deg, 0))],
        answer: 100.0 * (t - sin) / sin,
    }
}

/// The quiz generators of experiment 8, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "unstable_eigenvalue" => Some(quiz_unstable_eigenvalue),
        "feedback_force" => Some(quiz_feedback_force),
        "small_angle" => Some(quiz_small_angle),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::count_right_half_plane;
    use crate::route::{format, restore, Tab};

    fn run(e: &mut CartPoleBalance, seconds: f64) {
        for _ in 0..(seconds * 60.0).round() as usize {
            e.step(1.0 / 60.0);
        }
    }

    fn readout(e: &CartPoleBalance, key: &str) -> String {
        crate::experiment::readout_value(e, key).unwrap_or_else(|| panic!("no readout {key}"))
    }

    #[test]
    fn readouts_by_hand_at_the_start() {
        let e = CartPoleBalance::default();
        assert_eq!(readout(&e, "theta"), "6.0°");
        assert_eq!(readout(&e, "x"), "0.000 m");
        assert_eq!(readout(&e, "status"), "up");
        // √(g/D), D = l(4/3 − m/(M + m)) = 0.5·(4/3 − 0.1/1.1) = 0.62121…
        let d = 0.5 * (4.0 / 3.0 - 0.1 / 1.1);
        let unstable = (9.8_f64 / d).sqrt();
        assert_eq!(
            readout(&e, "open_eig"),
            format!(
                "{}, 0.000, 0.000, -{}",
                format_fixed(unstable, 3),
                format_fixed(unstable, 3)
            )
        );
        // Energy at rest with the pole at 6°: m g l cos θ.
        let energy = 0.1 * 9.8 * 0.5 * 6f64.to_radians().cos();
        assert_eq!(
            readout(&e, "energy"),
            format!("{} J", format_fixed(energy, 4))
        );
        assert_eq!(readout(&e, "closed_verdict"), "stable");
        assert_eq!(e.status().tone, Tone::Neutral);
    }

    #[test]
    fn the_default_gains_catch_the_pole_and_recover_from_a_nudge() {
        let mut e = CartPoleBalance::default();
        run(&mut e, 2.0);
        assert!(e.state().theta_rad.abs() < 1f64.to_radians());
        e.action("nudge").unwrap();
        assert!(e.state().omega_rad_s > 0.4);
        run(&mut e, 10.0);
        assert_eq!(readout(&e, "status"), "up");
        assert!(
            e.state().theta_rad.abs() < 0.2f64.to_radians(),
            "{:?}",
            e.state()
        );
        assert!(e.state().x_m.abs() < 0.5, "{:?}", e.state());
    }

    /// The linearised open loop has exactly one right-half-plane eigenvalue;
    /// the LQR button puts gains on the sliders whose closed loop has none,
    /// and the pole is then held.
    #[test]
    fn lqr_gains_give_a_stable_closed_loop() {
        let mut e = CartPoleBalance::default();
        let open = open_loop_eigenvalues(&e.sim.params).unwrap();
        assert_eq!(count_right_half_plane(&open), 1);
        let proposal = e.lqr_proposal().unwrap();
        assert_eq!(readout(&e, "lqr"), gains_text(&proposal));
        e.set_param("kth", 0.0).unwrap();
        assert_eq!(readout(&e, "closed_verdict"), "unstable");
        e.action("lqr").unwrap();
        assert_eq!(e.gains(), proposal);
        for (key, v) in [("kth", proposal.k_theta), ("kx", proposal.k_x)] {
            assert_eq!(e.param(key), Some(v));
            assert_eq!(v, (v * 100.0).round() / 100.0, "rounded like the slider");
        }
        let closed = closed_loop_eigenvalues(&e.sim.params, &e.gains()).unwrap();
        assert!(closed.iter().all(|z| z.re < 0.0), "{closed:?}");
        assert_eq!(readout(&e, "closed_verdict"), "stable");
        // Heavier weight on θ gives a stiffer angle loop.
        e.set_param("qth", 100.0).unwrap();
        assert!(e.lqr_proposal().unwrap().k_theta > proposal.k_theta);
        e.restart();
        run(&mut e, 20.0);
        assert_eq!(e.status().text, "balanced");
        assert!(!e.animating(), "a balanced pole lets the page idle");
    }

    /// The closed-loop polynomial of the default cart gains is
    /// s⁴ + a₃s³ + a₂s² + a₁s + a₀ with a₂ = 1.4634·kθ − 18.70 (by hand from
    /// A + B k); Hurwitz's a₃a₂a₁ > a₁² + a₃²a₀ needs kθ > 22.65 N/rad, well
    /// above the (M + m)·g = 10.78 N/rad of angle feedback alone. The
    /// procedure quotes "about 23".
    #[test]
    fn the_default_cart_gains_need_k_theta_above_about_23() {
        let mut e = CartPoleBalance::default();
        e.set_param("kth", 23.5).unwrap();
        assert_eq!(readout(&e, "closed_verdict"), "stable");
        e.set_param("kth", 22.0).unwrap();
        assert_eq!(readout(&e, "closed_verdict"), "unstable");
    }

    #[test]
    fn energy_stays_flat_under_rk4_with_control_off() {
        let drift = |integrator: f64| {
            let mut e = CartPoleBalance::default();
            e.set_param("integ", integrator).unwrap();
            e.set_param("th0", 10.0).unwrap();
            e.action("drop").unwrap();
            assert_eq!(e.param("ctl"), Some(0.0));
            run(&mut e, 5.0);
            assert_eq!(e.status().tone, Tone::Bad, "the dropped pole falls");
            let energy = &e.plots()[3].series[0].y;
            assert!(energy.len() > 20);
            let (lo, hi) = energy
                .iter()
                .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(*v), hi.max(*v)));
            (hi - lo) / energy[0].abs()
        };
        let rk4 = drift(1.0);
        let euler = drift(0.0);
        assert!(rk4 < 1e-6, "RK4 relative drift {rk4}");
        assert!(euler > 100.0 * rk4, "Euler {euler} vs RK4 {rk4}");
    }

    #[test]
    fn the_linear_model_agrees_at_2_degrees_and_parts_at_30() {
        let relative_gap = |deg: f64| {
            let mut e = CartPoleBalance::default();
            e.set_param("th0", deg).unwrap();
            run(&mut e, 5.0);
            let angle = &e.plots()[0];
            assert_eq!(angle.series[0].len(), angle.series[1].len());
            let gap = angle.series[0]
                .y
                .iter()
                .zip(&angle.series[1].y)
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            assert!((gap - e.max_gap_rad().to_degrees()).abs() < 1e-9);
            gap / deg
        };
        let small = relative_gap(2.0);
        let large = relative_gap(30.0);
        assert!(small < 1e-3, "2°: {small}");
        assert!(large > 0.02, "30°: {large}");
        // Nudges reach both models, so they stay together at small angles.
        let mut e = CartPoleBalance::default();
        e.set_param("th0", 2.0).unwrap();
        e.input(Input::Nudge(DVec2::new(-0.1, 0.0)));
        assert_eq!(e.state().omega_rad_s, e.linear_state().omega_rad_s);
        assert!(e.state().omega_rad_s < 0.0);
    }

    #[test]
    fn drop_and_catch() {
        let mut e = CartPoleBalance::default();
        run(&mut e, 3.0);
        e.action("drop").unwrap();
        assert_eq!(e.status().tone, Tone::Warning);
        e.action("nudge").unwrap();
        run(&mut e, 0.3);
        let leaning = e.state().theta_rad;
        assert!(leaning > 4f64.to_radians(), "{leaning}");
        assert!(
            e.linear_state().theta_rad > 4f64.to_radians(),
            "the linear model falls too"
        );
        e.action("catch").unwrap();
        run(&mut e, 8.0);
        assert_eq!(readout(&e, "status"), "up");
        assert!(e.state().theta_rad.abs() < 1f64.to_radians());
    }

    #[test]
    fn the_fall_criterion_is_selectable_and_ends_the_run() {
        let fall_time = |choice: f64| {
            let mut e = CartPoleBalance::default();
            e.set_param("fall", choice).unwrap();
            e.action("drop").unwrap();
            run(&mut e, 5.0);
            assert!(!e.animating());
            let Run::Ended { status, time_s } = e.run else {
                panic!("still going")
            };
            assert_eq!(status, PoleStatus::Fallen);
            let frozen = e.state();
            run(&mut e, 1.0);
            assert_eq!(e.state(), frozen, "a fallen run stays put");
            (time_s, e.state().theta_rad.to_degrees())
        };
        let (t90, th90) = fall_time(0.0);
        let (t12, th12) = fall_time(1.0);
        assert!(th90 > 90.0 && th90 < 100.0, "{th90}");
        assert!(th12 > 12.0 && th12 < 15.0, "{th12}");
        assert!(t12 < t90);
        let mut e = CartPoleBalance::default();
        e.set_param("fall", 1.0).unwrap();
        e.action("drop").unwrap();
        run(&mut e, 5.0);
        assert!(readout(&e, "status").starts_with("fallen at "));
        assert!(e.status().text.starts_with("pole fallen at t = "));
    }

    #[test]
    fn force_is_limited_and_shaded() {
        let mut e = CartPoleBalance::default();
        e.set_param("flim", 5.0).unwrap();
        e.set_param("th0", 8.0).unwrap();
        run(&mut e, 2.0);
        let force = &e.plots()[2];
        assert!(force.series[0].y.iter().all(|f| f.abs() <= 5.0 + 1e-12));
        assert!(!force.bands.is_empty());
        assert!(force.bands.iter().all(|b| b.axis == Axis::X && b.hi > b.lo));
        assert_eq!(force.ref_lines[0].value, 5.0);
    }

    #[test]
    fn dragging_the_tip_sets_the_start_angle() {
        let mut e = CartPoleBalance::default();
        let tip = e.tip_of(&e.state());
        assert!(e.handle_at(tip, 0.05));
        e.input(Input::PointerDown(tip));
        // 45° to the left of the pivot at x = 0.
        e.input(Input::PointerMove {
            pos: DVec2::new(-0.5, PIVOT_Y_M + 0.5),
            pressed: true,
        });
        assert_eq!(e.param("th0"), Some(-45.0));
        assert_eq!(e.time_s(), 0.0);
        e.input(Input::PointerMove {
            pos: DVec2::new(-1.0, PIVOT_Y_M - 0.2),
            pressed: true,
        });
        assert_eq!(e.param("th0"), Some(-60.0), "kept in range");
        e.input(Input::PointerUp(DVec2::ZERO));
        // A tap to the right, away from the tip, nudges the pole that way.
        e.input(Input::PointerDown(DVec2::new(2.0, 0.2)));
        assert!(e.state().omega_rad_s > 0.0);
        assert_eq!(e.param("th0"), Some(-60.0));
    }

    /// Data older than a minute is dropped, so a long run stays bounded.
    #[test]
    fn plots_keep_the_last_minute() {
        let mut e = CartPoleBalance::default();
        e.set_param("integ", 1.0).unwrap();
        for _ in 0..(90 * 60) {
            if !e.animating() {
                e.action("nudge").unwrap();
            }
            e.step(1.0 / 60.0);
        }
        for plot in e.plots() {
            let x = &plot.series[0].x;
            assert!(
                x[0] >= e.time_s() - KEEP_S - 1.0 - 1e-9,
                "{} {}",
                plot.key,
                x[0]
            );
            assert!(x.len() <= ((KEEP_S + 1.0) / CONTROL_PERIOD_S) as usize + 2);
        }
    }

    #[test]
    fn every_parameter_round_trips_through_the_link() {
        let mut e = CartPoleBalance::default();
        for (k, v) in [
            ("kth", 80.5),
            ("kom", 11.3),
            ("kx", -1.5),
            ("kv", 2.25),
            ("th0", -12.3),
            ("ctl", 0.0),
            ("integ", 1.0),
            ("fall", 1.0),
            ("flim", 12.0),
            ("qx", 2.0),
            ("qv", 0.5),
            ("qth", 40.0),
            ("qom", 3.0),
            ("r", 0.25),
        ] {
            e.set_param(k, v).unwrap();
        }
        let link = format(&e, Tab::Simulation);
        let (mut fresh, notices) = restore(&link, CartPoleBalance::default());
        assert!(notices.is_empty(), "{notices:?}");
        assert_eq!(format(&fresh, Tab::Simulation), link);
        for spec in PARAMS {
            assert_eq!(fresh.param(spec.key), e.param(spec.key), "{}", spec.key);
        }
        run(&mut e, 1.0);
        run(&mut fresh, 1.0);
        assert_eq!(e.state(), fresh.state());
    }

    #[test]
    fn bad_steps_and_inputs_change_nothing() {
        let mut e = CartPoleBalance::default();
        run(&mut e, 0.5);
        let before = (e.state(), e.time_s(), e.plots()[0].series[0].clone());
        for dt in [f64::NAN, -1.0, 0.0, 0.5, f64::INFINITY] {
            e.step(dt);
        }
        e.input(Input::PointerDown(DVec2::new(f64::NAN, 1.0)));
        e.input(Input::Nudge(DVec2::new(f64::NAN, 0.0)));
        assert_eq!(
            (e.state(), e.time_s(), e.plots()[0].series[0].clone()),
            before
        );
        assert!(e.set_param("kth", f64::INFINITY).is_err());
        assert!(e.action("nope").is_err());
    }

    #[test]
    fn quiz_generators_agree_with_the_formulas() {
        let mut rng = Lcg64::new(3);
        for _ in 0..200 {
            let d = quiz_unstable_eigenvalue(&mut rng);
            let (big, small, l) = (
                d.var("cart").unwrap(),
                d.var("pole").unwrap(),
                d.var("half").unwrap(),
            );
            let den = l * (4.0 / 3.0 - small / (big + small));
            assert!((d.answer - (9.8 / den).sqrt()).abs() < 1e-6, "{d:?}");
            let d = quiz_feedback_force(&mut rng);
            let v = |k: &str| d.var(k).unwrap();
            let f = v("kth") * v("theta").to_radians()
                + v("kom") * v("omega")
                + v("kx") * v("x")
                + v("kv") * v("v");
            assert!((d.answer - f).abs() < 1e-9);
            let d = quiz_small_angle(&mut rng);
            let t = v_rad(d.var("deg").unwrap());
            assert!((d.answer - 100.0 * (t - t.sin()) / t.sin()).abs() < 1e-9);
        }
    }

    fn v_rad(deg: f64) -> f64 {
        deg.to_radians()
    }
}
