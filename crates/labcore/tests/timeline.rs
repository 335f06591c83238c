//! Issue 26 §1 and §4: the timeline goes back to any step of a run exactly,
//! replaying at most one snapshot interval, for every experiment that
//! evolves in time or in iterations.

use labcore::clock::Clock;
use labcore::glam::DVec2;
use labcore::run_input::{self, RunInput};
use labcore::testkit::scene_of;
use labcore::timeline::Timeline;
use labcore::{Input, Lab, Lcg64, Modifiers};
use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

mod evolving;
use evolving::EVOLVING;

/// Everything the page shows of the state: the display list, the readouts,
/// the status, the tables and the plots (their data up to now), hashed.
fn shown(exp: &dyn Lab) -> u64 {
    let text = format!(
        "{:?}|{:?}|{:?}|{:?}|{:?}|{:?}",
        scene_of(exp),
        exp.readouts(),
        exp.status(),
        exp.tables(),
        exp.plots(),
        exp.handles(),
    );
    let mut h = DefaultHasher::new();
    text.hash(&mut h);
    h.finish()
}

fn step_once(exp: &mut dyn Lab) {
    exp.step(Clock::DT_S);
}

/// A random input a student could give: a parameter, an action, a click, a
/// handle moved.
fn random_input(exp: &mut dyn Lab, rng: &mut Lcg64) {
    let view = exp.view();
    let point = DVec2::new(
        rng.range(view.min.x, view.max.x),
        rng.range(view.min.y, view.max.y),
    );
    match rng.int(0, 3) {
        0 => {
            let params = exp.params();
            let spec = params[rng.int(0, params.len() as i64 - 1) as usize];
            // A 512 × 512 grid is the memory test's; here it would only be slow.
            if spec.key != "size" {
                let _ = exp.set_param(spec.key, rng.range(spec.min, spec.max));
            }
        }
        1 if !exp.actions().is_empty() => {
            let actions = exp.actions();
            let key = actions[rng.int(0, actions.len() as i64 - 1) as usize].key;
            let _ = exp.action(key);
        }
        2 => {
            exp.input(Input::PointerDown(point));
            exp.input(Input::PointerUp(point));
        }
        _ => {
            let handles = exp.handles();
            if !handles.is_empty() {
                let id = handles[rng.int(0, handles.len() as i64 - 1) as usize]
                    .id
                    .clone();
                exp.move_handle(&id, point);
            }
        }
    }
}

/// A live run of `steps` steps with random inputs, recorded by a timeline
/// (with a small budget, so thinning happens too): what it showed at each
/// step, and the timeline.
fn live_run(id: &str, seed: u64, steps: u64, budget: usize) -> (Vec<u64>, Timeline) {
    let mut rng = Lcg64::new(seed);
    let mut exp = labcore::testkit::open(id);
    // The run starts going: most experiments need an action or a target.
    for _ in 0..2 {
        random_input(exp.as_mut(), &mut rng);
    }
    let mut timeline = Timeline::with_budget(exp.as_ref(), 0, budget);
    let mut seen = Vec::new();
    for step in 0..=steps {
        if rng.next_f64() < 0.03 {
            timeline.input_at(step);
            random_input(exp.as_mut(), &mut rng);
        }
        seen.push(shown(exp.as_ref()));
        // Before a step, and before going back (the run's end).
        timeline.commit(exp.as_ref());
        if step == steps {
            break;
        }
        exp.step(Clock::DT_S);
        timeline.stepped(exp.as_ref());
    }
    (seen, timeline)
}

fn evolving_ids() -> Vec<&'static str> {
    let ids: Vec<&'static str> = labcore::registry()
        .iter()
        .filter(|e| (e.make)().animated())
        .map(|e| e.id)
        .collect();
    for id in EVOLVING {
        assert!(ids.contains(&id), "{id} evolves and has time controls");
    }
    ids
}

#[test]
fn scrub_exactness_the_state_at_step_k_is_the_live_runs_bit_for_bit() {
    for id in evolving_ids() {
        for seed in 1..=3 {
            // 48 KiB makes every experiment thin its snapshots at least once.
            let (seen, mut timeline) = live_run(id, seed, 360, 48 << 10);
            let mut rng = Lcg64::new(seed * 7919);
            let first = timeline.first();
            for _ in 0..25 {
                let k = rng.int(first as i64, seen.len() as i64 - 1) as u64;
                let (at, lab) = timeline.state_at(k, &mut step_once);
                assert_eq!(at, k);
                assert_eq!(
                    shown(lab.as_ref()),
                    seen[k as usize],
                    "{id} seed {seed}: step {k} differs from the live run's"
                );
            }
            // Stepping on along the record (a replay, Step in the past).
            let from = rng.int(first as i64, seen.len() as i64 - 20) as u64;
            let (_, mut lab) = timeline.state_at(from, &mut step_once);
            let mut at = from;
            while at < timeline.end() {
                at = timeline.forward(&mut lab, at, at + 7, &mut step_once);
                assert_eq!(
                    shown(lab.as_ref()),
                    seen[at as usize],
                    "{id}: forward to {at}"
                );
            }
        }
    }
}

