//! What the potential-field lab shows: the scene, the readouts and the
//! status badge. Everything here only reads the state.

use super::{PotentialFieldLab, DEFAULT_GOAL, FIELD_H_M, FIELD_W_M, MAX_PREVIEW_STEPS};
use crate::experiment::{Experiment, Notice, Presentation, Readout, Status, Tone};
use crate::live_math::{Equation, Expr, Quantity};
use crate::mobile::potential_field::{Attraction, Repulsion};
use crate::mobile::potential_field::{BasinClass, CircleObstacle, PotentialField, RunStatus};
use crate::scene::wheeled::{draw_field, draw_robot};
use crate::scene::{Item, RasterColour, Role, Scene, ViewBox};
use crate::units::{format_fixed, format_metres};
use glam::DVec2;

/// Heat map resolution: 0.1 m cells.
pub(super) const HEAT_COLS: usize = 80;
pub(super) const HEAT_ROWS: usize = 60;
/// Number of equal potential steps shaded as alternate bands.
const HEAT_BANDS: usize = 16;
/// Spacing of the field-arrow grid, metres.
const ARROW_SPACING_M: f64 = 0.5;
/// Drawn length of a unit force on the robot, metres.
const FORCE_SCALE_M: f64 = 0.6;

/// The field's laws at the robot (Khatib 1986; the lab's conic pull and
/// linear push): the goal distance, the pull, the nearest clearance and its push.
const fn laws(pull: Equation, push: Equation) -> [Equation; 4] {
    [GOAL_DISTANCE, pull, CLEARANCE, push]
}
const GOAL_DISTANCE: Equation = Equation {
    key: "goal_distance",
    symbol: "d_g",
    expr: Expr::Sqrt(&Expr::Add(
        &Expr::Sq(&Expr::Sub(&Expr::Var("xg"), &Expr::Var("x"))),
        &Expr::Sq(&Expr::Sub(&Expr::Var("yg"), &Expr::Var("y"))),
    )),
    readout: "goal",
    caption: "The distance from the robot to the goal.",
    absent: "No goal yet: put one on the canvas where the robot should go.",
};
const PULL: Equation = Equation {
    key: "f_att",
    symbol: "|F_att|",
    expr: Expr::Var("ka"),
    readout: "att",
    caption: "The conic pull: the same strength kₐ at any distance, pointing at the goal.",
    absent: "No goal yet: put one on the canvas where the robot should go.",
};
/// With the goal on the robot the pull has no direction: there is none.
const PULL_AT_GOAL: Equation = Equation {
    key: "f_att",
    symbol: "|F_att|",
    expr: Expr::Num(0.0, "0"),
    readout: "att",
    caption: "With the goal on the robot the pull has no direction to point in: there is none.",
    absent: "No goal yet: put one on the canvas where the robot should go.",
};
const CLEARANCE: Equation = Equation {
    key: "clearance",
    symbol: "d",
    expr: Expr::Sub(
        &Expr::Sqrt(&Expr::Add(
            &Expr::Sq(&Expr::Sub(&Expr::Var("x"), &Expr::Var("cx"))),
            &Expr::Sq(&Expr::Sub(&Expr::Var("y"), &Expr::Var("cy"))),
        )),
        &Expr::Var("r"),
    ),
    readout: "near_clearance",
    caption: "The clearance to the nearest obstacle: the distance to its centre less its radius.",
    absent: "No obstacle on the field: add one to see its clearance and its push.",
};
/// The push outside the nearest obstacle.
const PUSH: Equation = Equation {
        key: "f_rep",
        symbol: "|F_rep|",
        expr: Expr::Div(
            &Expr::Mul(
                &Expr::Var("kr"),
                &Expr::Max(&Expr::Num(0.0, "0"), &Expr::Sub(&Expr::Var("d0"), &Expr::Var("d"))),
            ),
            &Expr::Var("d0"),
        ),
        readout: "rep_near",
        caption: "The nearest obstacle's push: kᵣ at its surface, fading to nothing at the influence distance d₀.",
        absent: "No obstacle on the field: add one to see its clearance and its push.",
    };
