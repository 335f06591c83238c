//! Experiment 9 — n-link Jacobian inverse kinematics by damped least squares.
//!
//! Click a target and watch [`DlsSolver::step`] iterate
//! `Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e` at a chosen rate. The manipulability ellipse at
//! the tip has semi-axes `σᵢ uᵢ` (scaled by [`ELLIPSE_SCALE`]) from the
//! singular values and left singular vectors of the Jacobian.

use crate::experiment::{
    check_param, clamp_to_params, with_coordinate, ActionSpec, Experiment, Handle, Input,
    ParamError, ParamSpec, Sanitized,
};
use crate::kinematics::chain::Annulus;
use crate::kinematics::dls::{AdaptiveDamping, DlsSolver};
use crate::kinematics::jacobian::{jacobian, manipulability, Manipulability};
use crate::plot::{Plot, Series, SeriesRole};
use crate::quiz::{Draw, Generator};
use crate::rng::Lcg64;
use crate::units::format_number;
use glam::DVec2;

mod view;

const PARAMS: &[ParamSpec] = &[
    ParamSpec::slider("n", "Links", "", 2.0, 8.0, 1.0, 4.0).whole_numbers(),
    ParamSpec::slider("lambda", "λ", "m", 0.0, 1.0, 0.01, 0.1),
    ParamSpec::toggle("adaptive", "Adaptive damping", "off", "on", false),
    ParamSpec::toggle("guard", "Safeguards", "off", "on", true),
    ParamSpec::slider("rate", "Speed", "it/s", 1.0, 60.0, 1.0, 12.0),
    ParamSpec::slider("maxit", "Iteration limit", "", 20.0, 1000.0, 10.0, 500.0).whole_numbers(),
    ParamSpec::optional_number("tx", "Target x", "m", -VIEW_HALF_M, VIEW_HALF_M),
    ParamSpec::optional_number("ty", "Target y", "m", -VIEW_HALF_M, VIEW_HALF_M),
];

const ACTIONS: &[ActionSpec] = &[ActionSpec {
    key: "reset",
    label: "Reset pose",
}];

/// Total arm length, metres; each of the `n` links is `TOTAL_REACH_M / n`.
pub const TOTAL_REACH_M: f64 = 2.4;
/// Starting joint angle of every joint, radians.
pub const START_ANGLE_RAD: f64 = 0.3;
/// The drawn ellipse is the set of tip velocities for joint speeds `|q̇| ≤ ELLIPSE_SCALE` rad/s.
pub const ELLIPSE_SCALE: f64 = 0.3;
/// The animation stops once the error is below this, metres.
const TOLERANCE_M: f64 = 1e-6;
/// … or after the iteration limit (the `maxit` parameter, default 500) …
/// … or when the best error has not improved by [`PROGRESS_REL`] (relative)
/// for [`NO_PROGRESS_ITERATIONS`] iterations: at 12 it/s that is under 2 s,
/// where the bare update (λ = 0, no safeguards) would otherwise oscillate
/// around an unreachable target until the limit (about 40 s).
const NO_PROGRESS_ITERATIONS: usize = 20;
const PROGRESS_REL: f64 = 1e-3;
/// … or when the error changes by less than this for [`SETTLE_COUNT`] steps (unreachable target).
const SETTLE_DELTA_M: f64 = 1e-9;
const SETTLE_COUNT: usize = 5;
/// Adaptive damping starts below this manipulability (m²/rad) and reaches [`ADAPTIVE_LAMBDA_MAX_M`].
const ADAPTIVE_W0: f64 = 0.15;
const ADAPTIVE_LAMBDA_MAX_M: f64 = 0.4;
const VIEW_HALF_M: f64 = 2.7;
/// The link key of the pose a run started from (see [`Experiment::extra_state`]).
const RUN_START_KEY: &str = "q0";
/// Largest joint angle a link may give for `q0`, radians (the solver's
/// angles are not wrapped, but stay far below this).
const MAX_START_ANGLE_RAD: f64 = 1e6;

