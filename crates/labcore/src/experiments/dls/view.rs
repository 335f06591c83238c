//! What experiment 9 shows: the view box, the scene, the readouts and the status.

use super::{
    DampedLeastSquares, Run, ELLIPSE_SCALE, NO_PROGRESS_ITERATIONS, TOTAL_REACH_M, VIEW_HALF_M,
};
use crate::experiment::{Experiment, Presentation, Readout, Status, Tone};
use crate::kinematics::chain::{forward, Annulus};
use crate::kinematics::jacobian::jacobian;
use crate::live_math::{four_significant, Equation, Expr, Quantity};
use crate::scene::{Item, Role, Scene, ViewBox};
use crate::units::{format_degrees, format_fixed, format_magnitude, format_metres, format_point};
use glam::DVec2;

const A: Expr = Expr::Var("a");
const B: Expr = Expr::Var("b");
const C: Expr = Expr::Var("c");
/// The remaining error, then Yoshikawa's manipulability `w = √det(J Jᵀ)`
/// of the 2×2 `J Jᵀ` in closed form and the condition number `σmax/σmin`
/// (Yoshikawa 1985; Nakamura & Hanafusa 1986 for the damping it guides).
const EQUATIONS: &[Equation] = &[
    Equation {
        key: "error",
        symbol: "|e|",
        expr: Expr::Sqrt(&Expr::Add(
            &Expr::Sq(&Expr::Sub(&Expr::Var("xt"), &Expr::Var("x"))),
            &Expr::Sq(&Expr::Sub(&Expr::Var("yt"), &Expr::Var("y"))),
        )),
        readout: "error",
        caption: "The error e the next step Δq = Jᵀ(JJᵀ + λ²I)⁻¹e works on: from the tip p(q) = (x, y) to the target p* = (xₜ, yₜ).",
        absent: "No target yet: put one on the canvas, or type its x and y.",
    },
    Equation {
        key: "w",
        symbol: "w",
        expr: Expr::Sqrt(&Expr::Max(
            &Expr::Num(0.0, "0"),
            &Expr::Sub(&Expr::Mul(&A, &C), &Expr::Sq(&B)),
        )),
        readout: "w",
        caption: "The manipulability √det(JJᵀ), with JJᵀ = [[a, b], [b, c]]: the area of the velocity ellipse over π, 0 at a singularity.",
        absent: "",
    },
    Equation {
        key: "condition",
        symbol: "κ",
        expr: Expr::Div(&Expr::Var("smax"), &Expr::Var("smin")),
        readout: "cond",
        caption: "The condition number κ: the velocity ellipse's long semi-axis over its short one (J's singular values); it blows up near a singularity.",
        absent: "",
    },
];

/// "1 iteration", "4 iterations".
fn iterations(n: usize) -> String {
    format!("{n} iteration{}", if n == 1 { "" } else { "s" })
}

impl Presentation for DampedLeastSquares {
    fn view(&self) -> ViewBox {
        ViewBox::centered(VIEW_HALF_M)
    }

    fn scene(&self, out: &mut Scene) {
        out.axes(self.view());
        let lengths = self.lengths();
        out.bound_circle(Annulus::of_chain(&lengths).outer_m);
        let pose = forward(&lengths, &self.angles_rad);
        let tip = pose.tip();
        let m = self.manipulability();
        out.push(Item::Ellipse {
            center: tip,
            semi_axis_a: m.u_max * m.sigma_max * ELLIPSE_SCALE,
            semi_axis_b: m.u_min * m.sigma_min * ELLIPSE_SCALE,
            role: Role::Accent,
        });
        if let Some(target) = self.target {
            let unreachable = target.length() > TOTAL_REACH_M;
            let role = if unreachable {
                Role::Warning
            } else {
                Role::Target
            };
            out.push(Item::Line {
                from: tip,
                to: target,
                width_px: 1.5,
                role,
                dashed: true,
            });
            out.push(Item::Dot {
                center: target,
                radius_px: 6.0,
                role,
            });
        }
        out.chain(&pose.points, Role::Link);
        // What the error and the ellipse's quantities name (issue 27 §3):
        // the tip's coordinates x and y, the target, the error e from the
        // tip to it, and the velocity ellipse's semi-axes σmax and σmin.
        let foot = DVec2::new(tip.x, 0.0);
        out.tag_lines(&[
            ("x", DVec2::ZERO, foot),
            ("y", foot, tip),
            ("smax", tip, tip + m.u_max * m.sigma_max * ELLIPSE_SCALE),
            ("smin", tip, tip + m.u_min * m.sigma_min * ELLIPSE_SCALE),
        ]);
        if let Some(t) = self.target {
            out.tag_lines(&[("xt", t, t), ("yt", t, t), ("error", tip, t)]);
        }
    }

