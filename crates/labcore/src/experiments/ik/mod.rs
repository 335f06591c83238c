//! Experiment 2 — closed-form inverse kinematics of a 2-link arm.
//!
//! Click a target: [`two_link_ik::solve`] gives both elbow branches; the arm
//! moves to the chosen one by smooth (smoothstep-eased) interpolation in joint
//! space while the other branch is drawn as a ghost. A target outside the
//! annulus is reported (how far it is against the reach) and no solution is
//! drawn; the arm stretches (or folds) towards it, to the nearest reachable
//! point, so a move in progress never stops half-way. The θ sliders still drive
//! forward kinematics. With a wrist link `L3 > 0`, the last link is held at the
//! fixed absolute orientation `φ` and the wrist centre `p − L3 (cos φ, sin φ)`
//! is what the two links solve for.

use crate::experiment::{
    check_param, clamp_to_params, with_coordinate, Experiment, Handle, Input, ParamError,
    ParamSpec, Sanitized,
};
use crate::kinematics::chain::{forward, Annulus};
use crate::kinematics::two_link_ik::{
    lerp_angle, solve, Elbow, IkError, Singularity, TwoLinkAngles, TwoLinkSolution,
};
use crate::quiz::{Draw, Generator};
use crate::rng::Lcg64;
use crate::units::format_number;
use glam::DVec2;

mod view;

const PARAMS: &[ParamSpec] = &[
    ParamSpec::slider("t1", "θ₁", "°", -180.0, 180.0, 1.0, 35.0),
    ParamSpec::slider("t2", "θ₂", "°", -180.0, 180.0, 1.0, 60.0),
    ParamSpec::slider("l1", "L₁", "m", 0.2, 1.2, 0.05, 1.0),
    ParamSpec::slider("l2", "L₂", "m", 0.2, 1.2, 0.05, 0.7),
    ParamSpec::toggle("elbow", "Elbow", "down", "up", true),
    ParamSpec::slider("l3", "Wrist L₃", "m", 0.0, 0.6, 0.05, 0.0),
    ParamSpec::slider("phi", "Wrist φ", "°", -180.0, 180.0, 1.0, 0.0),
    ParamSpec::optional_number("tx", "Target x", "m", -VIEW_HALF_M, VIEW_HALF_M),
    ParamSpec::optional_number("ty", "Target y", "m", -VIEW_HALF_M, VIEW_HALF_M),
];

/// World half-width shown (metres): the longest arm with its wrist, plus a margin.
const VIEW_HALF_M: f64 = 3.1;
/// A reachable target closer than this to a boundary circle counts as near
/// singular in the status badge (the solver's own test is far tighter).
const NEAR_SINGULAR_M: f64 = 0.02;
/// Time for the arm to move to a new solution, seconds.
const MOVE_TIME_S: f64 = 0.8;

/// A solved target: the angles of both branches, or why there are none.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Solved {
    Reachable(TwoLinkSolution),
    /// No solution; `stretch` reaches the annulus point nearest to the target
    /// (the arm straight towards it, or folded towards a target in the hole).
    OutOfReach {
        stretch: Option<TwoLinkSolution>,
    },
}

/// State of the inverse-kinematics experiment.
#[derive(Clone, Debug)]
pub struct InverseKinematics {
    /// Current (displayed) joint angles, degrees.
    theta1_deg: f64,
    theta2_deg: f64,
    l1_m: f64,
    l2_m: f64,
    elbow: Elbow,
    l3_m: f64,
    phi_deg: f64,
    target: Option<DVec2>,
    solved: Option<Solved>,
    /// Joint-space move in progress: start angles (deg) and progress in `[0, 1]`.
    motion: Option<([f64; 2], f64)>,
}

impl Default for InverseKinematics {
    fn default() -> Self {
        Self {
            theta1_deg: PARAMS[0].default,
            theta2_deg: PARAMS[1].default,
            l1_m: PARAMS[2].default,
            l2_m: PARAMS[3].default,
            elbow: Elbow::Up,
            l3_m: PARAMS[5].default,
            phi_deg: PARAMS[6].default,
            target: None,
            solved: None,
            motion: None,
        }
    }
}

