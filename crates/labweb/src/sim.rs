//! The Simulation tab: canvas, controls, readouts and the animation loop.
//!
//! Logic first, then paint: each animation frame steps the experiment with a
//! fixed `dt`, rebuilds the display list from state and paints it. Every
//! listener, the resize observer and the animation-frame closure are owned by
//! [`SimView`] and removed when it is dropped.

use crate::dom::{self, escape, query, query_all, Listener};
use crate::draw::{paint, Palette, Viewport};
use crate::plot_view::{self, PlotView};
use glam::DVec2;
use labcore::clock::{Clock, SPEEDS};
use labcore::quiz::format_number;
use labcore::route::{self, Tab};
use labcore::{Experiment, Input, ParamKind, ParamSpec, Sanitized, Scene};
use std::cell::{Cell, RefCell};
use std::rc::{Rc, Weak};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{
    CanvasRenderingContext2d, Element, Event, HtmlCanvasElement, HtmlElement, HtmlInputElement,
    HtmlSelectElement, KeyboardEvent, PointerEvent, ResizeObserver,
};

/// Shortest time between two redraws of the plots, milliseconds.
const PLOT_INTERVAL_MS: f64 = 66.0;
/// How close (CSS pixels) a touch must start to a handle to grab it.
const TOUCH_GRAB_PX: f64 = 28.0;
/// A touch that moves this far (CSS pixels) without the browser scrolling becomes a drag.
const TOUCH_SLOP_PX: f64 = 10.0;
/// Minimum time between URL updates while a control moves, milliseconds.
const HASH_INTERVAL_MS: f64 = 250.0;

/// Why the simulation could not start (the reading tabs still work).
#[derive(Debug)]
pub struct SimError(pub String);

/// The HTML of the Simulation tab for an experiment.
pub fn render(exp: &dyn Experiment, caption: &str) -> String {
    let mut controls = String::new();
    for spec in exp.params() {
        controls.push_str(&control_html(spec));
    }
    let actions: String = exp
        .actions()
        .iter()
        .map(|a| {
            format!(
                "<button type=\"button\" data-action=\"{}\">{}</button>",
                a.key,
                escape(a.label)
            )
        })
        .collect();
    let readouts = readouts_html(&exp.readouts());
    let status = exp.status();
    let timebar = if exp.animated() {
        timebar_html()
    } else {
        String::new()
    };
    let plots: String = exp.plots().iter().map(plot_view::render).collect();
    let plots = if plots.is_empty() {
        String::new()
    } else {
        format!("<section class=\"plots\" aria-label=\"Plots\">{plots}</section>")
    };
    let files = if exp.file_types().is_empty() {
        String::new()
    } else {
        let accept = exp.file_types().join(",");
        format!(
            "<button type=\"button\" class=\"mini\" data-file=\"pick\">Load file…</button>\
             <input type=\"file\" class=\"file-input\" accept=\"{}\" hidden>",
            escape(&accept)
        )
    };
    let save = if exp.export_text().is_some() {
        "<button type=\"button\" class=\"mini\" data-export=\"text\">Save file</button>"
    } else {
        ""
    };
    let tables = tables_html(&exp.tables());
    let touch_note = if exp.captures_touch() {
        "<p class=\"touch-note\">On a touch screen this canvas takes every touch (you draw on it). \
         <button type=\"button\" class=\"mini\" data-touch-mode aria-pressed=\"true\">Touch draws</button> \
         Switch it off to scroll the page with a swipe over the canvas.</p>"
    } else {
        ""
    };
    format!(
        "<div class=\"sim\">\
           <div class=\"sim-stage\">\
             <p class=\"sim-caption\">{caption}</p>\
             <div class=\"sim-frame\">\
               <canvas class=\"sim-canvas\" data-touch=\"{touch}\" tabindex=\"0\" role=\"application\" aria-roledescription=\"simulation\" \
                 aria-label=\"Simulation canvas. Drag or tap to interact; with the canvas focused, arrow keys move the point (Shift for fine steps){keys}.\"></canvas>\
               <p class=\"sim-status\" data-tone=\"{tone}\">{text}</p>\
             </div>{touch_note}\
             {timebar}\
             <div class=\"sim-actions\">{actions}{files}{save}<button type=\"button\" class=\"mini\" data-export=\"png\">Save PNG</button></div>\
           </div>\
           <div class=\"sim-side\">\
             <dl class=\"readouts\">{readouts}</dl>\
             <p class=\"sim-message\" role=\"alert\" hidden></p>\
             <section class=\"tables\" aria-label=\"Tables\">{tables}</section>\
             <form class=\"sim-controls\" aria-label=\"Parameters\" onsubmit=\"return false\">{controls}</form>\
             <p class=\"sr-only sim-live\" aria-live=\"polite\"></p>\
           </div>\
           {plots}\
         </div>",
        tone = tone_name(status.tone),
        text = escape(&status.text),
        touch = if exp.captures_touch() { "all" } else { "handles" },
        keys = if exp.animated() { ", Space plays or pauses, full stop steps once" } else { "" },
    )
}

/// Time-control icons (inline SVG: no icon font, no emoji fallback boxes).
const ICON_PAUSE: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M3 2h3.5v12H3zM9.5 2H13v12H9.5z\"/></svg>";
const ICON_PLAY: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M3 1.5v13l11-6.5z\"/></svg>";
const ICON_STEP: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"currentColor\" d=\"M2 2v12l8-6zM11 2h3v12h-3z\"/></svg>";
const ICON_RESET: &str = "<svg viewBox=\"0 0 16 16\" width=\"14\" height=\"14\" aria-hidden=\"true\"><path fill=\"none\" stroke=\"currentColor\" stroke-width=\"2\" d=\"M3.5 6A5 5 0 1 1 3 9.5\"/><path fill=\"currentColor\" d=\"M1 2.5l5 .5-3 4z\"/></svg>";

