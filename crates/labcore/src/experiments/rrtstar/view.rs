//! What experiment 10 shows: the scene, the readouts, the status and the compare table.
//! Only reads the state.

use super::{path_role, RrtStarField, FIELD_M, GOAL_RADIUS_M};
use crate::experiment::{Notice, Presentation, Readout, Status, Tone};
use crate::live_math::{Equation, Expr, Quantity};
use crate::planning::rrt_star::{Planner, RrtError, RrtStar};
use crate::planning::world::Obstacle;
use crate::scene::{Item, Role, Scene, ViewBox};
use crate::table::Table;
use crate::units::format_metres;
use glam::DVec2;

/// The rewiring radius of RRT* in the plane (Karaman & Frazzoli 2011,
/// Theorem 38, with d = 2): `r(n) = min(γ √(ln n / n), η)`.
const EQUATIONS: &[Equation] = &[Equation {
    key: "radius",
    symbol: "r",
    expr: Expr::Min(
        &Expr::Mul(
            &Expr::Var("gamma"),
            &Expr::Sqrt(&Expr::Div(&Expr::Ln(&Expr::Var("n")), &Expr::Var("n"))),
        ),
        &Expr::Var("eta"),
    ),
    readout: "radius",
    caption: "The rewiring radius: it shrinks as the tree grows (the square root is d = 2's 1/d power), never beyond the step η.",
    absent: "No rewiring tree yet: press Grow with RRT* or Informed RRT* (plain RRT never rewires).",
}];

impl RrtStarField {
    /// The rewiring radius `r(n)` of the tree shown at its node count `n`,
    /// m; NaN without a tree and for plain RRT, which does not rewire.
    fn shown_radius(&self) -> f64 {
        match self.shown() {
            Some(t) if self.planner != Planner::Rrt => t.radius(t.len()),
            _ => f64::NAN,
        }
    }

    /// The step `η` of the tree shown (before any tree, the slider's), m.
    fn shown_eta(&self) -> f64 {
        self.shown().map_or(self.eta_m, |t| t.config().step_eta)
    }
}

impl Presentation for RrtStarField {
    fn view(&self) -> ViewBox {
        ViewBox {
            min: DVec2::splat(-0.2),
            max: FIELD_M + 0.2,
        }
    }