impl InverseKinematics {
    /// The wrist offset `L3 (cos φ, sin φ)` added to the 2-link tip.
    fn wrist_offset(&self) -> DVec2 {
        let phi = self.phi_deg.to_radians();
        DVec2::new(crate::math::cos(phi), crate::math::sin(phi)) * self.l3_m
    }

    /// Joint positions base..tip for the given 2-link angles (degrees), wrist included.
    fn points(&self, theta1_deg: f64, theta2_deg: f64) -> Vec<DVec2> {
        let mut points = forward(
            &[self.l1_m, self.l2_m],
            &[theta1_deg.to_radians(), theta2_deg.to_radians()],
        )
        .points;
        if self.l3_m > 0.0 {
            let wrist = points[2];
            points.push(wrist + self.wrist_offset());
        }
        points
    }

    /// The end-effector position, metres.
    #[must_use]
    pub fn tip(&self) -> DVec2 {
        *self
            .points(self.theta1_deg, self.theta2_deg)
            .last()
            .unwrap_or(&DVec2::ZERO)
    }

    fn solution(&self) -> Option<TwoLinkAngles> {
        match self.solved {
            Some(Solved::Reachable(sol)) => Some(sol.branch(self.elbow)),
            _ => None,
        }
    }

    /// Where the arm is moving: the chosen solution, or for an unreachable
    /// target the stretched pose towards it.
    fn goal(&self) -> Option<TwoLinkAngles> {
        match self.solved {
            Some(Solved::Reachable(sol)) | Some(Solved::OutOfReach { stretch: Some(sol) }) => {
                Some(sol.branch(self.elbow))
            }
            _ => None,
        }
    }

    /// Re-solves the current target and starts moving to the chosen branch
    /// (or, out of reach, to the stretched pose), from wherever the arm is —
    /// also half-way through an earlier move.
    fn resolve(&mut self) {
        let Some(target) = self.target else {
            self.solved = None;
            return;
        };
        let wrist_centre = target - self.wrist_offset();
        self.solved = Some(match solve(self.l1_m, self.l2_m, wrist_centre) {
            Ok(sol) => Solved::Reachable(sol),
            Err(IkError::Unreachable { .. } | IkError::InvalidInput) => {
                let nearest = Annulus::of_chain(&[self.l1_m, self.l2_m]).nearest(wrist_centre);
                Solved::OutOfReach {
                    stretch: solve(self.l1_m, self.l2_m, nearest).ok(),
                }
            }
        });
        self.motion = self
            .goal()
            .map(|_| ([self.theta1_deg, self.theta2_deg], 0.0));
    }

    /// Why an unreachable target is out of reach, with the numbers:
    /// `target 2.66 m away > L₁ + L₂ = 1.70 m`.
    fn out_of_reach_reason(&self) -> String {
        let (centre, annulus) = self.reach();
        let what = if self.l3_m > 0.0 {
            "wrist centre"
        } else {
            "target"
        };
        let d = self.target.map_or(f64::NAN, |t| {
            crate::math::hypot(t.x - centre.x, t.y - centre.y)
        });
        if d < annulus.inner_m {
            format!(
                "{what} {d:.2} m away < |L₁ − L₂| = {:.2} m",
                annulus.inner_m
            )
        } else {
            format!("{what} {d:.2} m away > L₁ + L₂ = {:.2} m", annulus.outer_m)
        }
    }

    /// Sets the target from the pointer or a nudge, clamped to the range of
    /// the `tx`/`ty` fields so the link reproduces it.
    fn set_target(&mut self, p: DVec2) {
        if !p.is_finite() {
            return;
        }
        self.target = Some(clamp_to_params(PARAMS, "tx", "ty", p));
        self.resolve();
    }

    /// Whether the arm has finished its move: no move in progress and the
    /// joints at the goal (the chosen solution or the stretched pose).
    fn arrived(&self) -> bool {
        self.motion.is_none()
            && self.goal().is_some_and(|g| {
                let close = |a_deg: f64, b_rad: f64| {
                    crate::kinematics::two_link_ik::wrap_pi(a_deg.to_radians() - b_rad).abs() < 1e-9
                };
                close(self.theta1_deg, g.theta1_rad) && close(self.theta2_deg, g.theta2_rad)
            })
    }