/// Why the iterations ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Run {
    Idle,
    Iterating,
    Converged,
    Settled,
    /// The error stopped improving for [`NO_PROGRESS_ITERATIONS`] iterations;
    /// `oscillating` when some of those steps went uphill.
    NoProgress {
        oscillating: bool,
    },
    GaveUp,
}

/// State of the DLS experiment.
#[derive(Clone, Debug)]
pub struct DampedLeastSquares {
    links: usize,
    lambda_m: f64,
    adaptive: bool,
    /// Levenberg–Marquardt step rejection and the 1 rad step clamp; off shows
    /// the bare update `Δq = Jᵀ(JJᵀ + λ²I)⁻¹e`.
    safeguards: bool,
    rate_hz: f64,
    /// The iteration limit (the visible `maxit` setting).
    max_iterations: usize,
    angles_rad: Vec<f64>,
    /// The joint angles the current run started from (the start pose, or
    /// where an earlier target left the arm): the time bar's Reset replays
    /// the run from here, and the link carries it (`q0`) when it differs
    /// from the start pose, so a link rebuilds the same run.
    run_start_rad: Vec<f64>,
    target: Option<DVec2>,
    run: Run,
    iterations: usize,
    error_m: Option<f64>,
    lambda_used_m: f64,
    clock_s: f64,
    flat_steps: usize,
    /// Error (log scale) and manipulability against iteration.
    plots: [Plot; 2],
    /// Smallest error so far in this run, metres, and iterations since it
    /// last improved by [`PROGRESS_REL`]; uphill steps among those.
    best_error_m: f64,
    since_best: usize,
    uphill_since_best: usize,
}

fn new_plots() -> [Plot; 2] {
    let mut error = Plot::new(
        "error",
        "Tip error",
        ("Iteration", ""),
        ("Error", "m"),
        vec![Series::new("error", "m", SeriesRole::Primary)],
    );
    error.log_y = true;
    let w = Plot::new(
        "manipulability",
        "Manipulability",
        ("Iteration", ""),
        ("w", "m²"),
        vec![Series::new("w", "m²", SeriesRole::Secondary)],
    );
    [error, w]
}

impl Default for DampedLeastSquares {
    fn default() -> Self {
        let links = PARAMS[0].default as usize;
        Self {
            links,
            lambda_m: PARAMS[1].default,
            adaptive: false,
            safeguards: true,
            rate_hz: PARAMS[4].default,
            max_iterations: PARAMS[5].default as usize,
            angles_rad: vec![START_ANGLE_RAD; links],
            run_start_rad: vec![START_ANGLE_RAD; links],
            target: None,
            run: Run::Idle,
            iterations: 0,
            error_m: None,
            lambda_used_m: PARAMS[1].default,
            clock_s: 0.0,
            flat_steps: 0,
            plots: new_plots(),
            best_error_m: f64::INFINITY,
            since_best: 0,
            uphill_since_best: 0,
        }
    }
}

impl DampedLeastSquares {
    fn lengths(&self) -> Vec<f64> {
        vec![TOTAL_REACH_M / self.links as f64; self.links]
    }

    fn solver(&self) -> DlsSolver {
        DlsSolver {
            damping: self.lambda_m,
            tolerance_m: TOLERANCE_M,
            max_iterations: 1,
            adaptive: self.adaptive.then_some(AdaptiveDamping {
                w_threshold: ADAPTIVE_W0,
                lambda_max: ADAPTIVE_LAMBDA_MAX_M,
            }),
            reject_uphill_steps: self.safeguards,
            max_step_rad: if self.safeguards {
                DlsSolver::default().max_step_rad
            } else {
                f64::INFINITY
            },
        }
    }

    /// The tip, metres.
    #[must_use]
    pub fn tip(&self) -> DVec2 {
        crate::kinematics::chain::tip(&self.lengths(), &self.angles_rad)
    }