/// The shell's time controls: the same widget, place and keys in every
/// animated experiment.
fn timebar_html() -> String {
    let speeds: String = SPEEDS
        .iter()
        .map(|v| {
            let sel = if *v == 1.0 { " selected" } else { "" };
            format!("<option value=\"{v}\"{sel}>{}×</option>", speed_label(*v))
        })
        .collect();
    format!(
        "<div class=\"timebar\" role=\"group\" aria-label=\"Time controls\">\
         <button type=\"button\" class=\"tb-play\" data-time=\"play\" aria-pressed=\"true\" aria-keyshortcuts=\"Space\">\
         <span class=\"tb-icon\">{ICON_PAUSE}</span> <span class=\"tb-label\">Pause</span></button>\
         <button type=\"button\" data-time=\"step\" aria-keyshortcuts=\".\" title=\"One step (key .)\">{ICON_STEP} Step</button>\
         <label class=\"tb-speed\">Playback <select data-time=\"speed\">{speeds}</select></label>\
         <button type=\"button\" data-time=\"reset\">{ICON_RESET} Reset</button>\
         <output class=\"tb-time\" aria-label=\"Simulated time\">t = 0.00 s</output></div>"
    )
}

fn speed_label(v: f64) -> &'static str {
    if v == 0.25 {
        "¼"
    } else if v == 0.5 {
        "½"
    } else if v == 2.0 {
        "2"
    } else if v == 4.0 {
        "4"
    } else {
        "1"
    }
}

fn readouts_html(readouts: &[labcore::Readout]) -> String {
    readouts
        .iter()
        .map(|r| {
            format!(
                "<div class=\"readout\"><dt>{}</dt><dd data-readout=\"{}\">{}</dd></div>",
                escape(r.label),
                r.key,
                escape(&r.value)
            )
        })
        .collect()
}

fn tone_name(tone: labcore::Tone) -> &'static str {
    match tone {
        labcore::Tone::Neutral => "neutral",
        labcore::Tone::Good => "good",
        labcore::Tone::Warning => "warning",
        labcore::Tone::Bad => "bad",
    }
}

fn decimals(step: f64) -> usize {
    let mut d = 0;
    let mut s = step;
    while d < 4 && (s - s.round()).abs() > 1e-9 {
        s *= 10.0;
        d += 1;
    }
    d
}

fn control_html(spec: &ParamSpec) -> String {
    let key = spec.key;
    let label = escape(spec.label);
    let unit = escape(spec.unit);
    let v = format_number(spec.default, 4);
    match spec.kind {
        ParamKind::Slider => format!(
            "<div class=\"ctl ctl-slider\"><label for=\"p-{key}\">{label}</label>\
             <input type=\"range\" id=\"p-{key}\" data-param=\"{key}\" min=\"{min}\" max=\"{max}\" step=\"{step}\" value=\"{v}\">\
             <span class=\"ctl-num\"><input type=\"text\" inputmode=\"decimal\" autocomplete=\"off\" spellcheck=\"false\" data-param=\"{key}\" min=\"{min}\" max=\"{max}\" step=\"any\" value=\"{v}\" aria-label=\"{label} value{unit_aria}\">\
             <span class=\"unit\" aria-hidden=\"true\">{unit}</span></span></div>",
            min = spec.min,
            max = spec.max,
            step = spec.step,
            unit_aria = if spec.unit.is_empty() { String::new() } else { format!(" in {unit}") },
        ),
        ParamKind::OptionalNumber => format!(
            "<div class=\"ctl ctl-number\"><label for=\"p-{key}\">{label}</label>\
             <span class=\"ctl-num\"><input type=\"text\" inputmode=\"decimal\" autocomplete=\"off\" spellcheck=\"false\" id=\"p-{key}\" data-param=\"{key}\" min=\"{min}\" max=\"{max}\" step=\"any\" \
             placeholder=\"—\" aria-label=\"{label}{unit_aria}\"><span class=\"unit\" aria-hidden=\"true\">{unit}</span></span></div>",
            min = spec.min,
            max = spec.max,
            unit_aria = if spec.unit.is_empty() { String::new() } else { format!(" in {unit}") },
        ),
        ParamKind::Number => format!(
            "<div class=\"ctl ctl-number\"><label for=\"p-{key}\">{label}</label>\
             <span class=\"ctl-num\"><input type=\"text\" inputmode=\"decimal\" autocomplete=\"off\" spellcheck=\"false\" id=\"p-{key}\" data-param=\"{key}\" min=\"{min}\" max=\"{max}\" step=\"1\" value=\"{v}\"></span></div>",
            min = spec.min,
            max = spec.max,
        ),
        ParamKind::Toggle { off, on } => format!(
            "<fieldset class=\"ctl ctl-toggle\"><legend>{label}</legend><div class=\"seg\">\
             <label><input type=\"radio\" name=\"p-{key}\" data-param=\"{key}\" value=\"1\"{c1}><span>{on}</span></label>\
             <label><input type=\"radio\" name=\"p-{key}\" data-param=\"{key}\" value=\"0\"{c0}><span>{off}</span></label>\
             </div></fieldset>",
            on = escape(on),
            off = escape(off),
            c1 = if spec.default >= 0.5 { " checked" } else { "" },
            c0 = if spec.default < 0.5 { " checked" } else { "" },
        ),
        ParamKind::Choice(options) => {
            let opts: String = options
                .iter()
                .enumerate()
                .map(|(i, o)| {
                    let sel = if (i as f64 - spec.default).abs() < 0.5 { " selected" } else { "" };
                    format!("<option value=\"{i}\"{sel}>{}</option>", escape(o))
                })
                .collect();
            format!(
                "<div class=\"ctl ctl-choice\"><label for=\"p-{key}\">{label}</label>\
                 <select id=\"p-{key}\" data-param=\"{key}\">{opts}</select></div>"
            )
        }
    }
}

/// State shared by the frame loop and the event handlers.
struct SimState {
    exp: Box<dyn Experiment>,
    canvas: HtmlCanvasElement,
    ctx: CanvasRenderingContext2d,
    panel: Element,
    scene: Scene,
    palette: Palette,
    viewport: Viewport,
    css_size: (f64, f64),
    dpr: f64,
    pressed_pointer: Option<i32>,
    /// A touch that started off every handle: a tap if it lifts in place, a
    /// scroll if the browser takes it, a drag if it moves sideways.
    pending_touch: Option<(i32, DVec2, DVec2)>,
    /// For an experiment that captures touch: whether touches draw (true)
    /// or, switched off by the student, scroll like elsewhere.
    touch_draws: bool,
    last_time_ms: Option<f64>,
    clock: Clock,
    plots: PlotView,
    plots_force: bool,
    last_plot_ms: f64,
    shown_time: (bool, f64, u64),
    needs_paint: bool,
    /// What each control shows; `None` = unknown (refresh it), `Some(None)` = empty.
    shown_values: Vec<Option<Option<f64>>>,
    shown_readouts: Vec<String>,
    shown_status: String,
    shown_tables: Vec<labcore::Table>,
    shown_view: labcore::ViewBox,
    hash_dirty: bool,
    last_hash_ms: f64,
    frame_times: FrameTimes,
}

