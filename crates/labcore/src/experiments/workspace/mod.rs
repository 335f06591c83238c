//! Experiment 3 — the 3R planar arm and its workspace.
//!
//! A live arm driven by θ1, θ2, θ3 (its tip can also be dragged: a few damped
//! least-squares iterations per pointer move), and a "Sweep workspace" action
//! that samples joint space with [`WorkspaceSampler`] — seeded Monte-Carlo or a
//! regular grid — spreading the work over animation frames so no frame runs
//! long. The cloud is shaded by density ([`DensityGrid`]); the measured inner
//! and outer radii are compared with the analytic `R = L1 + L2 + L3` and
//! `r = max(0, L_max − (R − L_max))`.

use crate::experiment::{
    check_param, ActionSpec, Experiment, Handle, Input, Notices, ParamError, ParamSpec, Sanitized,
    Tone,
};
use crate::kinematics::chain::{tip, Annulus};
use crate::kinematics::dls::DlsSolver;
use crate::kinematics::two_link_ik::wrap_pi;
use crate::kinematics::workspace::{DensityGrid, SamplingMode, WorkspaceSampler};
use crate::plot::{Axis, Plot, RefLine, Series, SeriesRole};
use crate::quiz::{Draw, Generator};
use crate::rng::Lcg64;
use crate::units::format_number;
use glam::DVec2;

mod view;

const MODES: &[&str] = &["Monte-Carlo", "Grid"];

const PARAMS: &[ParamSpec] = &[
    ParamSpec::slider("t1", "θ₁", "°", -180.0, 180.0, 1.0, 40.0),
    ParamSpec::slider("t2", "θ₂", "°", -180.0, 180.0, 1.0, 50.0),
    ParamSpec::slider("t3", "θ₃", "°", -180.0, 180.0, 1.0, -35.0),
    ParamSpec::slider("l1", "L₁", "m", 0.2, 1.2, 0.05, 1.0),
    ParamSpec::slider("l2", "L₂", "m", 0.2, 1.2, 0.05, 0.8),
    ParamSpec::slider("l3", "L₃", "m", 0.1, 1.2, 0.05, 0.7),
    ParamSpec::choice("mode", "Sampling", MODES, 0),
    ParamSpec::slider("n", "Samples", "", 1000.0, 60000.0, 1000.0, 20000.0).whole_numbers(),
    ParamSpec::number("seed", "Seed", 0.0, 999_999.0, 1.0),
];

const ACTIONS: &[ActionSpec] = &[
    ActionSpec {
        key: "sweep",
        label: "Sweep workspace",
    },
    ActionSpec {
        key: "clear",
        label: "Clear",
    },
];

/// World half-width shown (metres).
const VIEW_HALF_M: f64 = 3.7;
/// Density grid resolution (cells per side) before the first sweep.
const DENSITY_CELLS: usize = 110;
/// Aim for about this many samples per cell inside the reachable disc, so the
/// shading shows density rather than sampling noise.
const SAMPLES_PER_CELL: f64 = 6.0;

/// Cells per side of the density grid for `samples` tips spread over the
/// disc of radius `Σ L` in the view: `(2H)² · samples / (k π R²)` cells in all.
fn density_cells(samples: usize, lengths_m: &[f64; 3]) -> usize {
    let reach = lengths_m.iter().sum::<f64>().max(0.1);
    let disc_fraction =
        (std::f64::consts::PI * reach * reach / (4.0 * VIEW_HALF_M * VIEW_HALF_M)).min(1.0);
    let cells = samples as f64 / SAMPLES_PER_CELL / disc_fraction;
    (cells.sqrt().round() as usize).clamp(24, 200)
}
/// A sweep spreads over this many frames: each adds at most 1 % of the
/// samples, so the progress badge can move in 1 % steps with the cloud.
const SWEEP_FRAMES: usize = 100;

/// State of the workspace experiment.
#[derive(Clone, Debug)]
pub struct Workspace {
    angles_deg: [f64; 3],
    lengths_m: [f64; 3],
    mode: usize,
    samples: usize,
    seed: u64,
    sampler: Option<WorkspaceSampler>,
    tips: Vec<DVec2>,
    density: DensityGrid,
    /// "settings changed: sweep again" when a change cleared the cloud.
    notices: Notices,
    /// Measured outer and inner radius against samples drawn, with the
    /// theoretical radii as reference lines.
    plots: [Plot; 1],
}