    fn manipulability(&self) -> Manipulability {
        manipulability(&jacobian(&self.lengths(), &self.angles_rad))
    }

    /// Starts a new run from the current pose: the run's start, the damping
    /// shown, the iteration count, the stopping counters and the plots all
    /// begin again (with no target there is nothing to run).
    fn restart(&mut self) {
        self.run_start_rad.clone_from(&self.angles_rad);
        self.lambda_used_m = self.lambda_m;
        if self.target.is_some() {
            self.run = Run::Iterating;
            self.iterations = 0;
            self.flat_steps = 0;
            self.clock_s = 0.0;
            self.error_m = self.target.map(|t| (t - self.tip()).length());
            self.best_error_m = self.error_m.unwrap_or(f64::INFINITY);
            self.since_best = 0;
            self.uphill_since_best = 0;
            self.plots.iter_mut().for_each(Plot::clear);
            self.record();
        }
    }

    /// Appends the current error and manipulability to the plots.
    fn record(&mut self) {
        let i = self.iterations as f64;
        if let Some(e) = self.error_m {
            self.plots[0].series[0].push(i, e);
        }
        let w = self.manipulability().w;
        self.plots[1].series[0].push(i, w);
        self.plots.iter_mut().for_each(Plot::touch);
    }

    /// Sets the target from the pointer or a nudge, clamped to the range of
    /// the `tx`/`ty` fields so the link reproduces it.
    fn set_target(&mut self, p: DVec2) {
        if p.is_finite() {
            self.target = Some(clamp_to_params(PARAMS, "tx", "ty", p));
            self.restart();
        }
    }

    /// One DLS iteration towards the target; updates the run state.
    fn iterate(&mut self) {
        let Some(target) = self.target else { return };
        let lengths = self.lengths();
        let Ok(step) = self.solver().step(&lengths, &mut self.angles_rad, target) else {
            self.run = Run::GaveUp;
            return;
        };
        self.iterations += 1;
        self.lambda_used_m = step.lambda;
        self.error_m = Some(step.error_after_m);
        self.record();
        if (step.error_before_m - step.error_after_m).abs() < SETTLE_DELTA_M {
            self.flat_steps += 1;
        } else {
            self.flat_steps = 0;
        }
        if step.error_after_m < self.best_error_m * (1.0 - PROGRESS_REL) {
            self.best_error_m = step.error_after_m;
            self.since_best = 0;
            self.uphill_since_best = 0;
        } else {
            self.since_best += 1;
            if step.error_after_m > step.error_before_m {
                self.uphill_since_best += 1;
            }
        }
        let out_of_reach = !Annulus::of_chain(&lengths).contains(target, TOLERANCE_M);
        self.run = if step.error_after_m < TOLERANCE_M {
            Run::Converged
        } else if self.flat_steps >= SETTLE_COUNT {
            Run::Settled
        } else if self.since_best >= NO_PROGRESS_ITERATIONS {
            if self.uphill_since_best == 0 && out_of_reach {
                Run::Settled
            } else {
                Run::NoProgress {
                    oscillating: self.uphill_since_best > 0,
                }
            }
        } else if self.iterations >= self.max_iterations {
            Run::GaveUp
        } else {
            Run::Iterating
        };
    }
}

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "The bare update oscillates",
        description: "λ = 0 and no safeguards, a target just outside the reach: the joints jump and the run never converges.",
        query: "guard=0&lambda=0&tx=0&ty=2.5",
    },
    crate::experiment::Preset {
        name: "Adaptive damping settles",
        description: "The same kind of target with adaptive damping: λ rises near the singularity and the arm settles stretched.",
        query: "guard=0&lambda=0.01&adaptive=1&tx=0&ty=2.45",
    },
    crate::experiment::Preset {
        name: "Far outside the reach",
        description: "A target well beyond the arm: it settles fully stretched towards it, the gap left as the error.",
        query: "lambda=0.3&tx=2&ty=2",
    },
];

impl Experiment for DampedLeastSquares {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

