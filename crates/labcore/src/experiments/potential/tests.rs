//! Tests of experiment 5.

use super::quiz::{quiz_net_force, quiz_potential, quiz_repulsion};
use super::view::{HEAT_COLS, HEAT_ROWS};
use super::*;
use crate::experiment::{Notice, Phase, Presentation, Readout, Status};
use crate::mobile::potential_field::run_to_end;
use crate::mobile::potential_field::BasinClass;
use crate::rng::Lcg64;
use crate::route::{format, restore, Tab};
use crate::scene::{Item, Role, Scene};
use crate::units::{format_fixed, format_metres};

use crate::testkit::{
    self, click, notice_text, readout, run_until_phase, run_while_animating, scene_of, steps,
    DT_S as DT,
};

/// Two obstacles 0.4 m apart (surface to surface) straddling the
/// start–goal line: the classic symmetric trap.
fn trap() -> PotentialFieldLab {
    let mut e = PotentialFieldLab::default();
    for (k, v) in [
        ("rad", 0.4),
        ("o1x", 4.0),
        ("o1y", 3.6),
        ("o2x", 4.0),
        ("o2y", 2.4),
        ("gx", 7.4),
        ("gy", 3.0),
    ] {
        e.set_param(k, v).unwrap();
    }
    e
}

#[test]
fn starts_with_two_obstacles_and_waits_for_a_goal() {
    let mut e = PotentialFieldLab::default();
    assert_eq!(e.obstacles().len(), 2);
    assert_eq!(readout(&e, "obstacles"), "2");
    assert_eq!(e.status().text, "click to set a goal");
    assert!(!e.animating());
    e.step(DT);
    assert!(e.run().is_none());
    assert_eq!(e.param("o3x"), None);
    assert_eq!(e.param("gx"), None);
}

#[test]
fn reaches_a_goal_behind_an_obstacle_and_bows_around_it() {
    let mut e = PotentialFieldLab::default();
    e.set_param("nobs", 1.0).unwrap();
    e.set_param("o1y", 3.1).unwrap();
    click(&mut e, DVec2::new(7.2, 3.0));
    assert_eq!(e.param("gx"), Some(7.2));
    assert!(e.animating());
    let t = run_while_animating(&mut e, 60.0);
    let r = *e.run().unwrap();
    assert_eq!(r.status, RunStatus::Reached, "after {t} s: {r:?}");
    assert!(r.min_clearance_m > 0.05, "{r:?}");
    assert!(r.path_length_m > 6.7, "bowed around: {}", r.path_length_m);
    // The trail left the straight line y = 3 to pass the obstacle.
    let widest = e
        .trail
        .iter()
        .map(|p| (p.y - 3.0).abs())
        .fold(0.0, f64::max);
    assert!(widest > 0.4, "{widest}");
    assert!(e.status().text.starts_with("reached the goal in"));
    assert_eq!(readout(&e, "status"), "reached");
    assert!(!e.animating());
    let plot = &e.plots()[0];
    assert!(plot.series[0].len() > 50);
    assert_eq!(plot.markers.last().unwrap().label, "reached");
    assert!(
        plot.series[1].y.iter().any(|f| *f > 0.1),
        "felt the repulsion"
    );
}

#[test]
fn the_symmetric_trap_is_reported_in_bounded_time() {
    let mut e = trap();
    let t = run_while_animating(&mut e, 200.0);
    let r = *e.run().unwrap();
    assert_eq!(r.status, RunStatus::Trapped, "{r:?}");
    assert!(t < 20.0, "took {t} s");
    assert!(!e.animating());
    assert_eq!(e.status().tone, Tone::Bad);
    assert!(e.status().text.starts_with("trapped in a local minimum"));
    assert_eq!(readout(&e, "status"), "trapped");
    // A stop is a stop: further steps change nothing.
    let pose = r.pose;
    e.step(DT);
    assert_eq!(e.run().unwrap().pose, pose);
    let scene = scene_of(&e);
    assert!(scene
        .items
        .iter()
        .any(|i| matches!(i, Item::Label { text, .. } if text == "trapped")));
}

