//! Kept layers in headless Chromium (issue 16 §3): the work a frame does is
//! counted in operations (segments stroked, uploads), and the kept picture is
//! compared pixel for pixel with a full redraw. No milliseconds here: the
//! browser benchmark times the same scenes.

use labcore::glam::DVec2;
use labcore::scene::SegmentLayer;
use labcore::{Item, Role, Scene, ViewBox};
use labweb::draw::{paint, Palette, Viewport};
use labweb::layers::{counters, forget_all, reset_counters, Counters};
use wasm_bindgen::JsCast;
use wasm_bindgen_test::*;
use web_sys::{CanvasRenderingContext2d, HtmlCanvasElement};

wasm_bindgen_test_configure!(run_in_browser);

const W: f64 = 800.0;
const H: f64 = 600.0;

/// A canvas in the page (so CSS colours apply) and its context.
fn canvas(id: &str) -> (HtmlCanvasElement, CanvasRenderingContext2d) {
    let document = web_sys::window().unwrap().document().unwrap();
    if let Some(old) = document.get_element_by_id(id) {
        old.remove();
    }
    let c: HtmlCanvasElement = document
        .create_element("canvas")
        .unwrap()
        .dyn_into()
        .unwrap();
    c.set_id(id);
    c.set_width(W as u32);
    c.set_height(H as u32);
    document.body().unwrap().append_child(&c).unwrap();
    let ctx = c.get_context("2d").unwrap().unwrap().dyn_into().unwrap();
    (c, ctx)
}

fn viewport() -> Viewport {
    Viewport::fit(
        ViewBox {
            min: DVec2::ZERO,
            max: DVec2::splat(100.0),
        },
        W,
        H,
    )
}

fn pixels(ctx: &CanvasRenderingContext2d) -> Vec<u8> {
    ctx.get_image_data(0.0, 0.0, W, H).unwrap().data().0
}

/// Fresh caches and counters, a canvas and its palette.
fn setup(id: &str) -> (HtmlCanvasElement, CanvasRenderingContext2d, Palette) {
    forget_all();
    reset_counters();
    let (c, ctx) = canvas(id);
    let palette = Palette::from_css(&c);
    (c, ctx, palette)
}

fn kept(parts: &labweb::BigScene, layer: &SegmentLayer, version: u64) -> Scene {
    labweb::big_scene_kept(parts, layer, version)
}

#[wasm_bindgen_test]
fn a_static_tree_strokes_no_segment_and_uploads_nothing() {
    let (_c, ctx, palette) = setup("layers-static");
    let parts = labweb::big_scene_parts();
    let layer = SegmentLayer::from_segments(parts.tree.segments.clone());
    paint(
        &ctx,
        &kept(&parts, &layer, 1),
        &viewport(),
        W,
        H,
        1.0,
        &palette,
    );
    let first = counters();
    assert_eq!(first.segments_drawn, 100_000);
    assert_eq!(first.full_redraws, 1);
    assert_eq!(first.raster_uploads, 1);
    reset_counters();
    for _ in 0..5 {
        paint(
            &ctx,
            &kept(&parts, &layer, 1),
            &viewport(),
            W,
            H,
            1.0,
            &palette,
        );
    }
    assert_eq!(
        counters(),
        Counters {
            composites: 10,
            ..Counters::default()
        },
        "five frames of a static scene: two drawImage each, nothing else"
    );
}

#[wasm_bindgen_test]
fn a_growing_tree_strokes_only_its_new_edges_whatever_its_size() {
    for size in [10_000usize, 100_000] {
        let (_c, ctx, palette) = setup("layers-grow");
        let mut parts = labweb::big_scene_parts();
        let mut layer = SegmentLayer::from_segments(parts.tree.segments[..size].to_vec());
        paint(
            &ctx,
            &kept(&parts, &layer, 1),
            &viewport(),
            W,
            H,
            1.0,
            &palette,
        );
        reset_counters();
        for _ in 0..5 {
            for s in parts.tree.grow(100) {
                layer.push(*s);
            }
            paint(
                &ctx,
                &kept(&parts, &layer, 1),
                &viewport(),
                W,
                H,
                1.0,
                &palette,
            );
        }
        let c = counters();
        assert_eq!(c.segments_drawn, 500, "size {size}: 100 edges a frame");
        assert_eq!(
            (c.full_redraws, c.raster_uploads, c.segments_erased),
            (0, 0, 0)
        );
        assert_eq!(c.layer_uploads, 5, "one dirty rectangle a frame");
    }
}

