//! The work a frame does, counted (never timed): what the page asks of the
//! browser while a simulation runs with its plots streaming. These counts
//! hold the gains measured on a throttled phone (`cargo xtask bench
//! --browser`, issue 16 §3): plots take turns, one a frame; nothing unchanged
//! is written to the page; sizes are read before anything is written (no
//! forced layout); text is measured once; a long series is drawn with at
//! most a rectangle per pixel column.
//!
//! The browser's own methods are wrapped by a spy (installed once, below)
//! that counts calls per kind of canvas: the simulation canvas, or a plot.

use glam::DVec2;
use labcore::plot::{Plot, Series, SeriesRole};
use wasm_bindgen::JsCast;
use wasm_bindgen::JsValue;
use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

mod page;
use page::observers_report;

fn document() -> web_sys::Document {
    web_sys::window().unwrap().document().unwrap()
}

/// Wraps the canvas and DOM methods a frame may call with counters in
/// `window.__spy`. A canvas call counts for `sim` on the simulation canvas
/// and for `plot` on any other (a plot's canvas or its off-screen one); a
/// size read (`getBoundingClientRect`) after a DOM write in the same frame
/// counts as a forced layout.
const SPY: &str = r#"
if (!window.__spy) {
  const spy = (window.__spy = { c: {}, dirty: false, plotPaints: new Map() });
  const bump = (k) => (spy.c[k] = (spy.c[k] || 0) + 1);
  const kind = (ctx) => (ctx.canvas && ctx.canvas.classList && ctx.canvas.classList.contains("sim-canvas") ? "sim" : "plot");
  const protos = [window.CanvasRenderingContext2D, window.OffscreenCanvasRenderingContext2D]
    .filter(Boolean).map((c) => c.prototype);
  for (const proto of protos) {
    for (const m of ["fillText", "strokeText", "measureText", "lineTo", "moveTo", "setTransform", "fillRect"]) {
      const orig = proto[m];
      proto[m] = function (...a) {
        bump(`${kind(this)}.${m}`);
        if (m === "setTransform" && kind(this) === "plot") {
          spy.plotPaints.set(this.canvas, (spy.plotPaints.get(this.canvas) || 0) + 1);
        }
        return orig.apply(this, a);
      };
    }
    const font = Object.getOwnPropertyDescriptor(proto, "font");
    Object.defineProperty(proto, "font", {
      get: font.get,
      set(v) { bump(`${kind(this)}.font`); font.set.call(this, v); },
    });
  }
  const writes = [
    [Node.prototype, "textContent"], [Element.prototype, "innerHTML"], [HTMLElement.prototype, "hidden"],
    // A text rewritten in its node (labweb's dom::set_text).
    [CharacterData.prototype, "data"], [Node.prototype, "nodeValue"],
  ];
  const textWrites = ["textContent", "data", "nodeValue"];
  for (const [proto, p] of writes) {
    const d = Object.getOwnPropertyDescriptor(proto, p);
    Object.defineProperty(proto, p, {
      get: d.get,
      set(v) {
        bump(`dom.${p}`); bump("dom.writes"); spy.dirty = true;
        if (textWrites.includes(p)) bump("dom.text");
        const el = this.nodeType === 1 ? this : this.parentElement;
        bump(`dom.${p}@${el && el.className}`);
        d.set.call(this, v);
      },
    });
  }
  const replaceState = History.prototype.replaceState;
  History.prototype.replaceState = function (...a) {
    bump("history.replaceState");
    return replaceState.apply(this, a);
  };
  for (const m of ["setAttribute", "removeAttribute"]) {
    const orig = Element.prototype[m];
    Element.prototype[m] = function (...a) {
      bump(`dom.${m}`); bump("dom.writes"); spy.dirty = true;
      return orig.apply(this, a);
    };
  }
  // Nodes replaced by a text write that cannot reuse its node (empty to text).
  for (const [proto, m] of [[Element.prototype, "replaceChildren"], [Element.prototype, "replaceWith"], [CharacterData.prototype, "replaceWith"]]) {
    const orig = proto[m];
    proto[m] = function (...a) {
      if (this.isConnected) { bump(`dom.${m}`); bump("dom.writes"); bump("dom.text"); spy.dirty = true; }
      return orig.apply(this, a);
    };
  }
  const rect = Element.prototype.getBoundingClientRect;
  Element.prototype.getBoundingClientRect = function () {
    bump("dom.sizeReads");
    if (this.classList && this.classList.contains("sim-canvas")) bump("dom.simCanvasSizeReads");
    if (spy.dirty) bump("dom.forcedLayouts");
    spy.dirty = false;
    return rect.call(this);
  };
}
// A new count: the page is laid out (as between two real frames).
window.__spy.c = {};
window.__spy.dirty = false;
window.__spy.plotPaints = new Map();
"#;