#[test]
fn a_goal_inside_an_obstacle_is_refused_clearly_and_kept() {
    let mut e = PotentialFieldLab::default();
    let centre = e.obstacles()[0].centre;
    click(&mut e, DVec2::new(7.0, 1.0));
    e.step(DT);
    // Dragging the goal into obstacle 1 (pressing on the goal grabs it).
    e.input(Input::PointerDown(DVec2::new(7.0, 1.0)));
    e.input(Input::PointerMove {
        pos: centre,
        pressed: true,
    });
    e.input(Input::PointerUp(centre));
    assert_eq!(e.param("gx"), Some(centre.x));
    assert_eq!(e.status().tone, Tone::Bad);
    assert!(e.status().text.contains("goal is inside an obstacle"));
    assert!(!e.animating());
    let before = *e.run().unwrap();
    e.step(DT);
    assert_eq!(*e.run().unwrap(), before, "no motion while blocked");
    // Moving the obstacle away frees the goal again.
    e.set_param("o1x", 1.5).unwrap();
    assert!(e.animating());
    assert_eq!(readout(&e, "status"), "running");
}

#[test]
fn an_obstacle_on_the_robot_start_says_so() {
    let mut e = PotentialFieldLab::default();
    click(&mut e, DVec2::new(7.0, 3.0));
    e.set_param("o2x", 0.6).unwrap();
    e.set_param("o2y", 3.0).unwrap();
    assert_eq!(e.run().unwrap().status, RunStatus::StartInsideObstacle);
    assert!(e.status().text.contains("start is inside an obstacle"));
    assert!(!e.animating());
    let scene = scene_of(&e);
    assert!(scene.is_finite());
}

#[test]
fn add_drag_and_remove_obstacles() {
    let mut e = PotentialFieldLab::default();
    e.action("add").unwrap();
    assert_eq!(notice_text(&e), "click where the new obstacle goes");
    assert_eq!(
        e.status().text,
        "click to set a goal",
        "the prompt is a notice"
    );
    // A swipe places nothing and keeps the mode; a tap places the obstacle.
    e.input(Input::PointerDown(DVec2::new(6.0, 1.0)));
    e.input(Input::PointerMove {
        pos: DVec2::new(6.0, 2.0),
        pressed: true,
    });
    e.input(Input::PointerUp(DVec2::new(6.0, 2.0)));
    assert_eq!(e.obstacles().len(), 2);
    assert_eq!(e.mode, Some(Mode::Add), "a swipe keeps the mode");
    click(&mut e, DVec2::new(6.5, 1.25));
    assert_eq!(e.obstacles().len(), 3);
    assert_eq!(e.param("o3x"), Some(6.5));
    assert_eq!(e.param("nobs"), Some(3.0));
    assert!(e.goal.is_none(), "placing an obstacle sets no goal");
    // A swipe off every handle sets no goal either.
    e.input(Input::PointerDown(DVec2::new(7.0, 5.0)));
    e.input(Input::PointerMove {
        pos: DVec2::new(7.0, 4.0),
        pressed: true,
    });
    e.input(Input::PointerUp(DVec2::new(7.0, 4.0)));
    assert!(e.goal.is_none());
    // Drag obstacle 1 by its edge.
    let c = e.obstacles()[0].centre;
    e.input(Input::PointerDown(c + DVec2::new(0.3, 0.0)));
    e.input(Input::PointerMove {
        pos: DVec2::new(2.0, 5.0),
        pressed: true,
    });
    e.input(Input::PointerUp(DVec2::new(2.0, 5.0)));
    assert_eq!(e.obstacles()[0].centre, DVec2::new(2.0, 5.0));
    // Arrow keys move the obstacle last grabbed.
    e.input(Input::Nudge(DVec2::new(0.0, -0.5)));
    assert_eq!(e.obstacles()[0].centre, DVec2::new(2.0, 4.5));
    // Remove obstacle 2: obstacle 3 becomes 2.
    e.action("remove").unwrap();
    click(&mut e, DEFAULT_OBSTACLES[1]);
    assert_eq!(e.obstacles().len(), 2);
    assert_eq!(e.param("o2x"), Some(6.5));
    assert_eq!(e.param("o3x"), None);
    assert_eq!(readout(&e, "obstacles"), "2");
    // A removal click on empty ground removes nothing and says so.
    e.action("remove").unwrap();
    click(&mut e, DVec2::new(7.5, 5.5));
    assert_eq!(e.obstacles().len(), 2);
    assert!(notice_text(&e).contains("nothing removed"));
    assert_eq!(e.status().text, "click to set a goal");
    assert!(e.goal.is_none());
}