/// A drag forward through the past steps the shown state on where no
/// snapshot (so no input) lies between, and rebuilds it elsewhere: every
/// state is the live run's, and no move replays an interval.
#[test]
fn scrub_forward_a_drag_steps_the_shown_state_on_exactly_within_the_bound() {
    // Across all runs, both ways are taken.
    let mut rebuilt_in_all = 0;
    for id in evolving_ids() {
        let mut stepped_on = 0;
        for seed in 1..=3 {
            let (seen, mut timeline) = live_run(id, seed, 360, 48 << 10);
            let mut rng = Lcg64::new(seed * 104_729);
            let (mut at, mut lab) = timeline.state_at(timeline.first(), &mut step_once);
            let mut rebuilt = 0;
            while at < timeline.end() {
                let to = (at + rng.int(1, 40) as u64).min(timeline.end());
                match timeline.step_on_to(lab.as_mut(), at, to, &mut step_once) {
                    Some(reached) => {
                        assert_eq!(reached, to);
                        stepped_on += 1;
                    }
                    None => {
                        (_, lab) = timeline.state_at(to, &mut step_once);
                        rebuilt += 1;
                    }
                }
                at = to;
                assert_eq!(
                    shown(lab.as_ref()),
                    seen[at as usize],
                    "{id} seed {seed}: step {at} differs from the live run's"
                );
                assert!(
                    timeline.last_replay() < timeline.interval(),
                    "{id}: {} steps replayed to {at}, interval {}",
                    timeline.last_replay(),
                    timeline.interval()
                );
            }
            rebuilt_in_all += rebuilt;
            // Backwards, or beyond the record, is never a step on.
            assert!(timeline
                .step_on_to(lab.as_mut(), at, at - 1, &mut step_once)
                .is_none());
            assert!(timeline
                .step_on_to(lab.as_mut(), at, at + 1, &mut step_once)
                .is_none());
        }
        assert!(stepped_on > 0, "{id}: no drag stepped the state on");
    }
    assert!(rebuilt_in_all > 0, "no drag crossed a snapshot");
}

#[test]
fn scrub_replay_bound_any_step_replays_at_most_the_interval_less_one() {
    for id in evolving_ids() {
        let (seen, mut timeline) = live_run(id, 11, 600, 64 << 10);
        let mut worst = 0;
        for k in timeline.first()..seen.len() as u64 {
            timeline.state_at(k, &mut step_once);
            assert!(
                timeline.last_replay() < timeline.interval(),
                "{id}: step {k} replayed {} steps, interval {}",
                timeline.last_replay(),
                timeline.interval()
            );
            worst = worst.max(timeline.last_replay());
        }
        assert_eq!(worst, timeline.worst_replay());
        println!(
            "{id}: interval {} steps, worst replay {worst} steps, {} snapshots",
            timeline.interval(),
            timeline.snapshots()
        );
    }
}

/// A peek (the page's rehearsal of a scrub) rebuilds the very state a
/// scrub would, and leaves the record's counts as they were.
#[test]
fn scrub_rehearsal_a_peek_is_the_scrubs_state_and_counts_nothing() {
    for id in evolving_ids() {
        let (seen, mut timeline) = live_run(id, 5, 200, 64 << 10);
        let mut rng = Lcg64::new(31);
        for _ in 0..10 {
            let k = rng.int(timeline.first() as i64, seen.len() as i64 - 1) as u64;
            let (last, worst) = (timeline.last_replay(), timeline.worst_replay());
            let peeked = timeline.peek_at(k, &mut step_once);
            assert_eq!(
                (timeline.last_replay(), timeline.worst_replay()),
                (last, worst),
                "{id}: a peek at {k} counted its replay"
            );
            assert_eq!(
                shown(peeked.as_ref()),
                seen[k as usize],
                "{id}: peek at {k}"
            );
            let (_, lab) = timeline.state_at(k, &mut step_once);
            assert_eq!(
                shown(lab.as_ref()),
                shown(peeked.as_ref()),
                "{id}: step {k}"
            );
        }
    }
}