/// Recent busy-frame times (step + paint), published on the canvas as
/// `data-frame-p95-ms` and `data-frame-max-ms` for tests and curious users.
#[derive(Default)]
struct FrameTimes {
    recent_ms: Vec<f64>,
    next: usize,
    max_ms: f64,
    since_publish: usize,
}

impl FrameTimes {
    const WINDOW: usize = 300;

    fn record(&mut self, ms: f64, canvas: &HtmlCanvasElement) {
        if self.recent_ms.len() < Self::WINDOW {
            self.recent_ms.push(ms);
        } else {
            self.recent_ms[self.next] = ms;
        }
        self.next = (self.next + 1) % Self::WINDOW;
        self.max_ms = self.max_ms.max(ms);
        self.since_publish += 1;
        if self.since_publish >= 15 || ms > 16.0 {
            self.since_publish = 0;
            let mut sorted = self.recent_ms.clone();
            sorted.sort_by(f64::total_cmp);
            let p95 = sorted[(sorted.len() * 95 / 100).min(sorted.len() - 1)];
            let _ = canvas.set_attribute("data-frame-p95-ms", &format!("{p95:.2}"));
            let _ = canvas.set_attribute("data-frame-max-ms", &format!("{:.2}", self.max_ms));
        }
    }
}

impl SimState {
    fn resize(&mut self) {
        let rect = self.canvas.get_bounding_client_rect();
        let (w, h) = (rect.width(), rect.height());
        let dpr = dom::window().device_pixel_ratio().max(1.0);
        if w < 1.0 || h < 1.0 {
            return;
        }
        if (w, h) != self.css_size || dpr != self.dpr {
            self.css_size = (w, h);
            self.dpr = dpr;
            self.canvas.set_width((w * dpr).round() as u32);
            self.canvas.set_height((h * dpr).round() as u32);
            self.needs_paint = true;
            // The experiment may pick a finger-sized view (A* on a phone).
            self.exp.viewport_px(w, h);
        }
        let view = self.exp.view();
        if view != self.shown_view {
            // The world rectangle shown, for tests and tools that click world points.
            let _ = self.canvas.set_attribute(
                "data-view",
                &format!(
                    "{},{},{},{}",
                    view.min.x, view.min.y, view.max.x, view.max.y
                ),
            );
            self.shown_view = view;
        }
        self.viewport = Viewport::fit(view, w, h);
    }

    fn to_world(&self, event: &PointerEvent) -> DVec2 {
        let rect = self.canvas.get_bounding_client_rect();
        let px = DVec2::new(
            f64::from(event.client_x()) - rect.left(),
            f64::from(event.client_y()) - rect.top(),
        );
        self.viewport.to_world(px)
    }

    fn frame(&mut self, time_ms: f64) {
        let start = dom::now_ms();
        let elapsed_s = self
            .last_time_ms
            .map_or(0.0, |last| (time_ms - last) / 1000.0);
        self.last_time_ms = Some(time_ms);
        let was_animating = self.exp.animating();
        // An idle experiment's clock does not tick (t counts motion only).
        let steps = if was_animating || !self.exp.animated() {
            self.clock.advance(elapsed_s)
        } else {
            0
        };
        for _ in 0..steps {
            self.exp.step(Clock::DT_S);
        }
        let stopped = was_animating && !self.exp.animating();
        if stopped {
            // The state the motion ended in belongs in the link and is worth announcing.
            self.hash_dirty = true;
            self.announce();
        }
        // Paint while moving, and once more for the frame on which it stopped.
        if steps > 0 && (was_animating || self.exp.animating()) {
            self.needs_paint = true;
        }
        let busy = self.needs_paint || steps > 0;
        if self.needs_paint {
            self.resize();
            self.paint();
            self.sync_dom();
            self.needs_paint = false;
        }
        // Plots follow the data at most every PLOT_INTERVAL_MS: a curve
        // needs no 60 Hz, and the frame keeps its budget for the simulation.
        if self.plots_force || time_ms - self.last_plot_ms >= PLOT_INTERVAL_MS {
            self.plots
                .draw(self.exp.plots(), &self.palette, self.plots_force);
            self.plots_force = false;
            self.last_plot_ms = time_ms;
        }
        self.sync_timebar();
        if self.hash_dirty && time_ms - self.last_hash_ms >= HASH_INTERVAL_MS {
            self.write_hash();
            self.last_hash_ms = time_ms;
        }
        if busy {
            self.frame_times.record(dom::now_ms() - start, &self.canvas);
        }
    }

    /// One fixed step from a pause (the Step button and the `.` key).
    fn single_step(&mut self) {
        let was_animating = self.exp.animating();
        for _ in 0..self.clock.single_step() {
            self.exp.step(Clock::DT_S);
        }
        self.needs_paint = true;
        self.hash_dirty = true;
        self.plots_force = true;
        self.sync_timebar();
        if was_animating && !self.exp.animating() {
            self.announce();
        }
    }

    fn set_running(&mut self, running: bool) {
        self.clock.set_running(running);
        self.last_time_ms = None;
        self.hash_dirty = true;
        // The button says so at once, not at the next frame.
        self.sync_timebar();
    }

    fn reset_run(&mut self) {
        self.exp.reset();
        self.clock.reset();
        self.needs_paint = true;
        self.hash_dirty = true;
        self.plots_force = true;
    }

    /// Brings the play button, the speed and the time read-out up to date.
    fn sync_timebar(&mut self) {
        let now = (self.clock.running(), self.clock.speed(), self.clock.steps());
        if now == self.shown_time {
            return;
        }
        let _ = self.canvas.set_attribute("data-steps", &now.2.to_string());
        if let Some(bar) = query(&self.panel, ".timebar") {
            if now.0 != self.shown_time.0 {
                if let Some(play) = query(&bar, ".tb-play") {
                    let _ =
                        play.set_attribute("aria-pressed", if now.0 { "true" } else { "false" });
                    if let Some(icon) = query(&play, ".tb-icon") {
                        icon.set_inner_html(if now.0 { ICON_PAUSE } else { ICON_PLAY });
                    }
                    if let Some(label) = query(&play, ".tb-label") {
                        label.set_text_content(Some(if now.0 { "Pause" } else { "Play" }));
                    }
                }
            }
            if now.1 != self.shown_time.1 {
                if let Some(select) = query(&bar, "select[data-time=speed]")
                    .and_then(|e| e.dyn_into::<HtmlSelectElement>().ok())
                {
                    select.set_value(&format!("{}", now.1));
                }
            }
            if let Some(out) = query(&bar, ".tb-time") {
                out.set_text_content(Some(&format!("t = {:.2} s", self.clock.time_s())));
            }
        }
        self.shown_time = now;
    }

