//! Tests of experiment 4 (its Procedure is played by `tests/procedures/`).

use super::quiz::*;
use super::*;
use crate::experiment::{Lab, Phase, Presentation, Status, Tone};
use crate::mobile::field::MAX_TRAIL_POINTS;
use crate::plot::BOUNDED_SAMPLES;
use crate::rng::Lcg64;
use crate::route::{format, restore, Tab};
use crate::scene::wheeled::{BODY_RADIUS_M, NOSE_REACH};
use crate::scene::{Item, Role};
use crate::units::{format_degrees, format_fixed};
use std::f64::consts::PI;

use crate::testkit::{click, readout, run_while_animating, scene_of, steps, DT_S as DT};

#[test]
fn idle_robot_waits_in_the_middle_facing_right() {
    let mut d = DiffDrive::default();
    assert!(!d.animating());
    d.step(DT);
    assert_eq!(d.pose(), START);
    assert_eq!(d.status().text, "idle: click to drop a goal");
    assert_eq!(readout(&d, "goal"), "--");
    assert_eq!(readout(&d, "card"), "--");
}

/// The first step toward a goal straight up from the start, by hand:
/// eθ = π/2, ω = clamp(3.5·π/2, ±1.4) = 1.4 rad/s, v = Kv·d·max(0, cos eθ) ≈ 0,
/// so vL = −ωb/2 = −0.21 m/s and vR = +0.21 m/s (b = 0.3 m).
#[test]
fn readouts_and_wheel_speeds_match_a_hand_computation() {
    let mut d = DiffDrive::default();
    click(&mut d, START.position() + DVec2::new(0.0, 3.0));
    d.step(DT);
    assert_eq!(readout(&d, "omega"), "1.400 rad/s");
    assert_eq!(readout(&d, "v"), "0.000 m/s");
    assert_eq!(readout(&d, "vl"), "-0.210 m/s");
    assert_eq!(readout(&d, "vr"), "0.210 m/s");
    assert_eq!(
        readout(&d, "heading"),
        format_degrees((1.4 * DT).to_degrees())
    );
    assert_eq!(readout(&d, "goal"), "3.000 m");
    // The badge agrees with the readouts of the step just taken.
    assert_eq!(d.status().text, "waypoint 1 of 1: turning on the spot");
    // Once aligned it drives at the speed limit: 1.2 · 3 m > 1.1 m/s.
    steps(&mut d, 90);
    assert_eq!(readout(&d, "v"), "1.100 m/s");
    let (vl, vr) = d.wheels();
    let c = d.command();
    assert!((vr - vl - c.omega_radps * 0.3).abs() < 1e-12);
    assert!((0.5 * (vl + vr) - c.v_mps).abs() < 1e-12);
}

#[test]
fn reaches_each_waypoint_in_order_with_a_run_card_each() {
    let mut d = DiffDrive::default();
    let goals = [
        DVec2::new(7.4, 3.0),
        DVec2::new(7.4, 5.5),
        DVec2::new(4.4, 5.9),
    ];
    for g in goals {
        click(&mut d, g);
    }
    assert_eq!(d.waypoints(), goals.to_vec());
    assert_eq!(d.param("w3x"), Some(4.4));
    let t = run_while_animating(&mut d, 60.0);
    assert!(!d.animating(), "arrived after {t} s");
    assert_eq!(d.reached(), 3);
    assert!((d.pose().position() - goals[2]).length() <= TOLERANCE_M);
    assert_eq!(d.status().text, "reached all 3 waypoints");
    // Card 1: straight ahead along +x, 3.4 m: path ≈ 3.4 m, no heading error.
    let c1 = d.run_cards()[0];
    assert!((c1.path_length_m - 3.4).abs() < 0.06, "{c1:?}");
    assert!(c1.max_heading_error_rad < 1e-9);
    assert!(c1.v_limit_share() > 0.3 && c1.omega_limit_share() == 0.0);
    // Card 2: a quarter turn left first.
    let c2 = d.run_cards()[1];
    assert!((c2.max_heading_error_rad - PI / 2.0).abs() < 0.05, "{c2:?}");
    assert!(c2.omega_limit_share() > 0.0);
    // Times add up to the run's time.
    let sum: f64 = d
        .run_cards()
        .iter()
        .map(|c| c.time_to_goal_s.unwrap())
        .sum();
    assert!((sum - d.time_s).abs() < 4.0 * DT, "{sum} vs {}", d.time_s);
    assert_eq!(readout(&d, "card"), "waypoint 3 (reached)");
    assert_eq!(
        readout(&d, "time"),
        format!(
            "{} s",
            format_fixed(d.run_cards()[2].time_to_goal_s.unwrap(), 2)
        )
    );
    assert!(readout(&d, "at_limit").starts_with("v "));
    // The plot shows v, ω, vL, vR with a marker per arrival.
    let plot = &d.plots()[0];
    assert_eq!(plot.series.len(), 4);
    assert!(plot.sample_count() > 100);
    assert_eq!(plot.markers.len(), 3);
    assert!(!plot.bands.is_empty(), "time at a limit is shaded");
    assert!(plot
        .to_csv()
        .starts_with("Time (s),v (m/s),ω (rad/s),vL (m/s),vR (m/s)"));
}