#[test]
fn obstacles_and_goal_round_trip_through_the_link() {
    let mut e = PotentialFieldLab::default();
    e.action("remove").unwrap();
    click(&mut e, DEFAULT_OBSTACLES[0]);
    e.action("add").unwrap();
    click(&mut e, DVec2::new(1.234_567, 4.0));
    click(&mut e, DVec2::new(7.0, 2.5));
    e.set_param("view", 2.0).unwrap();
    let link = format(&e, Tab::Simulation);
    assert_eq!(
        link,
        "#/potential/simulation?ka=1&kr=1.6&d0=1&rad=0.5&view=2&nobs=2&sx=0.6&sy=3&gx=7&gy=2.5&o1x=5.2&o1y=2.2&o2x=1.23&o2y=4"
    );
    let (fresh, notices) = restore(&link, PotentialFieldLab::default());
    assert!(notices.is_empty(), "{notices:?}");
    assert_eq!(fresh.obstacles(), e.obstacles());
    assert_eq!(format(&fresh, Tab::Simulation), link);
    // Every obstacle removed is a state too: `nobs=0`.
    for _ in 0..2 {
        e.action("remove").unwrap();
        let c = e.obstacles()[0].centre;
        click(&mut e, c);
    }
    let link = format(&e, Tab::Simulation);
    assert!(link.contains("nobs=0") && !link.contains("o1x"), "{link}");
    let (mut fresh, notices) = restore(&link, PotentialFieldLab::default());
    assert!(notices.is_empty(), "{notices:?}");
    assert!(fresh.obstacles().is_empty());
    // The same link drives the same run.
    run_while_animating(&mut e, 30.0);
    run_while_animating(&mut fresh, 30.0);
    assert_eq!(e.run(), fresh.run());
}

/// The basin map fills in over many steps at a bounded number of cells
/// per step, completes, reports its share, and agrees with single runs
/// from sampled cells.
#[test]
fn basin_map_progresses_completes_and_agrees_with_runs() {
    let mut e = trap();
    e.action("basin").unwrap();
    assert!(e.animating());
    let total = BASIN_COLS * BASIN_ROWS;
    let mut steps = 0;
    let mut last_pending = total;
    while e.basin_computing() {
        e.step(DT);
        steps += 1;
        let pending = e.basin().unwrap().counts().pending;
        assert!(last_pending - pending <= BASIN_CELLS_PER_STEP);
        last_pending = pending;
        if steps == 10 {
            assert!(
                readout(&e, "reach").contains("so far"),
                "{}",
                readout(&e, "reach")
            );
        }
    }
    assert_eq!(steps, total.div_ceil(BASIN_CELLS_PER_STEP));
    let map = e.basin().unwrap();
    let c = map.counts();
    assert_eq!(c.pending, 0);
    assert!(
        c.reaches_goal > 0 && c.trapped > 0 && c.inside_obstacle > 0,
        "{c:?}"
    );
    let share = map.reach_share();
    assert!(share > 0.3 && share < 1.0, "{share}");
    // The share, then the two failures a student sees most, counted.
    assert_eq!(
        readout(&e, "reach"),
        format!(
            "{}%; {} trapped, {} collided",
            format_fixed(100.0 * share, 1),
            c.trapped,
            c.collided
        )
    );
    let mut rng = Lcg64::new(12);
    for _ in 0..25 {
        let (col, row) = (
            rng.int(0, BASIN_COLS as i64 - 1) as usize,
            rng.int(0, BASIN_ROWS as i64 - 1) as usize,
        );
        let start = map.start_pose(e.field(), col, row);
        let direct: BasinClass = run_to_end(e.field(), &basin_config(), start).status.into();
        assert_eq!(map.get(col, row), Some(direct), "cell ({col}, {row})");
    }
    // The start cell in front of the gap is trapped on the map, as the live run is.
    let col = (e.start.x / 0.2) as usize;
    let row = (e.start.y / 0.2) as usize;
    assert_eq!(map.get(col, row), Some(BasinClass::Trapped));
    run_while_animating(&mut e, 60.0);
    assert_eq!(e.run().unwrap().status, RunStatus::Trapped);
    let scene = scene_of(&e);
    assert!(scene.items.iter().any(|i| matches!(i, Item::Raster { .. })));
    // Changing the field recomputes the map; hiding it stops the work.
    e.set_param("kr", 0.5).unwrap();
    assert!(e.basin_computing());
    e.action("clear").unwrap();
    assert!(e.basin().is_none());
}