/// RRT*'s step grows a batch of iterations (24 by default), and the
/// workspace sweep's samples a hundredth of its poses (weight 8), so their
/// first intervals are shorter: a scrub replays at most one RRT* batch and
/// three sweep steps, not 31 of either.
#[test]
fn scrub_replay_bound_a_step_that_runs_a_batch_is_snapshot_more_often() {
    let rrt = labcore::testkit::open("rrtstar");
    assert_eq!(rrt.step_weight(), 24);
    assert_eq!(Timeline::first_interval(rrt.as_ref()), 2);
    assert_eq!(Timeline::new(rrt.as_ref(), 0).interval(), 2);
    let sweep = labcore::testkit::open("workspace");
    assert_eq!(sweep.step_weight(), 8);
    assert_eq!(Timeline::first_interval(sweep.as_ref()), 4);
    for id in evolving_ids()
        .into_iter()
        .filter(|id| !["rrtstar", "workspace"].contains(id))
    {
        let exp = labcore::testkit::open(id);
        assert_eq!(
            Timeline::first_interval(exp.as_ref()),
            Timeline::FIRST_INTERVAL,
            "{id}"
        );
    }
}

#[test]
fn scrub_input_in_the_past_starts_a_new_run_from_that_state() {
    let mut exp = labcore::testkit::open("pid");
    let mut timeline = Timeline::new(exp.as_ref(), 0);
    for _ in 0..100 {
        exp.step(Clock::DT_S);
        timeline.stepped(exp.as_ref());
    }
    let (at, mut past) = timeline.state_at(40, &mut step_once);
    assert_eq!(at, 40);
    timeline.input_at(40);
    past.set_param("kp", 60.0).unwrap();
    timeline.commit(past.as_ref());
    assert_eq!(timeline.end(), 40, "the old future is dropped");
    let expected = shown(past.as_ref());
    for _ in 0..10 {
        past.step(Clock::DT_S);
        timeline.stepped(past.as_ref());
    }
    let (_, again) = timeline.state_at(40, &mut step_once);
    assert_eq!(shown(again.as_ref()), expected);
    assert_eq!(again.param("kp"), Some(60.0));
}

/// Issue 53 §2, "pinned runs stay": PID pinned at step 100, the moment at
/// step 40 shown with the end's comparisons (as the page shows it) has the
/// pin, and stepped on to step 100 it is the run's end, pin and all: a
/// comparison never changes how the run steps.
#[test]
fn a_past_moment_with_its_ends_pins_steps_on_to_the_end_exactly() {
    let mut exp = labcore::testkit::open("pid");
    let mut timeline = Timeline::new(exp.as_ref(), 0);
    for _ in 0..100 {
        exp.step(Clock::DT_S);
        timeline.stepped(exp.as_ref());
    }
    timeline.input_at(100);
    exp.action("pin").unwrap();
    timeline.commit(exp.as_ref());
    let pin = |lab: &dyn Lab| labcore::experiment::readout_value(lab, "pinA");
    let pinned = pin(exp.as_ref()).unwrap();
    assert!(pinned.contains("so far (pinned at 1.67 s)"), "{pinned}");
    let (_, mut past) = timeline.state_at(40, &mut step_once);
    assert_eq!(pin(past.as_ref()), None, "the record has no pin before it");
    past.take_comparisons(exp.as_any());
    assert_eq!(pin(past.as_ref()), Some(pinned));
    for _ in 40..100 {
        past.step(Clock::DT_S);
    }
    assert_eq!(shown(past.as_ref()), shown(exp.as_ref()));
    // Another experiment's state is no source of pins.
    let before = shown(past.as_ref());
    past.take_comparisons(labcore::testkit::open("cartpole").as_any());
    assert_eq!(shown(past.as_ref()), before);
}

/// Issue 53 §2, "its link reopens both": the snapshot A* keeps where its
/// search ends (its work phase) is no input, so a moment of the drive that
/// follows is still the run's start (Plan pressed there) stepped on, and a
/// link names it; the report of astar scrubbed into the drive lost `at=`.
#[test]
fn a_work_phase_snapshot_leaves_the_link_of_a_later_moment() {
    let mut exp = labcore::testkit::open("astar");
    let mut timeline = Timeline::new(exp.as_ref(), 0);
    timeline.input_at(0);
    exp.action("plan").unwrap();
    timeline.acted("plan");
    timeline.commit(exp.as_ref());
    let mut searched = None;
    for step in 1..=2000 {
        exp.step(Clock::DT_S);
        timeline.stepped(exp.as_ref());
        if searched.is_none() && exp.work_phase() == 0 {
            searched = Some(step);
        }
        if searched.is_some_and(|s| step > s + 30) {
            break;
        }
    }
    let searched = searched.expect("the search ends");
    assert!(
        timeline.unbroken_to(searched + 30),
        "searched at {searched}"
    );
    assert_eq!(timeline.start_actions(), ["plan"]);
    // The moment there, stepped on from the start, is the state recorded.
    let (_, there) = timeline.state_at(searched + 10, &mut step_once);
    let mut again = labcore::testkit::open("astar");
    again.action("plan").unwrap();
    for _ in 0..searched + 10 {
        again.step(Clock::DT_S);
    }
    assert_eq!(shown(there.as_ref()), shown(again.as_ref()));
}

