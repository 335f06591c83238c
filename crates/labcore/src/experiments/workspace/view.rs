//! What experiment 3 shows: the view box, the scene, the readouts and the status.

use super::Workspace;
use crate::experiment::{Experiment, Notice, Presentation, Readout, Status, Tone};
use crate::kinematics::chain::{forward, Annulus};
use crate::kinematics::workspace::{SamplingMode, WorkspaceSampler};
use crate::live_math::{Equation, Expr, Quantity};
use crate::scene::{Item, Role, Scene, ViewBox};
use crate::units::format_point;

/// Most tips stippled individually (the most recent ones); the density map shows them all.
const STIPPLE_MAX: usize = 5000;

const L1: Expr = Expr::Var("l1");
const L2: Expr = Expr::Var("l2");
const L3: Expr = Expr::Var("l3");
const T1: Expr = Expr::Var("t1");
const T12: Expr = Expr::Add(&T1, &Expr::Var("t2"));
const T123: Expr = Expr::Add(&T12, &Expr::Var("t3"));
const REACH: Expr = Expr::Add(&Expr::Add(&L1, &L2), &L3);

/// The three-link arm's forward kinematics and its workspace annulus
/// (Craig, *Introduction to Robotics*, ch. 3–4): the outer radius is the
/// links laid straight, `R_outer = L₁ + L₂ + L₃`; the hole is what the
/// longest link cannot fold back over, `r_inner = max(0, 2 L_max − R_outer)`.
const EQUATIONS: &[Equation] = &[
    Equation {
        key: "x",
        symbol: "x",
        expr: Expr::Add(
            &Expr::Add(
                &Expr::Mul(&L1, &Expr::Cos(&T1)),
                &Expr::Mul(&L2, &Expr::Cos(&T12)),
            ),
            &Expr::Mul(&L3, &Expr::Cos(&T123)),
        ),
        readout: "x",
        caption: "The tip's x: each link adds its length along its absolute angle.",
        absent: "",
    },
    Equation {
        key: "outer",
        symbol: "R_outer",
        expr: REACH,
        readout: "outer_theory",
        caption: "The outer radius: every link laid out straight.",
        absent: "",
    },
    Equation {
        key: "hole",
        symbol: "r_inner",
        expr: Expr::Max(
            &Expr::Num(0.0, "0"),
            &Expr::Sub(&Expr::Mul(&Expr::Num(2.0, "2"), &Expr::Var("lmax")), &REACH),
        ),
        readout: "inner_theory",
        caption: "The hole: what the longest link cannot fold back over.",
        absent: "",
    },
];

impl Presentation for Workspace {
    /// The arm's current reach fills the canvas.
    fn view(&self) -> ViewBox {
        ViewBox::framing(self.lengths_m.iter().sum::<f64>())
    }

    fn scene(&self, out: &mut Scene) {
        out.axes(self.view());
        if !self.tips.is_empty() {
            out.push(Item::Heatmap {
                min: self.density.min,
                cell_m: self.density.cell_m,
                cols: self.density.cols,
                rows: self.density.rows,
                values: self.density.normalized(),
                role: Role::Sample,
            });
            let from = self.tips.len().saturating_sub(STIPPLE_MAX);
            out.push(Item::Points {
                points: self.tips[from..].to_vec(),
                radius_px: 0.9,
                role: Role::Sample,
            });
        }
        let annulus = Annulus::of_chain(&self.lengths_m);
        out.bound_circle(annulus.outer_m);
        out.bound_circle(annulus.inner_m);
        let pose = forward(&self.lengths_m, &self.angles_rad());
        out.chain(&pose.points, Role::Link);
        out.tag_arm(&pose.points, &self.angles_rad());
    }