/// One step of the basin map classifies at most `BASIN_CELLS_PER_STEP`
/// cells, each a run of at most `BASIN_MAX_TIME_S / BASIN_DT_S` = 1200 field
/// steps (plus the two of slack `run_to_end` allows): the field steps the
/// model counts in each step stay within that bound, on any machine, and the
/// trap map's long runs come near it. (Milliseconds are printed, never
/// asserted: `cargo xtask bench --browser` reports frames.)
#[test]
fn basin_step_cost_is_bounded() {
    let mut e = trap();
    assert_eq!(e.basin_steps_last_step(), 0);
    e.action("basin").unwrap();
    let per_run = (BASIN_MAX_TIME_S / BASIN_DT_S).ceil() as u64 + 2;
    let bound = BASIN_CELLS_PER_STEP as u64 * per_run;
    let mut counts = Vec::new();
    let mut times = Vec::new();
    let mut scene = Scene::default();
    while e.basin_computing() {
        let t0 = std::time::Instant::now();
        e.step(DT);
        scene.clear();
        e.scene(&mut scene);
        times.push(t0.elapsed().as_secs_f64() * 1e3);
        counts.push(e.basin_steps_last_step());
    }
    let frames = (BASIN_COLS * BASIN_ROWS).div_ceil(BASIN_CELLS_PER_STEP);
    assert_eq!(counts.len(), frames);
    let worst_count = *counts.iter().max().unwrap();
    assert!(worst_count <= bound, "{worst_count} field steps > {bound}");
    // The counter counts: trapped runs last their 5 s window at least, so
    // some step does far more than one field step per cell.
    assert!(
        worst_count > 100 * BASIN_CELLS_PER_STEP as u64,
        "{worst_count}"
    );
    // Every step while computing classifies cells, each with a run.
    assert!(counts.iter().all(|&c| c > 0), "{counts:?}");
    // Once the map is complete a step does no basin work.
    e.step(DT);
    assert_eq!(e.basin_steps_last_step(), 0);
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    let worst = times[times.len() - 1];
    eprintln!(
        "basin step + scene: {worst_count} field steps at most (bound {bound}); \
         median {median:.3} ms, worst {worst:.3} ms"
    );
}

#[test]
fn heat_map_and_arrows_follow_the_field_view() {
    let mut e = PotentialFieldLab::default();
    click(&mut e, DVec2::new(7.2, 3.0));
    let count = |e: &PotentialFieldLab, f: fn(&Item) -> bool| {
        let scene = scene_of(e);
        scene.items.iter().filter(|i| f(i)).count()
    };
    let heat = |i: &Item| matches!(i, Item::Heatmap { .. });
    let arrows = |i: &Item| matches!(i, Item::Arrows { .. });
    assert_eq!((count(&e, heat), count(&e, arrows)), (0, 1));
    e.set_param("view", 2.0).unwrap();
    assert_eq!((count(&e, heat), count(&e, arrows)), (1, 0));
    e.set_param("view", 0.0).unwrap();
    assert_eq!((count(&e, heat), count(&e, arrows)), (0, 0));
    let values = e.heat_values();
    assert_eq!(values.len(), HEAT_COLS * HEAT_ROWS);
    assert!(values.iter().all(|v| *v > 0.0 && *v <= 1.0));
}