    /// The link of the current state: the experiment's parameters, then the
    /// shell's own (`run=0` when paused, `speed` when not 1×).
    fn link(&self) -> String {
        let mut hash = route::format(self.exp.as_ref(), Tab::Simulation);
        let mut extra = Vec::new();
        if self.exp.animated() && !self.clock.running() {
            extra.push("run=0".to_owned());
        }
        if self.clock.speed() != 1.0 {
            extra.push(format!("speed={}", self.clock.speed()));
        }
        if !extra.is_empty() {
            hash.push(if hash.contains('?') { '&' } else { '?' });
            hash.push_str(&extra.join("&"));
        }
        hash
    }

    /// File names of exports: the experiment, the seed where there is one.
    fn file_stem(&self) -> String {
        match self.exp.param("seed") {
            Some(seed) => format!("{}-seed{}", self.exp.id(), seed as u64),
            None => self.exp.id().to_owned(),
        }
    }

    fn paint(&mut self) {
        let (w, h) = self.css_size;
        if w < 1.0 {
            return;
        }
        self.scene.clear();
        self.exp.scene(&mut self.scene);
        paint(
            &self.ctx,
            &self.scene,
            &self.viewport,
            w,
            h,
            self.dpr,
            &self.palette,
        );
    }

    /// Brings controls, readouts and the status badge up to date with the state.
    fn sync_dom(&mut self) {
        let active = dom::document().active_element();
        for (i, spec) in self.exp.params().iter().enumerate() {
            let value = self.exp.param(spec.key);
            if self.shown_values.get(i) == Some(&Some(value)) {
                continue;
            }
            set_control_value(&self.panel, spec, value, active.as_ref());
            if let Some(slot) = self.shown_values.get_mut(i) {
                *slot = Some(value);
            }
        }
        let readouts = self.exp.readouts();
        if self.shown_readouts.len() != readouts.len() {
            // The set of readouts changed: rebuild the list.
            if let Some(list) = query(&self.panel, "dl.readouts") {
                list.set_inner_html(&readouts_html(&readouts));
            }
            self.shown_readouts = vec![String::new(); readouts.len()];
        }
        for (r, shown) in readouts.iter().zip(self.shown_readouts.iter_mut()) {
            if *shown != r.value {
                if let Some(dd) = query(&self.panel, &format!("[data-readout=\"{}\"]", r.key)) {
                    dd.set_text_content(Some(&r.value));
                }
                shown.clone_from(&r.value);
            }
        }
        let status = self.exp.status();
        if status.text != self.shown_status {
            if let Some(badge) = query(&self.panel, ".sim-status") {
                badge.set_text_content(Some(&status.text));
                let _ = badge.set_attribute("data-tone", tone_name(status.tone));
            }
            self.shown_status = status.text;
        }
        let tables = self.exp.tables();
        if tables != self.shown_tables {
            if let Some(section) = query(&self.panel, ".tables") {
                section.set_inner_html(&tables_html(&tables));
            }
            self.shown_tables = tables;
        }
    }

    /// After a pointer release or a keyboard nudge: repaint, put the new state
    /// in the link, and announce it (once any motion has settled).
    fn interaction_ended(&mut self) {
        self.needs_paint = true;
        self.hash_dirty = true;
        self.announce_when_settled();
    }

    /// Tells screen-reader users the new readouts after an interaction ends;
    /// while the simulation is still moving, waits until it stops (the frame
    /// loop announces then).
    fn announce_when_settled(&self) {
        if !self.exp.animating() {
            self.announce();
        }
    }

    /// Tells screen-reader users the current status and readouts.
    fn announce(&self) {
        let text: Vec<String> = self
            .exp
            .readouts()
            .iter()
            .map(|r| format!("{}: {}", r.label, r.value))
            .collect();
        if let Some(live) = query(&self.panel, ".sim-live") {
            live.set_text_content(Some(&format!(
                "{}. {}",
                self.exp.status().text,
                text.join(", ")
            )));
        }
    }

    fn write_hash(&mut self) {
        self.hash_dirty = false;
        let hash = self.link();
        if let Ok(history) = dom::window().history() {
            let _ = history.replace_state_with_url(&JsValue::NULL, "", Some(&hash));
        }
    }

    fn show_message(&self, text: Option<&str>) {
        if let Some(m) = query(&self.panel, ".sim-message") {
            m.set_text_content(text);
            dom::set_hidden(&m, text.is_none());
        }
    }

    fn set_param(&mut self, key: &str, value: f64) {
        let label = self
            .exp
            .params()
            .iter()
            .find(|s| s.key == key)
            .map_or(key, |s| s.label);
        match self.exp.set_param(key, value) {
            Ok(Sanitized::InRange(_)) => self.show_message(None),
            Ok(Sanitized::Clamped(v)) => self.show_message(Some(&format!(
                "{label} is limited to its range; using {}.",
                format_number(v, 3)
            ))),
            Err(e) => {
                self.show_message(Some(&format!("{label}: {e}. Kept the previous value.")));
                // Force the control back to the kept value.
                self.shown_values.iter_mut().for_each(|v| *v = None);
            }
        }
        self.needs_paint = true;
        self.hash_dirty = true;
    }
}