    fn id(&self) -> &'static str {
        "dls"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        Some(match key {
            "n" => self.links as f64,
            "lambda" => self.lambda_m,
            "adaptive" => f64::from(u8::from(self.adaptive)),
            "guard" => f64::from(u8::from(self.safeguards)),
            "rate" => self.rate_hz,
            "maxit" => self.max_iterations as f64,
            "tx" => return self.target.map(|t| t.x),
            "ty" => return self.target.map(|t| t.y),
            _ => return None,
        })
    }

    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        match key {
            "n" => {
                let links = v.round() as usize;
                if links != self.links {
                    self.links = links;
                    self.angles_rad = vec![START_ANGLE_RAD; links];
                    self.run_start_rad = vec![START_ANGLE_RAD; links];
                }
            }
            "lambda" => {
                self.lambda_m = v;
                if self.run != Run::Iterating {
                    self.lambda_used_m = v;
                }
            }
            "adaptive" => self.adaptive = v >= 0.5,
            "guard" => self.safeguards = v >= 0.5,
            "rate" => self.rate_hz = v,
            "maxit" => {
                self.max_iterations = v as usize;
                // A lower limit applies to the run in progress; a higher one
                // lets a run stopped by the old limit go on.
                if self.run == Run::GaveUp && self.iterations < self.max_iterations {
                    self.run = Run::Iterating;
                } else if self.run == Run::Iterating && self.iterations >= self.max_iterations {
                    self.run = Run::GaveUp;
                }
            }
            "tx" | "ty" => {
                self.target = Some(with_coordinate(self.target, self.tip(), key, v));
            }
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        if !matches!(key, "rate" | "maxit") {
            self.restart();
        }
        Ok(applied)
    }

    fn actions(&self) -> &'static [ActionSpec] {
        ACTIONS
    }

    fn action(&mut self, key: &str) -> Result<(), ParamError> {
        match key {
            "reset" => {
                self.angles_rad = vec![START_ANGLE_RAD; self.links];
                self.target = None;
                self.run = Run::Idle;
                self.iterations = 0;
                self.error_m = None;
                self.clock_s = 0.0;
                self.flat_steps = 0;
                self.plots.iter_mut().for_each(Plot::clear);
                self.restart();
                Ok(())
            }
            _ => Err(ParamError::UnknownAction { key: key.into() }),
        }
    }

    /// The pose the run started from (`q0`, radians, `_`-separated, in the
    /// shortest form that reads back exactly), when it is not the start pose.
    fn extra_state(&self) -> Vec<(&'static str, String)> {
        if self.run_start_rad.iter().all(|&a| a == START_ANGLE_RAD) {
            return Vec::new();
        }
        let angles: Vec<String> = self.run_start_rad.iter().map(|a| format!("{a}")).collect();
        vec![(RUN_START_KEY, angles.join("_"))]
    }

    /// `q0`: the pose a run starts from; it also sets the number of links.
    fn set_extra_state(&mut self, key: &str, value: &str) -> Result<(), ParamError> {
        if key != RUN_START_KEY {
            return Err(ParamError::UnknownKey { key: key.into() });
        }
        let bad = |reason: String| ParamError::BadText {
            key: key.into(),
            reason,
        };
        let angles = value
            .split('_')
            .map(|a| a.trim().parse::<f64>())
            .collect::<Result<Vec<f64>, _>>()
            .map_err(|_| bad(format!("“{value}” is not a list of angles")))?;
        let links = PARAMS[0].min as usize..=PARAMS[0].max as usize;
        if !links.contains(&angles.len()) {
            return Err(bad(format!(
                "needs {} to {} joint angles, not {}",
                links.start(),
                links.end(),
                angles.len()
            )));
        }
        if angles
            .iter()
            .any(|a| !a.is_finite() || a.abs() > MAX_START_ANGLE_RAD)
        {
            return Err(bad("angles must be finite radians".into()));
        }
        self.links = angles.len();
        self.angles_rad = angles;
        self.restart();
        Ok(())
    }

    fn input(&mut self, input: Input) {
        if let Some(p) = input.drag_point(|| self.target.unwrap_or_else(|| self.tip())) {
            self.set_target(p);
        }
    }

    fn step(&mut self, dt_s: f64) {
        if self.run != Run::Iterating || !crate::clock::valid_dt(dt_s) {
            return;
        }
        self.clock_s += dt_s;
        let period = 1.0 / self.rate_hz;
        while self.clock_s >= period && self.run == Run::Iterating {
            self.clock_s -= period;
            self.iterate();
        }
    }

    fn animated(&self) -> bool {
        true
    }

    /// Back to the pose the run started from, iterating again toward the
    /// same target: every reset gives the same start, and the replay is the
    /// same run.
    fn reset(&mut self) {
        self.angles_rad.clone_from(&self.run_start_rad);
        self.restart();
    }

    fn plots(&self) -> &[Plot] {
        &self.plots
    }

    /// The target (before any is set: on the tip, where a press would set it).
    fn handles(&self) -> Vec<Handle> {
        vec![Handle::arm_target(self.target, self.tip())]
    }

    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        let near = |q: DVec2| (q - p).length() <= tolerance_m;
        near(self.tip()) || self.target.is_some_and(near)
    }

    fn animating(&self) -> bool {
        self.run == Run::Iterating
    }
}