#[test]
fn readouts_match_the_field_at_the_robot() {
    let mut e = PotentialFieldLab::default();
    // Start 0.25 m from obstacle 1's surface, straight below it.
    e.set_param("sx", 3.0).unwrap();
    e.set_param("sy", 2.65).unwrap();
    click(&mut e, DVec2::new(7.0, 1.0));
    // |F_rep| = 1.6 · (1 − 0.25)/1 = 1.2 from obstacle 1; obstacle 2 at
    // (5.2, 2.2) is 1.75 m from the surface: outside d₀.
    assert_eq!(readout(&e, "rep"), "1.200");
    assert_eq!(
        readout(&e, "goal"),
        format_metres(DVec2::new(4.0, -1.65).length())
    );
    assert_eq!(readout(&e, "speed"), "0.000 m/s");
    e.step(DT);
    assert_ne!(readout(&e, "speed"), "0.000 m/s");
}

#[test]
fn obstacle_keys_parse_and_odd_keys_are_refused() {
    assert_eq!(slot_of("o1x"), Some((0, true)));
    assert_eq!(slot_of("o6y"), Some((5, false)));
    for bad in ["o7x", "o0y", "o1z", "oé", "o", "ox", "obs", "o1xx"] {
        assert_eq!(slot_of(bad), None, "{bad}");
    }
    assert_eq!(PotentialFieldLab::default().param("o0x"), None);
}

#[test]
fn generators_agree_with_hand_formulas() {
    let mut rng = Lcg64::new(5);
    for _ in 0..50 {
        let r = quiz_repulsion(&mut rng);
        let (kr, d0, d) = (
            r.var("kr").unwrap(),
            r.var("d0").unwrap(),
            r.var("d").unwrap(),
        );
        assert!(d < d0);
        assert!((r.answer - kr * (d0 - d) / d0).abs() < 1e-12);
        let n = quiz_net_force(&mut rng);
        let v = |k: &str| n.var(k).unwrap();
        let d = v("s") - v("r");
        let push = if d < v("d0") {
            v("kr") * (v("d0") - d) / v("d0")
        } else {
            0.0
        };
        assert!((n.answer - (v("ka") - push)).abs() < 1e-9, "{n:?}");
        let u = quiz_potential(&mut rng);
        let v = |k: &str| u.var(k).unwrap();
        let expected = v("ka") * v("g") + v("kr") * (v("d0") - v("d")).powi(2) / (2.0 * v("d0"));
        assert!((u.answer - expected).abs() < 1e-9, "{u:?}");
    }
}

/// Everything observable: the link, the status, the notice, the readouts
/// and the display list.
fn observe(e: &PotentialFieldLab) -> (String, Status, Option<Notice>, Vec<Readout>, Scene) {
    let scene = scene_of(e);
    (
        format(e, Tab::Simulation),
        e.status(),
        e.notice(),
        e.readouts(),
        scene,
    )
}

/// Issue 13 §1: the repro link (`ka=0.1&kr=5&d0=3&rad=1.2…`) drives the
/// robot away from the goal at full speed and off the field's left edge. It
/// was reported "trapped in a local minimum 7.947 m from the goal" at
/// 1.1 m/s after 5 s without progress; now leaving the field is its own
/// ended state, and "trapped" needs the trap's evidence.
#[test]
fn extreme_gains_push_the_robot_off_the_field_and_that_is_not_a_trap() {
    let link = "#/potential/simulation?ka=0.1&kr=5&d0=3&rad=1.2&view=2&nobs=2&sx=0.6&sy=3&o1x=3&o1y=3.4&o2x=5.2&o2y=2.2&gx=7.5&gy=3";
    let (mut e, notices) = restore(link, PotentialFieldLab::default());
    assert!(notices.is_empty(), "{notices:?}");
    run_while_animating(&mut e, 200.0);
    let r = *e.run().unwrap();
    assert_eq!(r.status, RunStatus::LeftField, "{r:?}");
    assert!(r.pose.x_m < 0.0, "off the left edge: {r:?}");
    let status = e.status();
    assert!(
        status
            .text
            .starts_with("pushed off the left edge of the field"),
        "{status:?}"
    );
    assert!(!status.text.contains("trapped"));
    assert_eq!(status.phase, Phase::Ended);
    assert_eq!(readout(&e, "status"), "left the field");
    assert_eq!(
        readout(&e, "speed"),
        "0.000 m/s",
        "an ended run has stopped"
    );
    assert!(!e.animating());
}

