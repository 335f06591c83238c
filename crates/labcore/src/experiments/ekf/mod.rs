//! Experiment 11 — EKF localisation and EKF-SLAM.
//!
//! A unicycle robot drives a circular loop among point landmarks. Its
//! odometry is noisy ([`sample_motion`]); a range-bearing sensor with a
//! limited range and field of view ([`RangeBearingSensor`]) sees the
//! landmarks a few times a second. An extended Kalman filter fuses the two:
//!
//! ```text
//! predict   μ̄ = g(μ, u)                    P̄ = F P Fᵀ + Q,      Q = V M Vᵀ
//! update    ν = z − h(μ̄)  (bearing wrapped)  S = H P̄ Hᵀ + R,     K = P̄ Hᵀ S⁻¹
//!           μ = μ̄ + K ν                      P = (I − K H) P̄ (I − K H)ᵀ + K R Kᵀ   (Joseph form)
//! ```
//!
//! (Thrun, Burgard & Fox, *Probabilistic Robotics*, MIT Press 2005, Table 7.2;
//! Joseph form: Bar-Shalom, Li & Kirubarajan, *Estimation with Applications
//! to Tracking and Navigation*, Wiley 2001, eq. 5.2.3-18.) The solvers are
//! [`crate::estimation::ekf`] (localisation against the known map) and
//! [`crate::estimation::slam::EkfSlam`] (landmarks join the state on first
//! sight, with full cross-covariances; Durrant-Whyte & Bailey, *IEEE RAM*
//! 13(2), 2006).
//!
//! **Consistency.** The normalised estimation error squared
//! `ε = eᵀ P⁻¹ e` of the pose is χ²(3)-distributed for a consistent filter.
//! One run is plotted against the single-run 95 % band
//! `[χ²₀.₀₂₅(3), χ²₀.₉₇₅(3)] = [0.216, 9.348]`; the *Consistency check* action
//! averages ε over `N` seeded Monte-Carlo runs and compares the average with
//! `[χ²₀.₀₂₅(3N)/N, χ²₀.₉₇₅(3N)/N]` — `[2.36, 3.72]` for `N = 50`
//! (Bar-Shalom et al. 2001, §5.4.2). The runs are spread over frames within a
//! budget of filter steps per call, like the workspace sweep.
//!
//! **Timing.** The shell calls [`Experiment::step`] with `dt = 1/60 s`; the
//! filter itself always steps [`FILTER_DT_S`] (an accumulator decides how
//! many filter steps a call takes), and the sensor reads every
//! [`SENSOR_EVERY`] filter steps, so a run depends on the seed only.
//!
//! **The pilot.** The commanded controls `u` come from a pilot who sees the
//! true pose and keeps the robot on the loop (the filter, as in reality, only
//! knows the commanded `u`, never the executed one). This keeps the drawing
//! on screen forever without affecting what the filter can know.

use std::collections::VecDeque;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

use crate::estimation::consistency::{
    covariance_ellipse, heading_error_rad, nees, nees_bounds, pose_error, position_block,
    position_error_m,
};
use crate::estimation::ekf::{ekf_predict, ekf_update_sequential, Belief};
use crate::estimation::models::{
    motion_model, observation_model, sample_motion, Control, MotionNoise, Observation,
    RangeBearingSensor, SensorNoise,
};
use crate::estimation::slam::EkfSlam;
use crate::estimation::wrap_angle;
use crate::experiment::{
    check_param, format_fixed, format_magnitude, ActionSpec, Experiment, Input, ParamError,
    ParamSpec, Readout, Sanitized, Status, Tone,
};
use crate::plot::{Axis, Band, Plot, RefLine, Series, SeriesRole, XWindow};
use crate::quiz::{format_number, Draw, Generator};
use crate::rng::Lcg64;
use crate::scene::{Item, Role, Scene, ViewBox};
use glam::{DMat2, DMat3, DVec2, DVec3};

const MODES: &[&str] = &["Localisation", "EKF-SLAM"];

const PARAMS: &[ParamSpec] = &[
    ParamSpec::slider("sv", "Odometry noise σv", "m/s", 0.01, 0.5, 0.01, 0.1),
    ParamSpec::slider("sw", "Odometry noise σω", "°/s", 0.5, 30.0, 0.5, 6.0),
    ParamSpec::slider("sr", "Range noise σr", "m", 0.01, 1.0, 0.01, 0.1),
    ParamSpec::slider("sb", "Bearing noise σφ", "°", 0.1, 20.0, 0.1, 2.0),
    ParamSpec::slider("range", "Sensor range", "m", 0.5, 10.0, 0.1, 3.0),
    ParamSpec::slider("fov", "Field of view", "°", 10.0, 360.0, 5.0, 120.0),
    ParamSpec::choice("mode", "Mode", MODES, 0),
    ParamSpec::slider("runs", "Monte-Carlo runs N", "", 10.0, 200.0, 10.0, 50.0).whole_numbers(),
    ParamSpec::number("seed", "Seed", 0.0, 999_999.0, 1.0),
];

const ACTIONS: &[ActionSpec] = &[
    ActionSpec {
        key: "check",
        label: "Consistency check",
    },
    ActionSpec {
        key: "clear",
        label: "Clear check",
    },
];

/// The filter's fixed time step, seconds (odometry at 20 Hz).
pub const FILTER_DT_S: f64 = 0.05;
/// The sensor reads on every `SENSOR_EVERY`-th filter step (4 Hz), starting
/// with the first.
pub const SENSOR_EVERY: u64 = 5;
/// Observation lines stay visible for this many filter steps after a reading.
const FLASH_STEPS: u64 = 3;
/// Radius of the loop the robot drives, metres (centred on the origin).
pub const LOOP_RADIUS_M: f64 = 3.0;
/// Commanded forward speed, m/s: one loop takes 2π·3/0.5 ≈ 37.7 s.
pub const SPEED_MPS: f64 = 0.5;
/// Pilot gains: heading correction (1/s), and how sharply a radial offset
/// (1/m) turns the wanted heading back towards the loop.
const K_HEADING: f64 = 2.0;
const K_RADIAL: f64 = 1.0;
/// Largest commanded turn rate, rad/s.
const MAX_OMEGA_RADPS: f64 = 1.5;
/// Where every run starts: on the loop at (3, 0), heading +y (anticlockwise).
pub const START: DVec3 = DVec3::new(LOOP_RADIUS_M, 0.0, FRAC_PI_2);
/// Initial standard deviations of the filter: 5 cm in x and y, 2° in heading.
const START_SIGMA: DVec3 = DVec3::new(0.05, 0.05, 2.0 * PI / 180.0);
/// The landmarks, metres: dense on the right and top, one alone at the bottom
/// left, so the robot crosses a long stretch of dead reckoning every loop.
pub const LANDMARKS: [DVec2; 6] = [
    DVec2::new(4.3, -0.8),
    DVec2::new(3.6, 2.6),
    DVec2::new(1.0, 3.9),
    DVec2::new(-1.8, 3.6),
    DVec2::new(1.0, 1.2),
    DVec2::new(-1.0, -4.3),
];
/// Plots and trails keep the last minute.
const WINDOW_S: f64 = 60.0;
/// A trail point every this many filter steps (10 Hz), at most a minute of them.
const TRAIL_EVERY: u64 = 2;
const TRAIL_MAX: usize = 600;
/// Length of each Monte-Carlo run of the consistency check, filter steps:
/// 80 s, just over two loops, so EKF-SLAM runs close the loop.
pub const CHECK_STEPS: usize = 1600;
/// Most filter steps the consistency check takes per call of `step`
/// (0.6 of a run, about 0.2 ms natively): a check of 50 runs spreads over
/// 80 frames.
const CHECK_BUDGET_STEPS: usize = 1000;
/// 95 % two-sided band of χ²(3), one run: the 2.5 % and 97.5 % points
/// (standard χ² tables; the tests check them against the closed-form CDF
/// `erf(√(x/2)) − √(2x/π) e^(−x/2)`). `nees_bounds`' Wilson–Hilferty
/// approximation is too rough at 3 degrees of freedom (16 % low at 2.5 %).
pub const SINGLE_RUN_BAND: (f64, f64) = (0.2158, 9.3484);
/// Share of time steps whose average NEES must lie inside the band for the
/// check to call the filter consistent (95 % expected; a little slack).
const INSIDE_NEEDED: f64 = 0.9;
const VIEW_HALF_M: f64 = 4.7;
const VIEW_HEADROOM_M: f64 = 1.2;