fn new_plots() -> [Plot; 1] {
    [Plot::new(
        "radii",
        "Measured radii",
        ("Samples drawn", ""),
        ("Radius", "m"),
        vec![
            Series::new("outer radius (measured)", "m", SeriesRole::Primary),
            Series::new("inner hole (measured)", "m", SeriesRole::Secondary),
        ],
    )]
}

impl Default for Workspace {
    fn default() -> Self {
        Self {
            angles_deg: [PARAMS[0].default, PARAMS[1].default, PARAMS[2].default],
            lengths_m: [PARAMS[3].default, PARAMS[4].default, PARAMS[5].default],
            mode: 0,
            samples: PARAMS[7].default as usize,
            seed: PARAMS[8].default as u64,
            sampler: None,
            tips: Vec::new(),
            density: DensityGrid::new(VIEW_HALF_M, DENSITY_CELLS),
            notices: Notices::default(),
            plots: new_plots(),
        }
    }
}

impl Workspace {
    fn angles_rad(&self) -> [f64; 3] {
        self.angles_deg.map(f64::to_radians)
    }

    /// The live tip, metres.
    #[must_use]
    pub fn tip(&self) -> DVec2 {
        tip(&self.lengths_m, &self.angles_rad())
    }

    fn sampling_mode(&self) -> SamplingMode {
        if self.mode == 0 {
            SamplingMode::MonteCarlo { seed: self.seed }
        } else {
            SamplingMode::Grid {
                per_joint: crate::math::cbrt(self.samples as f64).round().max(2.0) as usize,
            }
        }
    }

    fn start_sweep(&mut self) {
        self.clear();
        self.density = DensityGrid::new(VIEW_HALF_M, density_cells(self.samples, &self.lengths_m));
        self.sampler = Some(WorkspaceSampler::new(
            self.lengths_m,
            self.sampling_mode(),
            self.samples,
        ));
        let annulus = Annulus::of_chain(&self.lengths_m);
        let radii = &mut self.plots[0];
        radii.ref_lines = vec![
            RefLine {
                axis: Axis::Y,
                value: annulus.outer_m,
                label: "outer (theory)".into(),
            },
            RefLine {
                axis: Axis::Y,
                value: annulus.inner_m,
                label: "inner (theory)".into(),
            },
        ];
    }

    fn clear(&mut self) {
        self.sampler = None;
        self.tips.clear();
        self.density.clear();
        self.notices.clear();
        self.plots[0].clear();
    }

    /// In grid mode, why the sample count differs from the one asked for:
    /// `grid of 39 angles per joint: 39³ = 59319 of 60000 requested`. `None`
    /// in Monte-Carlo mode or when the grid gives exactly the count asked for.
    fn grid_note(&self) -> Option<String> {
        let sampler = self.sampler.as_ref()?;
        let SamplingMode::Grid { per_joint } = sampler.mode() else {
            return None;
        };
        let requested = self.samples;
        let total = sampler.total();
        Some(if total == requested {
            format!("grid of {per_joint} angles per joint: {per_joint}³ = {total}")
        } else {
            format!(
                "grid of {per_joint} angles per joint: {per_joint}³ = {total} of {requested} requested"
            )
        })
    }

    fn sweeping(&self) -> bool {
        self.sampler.as_ref().is_some_and(|s| !s.is_done())
    }

