//! Experiment 1 — forward kinematics of a planar 2-link arm.
//!
//! The sliders set `θ1`, `θ2`, `L1`, `L2`; the readouts show the tip position
//! `x = L1 cos θ1 + L2 cos(θ1+θ2)`, `y = L1 sin θ1 + L2 sin(θ1+θ2)`, the reach
//! used `|p| / (L1 + L2)` and, while the tip is dragged, the distance from the
//! pointer to the tip. Dragging the tip solves closed-form IK on the current
//! elbow branch; a pointer outside the annulus pulls the tip to the nearest
//! reachable point.

use crate::experiment::{check_param, Experiment, Handle, Input, ParamError, ParamSpec, Sanitized};
use crate::kinematics::chain::{forward, Annulus};
use crate::kinematics::two_link_ik::{solve, Elbow};
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
];

/// State of the forward-kinematics experiment.
#[derive(Clone, Debug)]
pub struct ForwardKinematics {
    theta1_deg: f64,
    theta2_deg: f64,
    l1_m: f64,
    l2_m: f64,
    /// Pointer position while dragging the tip (world, metres).
    drag_target: Option<DVec2>,
}

impl Default for ForwardKinematics {
    fn default() -> Self {
        Self {
            theta1_deg: PARAMS[0].default,
            theta2_deg: PARAMS[1].default,
            l1_m: PARAMS[2].default,
            l2_m: PARAMS[3].default,
            drag_target: None,
        }
    }
}

impl ForwardKinematics {
    fn lengths(&self) -> [f64; 2] {
        [self.l1_m, self.l2_m]
    }

    fn angles_rad(&self) -> [f64; 2] {
        [self.theta1_deg.to_radians(), self.theta2_deg.to_radians()]
    }

    /// The tip position, metres.
    #[must_use]
    pub fn tip(&self) -> DVec2 {
        forward(&self.lengths(), &self.angles_rad()).tip()
    }

    /// Moves the tip as close as possible to `target` on the current elbow branch.
    fn drag_tip_to(&mut self, target: DVec2) {
        if !target.is_finite() {
            return;
        }
        let annulus = Annulus::of_chain(&self.lengths());
        let reachable = annulus.nearest(target);
        let elbow = if self.theta2_deg < 0.0 {
            Elbow::Up
        } else {
            Elbow::Down
        };
        if let Ok(sol) = solve(self.l1_m, self.l2_m, reachable) {
            let a = sol.branch(elbow);
            self.theta1_deg = a.theta1_rad.to_degrees().clamp(-180.0, 180.0);
            self.theta2_deg = a.theta2_rad.to_degrees().clamp(-180.0, 180.0);
        }
        self.drag_target = Some(target);
    }
}

impl ForwardKinematics {
    /// Distance from the dragging pointer to the tip when the pointer is
    /// beyond reach (`None` when not dragging or when the tip reaches it).
    fn target_gap_m(&self) -> Option<f64> {
        let t = self.drag_target?;
        let gap = (t - self.tip()).length();
        (gap > 1e-6).then_some(gap)
    }
}

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "Full stretch",
        description: "Both joints straight: the tip sits on the outer circle, L₁ + L₂ from the base.",
        query: "t1=0&t2=0",
    },
    crate::experiment::Preset {
        name: "Folded onto the inner rim",
        description: "The elbow folded back (θ₂ = 180°): the tip sits |L₁ − L₂| from the base, on the edge of the hole.",
        query: "t1=30&t2=180",
    },
    crate::experiment::Preset {
        name: "Equal links close the hole",
        description: "With L₁ = L₂ a folded arm brings the tip back to the base: the workspace has no hole.",
        query: "l1=0.8&l2=0.8&t2=180",
    },
];

impl Experiment for ForwardKinematics {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

    fn id(&self) -> &'static str {
        "fk"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        match key {
            "t1" => Some(self.theta1_deg),
            "t2" => Some(self.theta2_deg),
            "l1" => Some(self.l1_m),
            "l2" => Some(self.l2_m),
            _ => None,
        }
    }

    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        match key {
            "t1" => self.theta1_deg = v,
            "t2" => self.theta2_deg = v,
            "l1" => self.l1_m = v,
            "l2" => self.l2_m = v,
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        self.drag_target = None;
        Ok(applied)
    }

    fn input(&mut self, input: Input) {
        if let Some(p) = input.drag_point(|| self.tip()) {
            self.drag_tip_to(p);
        }
        // The pointer marker shows only while a pointer drags.
        if matches!(input, Input::PointerUp(_) | Input::Nudge(_)) {
            self.drag_target = None;
        }
    }

    /// Nothing moves on its own: the arm follows the sliders and the pointer.
    fn step(&mut self, _dt_s: f64) {}

    fn handles(&self) -> Vec<Handle> {
        vec![Handle::new("tip", "End-effector", self.tip())]
    }

    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        (self.tip() - p).length() <= tolerance_m
    }

    fn animating(&self) -> bool {
        false
    }
}