#[wasm_bindgen_test]
fn the_raster_is_uploaded_only_when_its_version_or_colours_change() {
    let (c, ctx, palette) = setup("layers-raster");
    let parts = labweb::big_scene_parts();
    let layer = SegmentLayer::from_segments(parts.tree.segments.clone());
    for version in [1, 1, 1, 2, 2, 3] {
        paint(
            &ctx,
            &kept(&parts, &layer, version),
            &viewport(),
            W,
            H,
            1.0,
            &palette,
        );
    }
    assert_eq!(counters().raster_uploads, 3);
    // Another theme colour for obstacles: the image is rebuilt once.
    c.style().set_property("--c-obstacle", "#123456").unwrap();
    let dark = Palette::from_css(&c);
    for _ in 0..3 {
        paint(
            &ctx,
            &kept(&parts, &layer, 3),
            &viewport(),
            W,
            H,
            1.0,
            &dark,
        );
    }
    assert_eq!(counters().raster_uploads, 4);
}

/// Pixel equality: a scene whose tree grew, was rewired and was viewed at
/// another zoom over many frames, painted with kept layers, equals the same
/// final scene painted from scratch with plain items.
#[wasm_bindgen_test]
fn kept_layers_paint_the_pixels_of_a_full_redraw() {
    let (_a, kept_ctx, palette) = setup("layers-kept");
    let (_b, full_ctx) = canvas("layers-full");
    let mut parts = labweb::big_scene_parts();
    let mut layer = SegmentLayer::from_segments(parts.tree.segments[..20_000].to_vec());
    let mut rng = labcore::Lcg64::new(9);
    let zoomed = Viewport::fit(
        ViewBox {
            min: DVec2::splat(30.0),
            max: DVec2::splat(70.0),
        },
        W,
        H,
    );
    for frame in 0..40 {
        for s in parts.tree.grow(150) {
            layer.push(*s);
        }
        rewire(&mut layer, &mut rng, 30);
        let view = if (10..14).contains(&frame) {
            zoomed
        } else {
            viewport()
        };
        paint(
            &kept_ctx,
            &kept(&parts, &layer, 1),
            &view,
            W,
            H,
            1.0,
            &palette,
        );
    }
    let c = counters();
    assert!(c.segments_erased >= 30 * 25, "rewires are erased: {c:?}");
    // The first frame, the zoom in and the zoom out; each is drawn again,
    // counting coverage, at the next frame's first erase.
    assert_eq!((c.full_redraws, c.recounts), (3, 3), "{c:?}");
    assert_same_as_full_redraw(&kept_ctx, &full_ctx, &parts, &layer, &palette);
}

/// Rewires `n` random slots of `layer`, as RRT* does: a drawn edge's end
/// moves to another node.
fn rewire(layer: &mut SegmentLayer, rng: &mut labcore::Lcg64, n: usize) {
    for _ in 0..n {
        let slot = (rng.next_f64() * layer.len() as f64) as usize;
        let (a, _) = layer.segments()[slot];
        let other = layer.segments()[(rng.next_f64() * layer.len() as f64) as usize].1;
        layer.set(slot, (a, other));
    }
}

