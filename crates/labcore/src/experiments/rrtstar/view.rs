//! What experiment 10 shows: the scene, the readouts, the status and the compare table.
//! Only reads the state.

use super::*;

pub(super) fn tables(f: &RrtStarField) -> Vec<Table> {
    if f.runs.len() < 2 {
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
    for r in &f.runs {
        let first = r.tree.cost_history().first();
        t.push_row(vec![
            r.planner.name().into(),
            r.tree.iterations().to_string(),
            r.tree.len().to_string(),
            first.map_or("--".into(), |s| s.iteration.to_string()),
            format_metres(r.tree.best_cost().unwrap_or(f64::NAN)),
        ]);
    }
    if let Some(i) = f.runs.iter().position(|r| r.planner == f.planner) {
        t.highlight = Some(i);
    }
    vec![t]
}

pub(super) fn scene(f: &RrtStarField, out: &mut Scene) {
    out.push(Item::Rect {
        min: DVec2::ZERO,
        max: FIELD_M,
        role: Role::Bound,
        fill: false,
    });
    for o in &f.obstacles {
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
    if let Some(run) = f.shown_run() {
        let tree = &run.tree;
        let nodes = tree.nodes();
        // The whole tree: one kept layer (a pointer copy; the page draws only
        // the edges added or rewired since its last frame).
        out.push(Item::SegmentLayer {
            layer: run.edges.clone(),
            width_px: 1.0,
            role: Role::Visited,
        });
        if f.growing {
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
    // The other planners' best paths (Compare), then the shown one on top.
    if f.runs.len() > 1 {
        for r in f.runs.iter().filter(|r| r.planner != f.planner) {
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
    let path = if f.driven_m.is_some() {
        Some(f.drive_path.clone())
    } else {
        f.best_path()
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
        center: f.goal,
        radius_m: GOAL_RADIUS_M,
        role: Role::Tip,
        fill: false,
        dashed: true,
    });
    out.push(Item::Dot {
        center: f.start,
        radius_px: 8.0,
        role: Role::Sample,
    });
    out.push(Item::Dot {
        center: f.goal,
        radius_px: 8.0,
        role: Role::Tip,
    });
    out.push(Item::Label {
        pos: f.start,
        text: "start".into(),
        role: Role::Text,
        offset_px: DVec2::new(10.0, -10.0),
    });
    out.push(Item::Label {
        pos: f.goal,
        text: "goal".into(),
        role: Role::Text,
        offset_px: DVec2::new(10.0, -10.0),
    });
    if let Some(p) = f.robot() {
        out.push(Item::Circle {
            center: p,
            radius_m: 0.18,
            role: Role::Robot,
            fill: true,
            dashed: false,
        });
    }
}

pub(super) fn readouts(f: &RrtStarField) -> Vec<Readout> {
    let tree = f.shown();
    let status = f.status().text;
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
        Readout::metres(
            "radius",
            "Rewiring radius r",
            tree.map_or(f64::NAN, |t| {
                if f.planner == Planner::Rrt {
                    f64::NAN
                } else {
                    t.radius(t.len())
                }
            }),
        ),
        Readout::new("status", "Status", status),
    ]
}

/// "Start at (…) m, goal at (…) m, 4 obstacles; 1125 nodes; done: best path 8.655 m."
pub(super) fn describe(f: &RrtStarField) -> String {
    use crate::units::format_point;
    let tree = f.shown().map_or(String::new(), |t| {
        format!(" {} nodes in the tree;", t.len())
    });
    let robot = f
        .robot()
        .map_or(String::new(), |p| format!(" Robot at {}.", format_point(p)));
    format!(
        "Start at {}, goal at {}, {} obstacle{};{tree} {}.{robot}",
        format_point(f.start),
        format_point(f.goal),
        f.obstacles.len(),
        if f.obstacles.len() == 1 { "" } else { "s" },
        status(f).text
    )
}

pub(super) fn status(f: &RrtStarField) -> Status {
    if let Some(e) = f.error {
        let text = match e {
            RrtError::StartNotFree => {
                "the start is in an obstacle: drag it to free space".to_owned()
            }
            RrtError::GoalNotFree => "the goal is in an obstacle: drag it to free space".to_owned(),
            e => e.to_string(),
        };
        return Status::new(text, Tone::Bad);
    }
    let Some(tree) = f.shown() else {
        return Status::new("idle: press Grow tree", Tone::Neutral);
    };
    let best = tree.best_cost();
    if f.driven_m.is_some() {
        return if f.driving() {
            Status::new("driving the best path", Tone::Good)
        } else {
            Status::ended("arrived at the goal", Tone::Good)
        };
    }
    let what = if f.runs.len() > 1 {
        "comparing"
    } else {
        "growing"
    };
    match (f.growing, best) {
        (true, None) => Status::new(
            format!("{what}… {} nodes, no path yet", tree.len()),
            Tone::Neutral,
        ),
        (true, Some(c)) => Status::new(format!("{what}… best {}", format_metres(c)), Tone::Good),
        (false, Some(c)) => {
            Status::ended(format!("done: best path {}", format_metres(c)), Tone::Good)
        }
        (false, None) => Status::ended(
            format!("no path found in {} iterations", tree.iterations()),
            Tone::Warning,
        ),
    }
}