/// The push inside it (where its surface's push holds).
const PUSH_INSIDE: Equation = Equation {
    key: "f_rep",
    symbol: "|F_rep|",
    expr: Expr::Var("kr"),
    readout: "rep_near",
    caption: "Inside the nearest obstacle (d < 0) its push is the surface's, kᵣ.",
    absent: "No obstacle on the field: add one to see its clearance and its push.",
};
/// Outside the nearest obstacle, and inside it; then the same with the
/// goal on the robot.
const EQUATIONS: [&[Equation]; 4] = [
    &laws(PULL, PUSH),
    &laws(PULL, PUSH_INSIDE),
    &laws(PULL_AT_GOAL, PUSH),
    &laws(PULL_AT_GOAL, PUSH_INSIDE),
];

impl PotentialFieldLab {
    /// The robot's position: where the run is, else the start.
    fn robot_m(&self) -> DVec2 {
        self.run.map_or(self.start, |r| r.pose.position())
    }

    /// The obstacle nearest the robot's surface, if any. Not inlined: the
    /// scene, the quantities and the equations each ask.
    #[inline(never)]
    fn nearest_obstacle(&self) -> Option<CircleObstacle> {
        let p = self.robot_m();
        self.field
            .obstacles
            .iter()
            .copied()
            .min_by(|a, b| a.clearance_m(p).total_cmp(&b.clearance_m(p)))
    }

    /// The push of the nearest obstacle alone, as the field computes it.
    fn nearest_push(&self) -> Option<f64> {
        let o = self.nearest_obstacle()?;
        let alone = PotentialField {
            obstacles: vec![o],
            ..self.field.clone()
        };
        Some(alone.repulsive_force(self.robot_m()).length())
    }
}

impl PotentialFieldLab {
    pub(super) fn status_of_run(&self) -> Status {
        let Some(run) = self.run else {
            return Status::new("click to set a goal", Tone::Neutral);
        };
        if self.goal_inside_obstacle() {
            return Status::new(
                "the goal is inside an obstacle: move the goal or the obstacle",
                Tone::Bad,
            );
        }
        let p = run.pose.position();
        let to_goal = format_metres((self.field.goal - p).length());
        match run.status {
            RunStatus::Running => Status::new("running", Tone::Neutral),
            RunStatus::Reached => Status::ended(
                format!("reached the goal in {} s", format_fixed(run.time_s, 1)),
                Tone::Good,
            ),
            // The run's own evidence: no progress and held near one spot
            // for the whole detection window (see `TrapDetection`).
            RunStatus::Trapped => Status::ended(
                format!("trapped in a local minimum {to_goal} from the goal"),
                Tone::Bad,
            ),
            RunStatus::LeftField => Status::ended(
                format!(
                    "pushed off the {} edge of the field, {to_goal} from the goal: the pushes outweigh the pull",
                    edge_name(p)
                ),
                Tone::Bad,
            ),
            RunStatus::Collided => Status::ended("collided with an obstacle", Tone::Bad),
            RunStatus::StartInsideObstacle => Status::new(
                "the start is inside an obstacle: drag the start or the obstacle away",
                Tone::Bad,
            ),
            RunStatus::TimedOut => Status::ended(
                format!(
                    "stopped after {} s without arriving",
                    format_fixed(run.time_s, 0)
                ),
                Tone::Warning,
            ),
        }
    }

    /// Potential over the field, scaled into `(0, 1]` for the heat map:
    /// darker is higher, and alternate bands of [`HEAT_BANDS`] equal steps of
    /// `U` are shaded a little darker, so the level sets (which bend around
    /// the obstacles' small hills) show even where the goal's cone dominates.
    pub(super) fn heat_values(&self) -> Vec<f32> {
        let mut field = self.field.clone();
        if self.goal.is_none() {
            field.params.k_att = 0.0;
        }
        let u = field.potential_map(
            DVec2::ZERO,
            DVec2::new(FIELD_W_M, FIELD_H_M),
            HEAT_COLS,
            HEAT_ROWS,
        );
        let lo = u.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = u.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let span = (hi - lo).max(1e-12);
        u.iter()
            .map(|v| {
                let t = ((v - lo) / span).clamp(0.0, 1.0);
                let band = (t * HEAT_BANDS as f64).floor() as u64 % 2;
                (0.02 + 0.5 * t + 0.18 * band as f64) as f32
            })
            .collect()
    }