/// `w = L1 L2 |sin θ2|` of a 2-link arm (ranges keep w ≥ 0.2 m², so the
/// ±0.01 tolerance is at most 5 %). Lengths within the L sliders of
/// experiments 1 and 2 (0.2–1.2 m), so the arm can be set up there.
fn quiz_manipulability(rng: &mut Lcg64) -> Draw {
    let l1 = rng.int(8, 12) as f64 / 10.0;
    let l2 = rng.int(5, 12) as f64 / 10.0;
    let t2 = rng.int(30, 150) as f64 * if rng.next_f64() < 0.5 { -1.0 } else { 1.0 };
    let m = manipulability(&jacobian(&[l1, l2], &[0.0, t2.to_radians()]));
    Draw {
        vars: vec![
            ("l1", format_number(l1, 2)),
            ("l2", format_number(l2, 2)),
            ("t2", format_number(t2, 0)),
        ],
        answer: m.w,
    }
}

/// DLS gain `σ / (σ² + λ²)` along one singular direction.
fn quiz_damped_gain(rng: &mut Lcg64) -> Draw {
    let sigma = rng.int(5, 20) as f64 / 10.0;
    let lambda = rng.int(1, 10) as f64 / 10.0;
    Draw {
        vars: vec![
            ("sigma", format_number(sigma, 2)),
            ("lambda", format_number(lambda, 2)),
        ],
        answer: sigma / (sigma * sigma + lambda * lambda),
    }
}

/// `J11 = ∂x/∂θ1 = −(L1 sin θ1 + L2 sin(θ1+θ2))`, lengths and angles within
/// the sliders of experiment 1.
fn quiz_jacobian_entry(rng: &mut Lcg64) -> Draw {
    let l1 = rng.int(5, 12) as f64 / 10.0;
    let l2 = rng.int(3, 12) as f64 / 10.0;
    let t1 = rng.int(-170, 170) as f64;
    let t2 = rng.int(-170, 170) as f64;
    let j = jacobian(&[l1, l2], &[t1.to_radians(), t2.to_radians()]);
    Draw {
        vars: vec![
            ("l1", format_number(l1, 2)),
            ("l2", format_number(l2, 2)),
            ("t1", format_number(t1, 0)),
            ("t2", format_number(t2, 0)),
        ],
        answer: j[0].x,
    }
}

/// The quiz generators of experiment 9, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "manipulability_2link" => Some(quiz_manipulability),
        "damped_gain" => Some(quiz_damped_gain),
        "jacobian_entry" => Some(quiz_jacobian_entry),
        _ => None,
    }
}

#[cfg(test)]
mod tests;
