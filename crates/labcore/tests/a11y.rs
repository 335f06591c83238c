//! Issue 17 §6: every drag has a non-drag alternative, and every scene has a
//! short description for screen readers.
//!
//! - An experiment with anything to drag lists its handles
//!   ([`Experiment::handles`]), each where a press grabs it.
//! - [`Experiment::move_handle`] (the keyboard and the typed coordinates)
//!   gives exactly the state the equivalent pointer drag gives, puts the
//!   handle where it was sent, and the result reloads from its link.
//! - [`labcore::Presentation::describe`] says what the scene shows, per experiment.

use labcore::glam::DVec2;
use labcore::route::{apply_params, format, parse, Page, Tab};
use labcore::{registry, Lab};

/// The page's keyboard step: 2 % of the view's width (see labweb's canvas input).
fn keyboard_step(exp: &dyn Lab) -> f64 {
    let view = exp.view();
    (view.max.x - view.min.x) * 0.02
}

/// A drag with the pointer from `from` to `to`.
fn drag(exp: &mut dyn Lab, from: DVec2, to: DVec2) {
    labcore::testkit::drag_through(exp, &[from, to]);
}

/// The two states every experiment is checked in: as built, and as its
/// home-page picture (waypoints dropped, a goal set, a tree grown).
fn states(entry: &labcore::Entry) -> [Box<dyn Lab>; 2] {
    let fresh = (entry.make)();
    let mut preview = (entry.make)();
    preview.preview();
    [fresh, preview]
}

fn reload(exp: &dyn Lab) -> Box<dyn Lab> {
    let ids: Vec<&str> = registry().iter().map(|e| e.id).collect();
    let link = format(exp, Tab::Simulation);
    let Page::Experiment { params, .. } = parse(&link, &ids).page else {
        panic!("{link} is not an experiment page");
    };
    let entry = labcore::find(exp.id()).expect("registered");
    let mut fresh = (entry.make)();
    let notices = apply_params(fresh.as_mut(), &params);
    assert!(notices.is_empty(), "{link}: {notices:?}");
    fresh
}

#[test]
fn every_experiment_with_a_drag_lists_its_handles_where_a_press_grabs_them() {
    let mut with_handles = Vec::new();
    for entry in registry() {
        for exp in states(entry) {
            let view = exp.view();
            let tolerance = keyboard_step(exp.as_ref());
            // A 41 × 41 lattice over the view: does a press anywhere grab something?
            let grabbable = (0..=40).any(|i| {
                (0..=40).any(|j| {
                    let t = DVec2::new(f64::from(i), f64::from(j)) / 40.0;
                    exp.handle_at(view.min + (view.max - view.min) * t, tolerance)
                })
            });
            let handles = exp.handles();
            assert_eq!(
                grabbable,
                !handles.is_empty(),
                "{}: draggable somewhere but lists {handles:?}",
                entry.id
            );
            for h in &handles {
                assert!(
                    exp.handle_at(h.at, tolerance),
                    "{}: a press on {} at {:?} grabs nothing",
                    entry.id,
                    h.id,
                    h.at
                );
                assert!(!h.label.is_empty() && !h.id.is_empty());
            }
            let mut ids: Vec<&str> = handles.iter().map(|h| h.id.as_str()).collect();
            ids.sort_unstable();
            ids.dedup();
            assert_eq!(ids.len(), handles.len(), "{}: ids repeat", entry.id);
            if !handles.is_empty() {
                with_handles.push(entry.id);
            }
        }
    }
    with_handles.dedup();
    // Everything but the EKF (which runs by itself) has something to drag.
    let without: Vec<&str> = registry()
        .iter()
        .map(|e| e.id)
        .filter(|id| !with_handles.contains(id))
        .collect();
    assert_eq!(without, ["ekf"]);
}