/// Shows `value` in every control of `spec` (`None`: an empty optional field).
fn set_control_value(
    panel: &Element,
    spec: &ParamSpec,
    value: Option<f64>,
    active: Option<&Element>,
) {
    for el in query_all(panel, &format!("[data-param=\"{}\"]", spec.key)) {
        let Some(v) = value else {
            if let Some(input) = el.dyn_ref::<HtmlInputElement>() {
                if active != Some(&el) {
                    input.set_value("");
                }
            }
            continue;
        };
        if let Some(input) = el.dyn_ref::<HtmlInputElement>() {
            match input.type_().as_str() {
                "radio" => input.set_checked((input.value() == "1") == (v >= 0.5)),
                "text" => {
                    if active != Some(&el) {
                        input.set_value(&format_number(v, (decimals(spec.step) + 1).min(3)));
                    }
                }
                _ => input.set_value(&format_number(v, 4)),
            }
        } else if let Some(select) = el.dyn_ref::<HtmlSelectElement>() {
            select.set_value(&format!("{}", v.round() as i64));
        }
    }
}

/// A `requestAnimationFrame` loop, cancelled when dropped.
struct AnimationLoop {
    inner: Rc<FrameRequest>,
}

/// The closure `requestAnimationFrame` calls with the frame time in milliseconds.
type FrameCallback = Closure<dyn FnMut(f64)>;

struct FrameRequest {
    id: Cell<Option<i32>>,
    closure: RefCell<Option<FrameCallback>>,
}

impl FrameRequest {
    fn request(&self) {
        if let Some(c) = self.closure.borrow().as_ref() {
            self.id.set(
                dom::window()
                    .request_animation_frame(c.as_ref().unchecked_ref())
                    .ok(),
            );
        }
    }
}

impl AnimationLoop {
    fn start(mut tick: impl FnMut(f64) + 'static) -> Self {
        let inner = Rc::new(FrameRequest {
            id: Cell::new(None),
            closure: RefCell::new(None),
        });
        let weak: Weak<FrameRequest> = Rc::downgrade(&inner);
        let closure = Closure::<dyn FnMut(f64)>::new(move |t: f64| {
            tick(t);
            if let Some(inner) = weak.upgrade() {
                inner.request();
            }
        });
        *inner.closure.borrow_mut() = Some(closure);
        inner.request();
        Self { inner }
    }
}

impl Drop for AnimationLoop {
    fn drop(&mut self) {
        if let Some(id) = self.inner.id.take() {
            let _ = dom::window().cancel_animation_frame(id);
        }
        self.inner.closure.borrow_mut().take();
    }
}

/// A resize observer disconnected when dropped.
struct ResizeWatch {
    observer: ResizeObserver,
    _closure: Closure<dyn FnMut(js_sys::Array)>,
}

impl Drop for ResizeWatch {
    fn drop(&mut self) {
        self.observer.disconnect();
    }
}

/// The mounted Simulation tab of one experiment.
pub struct SimView {
    state: Rc<RefCell<SimState>>,
    running: Option<AnimationLoop>,
    _listeners: Vec<Listener>,
    _resize: Option<ResizeWatch>,
}