/// What the truth and the filter are told: noises, sensor and mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub motion: MotionNoise,
    pub sensor: RangeBearingSensor,
    /// EKF-SLAM (landmarks unknown) instead of localisation on the known map.
    pub slam: bool,
}

#[derive(Clone, Debug, PartialEq)]
enum Filter {
    Localisation(Belief),
    Slam(EkfSlam),
}

/// One simulated run: the true robot, the filter, dead reckoning for
/// comparison, and the random stream every draw comes from.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    truth: DVec3,
    filter: Filter,
    /// The commanded controls integrated from the initial estimate, no fixes.
    dead_reckoning: DVec3,
    rng: Lcg64,
    /// Filter steps taken.
    steps: u64,
    /// The last sensor reading and the step it was taken on.
    observations: Vec<Observation>,
    reading_step: Option<u64>,
    /// Polar angle of the truth last step, and how far round it has gone.
    polar_rad: f64,
    travelled_rad: f64,
    laps: u64,
    obs_this_lap: usize,
    obs_last_lap: Option<usize>,
}

impl Run {
    /// A run from [`START`]: the estimate starts at a draw from its own prior
    /// `N(START, P₀)` (so the first NEES is already χ²(3)), then the run
    /// uses the same stream for motion and sensor noise.
    ///
    /// # Example
    /// ```
    /// use labcore::estimation::models::{MotionNoise, RangeBearingSensor};
    /// use labcore::experiments::ekf::{Run, Settings, LANDMARKS};
    /// let settings = Settings {
    ///     motion: MotionNoise::default(),
    ///     sensor: RangeBearingSensor::default(),
    ///     slam: false,
    /// };
    /// let mut run = Run::new(7, false);
    /// for _ in 0..400 {
    ///     run.advance(&settings, &LANDMARKS); // 20 s of driving and sensing
    /// }
    /// assert!((run.time_s() - 20.0).abs() < 1e-9);
    /// let error = (run.truth() - run.estimate()).truncate().length();
    /// assert!(error < 0.5, "the landmarks keep the estimate close: {error} m");
    /// assert!(run.nees().is_some());
    /// ```
    #[must_use]
    pub fn new(seed: u64, slam: bool) -> Self {
        let mut rng = Lcg64::new(seed);
        let p0 = initial_cov();
        let estimate = START
            + DVec3::new(
                rng.normal(0.0, START_SIGMA.x),
                rng.normal(0.0, START_SIGMA.y),
                rng.normal(0.0, START_SIGMA.z),
            );
        let filter = if slam {
            Filter::Slam(EkfSlam::new(estimate, p0))
        } else {
            Filter::Localisation(Belief {
                mean: estimate,
                cov: p0,
            })
        };
        Self {
            truth: START,
            filter,
            dead_reckoning: estimate,
            rng,
            steps: 0,
            observations: Vec::new(),
            reading_step: None,
            polar_rad: crate::math::atan2(START.y, START.x),
            travelled_rad: 0.0,
            laps: 0,
            obs_this_lap: 0,
            obs_last_lap: None,
        }
    }

    /// The pose estimate `(x, y, θ)`.
    #[must_use]
    pub fn estimate(&self) -> DVec3 {
        match &self.filter {
            Filter::Localisation(b) => b.mean,
            Filter::Slam(s) => s.pose(),
        }
    }

    /// The pose covariance (in SLAM, the pose block of the full `P`).
    #[must_use]
    pub fn pose_cov(&self) -> DMat3 {
        match &self.filter {
            Filter::Localisation(b) => b.cov,
            Filter::Slam(s) => s.pose_cov(),
        }
    }

    /// The true pose.
    #[must_use]
    pub fn truth(&self) -> DVec3 {
        self.truth
    }

    /// NEES of the pose estimate; `None` if `P` is not invertible.
    #[must_use]
    pub fn nees(&self) -> Option<f64> {
        nees(self.truth, self.estimate(), self.pose_cov())
    }

    /// Simulated time, seconds.
    #[must_use]
    pub fn time_s(&self) -> f64 {
        self.steps as f64 * FILTER_DT_S
    }

    /// One filter step of [`FILTER_DT_S`]: the pilot commands `u`, the filter
    /// predicts with it, the truth moves with noisy `u`, and on sensor steps
    /// the landmarks in view are observed from the true pose and folded in
    /// one after another. An observation the filter refuses (a landmark at
    /// the robot) is skipped; the state stays finite.
    pub fn advance(&mut self, settings: &Settings, landmarks: &[DVec2]) {
        let u = pilot(self.truth);
        match &mut self.filter {
            Filter::Localisation(b) => {
                if let Ok(next) = ekf_predict(b.mean, b.cov, u, FILTER_DT_S, &settings.motion) {
                    *b = next;
                }
            }
            Filter::Slam(s) => {
                let _ = s.predict(u, FILTER_DT_S, &settings.motion);
            }
        }
        self.dead_reckoning = motion_model(self.dead_reckoning, u, FILTER_DT_S);
        let (truth, _) = sample_motion(self.truth, u, FILTER_DT_S, &settings.motion, &mut self.rng);
        self.truth = truth;
        self.steps += 1;
        self.track_laps();
        if (self.steps - 1).is_multiple_of(SENSOR_EVERY) {
            let mut obs = std::mem::take(&mut self.observations);
            settings
                .sensor
                .observe_into(self.truth, landmarks, &mut self.rng, &mut obs);
            let r = settings.sensor.noise.r();
            match &mut self.filter {
                Filter::Localisation(b) => {
                    *b = ekf_update_sequential(b.mean, b.cov, &obs, landmarks, r).belief;
                }
                Filter::Slam(s) => {
                    s.observe_all(&obs, r);
                }
            }
            self.obs_this_lap += obs.len();
            self.observations = obs;
            self.reading_step = Some(self.steps);
        }
    }

    /// Counts laps by the truth's polar angle round the loop centre.
    fn track_laps(&mut self) {
        let polar = crate::math::atan2(self.truth.y, self.truth.x);
        self.travelled_rad += wrap_angle(polar - self.polar_rad);
        self.polar_rad = polar;
        if self.travelled_rad >= TAU * (self.laps + 1) as f64 {
            self.laps += 1;
            self.obs_last_lap = Some(self.obs_this_lap);
            self.obs_this_lap = 0;
        }
    }

    /// The last reading's observations while they still flash.
    fn flashing(&self) -> &[Observation] {
        match self.reading_step {
            Some(k) if self.steps - k < FLASH_STEPS => &self.observations,
            _ => &[],
        }
    }
}

/// `P₀ = diag(σx², σy², σθ²)` of [`START_SIGMA`].
fn initial_cov() -> DMat3 {
    DMat3::from_diagonal(START_SIGMA * START_SIGMA)
}

/// The pilot's command from the true pose: speed [`SPEED_MPS`], and a turn
/// rate that follows the loop's curvature `v/R` plus a correction towards the
/// wanted heading — the loop's tangent, turned inwards by
/// `atan(K_RADIAL (r − R))` when the robot is off the circle.
#[must_use]
pub fn pilot(truth: DVec3) -> Control {
    let p = truth.truncate();
    let r = p.length();
    if !(r.is_finite() && r > 1e-6 && truth.z.is_finite()) {
        return Control::new(SPEED_MPS, SPEED_MPS / LOOP_RADIUS_M);
    }
    let tangent = crate::math::atan2(p.y, p.x) + FRAC_PI_2;
    let wanted = tangent + crate::math::atan2(K_RADIAL * (r - LOOP_RADIUS_M), 1.0);
    let omega = SPEED_MPS / LOOP_RADIUS_M + K_HEADING * wrap_angle(wanted - truth.z);
    Control::new(SPEED_MPS, omega.clamp(-MAX_OMEGA_RADPS, MAX_OMEGA_RADPS))
}