/// Draws link lengths and joint angles for a question, in the units shown,
/// inside the sliders' ranges (so the student can set the arm up and read
/// the answer off the readouts).
fn draw_arm(rng: &mut Lcg64) -> (f64, f64, f64, f64) {
    let t1 = rng.int(-170, 170) as f64;
    let t2 = rng.int(-170, 170) as f64;
    let l1 = rng.int(4, 12) as f64 / 10.0;
    let l2 = rng.int(3, 12) as f64 / 10.0;
    (t1, t2, l1, l2)
}

fn arm_vars(t1: f64, t2: f64, l1: f64, l2: f64) -> Vec<(&'static str, String)> {
    vec![
        ("t1", format_number(t1, 0)),
        ("t2", format_number(t2, 0)),
        ("l1", format_number(l1, 2)),
        ("l2", format_number(l2, 2)),
    ]
}

fn fk_tip(t1: f64, t2: f64, l1: f64, l2: f64) -> DVec2 {
    forward(&[l1, l2], &[t1.to_radians(), t2.to_radians()]).tip()
}

/// `x` of the tip for drawn angles (degrees) and lengths (metres).
fn quiz_tip_x(rng: &mut Lcg64) -> Draw {
    let (t1, t2, l1, l2) = draw_arm(rng);
    Draw {
        vars: arm_vars(t1, t2, l1, l2),
        answer: fk_tip(t1, t2, l1, l2).x,
    }
}

/// `y` of the tip.
fn quiz_tip_y(rng: &mut Lcg64) -> Draw {
    let (t1, t2, l1, l2) = draw_arm(rng);
    Draw {
        vars: arm_vars(t1, t2, l1, l2),
        answer: fk_tip(t1, t2, l1, l2).y,
    }
}

/// Distance from base to tip, `√(L1² + L2² + 2 L1 L2 cos θ2)`.
fn quiz_tip_distance(rng: &mut Lcg64) -> Draw {
    let (t1, t2, l1, l2) = draw_arm(rng);
    Draw {
        vars: arm_vars(t1, t2, l1, l2),
        answer: fk_tip(t1, t2, l1, l2).length(),
    }
}

/// Reach used in percent, `100 |p| / (L1 + L2)`.
fn quiz_reach_percent(rng: &mut Lcg64) -> Draw {
    let (t1, t2, l1, l2) = draw_arm(rng);
    Draw {
        vars: arm_vars(t1, t2, l1, l2),
        answer: 100.0 * fk_tip(t1, t2, l1, l2).length() / (l1 + l2),
    }
}

