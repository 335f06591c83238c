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

/// Runs the mounted simulation for `frames` frames of one step each and
/// paints: the steps shown then (the record's end).
fn run_for_frames(frames: usize) -> u64 {
    for _ in 0..frames {
        frame(ONE_STEP_MS);
    }
    labweb::paint_now();
    steps_shown()
}

/// Issue 26 §1, the timeline: after a run, dragging the slider back shows
/// the run at that step (status, readouts, plots up to it, the scene's
/// description) exactly as the run had it, pauses, and the slider speaks
/// the time and the main readout.
#[wasm_bindgen_test]
fn timeline_slider_shows_step_k_exactly_as_the_run_had_it_and_pauses() {
    mount("#/pid/simulation");
    let entry = labcore::find("pid").unwrap();
    let end = run_for_frames(120);
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

/// The address of the mounted model: the same while the page steps it on,
/// another once it is rebuilt from a snapshot.
fn model_address() -> usize {
    labweb::inspect_sim(|exp, _| std::ptr::from_ref(exp).cast::<u8>() as usize).unwrap()
}

/// A drag forward through the past steps the state shown on where no
/// snapshot lies between (no copy, no replay from a snapshot), rebuilds it
/// where one does, and shows every step exactly as the run had it.
#[wasm_bindgen_test]
fn a_drag_forward_through_the_past_steps_the_shown_state_on_exactly() {
    mount("#/pid/simulation");
    let entry = labcore::find("pid").unwrap();
    let end = run_for_frames(120);
    // pid's snapshots are 32 steps apart: 33 is rebuilt from the one at 32.
    scrub_to(33);
    let model = model_address();
    for k in 34..=40 {
        scrub_to(k);
        assert_eq!(shown(), (k, snapshot(left_alone(entry, k).as_ref())));
        assert_eq!(model_address(), model, "step {k} was rebuilt");
    }
    // Across the snapshot at 64, and back: rebuilt.
    scrub_to(70);
    assert_eq!(shown(), (70, snapshot(left_alone(entry, 70).as_ref())));
    assert_ne!(model_address(), model);
    let model = model_address();
    scrub_to(66);
    assert_eq!(shown(), (66, snapshot(left_alone(entry, 66).as_ref())));
    assert_ne!(model_address(), model);
    // Stepped on to the record's end: the run's last state, and Play goes on
    // from it as the run would have.
    scrub_to(end - 1);
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
    let end = run_for_frames(90);
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

/// Presses Plan on the mounted A* page and End (Run to end), lets the
/// frames finish the search, and returns the step the timeline shows then.
fn plan_and_run_to_end() -> u64 {
    element("[data-action=plan]").click();
    press_key_on_canvas("End");
    let mut frames = 0;
    while labweb::inspect_sim(|exp, _| exp.animating()).unwrap() {
        frame(ONE_STEP_MS);
        frames += 1;
        assert!(frames < 200, "the search ends");
    }
    labweb::paint_now();
    steps_shown()
}

/// Issue 26 §1, Run to end for A*: `End` finishes the search at once (no
/// watching), and Step back then goes back one expansion step.
#[wasm_bindgen_test]
fn end_key_finishes_the_astar_search_and_step_back_undoes_one_step() {
    mount("#/astar/simulation");
    let entry = labcore::find("astar").unwrap();
    let end = plan_and_run_to_end();
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

/// Issue 53 §8: an action at step 0 is part of the run's start, and the
/// link of a moment carries it (`do=`): workspace, Sweep, 30 steps, paused,
/// reopened "ready to sweep" before.
#[wasm_bindgen_test]
fn an_action_at_the_start_travels_in_the_link_of_a_moment() {
    mount("#/workspace/simulation");
    element("[data-action=sweep]").click();
    for _ in 0..30 {
        frame(ONE_STEP_MS);
    }
    element("[data-time=play]").click();
    labweb::paint_now();
    let there = shown();
    frame(300.0);
    frame(300.0);
    let link = hash();
    assert!(link.contains("do=sweep"), "{link}");
    assert!(
        link.contains(&format!("at={:.2}", there.0 as f64 * Clock::DT_S)),
        "{link}"
    );
    mount(&link);
    assert_eq!(
        without_revisions(shown()),
        without_revisions(there),
        "{link}"
    );
    // Its own link again.
    frame(300.0);
    frame(300.0);
    assert_eq!(hash(), link);
}

// ---- Issue 26 §1 (the rest) and §2: plot cursor, plot points, slider
// keys, branches.

fn plot_canvas(key: &str) -> web_sys::HtmlElement {
    element(&format!("figure[data-plot={key}] canvas.plot-canvas"))
}

fn cursor_of(key: &str) -> Option<f64> {
    plot_canvas(key)
        .get_attribute("data-cursor")
        .map(|x| x.parse().unwrap())
}

fn key_on(target: &web_sys::HtmlElement, key: &str) {
    let init = web_sys::KeyboardEventInit::new();
    init.set_key(key);
    init.set_bubbles(true);
    init.set_cancelable(true);
    let event =
        web_sys::KeyboardEvent::new_with_keyboard_event_init_dict("keydown", &init).unwrap();
    target.dispatch_event(&event).unwrap();
    labweb::paint_now();
}

/// A click (or tap) at `fraction` of the plot canvas's width.
fn press_plot(key: &str, fraction: f64) {
    let canvas = plot_canvas(key);
    let rect = canvas.get_bounding_client_rect();
    // A click is a PointerEvent in the browser (a MouseEvent too).
    let init = web_sys::PointerEventInit::new();
    init.set_is_primary(true);
    init.set_pointer_type("mouse");
    init.set_bubbles(true);
    init.set_client_x((rect.left() + fraction * rect.width()) as i32);
    init.set_client_y((rect.top() + rect.height() / 2.0) as i32);
    let click = web_sys::PointerEvent::new_with_event_init_dict("click", &init).unwrap();
    canvas.dispatch_event(&click).unwrap();
    labweb::paint_now();
}

fn plot_xs_of(exp: &dyn labcore::Lab) -> Vec<(&'static str, Option<f64>)> {
    exp.plots()
        .iter()
        .map(|p| (p.key, labcore::timeline::plot_x(p)))
        .collect()
}

/// Issue 26 §1: while the timeline shows a past moment, every plot draws a
/// cursor there (the plot x its run had reached); live at the end, none.
#[wasm_bindgen_test]
fn plot_cursor_marks_the_moment_shown_on_every_plot_and_none_when_live() {
    mount("#/pid/simulation");
    let entry = labcore::find("pid").unwrap();
    let end = run_for_frames(120);
    let keys: Vec<&str> = entry_plot_keys(entry);
    assert!(keys.len() >= 2);
    for key in &keys {
        assert_eq!(cursor_of(key), None, "live: no cursor on {key}");
    }
    scrub_to(40);
    for (key, x) in plot_xs_of(left_alone(entry, 40).as_ref()) {
        assert_eq!(cursor_of(key), x, "{key} at step 40");
        assert!(x.is_some());
    }
    scrub_to(end);
    for key in &keys {
        assert_eq!(cursor_of(key), None, "back at the end: no cursor on {key}");
    }
}

/// A scrub frame leaves the page's structure alone, so the browser only
/// lays out and repaints what changed: the time and a readout are rewritten
/// in their text nodes (not new nodes each time), and a plot's cursor is
/// hidden by `visibility`, not the `hidden` attribute that the style
/// sheet's `:has()` rules name (counts of the browser's own style
/// invalidations: 504 in a 120-jump cartpole drag before, 82 after).
#[wasm_bindgen_test]
fn a_scrub_rewrites_text_in_place_and_hides_a_cursor_without_the_hidden_attribute() {
    mount("#/pid/simulation");
    let end = run_for_frames(120);
    let time = element(".timebar .tb-time");
    let readout = element("dl.readouts dd");
    scrub_to(40);
    let (time_node, readout_node) = (time.first_child().unwrap(), readout.first_child().unwrap());
    let (time_then, readout_then) = (time.text_content(), readout.text_content());
    let cursor = element("figure[data-plot=response] .plot-cursor");
    assert!(!cursor.hidden(), "the cursor is shown in the past");
    scrub_to(90);
    assert_ne!(time.text_content(), time_then, "the time moved");
    assert_ne!(readout.text_content(), readout_then, "the readout moved");
    assert!(time.first_child().unwrap().is_same_node(Some(&time_node)));
    assert!(readout
        .first_child()
        .unwrap()
        .is_same_node(Some(&readout_node)));
    assert_eq!(time.child_nodes().length(), 1);
    scrub_to(end);
    assert_eq!(cursor_of("response"), None, "live again: no cursor");
    assert!(
        !cursor.has_attribute("hidden"),
        "hidden without the attribute"
    );
    assert_eq!(
        cursor.style().get_property_value("visibility").unwrap(),
        "hidden"
    );
    // Hidden, it takes no room where a resize could push it past the plot.
    assert_eq!(
        cursor.style().get_property_value("transform").unwrap(),
        "none"
    );
    assert_eq!(cursor.style().get_property_value("height").unwrap(), "0px");
    scrub_to(40);
    assert_eq!(cursor.style().get_property_value("visibility").unwrap(), "");
}

fn entry_plot_keys(entry: &labcore::Entry) -> Vec<&'static str> {
    (entry.make)().plots().iter().map(|p| p.key).collect()
}

/// Issue 26 §1, plots lead to the scene: a press on a plot point moves the
/// timeline to that moment (the state the run had there), pauses, puts
/// the cursor there and says the moment; a point further left is earlier.
#[wasm_bindgen_test]
fn clicking_a_plot_point_moves_the_timeline_there_and_pauses() {
    mount("#/pid/simulation");
    let entry = labcore::find("pid").unwrap();
    let end = run_for_frames(120);
    press_plot("response", 0.5);
    let (at, state) = shown();
    assert!(at > 0 && at < end, "{at} of {end}");
    assert_eq!(state, snapshot(left_alone(entry, at).as_ref()));
    assert_eq!(attr(".sim-status", "data-clock").as_deref(), Some("paused"));
    let x = plot_xs_of(left_alone(entry, at).as_ref())[0].1;
    assert_eq!(cursor_of("response"), x);
    let said = labweb::inspect_sim(|exp, _| exp.readouts()[0].clone()).unwrap();
    assert_eq!(
        text(".sim-live"),
        format!(
            "t = {:.2} s, {} = {}",
            at as f64 * Clock::DT_S,
            said.label,
            said.value
        )
    );
    // The other plot's points lead there too.
    press_plot("effort", 0.2);
    let earlier = steps_shown();
    assert!(earlier < at, "{earlier} < {at}");
    frame(ONE_STEP_MS);
    assert_eq!(steps_shown(), earlier, "paused there");
}

/// Issue 26 §1: a focused plot moves the timeline point by point with its
/// arrow keys (Left back, Right on), Home and End to its ends.
#[wasm_bindgen_test]
fn a_focused_plots_arrow_keys_move_the_timeline_point_by_point() {
    mount("#/pid/simulation");
    let entry = labcore::find("pid").unwrap();
    let end = run_for_frames(60);
    let canvas = plot_canvas("response");
    assert_eq!(canvas.get_attribute("tabindex").as_deref(), Some("0"));
    let live = left_alone(entry, end);
    let xs = live.plots()[0].series[0].x.clone();
    key_on(&canvas, "ArrowLeft");
    let back = steps_shown();
    assert!(back < end);
    assert_eq!(shown().1, snapshot(left_alone(entry, back).as_ref()));
    // The cursor is on a point of the plot, each Left an earlier one, each
    // Right a later one (a step may add more than one point).
    let on_a_point = |x: Option<f64>| x.is_some_and(|x| xs.contains(&x));
    let first = cursor_of("response");
    assert!(on_a_point(first) && first < xs.last().copied(), "{first:?}");
    key_on(&canvas, "ArrowLeft");
    let second = cursor_of("response");
    assert!(
        on_a_point(second) && second < first,
        "{second:?} < {first:?}"
    );
    assert_eq!(steps_shown(), back - 1, "one step further back");
    key_on(&canvas, "ArrowRight");
    assert_eq!(cursor_of("response"), first);
    assert_eq!(steps_shown(), back);
    key_on(&canvas, "Home");
    assert_eq!(cursor_of("response"), Some(xs[0]));
    key_on(&canvas, "End");
    assert_eq!(steps_shown(), end);
    assert_eq!(cursor_of("response"), None, "live again");
}

/// Issue 26 §1: the slider's own keys. An arrow is one model step (an EKF
/// filter cycle, not one fixed step), Page keys one second; Home and End
/// the record's ends.
#[wasm_bindgen_test]
fn slider_arrows_move_one_model_step_and_page_keys_one_second() {
    mount("#/ekf/simulation");
    let entry = labcore::find("ekf").unwrap();
    let cycle = u64::from(Clock::fixed_steps_in(entry_step(entry)));
    assert!(cycle > 1, "an EKF cycle is several fixed steps");
    let end = run_for_frames(150);
    let slider = element(".tb-scrub");
    key_on(&slider, "ArrowLeft");
    assert_eq!(steps_shown(), end - cycle);
    key_on(&slider, "ArrowRight");
    assert_eq!(steps_shown(), end);
    key_on(&slider, "PageDown");
    assert_eq!(steps_shown(), end - 60);
    assert_eq!(shown().1, snapshot(left_alone(entry, end - 60).as_ref()));
    key_on(&slider, "PageUp");
    assert_eq!(steps_shown(), end);
    key_on(&slider, "Home");
    assert_eq!(steps_shown(), 0);
    key_on(&slider, "End");
    assert_eq!(steps_shown(), end);
}

/// Issue 26 §1: where the plots count iterations (A* expansions), the Page
/// keys move a tenth of the run.
#[wasm_bindgen_test]
fn slider_page_keys_move_a_tenth_of_an_iteration_run() {
    mount("#/astar/simulation");
    let end = plan_and_run_to_end();
    assert!(end >= 10, "{end}");
    let slider = element(".tb-scrub");
    key_on(&slider, "PageDown");
    assert_eq!(steps_shown(), end - end / 10);
}

/// Issue 26 §2: a parameter changed while the timeline shows the past
/// starts a new run there; the old future stays on the plots as a kept
/// run named after the change (pid's replays the step from its start: a
/// restart, issue 53 §3).
#[wasm_bindgen_test]
fn branching_in_the_past_keeps_the_abandoned_run_named_after_the_change() {
    mount("#/pid/simulation");
    let entry = labcore::find("pid").unwrap();
    for _ in 0..150 {
        frame(ONE_STEP_MS);
    }
    labweb::paint_now();
    let old_end = left_alone(entry, steps_shown());
    scrub_to(126);
    let slider: HtmlInputElement = element("input[type=range][data-param=kp]")
        .dyn_into()
        .unwrap();
    slider.set_value("60");
    let init = web_sys::EventInit::new();
    init.set_bubbles(true);
    slider
        .dispatch_event(&web_sys::Event::new_with_event_init_dict("input", &init).unwrap())
        .unwrap();
    frame(ONE_STEP_MS);
    labweb::paint_now();
    let name = "before Kp 12 N/m → 60 N/m restarted the run";
    let legend: Vec<(String, bool)> = page::document()
        .query_selector_all("figure[data-plot=response] .legend-item[data-series]")
        .unwrap()
        .values()
        .into_iter()
        .map(|n| {
            let el: web_sys::Element = n.unwrap().dyn_into().unwrap();
            (
                el.text_content().unwrap_or_default(),
                el.has_attribute("hidden"),
            )
        })
        .collect();
    assert!(legend.contains(&(name.to_owned(), false)), "{legend:?}");
    // The kept curve is the old run's response, on every plot.
    let kept = labcore::timeline::KeptRun::of(old_end.as_ref(), name.to_owned());
    let effort = page::document()
        .query_selector_all("figure[data-plot=effort] .legend-item[data-series]")
        .unwrap();
    let names: Vec<String> = (0..effort.length())
        .map(|i| effort.item(i).unwrap().text_content().unwrap_or_default())
        .collect();
    assert!(names.iter().any(|n| n == name), "{names:?}");
    assert!(kept.series[0].as_ref().is_some_and(|s| !s.is_empty()));
    // The new run goes on from there, live.
    assert_eq!(attr(".tb-scrub", "max"), Some(steps_shown().to_string()));
}

/// The cursor laid over plot `key`: shown, and its x in CSS px from the
/// canvas's left (its transform), else `None` (hidden).
fn cursor_overlay_px(key: &str) -> Option<f64> {
    let el = element(&format!("figure[data-plot={key}] .plot-cursor"));
    // Hidden until first shown, then by `visibility`.
    if el.hidden() || el.style().get_property_value("visibility").unwrap() == "hidden" {
        return None;
    }
    let transform = el.style().get_property_value("transform").unwrap();
    let x = transform
        .trim_start_matches("translate(")
        .split("px")
        .next()
        .unwrap();
    Some(x.parse().unwrap())
}

/// Issue 26 §1, the plot cursor on a long run: the EKF's plots keep a
/// rolling minute, so after 10 minutes the run's record has let the first
/// nine go. Scrubbed back to t = 10 s, every plot still shows that moment
/// (the window the run showed then) with the cursor on it, inside the
/// plot; back at the end, no cursor.
#[wasm_bindgen_test]
fn plot_cursor_is_on_every_plot_even_at_a_moment_the_rolling_record_has_let_go() {
    mount("#/ekf/simulation");
    let end = run_to_end_by_key();
    assert!(end as f64 * Clock::DT_S > 120.0, "a long run: {end} steps");
    let entry = labcore::find("ekf").unwrap();
    let keys: Vec<&str> = entry_plot_keys(entry);
    scrub_to(600);
    let at_600 = plot_xs_of(left_alone(entry, 600).as_ref());
    for (key, x) in at_600 {
        let px = cursor_overlay_px(key);
        if x.is_none() {
            assert_eq!(px, None, "{key} had no point at t = 10 s: no cursor");
            continue;
        }
        let width = plot_canvas(key).get_bounding_client_rect().width();
        assert!(
            px.is_some_and(|px| px > 0.0 && px < width),
            "{key}: the cursor at t = 10 s lies on the plot ({px:?} of {width} px)"
        );
    }
    scrub_to(end);
    for key in &keys {
        assert_eq!(cursor_overlay_px(key), None, "live: no cursor on {key}");
    }
}

fn slider_event(kind: &str) {
    let event = web_sys::Event::new_with_event_init_dict(kind, &{
        let init = web_sys::EventInit::new();
        init.set_bubbles(true);
        init
    })
    .unwrap();
    element(".tb-scrub").dispatch_event(&event).unwrap();
}

/// Issue 26 §4, a drag of the timeline slider is a stream of moves: the
/// link is written once it stops, not at every move (a link costs
/// Chromium 10–17 ms a write, and Safari refuses more than 100 in 30 s),
/// the readouts keep the text's pace, and the moment it stops at is
/// written at once, its `at=` in the link.
#[wasm_bindgen_test]
fn dragging_the_timeline_writes_the_link_once_it_stops_and_the_text_at_its_pace() {
    mount("#/pid/simulation");
    for _ in 0..150 {
        frame(ONE_STEP_MS);
    }
    let slider: HtmlInputElement = element(".tb-scrub").dyn_into().unwrap();
    slider_event("pointerdown");
    let mut links = Vec::new();
    let mut readouts = Vec::new();
    let mut cursor_attrs = Vec::new();
    // 40 moves, one a frame (0.67 s): back from step 100 to step 22.
    for k in (22..=100).rev().step_by(2) {
        slider.set_value(&k.to_string());
        slider_event("input");
        frame(ONE_STEP_MS);
        assert_eq!(steps_shown(), k, "the scene follows every move");
        links.push(hash());
        readouts.push(text("dl.readouts"));
        cursor_attrs.push(cursor_of("response"));
    }
    // The cursor's `data-cursor` (a re-style of the canvas at each write)
    // keeps the text's pace too; the cursor itself moves at every frame.
    cursor_attrs.dedup();
    assert!(
        (2..=6).contains(&cursor_attrs.len()),
        "data-cursor at the text's pace over 0.67 s: {cursor_attrs:?}"
    );
    links.dedup();
    assert_eq!(links.len(), 1, "no link written during the drag: {links:?}");
    readouts.dedup();
    assert!(
        (2..=6).contains(&readouts.len()),
        "the readouts at the text's pace (0.25 s) over 0.67 s: {} versions",
        readouts.len()
    );
    slider_event("change");
    frame(ONE_STEP_MS);
    let entry = labcore::find("pid").unwrap();
    let expected = left_alone(entry, 22);
    for (key, x) in plot_xs_of(expected.as_ref()) {
        assert_eq!(cursor_of(key), x, "{key}'s data-cursor at once on release");
    }
    let shown_readouts = text("dl.readouts");
    for r in expected.readouts() {
        assert!(
            shown_readouts.contains(&r.value),
            "{} = {} written at once",
            r.label,
            r.value
        );
    }
    for _ in 0..20 {
        frame(ONE_STEP_MS);
    }
    assert!(
        hash().contains(&format!("at={:.2}", 22.0 * Clock::DT_S)),
        "the link names the moment: {}",
        hash()
    );
}

/// Runs the mounted experiment to its end with Run to end (paused
/// meanwhile): done when the steps stop growing. Returns the last step.
fn run_to_end_by_key() -> u64 {
    press_key_on_canvas("End");
    let mut last = u64::MAX;
    for frames in 0.. {
        frame(ONE_STEP_MS);
        let now = steps_shown();
        if now == last {
            break;
        }
        last = now;
        assert!(frames < 5000, "Run to end finishes");
    }
    labweb::paint_now();
    steps_shown()
}

/// Issue 26 §4, a drag over a long run on a phone: a plot whose window
/// rolls (cartpole keeps 20 s) would need a new picture at every move, and
/// a plot paint is 12–16 ms on the 4×-throttled phone stand-in. While the
/// drag moves, the plots keep their pictures and their cursors move over
/// them (hidden where a picture does not reach the moment); once the drag
/// rests for 150 ms they are repainted around the moment shown, cursor on
/// the plot. The slider's spoken value (every readout computed) keeps the
/// text's pace and names the moment it stops at.
#[wasm_bindgen_test]
fn a_moving_drag_keeps_the_plots_pictures_and_a_resting_one_repaints_them_at_the_moment() {
    mount("#/cartpole/simulation");
    let end = run_to_end_by_key();
    assert!(
        end as f64 * Clock::DT_S > 25.0,
        "a run longer than the 20 s window: {end} steps"
    );
    let entry = labcore::find("cartpole").unwrap();
    let key = entry_plot_keys(entry)[0];
    let picture = || plot_canvas(key).get_attribute("data-layout");
    let at_end = picture();
    let slider: HtmlInputElement = element(".tb-scrub").dyn_into().unwrap();
    slider_event("pointerdown");
    let mut spoken = Vec::new();
    // 30 moves, one a frame (0.5 s), through the first 5 s of the run: the
    // plot at the end shows its last 20 s.
    for i in 0..30u64 {
        let k = 10 * i + 10;
        slider.set_value(&k.to_string());
        slider_event("input");
        frame(ONE_STEP_MS);
        assert_eq!(steps_shown(), k, "the scene follows every move");
        assert_eq!(
            picture(),
            at_end,
            "the plot keeps its picture while the drag moves (move {i})"
        );
        spoken.push(attr(".tb-scrub", "aria-valuetext"));
    }
    spoken.dedup();
    assert!(
        (2..=4).contains(&spoken.len()),
        "the spoken value at the text's pace (0.25 s) over 0.5 s: {spoken:?}"
    );
    // The drag rests (the pointer still down): the plots follow, at their
    // pace (a plot below the window at most once a second).
    let stopped_at = steps_shown();
    for _ in 0..70 {
        frame(ONE_STEP_MS);
    }
    assert_ne!(
        picture(),
        at_end,
        "the plot is repainted once the drag rests"
    );
    let x = plot_xs_of(left_alone(entry, stopped_at).as_ref())[0].1;
    assert_eq!(cursor_of(key), x);
    let px = cursor_overlay_px(key);
    let width = plot_canvas(key).get_bounding_client_rect().width();
    assert!(
        px.is_some_and(|px| px > 0.0 && px < width),
        "the cursor lies on the repainted plot: {px:?} of {width} px"
    );
    slider_event("change");
    frame(ONE_STEP_MS);
    let main = left_alone(entry, stopped_at).readouts()[0].clone();
    assert_eq!(
        attr(".tb-scrub", "aria-valuetext"),
        Some(format!(
            "t = {:.2} s, {} = {}",
            stopped_at as f64 * Clock::DT_S,
            main.label,
            main.value
        )),
        "the slider names the moment it stopped at"
    );
}

/// Issue 26 §4, running frames: RRT*'s step grows a batch of iterations, so
/// its timeline snapshots it every few steps (`Timeline::first_interval`).
/// A snapshot takes its own copy of the tree's edge layer, so the growing
/// run keeps its layer and the page draws only new and rewired edges: no
/// frame redraws the whole tree while the run grows and is recorded.
#[wasm_bindgen_test]
fn a_recorded_rrt_star_run_draws_only_its_new_edges_between_snapshots() {
    use labweb::layers::{counters, reset_counters};
    mount("#/rrtstar/simulation");
    element("[data-action=grow]").click();
    frame(ONE_STEP_MS);
    labweb::paint_now();
    let interval =
        labweb::inspect_sim(|exp, _| labcore::timeline::Timeline::first_interval(exp)).unwrap();
    assert!(
        interval < labcore::timeline::Timeline::FIRST_INTERVAL,
        "{interval}"
    );
    reset_counters();
    let before = steps_shown();
    for _ in 0..40 {
        frame(ONE_STEP_MS);
    }
    labweb::paint_now();
    let steps = steps_shown() - before;
    assert!(
        steps >= 4 * interval,
        "{steps} steps, {interval} a snapshot"
    );
    let c = counters();
    assert_eq!(c.full_redraws, 0, "{c:?}");
    assert!(c.segments_drawn > 0, "{c:?}");
}

/// Issue 26 §4, a drag over RRT*'s tree on a phone's DPR-2 screen: each
/// position shows another tree, redrawn in full (4,000 edges, 11 ms of a
/// 4×-throttled frame, nearly all per-pixel writes). While the drag moves,
/// the tree is drawn as a draft at one device pixel per CSS pixel (a
/// quarter of the pixels); once it rests, sharp at the screen's ratio.
#[wasm_bindgen_test]
fn a_moving_drag_draws_the_tree_as_a_draft_and_a_resting_one_sharp() {
    use labweb::layers::{counters, reset_counters};
    // The screen's ratio, put back when the test ends, passed or not.
    struct ScreenRatio;
    impl Drop for ScreenRatio {
        fn drop(&mut self) {
            let _ =
                js_sys::eval("Object.defineProperty(window, 'devicePixelRatio', window.__dprWas)");
        }
    }
    js_sys::eval(
        "window.__dprWas = Object.getOwnPropertyDescriptor(window, 'devicePixelRatio') \
         || Object.getOwnPropertyDescriptor(Object.getPrototypeOf(window), 'devicePixelRatio'); \
         Object.defineProperty(window, 'devicePixelRatio', { value: 2, configurable: true })",
    )
    .unwrap();
    let _ratio = ScreenRatio;
    mount("#/rrtstar/simulation");
    element("[data-action=grow]").click();
    let end = run_for_frames(60);
    assert!(end >= 40, "{end} steps");
    let slider: HtmlInputElement = element(".tb-scrub").dyn_into().unwrap();
    slider_event("pointerdown");
    let mut drafts = Vec::new();
    for k in [end / 2, end / 3, end / 4, end / 5] {
        slider.set_value(&k.to_string());
        slider_event("input");
        reset_counters();
        frame(ONE_STEP_MS);
        assert_eq!(steps_shown(), k, "the scene follows every move");
        drafts.push(counters().layer_upload_px);
    }
    // The pointer rests (still down) for more than 150 ms.
    reset_counters();
    for _ in 0..12 {
        frame(ONE_STEP_MS);
    }
    let sharp = counters().layer_upload_px;
    slider_event("change");
    frame(ONE_STEP_MS);
    let most = drafts.iter().copied().max().unwrap_or(0);
    assert!(
        drafts.iter().all(|&px| px > 0),
        "each move draws the tree: {drafts:?}"
    );
    assert!(
        sharp >= 3 * most,
        "at rest the tree is drawn at DPR 2, four times the pixels of a draft: {sharp} px against {drafts:?}"
    );
}

/// Writes of the timeline slider's `value` property since the page loaded
/// (a spy on `HTMLInputElement.prototype.value`, installed once).
fn slider_value_writes() -> u32 {
    js_sys::eval(
        "(() => {
          if (window.__scrubValueWrites === undefined) {
            window.__scrubValueWrites = 0;
            const d = Object.getOwnPropertyDescriptor(HTMLInputElement.prototype, 'value');
            Object.defineProperty(HTMLInputElement.prototype, 'value', {
              configurable: true,
              get: d.get,
              set(v) { if (this.classList.contains('tb-scrub')) window.__scrubValueWrites++; d.set.call(this, v); },
            });
          }
          return window.__scrubValueWrites;
        })()",
    )
    .ok()
    .and_then(|v| v.as_f64())
    .map_or(0, |n| n as u32)
}

