//! The platform's benchmark scene and the paint benchmarks the browser
//! benchmark (`tests/bench/browser.bench.mjs`) calls through the module's
//! exports, and its same-run A/B switches (the timeline recording, "The
//! math" panel open). Behind the `bench-exports` feature: the wasm tests and
//! `cargo xtask bench --browser` build it, shipped modules do not (it cost
//! every page about 250 lines of code).

use crate::{dom, draw, plot_view};
use wasm_bindgen::prelude::*;

/// The platform's big-scene budget: a 512×512 grid of cell states, its
/// three state colours, and a tree of 100,000 edges, seeded so every run
/// draws the same picture. [`BigTree::grow`] adds more edges the same way.
pub struct BigScene {
    pub cells: Vec<u8>,
    pub palette: Vec<labcore::RasterColour>,
    pub tree: BigTree,
}

/// A random tree in the 100 m square: each edge joins a random earlier node
/// to a new node at most 2 m away in x and y.
pub struct BigTree {
    rng: labcore::Lcg64,
    nodes: Vec<labcore::glam::DVec2>,
    pub segments: Vec<(labcore::glam::DVec2, labcore::glam::DVec2)>,
}

impl BigTree {
    /// Adds `n` edges and returns them.
    pub fn grow(&mut self, n: usize) -> &[(labcore::glam::DVec2, labcore::glam::DVec2)] {
        use labcore::glam::DVec2;
        let first = self.segments.len();
        for _ in 0..n {
            let parent = self.nodes[(self.rng.next_f64() * self.nodes.len() as f64) as usize];
            let child = parent + DVec2::new(self.rng.range(-2.0, 2.0), self.rng.range(-2.0, 2.0));
            let child = child.clamp(DVec2::ZERO, DVec2::splat(100.0));
            self.segments.push((parent, child));
            self.nodes.push(child);
        }
        &self.segments[first..]
    }
}

/// The big scene's content (see [`BigScene`]).
#[must_use]
pub fn big_scene_parts() -> BigScene {
    use labcore::glam::DVec2;
    use labcore::{RasterColour, Role};
    let mut rng = labcore::Lcg64::new(42);
    let n = 512;
    let cells: Vec<u8> = (0..n * n).map(|_| (rng.next_f64() * 4.0) as u8).collect();
    let mut tree = BigTree {
        rng,
        nodes: vec![DVec2::splat(50.0)],
        segments: Vec::with_capacity(100_000),
    };
    tree.grow(100_000);
    BigScene {
        cells,
        palette: vec![
            RasterColour {
                role: Role::Obstacle,
                alpha: 1.0,
            },
            RasterColour {
                role: Role::Visited,
                alpha: 0.5,
            },
            RasterColour {
                role: Role::Estimate,
                alpha: 0.6,
            },
        ],
        tree,
    }
}

/// The big scene as plain items, drawn from scratch every frame: one
/// [`labcore::Item::Raster`] and one [`labcore::Item::Segments`].
#[must_use]
pub fn big_scene() -> labcore::Scene {
    let parts = big_scene_parts();
    let mut scene = labcore::Scene::default();
    scene.push(raster_item(&parts, None));
    scene.push(labcore::Item::Segments {
        segments: parts.tree.segments,
        width_px: 0.6,
        role: labcore::Role::Path,
    });
    scene
}

/// The big scene's grid as a plain raster, or a versioned one (`Some((id, version))`).
fn raster_item(parts: &BigScene, versioned: Option<(u64, u64)>) -> labcore::Item {
    use labcore::glam::DVec2;
    let n = 512;
    match versioned {
        None => labcore::Item::Raster {
            min: DVec2::ZERO,
            cell_m: 100.0 / n as f64,
            cols: n,
            rows: n,
            cells: parts.cells.clone(),
            palette: parts.palette.clone(),
        },
        Some((id, version)) => labcore::Item::VersionedRaster {
            id,
            version,
            min: DVec2::ZERO,
            cell_m: 100.0 / n as f64,
            cols: n,
            rows: n,
            cells: parts.cells.clone(),
            palette: parts.palette.clone(),
        },
    }
}