    pub(super) fn field_arrows(&self) -> Vec<(DVec2, DVec2)> {
        let mut field = self.field.clone();
        if self.goal.is_none() {
            field.params.k_att = 0.0;
        }
        let reference = (field.params.k_att + field.params.k_rep).max(1e-9);
        let mut arrows = Vec::new();
        let cols = (FIELD_W_M / ARROW_SPACING_M) as usize;
        let rows = (FIELD_H_M / ARROW_SPACING_M) as usize;
        for r in 0..rows {
            for c in 0..cols {
                let p = DVec2::new(
                    (c as f64 + 0.5) * ARROW_SPACING_M,
                    (r as f64 + 0.5) * ARROW_SPACING_M,
                );
                if field.inside_obstacle(p) {
                    continue;
                }
                let f = field.force(p);
                let len = 0.8 * ARROW_SPACING_M * (f.length() / reference).min(1.0);
                if len < 0.02 {
                    continue;
                }
                let half = f.normalize_or_zero() * 0.5 * len;
                arrows.push((p - half, p + half));
            }
        }
        arrows
    }

    /// The fingerprint of what the backdrop is drawn from: the field (its
    /// gains, laws, goal and obstacles), the view, the start and the goal.
    pub(super) fn backdrop_key(&self) -> u64 {
        let p = &self.field.params;
        let mut key = crate::BackdropKey::default()
            .num(p.k_att)
            .num(p.k_rep)
            .num(p.influence_m)
            .num(f64::from(u8::from(p.attraction == Attraction::Quadratic)))
            .num(f64::from(u8::from(p.repulsion == Repulsion::Khatib)))
            .point(self.field.goal)
            .num(self.view as f64)
            .point(self.start)
            .num(self.field.obstacles.len() as f64);
        for o in &self.field.obstacles {
            key = key.point(o.centre).num(o.radius_m);
        }
        match self.goal {
            Some(g) => key.num(1.0).point(g),
            None => key.num(0.0),
        }
        .finish()
    }
}

impl Presentation for PotentialFieldLab {
    fn view(&self) -> ViewBox {
        ViewBox {
            min: DVec2::ZERO,
            max: DVec2::new(FIELD_W_M, FIELD_H_M),
        }
    }

