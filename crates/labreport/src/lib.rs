//! # labreport — the lab report, loaded on demand
//!
//! Making the report's HTML (its SVG scene and plots, data tables and quiz
//! table: [`labpage::report::render_sheet`]) is about 18 KB of gzipped wasm
//! that a student needs only when they press "Lab report". So it is a
//! module of its own, `pkg/report.<hash>.wasm`, which the page fetches on
//! that press (or when the pointer or focus first reaches the button): the
//! experiment's module copies what the report prints into a
//! [`labpage::report::Sheet`], writes it as bytes
//! ([`labpage::report::wire`]), and this module turns the bytes into the
//! file. Both come from the same build, so the bytes need no version.

use wasm_bindgen::prelude::*;

/// Talc, as in the experiments' modules (labweb's `ALLOCATOR`).
#[cfg(all(target_family = "wasm", not(target_feature = "atomics")))]
#[global_allocator]
static ALLOCATOR: talc::wasm::WasmDynamicTalc = talc::wasm::new_wasm_dynamic_allocator();

/// The report file (one HTML document) for the bytes of a sheet; an error
/// message when they cannot be read (a damaged or foreign buffer).
#[wasm_bindgen]
pub fn render(sheet: &[u8]) -> Result<String, String> {
    labpage::report::render_bytes(sheet).map_err(|e| e.to_string())
}
