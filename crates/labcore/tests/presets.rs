//! Every experiment's presets: each link parses and applies without a
//! notice, and each produces the state its description tells.

use labcore::route::{self, Tab};
use labcore::testkit::{self, readout, readout_number, run_for};
use labcore::{registry, Lab};

/// The experiment `id` opened from its preset `name`'s link, as the
/// Presets menu opens it; panics on any notice.
fn open(id: &str, name: &str) -> Box<dyn Lab> {
    let entry = labcore::find(id).expect(id);
    let preset = (entry.make)()
        .presets()
        .iter()
        .find(|p| p.name == name)
        .unwrap_or_else(|| panic!("{id} has no preset “{name}”"));
    let (exp, notices) = apply(id, &format!("#/{id}/simulation?{}", preset.query));
    assert!(notices.is_empty(), "{id} “{name}”: {notices:?}");
    exp
}

/// A fresh experiment `id` with `link` applied (locks, hides and note
/// checked too), and every notice.
fn apply(id: &str, link: &str) -> (Box<dyn Lab>, Vec<String>) {
    let mut exp = testkit::open(id);
    let notices = testkit::apply_link(exp.as_mut(), link);
    (exp, notices)
}

#[test]
fn every_experiment_ships_two_or_three_presets_that_apply_cleanly_and_reload_exactly() {
    for entry in registry() {
        let presets = (entry.make)().presets();
        assert!(
            (2..=3).contains(&presets.len()),
            "{}: {} presets",
            entry.id,
            presets.len()
        );
        for (i, p) in presets.iter().enumerate() {
            assert!(!p.name.is_empty() && p.description.len() > 20, "{p:?}");
            assert!(
                presets[..i].iter().all(|q| q.name != p.name),
                "{}: “{}” twice",
                entry.id,
                p.name
            );
            assert!(!p.query.starts_with('?') && !p.query.is_empty(), "{p:?}");
            let exp = open(entry.id, p.name);
            // The state a preset opens is a state like any other: its own link reproduces it.
            let link = route::format(exp.as_ref(), Tab::Simulation);
            let (again, notices) = apply(entry.id, &link);
            assert!(notices.is_empty(), "{link}: {notices:?}");
            assert_eq!(route::format(again.as_ref(), Tab::Simulation), link);
        }
    }
}

#[test]
fn fk_presets_put_the_tip_on_the_outer_circle_the_inner_rim_and_the_base() {
    let tip = |e: &dyn Lab| readout_number(e, "x").hypot(readout_number(e, "y"));
    let e = open("fk", "Full stretch");
    assert!((tip(e.as_ref()) - 1.7).abs() < 1e-3, "L₁ + L₂");
    assert_eq!(readout(e.as_ref(), "reach"), "100.0%");
    let e = open("fk", "Folded onto the inner rim");
    assert!((tip(e.as_ref()) - 0.3).abs() < 1e-3, "|L₁ − L₂|");
    let e = open("fk", "Equal links close the hole");
    assert!(tip(e.as_ref()) < 1e-3);
}

#[test]
fn ik_presets_miss_an_outside_target_flip_the_elbow_and_keep_the_wrist() {
    let mut e = open("ik", "Out of reach");
    run_for(e.as_mut(), 2.0);
    assert!(
        e.status().text.starts_with("out of reach"),
        "{:?}",
        e.status()
    );
    let mut up = open("ik", "Elbow down");
    run_for(up.as_mut(), 2.0);
    assert_eq!(up.status().text, "in reach");
    assert_eq!(
        (readout(up.as_ref(), "x"), readout(up.as_ref(), "y")),
        ("0.500 m".into(), "1.000 m".into())
    );
    // The elbow-up solution of the same target has the opposite θ₂.
    let (mut other, _) = apply("ik", "#/ik/simulation?elbow=1&tx=0.5&ty=1");
    run_for(other.as_mut(), 2.0);
    assert!(
        (readout_number(up.as_ref(), "theta2") + readout_number(other.as_ref(), "theta2")).abs()
            < 0.2
    );
    let mut w = open("ik", "Wrist keeps its angle");
    run_for(w.as_mut(), 2.0);
    assert_eq!(w.status().text, "in reach");
    assert_eq!(
        (readout(w.as_ref(), "x"), readout(w.as_ref(), "y")),
        ("0.500 m".into(), "1.200 m".into())
    );
}