/// A seed for run `index` of a family: SplitMix64 of the pair, so nearby
/// seeds and indices give unrelated streams.
fn run_seed(seed: u64, index: u64) -> u64 {
    let mut z = seed
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add(index.wrapping_add(1).wrapping_mul(0xD1B5_4A32_D192_ED03));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The outcome of a finished consistency check.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckResult {
    /// Time average of the average NEES.
    pub mean_anees: f64,
    /// Share of time steps whose average NEES lies inside the band.
    pub inside: f64,
    /// The 95 % band for `N` runs.
    pub band: (f64, f64),
}

/// The Monte-Carlo consistency check in progress (or done).
#[derive(Clone, Debug, PartialEq)]
struct Check {
    settings: Settings,
    landmarks: Vec<DVec2>,
    seed: u64,
    runs: usize,
    /// Runs finished so far.
    done: usize,
    current: Option<Run>,
    /// NEES of the current run, one per step.
    current_nees: Vec<f64>,
    /// Per-step NEES summed over the finished runs.
    sums: Vec<f64>,
    /// Runs whose covariance became singular (their NEES undefined); left out.
    dropped: usize,
    result: Option<CheckResult>,
}

impl Check {
    fn new(settings: Settings, landmarks: Vec<DVec2>, seed: u64, runs: usize) -> Self {
        Self {
            settings,
            landmarks,
            seed,
            runs,
            done: 0,
            current: None,
            current_nees: Vec::with_capacity(CHECK_STEPS),
            sums: vec![0.0; CHECK_STEPS],
            dropped: 0,
            result: None,
        }
    }

    fn finished(&self) -> bool {
        self.done >= self.runs
    }

    /// Runs at most `budget` filter steps; returns whether a run finished.
    fn work(&mut self, budget: usize) -> bool {
        let mut left = budget;
        let mut finished_one = false;
        while left > 0 && !self.finished() {
            let run = self.current.get_or_insert_with(|| {
                Run::new(
                    run_seed(self.seed, self.done as u64 + 1),
                    self.settings.slam,
                )
            });
            let todo = (CHECK_STEPS - self.current_nees.len()).min(left);
            for _ in 0..todo {
                run.advance(&self.settings, &self.landmarks);
                self.current_nees.push(run.nees().unwrap_or(f64::NAN));
            }
            left -= todo;
            if self.current_nees.len() == CHECK_STEPS {
                if self.current_nees.iter().all(|v| v.is_finite()) {
                    for (s, v) in self.sums.iter_mut().zip(&self.current_nees) {
                        *s += v;
                    }
                } else {
                    self.dropped += 1;
                }
                self.current_nees.clear();
                self.current = None;
                self.done += 1;
                finished_one = true;
            }
        }
        if self.finished() && self.result.is_none() {
            self.result = self.evaluate();
        }
        finished_one
    }

    /// Runs that count in the average.
    fn counted(&self) -> usize {
        self.done - self.dropped
    }

    fn band(&self) -> Option<(f64, f64)> {
        nees_bounds(3, self.counted(), 0.95)
    }

    fn evaluate(&self) -> Option<CheckResult> {
        let n = self.counted();
        let band = self.band()?;
        let avg: Vec<f64> = self.sums.iter().map(|s| s / n as f64).collect();
        let inside = avg
            .iter()
            .filter(|a| (band.0..=band.1).contains(*a))
            .count();
        Some(CheckResult {
            mean_anees: avg.iter().sum::<f64>() / avg.len() as f64,
            inside: inside as f64 / avg.len() as f64,
            band,
        })
    }
}

/// State of the EKF experiment.
#[derive(Clone, Debug)]
pub struct EkfExperiment {
    sigma_v_mps: f64,
    sigma_omega_degps: f64,
    sigma_range_m: f64,
    sigma_bearing_deg: f64,
    range_m: f64,
    fov_deg: f64,
    mode: usize,
    runs: usize,
    seed: u64,
    landmarks: Vec<DVec2>,
    live: Run,
    /// Time not yet consumed by a filter step, seconds.
    clock_s: f64,
    trails: [VecDeque<DVec2>; 3],
    /// x error, y error, NEES, trace(P), Monte-Carlo average NEES.
    plots: [Plot; 5],
    check: Option<Check>,
    /// A parameter changed after a check: its result no longer applies.
    check_stale: bool,
}

/// Indices into `plots` and `trails`.
const PLOT_X: usize = 0;
const PLOT_Y: usize = 1;
const PLOT_NEES: usize = 2;
const PLOT_TRACE: usize = 3;
const PLOT_ANEES: usize = 4;
const TRAIL_TRUTH: usize = 0;
const TRAIL_EKF: usize = 1;
const TRAIL_DR: usize = 2;

fn error_plot(key: &'static str, title: &'static str, axis: &'static str) -> Plot {
    let (label, plus, minus) = match axis {
        "x" => ("x error", "+3σx", "−3σx"),
        _ => ("y error", "+3σy", "−3σy"),
    };
    let mut p = Plot::new(
        key,
        title,
        ("Time", "s"),
        ("Error", "m"),
        vec![
            Series::new(label, "m", SeriesRole::Primary),
            Series::new(plus, "m", SeriesRole::Bound),
            Series::new(minus, "m", SeriesRole::Bound),
        ],
    );
    p.window = XWindow::Rolling(WINDOW_S);
    p
}

fn new_plots() -> [Plot; 5] {
    let mut nees_plot = Plot::new(
        "nees",
        "NEES of this run",
        ("Time", "s"),
        ("NEES", ""),
        vec![Series::new("NEES", "", SeriesRole::Primary)],
    );
    nees_plot.window = XWindow::Rolling(WINDOW_S);
    nees_plot.bands.push(Band {
        axis: Axis::Y,
        lo: SINGLE_RUN_BAND.0,
        hi: SINGLE_RUN_BAND.1,
        label: "95 % χ²(3) band, one run".into(),
    });
    nees_plot.ref_lines.push(RefLine {
        axis: Axis::Y,
        value: 3.0,
        label: "expected 3".into(),
    });
    let mut trace = Plot::new(
        "trace",
        "Uncertainty trace(P)",
        ("Time", "s"),
        ("trace(P)", "m² + rad²"),
        vec![Series::new("trace(P)", "m² + rad²", SeriesRole::Primary)],
    );
    trace.window = XWindow::Rolling(WINDOW_S);
    let mut anees = Plot::new(
        "anees",
        "Average NEES over N runs",
        ("Time", "s"),
        ("Average NEES", ""),
        vec![Series::new("average NEES", "", SeriesRole::Primary)],
    );
    anees.ref_lines.push(RefLine {
        axis: Axis::Y,
        value: 3.0,
        label: "expected 3".into(),
    });
    [
        error_plot("error_x", "Position error in x with ±3σ", "x"),
        error_plot("error_y", "Position error in y with ±3σ", "y"),
        nees_plot,
        trace,
        anees,
    ]
}

impl Default for EkfExperiment {
    fn default() -> Self {
        let seed = PARAMS[8].default as u64;
        let mut e = Self {
            sigma_v_mps: PARAMS[0].default,
            sigma_omega_degps: PARAMS[1].default,
            sigma_range_m: PARAMS[2].default,
            sigma_bearing_deg: PARAMS[3].default,
            range_m: PARAMS[4].default,
            fov_deg: PARAMS[5].default,
            mode: PARAMS[6].default as usize,
            runs: PARAMS[7].default as usize,
            seed,
            landmarks: LANDMARKS.to_vec(),
            live: Run::new(run_seed(seed, 0), false),
            clock_s: 0.0,
            trails: Default::default(),
            plots: new_plots(),
            check: None,
            check_stale: false,
        };
        e.restart();
        e
    }
}

impl EkfExperiment {
    /// The noises, sensor and mode the sliders describe (SI units, radians).
    #[must_use]
    pub fn settings(&self) -> Settings {
        Settings {
            motion: MotionNoise {
                sigma_v_mps: self.sigma_v_mps,
                sigma_omega_radps: self.sigma_omega_degps.to_radians(),
            },
            sensor: RangeBearingSensor {
                max_range_m: self.range_m,
                fov_rad: self.fov_deg.to_radians(),
                noise: SensorNoise {
                    sigma_range_m: self.sigma_range_m,
                    sigma_bearing_rad: self.sigma_bearing_deg.to_radians(),
                },
            },
            slam: self.mode == 1,
        }
    }

    /// The live run.
    #[must_use]
    pub fn live(&self) -> &Run {
        &self.live
    }

    /// The finished check's result, if any.
    #[must_use]
    pub fn check_result(&self) -> Option<CheckResult> {
        self.check.as_ref().and_then(|c| c.result)
    }

    /// The live run back to its start (same seed); plots and trails cleared.
    fn restart(&mut self) {
        self.live = Run::new(run_seed(self.seed, 0), self.mode == 1);
        self.clock_s = 0.0;
        for t in &mut self.trails {
            t.clear();
        }
        for p in &mut self.plots[..PLOT_ANEES] {
            p.clear();
        }
        self.record();
    }

    fn start_check(&mut self) {
        self.check = Some(Check::new(
            self.settings(),
            self.landmarks.clone(),
            self.seed,
            self.runs,
        ));
        self.check_stale = false;
        let p = &mut self.plots[PLOT_ANEES];
        p.clear();
        p.bands.clear();
    }

    fn clear_check(&mut self) {
        self.check = None;
        self.check_stale = false;
        let p = &mut self.plots[PLOT_ANEES];
        p.clear();
        p.bands.clear();
    }

    /// Appends the live run's current errors, bounds, NEES and trace to the
    /// plots, and drops samples older than [`WINDOW_S`].
    fn record(&mut self) {
        let run = &self.live;
        let t = run.time_s();
        let (truth, est, cov) = (run.truth, run.estimate(), run.pose_cov());
        let e = pose_error(truth, est);
        let sx = 3.0 * cov.x_axis.x.max(0.0).sqrt();
        let sy = 3.0 * cov.y_axis.y.max(0.0).sqrt();
        for (k, err, s) in [(PLOT_X, e.x, sx), (PLOT_Y, e.y, sy)] {
            let p = &mut self.plots[k];
            p.series[0].push(t, err);
            p.series[1].push(t, s);
            p.series[2].push(t, -s);
        }
        // NaN (singular P) is skipped by `push`.
        self.plots[PLOT_NEES].series[0].push(t, run.nees().unwrap_or(f64::NAN));
        self.plots[PLOT_TRACE].series[0].push(t, trace3(cov));
        for p in &mut self.plots[..PLOT_ANEES] {
            for s in &mut p.series {
                let old = s.x.iter().take_while(|x| **x < t - WINDOW_S).count();
                if old > 0 {
                    s.x.drain(..old);
                    s.y.drain(..old);
                }
            }
            p.touch();
        }
        if run.steps.is_multiple_of(TRAIL_EVERY) {
            let points = [
                truth.truncate(),
                est.truncate(),
                run.dead_reckoning.truncate(),
            ];
            for (trail, p) in self.trails.iter_mut().zip(points) {
                if trail.len() >= TRAIL_MAX {
                    trail.pop_front();
                }
                trail.push_back(p);
            }
        }
    }

    /// One filter step of the live run.
    fn advance_live(&mut self) {
        let settings = self.settings();
        self.live.advance(&settings, &self.landmarks);
        self.record();
    }

    /// Runs the consistency check within its budget and refreshes its plot.
    fn advance_check(&mut self) {
        let Some(check) = self.check.as_mut() else {
            return;
        };
        if check.finished() || !check.work(CHECK_BUDGET_STEPS) {
            return;
        }
        let n = check.counted();
        let p = &mut self.plots[PLOT_ANEES];
        p.clear();
        if n > 0 {
            for (k, s) in check.sums.iter().enumerate() {
                p.series[0].push((k + 1) as f64 * FILTER_DT_S, s / n as f64);
            }
        }
        p.bands.clear();
        if let Some((lo, hi)) = check.band() {
            p.bands.push(Band {
                axis: Axis::Y,
                lo,
                hi,
                label: format!("95 % band for {n} runs"),
            });
        }
        p.touch();
    }

    /// Position error readouts and the 3σ ellipse come from this.
    fn ellipse(center: DVec2, cov: DMat2) -> Item {
        let (a, b, phi) = covariance_ellipse(cov, 3.0);
        let (s, c) = crate::math::sin_cos(phi);
        Item::Ellipse {
            center,
            semi_axis_a: DVec2::new(c, s) * a,
            semi_axis_b: DVec2::new(-s, c) * b,
            role: Role::Estimate,
        }
    }
}

/// `tr(P)` of a pose covariance (m² + m² + rad²).
fn trace3(p: DMat3) -> f64 {
    p.x_axis.x + p.y_axis.y + p.z_axis.z
}

/// A robot outline at `pose`: a dart 0.36 m long.
fn robot_outline(pose: DVec3) -> Vec<DVec2> {
    let (s, c) = crate::math::sin_cos(pose.z);
    let at = |x: f64, y: f64| pose.truncate() + DVec2::new(c * x - s * y, s * x + c * y);
    vec![
        at(0.22, 0.0),
        at(-0.14, 0.13),
        at(-0.07, 0.0),
        at(-0.14, -0.13),
    ]
}

/// A five-pointed star of outer radius `r` at `c` (a landmark).
fn star(c: DVec2, r: f64) -> Vec<DVec2> {
    (0..10)
        .map(|k| {
            let a = FRAC_PI_2 + k as f64 * PI / 5.0;
            let rr = if k % 2 == 0 { r } else { 0.45 * r };
            let (s, co) = crate::math::sin_cos(a);
            c + DVec2::new(co, s) * rr
        })
        .collect()
}

impl Experiment for EkfExperiment {
    fn id(&self) -> &'static str {
        "ekf"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        Some(match key {
            "sv" => self.sigma_v_mps,
            "sw" => self.sigma_omega_degps,
            "sr" => self.sigma_range_m,
            "sb" => self.sigma_bearing_deg,
            "range" => self.range_m,
            "fov" => self.fov_deg,
            "mode" => self.mode as f64,
            "runs" => self.runs as f64,
            "seed" => self.seed as f64,
            _ => return None,
        })
    }

    /// Noise, range and field of view apply from the next step (truth and
    /// filter alike); mode and seed restart the run. Any change makes a
    /// consistency check out of date.
    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        let before = self.param(key);
        match key {
            "sv" => self.sigma_v_mps = v,
            "sw" => self.sigma_omega_degps = v,
            "sr" => self.sigma_range_m = v,
            "sb" => self.sigma_bearing_deg = v,
            "range" => self.range_m = v,
            "fov" => self.fov_deg = v,
            "mode" => self.mode = v as usize,
            "runs" => self.runs = v as usize,
            "seed" => self.seed = v as u64,
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        if before != Some(v) {
            if matches!(key, "mode" | "seed") {
                self.restart();
            }
            if self.check.is_some() {
                self.clear_check();
                self.check_stale = true;
            }
        }
        Ok(applied)
    }

    fn actions(&self) -> &'static [ActionSpec] {
        ACTIONS
    }

    fn action(&mut self, key: &str) -> Result<(), ParamError> {
        match key {
            "check" => self.start_check(),
            "clear" => self.clear_check(),
            _ => return Err(ParamError::UnknownAction { key: key.into() }),
        }
        Ok(())
    }

    /// Nothing to drag: every state is the seed's run, so a link reproduces it.
    fn input(&mut self, _input: Input) {}

    fn step(&mut self, dt_s: f64) {
        if !crate::clock::valid_dt(dt_s) {
            return;
        }
        self.clock_s += dt_s;
        // The tolerance absorbs rounding: three steps of 1/60 s make one 0.05 s step.
        while self.clock_s >= FILTER_DT_S - 1e-9 {
            self.clock_s -= FILTER_DT_S;
            self.advance_live();
        }
        self.advance_check();
    }

    fn animated(&self) -> bool {
        true
    }

    /// The same run again from the start; a consistency check restarts too.
    fn reset(&mut self) {
        self.restart();
        if self.check.is_some() {
            self.start_check();
        }
    }

    fn plots(&self) -> &[Plot] {
        &self.plots
    }

    /// The landmarks with a margin, and headroom at the top for the status
    /// badge that overlays the canvas there.
    fn view(&self) -> ViewBox {
        ViewBox {
            min: DVec2::splat(-VIEW_HALF_M),
            max: DVec2::new(VIEW_HALF_M, VIEW_HALF_M + VIEW_HEADROOM_M),
        }
    }

    fn scene(&self, out: &mut Scene) {
        let run = &self.live;
        out.push(Item::Circle {
            center: DVec2::ZERO,
            radius_m: LOOP_RADIUS_M,
            role: Role::Grid,
            fill: false,
            dashed: true,
        });
        // The sensor's field of view from the true pose.
        let settings = self.settings();
        let sensor = settings.sensor;
        let truth = run.truth;
        let fov = sensor.fov_rad.min(TAU);
        let arc_points = 24;
        let mut wedge = Vec::with_capacity(arc_points + 2);
        if fov < TAU - 1e-9 {
            wedge.push(truth.truncate());
        }
        for k in 0..=arc_points {
            let a = truth.z - 0.5 * fov + fov * k as f64 / arc_points as f64;
            let (s, c) = crate::math::sin_cos(a);
            wedge.push(truth.truncate() + DVec2::new(c, s) * sensor.max_range_m);
        }
        out.push(Item::Polyline {
            points: wedge,
            width_px: 1.0,
            role: Role::Bound,
            dashed: true,
            closed: true,
        });
        let trail_style = [
            (TRAIL_TRUTH, Role::Robot, false),
            (TRAIL_EKF, Role::Estimate, false),
            (TRAIL_DR, Role::Ghost, true),
        ];
        for (k, role, dashed) in trail_style {
            out.push(Item::Polyline {
                points: self.trails[k].iter().copied().collect(),
                width_px: 1.5,
                role,
                dashed,
                closed: false,
            });
        }
        for &m in &self.landmarks {
            out.push(Item::Polygon {
                points: star(m, 0.18),
                role: Role::Accent,
            });
        }
        if let Filter::Slam(slam) = &run.filter {
            for &id in slam.landmark_ids() {
                if let Some((m, cov)) = slam.landmark(id) {
                    out.push(Self::ellipse(m, cov));
                    out.push(Item::Dot {
                        center: m,
                        radius_px: 3.0,
                        role: Role::Estimate,
                    });
                }
            }
        }
        for z in run.flashing() {
            let (s, c) = crate::math::sin_cos(truth.z + z.bearing_rad);
            out.push(Item::Line {
                from: truth.truncate(),
                to: truth.truncate() + DVec2::new(c, s) * z.range_m,
                width_px: 2.0,
                role: Role::Path,
                dashed: false,
            });
        }
        out.push(Item::Polyline {
            points: robot_outline(run.dead_reckoning),
            width_px: 1.5,
            role: Role::Ghost,
            dashed: true,
            closed: true,
        });
        let est = run.estimate();
        out.push(Self::ellipse(
            est.truncate(),
            position_block(run.pose_cov()),
        ));
        out.push(Item::Polygon {
            points: robot_outline(est),
            role: Role::Estimate,
        });
        out.push(Item::Polygon {
            points: robot_outline(truth),
            role: Role::Robot,
        });
    }

    fn readouts(&self) -> Vec<Readout> {
        let run = &self.live;
        let (truth, est, cov) = (run.truth, run.estimate(), run.pose_cov());
        let per_loop = match run.obs_last_lap {
            Some(n) => n.to_string(),
            None => format!("{} so far", run.obs_this_lap),
        };
        let mapped = match &run.filter {
            Filter::Localisation(_) => format!("{} (known map)", self.landmarks.len()),
            Filter::Slam(s) => format!("{} of {}", s.landmark_count(), self.landmarks.len()),
        };
        let anees = self
            .check_result()
            .map_or("--".into(), |r| format_fixed(r.mean_anees, 2));
        vec![
            Readout::metres("error", "Position error", position_error_m(truth, est)),
            Readout::degrees(
                "heading_error",
                "Heading error",
                heading_error_rad(truth, est).to_degrees(),
            ),
            Readout::new("trace", "trace(P), pose", format_magnitude(trace3(cov))),
            Readout::new(
                "nees",
                "NEES",
                run.nees().map_or("--".into(), |v| format_fixed(v, 2)),
            ),
            Readout::new("obs_per_loop", "Observations per loop", per_loop),
            Readout::metres(
                "dr_error",
                "Dead-reckoning error",
                position_error_m(truth, run.dead_reckoning),
            ),
            Readout::new("landmarks", "Landmarks", mapped),
            Readout::new("anees", "Average NEES (check)", anees),
        ]
    }

    fn status(&self) -> Status {
        if self.check_stale {
            return Status::new(
                "settings changed: run the consistency check again",
                Tone::Warning,
            );
        }
        if let Some(check) = &self.check {
            if !check.finished() {
                return Status::new(
                    format!("consistency check… {}/{} runs", check.done, check.runs),
                    Tone::Neutral,
                );
            }
            let Some(r) = check.result else {
                return Status::new(
                    "consistency check failed: every run lost its covariance",
                    Tone::Bad,
                );
            };
            let (lo, hi) = r.band;
            let pct = (r.inside * 100.0).round();
            let n = check.counted();
            let detail = format!(
                "average NEES {:.2}, {pct:.0} % of steps inside [{lo:.2}, {hi:.2}] over {n} runs",
                r.mean_anees
            );
            return if r.inside >= INSIDE_NEEDED {
                Status::new(format!("consistent: {detail}"), Tone::Good)
            } else if r.mean_anees > hi {
                Status::new(format!("over-confident: {detail}"), Tone::Bad)
            } else if r.mean_anees < lo {
                Status::new(format!("under-confident: {detail}"), Tone::Warning)
            } else {
                Status::new(format!("inconsistent at times: {detail}"), Tone::Warning)
            };
        }
        match &self.live.filter {
            Filter::Localisation(_) => Status::new("EKF localisation running", Tone::Neutral),
            Filter::Slam(s) => Status::new(
                format!(
                    "EKF-SLAM: {} of {} landmarks mapped",
                    s.landmark_count(),
                    self.landmarks.len()
                ),
                Tone::Neutral,
            ),
        }
    }

    fn hint(&self) -> &'static str {
        "Watch the 3σ ellipse grow between landmark sightings and shrink at each fix; press Consistency check to average NEES over N seeded runs."
    }

    fn preview(&mut self) {
        for _ in 0..(24.0 / FILTER_DT_S) as usize {
            self.advance_live();
        }
    }

    /// The robot drives its loop for ever.
    fn animating(&self) -> bool {
        true
    }
}

