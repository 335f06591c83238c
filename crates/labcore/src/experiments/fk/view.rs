//! What experiment 1 shows: the view box, the scene, the readouts and the status.

use super::ForwardKinematics;
use crate::experiment::{Presentation, Readout, Status, Tone};
use crate::kinematics::chain::{forward, Annulus};
use crate::live_math::{Equation, Expr, Quantity};
use crate::scene::{Item, Role, Scene, ViewBox};
use crate::units::{format_degrees, format_fixed, format_length, format_point};
use glam::DVec2;

const L1: Expr = Expr::Var("l1");
const L2: Expr = Expr::Var("l2");
const T1: Expr = Expr::Var("t1");
const T12: Expr = Expr::Add(&T1, &Expr::Var("t2"));

/// Forward kinematics of the two-link arm (Craig, *Introduction to
/// Robotics*, ch. 3): `x = L₁cos θ₁ + L₂cos(θ₁+θ₂)`, `y = L₁sin θ₁ + L₂sin(θ₁+θ₂)`.
const EQUATIONS: &[Equation] = &[
    Equation {
        key: "x",
        symbol: "x",
        expr: Expr::Add(
            &Expr::Mul(&L1, &Expr::Cos(&T1)),
            &Expr::Mul(&L2, &Expr::Cos(&T12)),
        ),
        readout: "x",
        caption: "The tip's x: each link's length times the cosine of its absolute angle.",
        absent: "",
    },
    Equation {
        key: "y",
        symbol: "y",
        expr: Expr::Add(
            &Expr::Mul(&L1, &Expr::Sin(&T1)),
            &Expr::Mul(&L2, &Expr::Sin(&T12)),
        ),
        readout: "y",
        caption: "The tip's y: the same with sines.",
        absent: "",
    },
];

impl Presentation for ForwardKinematics {
    /// The arm's current reach fills the canvas.
    fn view(&self) -> ViewBox {
        ViewBox::framing(self.l1_m + self.l2_m)
    }

    fn scene(&self, out: &mut Scene) {
        let view = self.view();
        out.axes(view);
        let annulus = Annulus::of_chain(&self.lengths());
        out.bound_circle(annulus.outer_m);
        out.bound_circle(annulus.inner_m);
        let pose = forward(&self.lengths(), &self.angles_rad());
        if let Some(target) = self.drag_target {
            out.push(Item::Line {
                from: pose.tip(),
                to: target,
                width_px: 1.5,
                role: Role::Target,
                dashed: true,
            });
            out.push(Item::Dot {
                center: target,
                radius_px: 5.0,
                role: Role::Target,
            });
        }
        out.chain(&pose.points, Role::Link);
        let tip = pose.tip();
        out.tag_arm(&pose.points, &self.angles_rad());
        out.tag("x", vec![DVec2::ZERO, DVec2::new(tip.x, 0.0)]);
        out.tag("y", vec![DVec2::new(tip.x, 0.0), tip]);
        out.push(Item::Label {
            pos: tip,
            // The readouts' digits and unit: one format for the tip's position.
            text: format!(
                "({}, {}) m",
                format_fixed(tip.x, Readout::METRE_DECIMALS),
                format_fixed(tip.y, Readout::METRE_DECIMALS)
            ),
            role: Role::Tip,
            offset_px: DVec2::new(12.0, -12.0),
        });
    }

    fn readouts(&self) -> Vec<Readout> {
        let tip = self.tip();
        let annulus = Annulus::of_chain(&self.lengths());
        let mut r = vec![
            Readout::metres("x", "End-effector X", tip.x),
            Readout::metres("y", "End-effector Y", tip.y),
            Readout::new(
                "reach",
                "Reach used",
                format!("{}%", format_fixed(100.0 * annulus.reach_used(tip), 1)),
            ),
        ];
        // Only while a pointer drags beyond reach: inside, the tip follows the
        // pointer and the distance is always 0.
        if let Some(gap) = self.target_gap_m() {
            r.push(Readout::new("target", "Target dist", format_length(gap)));
        }
        r
    }

    fn quantities(&self) -> Vec<Quantity> {
        vec![
            Quantity::new("l1", "L_1", self.l1_m, 2, "m"),
            Quantity::new("l2", "L_2", self.l2_m, 2, "m"),
            Quantity::new("t1", "θ_1", self.theta1_deg, 1, "°"),
            Quantity::new("t2", "θ_2", self.theta2_deg, 1, "°"),
            Quantity::new("x", "x", self.tip().x, 3, "m"),
            Quantity::new("y", "y", self.tip().y, 3, "m"),
        ]
    }

    fn equations(&self) -> &'static [Equation] {
        EQUATIONS
    }

    fn status(&self) -> Status {
        match self.drag_target {
            Some(t) if !Annulus::of_chain(&self.lengths()).contains(t, 1e-9) => {
                Status::new("out of reach", Tone::Warning)
            }
            _ => Status::new("in reach", Tone::Good),
        }
    }

    /// "Two-link arm with θ₁ 35.0° and θ₂ 60.0°: tip at (0.76, 1.27) m, 87.1%
    /// of the reach used; in reach. 2 dashed circles bound the reach: outer
    /// radius 1.700 m, inner radius 0.300 m."
    fn describe(&self) -> String {
        let annulus = Annulus::of_chain(&self.lengths());
        format!(
            "Two-link arm with θ₁ {} and θ₂ {}: tip at {}, {}% of the reach used; {}. {}.",
            format_degrees(self.theta1_deg),
            format_degrees(self.theta2_deg),
            format_point(self.tip()),
            format_fixed(100.0 * annulus.reach_used(self.tip()), 1),
            self.status().text,
            annulus.words(None)
        )
    }

    fn hint(&self) -> &'static str {
        "Move the sliders, or drag the orange tip (arrow keys move it when the canvas has focus)."
    }

    fn touch_hint(&self) -> &'static str {
        "Move the sliders, or drag the orange tip."
    }
}