#[test]
fn tapping_a_waypoint_removes_it_and_dragging_moves_it() {
    let mut d = DiffDrive::default();
    for p in [
        DVec2::new(3.0, 3.0),
        DVec2::new(5.0, 3.0),
        DVec2::new(7.0, 3.0),
    ] {
        click(&mut d, p);
    }
    // Tap on waypoint 2: removed, 3 becomes 2.
    click(&mut d, DVec2::new(5.05, 3.0));
    assert_eq!(
        d.waypoints(),
        vec![DVec2::new(3.0, 3.0), DVec2::new(7.0, 3.0)]
    );
    assert_eq!(d.param("w2x"), Some(7.0));
    assert_eq!(d.param("w3x"), None);
    // Drag waypoint 1 to (2, 5).
    d.input(Input::PointerDown(DVec2::new(3.0, 3.1)));
    d.input(Input::PointerMove {
        pos: DVec2::new(2.5, 4.0),
        pressed: true,
    });
    d.input(Input::PointerMove {
        pos: DVec2::new(2.0, 5.0),
        pressed: true,
    });
    d.input(Input::PointerUp(DVec2::new(2.0, 5.0)));
    assert_eq!(d.waypoints()[0], DVec2::new(2.0, 5.0));
    assert_eq!(d.follower.queue.len(), 2);
    assert_eq!(d.follower.goal(), Some(DVec2::new(2.0, 5.0)));
    // The arrow keys move the waypoint last grabbed.
    d.input(Input::Nudge(DVec2::new(0.16, 0.0)));
    assert_eq!(d.waypoints()[0], DVec2::new(2.16, 5.0));
    d.action("clear").unwrap();
    assert!(d.waypoints().is_empty() && !d.animating());
}

/// On a touch screen a swipe that starts off every waypoint scrolls the
/// page; the page still reports it as a press and a move, so a press
/// only queues a waypoint when it is released where it started.
#[test]
fn a_swipe_off_the_waypoints_queues_nothing() {
    let mut d = DiffDrive::default();
    d.input(Input::PointerDown(DVec2::new(4.0, 1.0)));
    d.input(Input::PointerMove {
        pos: DVec2::new(4.0, 1.6),
        pressed: true,
    });
    d.input(Input::PointerUp(DVec2::new(4.0, 1.6)));
    assert!(d.waypoints().is_empty());
    // A click with a little jitter still counts as a tap.
    d.input(Input::PointerDown(DVec2::new(4.0, 1.0)));
    d.input(Input::PointerMove {
        pos: DVec2::new(4.02, 1.01),
        pressed: true,
    });
    d.input(Input::PointerUp(DVec2::new(4.02, 1.01)));
    assert_eq!(d.waypoints(), vec![DVec2::new(4.0, 1.0)]);
}

#[test]
fn removing_a_reached_waypoint_drops_its_card() {
    let mut d = DiffDrive::default();
    click(&mut d, DVec2::new(2.0, 0.6));
    click(&mut d, DVec2::new(3.0, 0.6));
    run_while_animating(&mut d, 30.0);
    assert_eq!(d.reached(), 2);
    let second = d.run_cards()[1];
    click(&mut d, DVec2::new(2.0, 0.6));
    assert_eq!(d.reached(), 1);
    assert_eq!(d.run_cards()[0], second);
    assert!(!d.animating());
    // A new click continues from where the robot stands.
    click(&mut d, DVec2::new(3.0, 2.0));
    assert!(d.animating());
    assert_eq!(readout(&d, "card"), "waypoint 2 (driving)");
    run_while_animating(&mut d, 30.0);
    assert_eq!(d.reached(), 2);
}

