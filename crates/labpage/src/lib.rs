//! # labpage — the lab shown as HTML and SVG
//!
//! What the lab looks like outside the canvas, as pure functions from
//! labcore's model to text: the reading pages ([`content_html`]: home, the
//! Aim/Theory/Procedure/References article, the navigation) and the lab
//! report a student hands in ([`report`]: one self-contained HTML file with
//! the scene and plots as SVG). No DOM, no JavaScript: it builds and tests
//! natively. The wasm front end (labweb) and the build tool (xtask) use it;
//! labcore never does (the arrow runs `labpage -> labcore`).

pub mod content_html;
pub mod math_panel;
pub mod report;

// labcore's modules, named as at home so the report and page code reads the
// same as when it lived in labcore (`crate::scene::Scene`, `crate::find`).
#[allow(unused_imports)]
pub(crate) use labcore::{
    catalogue, clock, content, experiment, find, math, plot, quiz, registry, route, scene, table,
    units,
};