/// Installs the spy (once) and zeroes its counts.
fn reset_counts() {
    js_sys::Function::new_no_args(SPY)
        .call0(&JsValue::NULL)
        .unwrap();
}

/// The count of `key` since the last [`reset_counts`].
fn count(key: &str) -> u32 {
    js_sys::Function::new_with_args("k", "return window.__spy.c[k] || 0")
        .call1(&JsValue::NULL, &JsValue::from_str(key))
        .unwrap()
        .as_f64()
        .unwrap() as u32
}

/// Paints per plot canvas since the last [`reset_counts`].
fn plot_paints() -> Vec<u32> {
    let v = js_sys::Function::new_no_args("return [...window.__spy.plotPaints.values()]")
        .call0(&JsValue::NULL)
        .unwrap();
    js_sys::Array::from(&v)
        .iter()
        .map(|n| n.as_f64().unwrap() as u32)
        .collect()
}

/// A stand-in for the experiments with several live plots (cart-pole and
/// EKF have four): every step adds a sample to each plot, while its
/// readouts and scene labels stay the same.
#[derive(Clone)]
struct Streamer {
    t_s: f64,
    plots: Vec<Plot>,
    /// Where a drag last moved the pointer (world x, m).
    dragged_x_m: f64,
}

/// Labels on the stand-in's scene.
const LABELS: usize = 6;

impl Streamer {
    fn new(n_plots: usize, samples: usize) -> Self {
        let keys = ["a", "b", "c", "d"];
        let plots = keys[..n_plots]
            .iter()
            .map(|key| {
                let mut p = Plot::new(
                    key,
                    "Signal",
                    ("Time", "s"),
                    ("Value", "m"),
                    vec![
                        Series::new("now", "m", SeriesRole::Primary),
                        Series::new("model", "m", SeriesRole::Secondary),
                    ],
                );
                for i in 0..samples {
                    let t = i as f64 * 1e-3;
                    p.series[0].push(t, (t * 40.0).sin());
                    p.series[1].push(t, (t * 7.0).cos());
                }
                p
            })
            .collect();
        Self {
            t_s: 0.0,
            plots,
            dragged_x_m: 0.0,
        }
    }
}

impl labcore::Experiment for Streamer {
    fn id(&self) -> &'static str {
        "streamer"
    }
    fn params(&self) -> &'static [labcore::ParamSpec] {
        &[]
    }
    fn param(&self, _key: &str) -> Option<f64> {
        None
    }
    fn set_param(&mut self, key: &str, _v: f64) -> Result<labcore::Sanitized, labcore::ParamError> {
        Err(labcore::ParamError::UnknownKey { key: key.into() })
    }
    fn input(&mut self, input: labcore::Input) {
        if let labcore::Input::PointerMove { pos, pressed: true } = input {
            self.dragged_x_m = pos.x;
        }
    }
    fn step(&mut self, dt_s: f64) {
        self.t_s += dt_s;
        let t = self.t_s;
        for p in &mut self.plots {
            p.series[0].push(t, (t * 3.0).sin());
            p.series[1].push(t, (t * 3.0).sin() * 0.9);
            p.touch();
        }
    }
    fn animated(&self) -> bool {
        true
    }
    fn plots(&self) -> &[Plot] {
        &self.plots
    }
}