/// Issue 13 §4: "all 6 waypoints are queued" is a notice beside the status,
/// never the status itself, and it goes once a waypoint is reached (today it
/// stayed after all six were reached).
#[test]
fn a_full_queue_posts_a_notice_that_goes_when_a_waypoint_is_reached() {
    let mut d = DiffDrive::default();
    for i in 0..MAX_WAYPOINTS {
        click(&mut d, DVec2::new(1.0 + i as f64, 2.0 + (i % 2) as f64));
    }
    assert_eq!(d.notice(), None);
    click(&mut d, DVec2::new(7.5, 5.5));
    assert_eq!(d.waypoints().len(), MAX_WAYPOINTS);
    let notice = d.notice().expect("a refused click says why");
    assert_eq!(notice.tone, Tone::Warning);
    assert!(notice.text.contains("all 6 waypoints"), "{notice:?}");
    // The status keeps telling the run's state.
    assert!(d.status().text.starts_with("waypoint 1 of 6: "));
    assert_eq!(d.status().phase, Phase::Live);
    // Once the first is reached the notice no longer applies, and it goes.
    while d.reached() == 0 {
        d.step(DT);
    }
    assert_eq!(d.notice(), None);
    // The last one reached ends the run, with no warning left over.
    run_while_animating(&mut d, 120.0);
    assert_eq!(d.reached(), MAX_WAYPOINTS);
    assert_eq!(
        d.status(),
        Status::ended("reached all 6 waypoints", Tone::Good)
    );
    assert_eq!(d.notice(), None);
    // With every slot used, a reached waypoint makes room for a new one.
    click(&mut d, DVec2::new(7.5, 5.5));
    assert_eq!(d.waypoints().len(), MAX_WAYPOINTS);
    assert_eq!(d.waypoints()[MAX_WAYPOINTS - 1], DVec2::new(7.5, 5.5));
    assert_eq!(d.reached(), MAX_WAYPOINTS - 1);
    assert_eq!(d.notice(), None);
    assert_eq!(d.status().phase, Phase::Live);
    // Removing a waypoint also withdraws the notice.
    let mut e = DiffDrive::default();
    for i in 0..=MAX_WAYPOINTS {
        click(&mut e, DVec2::new(1.0 + i as f64, 1.0));
    }
    assert!(e.notice().is_some());
    click(&mut e, DVec2::new(1.0, 1.0));
    assert_eq!(e.notice(), None);
}

#[test]
fn waypoints_round_trip_through_the_link() {
    let mut d = DiffDrive::default();
    click(&mut d, DVec2::new(3.333_333, 2.0));
    click(&mut d, DVec2::new(9.0, -1.0));
    d.set_param("kw", 5.0).unwrap();
    d.set_param("integ", 1.0).unwrap();
    let link = format(&d, Tab::Simulation);
    assert_eq!(
        link,
        "#/diffdrive/simulation?kw=5&kv=1.2&vmax=1.1&wmax=1.4&track=0.3&integ=1&w1x=3.33&w1y=2&w2x=8&w2y=0"
    );
    let (mut fresh, notices) = restore(&link, DiffDrive::default());
    assert!(notices.is_empty(), "{notices:?}");
    assert_eq!(fresh.waypoints(), d.waypoints());
    assert_eq!(format(&fresh, Tab::Simulation), link);
    // The loaded route drives the same run as the clicked one, after a reset.
    d.reset();
    for _ in 0..300 {
        d.step(DT);
        fresh.step(DT);
    }
    assert_eq!(d.pose(), fresh.pose());
}

#[test]
fn typed_waypoint_fields_create_and_move_waypoints() {
    let mut d = DiffDrive::default();
    d.set_param("w2x", 4.0).unwrap();
    assert_eq!(d.waypoints(), vec![DVec2::new(4.0, START.y_m)]);
    d.set_param("w2y", 5.0).unwrap();
    assert_eq!(d.follower.goal(), Some(DVec2::new(4.0, 5.0)));
    assert_eq!(d.set_param("w1y", 99.0), Ok(Sanitized::Clamped(FIELD_H_M)));
    assert_eq!(d.waypoints()[0], DVec2::new(START.x_m, FIELD_H_M));
    assert!(d.set_param("w7x", 1.0).is_err());
    assert!(d.set_param("w1x", f64::NAN).is_err());
}

