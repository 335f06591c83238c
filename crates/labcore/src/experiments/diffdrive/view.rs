//! What experiment 4 shows: the field, the robot and its route, the readouts
//! and the status. Only reads the model.

use super::{DiffDrive, FIELD_H_M, FIELD_W_M, START};
use crate::experiment::{Experiment, Notice, Presentation, Readout, Status, Tone};
use crate::mobile::go_to_goal::RunStats;
use crate::scene::wheeled::{draw_field, draw_robot, BODY_RADIUS_M, NOSE_REACH};
use crate::scene::{Item, Role, Scene, ViewBox};
use crate::units::{format_degrees, format_fixed, format_metres};
use glam::DVec2;

/// Scene labels are 13 px bold: a character is at most this wide, and a
/// label this tall (CSS px).
pub(super) const LABEL_CHAR_PX: f64 = 8.0;
pub(super) const LABEL_HEIGHT_PX: f64 = 16.0;
/// A waypoint's number label sits this far from it (px), as drawn.
pub(super) const NUMBER_OFFSET_PX: DVec2 = DVec2::new(-4.0, 18.0);

/// CSS px per metre on the canvas the page told (the field fitted to it),
/// or a laptop's scale before it tells one.
pub(super) fn scale_px_per_m(d: &DiffDrive) -> f64 {
    d.viewport_px
        .map_or(90.0, |v| (v.x / FIELD_W_M).min(v.y / FIELD_H_M))
}

/// A world point on the canvas (px, y down; the field's origin at the
/// bottom left, so only differences and the field's edges matter).
fn to_px(d: &DiffDrive, p: DVec2) -> DVec2 {
    DVec2::new(p.x, FIELD_H_M - p.y) * scale_px_per_m(d)
}

/// The box (px, min and max corners) of a label of `chars` characters
/// anchored at world point `at` with `offset_px` (its left end, middle).
pub(super) fn label_box(d: &DiffDrive, at: DVec2, offset_px: DVec2, chars: usize) -> [DVec2; 2] {
    let left_mid = to_px(d, at) + offset_px;
    let half = DVec2::new(0.0, 0.5 * LABEL_HEIGHT_PX);
    [
        left_mid - half,
        left_mid + half + DVec2::new(chars as f64 * LABEL_CHAR_PX, 0.0),
    ]
}

/// Whether box `b` comes within `r` of `c` (px).
pub(super) fn box_near(b: [DVec2; 2], c: DVec2, r: f64) -> bool {
    (c.clamp(b[0], b[1]) - c).length() < r
}

/// Where a run card's label goes beside waypoint `w` (px offset): the first
/// place, nearest first, whose box stays on the field and clears the robot's
/// body and nose, every waypoint's dot and number, and the cards placed
/// before (`cards`). The robot stands on a waypoint it has just reached.
fn card_offset(d: &DiffDrive, w: DVec2, chars: usize, cards: &[[DVec2; 2]]) -> DVec2 {
    let width = chars as f64 * LABEL_CHAR_PX;
    let robot = to_px(d, d.pose().position());
    let robot_r = BODY_RADIUS_M * NOSE_REACH * scale_px_per_m(d) + 3.0;
    let field = to_px(d, DVec2::new(FIELD_W_M, 0.0));
    let clear = |offset: DVec2| {
        let b = label_box(d, w, offset, chars);
        b[0].min_element() >= 0.0
            && b[1].x <= field.x
            && b[1].y <= field.y
            && !box_near(b, robot, robot_r)
            && d.waypoints().iter().all(|p| {
                !box_near(b, to_px(d, *p), 10.0)
                    && !box_near(
                        b,
                        to_px(d, *p) + NUMBER_OFFSET_PX + DVec2::new(4.0, 0.0),
                        9.0,
                    )
            })
            && cards.iter().all(|c| {
                b[1].x <= c[0].x || b[0].x >= c[1].x || b[1].y <= c[0].y || b[0].y >= c[1].y
            })
    };
    (0..8)
        .flat_map(|ring| {
            let g = 12.0 + 10.0 * f64::from(ring);
            [
                DVec2::new(g, -g),
                DVec2::new(g, g),
                DVec2::new(-g - width, -g),
                DVec2::new(-g - width, g),
                DVec2::new(-0.5 * width, -g - 8.0),
                DVec2::new(-0.5 * width, g + 8.0),
            ]
        })
        .find(|o| clear(*o))
        .unwrap_or(DVec2::new(10.0, -10.0))
}

