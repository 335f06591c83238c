//! A run in the real page, its frames driven by the test (issue 23): the
//! browser's `requestAnimationFrame` is replaced by a queue that the test
//! empties with a frame time of its choosing, so the app's own frame loop,
//! routing and time bar run exactly as in the page, but no step depends on
//! the wall clock. Tab switches are real clicks on the tab links (the
//! browser routes them through `popstate` and `hashchange`) and real
//! `history.back()`.

use labcore::clock::Clock;
use labcore::route::{self, Tab};
use labcore::Phase;
use wasm_bindgen::JsCast;
use wasm_bindgen_futures::JsFuture;
use wasm_bindgen_test::*;

mod page;
use page::{
    attr, element, frame, frame_alone, hash, idle, idle_asked, js, left_alone, mount,
    observers_report, press_key_on_canvas, shown, snapshot, text, ONE_STEP_MS,
};

wasm_bindgen_test_configure!(run_in_browser);

/// Resolves at the next `hashchange` (after the app's own listener).
fn next_hashchange() -> JsFuture {
    let promise =
        js("return new Promise((r) => addEventListener('hashchange', () => r(), { once: true }))");
    JsFuture::from(js_sys::Promise::from(promise))
}

/// Clicks the tab link `slug` of the shown article, as a student does.
async fn click_tab(slug: &str) {
    let routed = next_hashchange();
    element(&format!(
        "article.exp:not([hidden]) [role=tab][data-tab={slug}]"
    ))
    .click();
    routed.await.unwrap();
}

/// The browser's Back button.
async fn back() {
    let routed = next_hashchange();
    web_sys::window()
        .unwrap()
        .history()
        .unwrap()
        .back()
        .unwrap();
    routed.await.unwrap();
}

const OTHER_TABS: [&str; 5] = ["aim", "theory", "procedure", "quiz", "references"];

/// Issue 23 §2: run N steps, switch to other tabs and back any number of
/// times (by the tab links and by Back, in a seeded random order, with
/// frames in between), and the state, the plots and the link equal those
/// of the same run left alone at the same step.
#[wasm_bindgen_test]
async fn every_experiment_keeps_its_run_across_tab_switches() {
    let mut rng = labcore::Lcg64::new(23);
    for entry in labcore::registry() {
        mount(&format!("#/{}/simulation", entry.id));
        for _ in 0..rng.int(20, 120) {
            frame(ONE_STEP_MS);
        }
        for _ in 0..rng.int(1, 5) {
            let other = OTHER_TABS[rng.int(0, OTHER_TABS.len() as i64 - 1) as usize];
            let (steps_before, _) = shown();
            click_tab(other).await;
            // Frames while the tab is away: the run keeps its place.
            for _ in 0..rng.int(0, 4) {
                frame(ONE_STEP_MS);
            }
            assert_eq!(
                shown().0,
                steps_before,
                "{}: no step away from the tab",
                entry.id
            );
            if rng.next_f64() < 0.5 {
                click_tab("simulation").await;
            } else {
                back().await;
            }
            assert_eq!(
                attr("article.exp:not([hidden])", "data-tab").as_deref(),
                Some("simulation"),
                "{}",
                entry.id
            );
            for _ in 0..rng.int(0, 40) {
                frame(ONE_STEP_MS);
            }
        }
        labweb::paint_now();
        let (steps, state) = shown();
        let alone = left_alone(entry, steps);
        assert_eq!(
            state,
            snapshot(alone.as_ref()),
            "{} at step {steps}",
            entry.id
        );
        assert_eq!(
            hash(),
            route::format(alone.as_ref(), Tab::Simulation),
            "{}: the link",
            entry.id
        );
    }
}

/// Issue 23 §3, ekf: paused, the badge no longer reads "EKF localisation
/// running"; the status strip says the run is paused, for every experiment
/// with time controls (the model says what the run is, the shell whether
/// time goes on).
#[wasm_bindgen_test]
fn ekf_paused_the_badge_still_reads_running_no_more_it_says_paused() {
    mount("#/ekf/simulation");
    frame(ONE_STEP_MS);
    frame(ONE_STEP_MS);
    element(".tb-play").click();
    labweb::paint_now();
    let badge = text(".sim-status");
    assert!(!badge.contains("running"), "{badge}");
    for entry in labcore::registry() {
        if !(entry.make)().animated() {
            continue;
        }
        mount(&format!("#/{}/simulation", entry.id));
        frame(ONE_STEP_MS);
        assert_ne!(attr(".sim-status", "data-clock").as_deref(), Some("paused"));
        if attr(".sim-status", "data-clock").as_deref() == Some("held") {
            // Nothing moves yet: the button offers Play (issue 53 §3).
            assert_eq!(text(".tb-play .tb-label"), "Play", "{}", entry.id);
            continue;
        }
        element(".tb-play").click();
        frame(ONE_STEP_MS);
        let phase = attr(".sim-status", "data-phase");
        if phase.as_deref() == Some("ended") {
            continue;
        }
        assert_eq!(
            attr(".sim-status", "data-clock").as_deref(),
            Some("paused"),
            "{}",
            entry.id
        );
        let mark = js(
            "return getComputedStyle(document.querySelector('.sim-status'), '::before').content",
        )
        .as_string()
        .unwrap_or_default();
        assert!(mark.contains("paused · "), "{}: {mark}", entry.id);
        // Play again: the mark goes.
        element(".tb-play").click();
        frame(ONE_STEP_MS);
        assert_ne!(attr(".sim-status", "data-clock").as_deref(), Some("paused"));
    }
}