/// A drag moves the slider itself: the frames after its moves do not write
/// the value back (a range input given a value lays its thumb out again),
/// yet the slider follows a step taken by a key.
#[wasm_bindgen_test]
fn a_scrub_frame_leaves_the_slider_it_moved_alone_and_a_key_step_moves_it() {
    mount("#/pid/simulation");
    for _ in 0..150 {
        frame(ONE_STEP_MS);
    }
    let slider: HtmlInputElement = element(".tb-scrub").dyn_into().unwrap();
    slider_value_writes();
    slider_event("pointerdown");
    // The first move into the past may write the range and value (the
    // record's end committed at the move); the moves after it, none.
    slider.set_value("96");
    slider_event("input");
    frame(ONE_STEP_MS);
    for k in (30..=90).rev().step_by(6) {
        slider.set_value(&k.to_string());
        let before = slider_value_writes();
        slider_event("input");
        frame(ONE_STEP_MS);
        labweb::paint_now();
        assert_eq!(steps_shown(), k, "the scene follows the move");
        assert_eq!(
            slider_value_writes() - before,
            0,
            "the frame after a move to step {k} wrote the slider's value"
        );
        assert_eq!(slider.value(), k.to_string());
    }
    slider_event("change");
    frame(ONE_STEP_MS);
    // Step back with the key: the slider is told.
    let before = slider_value_writes();
    press_key_on_canvas(",");
    labweb::paint_now();
    let now = steps_shown();
    assert!(now < 30, "one step back from 30: {now}");
    assert!(slider_value_writes() > before, "Step back wrote the value");
    assert_eq!(slider.value(), now.to_string());
}