impl SimView {
    /// Wires the Simulation panel rendered by [`render`] to `exp`.
    pub fn mount(panel: &Element, exp: Box<dyn Experiment>) -> Result<Self, SimError> {
        let canvas: HtmlCanvasElement = query(panel, "canvas.sim-canvas")
            .and_then(|c| c.dyn_into().ok())
            .ok_or_else(|| SimError("the page has no canvas".into()))?;
        let ctx: CanvasRenderingContext2d = canvas
            .get_context("2d")
            .ok()
            .flatten()
            .and_then(|c| c.dyn_into().ok())
            .ok_or_else(|| {
                SimError("this browser could not give the simulation a 2D canvas".into())
            })?;
        let palette = Palette::from_css(&canvas);
        let view = exp.view();
        let n_params = exp.params().len();
        let state = Rc::new(RefCell::new(SimState {
            exp,
            canvas: canvas.clone(),
            ctx,
            panel: panel.clone(),
            scene: Scene::default(),
            palette,
            viewport: Viewport::fit(view, 1.0, 1.0),
            css_size: (0.0, 0.0),
            dpr: 1.0,
            pressed_pointer: None,
            pending_touch: None,
            touch_draws: true,
            last_time_ms: None,
            clock: Clock::default(),
            plots: PlotView::mount(panel),
            plots_force: true,
            last_plot_ms: f64::NEG_INFINITY,
            shown_time: (true, 0.0, u64::MAX),
            needs_paint: true,
            shown_values: vec![None; n_params],
            shown_readouts: Vec::new(),
            shown_status: String::new(),
            shown_tables: Vec::new(),
            shown_view: labcore::ViewBox::centered(0.0),
            hash_dirty: false,
            last_hash_ms: 0.0,
            frame_times: FrameTimes::default(),
        }));
        let mut listeners = Vec::new();
        let canvas_target: &web_sys::EventTarget = canvas.as_ref();

        let s = state.clone();
        listeners.push(Listener::new(
            canvas_target,
            "pointerdown",
            move |e: Event| {
                let Some(e) = e.dyn_ref::<PointerEvent>() else {
                    return;
                };
                if !e.is_primary() || e.button() > 0 {
                    return;
                }
                let mut st = s.borrow_mut();
                let w = st.to_world(e);
                let captured = st.exp.captures_touch() && st.touch_draws;
                if e.pointer_type() == "touch" && !captured {
                    let tolerance_m = TOUCH_GRAB_PX / st.viewport.scale_px_per_m;
                    if !st.exp.handle_at(w, tolerance_m) {
                        // Off every handle: let the browser scroll if it is a
                        // swipe; act on lift if it is a tap.
                        let px = DVec2::new(f64::from(e.client_x()), f64::from(e.client_y()));
                        st.pending_touch = Some((e.pointer_id(), w, px));
                        return;
                    }
                }
                // No preventDefault: the browser focuses the canvas itself (so
                // arrow keys work next) without a keyboard focus ring; a touch
                // on a handle is kept from scrolling by the touchstart below.
                let _ = st.canvas.set_pointer_capture(e.pointer_id());
                st.pressed_pointer = Some(e.pointer_id());
                st.exp.input_with(Input::PointerDown(w), modifiers(e));
                st.needs_paint = true;
            },
        ));
        // Files dropped on the canvas load like picked ones.
        if !state.borrow().exp.file_types().is_empty() {
            listeners.push(Listener::new(canvas_target, "dragover", |e: Event| {
                e.prevent_default();
            }));
            let s = state.clone();
            listeners.push(Listener::new(canvas_target, "drop", move |e: Event| {
                e.prevent_default();
                let file = e
                    .dyn_ref::<web_sys::DragEvent>()
                    .and_then(|d| d.data_transfer())
                    .and_then(|d| d.files())
                    .and_then(|f| f.get(0));
                if let Some(file) = file {
                    read_file(&s, file);
                }
            }));
        }
        // A touch that grabbed a handle must not scroll the page.
        let s = state.clone();
        listeners.push(Listener::new(
            canvas_target,
            "touchstart",
            move |e: Event| {
                if let Ok(st) = s.try_borrow() {
                    if st.pressed_pointer.is_some() && e.cancelable() {
                        e.prevent_default();
                    }
                }
            },
        ));
        let s = state.clone();
        listeners.push(Listener::new(
            canvas_target,
            "pointermove",
            move |e: Event| {
                let Some(e) = e.dyn_ref::<PointerEvent>() else {
                    return;
                };
                if !e.is_primary() {
                    return;
                }
                let mut st = s.borrow_mut();
                let w = st.to_world(e);
                if let Some((id, start, start_px)) = st.pending_touch {
                    let px = DVec2::new(f64::from(e.client_x()), f64::from(e.client_y()));
                    let moved = px - start_px;
                    // A mostly vertical move is the browser's (touch-action:
                    // pan-y): it scrolls and cancels the pointer. A sideways
                    // one it leaves to us: a drag from where the finger landed.
                    if id == e.pointer_id()
                        && moved.length() > TOUCH_SLOP_PX
                        && moved.x.abs() > moved.y.abs()
                    {
                        st.pending_touch = None;
                        let _ = st.canvas.set_pointer_capture(id);
                        st.pressed_pointer = Some(id);
                        st.exp.input_with(Input::PointerDown(start), modifiers(e));
                    }
                }
                let pressed = st.pressed_pointer == Some(e.pointer_id());
                st.exp
                    .input_with(Input::PointerMove { pos: w, pressed }, modifiers(e));
                if pressed {
                    st.needs_paint = true;
                    st.hash_dirty = true;
                }
            },
        ));
        for kind in ["pointerup", "pointercancel"] {
            let s = state.clone();
            listeners.push(Listener::new(canvas_target, kind, move |e: Event| {
                let Some(e) = e.dyn_ref::<PointerEvent>() else {
                    return;
                };
                let mut st = s.borrow_mut();
                if let Some((id, start, _)) = st.pending_touch {
                    if id == e.pointer_id() {
                        st.pending_touch = None;
                        if kind == "pointerup" {
                            // A tap: it acts where it landed.
                            st.exp.input_with(Input::PointerDown(start), modifiers(e));
                            st.exp.input_with(Input::PointerUp(start), modifiers(e));
                            st.interaction_ended();
                        }
                        return;
                    }
                }
                if st.pressed_pointer != Some(e.pointer_id()) {
                    return;
                }
                st.pressed_pointer = None;
                let w = st.to_world(e);
                st.exp.input_with(Input::PointerUp(w), modifiers(e));
                st.interaction_ended();
            }));
        }
        let s = state.clone();
        listeners.push(Listener::new(canvas_target, "keydown", move |e: Event| {
            let Some(e) = e.dyn_ref::<KeyboardEvent>() else {
                return;
            };
            match e.key().as_str() {
                " " | "Spacebar" => {
                    // Play/pause without scrolling the page.
                    e.prevent_default();
                    let mut st = s.borrow_mut();
                    if st.exp.animated() {
                        let running = !st.clock.running();
                        st.set_running(running);
                    }
                    return;
                }
                "." => {
                    e.prevent_default();
                    let mut st = s.borrow_mut();
                    if st.exp.animated() {
                        st.single_step();
                    }
                    return;
                }
                _ => {}
            }
            let dir = match e.key().as_str() {
                "ArrowLeft" => DVec2::NEG_X,
                "ArrowRight" => DVec2::X,
                "ArrowUp" => DVec2::Y,
                "ArrowDown" => DVec2::NEG_Y,
                _ => return,
            };
            e.prevent_default();
            let mut st = s.borrow_mut();
            let view = st.exp.view();
            let fraction = if e.shift_key() { 0.002 } else { 0.02 };
            let delta = dir * (view.max.x - view.min.x) * fraction;
            let mods = labcore::Modifiers {
                shift: false,
                ctrl: e.ctrl_key() || e.meta_key(),
            };
            st.exp.input_with(Input::Nudge(delta), mods);
            st.interaction_ended();
        }));

        if let Some(form) = query(panel, ".sim-controls") {
            let s = state.clone();
            listeners.push(Listener::new(form.as_ref(), "input", move |e: Event| {
                let Some(input) = e
                    .target()
                    .and_then(|t| t.dyn_into::<HtmlInputElement>().ok())
                else {
                    return;
                };
                let Some(key) = input.get_attribute("data-param") else {
                    return;
                };
                // Number boxes apply on change (Enter or leaving the box), never
                // mid-typing: "1e9" on the way to "1e99", "0" on the way to "0.5".
                if input.type_() == "text" {
                    return;
                }
                let value = input.value_as_number();
                let value = if input.type_() == "radio" {
                    input.value().parse().unwrap_or(0.0)
                } else {
                    value
                };
                let mut st = s.borrow_mut();
                st.set_param(&key, value);
                // Mirror slider → number box now (the number box is not focused).
                if let Some(i) = st.exp.params().iter().position(|p| p.key == key) {
                    st.shown_values[i] = None;
                }
            }));
            let s = state.clone();
            listeners.push(Listener::new(form.as_ref(), "change", move |e: Event| {
                let target = e.target();
                let mut st = s.borrow_mut();
                if let Some(select) = target
                    .clone()
                    .and_then(|t| t.dyn_into::<HtmlSelectElement>().ok())
                {
                    if let Some(key) = select.get_attribute("data-param") {
                        st.set_param(&key, select.value().parse().unwrap_or(f64::NAN));
                    }
                } else if let Some(input) =
                    target.and_then(|t| t.dyn_into::<HtmlInputElement>().ok())
                {
                    if let Some(key) = input.get_attribute("data-param") {
                        if input.type_() == "text" {
                            let raw = input.value();
                            let unit = st
                                .exp
                                .params()
                                .iter()
                                .find(|p| p.key == key)
                                .map_or("", |p| p.unit);
                            // One rule for commas and units everywhere (see
                            // `labcore::quiz::read_answer`); say what was read.
                            let reading = if raw.trim().is_empty() {
                                Err(None)
                            } else {
                                labcore::quiz::read_answer(&raw, unit).map_err(Some)
                            };
                            match reading {
                                Ok(r) => {
                                    st.set_param(&key, r.value);
                                    let plain = raw.trim().parse::<f64>().is_ok();
                                    if !plain {
                                        st.show_message(Some(&format!(
                                            "Read “{}” as {}.",
                                            raw.trim(),
                                            r.read_as
                                        )));
                                    }
                                }
                                Err(e) => {
                                    let why = e.map_or_else(
                                        || "nothing was typed".to_owned(),
                                        |e| e.to_string(),
                                    );
                                    st.show_message(Some(&format!(
                                        "Could not read that: {why}. Kept the previous value."
                                    )));
                                    // Show the kept value again.
                                    st.shown_values.iter_mut().for_each(|v| *v = None);
                                }
                            }
                            if let Some(i) = st.exp.params().iter().position(|p| p.key == key) {
                                st.shown_values[i] = None;
                            }
                            // Show the applied value even though the box has focus.
                            if let Some(spec) =
                                st.exp.params().iter().find(|p| p.key == key).copied()
                            {
                                set_control_value(&st.panel, &spec, st.exp.param(&key), None);
                            }
                        }
                    }
                }
                st.announce_when_settled();
            }));
        }
        if let Some(sim) = query(panel, ".sim") {
            let s = state.clone();
            listeners.push(Listener::new(sim.as_ref(), "click", move |e: Event| {
                let Some(button) = e
                    .target()
                    .and_then(|t| t.dyn_into::<Element>().ok())
                    .and_then(|el| el.closest("button").ok().flatten())
                else {
                    return;
                };
                let attr = |name: &str| button.get_attribute(name);
                let mut st = s.borrow_mut();
                if let Some(key) = attr("data-action") {
                    if let Err(err) = st.exp.action(&key) {
                        st.show_message(Some(&err.to_string()));
                    }
                    st.needs_paint = true;
                    st.hash_dirty = true;
                } else if let Some(what) = attr("data-time") {
                    match what.as_str() {
                        "play" => {
                            let running = !st.clock.running();
                            st.set_running(running);
                        }
                        "step" => st.single_step(),
                        "reset" => st.reset_run(),
                        _ => {}
                    }
                } else if button.has_attribute("data-touch-mode") {
                    st.touch_draws = !st.touch_draws;
                    let on = st.touch_draws;
                    let _ = button.set_attribute("aria-pressed", if on { "true" } else { "false" });
                    let _ = st
                        .canvas
                        .set_attribute("data-touch", if on { "all" } else { "handles" });
                } else if attr("data-file").as_deref() == Some("pick") {
                    if let Some(input) = query(&st.panel, "input.file-input")
                        .and_then(|i| i.dyn_into::<HtmlInputElement>().ok())
                    {
                        input.click();
                    }
                } else if attr("data-export").as_deref() == Some("text") {
                    if let Some((name, text)) = st.exp.export_text() {
                        plot_view::download(&name, "text/plain", &text);
                    }
                } else if attr("data-export").as_deref() == Some("png") {
                    st.paint();
                    export_png(&st.canvas, &format!("{}.png", st.file_stem()));
                } else if let Some(key) = attr("data-plot-csv") {
                    if let Some(plot) = st.exp.plots().iter().find(|p| p.key == key) {
                        let name = format!("{}-{}.csv", st.file_stem(), plot.key);
                        plot_view::download(&name, "text/csv", &plot.to_csv());
                    }
                } else if let Some(key) = attr("data-plot-table") {
                    let st = &*st;
                    st.plots.toggle_table(&key, st.exp.plots());
                }
            }));
            let s = state.clone();
            listeners.push(Listener::new(sim.as_ref(), "change", move |e: Event| {
                if let Some(input) = e
                    .target()
                    .and_then(|t| t.dyn_into::<HtmlInputElement>().ok())
                    .filter(|i| i.type_() == "file")
                {
                    if let Some(file) = input.files().and_then(|f| f.get(0)) {
                        read_file(&s, file);
                    }
                    input.set_value("");
                    return;
                }
                let Some(select) = e
                    .target()
                    .and_then(|t| t.dyn_into::<HtmlSelectElement>().ok())
                    .filter(|el| el.get_attribute("data-time").as_deref() == Some("speed"))
                else {
                    return;
                };
                let mut st = s.borrow_mut();
                let v = select.value().parse().unwrap_or(1.0);
                st.clock.set_speed(v);
                st.hash_dirty = true;
            }));
            for kind in ["pointermove", "pointerdown", "pointerleave"] {
                let s = state.clone();
                listeners.push(Listener::new(sim.as_ref(), kind, move |e: Event| {
                    let Some(e) = e.dyn_ref::<PointerEvent>() else {
                        return;
                    };
                    let Some(canvas) = e
                        .target()
                        .and_then(|t| t.dyn_into::<Element>().ok())
                        .filter(|el| el.class_list().contains("plot-canvas"))
                    else {
                        return;
                    };
                    let mut st = s.borrow_mut();
                    let st = &mut *st;
                    let x = (kind != "pointerleave").then(|| f64::from(e.client_x()));
                    st.plots.hover(&canvas, x, st.exp.plots(), &st.palette);
                }));
            }
        }
        // Theme changes (light/dark) repaint with the new palette.
        if let Ok(Some(mql)) = dom::window().match_media("(prefers-color-scheme: dark)") {
            let s = state.clone();
            listeners.push(Listener::new(mql.as_ref(), "change", move |_| {
                let mut st = s.borrow_mut();
                st.palette = Palette::from_css(&st.canvas);
                st.needs_paint = true;
                st.plots_force = true;
            }));
        }
        let s = state.clone();
        listeners.push(Listener::new(
            dom::document().as_ref(),
            "visibilitychange",
            move |_| {
                // Resume without a catch-up burst after the page was hidden.
                s.borrow_mut().last_time_ms = None;
            },
        ));

        let s = state.clone();
        let closure = Closure::<dyn FnMut(js_sys::Array)>::new(move |_entries: js_sys::Array| {
            if let Ok(mut st) = s.try_borrow_mut() {
                st.resize();
                st.needs_paint = true;
            }
        });
        let resize = ResizeObserver::new(closure.as_ref().unchecked_ref())
            .ok()
            .map(|observer| {
                observer.observe(&canvas);
                ResizeWatch {
                    observer,
                    _closure: closure,
                }
            });
        Ok(Self {
            state,
            running: None,
            _listeners: listeners,
            _resize: resize,
        })
    }