/// Issue 26 §2, the link's moment: a state is the start stepped on only
/// while no input came on the way; after one, a link of the start and a
/// time would not reproduce it.
#[test]
fn link_moment_unbroken_only_while_no_input_came_on_the_way() {
    let mut exp = labcore::testkit::open("pid");
    let mut timeline = Timeline::new(exp.as_ref(), 0);
    // The link's own parameters, applied at the start, are the start.
    timeline.input_at(0);
    exp.set_param("kp", 30.0).unwrap();
    timeline.commit(exp.as_ref());
    for _ in 0..50 {
        exp.step(Clock::DT_S);
        timeline.stepped(exp.as_ref());
    }
    assert!(timeline.unbroken_to(50));
    timeline.input_at(50);
    exp.set_param("kp", 60.0).unwrap();
    timeline.commit(exp.as_ref());
    for _ in 0..10 {
        exp.step(Clock::DT_S);
        timeline.stepped(exp.as_ref());
    }
    assert!(timeline.unbroken_to(49));
    assert!(!timeline.unbroken_to(50));
    assert!(!timeline.unbroken_to(60));
}

/// Issue 53 §8, "A paused run's link after an input": pid, 100 steps,
/// paused, Kp typed: until the next commit the record still looked
/// unbroken to step 100, so the page wrote `at=1.67` for a state the link
/// does not reproduce. An input on its way breaks the run at its step.
#[test]
fn a_paused_runs_link_after_an_input_names_no_moment_before_the_commit() {
    let mut exp = labcore::testkit::open("pid");
    let mut timeline = Timeline::new(exp.as_ref(), 0);
    for _ in 0..100 {
        exp.step(Clock::DT_S);
        timeline.stepped(exp.as_ref());
    }
    assert!(timeline.unbroken_to(100));
    timeline.input_at(100);
    exp.set_param("kp", 60.0).unwrap();
    assert!(!timeline.unbroken_to(100), "the input is on its way");
    assert!(timeline.unbroken_to(99));
    timeline.commit(exp.as_ref());
    assert!(!timeline.unbroken_to(100));
    // An input at the start is the start (a link's own parameters).
    let mut fresh = Timeline::new(exp.as_ref(), 0);
    fresh.input_at(0);
    assert!(fresh.unbroken_to(0));
}

/// Issue 53 §1 and §3: a change that starts the run again (the main
/// plot's progress goes back) is told from one that goes on from the
/// moment, and the run it leaves is named as the restart it is.
#[test]
fn a_restart_is_told_from_a_branch_and_named_as_a_restart() {
    use labcore::timeline::{plot_x, restart_label, restarted};
    assert!(restarted(Some(0.5), Some(0.0)));
    assert!(restarted(Some(3.0), None));
    assert!(!restarted(Some(0.5), Some(0.5)));
    assert!(!restarted(None, None));
    assert!(!restarted(None, Some(0.0)));
    let main_x = |lab: &dyn Lab| lab.plots().first().and_then(plot_x);
    // pid: every parameter replays the step from x = 0.
    let mut pid = labcore::testkit::open("pid");
    labcore::testkit::run_for(&mut *pid, 0.5);
    let (x, before) = (main_x(pid.as_ref()), params(pid.as_ref()));
    pid.set_param("kd", 10.0).unwrap();
    assert!(restarted(x, main_x(pid.as_ref())));
    assert_eq!(
        restart_label(pid.params(), &before, &params(pid.as_ref()), None),
        "before Kd 6 N·s/m → 10 N·s/m restarted the run"
    );
    // cartpole: a gain acts on the running pole, from that moment.
    let mut pole = labcore::testkit::open("cartpole");
    labcore::testkit::run_for(&mut *pole, 0.5);
    let x = main_x(pole.as_ref());
    pole.set_param("kth", 60.0).unwrap();
    assert!(!restarted(x, main_x(pole.as_ref())));
    pole.action("nudge").unwrap();
    assert!(!restarted(x, main_x(pole.as_ref())));
    pole.set_param("th0", 10.0).unwrap();
    assert!(restarted(x, main_x(pole.as_ref())));
}

fn params(lab: &dyn Lab) -> Vec<Option<f64>> {
    lab.params().iter().map(|s| lab.param(s.key)).collect()
}