/// Issue 13 §4: a status is `ended` exactly when the goal is reached, a trap
/// is confirmed (or the run collided, left the field or timed out); running,
/// waiting for a goal and a blocked goal are live.
#[test]
fn status_ends_when_the_goal_is_reached_or_a_trap_is_confirmed() {
    let mut e = PotentialFieldLab::default();
    assert_eq!(e.status().phase, Phase::Live);
    click(&mut e, DVec2::new(7.2, 1.0));
    assert_eq!(e.status().phase, Phase::Live);
    run_while_animating(&mut e, 60.0);
    assert_eq!(e.run().unwrap().status, RunStatus::Reached);
    assert_eq!(e.status().phase, Phase::Ended);
    let mut t = trap();
    steps(&mut t, 60);
    assert_eq!(t.status().phase, Phase::Live, "{:?}", t.status());
    run_while_animating(&mut t, 60.0);
    assert_eq!(t.run().unwrap().status, RunStatus::Trapped);
    let r = *t.run().unwrap();
    assert!(r.time_s - r.anchor_s >= TrapDetection::default().window_s);
    assert_eq!(t.status().phase, Phase::Ended);
    assert_eq!(t.status().tone, Tone::Bad);
    // A goal inside an obstacle is waiting for the student, not over.
    t.set_param("gx", 4.0).unwrap();
    t.set_param("gy", 3.6).unwrap();
    assert!(t.status().text.contains("goal is inside an obstacle"));
    assert_eq!(t.status().phase, Phase::Live);
}

/// Issue 13 §3: the field's grid carries no numbers, so the scene asks for a
/// metre scale bar.
#[test]
fn the_scene_has_a_scale_bar() {
    let e = PotentialFieldLab::default();
    let scene = scene_of(&e);
    assert_eq!(
        scene
            .items
            .iter()
            .filter(|i| matches!(i, Item::ScaleBar))
            .count(),
        1
    );
}

/// Issue 14: `preview()` with the goal inside an obstacle never returned
/// (its loop waited for a run that cannot move to end).
#[test]
fn preview_returns_when_the_goal_is_inside_an_obstacle() {
    let mut e = PotentialFieldLab::default();
    e.set_param("o1x", 7.2).unwrap();
    e.set_param("o1y", 3.0).unwrap();
    e.preview();
    assert!(e.status().text.contains("goal is inside an obstacle"));
    assert_eq!(e.run().unwrap().time_s, 0.0);
    // The ordinary preview still runs its run to the end.
    let mut e = PotentialFieldLab::default();
    e.preview();
    assert!(e.run().unwrap().status.is_final());
}

/// Issue 14: `action("basin")` with no goal, then `action("nope")`: the
/// second is refused and nothing observable changes (it used to replace
/// "set a goal first…" with "click to set a goal"). Also from the Add and
/// Remove modes.
#[test]
fn a_refused_action_changes_nothing_observable() {
    let mut e = PotentialFieldLab::default();
    e.action("basin").unwrap();
    assert!(notice_text(&e).starts_with("set a goal first"));
    let before = observe(&e);
    assert!(e.action("nope").is_err());
    assert_eq!(observe(&e), before);
    for armed in ["add", "remove"] {
        let mut e = PotentialFieldLab::default();
        e.action(armed).unwrap();
        let mode = e.mode;
        let before = observe(&e);
        assert!(matches!(
            e.action(""),
            Err(ParamError::UnknownAction { .. })
        ));
        assert_eq!(observe(&e), before);
        assert_eq!(e.mode, mode, "the {armed} mode is kept");
    }
}

/// Issue 13 §2: a link that leaves the goal out opens with no goal, and the
/// page rebuilds from the defaults, so what the link leaves out is the
/// default.
#[test]
fn a_link_without_a_goal_opens_with_no_goal() {
    let (e, notices) = restore(
        "#/potential/simulation?kr=2&o1x=2&o1y=2",
        PotentialFieldLab::default(),
    );
    assert!(notices.is_empty(), "{notices:?}");
    assert_eq!(e.param("gx"), None);
    assert_eq!(e.status().text, "click to set a goal");
    assert_eq!(e.param("o2x"), Some(DEFAULT_OBSTACLES[1].x));
}