    fn readouts(&self) -> Vec<Readout> {
        let m = self.manipulability();
        let error = self.error_m.map_or("--".into(), |e| {
            if e < 1e-3 && e > 0.0 {
                format!("{} m", format_magnitude(e))
            } else {
                format_metres(e)
            }
        });
        let angles: Vec<String> = self
            .angles_rad
            .iter()
            .map(|a| format_degrees(crate::kinematics::two_link_ik::wrap_pi(*a).to_degrees()))
            .collect();
        vec![
            Readout::new("iterations", "Iterations", self.iterations.to_string()),
            Readout::new("error", "Error", error),
            Readout::new(
                "w",
                "Manipulability w",
                format!("{} m²", format_fixed(m.w, 3)),
            ),
            Readout::new("cond", "Condition σmax/σmin", format_magnitude(m.condition)),
            Readout::metres("lambda_used", "λ used", self.lambda_used_m),
            Readout::new("angles", "Joint angles θ₁…θₙ", angles.join(", ")),
        ]
    }

    /// The tip, the target and the entries of `J Jᵀ` at the current pose.
    fn quantities(&self) -> Vec<Quantity> {
        let tip = self.tip();
        let target = self.target.unwrap_or(DVec2::NAN);
        let (a, b, c) =
            crate::kinematics::jacobian::jjt_entries(&jacobian(&self.lengths(), &self.angles_rad));
        let m = self.manipulability();
        // Four significant digits, so a small σ_min still shows what it is.
        let significant = four_significant;
        vec![
            Quantity::new("xt", "x_t", target.x, 3, "m"),
            Quantity::new("x", "x", tip.x, 3, "m"),
            Quantity::new("yt", "y_t", target.y, 3, "m"),
            Quantity::new("y", "y", tip.y, 3, "m"),
            Quantity::new("a", "a", a, 4, "m²"),
            Quantity::new("b", "b", b, 4, "m²"),
            Quantity::new("c", "c", c, 4, "m²"),
            Quantity::new("smax", "σ_max", m.sigma_max, significant(m.sigma_max), "m"),
            Quantity::new("smin", "σ_min", m.sigma_min, significant(m.sigma_min), "m"),
            Quantity::new("error", "|e|", (target - tip).length(), 3, "m"),
        ]
    }

    fn equations(&self) -> &'static [Equation] {
        EQUATIONS
    }

    fn status(&self) -> Status {
        match self.run {
            Run::Idle => Status::new("click a target", Tone::Neutral),
            Run::Iterating => Status::new("iterating…", Tone::Neutral),
            Run::Converged => Status::ended(
                format!("converged in {}", iterations(self.iterations)),
                Tone::Good,
            ),
            Run::Settled => Status::ended("closest reachable pose", Tone::Warning),
            Run::NoProgress { oscillating: true } => Status::ended(
                format!(
                    "not converging: the error rises and falls (no progress in {NO_PROGRESS_ITERATIONS} iterations)"
                ),
                Tone::Bad,
            ),
            Run::NoProgress { oscillating: false } => Status::ended(
                format!("stalled: no progress in {NO_PROGRESS_ITERATIONS} iterations"),
                Tone::Warning,
            ),
            Run::GaveUp => Status::ended(
                format!("stopped: iteration limit ({})", self.max_iterations),
                Tone::Warning,
            ),
        }
    }

    /// "4-link arm, tip at (…) m, target at (…) m: converged in 4 iterations; error 5.6 × 10⁻⁷ m."
    fn describe(&self) -> String {
        let value = |key| crate::experiment::readout_value(self, key).unwrap_or_default();
        let arm = format!(
            "{}-link arm, tip at {}",
            self.links,
            format_point(self.tip())
        );
        match self.target {
            None => format!("{arm}. No target yet; {}.", self.status().text),
            Some(t) => format!(
                "{arm}, target at {}: {}; error {}, {}.",
                format_point(t),
                self.status().text,
                value("error"),
                iterations(self.iterations)
            ),
        }
    }

    fn hint(&self) -> &'static str {
        "Click or tap a target (or type its x and y) and watch each damped least-squares iteration."
    }

    fn touch_hint(&self) -> &'static str {
        "Tap a target (or type its x and y) and watch each damped least-squares iteration."
    }

    fn preview(&mut self) {
        self.set_target(DVec2::new(1.3, 1.1));
        while self.animating() {
            self.iterate();
        }
    }
}
