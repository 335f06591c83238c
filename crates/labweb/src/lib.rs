//! labweb — the browser front end of the robotics virtual lab.
//!
//! It turns DOM events into plain [`labcore::Input`]s, steps the active
//! experiment, asks it for a [`labcore::Scene`] and paints it. All solver logic
//! lives in `labcore`.

pub mod app;
pub mod dom;
pub mod draw;
pub mod help;
pub mod layers;
pub mod lms;
pub mod palette;
pub mod plot_view;
pub mod quiz_view;
pub mod report_view;
pub mod sim;
pub mod text;
pub mod viewport;

use std::cell::RefCell;
use wasm_bindgen::prelude::*;

/// The heap allocator of every module: Talc (a maintained allocator made
/// for wasm) in place of Rust's default dlmalloc. Measured with
/// `cargo xtask dist` on the astar module: 2.4 KB gzip less (230,117 →
/// 227,749 B), and about as much in every other module. Its frames are no
/// slower: on the phone stand-in (4× throttled), fk and pid running with
/// the scene in view averaged 5.1–6.2 ms a frame against dlmalloc's
/// 6.9–7.3 ms (bench builds, runs minutes apart). It grows the memory with
/// `memory.grow` as dlmalloc does; the module is single-threaded.
#[cfg(all(target_family = "wasm", not(target_feature = "atomics")))]
#[global_allocator]
static ALLOCATOR: talc::wasm::WasmDynamicTalc = talc::wasm::new_wasm_dynamic_allocator();

thread_local! {
    static APP: RefCell<Option<app::App>> = const { RefCell::new(None) };
}

/// Entry point: installs the panic message and mounts the app when the page
/// has an `#app` element (test pages mount explicitly with [`boot`]).
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| report_panic(&info.to_string())));
    if dom::by_id("app").is_some() {
        boot();
    }
}

/// What the panic hook shows: a visible message on the page, not only a
/// console line.
pub fn report_panic(details: &str) {
    dom::fatal(&format!(
        "Something went wrong inside the lab ({details}). Reload the page to start again."
    ));
}

/// Drops the mounted application: its listeners, frame loop and pages
/// (tests that mount again; a page only ever mounts once).
#[wasm_bindgen]
pub fn unmount() {
    let old = APP.with(|a| a.borrow_mut().take());
    drop(old);
}

/// Mounts the application into the current document.
#[wasm_bindgen]
pub fn boot() {
    unmount();
    help::install();
    let app = app::App::boot(|_| reroute());
    APP.with(|a| *a.borrow_mut() = app);
}

/// Paints the mounted simulation synchronously (used by tests).
#[wasm_bindgen]
pub fn paint_now() {
    APP.with(|a| {
        if let Some(app) = a.borrow().as_ref() {
            app.paint_now();
        }
    });
}

/// Calls `f` with the mounted simulation's experiment and the steps its
/// clock counts; `None` when none is mounted (tests compare the page's run
/// with one of their own).
#[doc(hidden)]
pub fn inspect_sim<R>(f: impl FnOnce(&dyn labcore::Lab, u64) -> R) -> Option<R> {
    with_mounted_sim(|sim| sim.inspect(f))
}

/// Calls `f` with the mounted simulation's view; `None` when none is
/// mounted.
fn with_mounted_sim<R>(f: impl FnOnce(&sim::SimView) -> R) -> Option<R> {
    APP.with(|a| a.borrow().as_ref().and_then(|app| app.with_sim(f)))
}

/// Re-reads the location hash (used by tests; browsers call it on `hashchange`).
#[wasm_bindgen]
pub fn reroute() {
    APP.with(|a| {
        // A route triggered while routing (a nested event) is a no-op.
        if let Ok(mut app) = a.try_borrow_mut() {
            if let Some(app) = app.as_mut() {
                app.route();
            }
        }
    });
}

#[cfg(feature = "bench-exports")]
mod bench;
#[cfg(feature = "bench-exports")]
pub use bench::*;
