//! What experiment 2 shows: the view box, the scene, the readouts and the status.

use super::{InverseKinematics, Solved};
use crate::experiment::{Experiment, Presentation, Readout, Status, Tone};
use crate::kinematics::two_link_ik::{Elbow, Singularity};
use crate::live_math::{Equation, Expr, Quantity};
use crate::scene::{Item, Role, Scene, ViewBox};
use crate::units::{format_degrees, format_point};
use glam::DVec2;

const L1: Expr = Expr::Var("l1");
const L2: Expr = Expr::Var("l2");
/// The law of cosines for the elbow: `cos θ₂ = (x² + y² − L₁² − L₂²) / (2 L₁ L₂)`
/// (Craig, *Introduction to Robotics*, §4.4; Spong et al., §3.3).
const COS_THETA2: Expr = Expr::Div(
    &Expr::Sub(
        &Expr::Sub(
            &Expr::Add(&Expr::Sq(&Expr::Var("px")), &Expr::Sq(&Expr::Var("py"))),
            &Expr::Sq(&L1),
        ),
        &Expr::Sq(&L2),
    ),
    &Expr::Mul(&Expr::Mul(&Expr::Num(2.0, "2"), &L1), &L2),
);
/// The elbow angle for the point the two links reach for, on the branch
/// `caption` names.
const fn elbow(expr: Expr, caption: &'static str) -> [Equation; 1] {
    [Equation {
        key: "theta2",
        symbol: "θ_2",
        expr,
        readout: "theta2",
        caption,
        absent: "No elbow angle: there is no target yet (put one on the canvas), or it lies out of reach, where the cosine would pass ±1.",
    }]
}
/// `[elbow up, elbow down]` for the target itself, and for the wrist centre
/// `w` when a third link holds the tool's direction: the panel names the
/// point its x and y are of.
const ELBOWS: [[&[Equation]; 2]; 2] = [
    [
        &elbow(
            Expr::Neg(&Expr::Acos(&COS_THETA2)),
            "The elbow angle from the law of cosines, for the target (x, y); elbow up takes the negative root.",
        ),
        &elbow(
            Expr::Acos(&COS_THETA2),
            "The elbow angle from the law of cosines, for the target (x, y); elbow down takes the positive root.",
        ),
    ],
    [
        &elbow(
            Expr::Neg(&Expr::Acos(&COS_THETA2)),
            "The elbow angle from the law of cosines, for the wrist centre w, the point the two links reach for (the target stepped back along the tool); elbow up takes the negative root.",
        ),
        &elbow(
            Expr::Acos(&COS_THETA2),
            "The elbow angle from the law of cosines, for the wrist centre w, the point the two links reach for (the target stepped back along the tool); elbow down takes the positive root.",
        ),
    ],
];

impl Presentation for InverseKinematics {
    /// The arm's current reach fills the canvas.
    fn view(&self) -> ViewBox {
        ViewBox::framing(self.l1_m + self.l2_m + self.l3_m)
    }

    fn scene(&self, out: &mut Scene) {
        out.axes(self.view());
        let (centre, annulus) = self.reach();
        for r in [annulus.outer_m, annulus.inner_m] {
            if r > 1e-9 {
                out.push(Item::Circle {
                    center: centre,
                    radius_m: r,
                    role: Role::Bound,
                    fill: false,
                    dashed: true,
                });
            }
        }
        if let Some(Solved::Reachable(sol)) = self.solved {
            let ghost = sol.branch(self.elbow.other());
            if sol.singularity == Singularity::Regular {
                out.chain(
                    &self.points(ghost.theta1_rad.to_degrees(), ghost.theta2_rad.to_degrees()),
                    Role::Ghost,
                );
            }
        }
        let points = self.points(self.theta1_deg, self.theta2_deg);
        out.chain(&points, Role::Link);
        out.tag("l1", points[..2].to_vec());
        out.tag("l2", points[1..3].to_vec());
        if let Some(target) = self.target {
            // x and y of the point the two links reach for, and the point.
            let p = target - self.wrist_offset();
            let foot = DVec2::new(p.x, 0.0);
            out.tag("px", vec![DVec2::ZERO, foot]);
            out.tag("py", vec![foot, p]);
            out.tag("px", vec![p]);
            out.tag("py", vec![p]);
        }
        if let Some(target) = self.target {
            let out_of_reach = matches!(self.solved, Some(Solved::OutOfReach { .. }));
            let role = if out_of_reach {
                Role::Warning
            } else {
                Role::Target
            };
            let arm = 0.08;
            out.push(Item::Line {
                from: target - DVec2::new(arm, 0.0),
                to: target + DVec2::new(arm, 0.0),
                width_px: 2.0,
                role,
                dashed: false,
            });
            out.push(Item::Line {
                from: target - DVec2::new(0.0, arm),
                to: target + DVec2::new(0.0, arm),
                width_px: 2.0,
                role,
                dashed: false,
            });
            out.push(Item::Circle {
                center: target,
                radius_m: arm,
                role,
                fill: false,
                dashed: out_of_reach,
            });
            if out_of_reach {
                out.push(Item::Label {
                    pos: target,
                    text: "out of reach".into(),
                    role: Role::Warning,
                    offset_px: DVec2::new(12.0, -14.0),
                });
            }
        }
    }

