//! Issue 26 §1 in the page: the timeline slider, Step back (`,`) and Run to
//! end (`End`) of the time bar, with the frames driven by the test (as in
//! `runs.rs`), so no step depends on the wall clock.

use labcore::clock::Clock;
use labcore::Phase;
use wasm_bindgen::JsCast;
use wasm_bindgen_test::*;
use web_sys::HtmlInputElement;

mod page;
use page::{
    attr, element, frame, hash, left_alone, mount, press_key_on_canvas, shown, snapshot, text,
    ONE_STEP_MS,
};

wasm_bindgen_test_configure!(run_in_browser);

/// Moves the timeline slider to `step` as a drag (or its keys) does.
fn scrub_to(step: u64) {
    let slider: HtmlInputElement = element(".tb-scrub").dyn_into().unwrap();
    slider.set_value(&step.to_string());
    let event = web_sys::Event::new_with_event_init_dict("input", &{
        let init = web_sys::EventInit::new();
        init.set_bubbles(true);
        init
    })
    .unwrap();
    slider.dispatch_event(&event).unwrap();
    labweb::paint_now();
}

fn steps_shown() -> u64 {
    shown().0
}

/// Issue 26 §1, the timeline: after a run, dragging the slider back shows
/// the run at that step (status, readouts, plots up to it, the scene's
/// description) exactly as the run had it, pauses, and the slider speaks
/// the time and the main readout.
#[wasm_bindgen_test]
fn timeline_slider_shows_step_k_exactly_as_the_run_had_it_and_pauses() {
    mount("#/pid/simulation");
    let entry = labcore::find("pid").unwrap();
    for _ in 0..120 {
        frame(ONE_STEP_MS);
    }
    labweb::paint_now();
    let end = steps_shown();
    assert!(end >= 100, "{end} steps");
    assert_eq!(attr(".tb-scrub", "max"), Some(end.to_string()));
    scrub_to(40);
    assert_eq!(shown(), (40, snapshot(left_alone(entry, 40).as_ref())));
    assert_eq!(attr(".sim-status", "data-clock").as_deref(), Some("paused"));
    assert_eq!(text(".tb-time"), format!("t = {:.2} s", 40.0 * Clock::DT_S));
    let spoken = attr(".tb-scrub", "aria-valuetext").unwrap_or_default();
    let main = labweb::inspect_sim(|exp, _| exp.readouts()[0].clone()).unwrap();
    assert_eq!(
        spoken,
        format!(
            "t = {:.2} s, {} = {}",
            40.0 * Clock::DT_S,
            main.label,
            main.value
        )
    );
    // Paused there: frames change nothing.
    frame(ONE_STEP_MS);
    assert_eq!(steps_shown(), 40);
    // Forward again to the end of the record: the run's last state.
    scrub_to(end);
    assert_eq!(shown(), (end, snapshot(left_alone(entry, end).as_ref())));
}

/// Issue 26 §1, Step back: the button and `,` go back one model step (one
/// filter cycle of the EKF); `.` goes forward along the record.
#[wasm_bindgen_test]
fn step_back_button_and_comma_key_go_back_one_model_step() {
    mount("#/ekf/simulation");
    let entry = labcore::find("ekf").unwrap();
    let cycle = u64::from(Clock::fixed_steps_in(entry_step(entry)));
    for _ in 0..90 {
        frame(ONE_STEP_MS);
    }
    labweb::paint_now();
    let end = steps_shown();
    element("[data-time=back]").click();
    labweb::paint_now();
    assert_eq!(
        shown(),
        (
            end - cycle,
            snapshot(left_alone(entry, end - cycle).as_ref())
        )
    );
    press_key_on_canvas(",");
    labweb::paint_now();
    let two_back = end - 2 * cycle;
    assert_eq!(
        shown(),
        (two_back, snapshot(left_alone(entry, two_back).as_ref()))
    );
    let slider: HtmlInputElement = element(".tb-scrub").dyn_into().unwrap();
    assert_eq!(slider.value(), two_back.to_string());
    // The slider to a second before: `.` then steps on along the record.
    let one_back = end - cycle;
    let second_back = one_back - 60;
    scrub_to(second_back);
    assert_eq!(
        shown(),
        (
            second_back,
            snapshot(left_alone(entry, second_back).as_ref())
        )
    );
    press_key_on_canvas(".");
    labweb::paint_now();
    let one_back = second_back + cycle;
    assert_eq!(
        shown(),
        (one_back, snapshot(left_alone(entry, one_back).as_ref()))
    );
}