#[test]
fn rk4_and_euler_both_arrive_and_differ_slightly() {
    let mut a = DiffDrive::default();
    let mut b = DiffDrive::default();
    b.set_param("integ", 1.0).unwrap();
    for d in [&mut a, &mut b] {
        click(d, DVec2::new(5.0, 5.0));
        run_while_animating(d, 30.0);
        assert_eq!(d.reached(), 1);
    }
    let (ca, cb) = (a.run_cards()[0], b.run_cards()[0]);
    assert!((ca.path_length_m - cb.path_length_m).abs() < 0.05);
}

#[test]
fn hostile_values_keep_the_state_finite() {
    let mut d = DiffDrive::default();
    click(&mut d, DVec2::new(f64::NAN, 1.0));
    click(&mut d, DVec2::new(1e300, -1e300));
    assert_eq!(d.waypoints(), vec![DVec2::new(FIELD_W_M, 0.0)]);
    d.input(Input::Nudge(DVec2::new(f64::INFINITY, 0.0)));
    d.set_param("kw", 1e9).unwrap();
    d.set_param("wmax", 1e9).unwrap();
    run_while_animating(&mut d, 60.0);
    assert!(d.pose().is_finite());
    let scene = scene_of(&d);
    assert!(scene.is_finite());
}

#[test]
fn plots_and_trail_stay_bounded() {
    let mut d = DiffDrive::default();
    d.set_param("vmax", 0.1).unwrap();
    click(&mut d, DVec2::new(7.9, 5.9));
    click(&mut d, DVec2::new(0.1, 0.1));
    steps(&mut d, 60 * 400);
    assert!(d.plots[0].series.iter().all(|s| s.len() <= BOUNDED_SAMPLES));
    assert!(d.trail.len() <= MAX_TRAIL_POINTS);
    assert!(d.plots[0].bands.len() <= MAX_BANDS);
}

#[test]
fn waypoint_keys_parse_and_odd_keys_are_refused() {
    assert_eq!(slot_of("w1x"), Some((0, true)));
    assert_eq!(slot_of("w6y"), Some((5, false)));
    for bad in [
        "w7x", "w0y", "w1z", "wé", "w", "wx", "x1w", "w1xx", "w-1x", "w+1x",
    ] {
        assert_eq!(slot_of(bad), None, "{bad}");
    }
    let d = DiffDrive::default();
    assert_eq!(d.param("wé"), None);
}

#[test]
fn generators_agree_with_hand_formulas() {
    let mut rng = Lcg64::new(3);
    for _ in 0..50 {
        let w = quiz_right_wheel(&mut rng);
        let expected = w.var("v").unwrap() + w.var("w").unwrap() * w.var("b").unwrap() / 2.0;
        assert!((w.answer - expected).abs() < 1e-12);
        let h = quiz_heading_error(&mut rng);
        assert!(h.answer.abs() <= 180.0);
        let raw =
            h.var("y").unwrap().atan2(h.var("x").unwrap()).to_degrees() - h.var("theta").unwrap();
        let wrapped = (raw + 540.0).rem_euclid(360.0) - 180.0;
        assert!((h.answer - wrapped).abs() < 1e-9, "{h:?}");
        let f = quiz_forward_speed(&mut rng);
        let v = (f.var("kv").unwrap()
            * f.var("d").unwrap()
            * f.var("e").unwrap().to_radians().cos().max(0.0))
        .min(f.var("vmax").unwrap());
        assert!((f.answer - v).abs() < 1e-12);
    }
}

/// Issue 13 §3: the twelve waypoint fields sit under one collapsed
/// "Waypoints" heading; the gains and limits stay among the main controls.
#[test]
fn the_waypoint_fields_are_grouped_under_waypoints() {
    let d = DiffDrive::default();
    let grouped: Vec<&str> = d
        .params()
        .iter()
        .filter(|s| s.group == Some("Waypoints"))
        .map(|s| s.key)
        .collect();
    assert_eq!(grouped.len(), 2 * MAX_WAYPOINTS);
    assert!(grouped.iter().all(|k| slot_of(k).is_some()));
    for s in d.params().iter().filter(|s| slot_of(s.key).is_none()) {
        assert_eq!(s.group, None, "{}", s.key);
    }
}