    /// Drags the tip towards `target` with a few DLS iterations (redundant arm).
    fn drag_tip_to(&mut self, target: DVec2) {
        if !target.is_finite() {
            return;
        }
        let solver = DlsSolver {
            damping: 0.08,
            max_iterations: 12,
            ..DlsSolver::default()
        };
        let mut q = self.angles_rad();
        if solver.solve(&self.lengths_m, &mut q, target).is_ok() {
            self.angles_deg = q.map(|a| wrap_pi(a).to_degrees().clamp(-180.0, 180.0));
        }
    }
}

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "A dominant link opens a hole",
        description: "L₁ longer than L₂ + L₃: the workspace is a ring with a hole of radius L₁ − L₂ − L₃.",
        query: "l1=1.2&l2=0.3&l3=0.2",
    },
    crate::experiment::Preset {
        name: "Equal links fill the disc",
        description: "Three equal links can fold back onto the base: no hole at all.",
        query: "l1=0.6&l2=0.6&l3=0.6",
    },
    crate::experiment::Preset {
        name: "Few samples fake a hole",
        description: "Only 1,000 random samples: after a sweep the rim is nearly found, yet an empty hole shows round the base where none exists.",
        query: "n=1000",
    },
];

impl Experiment for Workspace {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

    fn id(&self) -> &'static str {
        "workspace"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        Some(match key {
            "t1" => self.angles_deg[0],
            "t2" => self.angles_deg[1],
            "t3" => self.angles_deg[2],
            "l1" => self.lengths_m[0],
            "l2" => self.lengths_m[1],
            "l3" => self.lengths_m[2],
            "mode" => self.mode as f64,
            "n" => self.samples as f64,
            "seed" => self.seed as f64,
            _ => return None,
        })
    }

    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        // A value set to what it already was changes nothing (the cloud stays).
        let had_cloud = self.sampler.is_some() && self.param(key) != Some(v);
        match key {
            "t1" => self.angles_deg[0] = v,
            "t2" => self.angles_deg[1] = v,
            "t3" => self.angles_deg[2] = v,
            "l1" => self.lengths_m[0] = v,
            "l2" => self.lengths_m[1] = v,
            "l3" => self.lengths_m[2] = v,
            "mode" => self.mode = v as usize,
            "n" => self.samples = v.round() as usize,
            "seed" => self.seed = v.round() as u64,
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        // A cloud belongs to the geometry and sampling settings it was drawn with.
        if had_cloud && !matches!(key, "t1" | "t2" | "t3") {
            self.clear();
            self.notices
                .post("settings changed: sweep again", Tone::Warning);
        }
        Ok(applied)
    }

    fn actions(&self) -> &'static [ActionSpec] {
        ACTIONS
    }

    fn action(&mut self, key: &str) -> Result<(), ParamError> {
        match key {
            "sweep" => self.start_sweep(),
            "clear" => self.clear(),
            _ => return Err(ParamError::UnknownAction { key: key.into() }),
        }
        Ok(())
    }

    fn input(&mut self, input: Input) {
        if let Some(p) = input.drag_point(|| self.tip()) {
            self.drag_tip_to(p);
        }
    }

    fn step(&mut self, dt_s: f64) {
        if !crate::clock::valid_dt(dt_s) {
            return;
        }
        let Some(sampler) = self.sampler.as_mut() else {
            return;
        };
        if sampler.is_done() {
            return;
        }
        let batch = (sampler.total() / SWEEP_FRAMES).max(1);
        let start = self.tips.len();
        sampler.sample_batch(batch, &mut self.tips);
        self.density.add_all(&self.tips[start..]);
        if let Some(m) = sampler.measured() {
            let drawn = sampler.produced() as f64;
            let radii = &mut self.plots[0];
            radii.series[0].push(drawn, m.outer_m);
            radii.series[1].push(drawn, m.inner_m);
            radii.touch();
        }
    }

    fn animated(&self) -> bool {
        true
    }

    /// Restarts the sweep from its first sample (same seed, same samples).
    fn reset(&mut self) {
        if self.sampler.is_some() {
            self.start_sweep();
        }
    }

    fn plots(&self) -> &[Plot] {
        &self.plots
    }

    fn handles(&self) -> Vec<Handle> {
        vec![Handle::new("tip", "End-effector", self.tip())]
    }

    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        (self.tip() - p).length() <= tolerance_m
    }

    /// The swept tips and the density grid's counts, with the plot.
    fn state_bytes(&self) -> usize {
        self.tips.capacity() * std::mem::size_of::<DVec2>()
            + self.density.cols * self.density.rows * 4
            + crate::plot::plots_bytes(&self.plots)
    }

    fn animating(&self) -> bool {
        self.sweeping()
    }

    /// A sweep step samples a hundredth of the sweep (600 poses by
    /// default: forward kinematics and a density count each), about 0.13 ms
    /// on the 4×-throttled phone stand-in. Counted as 8 light steps: a
    /// snapshot every 4 steps, so a scrub replays at most 3 (about 0.4 ms
    /// there). At 8 steps a scrub replayed up to 7, and the scrub frame
    /// p95 read 9.2–9.7 ms against its budget of 8 (issue 53 §9); the
    /// default sweep's 26 snapshots hold about 5 MB.
    fn step_weight(&self) -> u64 {
        8
    }
}