impl labcore::Presentation for Streamer {
    fn view(&self) -> labcore::ViewBox {
        labcore::ViewBox::centered(3.0)
    }
    fn scene(&self, out: &mut labcore::Scene) {
        let x = (self.t_s * 2.0).sin();
        out.items.push(labcore::Item::Line {
            from: DVec2::ZERO,
            to: DVec2::new(x, 1.0),
            width_px: 3.0,
            role: labcore::Role::Link,
            dashed: false,
        });
        for k in 0..LABELS {
            out.items.push(labcore::Item::Label {
                pos: DVec2::new(k as f64 - 2.5, -1.0),
                text: format!("{k} m"),
                role: labcore::Role::Text,
                offset_px: DVec2::ZERO,
            });
        }
    }
    fn readouts(&self) -> Vec<labcore::Readout> {
        vec![
            labcore::Readout::new("gain", "Gain", "2.00".to_owned()),
            labcore::Readout::new("mode", "Mode", "streaming".to_owned()),
            labcore::Readout::new("clock", "Clock", format!("{:.3} s", self.t_s)),
            labcore::Readout::new("drag", "Dragged to", format!("{:.4} m", self.dragged_x_m)),
        ]
    }
    fn status(&self) -> labcore::Status {
        labcore::Status::new("streaming", labcore::Tone::Neutral)
    }
    fn hint(&self) -> &'static str {
        "streamer"
    }
}

/// Mounts a [`Streamer`] in a bare Simulation panel (no animation loop: the
/// test runs the frames) and paints it once. Every plot is pinned to the top
/// of the window, in view whatever the test runner's window size.
fn mount(exp: Streamer) -> labweb::sim::SimView {
    mount_experiment(exp, "streamer")
}

/// Mounts any experiment on a 360 × 300 px canvas.
fn mount_experiment(exp: impl labcore::Lab + 'static, caption: &str) -> labweb::sim::SimView {
    labweb::unmount();
    if let Some(old) = document().get_element_by_id("lab-under-test") {
        old.remove();
    }
    let panel = document().create_element("div").unwrap();
    panel.set_id("lab-under-test");
    document().body().unwrap().append_child(&panel).unwrap();
    panel.set_inner_html(&format!(
        "<style>#lab-under-test{{width:390px}}.sim-canvas{{display:block;width:360px;height:300px}}\
         .plot-canvas{{display:block;width:360px;height:200px}}\
         #lab-under-test figure.plot{{position:fixed;top:0;left:0;width:360px}}</style>{}",
        labweb::sim::render(&exp, caption)
    ));
    let view = labweb::sim::SimView::mount(&panel, Box::new(exp)).unwrap();
    view.paint_now();
    view
}

/// Frame times of a 60 Hz display, ms (16.7 ms apart: one fixed step of
/// 1/60 s each, now and then two).
fn frame_ms(i: usize) -> f64 {
    1000.0 + i as f64 * 16.7
}

#[wasm_bindgen_test]
fn four_streaming_plots_take_turns_one_paint_a_frame_each_about_every_66_ms() {
    let view = mount(Streamer::new(4, 200));
    // Frame 0 only starts the clock; from frame 1 on every plot has new
    // data at every frame. The plots take turns: in frames 1 to 8 each is
    // painted twice, once every fourth frame (4 × 16.7 ms ≥ 66 ms).
    reset_counts();
    run_frames(&view, 0..9);
    let per_plot = plot_paints();
    assert_eq!(per_plot, [2, 2, 2, 2], "paints per plot in frames 0 to 8");
    // Two seconds more: never two plot paints in one frame, and each plot
    // still about every 66 ms.
    let mut most_in_a_frame = 0;
    let mut total = 0;
    for i in 9..129 {
        reset_counts();
        view.frame_at(frame_ms(i));
        let n: u32 = plot_paints().iter().sum();
        most_in_a_frame = most_in_a_frame.max(n);
        total += n;
    }
    assert!(
        most_in_a_frame <= 1,
        "{most_in_a_frame} plot paints in one frame"
    );
    // 120 frames, less the one in fifteen that writes the page's text
    // (every 250 ms) and paints no plot: 112, 28 a plot.
    assert!(total >= 4 * 26, "{total} plot paints in 120 frames");
}

/// Plot b's canvas in [`a_plot_out_of_view_is_painted_once_a_second_and_at_once_when_it_comes_back`].
const B_CANVAS: &str = "#lab-under-test figure[data-plot=\"b\"] canvas";

/// Paints since the last [`reset_counts`] of the plot whose canvas is
/// `width_px` device pixels wide.
fn plot_paints_at_width(width_px: u32) -> u32 {
    js_sys::Function::new_with_args(
        "w",
        "let n = 0; for (const [c, k] of window.__spy.plotPaints) if (c.width === w) n += k; return n",
    )
    .call1(&JsValue::NULL, &JsValue::from(width_px))
    .unwrap()
    .as_f64()
    .unwrap() as u32
}