    /// Starts the frame loop when the Simulation tab shows, stops it otherwise.
    pub fn set_active(&mut self, active: bool) {
        if active && self.running.is_none() {
            let s = self.state.clone();
            {
                let mut st = s.borrow_mut();
                st.last_time_ms = None;
                st.needs_paint = true;
            }
            self.running = Some(AnimationLoop::start(move |t| {
                // Browsers stop animation frames for hidden pages; this guards the rest.
                if dom::document().hidden() {
                    return;
                }
                if let Ok(mut st) = s.try_borrow_mut() {
                    st.frame(t);
                }
            }));
        } else if !active {
            self.running = None;
        }
    }

    /// Applies raw URL parameters; returns notices about what was wrong.
    pub fn apply_params(&self, params: &[(String, String)]) -> Vec<String> {
        let mut st = self.state.borrow_mut();
        let (shell, own): (Vec<_>, Vec<_>) = params
            .iter()
            .cloned()
            .partition(|(k, _)| k == "run" || k == "speed");
        let mut notices = route::apply_params(st.exp.as_mut(), &own);
        for (key, raw) in shell {
            match (key.as_str(), raw.trim().parse::<f64>()) {
                ("run", Ok(v)) if v == 0.0 || v == 1.0 => st.clock.set_running(v == 1.0),
                ("speed", Ok(v)) if v.is_finite() && v > 0.0 => {
                    let applied = st.clock.set_speed(v);
                    if applied != v {
                        notices.push(format!("Speed “{raw}” is not offered; using {applied}×."));
                    }
                }
                _ => notices.push(format!(
                    "“{key}={}” in the link is not understood; ignored.",
                    raw.chars().take(20).collect::<String>()
                )),
            }
        }
        st.needs_paint = true;
        st.shown_values.iter_mut().for_each(|v| *v = None);
        notices
    }