#[test]
fn keyboard_moves_give_the_state_of_the_equivalent_drag_and_reload_from_the_link() {
    let mut checked = 0;
    for entry in registry() {
        for (state, _) in states(entry).iter().enumerate().map(|(i, e)| (i, e.id())) {
            let make = || {
                let mut e = (entry.make)();
                if state == 1 {
                    e.preview();
                }
                e
            };
            let handles = make().handles();
            for h in &handles {
                for dir in [DVec2::X, DVec2::NEG_Y] {
                    let mut keyed = make();
                    let step = h.step_m.unwrap_or_else(|| keyboard_step(keyed.as_ref()));
                    let to = h.at + dir * step;
                    assert!(keyed.move_handle(&h.id, to), "{} {}", entry.id, h.id);
                    let mut dragged = make();
                    drag(dragged.as_mut(), h.at, to);
                    let link = format(keyed.as_ref(), Tab::Simulation);
                    assert_eq!(
                        link,
                        format(dragged.as_ref(), Tab::Simulation),
                        "{} {}: keyboard and drag differ",
                        entry.id,
                        h.id
                    );
                    assert_eq!(keyed.handles(), dragged.handles(), "{} {}", entry.id, h.id);
                    assert_eq!(keyed.describe(), dragged.describe());
                    // The link reproduces the moved state.
                    let reloaded = reload(keyed.as_ref());
                    assert_eq!(format(reloaded.as_ref(), Tab::Simulation), link);
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 30, "only {checked} moves checked");
}

/// Where a keyboard move sends a handle, there it is (to the centimetre the
/// links keep; the A* ends on the next cell; the PID setpoint along x only;
/// a two-link tip within the arm's reach).
#[test]
fn a_moved_handle_is_where_it_was_sent() {
    for entry in registry() {
        let mut exp = (entry.make)();
        exp.preview();
        for h in exp.handles() {
            let step = h.step_m.unwrap_or_else(|| keyboard_step(exp.as_ref()));
            let to = h.at + DVec2::new(-step, 0.0);
            assert!(exp.move_handle(&h.id, to));
            let now = exp
                .handles()
                .into_iter()
                .find(|m| m.id == h.id)
                .unwrap_or_else(|| panic!("{} {} vanished", entry.id, h.id));
            assert!(
                (now.at.x - to.x).abs() <= 0.006,
                "{} {}: sent to {to:?}, at {:?}",
                entry.id,
                h.id,
                now.at
            );
            if entry.id != "pid" && entry.id != "cartpole" {
                assert!((now.at.y - to.y).abs() <= 0.006, "{} {}", entry.id, h.id);
            }
        }
    }
}

#[test]
fn a_move_of_an_unknown_handle_or_to_no_point_changes_nothing() {
    for entry in registry() {
        let mut exp = (entry.make)();
        exp.preview();
        let link = format(exp.as_ref(), Tab::Simulation);
        assert!(!exp.move_handle("nonesuch", DVec2::ONE));
        for h in exp.handles() {
            assert!(!exp.move_handle(&h.id, DVec2::new(f64::NAN, 1.0)));
            assert!(!exp.move_handle(&h.id, DVec2::new(1.0, f64::INFINITY)));
        }
        assert_eq!(format(exp.as_ref(), Tab::Simulation), link, "{}", entry.id);
    }
}

/// Every description is short, finite and in sentences; none is the bare
/// default for an experiment that has a specific one.
#[test]
fn every_description_is_a_short_finite_sentence() {
    for entry in registry() {
        for exp in states(entry) {
            let text = exp.describe();
            assert!(text.ends_with('.'), "{}: {text}", entry.id);
            assert!(
                text.len() < 400,
                "{}: {} bytes: {text}",
                entry.id,
                text.len()
            );
            assert!(
                !text.contains("NaN") && !text.contains("inf"),
                "{}: {text}",
                entry.id
            );
            assert!(text.contains(&exp.status().text), "{}: {text}", entry.id);
        }
    }
}

fn describe(id: &str, setup: impl FnOnce(&mut dyn Lab)) -> String {
    let mut exp = (labcore::find(id).expect("registered").make)();
    setup(exp.as_mut());
    exp.describe()
}

#[test]
fn fk_describes_the_angles_and_the_tip() {
    // θ₁ = 90°, θ₂ = 0°, L₁ = 1, L₂ = 0.7: the arm points straight up, tip (0, 1.7).
    let text = describe("fk", |e| {
        for (k, v) in [("t1", 90.0), ("t2", 0.0), ("l1", 1.0), ("l2", 0.7)] {
            e.set_param(k, v).unwrap();
        }
    });
    // The dashed circles: L₁ + L₂ = 1.7 m and |L₁ − L₂| = 0.3 m.
    assert_eq!(
        text,
        "Two-link arm with θ₁ 90.0° and θ₂ 0.0°: tip at (0.00, 1.70) m, 100.0% of the reach used; in reach. \
         2 dashed circles bound the reach: outer radius 1.700 m, inner radius 0.300 m."
    );
    // Equal links, 1.2 m each: one circle of 2.4 m, and no hole.
    let equal = describe("fk", |e| {
        e.set_param("l1", 1.2).unwrap();
        e.set_param("l2", 1.2).unwrap();
    });
    assert!(
        equal.ends_with("1 dashed circle bounds the reach: outer radius 2.400 m, no hole."),
        "{equal}"
    );
}

#[test]
fn ik_describes_the_target_and_the_arm_once_it_arrived() {
    assert!(describe("ik", |_| {}).starts_with("No target yet: click a target. Arm at θ₁"));
    // Target (1.7, 0) with L₁ = 1, L₂ = 0.7: the stretched arm, θ = (0°, 0°).
    let text = describe("ik", |e| {
        e.set_param("l1", 1.0).unwrap();
        e.set_param("l2", 0.7).unwrap();
        e.set_param("tx", 1.7).unwrap();
        e.set_param("ty", 0.0).unwrap();
        for _ in 0..600 {
            e.step(1.0 / 60.0);
        }
    });
    assert!(
        text.starts_with("Target at (1.70, 0.00) m: singular: arm straight"),
        "{text}"
    );
    assert!(
        text.ends_with(
            "Arm at θ₁ 0.0°, θ₂ 0.0°, tip at (1.70, 0.00) m. No ghost arm: the branches merge. \
             2 dashed circles bound the reach: outer radius 1.700 m, inner radius 0.300 m."
        ),
        "{text}"
    );
    // Theory's worked example, target (1.2, 0.8) m: elbow up (the default)
    // is (59.80°, −65.08°), and the ghost is the elbow-down branch, (7.58°, 65.08°).
    let worked = describe("ik", |e| {
        e.set_param("tx", 1.2).unwrap();
        e.set_param("ty", 0.8).unwrap();
        for _ in 0..600 {
            e.step(1.0 / 60.0);
        }
    });
    assert!(
        worked.contains("1 ghost arm shows the other branch, θ₁ 7.6°, θ₂ 65.1°."),
        "{worked}"
    );
}

#[test]
fn workspace_describes_the_sweep_against_theory() {
    let before = describe("workspace", |_| {});
    assert!(before.contains("No workspace sweep yet"), "{before}");
    let text = describe("workspace", |e| e.preview());
    assert!(text.contains("8000 / 8000 samples"), "{text}");
    assert!(
        text.contains("outer radius 2.500 m measured, 2.500 m in theory"),
        "{text}"
    );
}

#[test]
fn diffdrive_describes_the_robot_and_the_waypoints_reached() {
    let idle = describe("diffdrive", |_| {});
    assert!(
        idle.ends_with("no waypoints yet; idle: click to drop a goal."),
        "{idle}"
    );
    // The robot starts at (4, 3) heading 0° (the experiment's START); with
    // no waypoint it stays there.
    assert!(
        idle.starts_with("Robot at (4.00, 3.00) m heading 0.0°"),
        "{idle}"
    );
    let text = describe("diffdrive", |e| {
        // Two waypoints typed; the first is reached after enough steps.
        for (k, v) in [("w1x", 2.0), ("w1y", 1.0), ("w2x", 6.0), ("w2y", 4.0)] {
            e.set_param(k, v).unwrap();
        }
        for _ in 0..60 * 60 {
            e.step(1.0 / 60.0);
            if e.describe().contains("1 of 2 waypoints reached") {
                break;
            }
        }
    });
    assert!(
        text.contains("1 of 2 waypoints reached, next at (6.00, 4.00) m; waypoint 2 of 2"),
        "{text}"
    );
}

#[test]
fn potential_describes_robot_goal_and_obstacles() {
    let idle = describe("potential", |_| {});
    assert!(idle.contains("no goal yet"), "{idle}");
    let text = describe("potential", |e| e.preview());
    assert!(text.contains("2 obstacles; reached the goal in"), "{text}");
    // No obstacles: from every one of the 40 × 30 cells of 0.2 m the conic
    // pull alone leads to the goal.
    let open = describe("potential", |e| {
        e.set_param("nobs", 0.0).unwrap();
        e.set_param("gx", 7.2).unwrap();
        e.set_param("gy", 3.0).unwrap();
        e.action("basin").unwrap();
        for _ in 0..60 * 10 {
            e.step(1.0 / 60.0);
        }
    });
    assert!(open.contains("no obstacles; reached the goal in"), "{open}");
    assert!(
        open.ends_with(
            "Basin map: 1200 starts reach the goal (green), 0 trapped (orange-red), 0 collided (grey)."
        ),
        "{open}"
    );
}

#[test]
fn astar_describes_the_ends_and_the_grid() {
    let text = describe("astar", |_| {});
    assert!(
        text.contains("grid with 0 walls") || text.contains(" walls; "),
        "{text}"
    );
    let a = labcore::experiments::astar::AStarGrid::default();
    let (s, g) = (a.start(), a.goal());
    assert!(
        text.starts_with(&format!(
            "Start at cell ({}, {}), goal at cell ({}, {})",
            s.x, s.y, g.x, g.y
        )),
        "{text}"
    );
}

#[test]
fn rrtstar_describes_the_ends_the_tree_and_the_best_path() {
    let text = describe("rrtstar", |e| e.preview());
    assert!(
        text.contains("nodes in the tree; done: best path"),
        "{text}"
    );
}

#[test]
fn pid_describes_the_response() {
    let text = describe("pid", |e| {
        for _ in 0..60 * 10 {
            e.step(1.0 / 60.0);
        }
    });
    assert!(text.starts_with("Cart at "), "{text}");
    assert!(text.contains("setpoint 1.000 m"), "{text}");
}

#[test]
fn cartpole_describes_the_pole_and_the_cart() {
    let text = describe("cartpole", |_| {});
    assert!(text.starts_with("Pole at "), "{text}");
    assert!(text.contains(" from upright"), "{text}");
}

#[test]
fn dls_describes_the_target_and_the_error() {
    let idle = describe("dls", |_| {});
    assert!(idle.contains("No target yet"), "{idle}");
    let text = describe("dls", |e| e.preview());
    assert!(text.contains("converged in"), "{text}");
    assert!(text.starts_with("4-link arm, tip at"), "{text}");
}

#[test]
fn ekf_describes_the_robot_and_the_estimate_error() {
    let text = describe("ekf", |e| {
        for _ in 0..120 {
            e.step(1.0 / 60.0);
        }
    });
    assert!(text.starts_with("Robot at ("), "{text}");
    assert!(text.contains("landmarks 6 (known map)"), "{text}");
    // At the start the filter's σ is 0.05 m in x and in y: its 3σ ellipse
    // is a circle of 0.15 m.
    let start = describe("ekf", |_| {});
    assert!(
        start.contains("its 3σ ellipse has semi-axes 0.150 m and 0.150 m; landmarks 6"),
        "{start}"
    );
}

/// Words a phone has no use for: keys, clicks, modifiers.
const KEY_WORDS: &[&str] = &[
    "click",
    "Click",
    "Shift",
    "Ctrl",
    "arrow key",
    "←",
    "→",
    "↑",
    "↓",
    "[ ]",
    "keyboard",
    "has focus",
];

fn assert_touch_words(id: &str, when: &str, exp: &dyn Lab) {
    let texts = [
        exp.touch_hint().to_owned(),
        labcore::experiment::for_touch(&exp.status().text),
        exp.notice()
            .map_or(String::new(), |n| labcore::experiment::for_touch(&n.text)),
    ];
    for text in texts {
        for word in KEY_WORDS {
            assert!(
                !text.contains(word),
                "{id} {when}: a phone shows “{text}” ({word})"
            );
        }
    }
}

/// Issue 23 §3 (phone hints): on a touch screen the hint, the badge and the
/// notice name no key, no click and no modifier, as built, as previewed and
/// after each action (the native half of the end-to-end phone test).
#[test]
fn phone_hints_name_no_key_a_phone_lacks_in_any_status_hint_or_notice() {
    for entry in registry() {
        for (k, mut exp) in states(entry).into_iter().enumerate() {
            let when = if k == 0 { "as built" } else { "previewed" };
            assert_touch_words(entry.id, when, exp.as_ref());
            for action in exp.actions() {
                let _ = exp.action(action.key);
                for _ in 0..3 {
                    exp.step(1.0 / 60.0);
                }
                assert_touch_words(
                    entry.id,
                    &format!("{when}, after {}", action.key),
                    exp.as_ref(),
                );
            }
        }
    }
}

/// Issue 23 §3: one system for one point. The numbers the Move form shows
/// for a handle take it back to where it is.
#[test]
fn every_handle_reads_back_the_numbers_the_move_form_shows() {
    for entry in registry() {
        let mut exp = (entry.make)();
        exp.preview();
        for h in exp.handles() {
            let back = h.from_typed(h.typed().1);
            assert!(
                (back - h.at).length() < 1e-9,
                "{} {}: {:?} → {back:?}",
                entry.id,
                h.id,
                h.at
            );
        }
    }
}