#[wasm_bindgen_test]
async fn a_plot_out_of_view_is_painted_once_a_second_and_at_once_when_it_comes_back() {
    let view = mount(Streamer::new(2, 200));
    // Plot b's canvas is narrower than plot a's, to tell their paints apart.
    let b_style = |css: &str| {
        document()
            .query_selector(B_CANVAS)
            .unwrap()
            .unwrap()
            .set_attribute("style", &format!("width: 300px; {css}"))
            .unwrap();
    };
    b_style("");
    view.paint_now();
    let dpr = web_sys::window().unwrap().device_pixel_ratio();
    let (a_px, b_px) = ((360.0 * dpr).round() as u32, (300.0 * dpr).round() as u32);
    run_frames(&view, 0..10);
    // Plot b scrolls far below the window (the browser's observers tell the
    // page after its next layout).
    b_style("margin-top: 20000px");
    observers_report(B_CANVAS).await;
    reset_counts();
    // Two seconds of streaming.
    run_frames(&view, 10..130);
    // The plot in view about every 66 ms (a few frames go to the page's
    // text); the other once a second (labweb::plot_view::HIDDEN_PLOT_INTERVAL_MS).
    let (a, b) = (plot_paints_at_width(a_px), plot_paints_at_width(b_px));
    assert!(a >= 24, "plot a painted {a} times");
    assert!((1..=3).contains(&b), "plot b painted {b} times");
    // Scrolled back into view: painted as soon as the plots are measured
    // again, within PLOT_INTERVAL_MS (four frames).
    b_style("");
    observers_report(B_CANVAS).await;
    reset_counts();
    run_frames(&view, 130..134);
    assert_eq!(
        plot_paints_at_width(b_px),
        1,
        "the plot back in view was not repainted"
    );
}

#[wasm_bindgen_test]
fn a_frame_reads_every_size_before_it_writes_so_the_page_is_never_laid_out_mid_frame() {
    let view = mount(Streamer::new(4, 200));
    let mut forced = 0;
    let mut reads = 0;
    for i in 0..60 {
        reset_counts();
        view.frame_at(frame_ms(i));
        forced += count("dom.forcedLayouts");
        reads += count("dom.sizeReads");
    }
    assert!(reads > 0, "the frames read the canvas sizes");
    assert_eq!(forced, 0, "size reads after a write in the same frame");
}

/// Runs the frames numbered `frames` (see [`frame_ms`]).
fn run_frames(view: &labweb::sim::SimView, frames: std::ops::Range<usize>) {
    for i in frames {
        view.frame_at(frame_ms(i));
    }
}

/// Clicks the time bar's Play/Pause button.
fn press_play() {
    document()
        .query_selector("#lab-under-test .tb-play")
        .unwrap()
        .unwrap()
        .dyn_into::<web_sys::HtmlElement>()
        .unwrap()
        .click();
}

#[wasm_bindgen_test]
fn repainting_what_has_not_changed_writes_nothing_to_the_page_and_measures_no_text() {
    let view = mount(Streamer::new(4, 200));
    run_frames(&view, 0..30);
    // Paused: the data, readouts and time stand still.
    press_play();
    view.paint_now();
    reset_counts();
    // A full repaint of the scene and of every plot (as after a theme change).
    view.paint_now();
    assert_eq!(count("plot.setTransform"), 4, "every plot repainted");
    assert_eq!(
        count("dom.writes"),
        0,
        "DOM writes: text {}, innerHTML {}, hidden {}, setAttribute {}, removeAttribute {}",
        count("dom.text"),
        count("dom.innerHTML"),
        count("dom.hidden"),
        count("dom.setAttribute"),
        count("dom.removeAttribute")
    );
    assert_eq!(count("plot.measureText"), 0, "plot texts are measured once");
    assert_eq!(
        count("sim.measureText"),
        0,
        "scene labels are measured once"
    );
    // One font a plot paint; the scene's labels set theirs once, not per label.
    assert_eq!(count("plot.font"), 4);
    assert_eq!(count("sim.font"), 1, "{LABELS} labels, one font setting");
    assert_eq!(count("sim.fillText"), LABELS as u32);
}