/// A*'s table (the open list as it was) follows a scrub with its nodes
/// kept: only the texts that changed are rewritten (`dom::rewrite_markup`),
/// so a table is not parsed anew at every text frame of a drag, and a
/// student's focus on it stays.
#[wasm_bindgen_test]
fn a_scrub_rewrites_the_astar_table_in_place() {
    mount("#/astar/simulation");
    let end = plan_and_run_to_end();
    let model_text = || {
        labweb::inspect_sim(|exp, _| {
            exp.tables()
                .iter()
                .map(|t| {
                    let rows: String = t.rows.iter().map(|r| r.concat()).collect();
                    format!("{}{}{rows}", t.caption, t.columns.concat())
                })
                .collect::<String>()
        })
        .unwrap()
    };
    scrub_to(end / 2);
    let table = element(".tables table");
    let first = text(".tables");
    assert!(!first.is_empty(), "A* shows a table");
    assert_eq!(first, model_text());
    scrub_to(end / 4);
    let second = text(".tables");
    assert_eq!(second, model_text());
    assert_ne!(second, first, "the table changed between the two moments");
    assert!(
        element(".tables table").is_same_node(Some(&table)),
        "the table kept its element"
    );
}

// ---- Issue 53 §1, §3 and §8: one run on the slider, one clock, changes
// that mean what they say, and the record's end.