/// Predicted spread across the track: a robot heading along x with
/// `σ_y`, `σ_θ` moves `d = v·Δt` metres; without process noise
/// `σ_y' = √(σ_y² + d² σ_θ²)` (the `F P Fᵀ` term of the predict step).
fn quiz_predicted_sigma(rng: &mut Lcg64) -> Draw {
    let sigma_y = rng.int(5, 30) as f64 / 100.0;
    let sigma_theta_deg = rng.int(2, 15) as f64;
    let v = rng.int(2, 10) as f64 / 10.0;
    let dt = rng.int(2, 8) as f64 / 2.0;
    let p = DMat3::from_diagonal(DVec3::new(
        0.01,
        sigma_y * sigma_y,
        sigma_theta_deg.to_radians().powi(2),
    ));
    let no_noise = MotionNoise {
        sigma_v_mps: 0.0,
        sigma_omega_radps: 0.0,
    };
    let answer = ekf_predict(DVec3::ZERO, p, Control::new(v, 0.0), dt, &no_noise)
        .map_or(f64::NAN, |b| b.cov.y_axis.y.sqrt());
    Draw {
        vars: vec![
            ("sy", format_number(sigma_y, 2)),
            ("st", format_number(sigma_theta_deg, 0)),
            ("v", format_number(v, 1)),
            ("dt", format_number(dt, 1)),
        ],
        answer,
    }
}