/// Issue 23 §3, ekf: one press of Step (and of `.`) takes one filter cycle,
/// t moving by the filter step the Procedure speaks of.
#[wasm_bindgen_test]
fn ekf_step_advances_t_by_one_filter_step_not_one_frame() {
    use labcore::experiments::ekf::FILTER_DT_S;
    mount("#/ekf/simulation?run=0");
    let t = |presses: f64| format!("t = {:.2} s", presses * FILTER_DT_S);
    assert_eq!(text(".tb-time"), t(0.0));
    element("[data-time=step]").click();
    labweb::paint_now();
    assert_eq!(text(".tb-time"), t(1.0));
    assert!((shown().0 as f64 * Clock::DT_S - FILTER_DT_S).abs() < 1e-9);
    press_key_on_canvas(".");
    labweb::paint_now();
    assert_eq!(text(".tb-time"), t(2.0));
    assert!((shown().0 as f64 * Clock::DT_S - 2.0 * FILTER_DT_S).abs() < 1e-9);
    // The time bar says what a step is.
    let title = attr("[data-time=step]", "title").unwrap_or_default();
    assert!(title.contains("0.05 s"), "{title}");
    // Each press was one filter cycle: the run equals that many cycles.
    let entry = labcore::find("ekf").unwrap();
    let mut alone = (entry.make)();
    for _ in 0..2 {
        for _ in 0..(FILTER_DT_S / Clock::DT_S).round() as u32 {
            alone.step(Clock::DT_S);
        }
    }
    assert_eq!(shown().1, snapshot(alone.as_ref()));
}

/// Issue 23 §3, cartpole: at "balanced" t stops while the time bar offered
/// Pause, and looked frozen; the time bar now says t is held.
#[wasm_bindgen_test]
fn cartpole_at_balanced_the_time_bar_shows_t_held_not_a_frozen_clock() {
    mount("#/cartpole/simulation");
    let mut frames = 0;
    while labweb::inspect_sim(|exp, _| exp.animating()).unwrap() {
        frame(250.0);
        frames += 1;
        assert!(frames < 1000, "the pole comes to rest");
    }
    frame(250.0);
    labweb::paint_now();
    assert_eq!(text(".sim-status"), "balanced");
    let held = text(".tb-time");
    assert!(held.ends_with(" · held"), "{held}");
    assert_eq!(attr(".timebar", "data-clock").as_deref(), Some("held"));
    // t holds: more frames change nothing.
    frame(250.0);
    labweb::paint_now();
    assert_eq!(text(".tb-time"), held);
    // Held, the play button offers Play (issue 53 §3); a Step pauses it,
    // and paused it is paused, not held.
    assert_eq!(text(".tb-play .tb-label"), "Play");
    element("[data-time=step]").click();
    labweb::paint_now();
    assert_eq!(attr(".timebar", "data-clock").as_deref(), Some("paused"));
    assert!(!text(".tb-time").contains("held"));
}

/// Issue 23 §3, numbers: "Replay of a PID run ends at 1.43 s; the first run
/// ended at 1.42 s". The steps a frame took after the run's end counted:
/// how many depended on how the frames fell. The same run now ends at the
/// same step, however many steps each frame takes.
#[wasm_bindgen_test]
fn pid_replay_of_a_run_ends_at_the_same_step_as_the_first_run() {
    mount("#/pid/simulation?kp=1&ki=5&kd=0&c=0");
    let ended =
        || labweb::inspect_sim(|exp, steps| (exp.status().phase == Phase::Ended, steps)).unwrap();
    let run_to_end = |gap_ms: f64| {
        let mut frames = 0;
        while !ended().0 {
            frame(gap_ms);
            frames += 1;
            assert!(frames < 5000, "the run ends");
        }
        labweb::paint_now();
        (ended().1, text(".tb-time"))
    };
    let first = run_to_end(ONE_STEP_MS);
    for steps_a_frame in [2.0, 3.0, 5.0, 7.0] {
        assert_eq!(attr(".tb-play", "data-offer").as_deref(), Some("replay"));
        element(".tb-play").click();
        let replay = run_to_end(ONE_STEP_MS * steps_a_frame);
        assert_eq!(replay, first, "replayed with {steps_a_frame} steps a frame");
    }
}

/// Issue 23 §2: the link is written at a pace while a run goes; a change
/// made just before leaving the tab is written as the tab is left, so Back
/// returns to the state left (not a link up to 250 ms old, which rebuilt
/// the run from it).
#[wasm_bindgen_test]
async fn a_change_just_before_leaving_the_tab_survives_back() {
    mount("#/pid/simulation");
    for _ in 0..30 {
        frame(ONE_STEP_MS);
    }
    let slider: web_sys::HtmlInputElement = element("input[type=range][data-param=kp]")
        .dyn_into()
        .unwrap();
    let set_kp = |value: &str| {
        slider.set_value(value);
        let init = web_sys::EventInit::new();
        init.set_bubbles(true);
        let input = web_sys::Event::new_with_event_init_dict("input", &init).unwrap();
        slider.dispatch_event(&input).unwrap();
        // One frame: the change shows; its link is written unless one was
        // written less than the pace before.
        frame(ONE_STEP_MS);
    };
    set_kp("30");
    assert!(hash().contains("kp=30"), "{}", hash());
    set_kp("40");
    let (steps, state) = shown();
    click_tab("theory").await;
    back().await;
    labweb::paint_now();
    assert_eq!(shown(), (steps, state));
    assert!(hash().contains("kp=40"), "{}", hash());
}

/// A drag of the timeline slider of the mounted run (at least 60 steps
/// long): grabbed with `pointerdown`, moved with `input` events.
struct ScrubDrag {
    slider: web_sys::HtmlInputElement,
    lo: f64,
    hi: f64,
}

impl ScrubDrag {
    fn grab() -> Self {
        let slider: web_sys::HtmlInputElement = element(".tb-scrub").dyn_into().unwrap();
        let (lo, hi) = (slider.min().parse().unwrap(), slider.max().parse().unwrap());
        assert!(hi - lo >= 60.0, "a run to scrub: {lo}..{hi}");
        let drag = Self { slider, lo, hi };
        drag.send("pointerdown");
        drag
    }