/// Sets the range control of parameter `key` to `value` as a drag does.
fn set_range(key: &str, value: f64) {
    let slider: HtmlInputElement = element(&format!("input[type=range][data-param={key}]"))
        .dyn_into()
        .unwrap();
    slider.set_value(&value.to_string());
    let init = web_sys::EventInit::new();
    init.set_bubbles(true);
    slider
        .dispatch_event(&web_sys::Event::new_with_event_init_dict("input", &init).unwrap())
        .unwrap();
}

/// A page's state without the plots' redraw counters (`revision`), which
/// count the page's own writes too (a link's parameters, a restart).
fn without_revisions((steps, text): (u64, String)) -> (u64, String) {
    let text: Vec<String> = text
        .split("revision: ")
        .map(|part| {
            part.trim_start_matches(|c: char| c.is_ascii_digit())
                .to_owned()
        })
        .collect();
    (steps, text.join("revision: _"))
}

/// The legend names of plot `key` that are shown.
fn legend_names(key: &str) -> Vec<String> {
    let items = page::document()
        .query_selector_all(&format!(
            "figure[data-plot={key}] .legend-item[data-series]:not([hidden])"
        ))
        .unwrap();
    (0..items.length())
        .map(|i| items.item(i).unwrap().text_content().unwrap_or_default())
        .collect()
}

