//! The browser benchmark's same-run A/B switches (labweb's `bench-exports`
//! feature, `tests/bench/browser.bench.mjs`): B must be the page as it was
//! before the feature compared, or the comparison says nothing. Frames are
//! driven by the test (`page`), so no step depends on the wall clock.

use wasm_bindgen_test::*;

mod page;
use page::{attr, element, frame, left_alone, mount, shown, snapshot, text, ONE_STEP_MS};

wasm_bindgen_test_configure!(run_in_browser);

fn frames(n: usize) {
    for _ in 0..n {
        frame(ONE_STEP_MS);
    }
    labweb::paint_now();
}

/// Issue 26 §4, "running frames no slower than today", B: with the
/// timeline switched off the run steps unrecorded (the slider stays where
/// the record ended) and exactly as recorded; switched on again, a new
/// record starts from the step shown and follows the run.
#[wasm_bindgen_test]
fn bench_timeline_recording_off_steps_unrecorded_and_on_records_anew() {
    mount("#/pid/simulation");
    let entry = labcore::find("pid").unwrap();
    frames(60);
    let off_at = shown().0;
    assert!(labweb::bench_timeline_recording(false));
    frames(60);
    let on_at = shown().0;
    assert!(on_at >= off_at + 50, "{off_at} → {on_at} steps");
    assert_eq!(attr(".tb-scrub", "max"), Some(off_at.to_string()));
    assert_eq!(
        shown(),
        (on_at, snapshot(left_alone(entry, on_at).as_ref()))
    );
    assert!(labweb::bench_timeline_recording(true));
    frames(60);
    let end = shown().0;
    assert_eq!(attr(".tb-scrub", "min"), Some(on_at.to_string()));
    assert_eq!(attr(".tb-scrub", "max"), Some(end.to_string()));
    assert_eq!(shown(), (end, snapshot(left_alone(entry, end).as_ref())));
}

/// Issue 27 Cost, "running frames … with the panel open", B: closed, "The
/// math" is hidden and no longer written while the run goes on; open
/// again, it shows and is written anew with the run's numbers now.
#[wasm_bindgen_test]
fn bench_math_panel_closed_is_hidden_and_unwritten_and_open_writes_it_anew() {
    mount("#/pid/simulation");
    frames(20);
    let result = "[data-equation=\"0\"] .equation-result";
    let key = attr("[data-equation=\"0\"]", "data-key").unwrap();
    assert!(labweb::bench_math_panel(false));
    assert!(element(".live-math").hidden());
    let frozen = text(result);
    frames(60);
    assert_eq!(text(result), frozen);
    let now = labweb::inspect_sim(|exp, _| {
        let eq = exp.equations().iter().find(|e| e.key == key).unwrap();
        labpage::math_panel::live_parts(eq, &exp.quantities(), &exp.readouts()).1
    })
    .unwrap();
    assert_ne!(now, frozen, "the run moved the result");
    assert!(labweb::bench_math_panel(true));
    assert!(!element(".live-math").hidden());
    labweb::paint_now();
    assert_eq!(text(result), now);
}