    /// A bubbling event of `kind` on the slider.
    fn send(&self, kind: &str) {
        let init = web_sys::EventInit::new();
        init.set_bubbles(true);
        let event = web_sys::Event::new_with_event_init_dict(kind, &init).unwrap();
        self.slider.dispatch_event(&event).unwrap();
    }

    fn move_to(&self, step: f64) {
        self.slider.set_value(&format!("{}", step.round()));
        self.send("input");
    }

    /// The `i`-th of 60 positions spread over the whole run, out of order.
    fn move_to_spread(&self, i: i32) {
        self.move_to(self.lo + (self.hi - self.lo) * f64::from((i * 37) % 60) / 59.0);
    }
}

/// pid's force readout as the page's run has it now.
fn pid_force() -> String {
    labweb::inspect_sim(|exp, _| {
        exp.readouts()
            .into_iter()
            .find(|r| r.key == "force")
            .map(|r| r.value)
    })
    .unwrap()
    .expect("pid has a force readout")
}

/// The first equation's result in "The math" panel.
fn math_result() -> String {
    text(".live-math [data-equation=\"0\"] .equation-result")
}

/// Issue 27, cost: a tab switch hides "The math" panel and shows it again.
/// Out of the window before and after (below the scene on a phone), the
/// panel stays unwritten while the run streams: the browser's intersection
/// observer says nothing when its answer has not changed, so the page asks
/// it afresh once the panel is shown again (`labWatchBox` in web/main.js).
/// Before, the page took the panel for seen after every tab switch and
/// wrote it four times a second, off-screen.
#[wasm_bindgen_test]
async fn the_math_panel_out_of_the_window_stays_unwritten_after_a_tab_switch() {
    mount("#/pid/simulation");
    // The test page is short: the panel starts below the window.
    observers_report(".live-math").await;
    for _ in 0..30 {
        frame(ONE_STEP_MS);
    }
    let unwritten = |why: &str| {
        let before = math_result();
        for _ in 0..60 {
            frame(ONE_STEP_MS);
            assert_eq!(math_result(), before, "{why}: not rewritten");
        }
    };
    unwritten("out of the window");
    for tab in ["theory", "procedure"] {
        click_tab(tab).await;
        frame(ONE_STEP_MS);
        click_tab("simulation").await;
        observers_report(".live-math").await;
        frame(ONE_STEP_MS);
        unwritten(&format!("back from {tab}, still out of the window"));
    }
    // In view, it is written at the run's pace, as ever.
    let panel = element(".live-math");
    panel.style().set_property("position", "fixed").unwrap();
    panel.style().set_property("top", "0").unwrap();
    observers_report(".live-math").await;
    let before = math_result();
    for _ in 0..30 {
        frame(ONE_STEP_MS);
    }
    assert_ne!(math_result(), before, "in view: written again");
}

/// Issue 27, cost: a stream of input (a held arrow key turning fk's arm)
/// with "The math" panel out of the window writes none of it, as a
/// streaming run does not, while the readouts follow the keys at the
/// text's pace; once the keys stop, the settled text update writes every
/// equation, seen or not. (Before, a stream of input on an experiment at
/// rest wrote the panel below the window four times a second: DLS driven
/// by keys on the phone stand-in, scene in view, ran ×1.14 at p95.)
#[wasm_bindgen_test]
async fn a_stream_of_keys_leaves_the_math_panel_out_of_the_window_unwritten_until_it_settles() {
    mount("#/fk/simulation");
    // The test page is short: the panel starts below the window.
    observers_report(".live-math").await;
    for _ in 0..30 {
        frame(ONE_STEP_MS);
    }
    let results = || texts(".live-math .equation-result");
    let before = results();
    let x_readout = || text("[data-readout=x]");
    hold_arrow_keys("the readouts", x_readout, |i| {
        assert_eq!(results(), before, "frame {i} of the keys wrote the panel");
    });
    // The keys stop: within the text's pace the panel is written.
    let_the_text_settle();
    assert_ne!(results(), before, "settled: the panel is written");
    each_result_is_its_readout("fk", "settled after the keys");
}

/// Issue 27, cost: on a phone fk's first equation shows under the scene and
/// its second is below the window. A stream of input (held arrow keys)
/// writes the one in the window at the text's pace, its result following
/// its readout, and leaves the other unwritten; once the keys stop, the
/// settled update writes both. (Before, the equation out of the window was
/// written too: fk moved by keys on the phone stand-in, scene in view,
/// laid out and painted the math twice for every time it was seen.)
#[wasm_bindgen_test]
async fn a_stream_of_keys_writes_only_the_equations_in_the_window_until_it_settles() {
    mount("#/fk/simulation");
    // The test page is short: the panel starts below the window. The first
    // equation, fixed at the window's top, is in view; the second is not.
    let first = element(".live-math [data-equation=\"0\"]");
    first.style().set_property("position", "fixed").unwrap();
    first.style().set_property("top", "0").unwrap();
    observers_report(".live-math [data-equation=\"1\"]").await;
    for _ in 0..30 {
        frame(ONE_STEP_MS);
    }
    let result = |i: usize| {
        text(&format!(
            ".live-math [data-equation=\"{i}\"] .equation-result"
        ))
    };
    let second_before = result(1);
    hold_arrow_keys(
        "the equation in the window",
        || result(0),
        |i| {
            assert_eq!(
                result(1),
                second_before,
                "frame {i} of the keys wrote the equation out of the window"
            );
        },
    );
    // The keys stop: within the text's pace both are written.
    let_the_text_settle();
    assert_ne!(
        result(1),
        second_before,
        "settled: the second equation is written"
    );
    each_result_is_its_readout("fk", "settled after the keys");
}