    /// True when the target lies within [`NEAR_SINGULAR_M`] of a boundary circle.
    fn near_boundary(&self) -> bool {
        let (centre, annulus) = self.reach();
        self.target.is_some_and(|t| {
            let d = (t - centre).length();
            (d - annulus.outer_m).abs() < NEAR_SINGULAR_M
                || (annulus.inner_m > 0.0 && (d - annulus.inner_m).abs() < NEAR_SINGULAR_M)
        })
    }

    /// The annulus the tip can reach with the wrist held at φ, as (centre, radii).
    fn reach(&self) -> (DVec2, Annulus) {
        (
            self.wrist_offset(),
            Annulus::of_chain(&[self.l1_m, self.l2_m]),
        )
    }
}

/// Smoothstep easing `3t² − 2t³` on `[0, 1]`.
fn ease(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "Out of reach",
        description: "A target beyond L₁ + L₂: no angles reach it; the arm points at it, fully stretched.",
        query: "tx=2.5&ty=0",
    },
    crate::experiment::Preset {
        name: "Elbow down",
        description: "The same kind of target solved on the other branch: the elbow flips, the tip still arrives.",
        query: "elbow=0&tx=0.5&ty=1",
    },
    crate::experiment::Preset {
        name: "Wrist keeps its angle",
        description: "A wrist link held at φ = 90°: the two-link arm solves for the wrist point below the target.",
        query: "l3=0.4&phi=90&tx=0.5&ty=1.2",
    },
];

impl Experiment for InverseKinematics {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

    fn id(&self) -> &'static str {
        "ik"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        Some(match key {
            "t1" => self.theta1_deg,
            "t2" => self.theta2_deg,
            "l1" => self.l1_m,
            "l2" => self.l2_m,
            "elbow" => f64::from(u8::from(self.elbow == Elbow::Up)),
            "l3" => self.l3_m,
            "phi" => self.phi_deg,
            "tx" => return self.target.map(|t| t.x),
            "ty" => return self.target.map(|t| t.y),
            _ => return None,
        })
    }

    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        match key {
            "t1" | "t2" => {
                if key == "t1" {
                    self.theta1_deg = v;
                } else {
                    self.theta2_deg = v;
                }
                // Sliders drive FK directly: stop any move in progress.
                self.motion = None;
            }
            "elbow" => {
                self.elbow = if v >= 0.5 { Elbow::Up } else { Elbow::Down };
                self.resolve();
            }
            "l1" => self.l1_m = v,
            "l2" => self.l2_m = v,
            "l3" => self.l3_m = v,
            "phi" => self.phi_deg = v,
            "tx" | "ty" => {
                self.target = Some(with_coordinate(self.target, self.tip(), key, v));
            }
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        if matches!(key, "l1" | "l2" | "l3" | "phi" | "tx" | "ty") {
            self.resolve();
        }
        Ok(applied)
    }

    fn input(&mut self, input: Input) {
        if let Some(p) = input.drag_point(|| self.target.unwrap_or_else(|| self.tip())) {
            self.set_target(p);
        }
    }

    fn step(&mut self, dt_s: f64) {
        if !crate::clock::valid_dt(dt_s) {
            return;
        }
        let Some(goal) = self.goal() else {
            self.motion = None;
            return;
        };
        let Some((start, progress)) = self.motion else {
            return;
        };
        let progress = (progress + dt_s / MOVE_TIME_S).min(1.0);
        let s = ease(progress);
        let t1 = lerp_angle(start[0].to_radians(), goal.theta1_rad, s).to_degrees();
        // The base joint may take the short way round; the elbow never passes
        // ±180° (that would fold the forearm through the upper arm).
        let t2 = start[1] + (goal.theta2_rad.to_degrees() - start[1]) * s;
        self.theta1_deg = crate::kinematics::two_link_ik::wrap_pi(t1.to_radians())
            .to_degrees()
            .clamp(-180.0, 180.0);
        self.theta2_deg = t2.clamp(-180.0, 180.0);
        self.motion = (progress < 1.0).then_some((start, progress));
    }

    fn animated(&self) -> bool {
        true
    }

    /// Back to the starting pose, then the move to the target again.
    fn reset(&mut self) {
        self.theta1_deg = PARAMS[0].default;
        self.theta2_deg = PARAMS[1].default;
        self.resolve();
    }

    /// The target (before any is set: on the tip, where a press would set it).
    fn handles(&self) -> Vec<Handle> {
        vec![Handle::arm_target(self.target, self.tip())]
    }

    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        let near = |q: DVec2| (q - p).length() <= tolerance_m;
        near(self.tip()) || self.target.is_some_and(near)
    }

    fn animating(&self) -> bool {
        self.motion.is_some()
    }
}