/// Paints `parts`' raster and all of `layer`'s segments from scratch on
/// `full_ctx` (the plain painter) and asserts that `kept_ctx` shows the same
/// pixels, and not a blank picture.
fn assert_same_as_full_redraw(
    kept_ctx: &CanvasRenderingContext2d,
    full_ctx: &CanvasRenderingContext2d,
    parts: &labweb::BigScene,
    layer: &SegmentLayer,
    palette: &Palette,
) {
    let mut full = Scene::default();
    full.push(Item::Raster {
        min: DVec2::ZERO,
        cell_m: 100.0 / 512.0,
        cols: 512,
        rows: 512,
        cells: parts.cells.clone(),
        palette: parts.palette.clone(),
    });
    full.push(Item::Segments {
        segments: layer.segments().to_vec(),
        width_px: 0.6,
        role: Role::Path,
    });
    paint(full_ctx, &full, &viewport(), W, H, 1.0, palette);
    let (k, f) = (pixels(kept_ctx), pixels(full_ctx));
    let differ = k.chunks(4).zip(f.chunks(4)).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "pixels that differ from a full redraw");
    assert!(
        f.chunks(4).any(|p| p != &f[0..4]),
        "the picture is not blank"
    );
}

/// A scrub shows a different layer every frame (a state restored from the
/// timeline is a copy, with its own identity), so every frame is a full
/// redraw, and none of them counts coverage: only erasing needs the counts.
/// The first frame that erases after them draws once more, counting, and
/// the picture stays the one a full redraw makes.
#[wasm_bindgen_test]
fn a_scrub_redraws_without_coverage_counts_and_the_first_erase_after_it_counts_once() {
    let (_a, kept_ctx, palette) = setup("layers-scrub");
    let (_b, full_ctx) = canvas("layers-scrub-full");
    let parts = labweb::big_scene_parts();
    let mut rng = labcore::Lcg64::new(5);
    let paint_kept = |layer: &SegmentLayer| {
        paint(
            &kept_ctx,
            &kept(&parts, layer, 1),
            &viewport(),
            W,
            H,
            1.0,
            &palette,
        );
    };
    let mut layer = SegmentLayer::new();
    for frame in 0..6 {
        let len = 2_000 + (rng.next_f64() * 18_000.0) as usize;
        layer = SegmentLayer::from_segments(parts.tree.segments[..len].to_vec());
        paint_kept(&layer);
        assert_eq!(counters().full_redraws, frame + 1, "frame {frame}");
    }
    for _ in 0..3 {
        // Run on from the last moment scrubbed to: grow and rewire.
        layer.push(parts.tree.segments[layer.len()]);
        rewire(&mut layer, &mut rng, 20);
        paint_kept(&layer);
    }
    let c = counters();
    assert_eq!((c.full_redraws, c.recounts), (6, 1), "{c:?}");
    assert!(
        c.segments_erased >= 2 * 15,
        "the later rewires are erased: {c:?}"
    );
    // One short edge in the middle: only its rows go up, at their place.
    reset_counters();
    layer.push((DVec2::new(40.0, 40.0), DVec2::new(46.0, 43.0)));
    paint_kept(&layer);
    let c = counters();
    assert_eq!((c.layer_uploads, c.segments_drawn), (1, 1), "{c:?}");
    assert!(c.layer_upload_px < (W * H / 100.0) as u64, "{c:?}");
    assert_same_as_full_redraw(&kept_ctx, &full_ctx, &parts, &layer, &palette);
}

/// A small layer (a tree's first batches) is kept too: its first frame draws
/// its edges once, and a frame after that draws only what was added.
#[wasm_bindgen_test]
fn a_small_layer_is_kept_too() {
    let (_c, ctx, palette) = setup("layers-small");
    let parts = labweb::big_scene_parts();
    let mut layer = SegmentLayer::from_segments(parts.tree.segments[..24].to_vec());
    let scene = |layer: &SegmentLayer| {
        let mut scene = Scene::default();
        scene.push(Item::SegmentLayer {
            layer: layer.clone(),
            width_px: 1.0,
            role: Role::Visited,
        });
        scene
    };
    reset_counters();
    paint(&ctx, &scene(&layer), &viewport(), W, H, 1.0, &palette);
    assert_eq!(
        (counters().segments_drawn, counters().full_redraws),
        (24, 1)
    );
    for s in &parts.tree.segments[24..48] {
        layer.push(*s);
    }
    reset_counters();
    paint(&ctx, &scene(&layer), &viewport(), W, H, 1.0, &palette);
    let c = counters();
    assert_eq!((c.segments_drawn, c.full_redraws), (24, 0), "{c:?}");
    assert_eq!(c.composites, 1);
    let p = pixels(&ctx);
    assert!(p.chunks(4).any(|px| px[3] != 0), "the edges are drawn");
}