    fn scene(&self, out: &mut Scene) {
        out.push(Item::Rect {
            min: DVec2::ZERO,
            max: FIELD_M,
            role: Role::Bound,
            fill: false,
        });
        for o in &self.obstacles {
            out.push(match *o {
                Obstacle::Circle { center, radius } => Item::Circle {
                    center,
                    radius_m: radius,
                    role: Role::Obstacle,
                    fill: true,
                    dashed: false,
                },
                Obstacle::Rect { min, max } => Item::Rect {
                    min,
                    max,
                    role: Role::Obstacle,
                    fill: true,
                },
            });
        }
        if let Some(run) = self.shown_run() {
            let tree = &run.tree;
            let nodes = tree.nodes();
            // The whole tree: one kept layer (a pointer copy; the page draws only
            // the edges added or rewired since its last frame).
            out.push(Item::SegmentLayer {
                layer: run.edges.clone(),
                width_px: 1.0,
                role: Role::Visited,
            });
            if self.growing {
                let rewired: Vec<(DVec2, DVec2)> = tree
                    .rewired_in_last_batch()
                    .iter()
                    .filter_map(|&i| {
                        let p = tree.parent(i as usize)?;
                        Some((nodes[p], nodes[i as usize]))
                    })
                    .collect();
                if !rewired.is_empty() {
                    out.push(Item::Segments {
                        segments: rewired,
                        width_px: 2.5,
                        role: Role::Warning,
                    });
                }
                if let Some(n) = tree.newest() {
                    let r = tree.last_radius();
                    if r > 0.0 {
                        out.push(Item::Circle {
                            center: nodes[n],
                            radius_m: r,
                            role: Role::Accent,
                            fill: false,
                            dashed: true,
                        });
                    }
                }
            }
        }
        // What r(n) = min(γ √(ln n / n), η) names (issue 27 §3): the newest
        // node, the n-th, and around it the rewiring radius r(n) and the step
        // η that caps it.
        if let Some(c) = self.shown().and_then(|t| Some(t.nodes()[t.newest()?])) {
            out.tag_lines(&[("n", c, c)]);
            let radius = self.shown_radius();
            if radius > 0.0 {
                out.tag_circle("radius", c, radius);
            }
            out.tag_circle("eta", c, self.shown_eta());
        }
        // The other planners' best paths (Compare), then the shown one on top.
        if self.runs.len() > 1 {
            for r in self.runs.iter().filter(|r| r.planner != self.planner) {
                if let Some(path) = r.tree.best_path() {
                    out.push(Item::Polyline {
                        points: path,
                        width_px: 2.0,
                        role: path_role(r.planner),
                        dashed: true,
                        closed: false,
                    });
                }
            }
        }
        let path = if self.driven_m.is_some() {
            Some(self.drive_path.points().to_vec())
        } else {
            self.best_path()
        };
        if let Some(path) = path.filter(|p| p.len() >= 2) {
            out.push(Item::Polyline {
                points: path,
                width_px: 3.0,
                role: Role::Path,
                dashed: false,
                closed: false,
            });
        }
        out.push(Item::Circle {
            center: self.goal,
            radius_m: GOAL_RADIUS_M,
            role: Role::Tip,
            fill: false,
            dashed: true,
        });
        out.push(Item::Dot {
            center: self.start,
            radius_px: 8.0,
            role: Role::Sample,
        });
        out.push(Item::Dot {
            center: self.goal,
            radius_px: 8.0,
            role: Role::Tip,
        });
        out.push(Item::Label {
            pos: self.start,
            text: "start".into(),
            role: Role::Text,
            offset_px: DVec2::new(10.0, -10.0),
        });
        out.push(Item::Label {
            pos: self.goal,
            text: "goal".into(),
            role: Role::Text,
            offset_px: DVec2::new(10.0, -10.0),
        });
        if let Some(p) = self.robot() {
            out.push(Item::Circle {
                center: p,
                radius_m: 0.18,
                role: Role::Robot,
                fill: true,
                dashed: false,
            });
        }
    }

    fn readouts(&self) -> Vec<Readout> {
        let tree = self.shown();
        let status = self.status().text;
        vec![
            Readout::new("nodes", "Nodes", tree.map_or(1, RrtStar::len).to_string()),
            Readout::new(
                "iterations",
                "Iterations",
                tree.map_or(0, RrtStar::iterations).to_string(),
            ),
            Readout::new(
                "rewires",
                "Rewires",
                tree.map_or(0, RrtStar::rewire_count).to_string(),
            ),
            Readout::metres(
                "best",
                "Best length",
                tree.and_then(RrtStar::best_cost).unwrap_or(f64::NAN),
            ),
            Readout::metres("radius", "Rewiring radius r", self.shown_radius()),
            Readout::new("status", "Status", status),
        ]
    }

    /// The tree shown: its node count, `γ` and the step `η` (before any
    /// tree, the field's `γ` and the slider's `η`).
    fn quantities(&self) -> Vec<Quantity> {
        let tree = self.shown();
        let gamma = tree.map_or_else(
            || crate::planning::rrt_star::default_gamma(FIELD_M.x * FIELD_M.y),
            RrtStar::gamma,
        );
        vec![
            Quantity::new("gamma", "γ", gamma, 3, "m"),
            Quantity::new("n", "n", tree.map_or(1, RrtStar::len) as f64, 0, ""),
            Quantity::new("eta", "η", self.shown_eta(), 2, "m"),
            Quantity::new("radius", "r", self.shown_radius(), 3, "m"),
        ]
    }