/// A reachable target well inside the annulus, with lengths and coordinates
/// rounded as the question shows them.
fn draw_target(rng: &mut Lcg64) -> (f64, f64, DVec2, TwoLinkSolution) {
    loop {
        // Inside the L sliders' range (0.2–1.2 m), so the arm can be set up.
        let l1 = rng.int(5, 12) as f64 / 10.0;
        let l2 = rng.int(3, 12) as f64 / 10.0;
        let angle = rng.range(-std::f64::consts::PI, std::f64::consts::PI);
        let radius = rng.range((l1 - l2).abs() + 0.1, l1 + l2 - 0.1);
        let p = DVec2::new(
            (radius * crate::math::cos(angle) * 100.0).round() / 100.0,
            (radius * crate::math::sin(angle) * 100.0).round() / 100.0,
        );
        if let Ok(sol) = solve(l1, l2, p) {
            if sol.singularity == Singularity::Regular && sol.cos_theta2.abs() < 0.98 {
                return (l1, l2, p, sol);
            }
        }
    }
}

fn target_vars(l1: f64, l2: f64, p: DVec2) -> Vec<(&'static str, String)> {
    vec![
        ("l1", format_number(l1, 2)),
        ("l2", format_number(l2, 2)),
        ("x", format_number(p.x, 2)),
        ("y", format_number(p.y, 2)),
    ]
}

/// θ2 of the elbow-down branch in degrees (0…180).
fn quiz_elbow_angle(rng: &mut Lcg64) -> Draw {
    let (l1, l2, p, sol) = draw_target(rng);
    Draw {
        vars: target_vars(l1, l2, p),
        answer: sol.elbow_down.theta2_rad.to_degrees(),
    }
}

/// θ1 of the elbow-down branch in degrees.
fn quiz_shoulder_angle(rng: &mut Lcg64) -> Draw {
    let (l1, l2, p, sol) = draw_target(rng);
    Draw {
        vars: target_vars(l1, l2, p),
        answer: sol.elbow_down.theta1_rad.to_degrees(),
    }
}

/// cos θ2 from the law of cosines.
fn quiz_cos_elbow(rng: &mut Lcg64) -> Draw {
    let (l1, l2, p, sol) = draw_target(rng);
    Draw {
        vars: target_vars(l1, l2, p),
        answer: sol.cos_theta2,
    }
}