/// Issue 13 §3: the grid carries no numbers, so the scene asks for a metre
/// scale bar; and a robot that circles off the field (Kv above twice Max ω)
/// is marked on the canvas edge.
#[test]
fn the_scene_has_a_scale_bar_and_marks_the_robot_when_it_leaves_the_field() {
    let off_view = |d: &DiffDrive| {
        let scene = scene_of(d);
        assert!(scene.items.iter().any(|i| matches!(i, Item::ScaleBar)));
        scene.items.iter().find_map(|i| match i {
            Item::OffView { at, label, role } => Some((*at, label.clone(), *role)),
            _ => None,
        })
    };
    let mut d = DiffDrive::default();
    assert_eq!(
        off_view(&d),
        Some((START.position(), "robot".to_owned(), Role::Robot))
    );
    d.set_param("kv", 3.0).unwrap();
    d.set_param("vmax", 2.0).unwrap();
    d.set_param("wmax", 0.2).unwrap();
    click(&mut d, DVec2::new(1.0, 3.0));
    let view = d.view();
    let inside = |p: DVec2| p.cmpge(view.min).all() && p.cmple(view.max).all();
    let mut left_at = None;
    for k in 0..60 * 20 {
        d.step(DT);
        if !inside(d.pose().position()) {
            left_at = Some(k);
            break;
        }
    }
    assert!(left_at.is_some(), "the robot stays in the field");
    let (at, _, _) = off_view(&d).expect("an edge mark for the robot");
    assert_eq!(at, d.pose().position());
    assert!(!inside(at));
}

// ---- Set-ups the tests below share. ----

/// Step 1's goal: near the left edge, behind the robot.
const STEP_1_GOAL: DVec2 = DVec2::new(0.8, 4.5);

/// Issue 23 §4: Theory ("Gains, limits and what you see") says a coarse
/// update would make the heading overshoot and the robot wobble, and that
/// it cannot happen here: Kω·Δt ≤ 0.17, so at the largest Kω and turn
/// limit the heading error shrinks without changing sign.
#[test]
fn diffdrive_theory_says_no_wobble_in_this_lab_and_k_omega_dt_is_at_most_0_17() {
    let content =
        crate::content::Content::parse(include_str!("../../../../../assets/diffdrive.json"))
            .unwrap();
    let paragraph = content
        .theory
        .iter()
        .find_map(|b| match b {
            crate::content::Block::Paragraph(p) if p.contains("wobble") => Some(p.clone()),
            _ => None,
        })
        .unwrap();
    assert!(paragraph.contains("not in this lab"), "{paragraph}");
    assert!(paragraph.contains("<mn>0.17</mn>"), "{paragraph}");
    let kw = crate::experiment::find_spec(PARAMS, "kw").unwrap().max;
    assert!(kw * DT <= 0.17, "Kω·Δt = {}", kw * DT);
    let mut d = DiffDrive::default();
    let wmax = crate::experiment::find_spec(PARAMS, "wmax").unwrap().max;
    d.set_param("kw", kw).unwrap();
    d.set_param("wmax", wmax).unwrap();
    // Goals behind, to the side and ahead: no sign change on any leg.
    for goal in [STEP_1_GOAL, DVec2::new(7.5, 5.5), DVec2::new(6.0, 0.5)] {
        click(&mut d, goal);
        let mut first: Option<f64> = None;
        while d.animating() {
            d.step(DT);
            let e = d.command().heading_error_rad;
            if e.abs() > 1e-9 {
                let sign = *first.get_or_insert(e.signum());
                assert_eq!(e.signum(), sign, "the heading error changed sign: {e}");
            }
        }
        assert_eq!(d.status().phase, Phase::Ended);
    }
}