    fn equations(&self) -> &'static [Equation] {
        EQUATIONS
    }

    fn status(&self) -> Status {
        if let Some(e) = self.error {
            let text = match e {
                RrtError::StartNotFree => {
                    "the start is in an obstacle: drag it to free space".to_owned()
                }
                RrtError::GoalNotFree => {
                    "the goal is in an obstacle: drag it to free space".to_owned()
                }
                e => e.to_string(),
            };
            return Status::new(text, Tone::Bad);
        }
        let Some(tree) = self.shown() else {
            return Status::new("idle: press Grow tree", Tone::Neutral);
        };
        let best = tree.best_cost();
        if self.driven_m.is_some() {
            return if self.driving() {
                Status::new("driving the best path", Tone::Good)
            } else {
                Status::ended("arrived at the goal", Tone::Good)
            };
        }
        let what = if self.runs.len() > 1 {
            "comparing"
        } else {
            "growing"
        };
        match (self.growing, best) {
            (true, None) => Status::new(
                format!("{what}… {} nodes, no path yet", tree.len()),
                Tone::Neutral,
            ),
            (true, Some(c)) => {
                Status::new(format!("{what}… best {}", format_metres(c)), Tone::Good)
            }
            (false, Some(c)) => {
                Status::ended(format!("done: best path {}", format_metres(c)), Tone::Good)
            }
            (false, None) => Status::ended(
                format!("no path found in {} iterations", tree.iterations()),
                Tone::Warning,
            ),
        }
    }

    fn notice(&self) -> Option<Notice> {
        self.notices.current()
    }

    /// "Start at (…) m, goal at (…) m, 4 obstacles; 1125 nodes; done: best path 8.655 m."
    fn describe(&self) -> String {
        use crate::units::format_point;
        let tree = self.shown().map_or(String::new(), |t| {
            format!(" {} nodes in the tree;", t.len())
        });
        let robot = self
            .robot()
            .map_or(String::new(), |p| format!(" Robot at {}.", format_point(p)));
        format!(
            "Start at {}, goal at {}, {} obstacle{};{tree} {}.{robot}",
            format_point(self.start),
            format_point(self.goal),
            self.obstacles.len(),
            if self.obstacles.len() == 1 { "" } else { "s" },
            self.status().text
        )
    }

    fn hint(&self) -> &'static str {
        "Press Grow tree. Drag the start, goal or obstacles; click free space to add a disc (drop one outside the field to remove it); Shift-click sets the start, Ctrl-click the goal."
    }

    fn touch_hint(&self) -> &'static str {
        "Press Grow tree. Drag the start, the goal or an obstacle; tap free space to add a disc, and drop a disc outside the field to remove it."
    }

    fn tables(&self) -> Vec<Table> {
        if self.runs.len() < 2 {
            return Vec::new();
        }
        let mut t = Table::new(
            "compare",
            "Same seed, same field. The selected planner's path is solid amber; the others are dashed (RRT orange, RRT* amber, Informed RRT* blue).",
            &[
                "planner",
                "iter.",
                "nodes",
                "first path",
                "best",
            ],
        );
        for r in &self.runs {
            let first = r.tree.cost_history().first();
            t.push_row(vec![
                r.planner.name().into(),
                r.tree.iterations().to_string(),
                r.tree.len().to_string(),
                first.map_or("--".into(), |s| s.iteration.to_string()),
                format_metres(r.tree.best_cost().unwrap_or(f64::NAN)),
            ]);
        }
        if let Some(i) = self.runs.iter().position(|r| r.planner == self.planner) {
            t.highlight = Some(i);
        }
        vec![t]
    }

    fn preview(&mut self) {
        self.start_run(&[self.planner]);
        if let Some(run) = self.runs.first_mut() {
            run.grow(1500);
        }
        self.growing = false;
    }
}