/// Issue 27, cost: while a run streams and "The math" panel is out of the
/// window (below the scene on a phone), the panel is not written (each
/// write costs the page a style and layout pass of its formulas); once it
/// is back in view the run's pace writes it again, and when the run stops
/// it shows the last state's numbers, seen or not.
#[wasm_bindgen_test]
async fn the_math_panel_out_of_the_window_is_not_rewritten_while_a_run_streams() {
    mount("#/pid/simulation");
    // The test page is short: the panel starts below the window. Fixed at
    // the window's top, it is in view.
    let panel = element(".live-math");
    let in_view = |yes: bool| {
        let style = panel.style();
        if yes {
            style.set_property("position", "fixed").unwrap();
            style.set_property("top", "0").unwrap();
        } else {
            style.remove_property("position").unwrap();
            style.remove_property("top").unwrap();
        }
    };
    in_view(true);
    observers_report(".live-math").await;
    for _ in 0..30 {
        frame(ONE_STEP_MS);
    }
    let mut seen = vec![math_result()];
    for _ in 0..60 {
        frame(ONE_STEP_MS);
        seen.push(math_result());
    }
    seen.dedup();
    assert!(
        seen.len() >= 3,
        "in view, written at the run's pace: {seen:?}"
    );
    // Out of the window: a second of the run writes nothing. (The browser's
    // observers tell the page after its next layout; the frame reads no
    // place.)
    in_view(false);
    observers_report(".live-math").await;
    for _ in 0..5 {
        frame(ONE_STEP_MS);
    }
    let before = math_result();
    for _ in 0..60 {
        frame(ONE_STEP_MS);
        assert_eq!(math_result(), before, "out of the window: not rewritten");
    }
    // Back in view: written again within the text's pace.
    in_view(true);
    observers_report(".live-math").await;
    for _ in 0..20 {
        frame(ONE_STEP_MS);
    }
    assert_ne!(math_result(), before, "back in view: written again");
    // Out of the window again, then the run is paused: the last state's
    // numbers are written anyway.
    in_view(false);
    observers_report(".live-math").await;
    for _ in 0..20 {
        frame(ONE_STEP_MS);
    }
    element("button[data-time=play]").click();
    for _ in 0..3 {
        frame(ONE_STEP_MS);
    }
    let force = pid_force();
    assert_eq!(
        math_result(),
        format!("= {force}"),
        "paused: the panel shows the state"
    );
}

/// A frame reads no element's place or size (`getBoundingClientRect`):
/// after an input (a timeline scrub, a slider) the page's layout is stale,
/// and one read makes the browser lay the whole page out in the middle of
/// the frame (2–3 ms of a throttled phone's scrub frame for "The math"
/// panel, 18–23 ms for the plots). The browser's observers tell the page
/// the sizes and what is in the window instead.
#[wasm_bindgen_test]
async fn scrub_frames_read_no_size_once_the_observers_have_reported() {
    let _in_view = mount_with_the_math_panel_in_view("#/pid/simulation");
    observers_report(".live-math").await;
    observers_report("figure.plot canvas").await;
    for _ in 0..120 {
        frame(ONE_STEP_MS);
    }
    js("window.__sizeReads = 0; if (!window.__countingReads) { window.__countingReads = true; \
        const read = Element.prototype.getBoundingClientRect; \
        Element.prototype.getBoundingClientRect = function () { window.__sizeReads += 1; return read.call(this); }; }");
    // A drag over the whole run, the slider let go, then more frames (the
    // plots and the panel are written again once it rests).
    let scrub = ScrubDrag::grab();
    for i in 0..60 {
        scrub.move_to_spread(i);
        frame(ONE_STEP_MS);
    }
    scrub.send("change");
    for _ in 0..30 {
        frame(ONE_STEP_MS);
    }
    let reads = js("const n = window.__sizeReads; window.__sizeReads = 0; return n")
        .as_f64()
        .unwrap();
    assert_eq!(reads, 0.0, "size reads in 90 frames of a scrub");
    assert!(
        !math_result().is_empty() && shown().0 > 0,
        "the scrub showed its moment"
    );
}

/// The texts of every element `selector` matches, in order.
fn texts(selector: &str) -> Vec<String> {
    let list = page::document().query_selector_all(selector).unwrap();
    (0..list.length())
        .filter_map(|i| list.item(i))
        .map(|n| n.text_content().unwrap_or_default().trim().to_string())
        .collect()
}

/// Issue 53 §10: the status badge is written with the readouts. ekf's
/// consistency check ends while the robot drives on, so its verdict comes
/// at a streaming run's pace; written in the frame while the readouts
/// waited for the idle time, the verdict ("… average NEES 1.02 …") stood
/// beside an "Average NEES" of "--" (a fresh-clone e2e run read that pair).
/// After every frame and every idle time, a verdict in the badge has its
/// average NEES in the readout.
#[wasm_bindgen_test]
fn a_verdict_in_the_status_is_never_shown_before_its_readout() {
    let _in_view = mount_ekf_with_the_math_panel_in_view();
    for _ in 0..10 {
        frame(ONE_STEP_MS);
    }
    element("[data-action=check]").click();
    let verdict = || {
        let status = text(".sim-status");
        [
            "consistent",
            "over-confident",
            "under-confident",
            "inconsistent",
        ]
        .iter()
        .any(|v| status.starts_with(v))
        .then_some(status)
    };
    let agree = |when: &str| {
        if let Some(status) = verdict() {
            let anees = text("[data-readout=anees]");
            assert!(
                anees.parse::<f64>().is_ok(),
                "{when}: the status says {status:?} while Average NEES reads {anees:?}"
            );
        }
    };
    let mut frames = 0;
    while verdict().is_none() && frames < 20_000 {
        frame_alone(ONE_STEP_MS);
        agree("after a frame");
        while idle_asked() {
            idle();
            agree("after an idle time");
        }
        frames += 1;
    }
    assert!(verdict().is_some(), "the check ended in {frames} frames");
    assert_ne!(
        attr(".sim-status", "data-phase").as_deref(),
        Some("ended"),
        "the run drives on"
    );
}