    /// The display list (the trait's `scene` delegates here).
    fn scene(&self, out: &mut Scene) {
        if let (Some(map), true) = (&self.basin, self.goal.is_some()) {
            out.push(Item::Raster {
                min: map.min,
                cell_m: (map.max.x - map.min.x) / map.cols as f64,
                cols: map.cols,
                rows: map.rows,
                cells: map.cells.iter().map(|c| basin_state(*c)).collect(),
                palette: BASIN_PALETTE.to_vec(),
            });
        } else if self.view == 2 {
            out.push(Item::Heatmap {
                min: DVec2::ZERO,
                cell_m: FIELD_W_M / HEAT_COLS as f64,
                cols: HEAT_COLS,
                rows: HEAT_ROWS,
                values: self.heat_values(),
                role: Role::Sample,
            });
        }
        draw_field(out, FIELD_W_M, FIELD_H_M);
        out.push(Item::ScaleBar);
        if self.view == 1 {
            out.push(Item::Arrows {
                arrows: self.field_arrows(),
                width_px: 1.2,
                role: Role::Bound,
            });
        }
        for o in &self.field.obstacles {
            out.push(Item::Circle {
                center: o.centre,
                radius_m: o.radius_m + self.field.params.influence_m,
                role: Role::Bound,
                fill: false,
                dashed: true,
            });
            out.push(Item::Circle {
                center: o.centre,
                radius_m: o.radius_m,
                role: Role::Obstacle,
                fill: true,
                dashed: false,
            });
        }
        out.push(Item::Circle {
            center: self.start,
            radius_m: 0.12,
            role: Role::Ghost,
            fill: false,
            dashed: true,
        });
        out.push(Item::Label {
            pos: self.start,
            text: "start".into(),
            role: Role::Text,
            offset_px: DVec2::new(-14.0, 22.0),
        });
        if let Some(g) = self.goal {
            let role = if self.goal_inside_obstacle() {
                Role::Warning
            } else {
                Role::Target
            };
            out.push(Item::Dot {
                center: g,
                radius_px: 7.0,
                role,
            });
            out.push(Item::Label {
                pos: g,
                text: "goal".into(),
                role: Role::Text,
                offset_px: DVec2::new(-14.0, -20.0),
            });
        }
        // The field, its quiver, the obstacles, the start and the goal stay
        // put while the robot runs (a basin map fills in as it runs: no
        // backdrop then).
        if self.basin.is_none() || self.goal.is_none() {
            out.end_backdrop(self.backdrop_key());
        }
        if self.trail.len() > 1 {
            out.push(Item::Polyline {
                points: self.trail.clone(),
                width_px: 2.5,
                role: Role::Path,
                dashed: false,
                closed: false,
            });
        }
        let pose = self.run.map_or(self.start_pose(), |r| r.pose);
        draw_robot(out, pose, 0.3);
        let p = pose.position();
        let force = self.field.force(p);
        let rep = self.field.repulsive_force(p);
        if let Some(run) = self.run {
            if force.length() > 1e-6 {
                out.push(Item::Arrow {
                    from: p,
                    to: p + force * FORCE_SCALE_M,
                    width_px: 2.5,
                    role: Role::Accent,
                });
            }
            if rep.length() > 1e-6 {
                out.push(Item::Arrow {
                    from: p,
                    to: p + rep * FORCE_SCALE_M,
                    width_px: 1.5,
                    role: Role::Warning,
                });
            }
            let label = match run.status {
                RunStatus::Trapped => Some("trapped"),
                RunStatus::LeftField => Some("off the field"),
                _ => None,
            };
            if let Some(text) = label {
                out.push(Item::Label {
                    pos: p,
                    text: text.into(),
                    role: Role::Warning,
                    offset_px: DVec2::new(12.0, 16.0),
                });
            }
        }
        // What the laws' quantities name (issue 27 §3): the pull towards
        // the goal, the clearance d from the nearest obstacle's surface, its
        // influence d₀ and its push (the arrows at the scale drawn).
        let scale = FORCE_SCALE_M;
        if self.goal.is_some() {
            out.tag_lines(&[("ka", p, p + (force - rep) * scale)]);
        }
        if let Some(o) = self.nearest_obstacle() {
            let (c, r) = (o.centre, o.radius_m.max(0.0));
            let surface = c + (p - c).normalize_or_zero() * r;
            out.tag_lines(&[("d", surface, p), ("kr", p, p + rep * scale)]);
            out.tag_circle("d0", c, r + self.field.params.influence_m);
        }
    }