/// The quiz generators of experiment 2, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "elbow_angle" => Some(quiz_elbow_angle),
        "shoulder_angle" => Some(quiz_shoulder_angle),
        "cos_elbow" => Some(quiz_cos_elbow),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::Presentation;
    use crate::experiment::{Status, Tone};
    use crate::scene::{Item, Role};
    use crate::testkit::{scene_of, steps};

    /// Two simulated seconds: longer than any move of the arm.
    fn settle(ik: &mut InverseKinematics) {
        steps(ik, 120);
    }

    #[test]
    fn click_solves_and_animates_to_the_target() {
        let mut ik = InverseKinematics::default();
        let target = DVec2::new(0.9, 0.8);
        ik.input(Input::PointerDown(target));
        assert!(ik.animating());
        ik.step(1.0 / 60.0);
        // Mid-way the tip is not yet there.
        assert!((ik.tip() - target).length() > 1e-3);
        settle(&mut ik);
        assert!(!ik.animating());
        assert!((ik.tip() - target).length() < 1e-9);
        assert!(ik.theta2_deg <= 0.0, "elbow up by default");
        assert_eq!(ik.status().tone, Tone::Good);
        // Toggle to elbow down: same tip, opposite bend.
        ik.set_param("elbow", 0.0).unwrap();
        settle(&mut ik);
        assert!((ik.tip() - target).length() < 1e-9);
        assert!(ik.theta2_deg >= 0.0);
    }

    #[test]
    fn out_of_reach_draws_no_solution_and_stretches_towards_the_target() {
        let mut ik = InverseKinematics::default();
        ik.input(Input::PointerDown(DVec2::new(2.9, 0.0)));
        settle(&mut ik);
        assert_eq!(
            ik.status().text,
            "out of reach: target 2.90 m away > L₁ + L₂ = 1.70 m"
        );
        assert_eq!(ik.readouts()[2].value, "--");
        assert!(
            (ik.tip() - DVec2::new(1.7, 0.0)).length() < 1e-9,
            "stretched"
        );
        let scene = scene_of(&ik);
        assert!(!scene.items.iter().any(|i| matches!(
            i,
            Item::Line {
                role: Role::Ghost,
                ..
            }
        )));
        // Inside the hole: folded towards the target.
        ik.input(Input::PointerDown(DVec2::new(0.0, 0.1)));
        settle(&mut ik);
        assert_eq!(
            ik.status().text,
            "out of reach: target 0.10 m away < |L₁ − L₂| = 0.30 m"
        );
        assert!((ik.tip() - DVec2::new(0.0, 0.3)).length() < 1e-9);
    }

    /// Regression (issue repro): click (1, 0.8), switch the elbow to down,
    /// then click (2.2, 1.5) within 0.4 s. The arm froze half-way between
    /// poses (θ₁ 22.3°, θ₂ 45.5°) with no explanation.
    #[test]
    fn unreachable_click_during_a_move_does_not_freeze_the_arm() {
        let mut ik = InverseKinematics::default();
        ik.input(Input::PointerDown(DVec2::new(1.0, 0.8)));
        settle(&mut ik);
        ik.set_param("elbow", 0.0).unwrap();
        for _ in 0..12 {
            ik.step(1.0 / 60.0); // 0.2 s: mid-move
        }
        assert!(ik.animating());
        let target = DVec2::new(2.2, 1.5);
        ik.input(Input::PointerDown(target));
        settle(&mut ik);
        assert!(!ik.animating());
        let reach = target * (1.7 / target.length());
        assert!((ik.tip() - reach).length() < 1e-9, "tip {}", ik.tip());
        assert_eq!(
            ik.status().text,
            "out of reach: target 2.66 m away > L₁ + L₂ = 1.70 m"
        );
        assert_eq!(ik.status().tone, Tone::Bad);
    }

    #[test]
    fn typed_target_coordinates_set_and_report_the_target() {
        let mut ik = InverseKinematics::default();
        assert_eq!(ik.param("tx"), None);
        ik.set_param("tx", 0.9).unwrap();
        ik.set_param("ty", 0.8).unwrap();
        assert_eq!(ik.param("tx"), Some(0.9));
        assert_eq!(ik.param("ty"), Some(0.8));
        settle(&mut ik);
        assert!((ik.tip() - DVec2::new(0.9, 0.8)).length() < 1e-9);
    }

    /// Regression: `PointerDown((3.3, 0))` wrote `tx=3.3`, beyond the ±3.1 m
    /// range of the target fields, so reloading the link clamped it with a notice.
    #[test]
    fn pointer_and_nudge_targets_stay_inside_the_field_range() {
        let mut ik = InverseKinematics::default();
        ik.input(Input::PointerDown(DVec2::new(3.3, 0.0)));
        assert_eq!(ik.param("tx"), Some(VIEW_HALF_M));
        assert_eq!(ik.param("ty"), Some(0.0));
        for _ in 0..10 {
            ik.input(Input::Nudge(DVec2::new(-0.05, -0.5)));
        }
        assert_eq!(ik.param("ty"), Some(-VIEW_HALF_M));
        assert!((ik.param("tx").unwrap() - (VIEW_HALF_M - 0.5)).abs() < 1e-12);
    }

    #[test]
    fn near_boundary_target_warns() {
        let mut ik = InverseKinematics::default();
        ik.input(Input::PointerDown(DVec2::new(1.69, 0.0)));
        assert!(ik.status().text.starts_with("near singular"));
        ik.input(Input::PointerDown(DVec2::new(1.0, 0.0)));
        assert_eq!(ik.status().text, "in reach");
    }

    #[test]
    fn boundary_target_is_flagged_singular() {
        let mut ik = InverseKinematics::default();
        ik.input(Input::PointerDown(DVec2::new(0.0, 1.7)));
        assert_eq!(ik.status().tone, Tone::Warning);
        assert!(ik.status().text.contains("singular"));
    }

    #[test]
    fn wrist_link_keeps_its_orientation_and_reaches_the_target() {
        let mut ik = InverseKinematics::default();
        ik.set_param("l3", 0.4).unwrap();
        ik.set_param("phi", 90.0).unwrap();
        let target = DVec2::new(0.8, 1.1);
        ik.input(Input::PointerDown(target));
        settle(&mut ik);
        assert!((ik.tip() - target).length() < 1e-9);
        let pts = ik.points(ik.theta1_deg, ik.theta2_deg);
        let wrist_dir = (pts[3] - pts[2]).normalize();
        assert!((wrist_dir - DVec2::Y).length() < 1e-9);
        assert_eq!(ik.readouts()[4].key, "theta3");
        assert_ne!(ik.readouts()[4].value, "--");
    }

    #[test]
    fn sliders_still_drive_forward_kinematics() {
        let mut ik = InverseKinematics::default();
        ik.input(Input::PointerDown(DVec2::new(0.9, 0.8)));
        ik.set_param("t1", 0.0).unwrap();
        ik.set_param("t2", 0.0).unwrap();
        settle(&mut ik);
        assert!((ik.tip() - DVec2::new(1.7, 0.0)).length() < 1e-12);
    }

    #[test]
    fn generators_agree_with_hand_law_of_cosines() {
        let mut rng = Lcg64::new(11);
        let d = quiz_cos_elbow(&mut rng);
        let get = |k: &str| d.var(k).unwrap();
        let (l1, l2, x, y) = (get("l1"), get("l2"), get("x"), get("y"));
        let c = (x * x + y * y - l1 * l1 - l2 * l2) / (2.0 * l1 * l2);
        assert!((d.answer - c).abs() < 1e-12);
    }

    /// Issue 13 §4: a move that has arrived is an ended run; a move in
    /// progress is live.
    #[test]
    fn an_arrived_move_is_an_ended_phase() {
        use crate::experiment::Phase;
        let mut ik = InverseKinematics::default();
        assert_eq!(ik.status().phase, Phase::Live);
        ik.input(Input::PointerDown(DVec2::new(0.9, 0.8)));
        assert_eq!(ik.status().phase, Phase::Live);
        settle(&mut ik);
        assert_eq!(ik.status(), Status::ended("in reach", Tone::Good));
        ik.input(Input::PointerDown(DVec2::new(2.9, 0.0)));
        assert_eq!(ik.status().phase, Phase::Live);
        settle(&mut ik);
        assert_eq!(ik.status().phase, Phase::Ended);
        // A slider takes the arm off its goal: live again.
        ik.set_param("t1", 0.0).unwrap();
        assert_eq!(ik.status().phase, Phase::Live);
    }

    /// Issue 15: generators draw inside the sliders' and target fields' ranges.
    #[test]
    fn generators_draw_inside_the_sliders_ranges() {
        for name in ["elbow_angle", "shoulder_angle", "cos_elbow"] {
            for seed in 0..500 {
                let draw = quiz_generator(name).unwrap()(&mut Lcg64::new(seed));
                let mut ik = InverseKinematics::default();
                for (key, field) in [("l1", "l1"), ("l2", "l2"), ("x", "tx"), ("y", "ty")] {
                    let v = draw.var(key).unwrap();
                    assert_eq!(
                        ik.set_param(field, v),
                        Ok(Sanitized::InRange(v)),
                        "{name}: {key} = {v}"
                    );
                }
                // Elbow down, as the questions ask: the readouts show the answer.
                ik.set_param("elbow", 0.0).unwrap();
                settle(&mut ik);
                let sol = ik.solution().unwrap();
                let shown = match name {
                    "elbow_angle" => sol.theta2_rad.to_degrees(),
                    "shoulder_angle" => sol.theta1_rad.to_degrees(),
                    _ => sol.theta2_rad.cos(),
                };
                assert!((shown - draw.answer).abs() < 1e-9, "{name} seed {seed}");
            }
        }
    }
}