/// Scalar Kalman update: prior `σ_p`, measurement `σ_z` of the same quantity;
/// posterior `σ = σ_p σ_z / √(σ_p² + σ_z²)`.
fn quiz_posterior_sigma(rng: &mut Lcg64) -> Draw {
    let sp = rng.int(10, 60) as f64 / 100.0;
    let sz = rng.int(5, 50) as f64 / 100.0;
    let k = sp * sp / (sp * sp + sz * sz);
    Draw {
        vars: vec![("sp", format_number(sp, 2)), ("sz", format_number(sz, 2))],
        answer: ((1.0 - k) * sp * sp).sqrt(),
    }
}

/// Expected bearing `wrap(atan2(dy, dx) − θ)` in degrees, from `h(x)`.
fn quiz_expected_bearing(rng: &mut Lcg64) -> Draw {
    let (x, y) = (
        rng.int(-20, 20) as f64 / 10.0,
        rng.int(-20, 20) as f64 / 10.0,
    );
    let theta = rng.int(-17, 18) as f64 * 10.0;
    let (mut mx, mut my) = (
        rng.int(-40, 40) as f64 / 10.0,
        rng.int(-40, 40) as f64 / 10.0,
    );
    if (mx - x).abs() + (my - y).abs() < 0.5 {
        mx = x + 2.0;
        my = y + 1.0;
    }
    let z = observation_model(DVec3::new(x, y, theta.to_radians()), DVec2::new(mx, my));
    Draw {
        vars: vec![
            ("x", format_number(x, 1)),
            ("y", format_number(y, 1)),
            ("t", format_number(theta, 0)),
            ("mx", format_number(mx, 1)),
            ("my", format_number(my, 1)),
        ],
        answer: z.y.to_degrees(),
    }
}