/// The text of the `<dd>` of readout `key` on the page.
fn readout_text(key: &str) -> String {
    document()
        .query_selector(&format!("#lab-under-test [data-readout=\"{key}\"]"))
        .unwrap()
        .unwrap()
        .text_content()
        .unwrap_or_default()
}

#[wasm_bindgen_test]
fn while_a_run_streams_the_page_text_is_written_every_250_ms_and_never_in_a_plot_frame() {
    // The clock readout and the time change at every step.
    let view = mount(Streamer::new(1, 10));
    run_frames(&view, 0..10);
    let mut text_frames = Vec::new();
    let summary = || {
        document()
            .query_selector("#lab-under-test .plot-summary")
            .unwrap()
            .unwrap()
            .text_content()
            .unwrap_or_default()
    };
    let mut summaries = vec![summary()];
    for i in 10..70 {
        reset_counts();
        view.frame_at(frame_ms(i));
        if summary() != *summaries.last().unwrap() {
            summaries.push(summary());
        }
        let writes = count("dom.text");
        let plot_paints: u32 = plot_paints().iter().sum();
        if writes > 0 {
            text_frames.push(i);
            assert_eq!(plot_paints, 0, "frame {i} wrote text and painted a plot");
        }
    }
    // 60 frames of 16.7 ms with a write at most every 250 ms
    // (labweb::sim::TEXT_INTERVAL_MS): 4, or 5 with the phase.
    assert!(
        (4..=5).contains(&text_frames.len()),
        "frames that wrote text: {text_frames:?}"
    );
    assert!(
        text_frames
            .windows(2)
            .all(|w| frame_ms(w[1]) - frame_ms(w[0]) >= labweb::sim::TEXT_INTERVAL_MS),
        "{text_frames:?}"
    );
    // The plot's summary for screen readers: once a second
    // (labweb::plot_view::SUMMARY_INTERVAL_MS).
    assert!(summaries.len() <= 3, "{summaries:?}");
}

/// Sends a mouse pointer event of `kind` at client (`x`, `y`) to the
/// simulation canvas, the button held unless it is the `pointerup`.
fn pointer(kind: &str, x: f64, y: f64) {
    let init = web_sys::PointerEventInit::new();
    init.set_is_primary(true);
    init.set_pointer_id(1);
    init.set_pointer_type("mouse");
    init.set_bubbles(true);
    init.set_client_x(x as i32);
    init.set_client_y(y as i32);
    init.set_buttons(u16::from(kind != "pointerup"));
    if kind == "pointerdown" {
        // The canvas has focus: a mouse press that focuses it only does that.
        document()
            .query_selector("#lab-under-test .sim-canvas")
            .unwrap()
            .and_then(|c| c.dyn_into::<web_sys::HtmlElement>().ok())
            .unwrap()
            .focus()
            .unwrap();
    }
    let event = web_sys::PointerEvent::new_with_event_init_dict(kind, &init).unwrap();
    dispatch_on_canvas(&event);
}

#[wasm_bindgen_test]
fn a_drag_writes_the_page_text_at_the_pace_of_a_run_and_its_last_value_when_it_ends() {
    let view = mount(Streamer::new(1, 10));
    press_play();
    view.frame_at(frame_ms(0));
    let rect = document()
        .query_selector("#lab-under-test .sim-canvas")
        .unwrap()
        .unwrap()
        .get_bounding_client_rect();
    let (x0, y) = (rect.left() + 20.0, rect.top() + rect.height() / 2.0);
    pointer("pointerdown", x0, y);
    view.frame_at(frame_ms(1));

    // 28 frames (467 ms) of dragging with a move at every frame, the clock
    // paused; the pointer went down (and the text was written) at frame 1.
    let mut text_frames = Vec::new();
    let mut link_writes = 0;
    for i in 2..30 {
        // 7 px a frame: never through the canvas's centre, where x is 0 m
        // as before the drag.
        pointer("pointermove", x0 + 7.0 * i as f64, y);
        reset_counts();
        view.frame_at(frame_ms(i));
        if count("dom.text") > 0 {
            text_frames.push((i, readout_text("drag")));
        }
        link_writes += count("history.replaceState");
    }
    // The link waits for the drag to end (each URL change makes the browser
    // fetch and decode the page's icon again).
    assert_eq!(link_writes, 0, "URL updates during the drag");
    // Every 250 ms (labweb::sim::TEXT_INTERVAL_MS): once, at frame 16.
    assert_eq!(
        text_frames.len(),
        1,
        "frames that wrote text: {text_frames:?}"
    );
    let during = readout_text("drag");
    pointer("pointerup", x0 + 7.0 * 30.0, y);
    view.frame_at(frame_ms(30));
    assert_ne!(
        readout_text("drag"),
        during,
        "the drag's last value shows when it ends"
    );
    // 250 ms after the last move, the link holds the state it ended in.
    reset_counts();
    run_frames(&view, 31..47);
    assert_eq!(
        count("history.replaceState"),
        1,
        "one URL update after the drag"
    );
}