/// pid built fresh with `pairs` set, then left alone for `steps` steps.
fn pid_with(pairs: &[(&str, f64)], steps: u64) -> (u64, String) {
    let mut exp = labcore::testkit::open("pid");
    for (k, v) in pairs {
        exp.set_param(k, *v).unwrap();
    }
    for _ in 0..steps {
        exp.step(Clock::DT_S);
    }
    without_revisions((steps, snapshot(exp.as_ref())))
}

/// Issue 53 §1, "the slider is the current run": after a run, a change that
/// replays pid's step starts a new run, and the slider spans that run from
/// its start (not the whole visit), with the time bar counting from it as
/// its plots do; the run before stays on the plots, named as the restart.
#[wasm_bindgen_test]
fn the_slider_is_the_current_run_and_the_earlier_run_stays_on_the_plots() {
    mount("#/pid/simulation");
    assert!(run_for_frames(120) >= 100);
    set_range("kp", 60.0);
    frame(ONE_STEP_MS);
    let k = run_for_frames(60);
    assert!(
        k <= 61,
        "{k} steps: the clock counts from the new run's start"
    );
    assert_eq!(attr(".tb-scrub", "min").as_deref(), Some("0"));
    assert_eq!(attr(".tb-scrub", "max"), Some(k.to_string()));
    assert_eq!(
        text(".tb-time"),
        format!("t = {:.2} s", k as f64 * Clock::DT_S)
    );
    assert_eq!(without_revisions(shown()), pid_with(&[("kp", 60.0)], k));
    // Its start is on the slider: the new run at t = 0.
    scrub_to(0);
    assert_eq!(without_revisions(shown()), pid_with(&[("kp", 60.0)], 0));
    let names = legend_names("response");
    assert!(
        names
            .iter()
            .any(|n| n == "before Kp 12 N/m → 60 N/m restarted the run"),
        "{names:?}"
    );
}