/// Issue 27, cost: while a run streams, its text update's frame writes
/// none of "The math" panel's equations, and lays none out; the browser's
/// idle times after it write them, the readouts with the first and one
/// equation an idle time, and lay the page out there. So the frame after
/// each paints one equation's new numbers, not the whole panel's; once
/// they are all written each result shown is its own readout on the page.
/// Where the browser has no idle callbacks (WebKit), the readouts are
/// written in the frame and the frames after it write the equations one
/// each.
#[wasm_bindgen_test]
fn a_streaming_run_writes_the_math_panel_one_equation_an_idle_time() {
    let _in_view = mount_ekf_with_the_math_panel_in_view();
    let results = || texts(".live-math .equation-result");
    let readouts = || texts(".readouts dd");
    let equations = results().len();
    assert!(equations >= 3, "ekf has several equations: {equations}");
    for _ in 0..40 {
        frame(ONE_STEP_MS);
    }
    let each_result_is_its_readout = |why: &str| each_result_is_its_readout("ekf", why);
    let (mut updates_in_idle, mut most_idle_times) = (0, 0);
    for _ in 0..120 {
        let (before_readouts, before_results) = (readouts(), results());
        frame_alone(ONE_STEP_MS);
        assert_eq!(
            results(),
            before_results,
            "a streaming frame writes no equation"
        );
        let readouts_in_frame = readouts() != before_readouts;
        each_result_is_its_readout("after the frame");
        let (mut last, mut idle_times) = (results(), 0);
        while idle_asked() {
            idle();
            let now = results();
            let written = now.iter().zip(&last).filter(|(a, b)| a != b).count();
            assert!(written <= 1, "one idle time wrote {written} equations");
            idle_times += usize::from(written == 1);
            last = now;
        }
        each_result_is_its_readout("after the idle times");
        if idle_times > 0 {
            updates_in_idle += 1;
            assert!(
                !readouts_in_frame && readouts() != before_readouts,
                "the readouts change with the equations, in the idle time"
            );
        }
        most_idle_times = most_idle_times.max(idle_times);
    }
    assert!(
        updates_in_idle >= 4,
        "the idle time wrote the panel {updates_in_idle} times in 2 s"
    );
    assert!(
        most_idle_times >= 2,
        "an update of several equations took {most_idle_times} idle times"
    );
    // Without idle callbacks: one equation a frame after the readouts'.
    js("window.__savedIdle = window.requestIdleCallback; window.requestIdleCallback = undefined;");
    let mut staggered = 0;
    for _ in 0..60 {
        let (before_readouts, before_results) = (readouts(), results());
        frame(ONE_STEP_MS);
        if readouts() == before_readouts {
            continue;
        }
        assert_eq!(
            results(),
            before_results,
            "the readouts' frame writes no equation"
        );
        let mut last = results();
        for n in 1..=equations {
            frame(ONE_STEP_MS);
            let now = results();
            let written = now.iter().zip(&last).filter(|(a, b)| a != b).count();
            assert!(
                written <= 1,
                "frame {n} after the readouts wrote {written} equations"
            );
            staggered += written;
            last = now;
        }
        each_result_is_its_readout("one a frame");
    }
    js("window.requestIdleCallback = window.__savedIdle;");
    assert!(staggered >= 3, "{staggered} equations written one a frame");
}

/// Holds the right arrow key on the canvas for 60 frames (a press every
/// third, as a key repeats), checking `each_frame` after every frame, and
/// asserts that `follows` (what the student watches) took at least three
/// values on the way: it follows the keys at the text's pace.
fn hold_arrow_keys(what: &str, follows: impl Fn() -> String, mut each_frame: impl FnMut(usize)) {
    let mut seen = vec![follows()];
    for i in 0..60 {
        if i % 3 == 0 {
            press_key_on_canvas("ArrowRight");
        }
        frame(ONE_STEP_MS);
        each_frame(i);
        seen.push(follows());
    }
    seen.dedup();
    assert!(seen.len() >= 3, "{what} follows the keys: {seen:?}");
}

/// Frames enough, with nothing pressed, for the text's pace to write the
/// settled update (20 frames of 16.7 ms: more than TEXT_INTERVAL_MS).
fn let_the_text_settle() {
    for _ in 0..20 {
        frame(ONE_STEP_MS);
    }
}

/// Asserts that every equation of "The math" panel of experiment `id`
/// shows as its result the readout it names on the page ("= --" where the
/// result has no value yet).
fn each_result_is_its_readout(id: &str, why: &str) {
    let entry = labcore::find(id).unwrap();
    let readout_of: std::collections::HashMap<&str, &str> = (entry.make)()
        .equations()
        .iter()
        .map(|eq| (eq.key, eq.readout))
        .collect();
    let blocks = page::document()
        .query_selector_all(".live-math .equation")
        .unwrap();
    assert!(blocks.length() > 0, "{why}: {id} shows its equations");
    for i in 0..blocks.length() {
        let block: web_sys::Element = blocks.item(i).unwrap().dyn_into().unwrap();
        let key = block.get_attribute("data-key").unwrap();
        let result = block
            .query_selector(".equation-result")
            .unwrap()
            .unwrap()
            .text_content()
            .unwrap_or_default();
        let readout = element(&format!("[data-readout=\"{}\"]", readout_of[key.as_str()]))
            .text_content()
            .unwrap_or_default();
        assert!(
            result.trim().is_empty() || result.trim() == format!("= {}", readout.trim()),
            "{why}: {key}'s result {result} is not its readout {readout}"
        );
    }
}