/// Issue 26 §1, plots lead to the scene: a point of any plot of a run
/// (its x, a time or an iteration) names the step whose plot reached
/// nearest it, found on one snapshot's copy with at most an interval of
/// steps, for every evolving experiment.
#[test]
fn plot_point_to_step_finds_the_step_whose_plot_is_nearest_the_point() {
    use labcore::timeline::plot_x;
    for id in evolving_ids() {
        let mut rng = Lcg64::new(26);
        let mut exp = labcore::testkit::open(id);
        for _ in 0..2 {
            random_input(exp.as_mut(), &mut rng);
        }
        let mut timeline = Timeline::with_budget(exp.as_ref(), 0, 48 << 10);
        timeline.commit(exp.as_ref());
        let mut xs: Vec<Vec<Option<f64>>> = Vec::new();
        for _ in 0..300 {
            xs.push(exp.plots().iter().map(plot_x).collect());
            exp.step(Clock::DT_S);
            timeline.stepped(exp.as_ref());
        }
        xs.push(exp.plots().iter().map(plot_x).collect());
        for (i, plot) in exp.plots().iter().enumerate() {
            let Some(main) = plot.series.iter().find(|s| !s.comparison && !s.is_empty()) else {
                continue;
            };
            for _ in 0..5 {
                let j = rng.int(0, main.len() as i64 - 1) as usize;
                // A point between two samples, too.
                let x = main.x[j]
                    + rng.range(-0.4, 0.4) * (main.x[j.min(main.len() - 2) + 1] - main.x[j]).abs();
                let step = timeline
                    .step_at_plot_x(i, x, &mut step_once)
                    .unwrap_or_else(|| panic!("{id} plot {i}: a step for x = {x}"));
                let best = xs
                    .iter()
                    .filter_map(|p| p[i])
                    .map(|px| (px - x).abs())
                    .fold(f64::INFINITY, f64::min);
                let got = xs[step as usize][i].map(|px| (px - x).abs());
                assert_eq!(got, Some(best), "{id} plot {i}: x = {x}, step {step}");
            }
        }
    }
}

/// Issue 26 §2: a branch's kept run is named after what changed, where, in
/// the parameter's own words and units; the plots keep a place for every
/// kept run from the start, named once filled, the oldest dropped first.
#[test]
fn branching_keeps_the_abandoned_run_and_names_it_exactly() {
    use labcore::timeline::{branch_label, keep, with_kept, KeptRun, MAX_KEPT};
    let mut exp = labcore::testkit::open("pid");
    let specs = exp.params();
    let values =
        |e: &dyn Lab| -> Vec<Option<f64>> { specs.iter().map(|s| e.param(s.key)).collect() };
    exp.set_param("kp", 20.0).unwrap();
    for _ in 0..300 {
        exp.step(Clock::DT_S);
    }
    let before = values(exp.as_ref());
    let abandoned = exp.snapshot();
    exp.set_param("kp", 60.0).unwrap();
    let label = branch_label(specs, &before, &values(exp.as_ref()), None, 2.1);
    assert_eq!(label, "before Kp 20 N/m → 60 N/m at t = 2.10 s");
    // Without a changed parameter, the action (or "the change") names it.
    assert_eq!(
        branch_label(specs, &before, &before, Some("Pin run"), 0.5),
        "before Pin run at t = 0.50 s"
    );
    assert_eq!(
        branch_label(specs, &before, &before, None, 12.0),
        "before the change at t = 12.00 s"
    );
    let run = KeptRun::of(abandoned.as_ref(), label.clone());
    let response = &abandoned.plots()[0].series[0];
    assert_eq!(run.series[0].as_ref(), Some(response));
    // The plots as shown: every plot ends with MAX_KEPT comparison places.
    let mut kept = Vec::new();
    let empty = with_kept(exp.plots(), &kept, 0);
    for (shown, own) in empty.iter().zip(exp.plots()) {
        assert_eq!(shown.series.len(), own.series.len() + MAX_KEPT);
        assert!(shown.series[own.series.len()..]
            .iter()
            .all(|s| s.comparison && s.is_empty()));
    }
    keep(&mut kept, run);
    let shown = with_kept(exp.plots(), &kept, 1);
    let slot = &shown[0].series[exp.plots()[0].series.len()];
    assert_eq!(slot.label, label);
    assert_eq!((&slot.x, &slot.y), (&response.x, &response.y));
    assert_ne!(shown[0].revision, empty[0].revision, "a kept run redraws");
    // Drawn unlike every live curve of its plot (PID's effort plot has
    // four roles of its own; its response plot, five with the pins).
    for plot in &shown {
        let own = &plot.series[..plot.series.len() - MAX_KEPT];
        for kept in &plot.series[own.len()..] {
            assert!(
                own.iter()
                    .filter(|s| !s.comparison)
                    .all(|s| s.role != kept.role),
                "{}: {:?}",
                plot.key,
                kept.role
            );
        }
        let first = &plot.series[own.len()];
        assert!(
            own.iter().all(|s| s.role != first.role),
            "{}: a role of its own",
            plot.key
        );
    }
    for k in 0..MAX_KEPT {
        keep(&mut kept, KeptRun::of(exp.as_ref(), format!("run {k}")));
    }
    assert_eq!(kept.len(), MAX_KEPT);
    assert_eq!(kept[0].label, "run 0", "the oldest went first");
}