/// The big scene with kept layers: a versioned raster and a segment layer.
#[must_use]
pub fn big_scene_kept(
    parts: &BigScene,
    layer: &labcore::scene::SegmentLayer,
    raster_version: u64,
) -> labcore::Scene {
    let mut scene = labcore::Scene::default();
    scene.push(raster_item(parts, Some((BIG_RASTER_ID, raster_version))));
    scene.push(labcore::Item::SegmentLayer {
        layer: layer.clone(),
        width_px: 0.6,
        role: labcore::Role::Path,
    });
    scene
}

/// The big scene's raster among the kept rasters.
const BIG_RASTER_ID: u64 = 0xb16;

/// Per-frame milliseconds of the big scene on an 800×600 canvas, `frames`
/// frames, each ended by a one-pixel read so the drawing has finished:
/// - `mode` 0: the plain items drawn from scratch every frame (the old way);
/// - `mode` 1: first frames of the kept layers (a new tree layer and a new
///   raster version every frame: a full redraw and an upload);
/// - `mode` 2: steady state of the kept layers: the tree gains
///   `edges_per_frame` edges a frame, the grid does not change;
/// - `mode` 3: like 2, and as many drawn edges a frame are rewired (moved to
///   another node, seeded), as an RRT* rewire does.
#[wasm_bindgen]
pub fn bench_big_scene_frames(frames: u32, mode: u32, edges_per_frame: u32) -> Vec<f64> {
    let (w, h) = (800.0, 600.0);
    let Some((canvas, ctx)) = scratch_canvas(w as u32, h as u32) else {
        return Vec::new();
    };
    let palette = draw::Palette::from_css(&canvas);
    let view = labcore::ViewBox {
        min: labcore::glam::DVec2::ZERO,
        max: labcore::glam::DVec2::splat(100.0),
    };
    let viewport = draw::Viewport::fit(view, w, h);
    let mut parts = big_scene_parts();
    let mut layer = labcore::scene::SegmentLayer::from_segments(parts.tree.segments.clone());
    let plain = big_scene();
    let mut times = Vec::with_capacity(frames as usize);
    let frame = |scene: &labcore::Scene| {
        let start = dom::now_ms();
        draw::paint(&ctx, scene, &viewport, w, h, 1.0, &palette);
        let _ = ctx.get_image_data(0.0, 0.0, 1.0, 1.0);
        dom::now_ms() - start
    };
    let mut rewire_rng = labcore::Lcg64::new(7);
    if mode >= 2 {
        // The first frame draws everything; the measured ones follow it.
        frame(&big_scene_kept(&parts, &layer, 1));
    }
    for i in 0..frames {
        let scene = match mode {
            0 => None,
            1 => {
                layer = labcore::scene::SegmentLayer::from_segments(parts.tree.segments.clone());
                Some(big_scene_kept(&parts, &layer, 1000 + u64::from(i)))
            }
            _ => {
                for s in parts.tree.grow(edges_per_frame as usize) {
                    layer.push(*s);
                }
                for _ in 0..if mode == 3 { edges_per_frame } else { 0 } {
                    let n = layer.len() as f64;
                    let slot = (rewire_rng.next_f64() * n) as usize;
                    let from = layer.segments()[(rewire_rng.next_f64() * n) as usize].1;
                    let to = layer.segments()[slot].1;
                    layer.set(slot, (from, to));
                }
                Some(big_scene_kept(&parts, &layer, 1))
            }
        };
        times.push(frame(scene.as_ref().unwrap_or(&plain)));
    }
    times
}

/// Paints [`big_scene`] `frames` times on an 800×600 canvas and returns the
/// mean milliseconds per frame (the end-to-end tests report it).
#[wasm_bindgen]
pub fn bench_big_scene(frames: u32) -> f64 {
    time_paint(big_scene(), frames)
}

/// Like [`bench_big_scene`] for one of its two items (0: the raster, 1: the segments).
#[wasm_bindgen]
pub fn bench_big_scene_part(frames: u32, item: usize) -> f64 {
    let mut scene = big_scene();
    let keep = scene.items.swap_remove(item.min(1));
    scene.items = vec![keep];
    time_paint(scene, frames)
}