/// A pause (an input) and a run's own end (a motion that stops) write the
/// readouts and every equation in the frame that shows them, whatever a
/// streaming run's idle chain had still to write: the status a run ends
/// with and its readouts change together (a student, or a test, reading
/// "reached all 2 waypoints" read "1 of 2" beside it while the idle time
/// had not come).
#[wasm_bindgen_test]
fn a_pause_or_a_run_that_ends_writes_all_of_the_math_in_its_frame() {
    // ekf: several equations, an idle chain half done when the pause comes.
    let _in_view = mount_ekf_with_the_math_panel_in_view();
    let mut paused_mid_chain = false;
    for _ in 0..120 {
        frame_alone(ONE_STEP_MS);
        if !idle_asked() {
            continue;
        }
        idle();
        if idle_asked() {
            paused_mid_chain = true;
            break;
        }
    }
    assert!(paused_mid_chain, "a text update left several idle times");
    element("button[data-time=play]").click();
    frame_alone(ONE_STEP_MS);
    each_result_is_its_readout("ekf", "paused mid-chain, before any idle time");
    let shown = texts(".live-math .equation-result");
    while idle_asked() {
        idle();
    }
    assert_eq!(
        texts(".live-math .equation-result"),
        shown,
        "the idle times after the pause have nothing left to write"
    );
    drop(_in_view);
    // pid: the run settles and ends on its own while the idle time, asked
    // for at every text update, has not come.
    let _in_view = mount_with_the_math_panel_in_view("#/pid/simulation");
    let ended = || labweb::inspect_sim(|exp, _| exp.status().phase == Phase::Ended).unwrap();
    let mut frames = 0;
    let mut left_to_idle = 0;
    while !ended() {
        frame_alone(ONE_STEP_MS);
        left_to_idle += usize::from(idle_asked());
        frames += 1;
        assert!(frames < 3000, "pid's run ends");
    }
    assert!(
        left_to_idle > 0,
        "the run's text updates waited for the idle time"
    );
    each_result_is_its_readout("pid", "the frame the run ended in");
    assert_eq!(math_result(), format!("= {}", pid_force()), "u at the end");
    let model: Vec<String> =
        labweb::inspect_sim(|exp, _| exp.readouts().into_iter().map(|r| r.value).collect())
            .unwrap();
    assert_eq!(
        texts(".readouts dd"),
        model,
        "the readouts the run ended with, in its last frame"
    );
}

/// A timeline scrub is a stream of input: the frames of the drag write
/// none of "The math" panel's equations, even out of the window (the page
/// is paused, so its text is written whether seen or not), and leave them
/// to the browser's idle time; letting go writes them in its own frame.
#[wasm_bindgen_test]
fn a_scrub_drag_leaves_the_math_panel_to_the_idle_time() {
    mount("#/pid/simulation");
    for _ in 0..120 {
        frame(ONE_STEP_MS);
    }
    element("button[data-time=play]").click();
    frame(ONE_STEP_MS);
    let scrub = ScrubDrag::grab();
    let mut written_in_idle = 0;
    for i in 0..60 {
        scrub.move_to_spread(i);
        let before = math_result();
        frame_alone(ONE_STEP_MS);
        assert_eq!(math_result(), before, "scrub frame {i} wrote the panel");
        idle();
        if math_result() != before {
            written_in_idle += 1;
        }
    }
    assert!(
        written_in_idle >= 2,
        "the idle time wrote the panel {written_in_idle} times in a 1 s drag"
    );
    // Let go at another moment: its frame writes the panel at once.
    scrub.move_to(scrub.lo);
    scrub.send("change");
    frame_alone(ONE_STEP_MS);
    let force = pid_force();
    assert_eq!(
        math_result(),
        format!("= {force}"),
        "let go: written in its frame"
    );
    idle();
}

/// While a run streams, "The math" panel never gets shorter: its tallest
/// height so far is held (a substituted form wrapping onto fewer lines
/// would move the page below it up and down four times a second); an input,
/// a pause or the run's end lets it take its own height again.
#[wasm_bindgen_test]
fn a_streaming_run_holds_the_math_panel_at_its_tallest_until_it_pauses() {
    let _in_view = mount_ekf_with_the_math_panel_in_view();
    let panel = element(".live-math");
    // Narrow, so the substituted forms wrap as their numbers change width.
    panel.style().set_property("width", "180px").unwrap();
    let mut tallest = 0;
    let mut held = 0;
    for _ in 0..240 {
        frame(ONE_STEP_MS);
        let height = panel.offset_height();
        assert!(
            height >= tallest,
            "the panel got shorter: {height} < {tallest} px"
        );
        tallest = height;
        let min_height = panel.style().get_property_value("min-height").unwrap();
        if !min_height.is_empty() {
            held += 1;
            assert_eq!(min_height, format!("{tallest}px"), "held at its tallest");
        }
    }
    assert!(held > 0, "the panel was held while the run streamed");
    element("button[data-time=play]").click();
    for _ in 0..3 {
        frame(ONE_STEP_MS);
    }
    assert_eq!(
        panel.style().get_property_value("min-height").unwrap(),
        "",
        "paused: the panel takes its own height"
    );
}

/// A streaming run rewrites an equation's numbers in place: while a term
/// of a formula keeps its shape, its elements stay the same ones (nothing
/// is parsed anew for the browser to style), only their text changes; and
/// each number stays where the markup puts it.
#[wasm_bindgen_test]
fn a_streaming_run_rewrites_the_numbers_of_an_equation_in_place() {
    let _in_view = mount_ekf_with_the_math_panel_in_view();
    let (in_place, _, _) = terms_rewritten_while_running(900);
    assert!(
        in_place >= 10,
        "terms whose numbers changed in place: {in_place}"
    );
    assert_numbers_are_their_twins();
}