/// Issue 53 §1, "one clock": the time bar, a mark and the link count the
/// run's own time, so a link of any run (not only the first) carries the
/// moment and the marks, and reopening it shows that moment.
#[wasm_bindgen_test]
fn one_clock_every_runs_link_carries_its_moment_and_marks_and_reopens_them() {
    mount("#/pid/simulation?kp=40&kd=2");
    run_for_frames(100);
    set_range("kp", 25.0);
    frame(ONE_STEP_MS);
    run_for_frames(50);
    element(".tb-play").click();
    labweb::paint_now();
    let n = steps_shown();
    element("[data-time=mark]").click();
    labweb::paint_now();
    scrub_to(30);
    let there = without_revisions(shown());
    assert_eq!(there, pid_with(&[("kp", 25.0), ("kd", 2.0)], 30));
    frame(300.0);
    frame(300.0);
    let link = hash();
    assert!(link.contains("at=0.50"), "{link}");
    let marks = format!("marks={:.2}", n as f64 * Clock::DT_S);
    assert!(link.contains(&marks), "{link}");
    mount(&link);
    assert_eq!(without_revisions(shown()), there, "{link}");
    frame(300.0);
    frame(300.0);
    assert!(hash().contains(&marks), "{}", hash());
}

/// Issue 53 §3, "a change in the past means what its label says": pid's
/// change at t = 0.50 s replays the step from x = 0, so the run it leaves
/// is named as the restart it is, not as a branch at 0.50 s.
#[wasm_bindgen_test]
fn a_change_in_the_past_that_restarts_the_run_is_named_as_the_restart() {
    mount("#/pid/simulation");
    run_for_frames(100);
    scrub_to(30);
    set_range("kd", 10.0);
    frame(ONE_STEP_MS);
    labweb::paint_now();
    let names = legend_names("response");
    assert!(
        names
            .iter()
            .any(|n| n == "before Kd 6 N·s/m → 10 N·s/m restarted the run"),
        "{names:?}"
    );
    assert!(
        !names.iter().any(|n| n.contains("at t = 0.50 s")),
        "{names:?}"
    );
}