/// NEES `eᵀ P⁻¹ e` with a diagonal `P`: a sum of squared standardised errors.
fn quiz_nees_diagonal(rng: &mut Lcg64) -> Draw {
    let ex = rng.int(-30, 30) as f64 / 100.0;
    let ey = rng.int(-30, 30) as f64 / 100.0;
    let et = rng.int(-10, 10) as f64;
    let sx = rng.int(5, 20) as f64 / 100.0;
    let sy = rng.int(5, 20) as f64 / 100.0;
    let st = rng.int(2, 8) as f64;
    let cov = DMat3::from_diagonal(DVec3::new(sx * sx, sy * sy, st.to_radians().powi(2)));
    let answer = nees(DVec3::new(ex, ey, et.to_radians()), DVec3::ZERO, cov).unwrap_or(f64::NAN);
    Draw {
        vars: vec![
            ("ex", format_number(ex, 2)),
            ("ey", format_number(ey, 2)),
            ("et", format_number(et, 0)),
            ("sx", format_number(sx, 2)),
            ("sy", format_number(sy, 2)),
            ("st", format_number(st, 0)),
        ],
        answer,
    }
}

/// The quiz generators of experiment 11, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "predicted_sigma" => Some(quiz_predicted_sigma),
        "posterior_sigma" => Some(quiz_posterior_sigma),
        "expected_bearing" => Some(quiz_expected_bearing),
        "nees_diagonal" => Some(quiz_nees_diagonal),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::format_metres;

    const DT: f64 = 1.0 / 60.0;

    fn run_for(e: &mut EkfExperiment, seconds: f64) {
        for _ in 0..(seconds / DT).round() as usize {
            e.step(DT);
        }
    }

    fn readout(e: &EkfExperiment, key: &str) -> String {
        crate::experiment::readout_value(e, key).unwrap_or_default()
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
    }

    fn close_mat(a: DMat3, b: DMat3) -> bool {
        (0..3).all(|j| (0..3).all(|i| close(a.col(j)[i], b.col(j)[i])))
    }

    /// An experiment whose filter starts exactly on the truth with `P₀`.
    fn exact_start(landmarks: Vec<DVec2>) -> EkfExperiment {
        let mut e = EkfExperiment {
            landmarks,
            ..EkfExperiment::default()
        };
        e.live.filter = Filter::Localisation(Belief {
            mean: START,
            cov: initial_cov(),
        });
        e.live.dead_reckoning = START;
        e
    }

    /// The first predict by hand: from (3, 0, 90°) on the loop the pilot
    /// commands u = (0.5 m/s, 0.5/3 rad/s); with P₀ = diag(a, a, c),
    /// s = sin θ, k = cos θ, d = v Δt:
    /// P̄xx = a + d²s²c + σv²Δt²k², P̄yy = a + d²k²c + σv²Δt²s², P̄θθ = c + σω²Δt²,
    /// P̄xy = −d²skc + σv²Δt²ks, P̄xθ = −dsc, P̄yθ = dkc.
    fn hand_predict() -> (DVec3, DMat3) {
        let (v, w, dt) = (0.5, 0.5 / 3.0, FILTER_DT_S);
        let th = FRAC_PI_2;
        let (s, k) = (th.sin(), th.cos());
        let a = 0.05 * 0.05;
        let c = (2.0f64).to_radians().powi(2);
        let sv2 = 0.1 * 0.1 * dt * dt;
        let sw2 = (6.0f64).to_radians().powi(2) * dt * dt;
        let d = v * dt;
        let mean = DVec3::new(3.0 + d * k, d * s, th + w * dt);
        let xx = a + d * d * s * s * c + sv2 * k * k;
        let yy = a + d * d * k * k * c + sv2 * s * s;
        let tt = c + sw2;
        let xy = -d * d * s * k * c + sv2 * k * s;
        let xt = -d * s * c;
        let yt = d * k * c;
        let cov = DMat3::from_cols(
            DVec3::new(xx, xy, xt),
            DVec3::new(xy, yy, yt),
            DVec3::new(xt, yt, tt),
        );
        (mean, cov)
    }

    #[test]
    fn first_predict_matches_a_hand_computed_step() {
        let mut e = exact_start(Vec::new());
        e.step(DT);
        e.step(DT);
        assert_eq!(e.live.steps, 0, "two frames are less than one filter step");
        e.step(DT);
        assert_eq!(e.live.steps, 1);
        let (mean, cov) = hand_predict();
        assert!((e.live.estimate() - mean).length() < 1e-15);
        assert!(close_mat(e.live.pose_cov(), cov), "{:?}", e.live.pose_cov());
        let tr = cov.x_axis.x + cov.y_axis.y + cov.z_axis.z;
        assert_eq!(readout(&e, "trace"), format_magnitude(tr));
        assert_eq!(readout(&e, "trace"), "0.006");
        assert_eq!(
            readout(&e, "error"),
            format_metres((e.live.truth.truncate() - mean.truncate()).length())
        );
        // Dead reckoning integrates the same commanded control.
        assert!((e.live.dead_reckoning - mean).length() < 1e-15);
    }

    /// The first update, against the information form
    /// P⁺ = (P̄⁻¹ + Hᵀ R⁻¹ H)⁻¹, μ⁺ = μ̄ + P⁺ Hᵀ R⁻¹ ν — algebraically equal
    /// to the Joseph form the filter uses, computed another way.
    #[test]
    fn first_update_matches_the_information_form() {
        let landmark = DVec2::new(3.0, 2.0);
        let mut e = exact_start(vec![landmark]);
        for _ in 0..3 {
            e.step(DT);
        }
        assert_eq!(e.live.observations.len(), 1, "the sensor reads on step 1");
        let z = e.live.observations[0];
        let (mbar, pbar) = hand_predict();
        let (dx, dy) = (landmark.x - mbar.x, landmark.y - mbar.y);
        let q = dx * dx + dy * dy;
        let h0 = DVec3::new(-dx / q.sqrt(), -dy / q.sqrt(), 0.0);
        let h1 = DVec3::new(dy / q, -dx / q, -1.0);
        let (sr, sb) = (0.1, (2.0f64).to_radians());
        let outer = |a: DVec3, b: DVec3| DMat3::from_cols(a * b.x, a * b.y, a * b.z);
        let info = pbar.inverse() + outer(h0, h0) / (sr * sr) + outer(h1, h1) / (sb * sb);
        let post = info.inverse();
        let nu_r = z.range_m - q.sqrt();
        let nu_b = wrap_angle(z.bearing_rad - (dy.atan2(dx) - mbar.z));
        let mean = mbar + post * (h0 * (nu_r / (sr * sr)) + h1 * (nu_b / (sb * sb)));
        let got = e.live.estimate();
        assert!((got - mean).length() < 1e-12, "{got} vs {mean}");
        let p = e.live.pose_cov();
        for j in 0..3 {
            for i in 0..3 {
                assert!((p.col(j)[i] - post.col(j)[i]).abs() < 1e-12, "P[{i}][{j}]");
            }
        }
        let tr = trace3(post);
        assert!(tr < trace3(pbar), "the update shrinks P");
        assert_eq!(readout(&e, "trace"), format_magnitude(tr));
        assert_eq!(
            readout(&e, "error"),
            format_metres((e.live.truth.truncate() - mean.truncate()).length())
        );
        assert_eq!(readout(&e, "obs_per_loop"), "1 so far");
    }

    #[test]
    fn three_sigma_bounds_are_the_square_roots_of_the_diagonal_of_p() {
        let mut e = EkfExperiment::default();
        run_for(&mut e, 10.0);
        let p = e.live.pose_cov();
        let err = pose_error(e.live.truth, e.live.estimate());
        for (k, var, err) in [(PLOT_X, p.x_axis.x, err.x), (PLOT_Y, p.y_axis.y, err.y)] {
            let plot = &e.plots[k];
            let last = |i: usize| *plot.series[i].y.last().unwrap();
            assert_eq!(last(0), err);
            assert_eq!(last(1), 3.0 * var.sqrt());
            assert_eq!(last(2), -3.0 * var.sqrt());
            assert_eq!(plot.series[1].role, SeriesRole::Bound);
        }
        assert_eq!(*e.plots[PLOT_TRACE].series[0].y.last().unwrap(), trace3(p));
        assert_eq!(
            *e.plots[PLOT_NEES].series[0].y.last().unwrap(),
            e.live.nees().unwrap()
        );
        // Errors stay inside ±3σ nearly all the time.
        let inside = |k: usize| {
            let s = &e.plots[k].series;
            s[0].y
                .iter()
                .zip(&s[1].y)
                .filter(|(a, b)| a.abs() <= **b)
                .count() as f64
                / s[0].len() as f64
        };
        assert!(inside(PLOT_X) > 0.95 && inside(PLOT_Y) > 0.95);
    }

    #[test]
    fn plots_and_trails_keep_only_the_last_minute() {
        let mut e = EkfExperiment::default();
        run_for(&mut e, 90.0);
        let t = e.live.time_s();
        for plot in &e.plots[..PLOT_ANEES] {
            for s in &plot.series {
                assert!(s.x[0] >= t - WINDOW_S - 1e-9, "{}: {}", plot.key, s.x[0]);
                assert!(s.len() <= (WINDOW_S / FILTER_DT_S) as usize + 1);
            }
        }
        assert!(e.trails.iter().all(|t| t.len() == TRAIL_MAX));
    }

    #[test]
    fn observation_lines_flash_after_a_reading_only() {
        let mut e = EkfExperiment::default();
        let lines = |e: &EkfExperiment| {
            let mut scene = Scene::default();
            e.scene(&mut scene);
            scene
                .items
                .iter()
                .filter(|i| {
                    matches!(
                        i,
                        Item::Line {
                            role: Role::Path,
                            ..
                        }
                    )
                })
                .count()
        };
        run_for(&mut e, FILTER_DT_S);
        assert_eq!(e.live.steps, 1);
        let seen = e.live.observations.len();
        assert!(seen > 0, "a landmark is in view at the start");
        assert_eq!(lines(&e), seen);
        run_for(&mut e, 3.0 * FILTER_DT_S);
        assert_eq!(e.live.steps, 4);
        assert_eq!(lines(&e), 0, "the flash is over");
    }

    #[test]
    fn consistency_check_at_default_noise_is_inside_the_band() {
        let mut e = EkfExperiment::default();
        e.action("check").unwrap();
        assert_eq!(e.status().text, "consistency check… 0/50 runs");
        let mut calls = 0;
        let mut last_done = 0;
        while e.check.as_ref().is_some_and(|c| !c.finished()) {
            e.step(DT);
            calls += 1;
            let done = e.check.as_ref().unwrap().done;
            assert!(
                done - last_done <= 1,
                "one call finished {} runs",
                done - last_done
            );
            last_done = done;
            if done < 50 {
                assert_eq!(
                    e.status().text,
                    format!("consistency check… {done}/50 runs")
                );
            }
        }
        let budget_calls = 50 * CHECK_STEPS / CHECK_BUDGET_STEPS;
        assert_eq!(calls, budget_calls, "spread over {calls} calls");
        let r = e.check_result().unwrap();
        assert!((r.band.0 - 2.36).abs() < 0.005 && (r.band.1 - 3.72).abs() < 0.005);
        assert!(r.inside >= INSIDE_NEEDED, "{r:?}");
        assert!(r.mean_anees > r.band.0 && r.mean_anees < r.band.1, "{r:?}");
        assert_eq!(e.status().tone, Tone::Good);
        assert!(e.status().text.starts_with("consistent: average NEES"));
        assert_eq!(readout(&e, "anees"), format_fixed(r.mean_anees, 2));
        let plot = &e.plots[PLOT_ANEES];
        assert_eq!(plot.series[0].len(), CHECK_STEPS);
        assert_eq!(plot.bands.len(), 1);
        assert_eq!((plot.bands[0].lo, plot.bands[0].hi), r.band);
        // The same seed gives the same verdict; a setting change makes it stale.
        let mut again = EkfExperiment::default();
        again.action("check").unwrap();
        while again.check.as_ref().is_some_and(|c| !c.finished()) {
            again.step(DT);
        }
        assert_eq!(again.check_result(), Some(r));
        again.set_param("sb", 5.0).unwrap();
        assert!(again.check.is_none());
        assert_eq!(again.status().tone, Tone::Warning);
        assert!(again.plots[PLOT_ANEES].series[0].is_empty());
    }

    #[test]
    fn check_verdicts_name_over_and_under_confidence() {
        let mut e = EkfExperiment::default();
        let mut check = Check::new(e.settings(), LANDMARKS.to_vec(), 1, 50);
        check.done = 50;
        let band = (2.36, 3.72);
        for (mean, inside, tone, word) in [
            (3.0, 0.96, Tone::Good, "consistent"),
            (7.0, 0.1, Tone::Bad, "over-confident"),
            (1.0, 0.0, Tone::Warning, "under-confident"),
            (3.1, 0.7, Tone::Warning, "inconsistent at times"),
        ] {
            check.result = Some(CheckResult {
                mean_anees: mean,
                inside,
                band,
            });
            e.check = Some(check.clone());
            let status = e.status();
            assert_eq!(status.tone, tone);
            assert!(status.text.starts_with(word), "{}", status.text);
        }
    }

    #[test]
    fn slam_mode_adds_landmarks_and_their_ellipses_shrink() {
        let mut e = EkfExperiment::default();
        e.set_param("mode", 1.0).unwrap();
        let slam = |e: &EkfExperiment| match &e.live.filter {
            Filter::Slam(s) => s.clone(),
            Filter::Localisation(_) => panic!("not in SLAM mode"),
        };
        assert_eq!(slam(&e).landmark_count(), 0);
        assert_eq!(e.status().text, "EKF-SLAM: 0 of 6 landmarks mapped");
        // The 3σ major semi-axis of each landmark when it joins the map.
        let major = |s: &EkfSlam, id: usize| {
            let (_, cov) = s.landmark(id).unwrap();
            covariance_ellipse(cov, 3.0).0
        };
        let mut at_first_sight = [f64::NAN; 6];
        for _ in 0..(40.0 / DT) as usize {
            e.step(DT);
            let s = slam(&e);
            for &id in s.landmark_ids() {
                if at_first_sight[id].is_nan() {
                    at_first_sight[id] = major(&s, id);
                }
            }
        }
        assert!(
            at_first_sight.iter().all(|a| a.is_finite()),
            "one loop maps every landmark"
        );
        run_for(&mut e, 40.0);
        let s = slam(&e);
        assert_eq!(s.landmark_count(), 6);
        assert_eq!(s.state_len(), 15);
        let ratios: Vec<f64> = (0..6)
            .map(|id| major(&s, id) / at_first_sight[id])
            .collect();
        assert!(
            ratios.iter().all(|r| *r < 0.9),
            "every map ellipse shrinks: {ratios:?}"
        );
        assert!(
            ratios.iter().any(|r| *r < 0.5),
            "closing the loop halves the worst ones: {ratios:?}"
        );
        // Each estimate lies within its own uncertainty of the true landmark:
        // eᵀ P⁻¹ e below the 99.9 % point of χ²(2), 13.8.
        for (id, truth) in LANDMARKS.iter().enumerate() {
            let (m, cov) = s.landmark(id).unwrap();
            let e = m - *truth;
            let d2 = e.dot(cov.inverse() * e);
            assert!(d2 < 13.8, "landmark {id} at {m}: {d2}");
        }
        // The map's shape is known better than where it sits: the absolute
        // frame carries the initial pose error, the distances between
        // landmarks do not.
        for (i, ti) in LANDMARKS.iter().enumerate() {
            for (j, tj) in LANDMARKS.iter().enumerate().skip(i + 1) {
                let (a, b) = (s.landmark(i).unwrap().0, s.landmark(j).unwrap().0);
                let err = (a - b).length() - (*ti - *tj).length();
                assert!(err.abs() < 0.15, "distance {i}–{j} off by {err} m");
            }
        }
        let mut scene = Scene::default();
        e.scene(&mut scene);
        let ellipses = scene
            .items
            .iter()
            .filter(|i| matches!(i, Item::Ellipse { .. }))
            .count();
        assert_eq!(ellipses, 1 + 6, "the pose's ellipse and one per landmark");
        assert_eq!(readout(&e, "landmarks"), "6 of 6");
    }

    #[test]
    fn every_parameter_round_trips_through_the_link() {
        use crate::route::{format, restore, Tab};
        let mut e = EkfExperiment::default();
        for (key, v) in [
            ("sv", 0.23),
            ("sw", 12.5),
            ("sr", 0.37),
            ("sb", 4.4),
            ("range", 6.2),
            ("fov", 215.0),
            ("mode", 1.0),
            ("runs", 120.0),
            ("seed", 4242.0),
        ] {
            assert_eq!(e.set_param(key, v), Ok(Sanitized::InRange(v)), "{key}");
        }
        let link = format(&e, Tab::Simulation);
        assert!(
            link.contains("fov=215") && link.contains("seed=4242"),
            "{link}"
        );
        let (mut fresh, notices) = restore(&link, EkfExperiment::default());
        assert!(notices.is_empty(), "{notices:?}");
        for spec in PARAMS {
            assert_eq!(fresh.param(spec.key), e.param(spec.key), "{}", spec.key);
        }
        // The link reproduces the run itself.
        e.reset();
        run_for(&mut e, 5.0);
        run_for(&mut fresh, 5.0);
        assert_eq!(e.live, fresh.live);
        assert!(e.set_param("nope", 1.0).is_err());
        assert!(e.set_param("sv", f64::NAN).is_err());
        assert_eq!(e.set_param("fov", 999.0), Ok(Sanitized::Clamped(360.0)));
    }

    #[test]
    fn same_seed_same_run_and_reset_replays_it() {
        let mut a = EkfExperiment::default();
        let mut b = EkfExperiment::default();
        run_for(&mut a, 10.0);
        run_for(&mut b, 10.0);
        assert_eq!(a.live, b.live);
        assert_eq!(a.plots, b.plots);
        let first = a.live.clone();
        a.reset();
        assert_eq!(a.live.steps, 0);
        run_for(&mut a, 10.0);
        assert_eq!(a.live, first);
        b.set_param("seed", 2.0).unwrap();
        run_for(&mut b, 10.0);
        assert_ne!(b.live.truth, first.truth);
    }

    #[test]
    fn extreme_settings_stay_finite() {
        let mut e = EkfExperiment::default();
        for (key, v) in [
            ("sv", 0.5),
            ("sw", 30.0),
            ("sr", 1.0),
            ("sb", 20.0),
            ("range", 0.5),
            ("fov", 10.0),
        ] {
            e.set_param(key, v).unwrap();
        }
        run_for(&mut e, 300.0);
        let mut scene = Scene::default();
        e.scene(&mut scene);
        assert!(scene.is_finite());
        assert!(e.live.estimate().is_finite() && e.live.pose_cov().is_finite());
        assert!(e.live.nees().is_some());
        assert!(
            (e.live.truth.truncate().length() - LOOP_RADIUS_M).abs() < 1.0,
            "the pilot keeps the loop"
        );
        for r in e.readouts() {
            assert!(
                !r.value.contains("NaN") && !r.value.contains("inf"),
                "{r:?}"
            );
        }
    }

    /// The single-run band is the 2.5 % and 97.5 % points of χ²(3), whose CDF
    /// is `erf(√(x/2)) − √(2x/π) e^(−x/2)`.
    #[test]
    fn single_run_band_matches_the_chi_square_distribution() {
        let cdf = |x: f64| libm::erf((x / 2.0).sqrt()) - (2.0 * x / PI).sqrt() * (-x / 2.0).exp();
        assert!((cdf(SINGLE_RUN_BAND.0) - 0.025).abs() < 1e-4);
        assert!((cdf(SINGLE_RUN_BAND.1) - 0.975).abs() < 1e-4);
        let band = &EkfExperiment::default().plots[PLOT_NEES].bands[0];
        assert_eq!((band.lo, band.hi), SINGLE_RUN_BAND);
    }

    #[test]
    fn pilot_holds_the_loop_and_turns_back_towards_it() {
        let on = pilot(START);
        assert!(close(on.omega_radps, SPEED_MPS / LOOP_RADIUS_M));
        // Outside the circle, heading along the tangent: turn left (inwards).
        assert!(pilot(DVec3::new(4.0, 0.0, FRAC_PI_2)).omega_radps > on.omega_radps);
        assert!(pilot(DVec3::new(2.0, 0.0, FRAC_PI_2)).omega_radps < on.omega_radps);
        assert!(pilot(DVec3::new(f64::NAN, 0.0, 0.0))
            .omega_radps
            .is_finite());
    }

    #[test]
    fn quiz_generators_match_closed_forms() {
        let mut rng = Lcg64::new(11);
        for _ in 0..50 {
            let d = quiz_predicted_sigma(&mut rng);
            let g = |k: &str| d.var(k).unwrap();
            let st = g("st").to_radians();
            let expected = (g("sy").powi(2) + (g("v") * g("dt") * st).powi(2)).sqrt();
            assert!((d.answer - expected).abs() < 1e-9, "{d:?}");

            let d = quiz_posterior_sigma(&mut rng);
            let (sp, sz) = (d.var("sp").unwrap(), d.var("sz").unwrap());
            assert!((d.answer - sp * sz / (sp * sp + sz * sz).sqrt()).abs() < 1e-12);
            assert!(d.answer < sp.min(sz));

            let d = quiz_expected_bearing(&mut rng);
            let g = |k: &str| d.var(k).unwrap();
            let b = ((g("my") - g("y")).atan2(g("mx") - g("x")) - g("t").to_radians()).to_degrees();
            let diff = (d.answer - b).rem_euclid(360.0);
            assert!(!(1e-9..=360.0 - 1e-9).contains(&diff), "{d:?}");
            assert!((-180.0..180.0).contains(&d.answer));

            let d = quiz_nees_diagonal(&mut rng);
            let g = |k: &str| d.var(k).unwrap();
            let n = (g("ex") / g("sx")).powi(2)
                + (g("ey") / g("sy")).powi(2)
                + (g("et") / g("st")).powi(2);
            assert!((d.answer - n).abs() < 1e-9, "{d:?}");
        }
        assert!(quiz_generator("nope").is_none());
    }
}