/// Issue 15: every generated question can be set up on the Simulation tab —
/// speeds, turn rates, gains and the track inside their sliders' ranges, and
/// the goal offset one the field allows from the start pose.
#[test]
fn generators_draw_inside_the_slider_ranges() {
    let spec = |key: &str| *crate::experiment::find_spec(PARAMS, key).unwrap();
    let within = |key: &str, v: f64| {
        let s = spec(key);
        assert!((s.min..=s.max).contains(&v), "{key} = {v}");
    };
    let mut rng = Lcg64::new(15);
    for _ in 0..2000 {
        let w = quiz_right_wheel(&mut rng);
        assert!((0.0..=spec("vmax").max).contains(&w.var("v").unwrap()));
        assert!(w.var("w").unwrap().abs() <= spec("wmax").max);
        within("track", w.var("b").unwrap());
        let h = quiz_heading_error(&mut rng);
        let goal = START.position() + DVec2::new(h.var("x").unwrap(), h.var("y").unwrap());
        assert!(
            goal.cmpge(DVec2::ZERO).all() && goal.cmple(DVec2::new(FIELD_W_M, FIELD_H_M)).all(),
            "{h:?}"
        );
        let f = quiz_forward_speed(&mut rng);
        within("kv", f.var("kv").unwrap());
        within("vmax", f.var("vmax").unwrap());
        assert!(f.var("d").unwrap() <= DVec2::new(FIELD_W_M, FIELD_H_M).length());
    }
}

/// Issue 15: the correct option is the strictly longest in at most a
/// quarter of the choice questions, so its length gives nothing away.
#[test]
fn quiz_option_lengths_do_not_give_the_answer_away() {
    let tells = crate::experiments::find("diffdrive")
        .unwrap()
        .content()
        .unwrap()
        .length_tells();
    assert!(tells.choices >= 6, "{tells:?}");
    assert!(4 * tells.longest <= tells.choices, "{tells:?}");
}

/// A student's session that touches every way of making waypoints: clicks
/// (also outside the field), taps that remove, drags, arrow-key nudges,
/// typed fields with many decimals or out of range, gains, the two buttons
/// and time.
fn waypoint_session(d: &mut DiffDrive, seed: u64) {
    let mut rng = Lcg64::new(seed);
    for _ in 0..40 {
        let any_point = |rng: &mut Lcg64| DVec2::new(rng.range(-1.0, 9.0), rng.range(-1.0, 7.0));
        let existing = |d: &DiffDrive, rng: &mut Lcg64| {
            let w = d.waypoints();
            (!w.is_empty()).then(|| w[rng.int(0, w.len() as i64 - 1) as usize])
        };
        match rng.int(0, 9) {
            0 | 1 => click(d, any_point(&mut rng)),
            2 => {
                if let Some(w) = existing(d, &mut rng) {
                    click(d, w);
                }
            }
            3 => {
                let from = existing(d, &mut rng).unwrap_or_else(|| any_point(&mut rng));
                let to = any_point(&mut rng);
                d.input(Input::PointerDown(from));
                d.input(Input::PointerMove {
                    pos: (from + to) * 0.5,
                    pressed: true,
                });
                d.input(Input::PointerMove {
                    pos: to,
                    pressed: true,
                });
                d.input(Input::PointerUp(to));
            }
            4 => d.input(Input::Nudge(DVec2::new(
                rng.range(-0.3, 0.3),
                rng.range(-0.3, 0.3),
            ))),
            5 => {
                let slot = rng.int(1, MAX_WAYPOINTS as i64);
                let axis = if rng.int(0, 1) == 0 { 'x' } else { 'y' };
                let _ = d.set_param(&format!("w{slot}{axis}"), rng.range(-1.0, 9.0));
            }
            6 => {
                let spec = PARAMS[rng.int(0, 5) as usize];
                let _ = d.set_param(spec.key, rng.range(spec.min, spec.max));
            }
            7 => {
                let key = if rng.int(0, 3) == 0 { "clear" } else { "reset" };
                d.action(key).unwrap();
            }
            _ => {
                steps(d, usize::try_from(rng.int(0, 300)).unwrap());
            }
        }
    }
}

/// Issue 13 §2: every route a student can make is in the link — format,
/// parse and apply to a fresh experiment reproduce every waypoint and gain
/// exactly, with no notice, and the same run.
#[test]
fn links_reproduce_every_route_a_student_can_make() {
    for seed in 0..150 {
        let mut d = DiffDrive::default();
        waypoint_session(&mut d, seed);
        let link = format(&d, Tab::Simulation);
        let (mut opened, notices) = restore(&link, DiffDrive::default());
        assert!(notices.is_empty(), "seed {seed}: {link}: {notices:?}");
        assert_eq!(format(&opened, Tab::Simulation), link, "seed {seed}");
        assert_eq!(opened.slots, d.slots, "seed {seed}: {link}");
        for spec in PARAMS {
            assert!(d.param(spec.key) == opened.param(spec.key), "{}", spec.key);
        }
        d.reset();
        for _ in 0..120 {
            d.step(DT);
            opened.step(DT);
        }
        assert_eq!(d.pose(), opened.pose(), "seed {seed}");
    }
}