/// Issue 26 §2: where the scene has a trail, the run a branch left behind
/// is drawn as a ghost: dimmed and dashed, not told by colour alone.
#[test]
fn a_kept_run_draws_its_trail_as_a_dashed_ghost() {
    use labcore::timeline::KeptRun;
    use labcore::{Item, Role, Scene};
    for id in ["diffdrive", "potential"] {
        let mut rng = Lcg64::new(5);
        let mut exp = labcore::testkit::open(id);
        let mut run = KeptRun::of(exp.as_ref(), String::new());
        for attempt in 0..20 {
            random_input(exp.as_mut(), &mut rng);
            for _ in 0..120 {
                exp.step(Clock::DT_S);
            }
            run = KeptRun::of(exp.as_ref(), String::new());
            if !run.trails.is_empty() || attempt == 19 {
                break;
            }
        }
        assert!(!run.trails.is_empty(), "{id} leaves a trail");
        let mut scene = Scene::default();
        run.ghosts(&mut scene);
        assert_eq!(scene.items.len(), run.trails.len());
        for item in &scene.items {
            assert!(
                matches!(
                    item,
                    Item::Polyline {
                        role: Role::Ghost,
                        dashed: true,
                        ..
                    }
                ),
                "{id}: {item:?}"
            );
        }
    }
}

/// The link the Simulation tab writes for a paused run at `step`
/// (`labweb/src/sim/mod.rs`, `state_link`): where the record says a link
/// of the start reproduces the moment, the start's parameters and set-up
/// and `at=`; else the state's.
fn paused_link(live: &dyn Lab, timeline: &Timeline, step: u64) -> String {
    let start = timeline.link_start(live, step).filter(|_| step > 0);
    let mut link = labcore::route::format(start.unwrap_or(live), labcore::route::Tab::Simulation);
    if start.is_some() {
        link.push(if link.contains('?') { '&' } else { '?' });
        link.push_str(&format!("run=0&at={:.2}", step as f64 * Clock::DT_S));
        if !timeline.start_actions().is_empty() {
            link.push_str(&format!("&do={}", timeline.start_actions().join(",")));
        }
        let inputs = timeline.inputs_link(step);
        if !inputs.is_empty() {
            link.push_str(&format!("&then={inputs}"));
        }
    }
    link
}

/// [`shown`] but for the plots' redraw counters (`Plot::revision`): a
/// link's parameters, set one by one, count more redraws than the run did.
fn shown_again(exp: &dyn Lab) -> u64 {
    let plots: Vec<_> = exp
        .plots()
        .iter()
        .cloned()
        .map(|mut p| {
            p.revision = 0;
            p
        })
        .collect();
    let text = format!(
        "{:?}|{:?}|{:?}|{:?}|{:?}|{:?}",
        scene_of(exp),
        exp.readouts(),
        exp.status(),
        exp.tables(),
        plots,
        exp.handles(),
    );
    let mut h = DefaultHasher::new();
    text.hash(&mut h);
    h.finish()
}

/// Opens `link` as a fresh page does: its parameters and set-up, then its
/// actions (`do=`), are the start, stepped on to its `at=`.
fn open_paused_link(id: &str, link: &str) -> Box<dyn Lab> {
    let mut exp = labcore::testkit::open(id);
    // `run`, `at` and `do` are the shell's (labweb's `apply_params`).
    let notices = labcore::testkit::apply_link(exp.as_mut(), link);
    assert!(
        notices.iter().all(|n| ["“run”", "“at”", "“do”", "“then”"]
            .iter()
            .any(|k| n.contains(k))),
        "{link}: {notices:?}"
    );
    let actions = link.split(['?', '&']).find_map(|p| p.strip_prefix("do="));
    for key in actions.into_iter().flat_map(|a| a.split(',')) {
        exp.action(key).unwrap();
    }
    let at = link
        .split(['?', '&'])
        .find_map(|p| p.strip_prefix("at="))
        .map_or(0.0, |t| t.parse::<f64>().unwrap());
    // The inputs during the run (`then=`), each at its step.
    let then = link.split(['?', '&']).find_map(|p| p.strip_prefix("then="));
    let mut inputs = run_input::parse(then.unwrap_or(""))
        .unwrap()
        .into_iter()
        .peekable();
    let end = (at / Clock::DT_S).round() as u64;
    for step in 0..=end {
        while let Some((_, input)) = inputs.next_if(|(s, _)| *s == step) {
            let _ = input.apply(exp.as_mut());
        }
        if step < end {
            exp.step(Clock::DT_S);
        }
    }
    assert!(inputs.next().is_none(), "{link}: an input after the moment");
    exp
}