fn entry_step(entry: &labcore::Entry) -> f64 {
    (entry.make)().natural_step_s()
}

/// Issue 26 §1, Run to end: the button finishes a PID run over a few
/// frames (each bounded), at the step the run ends however it is reached;
/// then the timeline scrubs back through it.
#[wasm_bindgen_test]
fn run_to_end_button_finishes_the_run_and_the_timeline_spans_it() {
    mount("#/pid/simulation?run=0");
    let entry = labcore::find("pid").unwrap();
    let mut alone = (entry.make)();
    let mut end = 0;
    while alone.status().phase != Phase::Ended {
        alone.step(Clock::DT_S);
        end += 1;
    }
    element("[data-time=end]").click();
    let mut frames = 0;
    while labweb::inspect_sim(|exp, _| exp.status().phase != Phase::Ended).unwrap() {
        frame(ONE_STEP_MS);
        frames += 1;
        assert!(frames < 100, "the run ends");
    }
    labweb::paint_now();
    assert_eq!(shown(), (end, snapshot(alone.as_ref())));
    assert_eq!(attr(".tb-scrub", "max"), Some(end.to_string()));
    scrub_to(end / 2);
    assert_eq!(
        shown(),
        (end / 2, snapshot(left_alone(entry, end / 2).as_ref()))
    );
}

/// Issue 26 §1, Run to end for A*: `End` finishes the search at once (no
/// watching), and Step back then goes back one expansion step.
#[wasm_bindgen_test]
fn end_key_finishes_the_astar_search_and_step_back_undoes_one_step() {
    mount("#/astar/simulation");
    let entry = labcore::find("astar").unwrap();
    element("[data-action=plan]").click();
    press_key_on_canvas("End");
    let mut frames = 0;
    while labweb::inspect_sim(|exp, _| exp.animating()).unwrap() {
        frame(ONE_STEP_MS);
        frames += 1;
        assert!(frames < 200, "the search ends");
    }
    labweb::paint_now();
    let end = steps_shown();
    let planned = |steps: u64| {
        let mut exp = (entry.make)();
        exp.action("plan").unwrap();
        for _ in 0..steps {
            exp.step(Clock::DT_S);
        }
        snapshot(exp.as_ref())
    };
    assert!(end > 1, "{end} steps");
    assert_eq!(shown(), (end, planned(end)));
    press_key_on_canvas(",");
    labweb::paint_now();
    assert_eq!(shown(), (end - 1, planned(end - 1)));
}

/// Issue 26 §2, the moment in the link: a paused run's link carries the
/// time shown (`at=`), and opening it shows that moment exactly: the
/// steps, status, readouts, plots up to it and the scene's description.
#[wasm_bindgen_test]
fn at_in_the_link_reopens_the_moment_shown_exactly() {
    mount("#/pid/simulation?kp=40&kd=2");
    for _ in 0..100 {
        frame(ONE_STEP_MS);
    }
    scrub_to(41);
    let there = shown();
    assert_eq!(there.0, 41);
    // The link is written at its pace (frames while paused take no step).
    frame(300.0);
    frame(300.0);
    let link = hash();
    assert!(link.contains("at=0.68"), "{link}");
    assert!(link.contains("run=0"), "{link}");
    mount(&link);
    // Equal but for the plots' redraw counters (`revision`), which count
    // the link's parameter writes too: they are the page's, not the run's.
    let without_revisions = |(steps, text): (u64, String)| {
        let text: Vec<String> = text
            .split("revision: ")
            .map(|part| {
                part.trim_start_matches(|c: char| c.is_ascii_digit())
                    .to_owned()
            })
            .collect();
        (steps, text.join("revision: _"))
    };
    assert_eq!(
        without_revisions(shown()),
        without_revisions(there),
        "{link}"
    );
    // Still paused there, and the timeline spans the steps to it.
    frame(ONE_STEP_MS);
    labweb::paint_now();
    assert_eq!(shown().0, 41);
    assert_eq!(attr(".tb-scrub", "max"), Some("41".into()));
}