    fn quantities(&self) -> Vec<Quantity> {
        let [l1, l2, l3] = self.lengths_m;
        let [t1, t2, t3] = self.angles_deg;
        vec![
            Quantity::new("l1", "L_1", l1, 2, "m"),
            Quantity::new("l2", "L_2", l2, 2, "m"),
            Quantity::new("l3", "L_3", l3, 2, "m"),
            Quantity::new("lmax", "L_max", l1.max(l2).max(l3), 2, "m"),
            Quantity::new("t1", "θ_1", t1, 1, "°"),
            Quantity::new("t2", "θ_2", t2, 1, "°"),
            Quantity::new("t3", "θ_3", t3, 1, "°"),
        ]
    }

    fn equations(&self) -> &'static [Equation] {
        EQUATIONS
    }

    fn readouts(&self) -> Vec<Readout> {
        let tip = self.tip();
        let annulus = Annulus::of_chain(&self.lengths_m);
        let measured = self.sampler.as_ref().and_then(WorkspaceSampler::measured);
        // The same 3 decimals (1 mm) as every length readout: with the
        // default 20,000 samples the measured radii stay a few mm inside theory.
        let metres = crate::units::format_metres;
        let (outer, inner) = measured.map_or(("--".into(), "--".into()), |m| {
            (metres(m.outer_m), metres(m.inner_m))
        });
        vec![
            Readout::new("x", "Tip X", metres(tip.x)),
            Readout::new("y", "Tip Y", metres(tip.y)),
            Readout::new("outer", "Outer radius (measured)", outer),
            Readout::new(
                "outer_theory",
                "Outer radius (theory)",
                metres(annulus.outer_m),
            ),
            Readout::new("inner", "Inner hole (measured)", inner),
            Readout::new(
                "inner_theory",
                "Inner hole (theory)",
                metres(annulus.inner_m),
            ),
            Readout::new(
                "samples",
                "Samples drawn",
                self.sampler
                    .as_ref()
                    .map_or("0".into(), |s| match s.mode() {
                        SamplingMode::Grid { per_joint } if s.total() != self.samples => format!(
                            "{} / {} ({per_joint}³ grid of {} requested)",
                            s.produced(),
                            s.total(),
                            self.samples
                        ),
                        _ => format!("{} / {}", s.produced(), s.total()),
                    }),
            ),
        ]
    }

    fn status(&self) -> Status {
        match &self.sampler {
            None => Status::new("ready to sweep", Tone::Neutral),
            // Whole percents, current with the cloud (the page decides how
            // often its live region announces them).
            Some(s) if !s.is_done() => Status::new(
                format!(
                    "sweeping… {}%{}",
                    // Integer arithmetic: 0.29 × 100 would floor to 28.
                    s.produced().saturating_mul(100) / s.total().max(1),
                    self.grid_note()
                        .map_or(String::new(), |n| format!(" ({n})"))
                ),
                Tone::Neutral,
            ),
            Some(s) => Status::ended(
                match self.grid_note() {
                    None => format!("swept {} samples", s.produced()),
                    Some(note) => format!("swept {} samples ({note})", s.produced()),
                },
                Tone::Good,
            ),
        }
    }

    fn notice(&self) -> Option<Notice> {
        self.notices.current()
    }

    /// "Tip at (1.17, 2.02) m. Swept 8000 samples: outer radius 2.500 m (theory 2.500 m), …"
    fn describe(&self) -> String {
        let value = |key| crate::experiment::readout_value(self, key).unwrap_or_default();
        let tip = format!(
            "{}-link arm, tip at {}",
            self.lengths_m.len(),
            format_point(self.tip())
        );
        if self.tips.is_empty() {
            format!(
                "{tip}. No workspace sweep yet: press Sweep workspace; {}.",
                self.status().text
            )
        } else {
            format!(
                "{tip}. {}: {} samples; outer radius {} measured, {} in theory; inner hole {} measured, {} in theory.",
                self.status().text,
                value("samples"),
                value("outer"),
                value("outer_theory"),
                value("inner"),
                value("inner_theory")
            )
        }
    }

    fn hint(&self) -> &'static str {
        "Press Sweep workspace to sample joint space; drag the tip or use the sliders to pose the arm."
    }

    fn preview(&mut self) {
        self.samples = 8000;
        self.start_sweep();
        while self.sweeping() {
            self.step(1.0 / 60.0);
        }
    }
}