#[wasm_bindgen_test]
fn pausing_shows_the_readouts_of_the_moment_it_stopped_at_the_next_frame() {
    let view = mount(Streamer::new(1, 10));
    run_frames(&view, 0..37);
    press_play();
    view.frame_at(frame_ms(37));
    // The model's time when it stopped: the steps the clock took, 1/60 s each.
    let steps: f64 = document()
        .query_selector("#lab-under-test .sim-canvas")
        .unwrap()
        .unwrap()
        .get_attribute("data-steps")
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(readout_text("clock"), format!("{:.3} s", steps / 60.0));
    let time = document()
        .query_selector("#lab-under-test .tb-time")
        .unwrap()
        .unwrap()
        .text_content()
        .unwrap();
    assert_eq!(time, format!("t = {:.2} s", steps / 60.0));
}

/// A series denser than the plot's pixel columns is drawn as one rectangle
/// a column (`labcore::plot::column_spans`): a thick stroke through its
/// zigzag of first, lowest, highest and last points rasterised 5–10 times
/// slower in Chromium's software canvas.
#[wasm_bindgen_test]
fn a_plot_of_100000_samples_draws_at_most_one_rectangle_a_series_per_device_pixel_column() {
    let view = mount(Streamer::new(1, 100_000));
    reset_counts();
    view.paint_now();
    let canvas = document()
        .query_selector("#lab-under-test .plot-canvas")
        .unwrap()
        .unwrap();
    let width_px = canvas.get_bounding_client_rect().width();
    assert!((300.0..=400.0).contains(&width_px), "{width_px}");
    // Two series over the plot area (narrower than the canvas): at most a
    // rectangle a device-pixel column each, plus the background and bands.
    let dpr = web_sys::window().unwrap().device_pixel_ratio();
    let rects = count("plot.fillRect");
    let bound = (2.0 * width_px * dpr) as u32 + 10;
    assert!(
        rects <= bound,
        "{rects} rectangles for 200,000 samples, bound {bound}"
    );
    assert!(rects >= 200, "the curves are drawn: {rects}");
    // No path through the samples: the lines left are the grid's and ticks'.
    let points = count("plot.lineTo") + count("plot.moveTo");
    assert!(points <= 60, "{points} path points");
}

/// Presses `key` on the simulation canvas.
fn key_on_canvas(key: &str) {
    let init = web_sys::KeyboardEventInit::new();
    init.set_key(key);
    init.set_bubbles(true);
    let event =
        web_sys::KeyboardEvent::new_with_keyboard_event_init_dict("keydown", &init).unwrap();
    dispatch_on_canvas(&event);
}

/// A held arrow key moving the IK target: each press starts the arm turning
/// and the arm stops before the next, yet the page's text keeps the 250 ms
/// pace (before, every start and stop wrote it: 20 times a second).
#[cfg(feature = "reading")]
#[wasm_bindgen_test]
async fn a_held_key_whose_presses_start_and_end_motions_writes_the_text_at_the_pace() {
    // With the target chosen ([) and moved as a handle, and without (the
    // arrows nudge what the experiment moves by default).
    for choose_handle in [true, false] {
        let view = mount_experiment(labcore::experiments::ik::InverseKinematics::default(), "ik");
        // "The math" panel is below the window: the browser's observers tell
        // the page so, and a stream of input does not write it.
        observers_report("#lab-under-test .live-math").await;
        view.frame_at(frame_ms(0));
        if choose_handle {
            key_on_canvas("]");
        }
        view.frame_at(frame_ms(1));
        let mut text_frames = 0;
        let mut painted = 0;
        for i in 2..62 {
            if i % 3 == 2 {
                // Back and forth, within reach.
                key_on_canvas(if i % 2 == 0 {
                    "ArrowLeft"
                } else {
                    "ArrowRight"
                });
            }
            reset_counts();
            view.frame_at(frame_ms(i));
            if count("dom.text") > 0 {
                text_frames += 1;
            }
            if count("sim.setTransform") > 0 {
                painted += 1;
            }
        }
        assert!(
            painted > 40,
            "handle {choose_handle}: the arm moved in {painted} of 60 frames"
        );
        // One second of presses: every 250 ms, give or take one.
        assert!(
            (3..=5).contains(&text_frames),
            "handle {choose_handle}: frames that wrote text: {text_frames}"
        );
        // Once the key is let go and the arm has stopped, the state is announced.
        run_frames(&view, 62..240);
        let live = document()
            .query_selector("#lab-under-test .sim-live")
            .unwrap()
            .unwrap()
            .text_content()
            .unwrap();
        assert!(
            live.contains("in reach") && live.contains("Arm at θ₁"),
            "handle {choose_handle}: announced: {live}"
        );
    }
}