/// A scene whose backdrop (a quiver, discs, a label) stays put while a dot
/// moves: the backdrop is painted into its kept picture once, every later
/// frame composites it, and the pixels are those of a full redraw. A changed
/// backdrop is painted directly until it has stayed the same for a frame.
#[wasm_bindgen_test]
fn a_backdrop_is_painted_once_while_it_stays_and_gives_the_pixels_of_a_full_redraw() {
    let (_a, kept_ctx, palette) = setup("backdrop-kept");
    let (_b, full_ctx) = canvas("backdrop-full");
    let scene = |disc_x: f64, dot_x: f64| {
        let mut scene = Scene::default();
        let arrows = (0..300)
            .map(|i| {
                let p = DVec2::new(5.0 + 3.0 * (i % 30) as f64, 5.0 + 9.0 * (i / 30) as f64);
                (p, p + DVec2::new(1.5, 0.8))
            })
            .collect();
        scene.push(Item::Arrows {
            arrows,
            width_px: 1.2,
            role: Role::Bound,
        });
        scene.push(Item::Circle {
            center: DVec2::new(disc_x, 50.0),
            radius_m: 8.0,
            role: Role::Obstacle,
            fill: true,
            dashed: false,
        });
        scene.push(Item::Label {
            pos: DVec2::new(20.0, 20.0),
            text: "start".into(),
            role: Role::Text,
            offset_px: DVec2::new(-14.0, 22.0),
        });
        scene.end_backdrop(labcore::BackdropKey::default().num(disc_x).finish());
        scene.push(Item::Dot {
            center: DVec2::new(dot_x, 30.0),
            radius_px: 7.0,
            role: Role::Robot,
        });
        scene
    };
    let mut backdrop = labweb::layers::Backdrop::default();
    let frame = |backdrop: &mut labweb::layers::Backdrop, s: &Scene| {
        labweb::draw::paint_with_backdrop(&kept_ctx, s, &viewport(), W, H, 1.0, &palette, backdrop)
    };
    for i in 0..6 {
        frame(&mut backdrop, &scene(40.0, 10.0 + 10.0 * f64::from(i)));
    }
    let c = counters();
    assert_eq!(c.backdrop_draws, 1, "{c:?}");
    assert_eq!(c.composites, 5, "every frame after the first: {c:?}");
    paint(
        &full_ctx,
        &scene(40.0, 60.0),
        &viewport(),
        W,
        H,
        1.0,
        &palette,
    );
    let (k, f) = (pixels(&kept_ctx), pixels(&full_ctx));
    let differ = k.chunks(4).zip(f.chunks(4)).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "pixels that differ from a full redraw");

    // A dragged disc: painted directly while it moves, kept once it stops.
    reset_counters();
    for i in 0..3 {
        frame(&mut backdrop, &scene(41.0 + f64::from(i), 60.0));
    }
    assert_eq!(counters().backdrop_draws, 0);
    assert_eq!(counters().composites, 0);
    frame(&mut backdrop, &scene(43.0, 60.0));
    assert_eq!(counters().backdrop_draws, 1);
    paint(
        &full_ctx,
        &scene(43.0, 60.0),
        &viewport(),
        W,
        H,
        1.0,
        &palette,
    );
    assert_eq!(pixels(&kept_ctx), pixels(&full_ctx));
    // Colours read again (the theme changed): drawn anew.
    let palette = Palette::from_css(&_a);
    reset_counters();
    for _ in 0..3 {
        labweb::draw::paint_with_backdrop(
            &kept_ctx,
            &scene(43.0, 60.0),
            &viewport(),
            W,
            H,
            1.0,
            &palette,
            &mut backdrop,
        );
    }
    assert_eq!((counters().backdrop_draws, counters().composites), (1, 2));
}