/// Issue 53 §8, ik: the joint angles are parameters the run moves. Drag
/// the target at step 0, 13 steps, pause: the `at=` link carried the
/// moment's angles with the start's time, so it reopened another pose
/// (x 0.309 m for 0.550 m). A link reopens exactly the state shown.
#[test]
fn an_at_link_carries_the_starts_parameters_where_the_run_moves_them() {
    let mut exp = labcore::testkit::open("ik");
    let mut timeline = Timeline::new(exp.as_ref(), 0);
    timeline.input_at(0);
    assert!(exp.move_handle("target", DVec2::new(0.55, 0.9)));
    timeline.commit(exp.as_ref());
    for _ in 0..13 {
        exp.step(Clock::DT_S);
        timeline.stepped(exp.as_ref());
    }
    let link = paused_link(exp.as_ref(), &timeline, 13);
    assert!(link.contains("at=0.22"), "{link}");
    let reopened = open_paused_link("ik", &link);
    assert_eq!(
        exp.readouts(),
        reopened.readouts(),
        "{link} reopens another pose"
    );
    assert_eq!(
        shown_again(exp.as_ref()),
        shown_again(reopened.as_ref()),
        "{link}"
    );
}

/// Issue 53 §8: an action at step 0 is part of the start (workspace Sweep,
/// astar Plan and Compare, pid Pin, …), but no link carried it: 30 steps
/// on, the `at=` link reopened "ready to sweep", "ready: press Plan &
/// drive", one pin fewer. Every action of every evolving experiment,
/// pressed at the start, round-trips through the paused run's link.
#[test]
fn an_action_at_the_start_is_carried_by_the_link_of_a_moment() {
    let mut carried = std::collections::BTreeSet::new();
    for id in evolving_ids() {
        for action in labcore::testkit::open(id).actions() {
            let mut exp = labcore::testkit::open(id);
            let mut timeline = Timeline::new(exp.as_ref(), 0);
            timeline.input_at(0);
            exp.action(action.key).unwrap();
            timeline.acted(action.key);
            timeline.commit(exp.as_ref());
            for _ in 0..30 {
                exp.step(Clock::DT_S);
                timeline.stepped(exp.as_ref());
            }
            let link = paused_link(exp.as_ref(), &timeline, 30);
            if !link.contains("at=") {
                continue;
            }
            let reopened = open_paused_link(id, &link);
            carried.insert(id);
            assert_eq!(
                shown_again(exp.as_ref()),
                shown_again(reopened.as_ref()),
                "{id}, {} at the start: {link} reopens {:?} for {:?}",
                action.key,
                reopened.status(),
                exp.status()
            );
        }
    }
    assert!(carried.len() >= 7, "{carried:?}");
    // A parameter set after an action at the start: a link sets its
    // parameters first, so no link of the start reproduces it.
    let mut pid = labcore::testkit::open("pid");
    let mut timeline = Timeline::new(pid.as_ref(), 0);
    timeline.input_at(0);
    pid.action("pin").unwrap();
    timeline.acted("pin");
    timeline.input_at(0);
    pid.set_param("kp", 60.0).unwrap();
    assert!(!timeline.unbroken_to(0));
    timeline.commit(pid.as_ref());
    pid.step(Clock::DT_S);
    timeline.stepped(pid.as_ref());
    assert!(!timeline.unbroken_to(1));
}