/// Dispatches `event` on the mounted simulation canvas.
fn dispatch_on_canvas(event: &web_sys::Event) {
    document()
        .query_selector("#lab-under-test .sim-canvas")
        .unwrap()
        .unwrap()
        .dispatch_event(event)
        .unwrap();
}

/// Resolves at the browser's next animation frame (after its rendering
/// steps, where a `ResizeObserver` is told of a resize).
async fn next_browser_frame() {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        let _ = web_sys::window().unwrap().request_animation_frame(&resolve);
    });
    wasm_bindgen_futures::JsFuture::from(promise).await.unwrap();
}

#[wasm_bindgen_test]
async fn a_frame_reads_the_canvas_size_only_after_the_canvas_was_resized() {
    let view = mount(Streamer::new(1, 10));
    // Let the observer report the canvas's first size.
    next_browser_frame().await;
    next_browser_frame().await;
    press_play();
    reset_counts();
    run_frames(&view, 0..30);
    assert_eq!(
        count("dom.simCanvasSizeReads"),
        0,
        "running frames read the canvas's size"
    );
    let canvas: web_sys::HtmlCanvasElement = document()
        .query_selector("#lab-under-test canvas.sim-canvas")
        .unwrap()
        .unwrap()
        .dyn_into()
        .unwrap();
    let dpr = web_sys::window().unwrap().device_pixel_ratio().max(1.0);
    assert_eq!(canvas.width(), (360.0 * dpr).round() as u32);
    canvas.style().set_property("width", "300px").unwrap();
    next_browser_frame().await;
    next_browser_frame().await;
    // The observer read the new size (where layout was clean anyway) and
    // painted the scene at once: the resized canvas, cleared by its new
    // size, is never shown blank.
    let ctx: web_sys::CanvasRenderingContext2d = canvas
        .get_context("2d")
        .unwrap()
        .unwrap()
        .dyn_into()
        .unwrap();
    let corner = ctx.get_image_data(1.0, 1.0, 1.0, 1.0).unwrap().data().0;
    assert_eq!(corner[3], 255, "the resized canvas was painted: {corner:?}");
    // The backing store follows it, and the frames still read nothing.
    reset_counts();
    run_frames(&view, 30..60);
    assert_eq!(canvas.width(), (300.0 * dpr).round() as u32);
    assert_eq!(count("dom.simCanvasSizeReads"), 0);
    // Resized while hidden (another tab shown: the observer sees 0 × 0):
    // the first frame once shown reads and uses the new size, before the
    // observer has said anything.
    let panel: web_sys::HtmlElement = document()
        .get_element_by_id("lab-under-test")
        .unwrap()
        .dyn_into()
        .unwrap();
    panel.style().set_property("display", "none").unwrap();
    next_browser_frame().await;
    next_browser_frame().await;
    canvas.style().set_property("width", "280px").unwrap();
    panel.style().remove_property("display").unwrap();
    view.frame_at(frame_ms(60));
    assert_eq!(canvas.width(), (280.0 * dpr).round() as u32);
}