/// Issue 13 §2's repro: the default link pasted into a tab where three
/// waypoints were clicked gives no waypoints ("0 of 0"), as a fresh page.
#[test]
fn the_default_link_in_a_used_tab_gives_no_waypoints() {
    use crate::route::{open_in_tab, parse, Page};
    let default_link = format(&DiffDrive::default(), Tab::Simulation);
    let Page::Experiment { params, .. } = parse(&default_link, &["diffdrive"]).page else {
        panic!("{default_link}");
    };
    let make = || -> Box<dyn Lab> { Box::new(DiffDrive::default()) };
    let mut tab = make();
    for p in [
        DVec2::new(1.0, 1.0),
        DVec2::new(2.0, 5.0),
        DVec2::new(7.0, 2.0),
    ] {
        tab.input(Input::PointerDown(p));
        tab.input(Input::PointerUp(p));
    }
    assert_eq!(readout(tab.as_ref(), "waypoints"), "0 of 3");
    assert!(open_in_tab(&mut tab, make, &params).is_empty());
    assert_eq!(readout(tab.as_ref(), "waypoints"), "0 of 0");
    assert_eq!(format(tab.as_ref(), Tab::Simulation), default_link);
}

/// Issue 23 §3: "Waypoints (12)" counted the input fields. The heading
/// counts the waypoints set: none at first, two after two clicks.
#[test]
fn diffdrive_waypoints_heading_counts_waypoints_not_fields() {
    use crate::experiment::group_count;
    let mut d = DiffDrive::default();
    let count = |d: &DiffDrive| group_count(d.params(), "Waypoints", &|k| d.param(k));
    assert_eq!(count(&d), 0);
    for p in [DVec2::new(2.0, 2.0), DVec2::new(6.0, 4.0)] {
        d.input(Input::PointerDown(p));
        d.input(Input::PointerUp(p));
    }
    assert_eq!(d.waypoints().len(), 2);
    assert_eq!(count(&d), 2);
    assert_eq!(
        d.params()
            .iter()
            .filter(|s| s.group == Some("Waypoints"))
            .count(),
        12
    );
}

/// Issue 23 §3: on a phone the badge said "click to drop a goal"; in a
/// finger's words it says tap.
#[test]
fn diffdrive_the_idle_badge_in_touch_words_says_tap_not_click() {
    let d = DiffDrive::default();
    assert_eq!(d.status().text, "idle: click to drop a goal");
    assert_eq!(
        crate::experiment::for_touch(&d.status().text),
        "idle: tap to drop a goal"
    );
}