/// The run card shown in the readouts: the active run, else the last one
/// finished; with its 1-based waypoint number and whether it is done.
/// A run card's path length, time to goal (`done`: reached, else so far),
/// largest heading error and time at a limit, as the readouts and the
/// table of cards show them.
fn card_cells(s: &RunStats, done: bool) -> [String; 4] {
    [
        format_metres(s.path_length_m),
        match (done, s.time_to_goal_s) {
            (true, Some(t)) => format!("{} s", format_fixed(t, 2)),
            _ => format!("{} s so far", format_fixed(s.elapsed_s, 2)),
        },
        format_degrees(s.max_heading_error_rad.to_degrees()),
        format!(
            "v {}%, ω {}%",
            format_fixed(100.0 * s.v_limit_share(), 1),
            format_fixed(100.0 * s.omega_limit_share(), 1)
        ),
    ]
}

pub(super) fn shown_card(d: &DiffDrive) -> Option<(usize, RunStats, bool)> {
    let reached = d.reached();
    if !d.follower.queue.is_empty() {
        Some((reached + 1, d.follower.current, false))
    } else {
        d.follower.completed.last().map(|s| (reached, *s, true))
    }
}

use crate::live_math::{Equation, Expr, Quantity};

/// The go-to-goal law (Siegwart, Nourbakhsh & Scaramuzza, *Autonomous Mobile
/// Robots*, §3.6; Corke, *Robotics, Vision and Control*, §4.1): turn in
/// proportion to the heading error, within the limit …
const TURN: Equation = Equation {
    key: "omega",
    symbol: "ω",
    expr: Expr::Clamp(
        &Expr::Mul(&Expr::Var("kw"), &Expr::Var("e")),
        &Expr::Var("wmax"),
    ),
    readout: "omega",
    caption: "The turn rate: the heading error eθ (radians) times Kω, held within ±ω_max.",
    absent: "",
};
/// … and the unicycle: the robot moves along its heading.
const UNICYCLE: [Equation; 2] = [
    Equation {
        key: "xdot",
        symbol: "x\u{307}",
        expr: Expr::Mul(&Expr::Var("v"), &Expr::Cos(&Expr::Var("theta"))),
        readout: "xdot",
        caption: "The unicycle: the speed along the heading θ the command started from, x part …",
        absent: "",
    },
    Equation {
        key: "ydot",
        symbol: "y\u{307}",
        expr: Expr::Mul(&Expr::Var("v"), &Expr::Sin(&Expr::Var("theta"))),
        readout: "ydot",
        caption: "… and y part.",
        absent: "",
    },
];
/// Driving, and arrived (within the tolerance the command is zero).
const EQUATIONS: [&[Equation]; 2] = [
    &[
        Equation {
            key: "v",
            symbol: "v",
            expr: Expr::Min(
                &Expr::Mul(
                    &Expr::Mul(&Expr::Var("kv"), &Expr::Var("d")),
                    &Expr::Max(&Expr::Num(0.0, "0"), &Expr::CosRad(&Expr::Var("e"))),
                ),
                &Expr::Var("vmax"),
            ),
            readout: "v",
            caption: "The speed: Kv times the distance d to the goal, slowed by the cosine of the heading error (none while facing away), at most v_max.",
            absent: "",
        },
        TURN,
        UNICYCLE[0],
        UNICYCLE[1],
    ],
    &[
        Equation {
            key: "v",
            symbol: "v",
            expr: Expr::Num(0.0, "0"),
            readout: "v",
            caption: "Within the arrival radius of the goal the robot stops.",
            absent: "",
        },
        TURN,
        UNICYCLE[0],
        UNICYCLE[1],
    ],
];

impl Presentation for DiffDrive {
    fn view(&self) -> ViewBox {
        ViewBox {
            min: DVec2::ZERO,
            max: DVec2::new(FIELD_W_M, FIELD_H_M),
        }
    }

    fn viewport_px(&mut self, width_px: f64, height_px: f64) {
        let size = DVec2::new(width_px, height_px);
        if size.is_finite() && size.min_element() > 0.0 {
            self.viewport_px = Some(size);
        }
    }