/// The same where numbers change sign as the pole swings (cartpole's
/// u = −Kx): a number's sign and brackets are in its `<mn>`, so a term
/// whose number gains or loses its minus keeps its elements too, and no
/// term is written anew.
#[wasm_bindgen_test]
fn a_number_that_changes_sign_is_rewritten_in_place() {
    let _in_view = mount_with_the_math_panel_in_view("#/cartpole/simulation");
    // A push sets the pole swinging.
    element(".sim-actions button[data-action=nudge]").click();
    frame(ONE_STEP_MS);
    let (in_place, reshaped, signs) = terms_rewritten_while_running(900);
    assert!(
        in_place >= 10,
        "terms whose numbers changed in place: {in_place}"
    );
    assert!(signs >= 1, "a number changed sign in place: {signs}");
    assert_eq!(reshaped, 0, "terms written anew");
    assert_numbers_are_their_twins();
}

/// `dom::rewrite_markup` (main.js's `labRewriteMarkup`) leaves what
/// `innerHTML` would, whatever came before: markup written by other means,
/// the same tags with other texts
/// (entities among them, the shape's fast path), another shape, another
/// attribute, a text that became empty, a reference it does not decode, an
/// element's text that gains a `<`, plain text into a lone text node (with
/// a `\r` or NUL, which the parser rewrites).
#[wasm_bindgen_test]
fn rewriting_markup_in_place_leaves_what_inner_html_would() {
    let document = web_sys::window().unwrap().document().unwrap();
    let kept = document.create_element("div").unwrap();
    let fresh = document.create_element("div").unwrap();
    let term = |n: &str| {
        format!(
            "<span class=\"eq-part\"><math><mo>=</mo><mn>{n}</mn><mo>&#x2061;</mo><mi>cos</mi></math></span> <span>m</span>"
        )
    };
    // Written before by other means: nothing is known of its shape.
    kept.set_inner_html("<b>old</b>");
    let steps = [
        "plain at first".into(),
        term("1.00"),
        term("1.25"),
        term("&lt;2"),
        term("3&#955;"),
        term(""),
        term("4"),
        term("5&nbsp;6"),
        term("7&amp;8"),
        term("9"),
        "<span class=\"eq-part\"><math><mo>(</mo><mn>-1</mn><mo>)</mo></math></span> <span>m</span>".into(),
        "<span class=\"other\"><math><mo>(</mo><mn>-2</mn><mo>)</mo></math></span> <span>m</span>".into(),
        "plain text &quot;q&quot; &#39;".into(),
        "plain text again".into(),
        // Plain text into a lone text node: written to it without a parse,
        // but a `\r` or NUL still goes through the parser, as innerHTML.
        "plain once more".into(),
        "line\r\nbreak".into(),
        "nul\u{0}byte".into(),
        "plain at last".into(),
        String::new(),
        term("10"),
    ];
    for (i, html) in steps.iter().enumerate() {
        let numbers_before = kept.query_selector("mn").unwrap();
        labweb::dom::rewrite_markup(&kept, html);
        fresh.set_inner_html(html);
        assert_eq!(kept.inner_html(), fresh.inner_html(), "step {i}: {html}");
        if !html.is_empty() {
            assert_eq!(
                kept.child_nodes().length(),
                fresh.child_nodes().length(),
                "step {i}: {html}"
            );
        }
        if i == 2 || i == 9 {
            let numbers_after = kept.query_selector("mn").unwrap();
            assert!(
                numbers_after.is_some()
                    && numbers_after
                        .as_ref()
                        .unwrap()
                        .is_same_node(numbers_before.as_ref().map(|n| n.as_ref())),
                "step {i}: the number's element is kept"
            );
        }
    }
}

/// Runs `frames` frames of the mounted simulation, checking after each that
/// every term of "The math" that kept its shape (its elements' names in
/// order) kept its elements. Returns how many terms changed their numbers
/// in place, how many changed shape, and how many of the in-place changes
/// turned a number's sign.
fn terms_rewritten_while_running(frames: usize) -> (usize, usize, usize) {
    let terms = || {
        web_sys_all(".live-math .equation-numbers .eq-part")
            .iter()
            .map(|term| {
                let all = term.query_selector_all("*").unwrap();
                let shape: Vec<String> = (0..all.length())
                    .filter_map(|i| all.get(i))
                    .map(|n| n.node_name())
                    .collect();
                let mns = term.query_selector_all("mn").unwrap();
                let mns: Vec<web_sys::Node> =
                    (0..mns.length()).filter_map(|i| mns.get(i)).collect();
                (shape, mns)
            })
            .collect::<Vec<_>>()
    };
    for _ in 0..20 {
        frame(ONE_STEP_MS);
    }
    let (mut in_place, mut reshaped, mut signs) = (0, 0, 0);
    for _ in 0..frames {
        let before = terms();
        let before_text: Vec<Vec<Option<String>>> = before
            .iter()
            .map(|(_, mns)| mns.iter().map(web_sys::Node::text_content).collect())
            .collect();
        frame(ONE_STEP_MS);
        let after = terms();
        assert_eq!(after.len(), before.len(), "as many terms");
        for (i, ((shape, mns), (shape_was, mns_was))) in after.iter().zip(&before).enumerate() {
            if shape != shape_was {
                reshaped += 1;
                continue;
            }
            assert!(
                mns.iter()
                    .zip(mns_was)
                    .all(|(a, b)| a.is_same_node(Some(b))),
                "term {i} kept its shape and its elements"
            );
            let text: Vec<Option<String>> = mns.iter().map(web_sys::Node::text_content).collect();
            if text != before_text[i] {
                in_place += 1;
                let negative = |t: &Option<String>| t.as_deref().is_some_and(|t| t.contains('−'));
                if text
                    .iter()
                    .zip(&before_text[i])
                    .any(|(a, b)| negative(a) != negative(b))
                {
                    signs += 1;
                }
            }
        }
    }
    (in_place, reshaped, signs)
}