/// Issue 53 §3, "a change plays": after Run to end or a scrub (the
/// timeline paused the run, not the student) a change plays, as on the
/// live page and as pid's text says ("each change replays the step"); a
/// run the student paused stays paused.
#[wasm_bindgen_test]
fn after_run_to_end_or_a_scrub_a_change_plays_and_a_students_pause_holds() {
    mount("#/pid/simulation");
    element("[data-time=end]").click();
    let mut frames = 0;
    while labweb::inspect_sim(|exp, _| exp.status().phase != Phase::Ended).unwrap() {
        frame(ONE_STEP_MS);
        frames += 1;
        assert!(frames < 100, "the run ends");
    }
    let playing = || attr(".tb-play", "aria-pressed").as_deref() == Some("true");
    set_range("kp", 60.0);
    run_for_frames(10);
    assert!(playing() && steps_shown() >= 8, "{}", steps_shown());
    scrub_to(3);
    assert!(!playing());
    set_range("kd", 10.0);
    run_for_frames(10);
    assert!(playing() && steps_shown() >= 8, "{}", steps_shown());
    // The student's own pause holds.
    element(".tb-play").click();
    set_range("kp", 30.0);
    run_for_frames(10);
    assert!(!playing());
    assert_eq!(steps_shown(), 0);
}

