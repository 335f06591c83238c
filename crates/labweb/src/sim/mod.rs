//! The Simulation tab: canvas, controls, readouts and the animation loop.
//!
//! Logic first, then paint: each animation frame steps the experiment with a
//! fixed `dt`, rebuilds the display list from state and paints it. Every
//! listener, the resize observer and the animation-frame closure are owned by
//! [`SimView`] and removed when it is dropped.
//!
//! The rooms: this file holds the state, the frame loop, painting and the
//! link; [`timebar`] the time controls; [`canvas_input`] pointer, touch and
//! keyboard input on the canvas; [`panel`] the controls, readouts, tables
//! and buttons beside it; [`status`] the status badge, notices and the
//! screen-reader announcements.

use crate::dom::{self, escape, query, query_all, Listener};
use crate::draw::{paint, paint_with_backdrop, Palette, Viewport};
use crate::plot_view::{self, PlotView};
use glam::DVec2;
use labcore::clock::Clock;
use labcore::route::{self, Tab};
use labcore::{Lab, ParamSpec, Phase, Scene};
use std::cell::{Cell, RefCell};
use std::rc::{Rc, Weak};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{
    CanvasRenderingContext2d, Element, HtmlCanvasElement, HtmlElement, PointerEvent, ResizeObserver,
};

mod a11y;
mod canvas_input;
mod instructor;
mod live;
mod marks;
mod panel;
mod scrub;
mod status;
mod timebar;

use panel::{readouts_html, tables_html};
use status::{statusbar_html, NoticeShelf};
use timebar::timebar_html;

/// Minimum time between URL updates while a control moves, milliseconds.
/// While a drag or a held arrow key streams, the URL waits until the stream
/// has been still this long: each URL change makes the browser fetch the
/// page's icon again and decode it (an SVG, a document of its own: about
/// 12 ms a time on a 4x-throttled phone).
const HASH_INTERVAL_MS: f64 = 250.0;

/// Minimum time between two writes of the page's text (readouts, status,
/// tables, the time, plot summaries) while the clock alone changes them,
/// milliseconds. Numbers that change 60 times a second cannot be read, and
/// every text write makes the browser restyle, lay out and repaint the page:
/// on a phone at a 4× CPU throttle that cost a frame each time. An input, an
/// action or the end of a motion writes at once.
pub const TEXT_INTERVAL_MS: f64 = 250.0;

/// The share of a frame the simulation's steps may take, milliseconds (see
/// [`Clock::take_steps`]): after a slow frame the clock asks for several
/// steps to catch up, and taking them all made that frame slower still (RRT*
/// grew up to 16 batches in one frame). Half of a 60 Hz frame; the paint
/// needs the rest.
pub const STEP_BUDGET_MS: f64 = 8.0;

/// Why the simulation could not start (the reading tabs still work).
#[derive(Debug)]
pub struct SimError(pub String);

/// The equations "The math" panel shows: those the content's `math` list
/// names, in its order.
pub(super) fn panel_equations(exp: &dyn Lab) -> Vec<labcore::live_math::Equation> {
    let names = labcore::find(exp.id())
        .and_then(|e| e.content().ok())
        .map_or(&[][..], |c| &c.math[..]);
    labcore::live_math::named(exp.equations(), names)
}

/// Watches each equation block of "The math" panel in `panel`, in the
/// panel's order (that of [`panel_equations`]), with the browser's observers
/// ([`dom::watch_box`]): a streaming run writes only the equations a
/// student can see ([`SimState::sync_math`]).
fn watch_equations(panel: &Element) -> Vec<Option<dom::BoxWatch>> {
    query_all(panel, ".live-math [data-equation]")
        .iter()
        .map(dom::watch_box)
        .collect()
}