    /// The point the two links reach for (the target (x, y), or with a
    /// wrist the wrist centre (w_x, w_y), as the Theory names them), and the
    /// link lengths.
    fn quantities(&self) -> Vec<Quantity> {
        let p = self.target.map_or(DVec2::NAN, |t| t - self.wrist_offset());
        let wrist = self.l3_m > 0.0;
        vec![
            Quantity::new("px", if wrist { "w_x" } else { "x" }, p.x, 3, "m"),
            Quantity::new("py", if wrist { "w_y" } else { "y" }, p.y, 3, "m"),
            Quantity::new("l1", "L_1", self.l1_m, 2, "m"),
            Quantity::new("l2", "L_2", self.l2_m, 2, "m"),
        ]
    }

    fn equations(&self) -> &'static [Equation] {
        ELBOWS[usize::from(self.l3_m > 0.0)][usize::from(self.elbow == Elbow::Down)]
    }

    fn readouts(&self) -> Vec<Readout> {
        let tip = self.tip();
        let sol = self.solution();
        let angle = |key, label, a: Option<f64>| match a {
            Some(rad) => Readout::degrees(key, label, rad.to_degrees()),
            None => Readout::new(key, label, "--"),
        };
        let mut r = vec![
            Readout::metres("x", "End-effector X", tip.x),
            Readout::metres("y", "End-effector Y", tip.y),
            angle("theta1", "θ₁ solved", sol.map(|a| a.theta1_rad)),
            angle("theta2", "θ₂ solved", sol.map(|a| a.theta2_rad)),
        ];
        r.push(match sol {
            Some(a) if self.l3_m > 0.0 => angle(
                "theta3",
                "θ₃ (wrist)",
                Some(crate::kinematics::two_link_ik::wrap_pi(
                    self.phi_deg.to_radians() - a.theta1_rad - a.theta2_rad,
                )),
            ),
            _ if self.l3_m > 0.0 => Readout::new("theta3", "θ₃ (wrist)", "--"),
            _ => Readout::new("theta3", "θ₃ (wrist)", "no wrist"),
        });
        r
    }

    fn status(&self) -> Status {
        // A move that has arrived is over (the page offers Replay); while
        // the arm moves, or after a slider took it off its goal, it is live.
        let status = |text: String, tone| {
            if self.arrived() {
                Status::ended(text, tone)
            } else {
                Status::new(text, tone)
            }
        };
        match self.solved {
            None => Status::new("click a target", Tone::Neutral),
            Some(Solved::OutOfReach { .. }) => status(
                format!("out of reach: {}", self.out_of_reach_reason()),
                Tone::Bad,
            ),
            Some(Solved::Reachable(sol)) => match sol.singularity {
                Singularity::Regular if self.near_boundary() => status(
                    "near singular: the branches almost merge".into(),
                    Tone::Warning,
                ),
                Singularity::Regular => status("in reach".into(), Tone::Good),
                Singularity::OuterBoundary => status(
                    "singular: arm straight, branches merge".into(),
                    Tone::Warning,
                ),
                Singularity::InnerBoundary => {
                    status("singular: arm folded, branches merge".into(), Tone::Warning)
                }
                Singularity::AtBase => status("singular: any θ₁ works".into(), Tone::Warning),
            },
        }
    }

    /// "Target at (1.10, 0.90) m: in reach. Arm at θ₁ 66.4°, θ₂ -67.8°, tip at (1.10, 0.90) m."
    fn describe(&self) -> String {
        let arm = format!(
            "Arm at θ₁ {}, θ₂ {}, tip at {}",
            format_degrees(self.theta1_deg),
            format_degrees(self.theta2_deg),
            format_point(self.tip())
        );
        // The other branch, drawn as a ghost arm where the two differ.
        let ghost = match self.solved {
            Some(Solved::Reachable(sol)) if sol.singularity == Singularity::Regular => {
                let g = sol.branch(self.elbow.other());
                format!(
                    " 1 ghost arm shows the other branch, θ₁ {}, θ₂ {}.",
                    format_degrees(g.theta1_rad.to_degrees()),
                    format_degrees(g.theta2_rad.to_degrees())
                )
            }
            Some(Solved::Reachable(_)) => " No ghost arm: the branches merge.".to_owned(),
            _ => String::new(),
        };
        let (centre, annulus) = self.reach();
        let reach = annulus.words((centre != DVec2::ZERO).then_some(centre));
        match self.target {
            None => format!("No target yet: {}. {arm}. {reach}.", self.status().text),
            Some(t) => format!(
                "Target at {}: {}. {arm}{}.{ghost} {reach}.",
                format_point(t),
                self.status().text,
                if self.animating() { ", moving" } else { "" }
            ),
        }
    }

    fn hint(&self) -> &'static str {
        "Click or tap a target, or type its x and y; the arm moves to the closed-form solution."
    }

    fn touch_hint(&self) -> &'static str {
        "Tap a target, or type its x and y; the arm moves to the closed-form solution."
    }

    fn preview(&mut self) {
        self.set_target(DVec2::new(1.1, 0.9));
        while self.animating() {
            self.step(0.05);
        }
    }
}