/// Issue 53 §3: before anything moves (A* waits for Plan & drive) the time
/// bar reads held, and the play button offers Play, not Pause; pressing it
/// keeps the clock ready; once the search moves it offers Pause.
#[wasm_bindgen_test]
fn before_anything_moves_the_play_button_offers_play_where_the_bar_reads_held() {
    mount("#/astar/simulation");
    frame(ONE_STEP_MS);
    labweb::paint_now();
    assert_eq!(text(".tb-time"), "t = 0.00 s · held");
    assert_eq!(text(".tb-play .tb-label"), "Play");
    assert_eq!(attr(".tb-play", "aria-pressed").as_deref(), Some("false"));
    element(".tb-play").click();
    frame(ONE_STEP_MS);
    labweb::paint_now();
    assert_eq!(attr(".timebar", "data-clock").as_deref(), Some("held"));
    element("[data-action=plan]").click();
    frame(ONE_STEP_MS);
    frame(ONE_STEP_MS);
    labweb::paint_now();
    assert!(steps_shown() > 0);
    assert_eq!(text(".tb-play .tb-label"), "Pause");
}

/// Issue 53 §3: Run to end on a run with no end (the EKF drives on for
/// ever) stops after ten minutes and says so, and its button says it will.
#[wasm_bindgen_test]
fn run_to_end_on_a_run_with_no_end_says_what_it_did() {
    mount("#/ekf/simulation");
    let title = attr("[data-time=end]", "title").unwrap_or_default();
    assert!(title.contains("no end"), "{title}");
    element("[data-time=end]").click();
    let mut frames = 0;
    while attr(".sim-message", "hidden").is_some() {
        frame(ONE_STEP_MS);
        frames += 1;
        assert!(frames < 5000, "Run to end stops");
    }
    assert_eq!(
        text(".sim-message"),
        "Run to end: this run has no end, so it went 10 minutes on, to t = 600.00 s."
    );
    assert_eq!(steps_shown(), 36_000);
}

/// Issue 53 §8, "Play from the past overruns the record's end": pid played
/// to step 96, the slider to 94, Play 60 frames: the frame that reaches the
/// record's end replays up to it and the run goes on live from there, every
/// step the run's own.
#[wasm_bindgen_test]
fn play_from_the_past_stops_replaying_at_the_records_end_and_goes_on_live() {
    let entry = labcore::find("pid").unwrap();
    let end = paused_after("#/pid/simulation", 96);
    scrub_to(end - 2);
    element(".tb-play").click();
    let k = run_for_frames(60);
    element(".tb-play").click();
    labweb::paint_now();
    assert!(k > end + 50, "{k}");
    assert_eq!(attr(".tb-scrub", "max"), Some(k.to_string()));
    assert_eq!(shown(), (k, snapshot(left_alone(entry, k).as_ref())));
    scrub_to(end + 20);
    assert_eq!(
        shown(),
        (end + 20, snapshot(left_alone(entry, end + 20).as_ref()))
    );
}

/// Issue 53 §8, "a paused run's link after an input": cartpole paused at
/// step 100, kθ typed: until the input was committed the page wrote
/// `at=1.67`, a moment the link does not reopen. The link now carries the
/// change with its time (`then=`, the start's kθ before it) and reopens
/// what the page shows. pid's change starts the run again: its link
/// reopens what the page shows.
#[wasm_bindgen_test]
fn a_paused_runs_link_after_an_input_names_only_a_moment_it_reopens() {
    paused_after("#/cartpole/simulation", 100);
    let link = link_after(|| set_range("kth", 60.0));
    assert!(
        link.contains("at=1.67") && link.contains("then=1.67:p:kth:60") && !link.contains("kth=60"),
        "{link}"
    );
    let there = without_revisions(shown());
    mount(&link);
    assert_eq!(without_revisions(shown()), there, "{link}");
    paused_after("#/pid/simulation", 100);
    let link = link_after(|| set_range("kp", 60.0));
    let there = without_revisions(shown());
    assert!(link.contains("kp=60") && link.contains("run=0"), "{link}");
    mount(&link);
    assert_eq!(without_revisions(shown()), there, "{link}");
}

/// Mounts `link`, runs it to step `steps` and pauses there; the steps shown.
fn paused_after(link: &str, steps: u64) -> u64 {
    mount(link);
    while steps_shown() < steps {
        frame(ONE_STEP_MS);
    }
    element(".tb-play").click();
    labweb::paint_now();
    steps_shown()
}

/// Does `input` on a paused page and returns the link written after it (the
/// link waits for its pace: frames while paused take no step).
fn link_after(input: impl FnOnce()) -> String {
    input();
    frame(300.0);
    frame(300.0);
    hash()
}