/// The quiz generators of experiment 1, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "tip_x" => Some(quiz_tip_x),
        "tip_y" => Some(quiz_tip_y),
        "tip_distance" => Some(quiz_tip_distance),
        "reach_percent" => Some(quiz_reach_percent),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::{Presentation, Tone};
    use crate::scene::{Item, Role};
    use crate::testkit::{readout, scene_of};

    #[test]
    fn default_readouts_match_hand_values() {
        let fk = ForwardKinematics::default();
        // x = 1.0 cos35° + 0.7 cos95°, y = 1.0 sin35° + 0.7 sin95°
        let x = 35f64.to_radians().cos() + 0.7 * 95f64.to_radians().cos();
        let y = 35f64.to_radians().sin() + 0.7 * 95f64.to_radians().sin();
        assert!((fk.tip() - DVec2::new(x, y)).length() < 1e-12);
        assert_eq!(fk.readouts()[0].value, format!("{x:.3} m"));
    }

    #[test]
    fn dragging_the_tip_moves_it_there_keeping_the_elbow() {
        let mut fk = ForwardKinematics::default();
        let target = DVec2::new(0.5, 1.2);
        fk.input(Input::PointerDown(target));
        assert!((fk.tip() - target).length() < 1e-9);
        assert!(fk.theta2_deg >= 0.0);
        // Outside reach: the tip goes to the nearest point of the outer circle.
        fk.input(Input::PointerMove {
            pos: DVec2::new(3.0, 0.0),
            pressed: true,
        });
        assert!((fk.tip() - DVec2::new(1.7, 0.0)).length() < 1e-6);
        assert_eq!(fk.status().tone, Tone::Warning);
        fk.input(Input::PointerUp(DVec2::new(3.0, 0.0)));
        assert_eq!(fk.status().tone, Tone::Good);
    }

    /// Regression: "Target dist" showed `0 m` while the tip followed the
    /// pointer, and `--` when nothing was dragged; it now appears only while
    /// a dragging pointer is beyond reach.
    #[test]
    fn target_distance_shows_only_while_dragging_beyond_reach() {
        let has_target = |fk: &ForwardKinematics| fk.readouts().iter().any(|r| r.key == "target");
        let mut fk = ForwardKinematics::default();
        assert!(!has_target(&fk));
        fk.input(Input::PointerDown(DVec2::new(0.5, 1.2)));
        assert!(!has_target(&fk), "inside reach the tip is on the pointer");
        fk.input(Input::PointerMove {
            pos: DVec2::new(3.0, 0.0),
            pressed: true,
        });
        let gap = fk
            .readouts()
            .into_iter()
            .find(|r| r.key == "target")
            .unwrap();
        assert_eq!(gap.value, "1.300 m");
        fk.input(Input::PointerUp(DVec2::new(3.0, 0.0)));
        assert!(!has_target(&fk));
    }

    #[test]
    fn bad_values_keep_the_last_good_state() {
        let mut fk = ForwardKinematics::default();
        assert!(fk.set_param("t1", f64::NAN).is_err());
        assert!(fk.set_param("nope", 1.0).is_err());
        assert_eq!(fk.param("t1"), Some(35.0));
        assert_eq!(fk.set_param("l1", 9.0), Ok(Sanitized::Clamped(1.2)));
        fk.input(Input::PointerDown(DVec2::new(f64::NAN, 0.0)));
        assert!(fk.tip().is_finite());
    }

    /// Issue 14: a pointer 6.85·10³³ m away printed 34 digits.
    #[test]
    fn a_far_pointer_distance_reads_as_a_power_of_ten() {
        let mut fk = ForwardKinematics::default();
        fk.input(Input::PointerDown(DVec2::new(6.85e33, 0.0)));
        let gap = readout(&fk, "target");
        assert!(gap.ends_with("× 10³³ m"), "{gap}");
        assert!(gap.chars().count() <= 14, "{gap}");
        fk.input(Input::PointerDown(DVec2::new(3.0, 0.0)));
        assert_eq!(readout(&fk, "target"), "1.300 m");
        fk.input(Input::PointerDown(DVec2::new(1001.7, 0.0)));
        assert_eq!(readout(&fk, "target"), "1.0 × 10³ m");
    }

    /// Issue 15: quizzes 9–12 drew L₁ up to 2.0 m, beyond the 1.2 m slider,
    /// so "what would the readout show?" could not be set up.
    #[test]
    fn generators_draw_inside_the_sliders_ranges() {
        for name in ["tip_x", "tip_y", "tip_distance", "reach_percent"] {
            for seed in 0..500 {
                let draw = quiz_generator(name).unwrap()(&mut Lcg64::new(seed));
                let mut fk = ForwardKinematics::default();
                for (key, _) in &draw.vars {
                    let v = draw.var(key).unwrap();
                    assert_eq!(
                        fk.set_param(key, v),
                        Ok(Sanitized::InRange(v)),
                        "{name} seed {seed}: {key} = {v}"
                    );
                    let spec = PARAMS.iter().find(|s| s.key == *key).unwrap();
                    let steps = (v - spec.min) / spec.step;
                    assert!(
                        (steps - steps.round()).abs() < 1e-9,
                        "{key} = {v} is on the slider"
                    );
                }
                // The readouts then show the answer.
                let shown = match name {
                    "tip_x" => fk.tip().x,
                    "tip_y" => fk.tip().y,
                    "tip_distance" => fk.tip().length(),
                    _ => 100.0 * fk.tip().length() / (fk.l1_m + fk.l2_m),
                };
                assert!((shown - draw.answer).abs() < 1e-12);
            }
        }
    }

    /// Issue 15: the correct option was the longest in most choice
    /// questions. In the four arm experiments it is now neither the strictly
    /// longest nor the strictly shortest in more than a quarter of them.
    #[test]
    fn arm_quiz_option_lengths_do_not_give_the_answer_away() {
        for id in ["fk", "ik", "workspace", "dls"] {
            let tells = crate::experiments::find(id)
                .unwrap()
                .content()
                .unwrap()
                .length_tells();
            assert!(tells.choices >= 4, "{id}: {tells:?}");
            assert!(tells.at_most_one_in(4), "{id}: {tells:?}");
        }
    }

    /// Issue 23 §3 (numbers): the tip label "(1.4, 0.96)" mixed digit counts
    /// and had no unit. It shows the readouts' X and Y, digits and unit.
    #[test]
    fn fk_tip_label_has_one_digit_count_and_a_unit() {
        let mut fk = ForwardKinematics::default();
        fk.input(Input::PointerDown(DVec2::new(1.4, 0.96)));
        fk.input(Input::PointerUp(DVec2::new(1.4, 0.96)));
        let scene = scene_of(&fk);
        let label = scene
            .items
            .iter()
            .find_map(|item| match item {
                Item::Label {
                    text,
                    role: Role::Tip,
                    ..
                } => Some(text.clone()),
                _ => None,
            })
            .expect("the tip label");
        let r = fk.readouts();
        let number = |v: &str| v.strip_suffix(" m").unwrap().to_owned();
        assert_eq!(
            label,
            format!("({}, {}) m", number(&r[0].value), number(&r[1].value))
        );
        assert_eq!(label, "(1.400, 0.960) m");
    }
}