/// Issue 23 §3: the "3.90 m · 6.3 s" label covered the robot and waypoint 1.
/// On a laptop's and a phone's canvas, along routes with waypoints near the
/// field's edges and close together, every run card's label box (13 px bold,
/// at most 7 px a character here, 14 px tall) clears the robot's body and
/// nose, every waypoint's dot and number, and the other cards.
#[test]
fn diffdrive_run_card_label_covers_neither_the_robot_nor_a_waypoint() {
    let routes: &[&[(f64, f64)]] = &[
        &[(0.3, 3.0)],
        &[(0.3, 3.0), (1.2, 3.4)],
        &[(7.6, 5.6), (6.8, 5.0), (7.5, 0.4)],
        &[(2.0, 1.0), (3.0, 1.5), (2.2, 2.2), (1.0, 1.6)],
    ];
    for &(w, h) in &[(760.0, 570.0), (358.0, 268.5)] {
        for route in routes {
            let mut d = DiffDrive::default();
            d.viewport_px(w, h);
            for &(x, y) in *route {
                let p = DVec2::new(x, y);
                d.input(Input::PointerDown(p));
                d.input(Input::PointerUp(p));
            }
            let scale = (w / FIELD_W_M).min(h / FIELD_H_M);
            let px = |p: DVec2| DVec2::new(p.x, FIELD_H_M - p.y) * scale;
            for frame in 0..(60 * 40) {
                d.step(1.0 / 60.0);
                if frame % 15 != 0 {
                    continue;
                }
                let scene = scene_of(&d);
                let boxes: Vec<(String, DVec2, DVec2)> = scene
                    .items
                    .iter()
                    .filter_map(|item| match item {
                        Item::Label {
                            pos,
                            text,
                            offset_px,
                            ..
                        } if text.contains(" m · ") => {
                            let left = px(*pos) + *offset_px;
                            let n = text.chars().count() as f64;
                            Some((
                                text.clone(),
                                left - DVec2::new(0.0, 7.0),
                                left + DVec2::new(7.0 * n, 7.0),
                            ))
                        }
                        _ => None,
                    })
                    .collect();
                let near =
                    |lo: DVec2, hi: DVec2, c: DVec2, r: f64| (c.clamp(lo, hi) - c).length() < r;
                let robot = px(d.pose().position());
                for (text, lo, hi) in &boxes {
                    let at = format!("{w}×{h} px, route {route:?}, t {:.2} s: “{text}”", d.time_s);
                    assert!(
                        !near(*lo, *hi, robot, BODY_RADIUS_M * NOSE_REACH * scale),
                        "{at} covers the robot"
                    );
                    for p in d.waypoints() {
                        assert!(!near(*lo, *hi, px(p), 6.0), "{at} covers waypoint {p}");
                        assert!(
                            !near(*lo, *hi, px(p) + DVec2::new(0.0, 18.0), 5.0),
                            "{at} covers the number of {p}"
                        );
                    }
                    for (other, olo, ohi) in &boxes {
                        let apart =
                            hi.x <= olo.x || lo.x >= ohi.x || hi.y <= olo.y || lo.y >= ohi.y;
                        assert!(other == text || apart, "{at} covers “{other}”");
                    }
                }
            }
            assert_eq!(d.reached(), route.len(), "{route:?} driven");
        }
    }
}

/// Issue 53 §5: each waypoint reached keeps its run card in a table while
/// the next leg drives, so the Procedure's per-waypoint comparison reads
/// them side by side without scrubbing back to each arrival.
#[test]
fn every_waypoint_reached_keeps_its_run_card_in_a_table() {
    let mut d = DiffDrive::default();
    assert!(
        d.tables().is_empty(),
        "no card before a waypoint is reached"
    );
    for g in [
        DVec2::new(7.4, 3.0),
        DVec2::new(7.4, 5.5),
        DVec2::new(4.4, 5.9),
    ] {
        click(&mut d, g);
    }
    for _ in 0..6000 {
        if d.reached() == 2 {
            break;
        }
        d.step(DT);
    }
    steps(&mut d, 5);
    assert_eq!(d.reached(), 2);
    assert_eq!(readout(&d, "card"), "waypoint 3 (driving)");
    let tables = d.tables();
    let cards = &tables[0];
    assert_eq!(cards.key, "cards");
    assert_eq!(cards.rows.len(), 2, "{:?}", cards.rows);
    // Card 1 is the straight 3.4 m leg along +x: no heading error.
    let first = &cards.rows[0];
    assert_eq!(first[0], "1");
    let path_m = crate::testkit::leading_number(&first[1]).unwrap();
    assert!((path_m - 3.4).abs() < 0.06, "{first:?}");
    assert_eq!(first[3], "0.0°");
    // Card 2 opens with a quarter turn: a heading error of about 90°.
    let second = &cards.rows[1];
    assert_eq!(second[0], "2");
    let err_deg = crate::testkit::leading_number(&second[3]).unwrap();
    assert!((err_deg - 90.0).abs() < 3.0, "{second:?}");
    // The cells are the cards' own numbers.
    for (row, card) in cards.rows.iter().zip(d.run_cards()) {
        assert_eq!(row[1], crate::units::format_metres(card.path_length_m));
        assert_eq!(
            row[2],
            format!("{} s", format_fixed(card.time_to_goal_s.unwrap(), 2))
        );
    }
    // Reaching the last one adds its card; the first two stay.
    run_while_animating(&mut d, 60.0);
    let rows = &d.tables()[0].rows;
    assert_eq!(rows.len(), 3);
    assert_eq!(&rows[..2], &cards.rows[..]);
}