/// A watch of a new element whose observers are fakes that keep their
/// callbacks, for [`report_to_watches`] to call (the browser's own are put
/// back at once).
fn watch_with_fake_observers() -> labweb::dom::BoxWatch {
    js_sys::Function::new_no_args(
        "window.__observers = { real: [window.ResizeObserver, window.IntersectionObserver], calls: [], observed: [] };
         const fake = (kind) => class { constructor(cb) { window.__observers.calls.push([kind, cb]); }
           observe() { window.__observers.observed.push(kind); } unobserve() {} disconnect() {} };
         window.ResizeObserver = fake('resize');
         window.IntersectionObserver = fake('seen');",
    )
    .call0(&JsValue::NULL)
    .unwrap();
    let watch = labweb::dom::watch_box(&document().create_element("div").unwrap());
    js_sys::Function::new_no_args(
        "[window.ResizeObserver, window.IntersectionObserver] = window.__observers.real;",
    )
    .call0(&JsValue::NULL)
    .unwrap();
    watch.expect("labWatchBox is installed from main.js on the test page")
}

/// Calls every faked observer's callback: a size (CSS px) for the resize
/// observers, in the window or not for the others.
fn report_to_watches(size: Option<(f64, f64)>, in_window: Option<bool>) -> Result<(), JsValue> {
    js_sys::Function::new_with_args(
        "w, h, seen",
        "for (const [kind, cb] of window.__observers.calls) {
           if (kind === 'resize' && w !== undefined) cb([{ contentRect: { width: w, height: h } }]);
           if (kind === 'seen' && seen !== undefined) cb([{ isIntersecting: seen }]);
         }",
    )
    .call3(
        &JsValue::NULL,
        &size.map_or(JsValue::UNDEFINED, |s| s.0.into()),
        &size.map_or(JsValue::UNDEFINED, |s| s.1.into()),
        &in_window.map_or(JsValue::UNDEFINED, JsValue::from_bool),
    )
    .map(|_| ())
}

/// A watch stopped by dropping it (an experiment left, "The math" panel
/// written anew) is never called again, even by a report its
/// `IntersectionObserver` queued before `disconnect`: the page has freed
/// the closure, and calling it would throw.
#[wasm_bindgen_test]
fn a_dropped_box_watch_ignores_a_report_queued_before_it_stopped() {
    let watch = watch_with_fake_observers();
    let seen = watch.seen.clone();
    drop(watch);
    // The reports arrive after the watch stopped: nothing throws, nothing
    // is recorded.
    report_to_watches(Some((120.0, 80.0)), Some(false)).unwrap();
    assert_eq!(seen.get(), None);
}

/// A box shown again (its tab, its panel) counts as in the window from the
/// size report, which comes first: the other observer's last word, "not in
/// the window", was about the box while it had no size. Otherwise a frame
/// between the two reports would paint its plots once a second.
#[wasm_bindgen_test]
fn a_box_shown_again_is_in_the_window_until_told_otherwise() {
    let watch = watch_with_fake_observers();
    let seen = || watch.seen.get().map(|s| (s.width, s.height, s.in_window));
    report_to_watches(Some((120.0, 80.0)), Some(true)).unwrap();
    assert_eq!(seen(), Some((120.0, 80.0, true)));
    // Hidden: no size, and out of the window.
    report_to_watches(Some((0.0, 0.0)), Some(false)).unwrap();
    assert_eq!(seen(), Some((0.0, 0.0, false)));
    // Shown again: the size comes first, and the other observer is asked
    // afresh (it speaks only when its answer changes: a box hidden out of
    // the window and shown again still out of it would get no report).
    let observed = || {
        js_sys::Function::new_no_args(
            "return window.__observers.observed.filter((k) => k === 'seen').length",
        )
        .call0(&JsValue::NULL)
        .unwrap()
        .as_f64()
        .unwrap()
    };
    let before = observed();
    report_to_watches(Some((120.0, 80.0)), None).unwrap();
    assert_eq!(seen(), Some((120.0, 80.0, true)));
    assert_eq!(observed(), before + 1.0, "observed afresh when shown again");
    // Its report then says where the box is.
    report_to_watches(None, Some(false)).unwrap();
    assert_eq!(seen(), Some((120.0, 80.0, false)));
    report_to_watches(None, Some(true)).unwrap();
    // Scrolled out while it keeps its size.
    report_to_watches(None, Some(false)).unwrap();
    assert_eq!(seen(), Some((120.0, 80.0, false)));
    report_to_watches(Some((100.0, 80.0)), None).unwrap();
    assert_eq!(
        seen(),
        Some((100.0, 80.0, false)),
        "resized, still out of the window"
    );
}
