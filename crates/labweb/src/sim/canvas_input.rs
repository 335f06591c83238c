//! Canvas input: pointer (mouse, pen, touch), keyboard and dropped files,
//! turned into plain [`Input`]s in world coordinates.

use super::{read_file, SimState};
use crate::dom::{self, Listener};
use glam::DVec2;
use labcore::Input;
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::JsCast;
use web_sys::{Event, HtmlCanvasElement, KeyboardEvent, PointerEvent};

/// How close (CSS pixels) a touch must start to a handle to grab it.
const TOUCH_GRAB_PX: f64 = 28.0;
/// A touch that moves this far (CSS pixels) without the browser scrolling becomes a drag.
const TOUCH_SLOP_PX: f64 = 10.0;

/// Wires the canvas's pointer, touch, keyboard and drop listeners to `state`.
pub(super) fn listen(
    state: &Rc<RefCell<SimState>>,
    canvas: &HtmlCanvasElement,
    listeners: &mut Vec<Listener>,
) {
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
            st.student_acted();
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
            st.guarded_input(Input::PointerDown(w), modifiers(e));
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
                    st.guarded_input(Input::PointerDown(start), modifiers(e));
                }
            }
            let pressed = st.pressed_pointer == Some(e.pointer_id());
            st.guarded_input(Input::PointerMove { pos: w, pressed }, modifiers(e));
            if pressed {
                st.needs_paint = true;
                st.text_paced = true;
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
                        st.guarded_input(Input::PointerDown(start), modifiers(e));
                        st.guarded_input(Input::PointerUp(start), modifiers(e));
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
            st.guarded_input(Input::PointerUp(w), modifiers(e));
            st.interaction_ended();
        }));
    }
    let s = state.clone();
    listeners.push(Listener::new(canvas_target, "keydown", move |e: Event| {
        let Some(e) = e.dyn_ref::<KeyboardEvent>() else {
            return;
        };
        // Handles chosen with [ ], moved with the arrows; D describes (the
        // time keys are the whole tab's: [`listen_time_keys`]).
        if s.borrow_mut().a11y_key(e) {
            e.prevent_default();
            return;
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
        st.student_acted();
        let view = st.exp.view();
        let fraction = if e.shift_key() { 0.002 } else { 0.02 };
        let delta = dir * (view.max.x - view.min.x) * fraction;
        let mods = labcore::Modifiers {
            shift: false,
            ctrl: e.ctrl_key() || e.meta_key(),
        };
        st.guarded_input(Input::Nudge(delta), mods);
        st.interaction_ended();
        // Keys repeat: a held arrow is a stream, written at the text's pace.
        st.text_paced = true;
    }));
}
/// The time keys (Space, `.`, `,`, `End`, `M`) anywhere in the Simulation
/// tab (focus in it, or on nothing while it shows), but not in a text
/// field or a select, not Space on a control that Space presses, and not
/// a key a control took already (the timeline slider's `End`, a plot's).
pub(super) fn listen_time_keys(state: &Rc<RefCell<SimState>>, listeners: &mut Vec<Listener>) {
    let s = state.clone();
    let doc = dom::document();
    listeners.push(Listener::new(doc.as_ref(), "keydown", move |e: Event| {
        let Some(k) = e.dyn_ref::<KeyboardEvent>() else {
            return;
        };
        if e.default_prevented() || k.ctrl_key() || k.meta_key() || k.alt_key() {
            return;
        }
        let key = k.key();
        let Some(el) = e
            .target()
            .and_then(|t| t.dyn_into::<web_sys::Element>().ok())
        else {
            return;
        };
        let tag = el.tag_name().to_ascii_lowercase();
        let mut st = s.borrow_mut();
        let here = if tag == "body" {
            // Focus on nothing (WebKit after a click on a button): the tab shows.
            st.canvas.offset_parent().is_some()
        } else {
            st.panel.contains(Some(el.as_ref()))
        };
        let field = match tag.as_str() {
            "textarea" | "select" => true,
            "input" => !matches!(
                el.get_attribute("type").as_deref(),
                Some("range" | "radio" | "checkbox")
            ),
            _ => el.has_attribute("contenteditable"),
        };
        let presses = matches!(tag.as_str(), "button" | "summary" | "input" | "a");
        if !here || field || !st.exp.animated() {
            return;
        }
        let act: fn(&mut SimState) = match key.as_str() {
            " " if !presses => SimState::play_pressed,
            "." => SimState::single_step,
            "," => SimState::step_back,
            "End" if tag != "input" => SimState::start_run_to_end,
            "m" | "M" => SimState::toggle_mark,
            _ => return,
        };
        e.prevent_default();
        st.student_acted();
        act(&mut st);
    }));
}

/// The modifier keys of a pointer event (⌘ counts as Ctrl on a Mac).
fn modifiers(e: &PointerEvent) -> labcore::Modifiers {
    labcore::Modifiers {
        shift: e.shift_key(),
        ctrl: e.ctrl_key() || e.meta_key(),
    }
}