#[test]
fn workspace_presets_open_and_close_the_hole_and_few_samples_fake_one() {
    let e = open("workspace", "A dominant link opens a hole");
    assert_eq!(readout(e.as_ref(), "inner_theory"), "0.700 m");
    let e = open("workspace", "Equal links fill the disc");
    assert_eq!(readout(e.as_ref(), "inner_theory"), "0.000 m");
    let mut e = open("workspace", "Few samples fake a hole");
    e.action("sweep").unwrap();
    run_for(e.as_mut(), 5.0);
    assert_eq!(readout(e.as_ref(), "samples"), "1000 / 1000");
    let (outer, theory) = (
        readout_number(e.as_ref(), "outer"),
        readout_number(e.as_ref(), "outer_theory"),
    );
    assert!(
        theory - outer < 0.01,
        "the rim is found: {outer} vs {theory}"
    );
    assert_eq!(readout(e.as_ref(), "inner_theory"), "0.000 m");
    assert!(
        readout_number(e.as_ref(), "inner") > 0.02,
        "a hole that is not there"
    );
}

#[test]
fn dls_presets_oscillate_without_damping_settle_with_adaptive_damping_and_stretch_outside() {
    let mut e = open("dls", "The bare update oscillates");
    run_for(e.as_mut(), 20.0);
    assert!(
        e.status().text.starts_with("not converging"),
        "{:?}",
        e.status()
    );
    let mut e = open("dls", "Adaptive damping settles");
    run_for(e.as_mut(), 20.0);
    assert_eq!(e.status().text, "closest reachable pose");
    assert_eq!(readout(e.as_ref(), "error"), "0.050 m");
    let mut e = open("dls", "Far outside the reach");
    run_for(e.as_mut(), 20.0);
    assert_eq!(e.status().text, "closest reachable pose");
    // Four links of 0.6 m stretched towards (2, 2): the gap is |t| − 2.4 m.
    let gap = 2.0f64.hypot(2.0) - 2.4;
    assert!((readout_number(e.as_ref(), "error") - gap).abs() < 1e-3);
}

/// The trap maze: the start sits in a cup open away from the goal, so a
/// search guided towards the goal fills the cup before it goes round.
#[test]
fn astar_trap_maze_makes_a_star_and_greedy_search_expand_the_whole_cup() {
    let planned = |mut e: Box<dyn Lab>| {
        e.set_param("rate", 50.0).unwrap();
        e.action("plan").unwrap();
        run_for(e.as_mut(), 30.0);
        assert!(e.status().text.starts_with("arrived"), "{:?}", e.status());
        (
            readout_number(e.as_ref(), "expanded"),
            readout_number(e.as_ref(), "path_cells"),
        )
    };
    let (trap, path) = planned(open("astar", "The trap maze"));
    // Without the cup the same ends cost 15 expansions.
    let (open_field, straight) = planned(
        apply(
            "astar",
            "#/astar/simulation?walls=32x24&sx=14&sy=12&gx=28&gy=12",
        )
        .0,
    );
    assert_eq!((open_field, straight), (15.0, 15.0));
    assert!(
        trap > 200.0 && trap > 6.0 * path,
        "{trap} expanded for {path} cells"
    );
    // Greedy (weight 5) is caught just the same.
    let mut greedy = open("astar", "The trap maze");
    greedy.set_param("w", 5.0).unwrap();
    let (greedy, _) = planned(greedy);
    assert!(greedy > 200.0, "{greedy}");
    let (dijkstra, _) = planned(open("astar", "Dijkstra floods the grid"));
    let (a_star, _) = planned((labcore::find("astar").unwrap().make)());
    assert!(dijkstra > 3.0 * a_star, "{dijkstra} vs {a_star}");
    let manhattan = open("astar", "Manhattan with diagonals");
    let mut m = manhattan;
    m.set_param("rate", 50.0).unwrap();
    m.action("plan").unwrap();
    run_for(m.as_mut(), 30.0);
    assert!(
        m.status().text.contains("Manhattan overestimates"),
        "{:?}",
        m.status()
    );
    assert_eq!(m.status().tone, labcore::Tone::Warning);
}

#[test]
fn pid_overshoot_vs_damping_and_the_offset_of_a_push() {
    let mut little = open("pid", "Overshoot vs damping: little damping");
    run_for(little.as_mut(), 10.0);
    let overshoot = readout_number(little.as_ref(), "overshoot");
    assert!(overshoot > 50.0, "{overshoot} %");
    let mut plenty = open("pid", "Overshoot vs damping: plenty of damping");
    run_for(plenty.as_mut(), 10.0);
    assert!(readout_number(plenty.as_ref(), "overshoot") < 1.0);
    assert_eq!(
        little.param("kp"),
        plenty.param("kp"),
        "only the damping differs"
    );
    let mut push = open("pid", "A push leaves an offset");
    run_for(push.as_mut(), 15.0);
    // Steady state: Kp · e = −d, so e = −5 / 20.
    assert_eq!(readout(push.as_ref(), "sse"), "-0.250 m");
}