/// A random input a student could give during a run, as the page gives it
/// and a link carries it: a parameter, an action, a press, drag and
/// release, a handle moved.
fn random_run_inputs(exp: &dyn Lab, rng: &mut Lcg64) -> Vec<RunInput> {
    let view = exp.view();
    let mut point = || {
        DVec2::new(
            rng.range(view.min.x, view.max.x),
            rng.range(view.min.y, view.max.y),
        )
    };
    let (a, b) = (point(), point());
    let pointer = |i| RunInput::Pointer(i, Modifiers::default());
    let pick = rng.int(0, 3);
    match pick {
        0 => {
            let params = exp.params();
            let spec = params[rng.int(0, params.len() as i64 - 1) as usize];
            if spec.key == "size" {
                return Vec::new();
            }
            vec![RunInput::Param(
                spec.key.into(),
                rng.range(spec.min, spec.max),
            )]
        }
        1 if !exp.actions().is_empty() => {
            let actions = exp.actions();
            let key = actions[rng.int(0, actions.len() as i64 - 1) as usize].key;
            vec![RunInput::Action(key.into())]
        }
        2 => vec![
            pointer(Input::PointerDown(a)),
            pointer(Input::PointerMove {
                pos: (a + b) / 2.0,
                pressed: true,
            }),
            pointer(Input::PointerUp(b)),
        ],
        _ => exp
            .handles()
            .first()
            .map(|h| vec![RunInput::Handle(h.id.clone(), a)])
            .unwrap_or_default(),
    }
}

/// Issue 53: a moment after an input made during the run (cart-pole's
/// Nudge pole, a drag in RRT*) had no link: `at=` was left out, silently.
/// Every evolving experiment, run with random inputs at random steps (as
/// the page records them), paused at a random later moment: the link names
/// the moment and its inputs (`then=`), and reopens it bit for bit. Seeded.
#[test]
fn a_moment_after_inputs_during_the_run_round_trips_through_its_link() {
    let mut rng = Lcg64::new(5_300);
    let mut linked = 0;
    for id in evolving_ids() {
        for _ in 0..6 {
            let mut exp = labcore::testkit::open(id);
            let mut timeline = Timeline::new(exp.as_ref(), 0);
            let mut step = 0;
            for _ in 0..rng.int(1, 3) {
                for _ in 0..rng.int(1, 40) {
                    exp.step(Clock::DT_S);
                    step += 1;
                    timeline.stepped(exp.as_ref());
                }
                for input in random_run_inputs(exp.as_ref(), &mut rng) {
                    timeline.input_at(step);
                    let _ = input.apply(exp.as_mut());
                    timeline.linked(input);
                }
                timeline.commit(exp.as_ref());
            }
            for _ in 0..rng.int(1, 40) {
                exp.step(Clock::DT_S);
                step += 1;
                timeline.stepped(exp.as_ref());
            }
            assert!(timeline.unbroken_to(step), "{id}: every input was linked");
            let link = paused_link(exp.as_ref(), &timeline, step);
            assert!(link.contains("&at="), "{id}: {link}");
            let reopened = open_paused_link(id, &link);
            assert_eq!(
                shown_again(exp.as_ref()),
                shown_again(reopened.as_ref()),
                "{id}: {link} reopens {:?} for {:?}",
                reopened.status(),
                exp.status()
            );
            linked += usize::from(link.contains("then="));
        }
    }
    assert!(linked >= 40, "{linked} links carried inputs");
}

/// An input the record was not told how to carry (a file, a reset) still
/// breaks the link of every moment from its step on, and a linked one
/// after it does not mend it; going back before it does.
#[test]
fn an_input_no_link_carries_breaks_the_moments_after_it() {
    let mut exp = labcore::testkit::open("cartpole");
    let mut timeline = Timeline::new(exp.as_ref(), 0);
    let mut step = 0;
    let mut run = |exp: &mut Box<dyn Lab>, timeline: &mut Timeline, n: u64| {
        for _ in 0..n {
            exp.step(Clock::DT_S);
            step += 1;
            timeline.stepped(exp.as_ref());
        }
        step
    };
    let at = run(&mut exp, &mut timeline, 30);
    timeline.input_at(at);
    exp.action("nudge").unwrap();
    timeline.acted("nudge");
    timeline.commit(exp.as_ref());
    let at = run(&mut exp, &mut timeline, 30);
    assert!(timeline.unbroken_to(at));
    assert_eq!(timeline.inputs_link(at), "0.50:a:nudge");
    // Unlinked (no `linked` call): breaks from its step on.
    timeline.input_at(at);
    timeline.commit(exp.as_ref());
    let end = run(&mut exp, &mut timeline, 10);
    assert!(timeline.unbroken_to(at - 1));
    assert!(!timeline.unbroken_to(at) && !timeline.unbroken_to(end));
    assert!(timeline.inputs_link(end).is_empty());
    timeline.input_at(end);
    timeline.linked(RunInput::Action("nudge".into()));
    assert!(!timeline.unbroken_to(end));
    // A new run from before it drops it with the future.
    timeline.input_at(40);
    timeline.linked(RunInput::Action("nudge".into()));
    timeline.commit(exp.as_ref());
    assert!(timeline.unbroken_to(40));
    assert_eq!(timeline.inputs_link(40), "0.50:a:nudge;0.67:a:nudge");
}