/// Link lengths inside the L sliders' ranges (so a question can be set up
/// and swept), often with one link dominant so that some arms have a hole.
fn draw_lengths(rng: &mut Lcg64) -> [f64; 3] {
    [
        rng.int(5, 12) as f64 / 10.0,
        rng.int(2, 10) as f64 / 10.0,
        rng.int(1, 8) as f64 / 10.0,
    ]
}

fn length_vars(l: [f64; 3]) -> Vec<(&'static str, String)> {
    vec![
        ("l1", format_number(l[0], 2)),
        ("l2", format_number(l[1], 2)),
        ("l3", format_number(l[2], 2)),
    ]
}

/// Outer radius `L1 + L2 + L3`.
fn quiz_outer_radius(rng: &mut Lcg64) -> Draw {
    let l = draw_lengths(rng);
    Draw {
        vars: length_vars(l),
        answer: Annulus::of_chain(&l).outer_m,
    }
}

/// Inner hole `max(0, L_max − sum of the others)`.
fn quiz_inner_radius(rng: &mut Lcg64) -> Draw {
    let l = draw_lengths(rng);
    Draw {
        vars: length_vars(l),
        answer: Annulus::of_chain(&l).inner_m,
    }
}

/// `x` of the tip of a 3R arm.
fn quiz_tip_x(rng: &mut Lcg64) -> Draw {
    let l = draw_lengths(rng);
    let t = [
        rng.int(-170, 170) as f64,
        rng.int(-170, 170) as f64,
        rng.int(-170, 170) as f64,
    ];
    let mut vars = length_vars(l);
    vars.extend([
        ("t1", format_number(t[0], 0)),
        ("t2", format_number(t[1], 0)),
        ("t3", format_number(t[2], 0)),
    ]);
    Draw {
        vars,
        answer: tip(&l, &t.map(f64::to_radians)).x,
    }
}