/// Every number of a formula is in its text twin, written from the same
/// update: the text went to the right nodes.
fn assert_numbers_are_their_twins() {
    for block in web_sys_all(".live-math [data-equation]") {
        let twin = block
            .query_selector(".equation-text")
            .unwrap()
            .and_then(|t| t.text_content())
            .unwrap_or_default();
        let mns = block.query_selector_all(".equation-numbers mn").unwrap();
        for i in 0..mns.length() {
            let n = mns
                .get(i)
                .and_then(|n| n.text_content())
                .unwrap_or_default();
            // The twin reads a plain space where the number keeps its unit
            // by a narrow one.
            let n = n.replace('\u{202F}', " ");
            assert!(
                !n.is_empty() && twin.contains(&n),
                "{n:?} is a number of {twin:?}"
            );
        }
    }
}

/// Mounts ekf's simulation with "The math" panel fixed at the window's top,
/// in view (the test page is short).
#[must_use]
fn mount_ekf_with_the_math_panel_in_view() -> MathInView {
    mount_with_the_math_panel_in_view("#/ekf/simulation")
}

/// Mounts `route` with "The math" panel fixed at the window's top, in view,
/// by a style rule (which also holds for a panel written anew when another
/// set of equations applies) that lasts as long as the returned guard.
#[must_use]
fn mount_with_the_math_panel_in_view(route: &str) -> MathInView {
    mount(route);
    let document = web_sys::window().unwrap().document().unwrap();
    let style = document.create_element("style").unwrap();
    style.set_text_content(Some(".live-math { position: fixed; top: 0; }"));
    document.body().unwrap().append_child(&style).unwrap();
    MathInView(style)
}

/// The rule that keeps "The math" in view; dropped, it is gone.
struct MathInView(web_sys::Element);

impl Drop for MathInView {
    fn drop(&mut self) {
        self.0.remove();
    }
}

fn web_sys_all(selector: &str) -> Vec<web_sys::Element> {
    let list = web_sys::window()
        .unwrap()
        .document()
        .unwrap()
        .query_selector_all(selector)
        .unwrap();
    (0..list.length())
        .filter_map(|i| list.get(i))
        .filter_map(|n| n.dyn_into::<web_sys::Element>().ok())
        .collect()
}

/// Issue 26, cost: once the record holds a replay to go back to, the
/// browser's idle time rehearses a scrub (its code compiled before a
/// student's first drag), and nothing shown changes: not the model, not
/// the time, not the timeline, not a pixel of the scene.
#[wasm_bindgen_test]
fn a_scrub_is_rehearsed_in_idle_time_and_changes_nothing_shown() {
    mount("#/pid/simulation");
    let canvas: web_sys::HtmlCanvasElement = element("canvas.sim-canvas").dyn_into().unwrap();
    let rehearsed = || canvas.has_attribute("data-scrub-rehearsed");
    let slider: web_sys::HtmlInputElement = element(".tb-scrub").dyn_into().unwrap();
    let seen = || {
        (
            labweb::inspect_sim(|exp, steps| (page::snapshot(exp), steps)).unwrap(),
            text(".tb-time"),
            (slider.min(), slider.max(), slider.value()),
            canvas.to_data_url().unwrap(),
            hash(),
        )
    };
    // A record shorter than two snapshot intervals has nothing to rehearse.
    for _ in 0..30 {
        frame(ONE_STEP_MS);
    }
    assert!(!rehearsed(), "30 steps: too short to rehearse");
    run_until_the_rehearsal_is_asked_for();
    let before = seen();
    idle();
    assert!(rehearsed(), "the idle time rehearsed a scrub");
    assert!(
        before == seen(),
        "the rehearsal changed what the page shows"
    );
    // A scrub after it is exact, as ever.
    let drag = ScrubDrag::grab();
    drag.move_to(drag.lo + 0.5 * (drag.hi - drag.lo));
    drag.send("change");
    frame(ONE_STEP_MS);
    let (steps, model) = labweb::inspect_sim(|exp, steps| (steps, page::snapshot(exp))).unwrap();
    let entry = labcore::registry().iter().find(|e| e.id == "pid").unwrap();
    assert_eq!(
        model,
        page::snapshot(page::left_alone(entry, steps).as_ref())
    );
}

/// A scrub that comes before the idle time leaves the rehearsal nothing to
/// do: its code has run.
#[wasm_bindgen_test]
fn a_scrub_before_the_idle_time_needs_no_rehearsal() {
    mount("#/pid/simulation");
    let canvas = element("canvas.sim-canvas");
    run_until_the_rehearsal_is_asked_for();
    let drag = ScrubDrag::grab();
    drag.move_to(drag.lo + 0.25 * (drag.hi - drag.lo));
    drag.send("change");
    idle();
    assert!(
        !canvas.has_attribute("data-scrub-rehearsed"),
        "the idle time rehearsed a scrub after a real one"
    );
}

/// Runs frames, with no idle time after them, until the page has asked
/// for the rehearsal of a scrub (its record is two snapshot intervals long
/// and an idle callback is queued).
fn run_until_the_rehearsal_is_asked_for() {
    let due = || {
        labweb::inspect_sim(|_, steps| steps >= 2 * labcore::timeline::Timeline::FIRST_INTERVAL)
            .unwrap()
    };
    let mut frames = 0;
    while !idle_asked() || !due() {
        frame_alone(ONE_STEP_MS);
        frames += 1;
        assert!(frames < 200, "the rehearsal is asked for");
    }
}