#[test]
fn cartpole_presets_lose_the_pole() {
    for name in ["Too soft: the pole is lost", "Control off"] {
        let mut e = open("cartpole", name);
        run_for(e.as_mut(), 12.0);
        assert!(
            e.status().text.starts_with("pole fallen"),
            "{name}: {:?}",
            e.status()
        );
    }
}

#[test]
fn diffdrive_presets_turn_to_a_goal_behind_and_a_low_gain_drives_wider() {
    let mut e = open("diffdrive", "A goal behind the robot");
    run_for(e.as_mut(), 20.0);
    assert_eq!(e.status().text, "reached the goal");
    assert_eq!(
        readout(e.as_ref(), "max_error"),
        "180.0°",
        "it started facing away"
    );
    let mut lazy = open("diffdrive", "Lazy steering: wide arcs");
    run_for(lazy.as_mut(), 40.0);
    assert_eq!(lazy.status().text, "reached all 2 waypoints");
    let (mut brisk, _) = apply(
        "diffdrive",
        "#/diffdrive/simulation?w1x=7&w1y=5&w2x=1&w2y=5",
    );
    run_for(brisk.as_mut(), 40.0);
    assert!(readout_number(lazy.as_ref(), "path") > readout_number(brisk.as_ref(), "path") + 0.3);
}

#[test]
fn ekf_no_landmarks_in_view_only_predicts_and_good_sensing_beats_bad_odometry() {
    let mut e = open("ekf", "No landmarks in view");
    run_for(e.as_mut(), 2.0);
    let early = readout_number(e.as_ref(), "trace");
    run_for(e.as_mut(), 8.0);
    assert_eq!(
        readout(e.as_ref(), "obs_per_loop"),
        "0 so far",
        "no landmark ever in view"
    );
    assert!(
        readout_number(e.as_ref(), "trace") > 3.0 * early,
        "the ellipse keeps growing"
    );
    assert_eq!(
        readout(e.as_ref(), "error"),
        readout(e.as_ref(), "dr_error"),
        "the estimate is dead reckoning"
    );
    let mut e = open("ekf", "Sloppy odometry, good sensor");
    run_for(e.as_mut(), 20.0);
    assert!(readout_number(e.as_ref(), "dr_error") > 5.0 * readout_number(e.as_ref(), "error"));
    let mut e = open("ekf", "EKF-SLAM builds the map");
    run_for(e.as_mut(), 20.0);
    assert!(
        e.status().text.starts_with("EKF-SLAM:") && readout_number(e.as_ref(), "landmarks") >= 3.0,
        "{:?}",
        e.status()
    );
}

#[test]
fn potential_presets_trap_collide_and_keep_clear() {
    let mut e = open("potential", "Two obstacles trap the robot");
    run_for(e.as_mut(), 60.0);
    assert!(
        e.status().text.starts_with("trapped in a local minimum"),
        "{:?}",
        e.status()
    );
    let mut e = open("potential", "The pull beats the push");
    run_for(e.as_mut(), 60.0);
    assert_eq!(e.status().text, "collided with an obstacle");
    let mut wide = open("potential", "A wide berth");
    run_for(wide.as_mut(), 60.0);
    let (mut plain, _) = apply("potential", "#/potential/simulation?gx=7.2&gy=3");
    run_for(plain.as_mut(), 60.0);
    assert!(
        readout_number(wide.as_ref(), "clearance")
            > readout_number(plain.as_ref(), "clearance") + 0.2
    );
}

#[test]
fn rrtstar_keeps_its_first_path_and_rrt_star_shortens_it() {
    let grown = |name: &str| {
        let mut e = open("rrtstar", name);
        e.action("grow").unwrap();
        run_for(e.as_mut(), 30.0);
        assert!(
            e.status().text.starts_with("done: best path"),
            "{:?}",
            e.status()
        );
        e
    };
    let rrt = grown("RRT keeps its first path");
    let star = grown("RRT* straightens it");
    assert_eq!(readout(rrt.as_ref(), "rewires"), "0");
    assert!(readout_number(star.as_ref(), "rewires") > 0.0);
    assert!(readout_number(rrt.as_ref(), "best") > 1.1 * readout_number(star.as_ref(), "best"));
}