    /// The live numbers beside the canvas.
    fn readouts(&self) -> Vec<Readout> {
        let run = self.run;
        let p = run.map_or(self.start, |r| r.pose.position());
        let rep = self.field.repulsive_force(p).length();
        // A run that has ended has stopped the robot.
        let speed = run.map_or(0.0, |r| {
            if r.status.is_final() {
                0.0
            } else {
                r.last_command.v_mps
            }
        });
        let reach = match &self.basin {
            Some(map) if self.goal.is_some() => {
                let share = format!("{}%", format_fixed(100.0 * map.reach_share(), 1));
                if map.is_complete() {
                    // The colours the student sees most, counted.
                    let c = map.counts();
                    format!("{share}; {} trapped, {} collided", c.trapped, c.collided)
                } else {
                    format!(
                        "{share} so far ({} of {} cells)",
                        map.cells.len() - map.counts().pending,
                        map.cells.len()
                    )
                }
            }
            _ => "--".into(),
        };
        vec![
            Readout::new(
                "speed",
                "Speed v",
                format!("{} m/s", format_fixed(speed, 3)),
            ),
            Readout::new("rep", "Repulsive force |F_rep|", format_fixed(rep, 3)),
            Readout::new(
                "att",
                "Attractive force |F_att|",
                self.goal.map_or("--".into(), |_| {
                    format_fixed(self.field.attractive_force(p).length(), 3)
                }),
            ),
            Readout::metres(
                "near_clearance",
                "Nearest clearance d",
                self.nearest_obstacle()
                    .map_or(f64::NAN, |o| o.clearance_m(p)),
            ),
            Readout::new(
                "rep_near",
                "Nearest obstacle's push",
                self.nearest_push()
                    .map_or("--".into(), |f| format_fixed(f, 3)),
            ),
            Readout::new("obstacles", "Obstacles", self.count.to_string()),
            Readout::new(
                "goal",
                "Goal distance",
                self.goal
                    .map_or("--".into(), |g| format_metres((g - p).length())),
            ),
            Readout::new(
                "status",
                "Status",
                match run.map(|r| r.status) {
                    None => "no goal",
                    Some(_) if self.goal_inside_obstacle() => "goal blocked",
                    Some(RunStatus::Running) => "running",
                    Some(RunStatus::Reached) => "reached",
                    Some(RunStatus::Trapped) => "trapped",
                    Some(RunStatus::Collided) => "collided",
                    Some(RunStatus::StartInsideObstacle) => "start blocked",
                    Some(RunStatus::TimedOut) => "timed out",
                    Some(RunStatus::LeftField) => "left the field",
                },
            ),
            Readout::new(
                "time",
                "Time",
                format!("{} s", format_fixed(run.map_or(0.0, |r| r.time_s), 2)),
            ),
            Readout::metres("path", "Path length", run.map_or(0.0, |r| r.path_length_m)),
            Readout::new(
                "clearance",
                "Closest approach to an obstacle",
                run.map_or("--".into(), |r| {
                    if r.min_clearance_m.is_finite() {
                        // A collision ends the step just inside: touched is 0.
                        format_metres(r.min_clearance_m.max(0.0))
                    } else {
                        "--".into()
                    }
                }),
            ),
            Readout::new("reach", "Starts that reach the goal", reach),
        ]
    }

    /// The status badge: the run's state only (prompts and refusals are
    /// notices).
    /// The robot, the goal, the gains and the nearest obstacle.
    fn quantities(&self) -> Vec<Quantity> {
        let p = self.robot_m();
        let goal = self.goal.unwrap_or(DVec2::NAN);
        let near = self.nearest_obstacle();
        let centre = near.map_or(DVec2::NAN, |o| o.centre);
        let params = &self.field.params;
        vec![
            Quantity::new("x", "p_x", p.x, 3, "m"),
            Quantity::new("y", "p_y", p.y, 3, "m"),
            Quantity::new("xg", "g_x", goal.x, 3, "m"),
            Quantity::new("yg", "g_y", goal.y, 3, "m"),
            Quantity::new("ka", "k_a", params.k_att, 2, ""),
            Quantity::new("cx", "c_x", centre.x, 3, "m"),
            Quantity::new("cy", "c_y", centre.y, 3, "m"),
            Quantity::new(
                "r",
                "r",
                near.map_or(f64::NAN, |o| o.radius_m.max(0.0)),
                2,
                "m",
            ),
            Quantity::new("kr", "k_r", params.k_rep, 2, ""),
            Quantity::new("d0", "d_0", params.influence_m, 2, "m"),
            Quantity::new(
                "d",
                "d",
                near.map_or(f64::NAN, |o| o.clearance_m(p)),
                3,
                "m",
            ),
        ]
    }