/// The quiz generators of experiment 3, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "outer_radius" => Some(quiz_outer_radius),
        "inner_radius" => Some(quiz_inner_radius),
        "tip_x" => Some(quiz_tip_x),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::{Presentation, Status};
    use crate::testkit::{press, readout, settle};

    fn sweep(ws: &mut Workspace) -> usize {
        press(ws, "sweep");
        let frames = settle(ws);
        assert!(frames < 1000);
        frames
    }

    #[test]
    fn sweep_is_spread_over_frames_and_measures_the_annulus() {
        let mut ws = Workspace::default();
        let frames = sweep(&mut ws);
        assert!(frames >= SWEEP_FRAMES / 2, "spread over {frames} frames");
        assert_eq!(ws.tips.len(), 20000);
        assert_eq!(ws.density.total(), 20000);
        let m = ws.sampler.as_ref().unwrap().measured().unwrap();
        assert!((m.outer_m - 2.5).abs() < 0.02, "outer {}", m.outer_m);
        assert!(m.inner_m < 0.05, "inner {}", m.inner_m);
        assert_eq!(ws.status().tone, Tone::Good);
    }

    #[test]
    fn inner_hole_appears_when_one_link_dominates() {
        let mut ws = Workspace::default();
        ws.set_param("l1", 1.2).unwrap();
        ws.set_param("l2", 0.3).unwrap();
        ws.set_param("l3", 0.2).unwrap();
        sweep(&mut ws);
        let m = ws.sampler.as_ref().unwrap().measured().unwrap();
        assert!((m.inner_m - 0.7).abs() < 0.02, "inner {}", m.inner_m);
        assert!(ws.tips.iter().all(|p| p.length() >= 0.7 - 1e-9));
    }

    #[test]
    fn same_seed_same_cloud_and_geometry_change_marks_it_stale() {
        let mut a = Workspace::default();
        let mut b = Workspace::default();
        sweep(&mut a);
        sweep(&mut b);
        assert_eq!(a.tips, b.tips);
        b.set_param("seed", 2.0).unwrap();
        assert!(b.tips.is_empty());
        assert_eq!(b.notice().unwrap().text, "settings changed: sweep again");
        assert_eq!(b.status().text, "ready to sweep");
        sweep(&mut b);
        assert_ne!(a.tips, b.tips);
    }

    #[test]
    fn grid_mode_samples_per_joint_cubed() {
        let mut ws = Workspace::default();
        ws.set_param("mode", 1.0).unwrap();
        ws.set_param("n", 8000.0).unwrap();
        sweep(&mut ws);
        assert_eq!(ws.tips.len(), 8000);
    }

    #[test]
    fn dragging_the_tip_moves_the_redundant_arm_there() {
        let mut ws = Workspace::default();
        let target = DVec2::new(1.2, -0.9);
        ws.input(Input::PointerDown(target));
        for _ in 0..5 {
            ws.input(Input::PointerMove {
                pos: target,
                pressed: true,
            });
        }
        assert!((ws.tip() - target).length() < 1e-4);
    }

    /// Regression: a pointer 1e200 m away used to fold the arm onto its base
    /// (`Annulus::nearest` overflowed to (0, 0)); now the arm reaches towards it.
    #[test]
    fn very_far_drag_target_stretches_the_arm_towards_it() {
        let mut ws = Workspace::default();
        for _ in 0..20 {
            ws.input(Input::PointerMove {
                pos: DVec2::new(1e200, 1e200),
                pressed: true,
            });
        }
        let tip = ws.tip();
        assert!((tip.length() - 2.5).abs() < 1e-2, "tip {tip}");
        assert!((tip.x - tip.y).abs() < 1e-2, "along the diagonal: {tip}");
    }

    /// Regression: the badge moved in 25 % steps and lagged behind the cloud.
    #[test]
    fn sweep_progress_is_reported_at_least_every_percent() {
        for (mode, n) in [(0.0, 20000.0), (1.0, 60000.0), (0.0, 1000.0)] {
            let mut ws = Workspace::default();
            ws.set_param("mode", mode).unwrap();
            ws.set_param("n", n).unwrap();
            ws.action("sweep").unwrap();
            let total = ws.sampler.as_ref().unwrap().total();
            let mut last = 0;
            while ws.animating() {
                ws.step(1.0 / 60.0);
                let produced = ws.sampler.as_ref().unwrap().produced();
                assert!(
                    100 * (produced - last) <= total,
                    "one frame added {} of {total}",
                    produced - last
                );
                last = produced;
                if ws.animating() {
                    let percent = 100 * produced / total;
                    assert!(
                        ws.status()
                            .text
                            .starts_with(&format!("sweeping… {percent}%")),
                        "{} at {produced}/{total}",
                        ws.status().text
                    );
                }
            }
        }
    }

    /// In grid mode 60,000 requested samples become 39³ = 59,319: say so.
    #[test]
    fn grid_mode_explains_the_sample_count() {
        let mut ws = Workspace::default();
        ws.set_param("mode", 1.0).unwrap();
        ws.set_param("n", 60000.0).unwrap();
        sweep(&mut ws);
        assert_eq!(
            ws.status().text,
            "swept 59319 samples (grid of 39 angles per joint: 39³ = 59319 of 60000 requested)"
        );
        let samples = ws
            .readouts()
            .into_iter()
            .find(|r| r.key == "samples")
            .unwrap();
        assert_eq!(samples.value, "59319 / 59319 (39³ grid of 60000 requested)");
        // Monte-Carlo keeps the plain wording.
        let mut mc = Workspace::default();
        sweep(&mut mc);
        assert_eq!(mc.status().text, "swept 20000 samples");
    }

    fn measured(ws: &Workspace) -> crate::kinematics::workspace::MeasuredRadii {
        ws.sampler.as_ref().unwrap().measured().unwrap()
    }

    /// Issue 13 §4: a changed setting is a notice beside the state, and a
    /// finished sweep is an ended run.
    #[test]
    fn a_finished_sweep_has_ended_and_a_changed_setting_is_a_notice() {
        use crate::experiment::Phase;
        let mut ws = Workspace::default();
        assert_eq!(ws.status().phase, Phase::Live);
        ws.action("sweep").unwrap();
        ws.step(1.0 / 60.0);
        assert_eq!(ws.status().phase, Phase::Live);
        sweep(&mut ws);
        assert_eq!(ws.status().phase, Phase::Ended);
        assert_eq!(ws.notice(), None);
        ws.set_param("l2", 0.8).unwrap();
        assert_eq!(
            ws.status().phase,
            Phase::Ended,
            "the same value keeps the cloud"
        );
        assert_eq!(ws.notice(), None);
        ws.set_param("l2", 0.5).unwrap();
        assert_eq!(ws.status(), Status::new("ready to sweep", Tone::Neutral));
        let notice = ws.notice().unwrap();
        assert_eq!(
            (notice.text.as_str(), notice.tone),
            ("settings changed: sweep again", Tone::Warning)
        );
        // Sweeping again withdraws it; a pose change never posts it.
        ws.action("sweep").unwrap();
        assert_eq!(ws.notice(), None);
        ws.set_param("t1", 10.0).unwrap();
        assert_eq!(ws.notice(), None);
    }

    /// Issue 15: in grid mode with an even number of angles per joint the
    /// straight pose is a sample, so the measured outer radius equals
    /// L₁ + L₂ + L₃; with an odd number it falls short.
    #[test]
    fn an_even_grid_measures_the_outer_radius_exactly() {
        for (n, per_joint) in [(8000.0, 20), (27000.0, 30), (1000.0, 10)] {
            let mut ws = Workspace::default();
            ws.set_param("mode", 1.0).unwrap();
            ws.set_param("n", n).unwrap();
            sweep(&mut ws);
            assert_eq!(
                ws.sampler.as_ref().unwrap().mode(),
                SamplingMode::Grid { per_joint }
            );
            assert!(
                (measured(&ws).outer_m - 2.5).abs() < 1e-12,
                "{n}: {}",
                measured(&ws).outer_m
            );
            assert_eq!(readout(&ws, "outer"), readout(&ws, "outer_theory"));
        }
        for (n, per_joint) in [(9000.0, 21), (20000.0, 27)] {
            let mut ws = Workspace::default();
            ws.set_param("mode", 1.0).unwrap();
            ws.set_param("n", n).unwrap();
            sweep(&mut ws);
            assert_eq!(
                ws.sampler.as_ref().unwrap().mode(),
                SamplingMode::Grid { per_joint }
            );
            assert!(
                measured(&ws).outer_m < 2.5 - 1e-3,
                "{n}: {}",
                measured(&ws).outer_m
            );
        }
        let content = format!(
            "{:?}",
            crate::content::Content::parse(include_str!("../../../../../assets/workspace.json"))
                .unwrap()
        );
        assert!(content.contains("even number"), "theory and quiz say so");
    }

    /// Issue 15: generators draw inside the sliders' ranges.
    #[test]
    fn generators_draw_inside_the_sliders_ranges() {
        for name in ["outer_radius", "inner_radius", "tip_x"] {
            for seed in 0..500 {
                let draw = quiz_generator(name).unwrap()(&mut Lcg64::new(seed));
                let mut ws = Workspace::default();
                for (key, _) in &draw.vars {
                    let v = draw.var(key).unwrap();
                    assert_eq!(
                        ws.set_param(key, v),
                        Ok(Sanitized::InRange(v)),
                        "{name}: {key} = {v}"
                    );
                }
                let shown = match name {
                    "outer_radius" => Annulus::of_chain(&ws.lengths_m).outer_m,
                    "inner_radius" => Annulus::of_chain(&ws.lengths_m).inner_m,
                    _ => ws.tip().x,
                };
                assert!((shown - draw.answer).abs() < 1e-12, "{name}");
            }
        }
    }
}