    fn scene(&self, out: &mut Scene) {
        draw_field(out, FIELD_W_M, FIELD_H_M);
        // The grid lines are 1 m apart but carry no numbers: a scale bar says so.
        out.push(Item::ScaleBar);
        out.push(Item::Circle {
            center: START.position(),
            radius_m: BODY_RADIUS_M,
            role: Role::Ghost,
            fill: false,
            dashed: true,
        });
        if self.trail.len() > 1 {
            out.push(Item::Polyline {
                points: self.trail.clone(),
                width_px: 2.5,
                role: Role::Path,
                dashed: false,
                closed: false,
            });
        }
        // The route still to drive, dashed.
        if !self.follower.queue.is_empty() {
            let mut route = vec![self.pose().position()];
            route.extend(self.follower.queue.iter().copied());
            out.push(Item::Polyline {
                points: route,
                width_px: 1.5,
                role: Role::Target,
                dashed: true,
                closed: false,
            });
        }
        let reached = self.reached();
        // The run cards' label boxes placed so far (canvas px).
        let mut cards: Vec<[DVec2; 2]> = Vec::new();
        for (k, (slot, w)) in self
            .slots
            .iter()
            .enumerate()
            .filter_map(|(i, w)| w.map(|w| (i, w)))
            .enumerate()
        {
            let done = k < reached;
            let role = if done { Role::Visited } else { Role::Target };
            out.push(Item::Dot {
                center: w,
                radius_px: if k == reached { 8.0 } else { 6.0 },
                role,
            });
            out.push(Item::Label {
                pos: w,
                text: (slot + 1).to_string(),
                role: Role::Text,
                offset_px: DVec2::new(-4.0, 18.0),
            });
            if let Some(card) = self.follower.completed.get(k) {
                let text = format!(
                    "{} m · {} s",
                    format_fixed(card.path_length_m, 2),
                    format_fixed(card.time_to_goal_s.unwrap_or(card.elapsed_s), 1)
                );
                let offset_px = card_offset(self, w, text.chars().count(), &cards);
                cards.push(label_box(self, w, offset_px, text.chars().count()));
                out.push(Item::Label {
                    pos: w,
                    text,
                    role: Role::Text,
                    offset_px,
                });
            }
        }
        let pose = self.pose();
        draw_robot(out, pose, self.track_m);
        // With Kv above twice Max ω the robot can circle wide of its goal and
        // leave the field: the page marks the canvas edge toward it meanwhile.
        if pose.is_finite() {
            out.push(Item::OffView {
                at: pose.position(),
                label: "robot".into(),
                role: Role::Robot,
            });
        }
        let cmd = self.command();
        let at = pose.position();
        let speed_tip = at + pose.heading() * cmd.v_mps;
        if cmd.v_mps > 1e-3 {
            out.push(Item::Arrow {
                from: at,
                to: speed_tip,
                width_px: 2.0,
                role: Role::Accent,
            });
        }
        // What the control law's quantities name (issue 27 §3): the heading
        // θ from the x axis, the heading error eθ from the heading towards
        // the goal, the distance d to it and the speed v along the heading.
        out.tag_arc("theta", at, 0.45, 0.0, cmd.heading_rad);
        out.tag_arc(
            "e",
            at,
            0.7,
            cmd.heading_rad,
            cmd.heading_rad + cmd.heading_error_rad,
        );
        let goal = self.follower.goal().unwrap_or(at);
        out.tag_lines(&[("d", at, goal), ("v", at, speed_tip)]);
    }

    /// The gains and limits, and what the last command was computed from.
    fn quantities(&self) -> Vec<Quantity> {
        let cmd = self.command();
        let c = &self.follower.last_controller;
        vec![
            Quantity::new("kw", "K_ω", c.k_omega_per_s, 2, "s⁻¹"),
            Quantity::new("e", "e_θ", cmd.heading_error_rad, 3, "rad"),
            Quantity::new("wmax", "ω_max", c.max_omega_radps, 2, "rad/s"),
            Quantity::new("kv", "K_v", c.k_v_per_s, 2, "s⁻¹"),
            Quantity::new("d", "d", cmd.distance_m, 3, "m"),
            Quantity::new("vmax", "v_max", c.max_v_mps, 2, "m/s"),
            Quantity::new("v", "v", cmd.v_mps, 3, "m/s"),
            Quantity::new("theta", "θ", cmd.heading_rad.to_degrees(), 1, "°"),
        ]
    }

