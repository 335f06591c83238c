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

use crate::estimation::consistency::{nees, nees_bounds, pose_error};
use crate::estimation::ekf::{ekf_predict, ekf_update_sequential, Belief};
use crate::estimation::models::{
    motion_model, observation_model, sample_motion, Control, MotionNoise, Observation,
    RangeBearingSensor, SensorNoise,
};
use crate::estimation::slam::EkfSlam;
use crate::estimation::wrap_angle;
use crate::experiment::{
    check_param, ActionSpec, Experiment, Input, Notices, ParamError, ParamSpec, Sanitized, Tone,
};
use crate::plot::{Axis, Band, Plot, RefLine, Series, SeriesRole, XWindow};
use crate::quiz::{Draw, Generator};
use crate::rng::Lcg64;
use crate::units::format_number;
use glam::{DMat3, DVec2, DVec3};

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
/// The notice posted when a setting changes under a consistency check.
pub const STALE_CHECK_NOTICE: &str = "settings changed: run the consistency check again";

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
    /// The last observation the localisation filter folded in, `z` (range m,
    /// bearing rad), with its update (`ẑ`, `ν`); none in SLAM.
    last_update: Option<(DVec2, crate::estimation::ekf::Update)>,
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
            last_update: None,
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

    /// The last observation folded in (localisation only): `z` and its update.
    #[must_use]
    pub fn last_update(&self) -> Option<(DVec2, crate::estimation::ekf::Update)> {
        self.last_update
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
                    let update = ekf_update_sequential(b.mean, b.cov, &obs, landmarks, r);
                    *b = update.belief;
                    self.last_update = update.last.or(self.last_update);
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
    /// Transient messages ("settings changed: run the consistency check
    /// again"), shown under the status, never in its place.
    notices: Notices,
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
        "Position uncertainty: trace of P's position block",
        ("Time", "s"),
        ("σx² + σy²", "m²"),
        vec![Series::new("σx² + σy²", "m²", SeriesRole::Primary)],
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
            notices: Notices::default(),
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
        self.notices.clear();
        let p = &mut self.plots[PLOT_ANEES];
        p.clear();
        p.bands.clear();
    }

    fn clear_check(&mut self) {
        self.check = None;
        self.notices.clear();
        let p = &mut self.plots[PLOT_ANEES];
        p.clear();
        p.bands.clear();
    }

    /// Appends the live run's current errors, bounds, NEES and trace to the
    /// plots, and drops samples older than [`WINDOW_S`] (a second's worth
    /// at a time).
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
        self.plots[PLOT_TRACE].series[0].push(t, position_trace(cov));
        for p in &mut self.plots[..PLOT_ANEES] {
            // In batches of a second: each sample moves rarely.
            p.forget_before(t - WINDOW_S, 1.0);
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
}

/// `tr(P_xy) = P_xx + P_yy`, m²: the trace of the position block of a pose
/// covariance. (The trace of the whole pose block would add m² and rad².)
fn position_trace(p: DMat3) -> f64 {
    p.x_axis.x + p.y_axis.y
}

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "No landmarks in view",
        description: "A sensor range of 0.5 m: no landmark is ever seen, so the filter only predicts and its ellipse keeps growing like dead reckoning.",
        query: "range=0.5",
    },
    crate::experiment::Preset {
        name: "Sloppy odometry, good sensor",
        description: "Very noisy wheels: dead reckoning drifts metres away while the EKF stays close to the truth.",
        query: "sv=0.5&sw=30",
    },
    crate::experiment::Preset {
        name: "EKF-SLAM builds the map",
        description: "No map given: the filter estimates the landmarks as it meets them.",
        query: "mode=1",
    },
];

impl Experiment for EkfExperiment {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

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
                self.notices.post(STALE_CHECK_NOTICE, Tone::Warning);
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

    /// One press of Step is one filter cycle (predict, then any update).
    fn natural_step_s(&self) -> f64 {
        FILTER_DT_S
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

    /// The robot drives its loop for ever.
    fn animating(&self) -> bool {
        true
    }

    /// The plots, the three trails (most of a long run), the landmarks and
    /// the sightings, and a consistency check's per-step sums.
    fn state_bytes(&self) -> usize {
        use std::mem::size_of;
        let trails: usize = self.trails.iter().map(VecDeque::capacity).sum();
        let check = self.check.as_ref().map_or(0, |c| {
            (c.current_nees.capacity() + c.sums.capacity()) * size_of::<f64>()
                + c.landmarks.capacity() * size_of::<DVec2>()
                + c.current.as_ref().map_or(0, |r| {
                    size_of::<Run>() + r.observations.capacity() * size_of::<Observation>()
                })
        });
        crate::plot::plots_bytes(&self.plots)
            + (trails + self.landmarks.capacity()) * size_of::<DVec2>()
            + self.live.observations.capacity() * size_of::<Observation>()
            + check
    }
}

mod quiz;
mod view;
pub use quiz::quiz_generator;

#[cfg(test)]
mod tests;