/// A streaming cloud of dots (the workspace sweep) is one crisp blit of its
/// bounding box, which changes size at every frame. The canvas the blit
/// goes through only grows, so a smaller cloud after a bigger one does not
/// resize it, and the smaller cloud's picture shows none of the bigger one.
#[wasm_bindgen_test]
fn crisp_blits_of_a_shrinking_cloud_keep_their_canvas_and_only_their_own_pixels() {
    let (_a, big_ctx, palette) = setup("blit-big");
    let (_b, small_ctx) = canvas("blit-small");
    let cloud = |from: f64, span: f64| {
        let mut rng = labcore::Lcg64::new(3);
        let points: Vec<DVec2> = (0..5_000)
            .map(|_| DVec2::new(from + rng.next_f64() * span, from + rng.next_f64() * span))
            .collect();
        let mut scene = Scene::default();
        scene.push(Item::Points {
            points,
            radius_px: 1.0,
            role: Role::Visited,
        });
        scene
    };
    // Drawn first, before the big cloud grows the blit canvas.
    let (_r, reference_ctx) = canvas("blit-reference");
    let paint_cloud = |ctx: &CanvasRenderingContext2d, scene: &Scene| {
        paint(ctx, scene, &viewport(), W, H, 1.0, &palette);
    };
    paint_cloud(&reference_ctx, &cloud(40.0, 5.0));
    paint_cloud(&big_ctx, &cloud(0.0, 100.0));
    reset_counters();
    paint_cloud(&small_ctx, &cloud(40.0, 5.0));
    assert_eq!(counters().blit_resizes, 0, "{:?}", counters());
    assert!(
        pixels(&small_ctx) == pixels(&reference_ctx),
        "the small cloud after the big one is drawn as before it"
    );
    // The small cloud covers world 40..45 m: pixels 6 px/m from the
    // viewport's left edge, well inside x 300..400 px and y 300..400 px.
    let v = viewport();
    let (lo, hi) = (
        v.to_px(DVec2::new(40.0, 45.0)),
        v.to_px(DVec2::new(45.0, 40.0)),
    );
    let p = pixels(&small_ctx);
    // The canvas is painted with its background first: a corner's pixel.
    let background = &p[0..4];
    let (mut inside, mut outside) = (0, 0);
    for (i, px) in p.chunks(4).enumerate() {
        let (x, y) = ((i % W as usize) as f64, (i / W as usize) as f64);
        let near = x >= lo.x - 2.0 && x <= hi.x + 2.0 && y >= lo.y - 2.0 && y <= hi.y + 2.0;
        if px != background {
            if near {
                inside += 1;
            } else {
                outside += 1;
            }
        }
    }
    assert!(inside > 100, "the small cloud is drawn: {inside} pixels");
    assert_eq!(outside, 0, "pixels lit outside the small cloud's box");
}

/// The dash patterns are built once and handed to every line
/// (`draw::set_dash`): a dashed line after a solid one is dashed again,
/// with the same pattern, and draws the same pixels as the first.
#[wasm_bindgen_test]
fn a_dashed_line_after_a_solid_one_is_dashed_again_with_the_same_pixels() {
    let (_c, ctx, palette) = setup("layers-dash");
    let line = |dashed: bool| {
        let mut scene = Scene::default();
        scene.push(Item::Polyline {
            points: vec![DVec2::new(5.0, 50.0), DVec2::new(95.0, 50.0)],
            width_px: 2.0,
            role: Role::Path,
            dashed,
            closed: false,
        });
        scene
    };
    let dash = |ctx: &CanvasRenderingContext2d| -> Vec<f64> {
        ctx.get_line_dash()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    paint(&ctx, &line(true), &viewport(), W, H, 1.0, &palette);
    assert_eq!(dash(&ctx), labcore::scene::style::DASH_PX.to_vec());
    let first = pixels(&ctx);
    paint(&ctx, &line(false), &viewport(), W, H, 1.0, &palette);
    assert!(dash(&ctx).is_empty());
    let solid = pixels(&ctx);
    assert_ne!(
        first, solid,
        "a solid line lights the gaps of the dashed one"
    );
    paint(&ctx, &line(true), &viewport(), W, H, 1.0, &palette);
    assert_eq!(dash(&ctx), labcore::scene::style::DASH_PX.to_vec());
    assert_eq!(pixels(&ctx), first);
}