    fn equations(&self) -> &'static [Equation] {
        EQUATIONS[usize::from(self.command().arrived)]
    }

    fn readouts(&self) -> Vec<Readout> {
        let cmd = self.command();
        let (vl, vr) = self.wheels();
        let pose = self.pose();
        let speed = |v: f64| format!("{} m/s", format_fixed(v, 3));
        let goal = self.follower.goal().map_or("--".into(), |g| {
            format_metres((g - pose.position()).length())
        });
        let mut out = vec![
            Readout::new("v", "Speed v", speed(cmd.v_mps)),
            Readout::new(
                "xdot",
                "Velocity ẋ",
                speed(cmd.v_mps * crate::math::cos(cmd.heading_rad)),
            ),
            Readout::new(
                "ydot",
                "Velocity ẏ",
                speed(cmd.v_mps * crate::math::sin(cmd.heading_rad)),
            ),
            Readout::new(
                "omega",
                "Turn rate ω",
                format!("{} rad/s", format_fixed(cmd.omega_radps, 3)),
            ),
            Readout::degrees("heading", "Heading θ", pose.theta_rad.to_degrees()),
            Readout::new("goal", "Goal distance", goal),
            Readout::new("vl", "Left wheel vL", speed(vl)),
            Readout::new("vr", "Right wheel vR", speed(vr)),
            Readout::new(
                "waypoints",
                "Waypoints reached",
                format!("{} of {}", self.reached(), self.waypoints().len()),
            ),
        ];
        let card = shown_card(self);
        let [path, time, max_error, at_limit] = card.as_ref().map_or_else(
            || ["--".into(), "--".into(), "--".into(), "--".into()],
            |(_, s, done)| card_cells(s, *done),
        );
        out.extend([
            Readout::new(
                "card",
                "Run card",
                card.as_ref().map_or("--".into(), |(n, _, done)| {
                    format!(
                        "waypoint {n}{}",
                        if *done { " (reached)" } else { " (driving)" }
                    )
                }),
            ),
            Readout::new("path", "Path length", path),
            Readout::new("time", "Time to goal", time),
            Readout::new("max_error", "Largest heading error", max_error),
            Readout::new("at_limit", "Time at a limit", at_limit),
        ]);
        out
    }

    fn status(&self) -> Status {
        let total = self.waypoints().len();
        if total == 0 {
            return Status::new("idle: click to drop a goal", Tone::Neutral);
        }
        let reached = self.reached();
        let Some(goal) = self.follower.goal() else {
            // Every waypoint of the route reached: the run is over until the
            // student adds one (or replays it).
            return Status::ended(
                if total == 1 {
                    "reached the goal".to_owned()
                } else {
                    format!("reached all {total} waypoints")
                },
                Tone::Good,
            );
        };
        // The command the readouts show, once the robot has been stepped toward
        // this goal; before that, what the controller commands from here. No
        // forward speed while the goal is more than 90° off the heading.
        let cmd = if self.follower.current.elapsed_s > 0.0 {
            self.command()
        } else {
            self.follower.controller.command(self.pose(), goal)
        };
        let doing = if cmd.v_mps < 1e-3 && cmd.heading_error_rad.abs() > 0.1 {
            "turning on the spot"
        } else {
            "driving"
        };
        Status::new(
            format!("waypoint {} of {total}: {doing}", reached + 1),
            Tone::Neutral,
        )
    }

    fn notice(&self) -> Option<Notice> {
        self.notices.current()
    }

    /// "Robot at (2.10, 3.40) m heading 45.0°, 2 of 3 waypoints reached; waypoint 3 of 3: driving."
    fn describe(&self) -> String {
        let pose = self.pose();
        let heading = crate::kinematics::two_link_ik::wrap_pi(pose.theta_rad).to_degrees();
        let robot = format!(
            "Robot at {} heading {}",
            crate::units::format_point(pose.position()),
            format_degrees(heading)
        );
        let total = self.waypoints().len();
        if total == 0 {
            return format!("{robot}, no waypoints yet; {}.", self.status().text);
        }
        let next = self.follower.goal().map_or(String::new(), |g| {
            format!(", next at {}", crate::units::format_point(g))
        });
        format!(
            "{robot}, {} of {total} waypoint{} reached{next}; {}.",
            self.reached(),
            if total == 1 { "" } else { "s" },
            self.status().text
        )
    }

    /// One run card per waypoint reached, kept for the whole run (issue 53
    /// §5): the Procedure compares them waypoint by waypoint, and the
    /// readouts' card follows only the current leg.
    fn tables(&self) -> Vec<crate::Table> {
        let cards = &self.follower.completed;
        if cards.is_empty() {
            return Vec::new();
        }
        let mut t = crate::Table::new(
            "cards",
            "Run cards of the waypoints reached",
            &[
                "waypoint",
                "path",
                "time",
                "largest heading error",
                "time at a limit",
            ],
        );
        for (i, s) in cards.iter().enumerate() {
            let mut row = vec![(i + 1).to_string()];
            row.extend(card_cells(s, true));
            t.push_row(row);
        }
        vec![t]
    }

    fn hint(&self) -> &'static str {
        "Click or tap to drop a goal; click again to queue more waypoints. Drag a waypoint to move it, tap it to remove it."
    }

    fn touch_hint(&self) -> &'static str {
        "Tap to drop a goal; tap again to queue more waypoints. Drag a waypoint to move it, tap it to remove it."
    }

    fn preview(&mut self) {
        for p in [
            DVec2::new(3.2, 4.6),
            DVec2::new(6.4, 4.2),
            DVec2::new(6.8, 1.2),
        ] {
            self.add_waypoint(p);
        }
        for _ in 0..60 * 14 {
            self.step(crate::clock::Clock::DT_S);
        }
    }
}