    /// The URL hash of the current state on `tab`.
    pub fn hash(&self, tab: Tab) -> String {
        let st = self.state.borrow();
        match tab {
            Tab::Simulation => st.link(),
            _ => format!("#/{}/{}", st.exp.id(), tab.slug()),
        }
    }

    /// Paints once now (used by tests and right after mounting).
    pub fn paint_now(&self) {
        let mut st = self.state.borrow_mut();
        st.resize();
        st.paint();
        st.sync_dom();
        let st = &mut *st;
        st.plots.draw(st.exp.plots(), &st.palette, true);
        st.sync_timebar();
    }
}

/// The modifier keys of a pointer event (⌘ counts as Ctrl on a Mac).
fn modifiers(e: &PointerEvent) -> labcore::Modifiers {
    labcore::Modifiers {
        shift: e.shift_key(),
        ctrl: e.ctrl_key() || e.meta_key(),
    }
}

/// The HTML of the experiment's tables.
fn tables_html(tables: &[labcore::Table]) -> String {
    tables
        .iter()
        .map(|t| {
            let head: String = t
                .columns
                .iter()
                .map(|c| format!("<th scope=\"col\">{}</th>", escape(c)))
                .collect();
            let body: String = t
                .rows
                .iter()
                .enumerate()
                .map(|(i, r)| {
                    let cells: String = r.iter().map(|c| format!("<td>{}</td>", escape(c))).collect();
                    let mark = if t.highlight == Some(i) {
                        " class=\"current\" aria-current=\"true\""
                    } else {
                        ""
                    };
                    format!("<tr{mark}>{cells}</tr>")
                })
                .collect();
            format!(
                "<div class=\"table-scroll live-table\" data-table=\"{}\" tabindex=\"0\"><table><caption>{}</caption>\
                 <thead><tr>{head}</tr></thead><tbody>{body}</tbody></table></div>",
                t.key,
                escape(&t.caption)
            )
        })
        .collect()
}

/// Reads a dropped or picked file as text and hands it to the experiment.
fn read_file(state: &Rc<RefCell<SimState>>, file: web_sys::File) {
    let Ok(reader) = web_sys::FileReader::new() else {
        return;
    };
    let name = file.name();
    let s = state.clone();
    let r = reader.clone();
    let onload = Closure::once_into_js(move || {
        let text = r
            .result()
            .ok()
            .and_then(|v| v.as_string())
            .unwrap_or_default();
        let mut st = s.borrow_mut();
        match st.exp.load_file(&name, &text) {
            Ok(()) => {
                st.show_message(Some(&format!("Loaded “{name}”.")));
                st.clock.reset();
            }
            Err(e) => st.show_message(Some(&format!("Could not load “{name}”: {e}"))),
        }
        st.needs_paint = true;
        st.hash_dirty = true;
        st.plots_force = true;
    });
    reader.set_onload(Some(onload.unchecked_ref()));
    let _ = reader.read_as_text(&file);
}

/// Saves the canvas as a PNG through a Blob URL.
fn export_png(canvas: &HtmlCanvasElement, file_name: &str) {
    let name = file_name.to_owned();
    let callback = Closure::once_into_js(move |blob: JsValue| {
        if let Ok(blob) = blob.dyn_into::<web_sys::Blob>() {
            plot_view::download_blob(&name, &blob);
        }
    });
    let _ = canvas.to_blob(callback.unchecked_ref());
}

/// Paints an experiment's default scene on a small canvas (home-page cards).
pub fn paint_thumbnail(canvas: &HtmlCanvasElement, exp: &dyn Experiment) {
    let Some(ctx) = canvas
        .get_context("2d")
        .ok()
        .flatten()
        .and_then(|c| c.dyn_into::<CanvasRenderingContext2d>().ok())
    else {
        return;
    };
    let el: &HtmlElement = canvas.unchecked_ref();
    let (w, h) = (f64::from(el.client_width()), f64::from(el.client_height()));
    let (w, h) = if w < 1.0 { (240.0, 160.0) } else { (w, h) };
    let dpr = dom::window().device_pixel_ratio().max(1.0);
    canvas.set_width((w * dpr) as u32);
    canvas.set_height((h * dpr) as u32);
    let mut scene = Scene::default();
    exp.scene(&mut scene);
    let palette = Palette::from_css(canvas);
    let viewport = Viewport::fit(exp.view(), w, h);
    paint(&ctx, &scene, &viewport, w, h, dpr, &palette);
}