fn time_paint(scene: labcore::Scene, frames: u32) -> f64 {
    let (w, h) = (800.0, 600.0);
    let Some((canvas, ctx)) = scratch_canvas(w as u32, h as u32) else {
        return f64::NAN;
    };
    let palette = draw::Palette::from_css(&canvas);
    let view = labcore::ViewBox {
        min: labcore::glam::DVec2::ZERO,
        max: labcore::glam::DVec2::splat(100.0),
    };
    let viewport = draw::Viewport::fit(view, w, h);
    let frames = frames.max(1);
    let start = dom::now_ms();
    for _ in 0..frames {
        draw::paint(&ctx, &scene, &viewport, w, h, 1.0, &palette);
    }
    // Reading one pixel waits for the drawing to finish.
    let _ = ctx.get_image_data(0.0, 0.0, 1.0, 1.0);
    (dom::now_ms() - start) / f64::from(frames)
}

/// Paints a plot of two 10,000-sample series (`points` each) `frames` times
/// on a 600×240 canvas; returns the mean milliseconds per frame. The plot
/// keeps every sample and draws a min/max decimation of them.
#[wasm_bindgen]
pub fn bench_plot(points: u32, frames: u32) -> f64 {
    use labcore::plot::{Plot, Series, SeriesRole};
    let mut plot = Plot::new(
        "bench",
        "Benchmark",
        ("Time", "s"),
        ("Value", "m"),
        vec![
            Series::new("a", "m", SeriesRole::Primary),
            Series::new("b", "m", SeriesRole::Secondary),
        ],
    );
    let mut rng = labcore::Lcg64::new(3);
    for i in 0..points {
        let t = f64::from(i) * 0.01;
        plot.series[0].push(t, labcore::math::sin(t) + rng.range(-0.1, 0.1));
        plot.series[1].push(t, labcore::math::cos(t * 0.3));
    }
    let Some((canvas, ctx)) = scratch_canvas(600, 240) else {
        return f64::NAN;
    };
    let palette = draw::Palette::from_css(&canvas);
    let frames = frames.max(1);
    let start = dom::now_ms();
    for _ in 0..frames {
        plot_view::paint_plot(&ctx, &plot, &palette, (600.0, 240.0, 1.0));
    }
    let _ = ctx.get_image_data(0.0, 0.0, 1.0, 1.0);
    (dom::now_ms() - start) / f64::from(frames)
}

/// Same-run A/B switch of the browser benchmark (issue 26 §4): the
/// mounted simulation records its timeline (`true`, as shipped: a new
/// record from the state shown) or runs without one (`false`, the page
/// before the timeline). Returns whether a simulation is mounted.
#[wasm_bindgen]
pub fn bench_timeline_recording(on: bool) -> bool {
    crate::with_mounted_sim(|sim| sim.bench_timeline_recording(on)).is_some()
}

/// Same-run A/B switch of the browser benchmark (issue 27, Cost): "The
/// math" panel of the mounted simulation open (`true`, as shipped) or
/// closed (`false`: hidden and not written, the page before the panel).
/// Returns whether the mounted simulation has the panel.
#[wasm_bindgen]
pub fn bench_math_panel(open: bool) -> bool {
    crate::with_mounted_sim(|sim| sim.bench_math_panel(open)).unwrap_or(false)
}

/// A detached canvas of `w` × `h` pixels and its 2D context (benchmarks).
fn scratch_canvas(
    w: u32,
    h: u32,
) -> Option<(
    web_sys::HtmlCanvasElement,
    web_sys::CanvasRenderingContext2d,
)> {
    use wasm_bindgen::JsCast;
    let canvas: web_sys::HtmlCanvasElement = dom::document()
        .create_element("canvas")
        .ok()?
        .dyn_into()
        .ok()?;
    canvas.set_width(w);
    canvas.set_height(h);
    let ctx = canvas.get_context("2d").ok()??.dyn_into().ok()?;
    Some((canvas, ctx))
}