    fn equations(&self) -> &'static [Equation] {
        let p = self.robot_m();
        let inside = self
            .nearest_obstacle()
            .is_some_and(|o| o.clearance_m(p) < 0.0);
        // The goal on the robot: no direction to pull in (the readout's 0).
        let at_goal = self
            .goal
            .is_some_and(|g| (g - p).normalize_or_zero() == DVec2::ZERO);
        EQUATIONS[usize::from(inside) + 2 * usize::from(at_goal)]
    }

    fn status(&self) -> Status {
        let mut status = self.status_of_run();
        // A basin map still filling in is work in progress: the page keeps
        // time running for it even when the run itself has ended.
        if self.basin_computing() {
            status.phase = crate::experiment::Phase::Live;
        }
        status
    }

    fn notice(&self) -> Option<Notice> {
        self.notices.current()
    }

    /// "Robot at (…) m, goal at (…) m, 2 obstacles; reached the goal in 8.7 s."
    /// With a basin map, its cells by colour, counted.
    fn describe(&self) -> String {
        use crate::units::format_point;
        let robot = self.run.map_or(self.start, |r| r.pose.position());
        let obstacles = match self.count {
            0 => "no obstacles".to_owned(),
            1 => "1 obstacle".to_owned(),
            n => format!("{n} obstacles"),
        };
        match (self.goal, &self.basin) {
            (None, _) => format!(
                "Robot at the start {}, {obstacles}, no goal yet; {}.",
                format_point(robot),
                self.status().text
            ),
            (Some(g), basin) => {
                // The basin map's cells by colour, counted.
                let map = basin.as_ref().map_or(String::new(), |map| {
                    let c = map.counts();
                    let so_far = if map.is_complete() {
                        String::new()
                    } else {
                        format!(" so far ({} of {} cells)", map.cells.len() - c.pending, map.cells.len())
                    };
                    // The rarer two only when there are any.
                    let rare = |n: usize, what: &str| {
                        if n > 0 {
                            format!(", {n} {what}")
                        } else {
                            String::new()
                        }
                    };
                    format!(
                        " Basin map{so_far}: {} starts reach the goal (green), {} trapped (orange-red), {} collided (grey){}{}.",
                        c.reaches_goal,
                        c.trapped,
                        c.collided,
                        rare(c.left_field, "pushed off the field (light blue)"),
                        rare(c.timed_out, "timed out (pink)")
                    )
                });
                format!(
                    "Robot at {}, goal at {} ({} away), {obstacles}; {}.{map}",
                    format_point(robot),
                    format_point(g),
                    format_metres((g - robot).length()),
                    self.status().text
                )
            }
        }
    }

    fn hint(&self) -> &'static str {
        "Click or tap to set the goal; drag obstacles, the goal or the start. Add obstacle, then click to place it."
    }

    fn touch_hint(&self) -> &'static str {
        "Tap to set the goal; drag obstacles, the goal or the start. Add obstacle, then tap to place it."
    }

    /// The default field with the default goal, run to its end. Bounded:
    /// at most [`MAX_PREVIEW_STEPS`] steps, since a run that cannot move (a
    /// goal inside an obstacle) never ends by itself.
    fn preview(&mut self) {
        self.set_goal(DEFAULT_GOAL);
        for _ in 0..MAX_PREVIEW_STEPS {
            if !self.animating() {
                break;
            }
            self.step(crate::clock::Clock::DT_S);
        }
    }
}

/// Which edge of the field a point beyond it lies past.
fn edge_name(p: DVec2) -> &'static str {
    if p.x < 0.0 {
        "left"
    } else if p.x > FIELD_W_M {
        "right"
    } else if p.y < 0.0 {
        "bottom"
    } else {
        "top"
    }
}

/// Raster state of a basin class (0 = transparent).
fn basin_state(c: BasinClass) -> u8 {
    match c {
        BasinClass::Pending | BasinClass::InsideObstacle => 0,
        BasinClass::ReachesGoal => 1,
        BasinClass::Trapped => 2,
        BasinClass::Collided => 3,
        BasinClass::TimedOut => 4,
        BasinClass::LeftField => 5,
    }
}

const BASIN_PALETTE: [RasterColour; 5] = [
    RasterColour {
        role: Role::Sample,
        alpha: 0.35,
    },
    RasterColour {
        role: Role::Warning,
        alpha: 0.5,
    },
    RasterColour {
        role: Role::Obstacle,
        alpha: 0.45,
    },
    RasterColour {
        role: Role::Estimate,
        alpha: 0.4,
    },
    RasterColour {
        role: Role::Visited,
        alpha: 0.45,
    },
];