/// The HTML of the Simulation tab for an experiment.
///
/// Three parts side by side on a laptop (see `style.css`): the stage (the
/// canvas, the status strip under it, the time bar, the actions that start
/// a run, then the tools: files, Save PNG, report, Describe and the
/// description it shows), the plots (the experiment's main plot, its first,
/// on top, then the watched ones, then the others) and the side (the
/// caption, readouts, tables, "The math" and controls). The stage and the plots stay put while the page scrolls the
/// side, so the scene and its plots stay in view while any control is used.
/// On a phone the parts dissolve into one ordered column: the canvas, its
/// status and time bar, the actions, the main plot, the plots the
/// experiment has the student watch ([`labcore::Presentation::watched_plots`])
/// and the live tables, then the rest.
pub fn render(exp: &dyn Lab, caption: &str) -> String {
    let controls = panel::controls_html(exp.params());
    let actions: String = exp
        .actions()
        .iter()
        .map(|a| {
            format!(
                "<button type=\"button\" data-action=\"{}\"{}>{}</button>",
                a.key,
                if exp.action_shown(a.key) {
                    ""
                } else {
                    " hidden"
                },
                escape(a.label)
            )
        })
        .chain([panel::group_html(
            exp.params(),
            Some(ParamSpec::WITH_ACTIONS),
        )])
        .collect();
    let readouts = readouts_html(&exp.readouts());
    let math =
        labpage::math_panel::panel_html(&panel_equations(exp), &exp.quantities(), &exp.readouts());
    let statusbar = statusbar_html(&exp.status());
    let timebar = if exp.animated() {
        timebar_html(exp.natural_step_s())
    } else {
        String::new()
    };
    // An experiment with a timeline keeps the runs its branches leave: each
    // plot has their places in its legend from the start.
    let slotted;
    let all_plots = if exp.animated() && !exp.plots().is_empty() {
        slotted = labcore::timeline::with_kept(exp.plots(), &[], 0);
        &slotted[..]
    } else {
        exp.plots()
    };
    let main_plot = all_plots.first().map_or(String::new(), |p| {
        format!(
            "<section class=\"sim-mainplot\" aria-label=\"Main plot\">{}</section>",
            plot_view::render(p)
        )
    });
    // The plots the Procedure has the student watch come first, in a box
    // the phone's column moves up (style.css), then the others in order.
    let watched = exp.watched_plots();
    let (mut first, mut more_plots) = (String::new(), String::new());
    for p in all_plots.iter().skip(1) {
        let html = plot_view::render(p);
        if watched.contains(&p.key) {
            first.push_str(&html);
        } else {
            more_plots.push_str(&html);
        }
    }
    if !first.is_empty() {
        more_plots.insert_str(0, &format!("<div class=\"watched\">{first}</div>"));
    }
    let more_plots = if more_plots.is_empty() {
        more_plots
    } else {
        format!("<section class=\"plots\" aria-label=\"Plots\">{more_plots}</section>")
    };
    let plots = if all_plots.is_empty() {
        String::new()
    } else {
        format!("<div class=\"sim-plots\">{main_plot}{more_plots}</div>")
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
    let note = instructor::note_html();
    let presets = instructor::presets_html(exp);
    let instructor_panel = instructor::panel_html(exp.params());
    format!(
        "{note}<div class=\"sim\">\
           <div class=\"sim-stage\">\
             <div class=\"sim-frame\">\
               <canvas class=\"sim-canvas\" data-touch=\"{touch}\" tabindex=\"0\" role=\"application\" aria-roledescription=\"simulation\" \
                 aria-label=\"Simulation canvas. Drag or tap to interact; with the canvas focused, arrow keys move the point (Shift for fine steps), [ and ] choose a point to move{keys}, D describes the scene, question mark lists every key.\"></canvas>\
             </div>{statusbar}{touch_note}\
             {timebar}\
             <div class=\"sim-actions\">{actions}</div>\
             <div class=\"sim-tools\">{files}{save}<button type=\"button\" class=\"mini\" data-export=\"png\">Save PNG</button>{report}{describe}</div>\
             {description}\
           </div>{plots}\
           <div class=\"sim-side\">\
             <p class=\"sim-caption\">{caption}</p>\
             <dl class=\"readouts\">{readouts}</dl>\
             <p class=\"sim-message\" role=\"alert\" hidden></p>\
             <section class=\"tables\" aria-label=\"Tables\">{tables}</section>{math}\
             {presets}<form class=\"sim-controls\" aria-label=\"Parameters\">{controls}</form>{move_form}\
             {report_fields}\
             <p class=\"sr-only sim-live\" aria-live=\"polite\"></p>\
           </div>\
         </div>{instructor_panel}",
        touch = if exp.captures_touch() { "all" } else { "handles" },
        report = crate::report_view::BUTTON_HTML,
        report_fields = crate::report_view::fields_html(exp.id()),
        keys = if exp.animated() { ", Space plays or pauses, full stop steps once, comma steps back, End runs to the end, M marks the moment" } else { "" },
        describe = a11y::describe_button_html(),
        description = a11y::DESCRIPTION_HTML,
        move_form = a11y::move_form_html(),
    )
}

/// Whether the device's main pointer is a finger (the touch hint shows first).
fn coarse_pointer() -> bool {
    web_sys::window()
        .and_then(|w| w.match_media("(pointer: coarse)").ok().flatten())
        .is_some_and(|m| m.matches())
}

/// State shared by the frame loop and the event handlers.
struct SimState {
    exp: Box<dyn Lab>,
    canvas: HtmlCanvasElement,
    ctx: CanvasRenderingContext2d,
    panel: Element,
    scene: Scene,
    palette: Palette,
    viewport: Viewport,
    css_size: (f64, f64),
    dpr: f64,
    /// Set by the canvas's `ResizeObserver`: `css_size` is to be read again.
    /// Between resizes a frame reads no layout for it (a size read after
    /// an input, a scrub's slider moved, made the browser lay out what the
    /// input changed mid-frame, then again after it).
    size_stale: Rc<Cell<bool>>,
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
    /// A jump in time: every plot whose picture changed (not only one, as
    /// while a run streams) is repainted in the next frame.
    plots_stale: bool,
    /// A jump in time: the next frame moves the plots' cursors and writes
    /// the time bar (the slider, the time), whatever the text's pace.
    jumped: bool,
    /// Running, speed, steps and whether the play button offers Replay, as shown.
    shown_time: (bool, f64, u64, bool),
    /// The run's phase at the last frame (the time bar offers Replay when ended).
    phase: Phase,
    /// What the badge and the time bar show of the clock (`data-clock`).
    shown_clock: Option<timebar::ClockState>,
    /// The clock was stopped because the run ended (not by the student): it
    /// resumes by itself when the run is live again (a new goal, a reset).
    ended_hold: bool,
    needs_paint: bool,
    /// What each control shows; `None` = unknown (refresh it), `Some(None)` = empty.
    shown_values: Vec<Option<Option<f64>>>,
    shown_readouts: Vec<String>,
    /// The `<dd>` of each shown readout, found when the list is built.
    readout_elements: Vec<Option<Element>>,
    /// The time bar's `t = … s` output and its text.
    time_output: Option<Element>,
    shown_time_text: String,
    /// When the page's text was last written (animation-frame time, ms).
    text_ms: f64,
    /// The model moved since the page's text was last written.
    text_stale: bool,
    /// This frame's input is part of a stream (a drag's moves, arrow keys
    /// moving a point): its text keeps the pace of a run instead of being
    /// written at every event.
    text_paced: bool,
    /// A pointer holds the timeline slider: its moves are a stream
    /// ([`SimState::text_paced`]) until it lets go.
    scrub_dragging: bool,
    /// The dragged timeline slider moved since the last frame.
    scrub_moved: bool,
    /// The frame (animation-frame time, ms) after its last move.
    scrub_moved_ms: f64,
    /// The next paint draws the scene's kept layers as drafts (a moving
    /// timeline drag: [`crate::layers::set_draft`]).
    scene_draft: bool,
    /// A layer of the scene on the canvas is a draft: painted again, sharp,
    /// once the drag rests.
    scene_drafted: bool,
    shown_status: Option<labcore::Status>,
    notices: NoticeShelf,
    /// Serial of the notice on screen.
    shown_notice: Option<u64>,
    /// Whether the last pointer was a finger (the caption shows the touch hint).
    touch_input: bool,
    shown_hint: Option<(&'static str, bool)>,
    shown_tables: Vec<labcore::Table>,
    /// Which action buttons are shown, a bit each in the order of
    /// `actions()`, as last written (`None` until the first write).
    shown_actions: Option<u32>,
    /// "The math" panel's changing parts as last written, an entry per
    /// equation: the substituted form, the result and the text twin.
    shown_math: Vec<(String, String, String)>,
    /// Equations a streaming run's text update left to write, with their
    /// parts as of that update: written one an idle time after the frames
    /// that follow ([`SimState::write_math_when_idle`]), or where the
    /// browser cannot tell, one a frame ([`SimState::write_next_equation`]),
    /// so no frame lays out, or paints, the readouts and every formula
    /// together.
    math_pending: Vec<(usize, (String, String, String))>,
    /// The simulation step (`Clock::steps`) whose numbers
    /// [`SimState::math_pending`] holds, when that collection weighed every
    /// equation (none left out of the window): once the last of them is
    /// written, the panel's `data-step` names it, so the panel's numbers
    /// are known to be that step's, like the readouts' `data-step`.
    math_step: Option<u64>,
    /// The idle-time call that writes [`SimState::math_pending`] and lays
    /// the page out then ([`SimState::write_math_when_idle`]) is asked for.
    math_idle_asked: bool,
    /// The height (CSS px) "The math" panel is held at while a run streams
    /// ([`SimState::write_math_when_idle`]); 0 when not held.
    math_held_px: i32,
    /// A streaming run's text update left the readouts for the idle time,
    /// with the panel's equations ([`SimState::write_math_when_idle`]).
    readouts_in_idle: bool,
    /// The idle-time rehearsal of a scrub ([`SimState::rehearse_scrub`])
    /// is asked for.
    rehearse_asked: bool,
    /// A scrub was rehearsed (or done): the browser has compiled its code.
    scrub_rehearsed: bool,
    /// Which equations the panel was written for (the slice's address): a
    /// parameter may choose another set (pid's actuator limit).
    shown_equations: usize,
    /// Whether each equation of "The math" panel was in the window at the
    /// last [`SimState::measure_math`] (each true until measured).
    equations_on_screen: Vec<bool>,
    /// The browser's observers watching each equation of "The math" panel
    /// (its size, and whether it is in the window), so no frame reads its
    /// place; `None` where there are none ([`watch_equations`]).
    math_watch: Vec<Option<dom::BoxWatch>>,
    /// The text being written follows an input or the end of a motion
    /// (not a run's pace): every part is written, seen or not.
    text_at_once: bool,
    /// The text being written follows a single input (a click, a typed
    /// value, a scrub) or the end of a motion or of a stream of input, not
    /// the pace of a run or of a stream: the page shows all of it, the
    /// readouts and every equation, in the same frame, and any equations
    /// still left to the idle time are written with it.
    /// Left false by a text update at a run's or a stream's pace: when both
    /// are over, the frame writes the text once more, settled, so what the
    /// pace left unwritten (the panel out of the window) shows the state
    /// it rests in.
    text_settled: bool,
    /// The key of the live quantity whose symbol is hovered or focused: its
    /// tagged parts of the scene are drawn as a halo.
    live_key: Option<String>,
    shown_view: labcore::ViewBox,
    hash_dirty: bool,
    last_hash_ms: f64,
    /// The kept picture of the scene's backdrop.
    backdrop: crate::layers::Backdrop,
    /// When a streamed input (a drag, a held arrow key) last moved the scene.
    last_stream_ms: f64,
    /// A motion ended during a stream of input: announce the state once the
    /// stream has been still for [`TEXT_INTERVAL_MS`].
    announce_when_still: bool,
    frame_times: FrameTimes,
    /// The instructor's locks, hidden controls and note from the link.
    instructor: route::Instructor,
    /// The quiz seed the link fixed, kept in the Simulation tab's link.
    quiz_seed: Option<u64>,
    /// The handle the keyboard and the Move form act on (drawn with a ring).
    focused_handle: Option<String>,
    shown_move: a11y::ShownMove,
    /// The run's record, for an experiment with time controls (the
    /// timeline: [`scrub`]).
    timeline: Option<labcore::timeline::Timeline>,
    /// Run to end is finishing the run; the step it started from.
    run_to_end: Option<u64>,
    /// The timeline paused the run (a scrub, Run to end), not the student:
    /// the next change plays ([`SimState::finish_branch`]).
    timeline_paused: bool,
    /// The timeline slider and what it shows: (first, last, shown) step.
    scrub_slider: Option<Element>,
    shown_scrub: (u64, u64, u64),
    /// The (first, last, shown) step the slider's `aria-valuetext` names.
    shown_valuetext: (u64, u64, u64),
    /// The marked moments of the run ([`marks`]).
    marks: marks::MarkState,
    /// The run's last state while the scene shows the past: its plots are
    /// drawn (with a cursor at the moment shown), and an input there keeps
    /// it as the run the branch left behind ([`scrub`]).
    record_end: Option<Box<dyn Lab>>,
    /// Runs that branches left behind, on the plots and as ghosts.
    kept: Vec<labcore::timeline::KeptRun>,
    /// Bumped whenever `kept` changes (the plots redraw).
    kept_serial: u64,
    /// A branch whose name waits for the input to be applied.
    pending_branch: Option<scrub::PendingBranch>,
    /// What the next input is, when the page knows (an action).
    branch_cause: Option<&'static labcore::ActionSpec>,
    /// The browser benchmark closed "The math" panel: hidden and not
    /// written, as the page was before it ([`SimView::bench_math_panel`]).
    #[cfg(feature = "bench-exports")]
    bench_math_closed: bool,
}

/// Recent busy-frame times (step + paint), published on the canvas as
/// `data-frame-p95-ms` and `data-frame-max-ms` for tests and curious users.
#[derive(Default)]
struct FrameTimes {
    recent_ms: Vec<f64>,
    next: usize,
    max_ms: f64,
    published_max_ms: f64,
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
        // Every 15 frames, and at once for a new worst frame (a slow frame
        // alone would otherwise publish at every frame it happens).
        if self.since_publish >= 15 || ms > self.published_max_ms {
            self.published_max_ms = self.max_ms;
            self.since_publish = 0;
            // An insertion sort of at most WINDOW times every 15 frames: a
            // generic sort would add about 1 KB to every module's gzip bytes.
            let mut sorted = self.recent_ms.clone();
            for i in 1..sorted.len() {
                let mut j = i;
                while j > 0 && sorted[j - 1].total_cmp(&sorted[j]).is_gt() {
                    sorted.swap(j - 1, j);
                    j -= 1;
                }
            }
            let p95 = sorted[(sorted.len() * 95 / 100).min(sorted.len() - 1)];
            let _ = canvas.set_attribute("data-frame-p95-ms", &format!("{p95:.2}"));
            let _ = canvas.set_attribute("data-frame-max-ms", &format!("{:.2}", self.max_ms));
        }
    }
}

impl SimState {
    /// Reads the canvas's size only when it may have changed
    /// ([`SimState::size_stale`], no size yet, another pixel ratio), then
    /// fits the view as [`SimState::resize`] does.
    fn resize_if_needed(&mut self) {
        let dpr = dom::window().device_pixel_ratio().max(1.0);
        if self.size_stale.get() || self.css_size.0 < 1.0 || dpr != self.dpr {
            let _ = self.resize();
        } else {
            self.fit_view();
        }
    }

    /// Reads the canvas's size and pixel ratio; when they changed, sizes its
    /// backing store (which clears it) and returns true. A zero size (the
    /// tab hidden) changes nothing and leaves the size to be read again.
    fn resize(&mut self) -> bool {
        let rect = self.canvas.get_bounding_client_rect();
        let (w, h) = (rect.width(), rect.height());
        let dpr = dom::window().device_pixel_ratio().max(1.0);
        if w < 1.0 || h < 1.0 {
            return false;
        }
        self.size_stale.set(false);
        let changed = (w, h) != self.css_size || dpr != self.dpr;
        if changed {
            self.css_size = (w, h);
            self.dpr = dpr;
            self.canvas.set_width((w * dpr).round() as u32);
            self.canvas.set_height((h * dpr).round() as u32);
            self.needs_paint = true;
            // The experiment may pick a view that keeps cells finger-sized.
            self.exp.viewport_px(w, h);
        }
        self.fit_view();
        changed
    }

    /// Fits the experiment's view (it may change with the state) into the
    /// canvas's size.
    fn fit_view(&mut self) {
        let (w, h) = self.css_size;
        if w < 1.0 || h < 1.0 {
            return;
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
        // Reads before writes: the plots' sizes are read while the page's
        // layout is still clean; read after the readouts are written, each
        // would make the browser lay the page out again mid-frame.
        self.finish_branch();
        if std::mem::take(&mut self.scrub_moved) {
            self.scrub_moved_ms = time_ms;
        }
        // A moving drag of the timeline draws drafts and keeps the plots'
        // pictures until it rests.
        self.scene_draft = self.scrub_moving(time_ms);
        if self.scene_drafted && !self.scene_draft {
            self.needs_paint = true;
        }
        let plots_due =
            self.plots_force || self.plots_stale || (!self.scene_draft && self.plots.due(time_ms));
        if plots_due {
            self.plots.measure();
        }
        if time_ms - self.text_ms >= TEXT_INTERVAL_MS {
            // The text may be written this frame: is the panel seen?
            self.measure_math();
        }
        // Painting asked for by an input, an action or a resize (before the
        // clock's steps ask for theirs): its text is written at once, unless
        // the input is a stream (a drag, a held arrow key), whose text is
        // written at most every TEXT_INTERVAL_MS and once more when it ends.
        let input_paint = self.needs_paint && !self.text_paced;
        let streamed_input = self.needs_paint && self.text_paced;
        self.text_paced = false;
        if streamed_input {
            self.last_stream_ms = time_ms;
        }
        // A stream of input keeps the page's text at its pace, even when each
        // input starts and ends a motion (an IK arm turning to a target moved
        // by a held key started and stopped 20 times a second).
        let streaming = time_ms - self.last_stream_ms < TEXT_INTERVAL_MS;
        let was_animating = self.exp.animating();
        // Asked before the clock counts this frame's steps: the frame that
        // reaches the record's end replays up to it, not on from the past.
        let in_past = self.in_past();
        // An idle experiment's clock does not tick (t counts motion only).
        let steps = if was_animating || !self.exp.animated() {
            self.clock.advance(elapsed_s)
        } else {
            0
        };
        let steps = if self.run_to_end.is_some() {
            self.run_to_end_frame(start) as u32
        } else if steps > 0 && in_past {
            // Play from the past replays the record up to its end.
            let from = self.clock.steps() - u64::from(steps);
            self.forward_in_past(from, u64::from(steps)) as u32
        } else if steps > 0 {
            self.timeline_commit();
            // A run may move a locked parameter (an arm turning to its
            // target): it is held, quietly.
            let clock = &mut self.clock;
            let timeline = &mut self.timeline;
            let mut taken = 0;
            let _ = route::keep_locked(self.exp.as_mut(), &self.instructor, |exp| {
                taken = clock.take_steps(
                    steps,
                    STEP_BUDGET_MS,
                    || dom::now_ms() - start,
                    // A run ends on the step that ends it, however the
                    // frames fell (a replay ends at the same t).
                    || {
                        exp.step(Clock::DT_S);
                        if let Some(tl) = timeline.as_mut() {
                            tl.stepped(exp);
                        }
                        exp.status().phase != Phase::Ended
                    },
                );
            });
            taken
        } else {
            0
        };
        let phase_before = self.phase;
        self.follow_phase();
        let stopped = was_animating && !self.exp.animating();
        if stopped {
            // The state the motion ended in belongs in the link.
            self.hash_dirty = true;
        }
        let run_over = phase_before == Phase::Live && self.phase == Phase::Ended;
        if streaming && (stopped || run_over) {
            // Under a held key each press starts and ends a motion: one
            // announcement when the stream settles, not twenty a second.
            self.announce_when_still = true;
        } else {
            if stopped {
                // The state the motion ended in is worth announcing.
                self.announce();
            }
            if run_over {
                // The run is over: say what the scene shows now.
                self.describe_scene();
            }
        }
        if self.announce_when_still && !streaming && !self.exp.animating() {
            self.announce_when_still = false;
            self.announce();
        }
        // Paint while moving, and once more for the frame on which it stopped.
        if steps > 0 && (was_animating || self.exp.animating()) {
            self.needs_paint = true;
        }
        let busy = self.needs_paint || steps > 0;
        // The page's text follows the model at once after an input or when a
        // motion ends; while only the clock moves it, every TEXT_INTERVAL_MS.
        let text_due = input_paint
            || ((stopped || self.phase != phase_before) && !streaming)
            || time_ms - self.text_ms >= TEXT_INTERVAL_MS;
        if self.needs_paint {
            self.resize_if_needed();
            self.paint();
            self.text_stale = true;
            self.needs_paint = false;
        }
        // A stream's last text update, at its pace, left "The math" panel
        // out of the window unwritten: once the stream and any motion are
        // over, the text is written once more, settled.
        let settle_due = !self.text_settled && !streaming && !self.exp.animating();
        let write_text = (self.text_stale && text_due) || settle_due;
        if streamed_input && !write_text {
            // The status badge follows a drag at once (it is written only
            // when it changes: "in reach", "out of reach").
            self.sync_status_during_stream();
        }
        if write_text {
            let at_once = input_paint || !self.exp.animating();
            self.text_at_once = at_once;
            self.text_settled = input_paint || (at_once && !streaming);
            self.sync_dom();
            self.with_shown_plots(|view, plots, _| view.sync_text(plots, time_ms, at_once));
            self.text_ms = time_ms;
            self.text_stale = false;
        } else if !self.math_idle_asked {
            self.write_next_equation();
        }
        self.sync_marks();
        if self.jumped {
            self.sync_cursors();
        }
        // The cursors' `data-cursor` follows with the text (and with a
        // forced repaint of the plots, below).
        let cursor_attrs_due = write_text || input_paint || self.plots_force;
        // Plots follow the data, each at most every PLOT_INTERVAL_MS and
        // one a frame (they take turns), so no frame pays for all of them;
        // nor for a plot and the page's text together, unless forced.
        if self.plots_force {
            self.sync_cursors();
            self.with_shown_plots(|view, plots, palette| view.draw(plots, palette, true));
            self.plots_force = false;
            self.plots_stale = false;
        } else if self.plots_stale {
            self.with_shown_plots(|view, plots, palette| view.draw(plots, palette, false));
            self.plots_stale = false;
        } else if plots_due && (input_paint || !write_text) {
            self.with_shown_plots(|view, plots, palette| {
                view.draw_next(plots, palette, time_ms);
            });
        }
        if cursor_attrs_due {
            self.plots.sync_cursor_attrs();
        }
        self.sync_notice(time_ms);
        self.sync_timebar(write_text || input_paint || self.jumped);
        if write_text || input_paint {
            self.sync_valuetext();
        }
        self.jumped = false;
        if self.hash_dirty
            && time_ms - self.last_hash_ms >= HASH_INTERVAL_MS
            && time_ms - self.last_stream_ms >= HASH_INTERVAL_MS
        {
            self.write_hash();
            self.last_hash_ms = time_ms;
        }
        if busy {
            self.frame_times.record(dom::now_ms() - start, &self.canvas);
        }
        self.ask_for_scrub_rehearsal();
    }

    /// Hands the plot view the plots as the page shows them
    /// ([`scrub::shown_plots`]: the record's while the past is shown, with
    /// the kept runs) and the palette.
    fn with_shown_plots<R>(
        &mut self,
        f: impl FnOnce(&mut PlotView, &[labcore::plot::Plot], &Palette) -> R,
    ) -> R {
        let plots = scrub::shown_plots(
            self.exp.as_ref(),
            self.record_end.as_deref(),
            &self.kept,
            self.kept_serial,
        );
        f(&mut self.plots, &plots, &self.palette)
    }

    /// The link of the current state ([`SimState::state_link`]), then the
    /// instructor's locks, hidden controls and note, then the quiz seed.
    fn link(&self) -> String {
        route::with_query(self.state_link(), &self.instructor_query())
    }

    /// The link of the current state: the experiment's parameters (the
    /// hidden ones veiled: [`route::format_veiled`]), then the shell's own
    /// (`run=0` when paused, `speed` when not 1×).
    fn state_link(&self) -> String {
        let mut extra = Vec::new();
        let mut moment = false;
        if self.exp.animated() && !self.clock.running() && !self.ended_hold {
            extra.push("run=0".to_owned());
            // The moment shown, when the link's state and the steps since
            // reproduce it (no input on the way).
            let steps = self.clock.steps();
            if steps > 0 && self.timeline.as_ref().is_some_and(|t| t.unbroken_to(steps)) {
                extra.push(format!("at={:.2}", self.clock.time_s()));
                moment = true;
            }
        }
        if self.clock.speed() != 1.0 {
            extra.push(format!("speed={}", self.clock.speed()));
        }
        let marks = self.marks_link();
        // The link's last moment: the one shown, or its last mark after it.
        let last_mark = self
            .marks
            .marks
            .steps()
            .last()
            .copied()
            .filter(|_| marks.is_some());
        let linked_to = last_mark.unwrap_or(0).max(self.clock.steps());
        let inputs =
            (self.timeline.as_ref()).map_or_else(String::new, |t| t.inputs_link(linked_to));
        // A running page's link plays from the start: inputs during the run
        // come only with a moment (`at=`), so marks without one go only
        // where there were none.
        let marks = marks.filter(|_| moment || inputs.is_empty());
        moment |= marks.is_some();
        extra.extend(marks);
        // …and the actions pressed at the start, and the inputs after it.
        if let Some(tl) = self.timeline.as_ref().filter(|_| moment) {
            if !tl.start_actions().is_empty() {
                extra.push(format!("do={}", tl.start_actions().join(",")));
            }
            if !inputs.is_empty() {
                extra.push(format!("{}={inputs}", labcore::run_input::THEN_KEY));
            }
        }
        // A link naming moments carries the start they are stepped on from
        // (the run moves some parameters: ik's angles).
        let shown = self.exp.as_ref();
        let state = (self.timeline.as_ref())
            .filter(|_| moment)
            .and_then(|t| t.link_start(shown, 0))
            .unwrap_or(shown);
        let mut hash = route::format_veiled(state, Tab::Simulation, &self.instructor.hidden);
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
        for run in &self.kept {
            run.ghosts(&mut self.scene);
        }
        self.push_focus_ring();
        // Not under a kept backdrop: its picture would keep the draft (no
        // backdrop holds a segment layer today).
        crate::layers::set_draft(self.scene_draft && self.scene.backdrop == 0);
        paint_with_backdrop(
            &self.ctx,
            &self.scene,
            &self.viewport,
            w,
            h,
            self.dpr,
            &self.palette,
            &mut self.backdrop,
        );
        self.scene_drafted = crate::layers::drafted();
        crate::layers::set_draft(false);
        if let Some(key) = &self.live_key {
            crate::draw::paint_tags(
                &self.ctx,
                &self.scene.tags,
                key,
                &self.viewport,
                &self.palette,
                self.dpr,
            );
        }
        // Let go of the display list now: a kept layer it shares with the
        // model (copy-on-write) would otherwise be copied by the next step.
        self.scene.clear();
    }

    fn write_hash(&mut self) {
        // An input on its way is settled: a restart is a new run at t = 0.
        self.finish_branch();
        self.hash_dirty = false;
        let hash = self.link();
        if let Ok(history) = dom::window().history() {
            let _ = history.replace_state_with_url(&JsValue::NULL, "", Some(&hash));
        }
        self.link_written();
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
    pub fn mount(panel: &Element, exp: Box<dyn Lab>) -> Result<Self, SimError> {
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
        let equations = exp.equations().as_ptr() as usize;
        let math_watch = watch_equations(panel);
        let state = Rc::new(RefCell::new(SimState {
            exp,
            canvas: canvas.clone(),
            ctx,
            panel: panel.clone(),
            scene: Scene::default(),
            palette,
            viewport: Viewport::fit(view, 1.0, 1.0),
            css_size: (0.0, 0.0),
            size_stale: Rc::new(Cell::new(true)),
            dpr: 1.0,
            pressed_pointer: None,
            pending_touch: None,
            touch_draws: true,
            last_time_ms: None,
            clock: Clock::default(),
            plots: PlotView::mount(panel),
            plots_force: true,
            plots_stale: false,
            jumped: false,
            shown_time: (true, 0.0, u64::MAX, false),
            phase: Phase::Live,
            shown_clock: None,
            ended_hold: false,
            needs_paint: true,
            shown_values: vec![None; n_params],
            shown_readouts: Vec::new(),
            readout_elements: Vec::new(),
            time_output: query(panel, ".timebar .tb-time"),
            shown_time_text: String::new(),
            text_ms: f64::NEG_INFINITY,
            text_stale: false,
            text_paced: false,
            scrub_dragging: false,
            scrub_moved: false,
            scrub_moved_ms: f64::NEG_INFINITY,
            scene_draft: false,
            scene_drafted: false,
            shown_status: None,
            notices: NoticeShelf::default(),
            shown_notice: None,
            touch_input: coarse_pointer(),
            shown_hint: None,
            shown_tables: Vec::new(),
            shown_actions: None,
            shown_math: Vec::new(),
            math_pending: Vec::new(),
            math_step: None,
            math_idle_asked: false,
            math_held_px: 0,
            readouts_in_idle: false,
            rehearse_asked: false,
            scrub_rehearsed: false,
            shown_equations: equations,
            equations_on_screen: vec![true; math_watch.len()],
            math_watch,
            text_at_once: true,
            text_settled: true,
            live_key: None,
            shown_view: labcore::ViewBox::centered(0.0),
            hash_dirty: false,
            last_hash_ms: 0.0,
            backdrop: crate::layers::Backdrop::default(),
            last_stream_ms: f64::NEG_INFINITY,
            announce_when_still: false,
            frame_times: FrameTimes::default(),
            instructor: route::Instructor::default(),
            quiz_seed: None,
            focused_handle: None,
            shown_move: a11y::ShownMove::default(),
            timeline: None,
            run_to_end: None,
            timeline_paused: false,
            scrub_slider: query(panel, ".tb-scrub"),
            shown_scrub: (0, 0, u64::MAX),
            shown_valuetext: (0, 0, u64::MAX),
            marks: marks::MarkState::default(),
            record_end: None,
            kept: Vec::new(),
            kept_serial: 0,
            pending_branch: None,
            branch_cause: None,
            #[cfg(feature = "bench-exports")]
            bench_math_closed: false,
        }));
        state.borrow_mut().restart_timeline();
        let mut listeners = Vec::new();
        canvas_input::listen(&state, &canvas, &mut listeners);
        canvas_input::listen_time_keys(&state, &mut listeners);
        panel::listen(&state, panel, &mut listeners);
        a11y::listen(&state, panel, &mut listeners);
        scrub::listen(&state, panel, &mut listeners);
        live::listen(&state, panel, &mut listeners);
        // Theme changes (light/dark, more contrast, forced colours) repaint
        // with the new palette.
        for query in [
            "(prefers-color-scheme: dark)",
            "(prefers-contrast: more)",
            "(forced-colors: active)",
        ] {
            if let Ok(Some(mql)) = dom::window().match_media(query) {
                let s = state.clone();
                listeners.push(Listener::new(mql.as_ref(), "change", move |_| {
                    let mut st = s.borrow_mut();
                    st.palette = Palette::from_css(&st.canvas);
                    st.needs_paint = true;
                    st.plots_force = true;
                }));
            }
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
        let size_stale = state.borrow().size_stale.clone();
        let closure = Closure::<dyn FnMut(js_sys::Array)>::new(move |_entries: js_sys::Array| {
            size_stale.set(true);
            if let Ok(mut st) = s.try_borrow_mut() {
                // A new size clears the canvas: the scene is painted again
                // here, in the rendering step that shows the new size, so
                // no frame shows it blank (a running frame had painted at
                // the old size just before).
                if st.resize() {
                    st.paint();
                }
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
                // The canvas may have been resized while its tab was hidden.
                st.size_stale.set(true);
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
        let (shell, own): (Vec<_>, Vec<_>) = params.iter().cloned().partition(|(k, _)| {
            [
                "run",
                "speed",
                "at",
                "do",
                labcore::marks::MARKS_KEY,
                labcore::run_input::THEN_KEY,
            ]
            .contains(&k.as_str())
        });
        st.timeline_input();
        let mut notices = route::apply_params(st.exp.as_mut(), &own);
        // Settled now: a run it starts again starts before the link's marks.
        st.finish_branch();
        let mut at_s = None;
        let mut link_inputs = Vec::new();
        // A link is a whole state: its marks, or none.
        let mut link_marks = labcore::marks::Marks::default();
        for (key, raw) in shell {
            match (key.as_str(), raw.trim().parse::<f64>()) {
                (labcore::marks::MARKS_KEY, _) if st.timeline.is_some() => {
                    match labcore::marks::Marks::parse(&raw) {
                        Ok(marks) => link_marks = marks,
                        Err(message) => notices.push(message),
                    }
                }
                (labcore::run_input::THEN_KEY, _) if st.timeline.is_some() => {
                    match labcore::run_input::parse(&raw) {
                        Ok(inputs) => link_inputs = inputs,
                        Err(message) => notices.push(message),
                    }
                }
                ("do", _) => {
                    // The actions pressed at the link's start, after its
                    // parameters.
                    for key in raw.split(',') {
                        let Some(action) = st.exp.actions().iter().find(|a| a.key == key) else {
                            notices.push(format!("No button “{key}”; ignored."));
                            continue;
                        };
                        st.branch_cause = Some(action);
                        let mut done = Ok(());
                        st.guarded(|exp| done = exp.action(key));
                        st.finish_branch();
                        notices.extend(done.err().map(|e| e.to_string()));
                    }
                }
                ("run", Ok(v)) if v == 0.0 || v == 1.0 => st.clock.set_running(v == 1.0),
                ("at", Ok(v)) if st.timeline.is_some() && v.is_finite() && v >= 0.0 => {
                    at_s = Some((v, raw));
                }
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
        if let Some((t_s, raw)) = at_s {
            notices.extend(st.open_at(t_s, link_marks.steps().last().copied(), &link_inputs));
            let step = st.clock.steps();
            notices.extend(labcore::marks::link_time_notice(&raw, t_s, step));
        }
        st.set_marks(link_marks);
        st.needs_paint = true;
        st.shown_values.iter_mut().for_each(|v| *v = None);
        // The controls and readouts say the link's state at once, not after
        // the next frame: until then they would show (and announce) the
        // constructor's state the page was mounted with.
        st.text_at_once = true;
        st.text_settled = true;
        st.sync_dom();
        notices
    }

    /// Sets the instructor's locks, hidden controls, note and quiz seed from
    /// a link (replacing any before) and shows them; returns a notice for
    /// each key the experiment does not have.
    pub fn set_instructor(
        &self,
        mut instructor: route::Instructor,
        quiz_seed: Option<u64>,
    ) -> Vec<String> {
        let mut st = self.state.borrow_mut();
        let notices = instructor.resolve(st.exp.params());
        st.instructor = instructor;
        st.quiz_seed = quiz_seed;
        st.show_instructor();
        st.shown_values.iter_mut().for_each(|v| *v = None);
        // "The math" says "hidden" (or the number again) at once.
        st.shown_math.clear();
        st.text_at_once = true;
        st.text_settled = true;
        st.sync_dom();
        st.needs_paint = true;
        notices
    }

    /// Sets the quiz seed a link fixes (`?quiz=123`), keeping the
    /// instructor's locks, hidden controls, note and answer-key choice.
    pub fn set_quiz_seed(&self, quiz_seed: Option<u64>) {
        self.state.borrow_mut().quiz_seed = quiz_seed;
    }

    /// The URL hash of the current state on `tab`.
    pub fn hash(&self, tab: Tab) -> String {
        let st = self.state.borrow();
        match tab {
            Tab::Simulation => st.link(),
            _ => format!("#/{}/{}", st.exp.id(), tab.slug()),
        }
    }

    /// Writes the link now if the state moved since it was last written
    /// (before the page leaves the Simulation tab).
    pub fn flush_link(&self) {
        if let Ok(mut st) = self.state.try_borrow_mut() {
            if st.hash_dirty {
                st.write_hash();
            }
        }
    }

    /// Calls `f` with the experiment and the steps the clock counts (tests
    /// compare a run in the page with one of their own).
    #[doc(hidden)]
    pub fn inspect<R>(&self, f: impl FnOnce(&dyn Lab, u64) -> R) -> R {
        let st = self.state.borrow();
        f(st.exp.as_ref(), st.clock.steps())
    }

    /// The browser benchmark's A/B switch for the timeline (issue 26 §4):
    /// `false` drops the run's record, so the run steps unrecorded as the
    /// page did before the timeline (no snapshots, no slider to keep up);
    /// `true` starts a new record from the state shown, as Reset does.
    #[cfg(feature = "bench-exports")]
    pub fn bench_timeline_recording(&self, on: bool) {
        let mut st = self.state.borrow_mut();
        if on {
            st.restart_timeline();
        } else {
            st.timeline = None;
        }
    }

    /// The browser benchmark's A/B switch for "The math" panel (issue 27,
    /// Cost): closed (`false`), the panel is hidden and not written, as the
    /// page was before it; open again, it is written at the next text
    /// update where its numbers changed while it was closed, as a running
    /// panel is (its record of what it shows, [`SimState::shown_math`], is
    /// kept: it was not written while closed). Writing every equation anew
    /// at each switch would time, in every open block, a rewrite of the
    /// whole panel that a running panel does not do. Returns whether the
    /// experiment has the panel.
    #[cfg(feature = "bench-exports")]
    pub fn bench_math_panel(&self, open: bool) -> bool {
        let mut st = self.state.borrow_mut();
        st.bench_math_closed = !open;
        st.math_pending.clear();
        let Some(section) = query(&st.panel, ".live-math") else {
            return false;
        };
        let _ = section.toggle_attribute_with_force("hidden", !open);
        true
    }

    /// Runs one animation frame at `time_ms` (browser tests drive the clock
    /// with it instead of waiting for real frames).
    #[doc(hidden)]
    pub fn frame_at(&self, time_ms: f64) {
        self.state.borrow_mut().frame(time_ms);
    }

    /// Paints once now (used by tests and right after mounting).
    pub fn paint_now(&self) {
        let mut st = self.state.borrow_mut();
        st.plots.measure();
        let _ = st.resize();
        st.scene_draft = false;
        st.paint();
        st.text_at_once = true;
        st.text_settled = true;
        st.sync_dom();
        let st = &mut *st;
        st.finish_branch();
        st.sync_cursors();
        st.with_shown_plots(|view, plots, palette| {
            view.draw(plots, palette, true);
            view.sync_text(plots, dom::now_ms(), true);
        });
        st.plots_force = false;
        st.plots.sync_cursor_attrs();
        st.sync_timebar(true);
        st.sync_marks();
        if st.plots_force {
            // The plots as shown (the run's end's in the past, with the
            // kept runs), as above: not the moment's own, cut at it.
            st.with_shown_plots(|view, plots, palette| view.draw(plots, palette, true));
            st.plots_force = false;
        }
    }
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
        let mut loaded = Ok(());
        st.guarded(|exp| loaded = exp.load_file(&name, &text));
        match loaded {
            Ok(()) => {
                st.show_message(Some(&format!("Loaded “{name}”.")));
                st.clock.reset();
                st.restart_timeline();
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
pub fn paint_thumbnail(canvas: &HtmlCanvasElement, exp: &dyn Lab) {
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