/// Issue 13 §2: whatever a student does — clicks, drags, nudges, actions,
/// typed values, the basin map — the state's link, opened fresh, gives the
/// same state (link, status, readouts, display list after a run) with no
/// notice.
#[test]
fn every_reachable_state_round_trips_through_its_link() {
    let mut rng = Lcg64::new(2024);
    let keys: Vec<&ParamSpec> = PARAMS.iter().collect();
    for case in 0..60 {
        let mut e = PotentialFieldLab::default();
        for _ in 0..rng.int(1, 12) {
            let p = DVec2::new(rng.range(-0.5, 8.5), rng.range(-0.5, 6.5));
            match rng.int(0, 5) {
                0 => click(&mut e, p),
                1 => {
                    let from = match rng.int(0, 2) {
                        0 => e.goal.unwrap_or(e.start),
                        1 => e.start,
                        _ => e.slots[0],
                    };
                    e.input(Input::PointerDown(from));
                    e.input(Input::PointerMove {
                        pos: p,
                        pressed: true,
                    });
                    e.input(Input::PointerUp(p));
                }
                2 => {
                    let a = ACTIONS[rng.int(0, ACTIONS.len() as i64 - 1) as usize];
                    e.action(a.key).unwrap();
                }
                3 => e.input(Input::Nudge(DVec2::new(
                    rng.int(-3, 3) as f64 * 0.1,
                    rng.int(-3, 3) as f64 * 0.1,
                ))),
                _ => {
                    let spec = keys[rng.int(0, keys.len() as i64 - 1) as usize];
                    // Values a number box accepts, to the link's precision.
                    let v = (rng.range(spec.min, spec.max) * 100.0).round() / 100.0;
                    e.set_param(spec.key, v).unwrap();
                }
            }
        }
        let link = format(&e, Tab::Simulation);
        let (mut fresh, notices) = restore(&link, PotentialFieldLab::default());
        assert!(notices.is_empty(), "case {case}: {link}: {notices:?}");
        assert_eq!(format(&fresh, Tab::Simulation), link, "case {case}");
        assert_eq!(fresh.obstacles(), e.obstacles(), "case {case}");
        assert_eq!(fresh.basin().is_some(), e.basin().is_some(), "case {case}");
        // The same link drives the same run.
        e.reset();
        fresh.reset();
        for _ in 0..120 {
            e.step(DT);
            fresh.step(DT);
        }
        assert_eq!(observe(&fresh), observe(&e), "case {case}: {link}");
    }
}

/// Issue 15: every generator draws its gains, distances and radii inside
/// the sliders' ranges, so a question can be set up on the page.
#[test]
fn generators_draw_inside_the_slider_ranges() {
    let spec = |key: &str| *PARAMS.iter().find(|s| s.key == key).unwrap();
    let inside = |key: &str, v: f64| {
        let s = spec(key);
        assert!(
            v >= s.min && v <= s.max,
            "{key} = {v} outside [{}, {}]",
            s.min,
            s.max
        );
    };
    let mut rng = Lcg64::new(11);
    for _ in 0..500 {
        for draw in [
            quiz_repulsion(&mut rng),
            quiz_net_force(&mut rng),
            quiz_potential(&mut rng),
        ] {
            for (name, key) in [("ka", "ka"), ("kr", "kr"), ("d0", "d0"), ("r", "rad")] {
                if let Some(v) = draw.var(name) {
                    inside(key, v);
                }
            }
            // Distances fit in the 8 m × 6 m field.
            for name in ["d", "s", "g"] {
                if let Some(v) = draw.var(name) {
                    assert!(v > 0.0 && v < FIELD_W_M, "{name} = {v}");
                }
            }
        }
    }
}

/// Issue 15: the correct option of a choice question is seldom the
/// (strictly) longest, so option length does not give the answer away.
#[test]
fn the_correct_option_is_seldom_the_longest() {
    testkit::assert_the_correct_option_is_seldom_the_longest("potential");
}

