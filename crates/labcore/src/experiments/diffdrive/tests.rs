//! Tests of experiment 4, the Procedure steps among them.

use super::quiz::*;
use super::*;
use crate::experiment::{format_degrees, format_fixed, Phase, Tone};
use crate::rng::Lcg64;
use crate::route::{format, restore, Tab};
use crate::scene::{Item, Role, Scene};
use std::f64::consts::PI;

const DT: f64 = crate::clock::Clock::DT_S;

fn run(d: &mut DiffDrive, max_s: f64) -> f64 {
    let mut t = 0.0;
    while d.animating() && t < max_s {
        d.step(DT);
        t += DT;
    }
    t
}

fn readout(d: &DiffDrive, key: &str) -> String {
    crate::experiment::readout_value(d, key).unwrap_or_else(|| panic!("no readout {key}"))
}

fn click(d: &mut DiffDrive, p: DVec2) {
    d.input(Input::PointerDown(p));
    d.input(Input::PointerUp(p));
}

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
    // A goal exactly beside the robot: after one step of turning it is less
    // than 90° off the heading, and the robot already rolls (slowly).
    assert_eq!(d.status().text, "waypoint 1 of 1: driving");
    // Once aligned it drives at the speed limit: 1.2 · 3 m > 1.1 m/s.
    for _ in 0..90 {
        d.step(DT);
    }
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
    let t = run(&mut d, 60.0);
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
    run(&mut d, 30.0);
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
    run(&mut d, 30.0);
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
    run(&mut d, 120.0);
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
        run(d, 30.0);
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
    run(&mut d, 60.0);
    assert!(d.pose().is_finite());
    let mut scene = Scene::default();
    d.scene(&mut scene);
    assert!(scene.is_finite());
}

#[test]
fn plots_and_trail_stay_bounded() {
    let mut d = DiffDrive::default();
    d.set_param("vmax", 0.1).unwrap();
    click(&mut d, DVec2::new(7.9, 5.9));
    click(&mut d, DVec2::new(0.1, 0.1));
    for _ in 0..60 * 400 {
        d.step(DT);
    }
    assert!(d.plots[0]
        .series
        .iter()
        .all(|s| s.len() <= MAX_PLOT_SAMPLES));
    assert!(d.trail.len() <= MAX_TRAIL_POINTS);
    assert!(d.plots[0].bands.len() <= MAX_BANDS);
}

#[test]
fn waypoint_keys_parse_and_odd_keys_are_refused() {
    assert_eq!(slot_of("w1x"), Some((0, true)));
    assert_eq!(slot_of("w6y"), Some((5, false)));
    for bad in ["w7x", "w0y", "w1z", "wé", "w", "wx", "x1w", "w1xx", "w-1x"] {
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
        let mut scene = Scene::default();
        d.scene(&mut scene);
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