/// The page stops time once a run has ended; a basin map started after a
/// trap must still fill in, so the status stays live while it computes.
#[test]
fn a_basin_map_after_an_ended_run_keeps_time_running_until_it_is_complete() {
    let mut e = trap();
    assert!(run_until_phase(&mut e, Phase::Ended, 20_000).is_some());
    e.action("basin").unwrap();
    assert!(e.basin_computing());
    assert_eq!(e.status().phase, crate::experiment::Phase::Live);
    let mut guard = 0;
    while e.basin_computing() && guard < 100_000 {
        e.step(DT);
        guard += 1;
    }
    assert!(!e.basin_computing());
    assert_eq!(e.status().phase, crate::experiment::Phase::Ended);
}

/// The backdrop (the quiver, the obstacles, the start and the goal) holds
/// still while the robot runs, so the page can keep its picture; the robot
/// and its trail come after it.
#[test]
fn the_backdrop_holds_still_while_the_robot_runs() {
    let mut e = PotentialFieldLab::default();
    click(&mut e, DVec2::new(7.2, 3.0));
    let before = scene_of(&e);
    assert!(before.items[..before.backdrop]
        .iter()
        .any(|i| matches!(i, Item::Arrows { .. })));
    steps(&mut e, 60);
    assert!(e.animating(), "still running after 1 s");
    let after = scene_of(&e);
    assert_eq!(before.backdrop_key, after.backdrop_key);
    assert_eq!(
        before.items[..before.backdrop],
        after.items[..after.backdrop]
    );
    assert!(after.items[after.backdrop..].iter().any(|i| matches!(
        i,
        Item::Polyline {
            role: Role::Path,
            ..
        }
    )));
}

/// Property: equal backdrop keys mean equal backdrop items (the page shows a
/// kept picture while the key stays the same, so a key that missed an input
/// would show a stale field). Random edits from a small set of values, so
/// states repeat.
#[test]
fn equal_backdrop_keys_mean_equal_backdrop_items() {
    use std::collections::HashMap;
    let mut rng = Lcg64::new(16);
    let mut seen: HashMap<u64, Vec<Item>> = HashMap::new();
    let mut e = PotentialFieldLab::default();
    let keys = [
        "ka", "kr", "d0", "rad", "view", "nobs", "sx", "sy", "o1x", "o1y", "gx", "gy",
    ];
    let mut distinct = 0;
    for _ in 0..600 {
        let key = keys[(rng.next_f64() * keys.len() as f64) as usize];
        let spec = e.params().iter().find(|p| p.key == key).unwrap();
        let pick = (rng.next_f64() * 3.0).floor() / 2.0;
        let v = spec.min + pick * (spec.max - spec.min);
        let _ = e.set_param(
            key,
            if key == "view" {
                (pick * 2.0).round()
            } else {
                v
            },
        );
        if rng.next_f64() < 0.1 {
            click(&mut e, DVec2::new(7.2, 3.0));
        }
        let scene = scene_of(&e);
        if scene.backdrop == 0 {
            continue;
        }
        let items = scene.items[..scene.backdrop].to_vec();
        match seen.get(&scene.backdrop_key) {
            Some(old) => assert_eq!(old, &items, "one key, two backdrops"),
            None => {
                distinct += 1;
                seen.insert(scene.backdrop_key, items);
            }
        }
    }
    assert!(distinct > 20, "{distinct} distinct backdrops visited");
}

/// Issue 53 §7: a "Hide basin map" button stood beside a field with no
/// basin map. It is shown while a map is, from the button or from a link.
#[test]
fn hide_basin_map_is_shown_only_with_a_basin_map() {
    let mut e = trap();
    assert!(e.action_shown("basin") && e.action_shown("add") && e.action_shown("remove"));
    assert!(!e.action_shown("clear"), "no map yet");
    e.action("basin").unwrap();
    assert!(e.action_shown("clear"), "the map is computing");
    run_while_animating(&mut e, 30.0);
    assert!(e.action_shown("clear"), "the map is done");
    let link = format(&e, Tab::Simulation);
    assert!(link.contains("map=1"), "{link}");
    let (fresh, _) = restore(&link, PotentialFieldLab::default());
    assert!(fresh.action_shown("clear"), "{link}");
    e.action("clear").unwrap();
    assert!(e.basin().is_none() && !e.action_shown("clear"));
}
