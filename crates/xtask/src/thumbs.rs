//! Build-time pictures for the home page's cards: an experiment's preview
//! display list written as a small inline SVG, so the home page shows every
//! experiment without downloading the simulation engine. Colours are the
//! page's theme variables, so the pictures follow light and dark mode: each
//! shape has a role class (`class="c-link"`, whose rule in `web/style.css`
//! sets `color: var(--c-link)`) and paints with `currentColor`. No `style="…"`
//! attribute: the Content-Security-Policy (`style-src 'self'`) forbids them,
//! and presentation attributes cannot hold `var(…)`.

use labcore::glam::DVec2;
use labcore::layout::arrow::arrow_head;
use labcore::layout::map::WorldMap;
use labcore::{Item, Role, Scene, ViewBox};
use std::fmt::Write;

/// Thumbnail size in CSS pixels (the card picture is 3:2).
const W: f64 = 240.0;
const H: f64 = 160.0;
/// Most points of a sample cloud drawn (the rest add bytes, not insight).
const POINTS_MAX: usize = 500;
/// Most segments of a batch drawn.
const SEGMENTS_MAX: usize = 1500;

/// The role's class (the style table's); `web/style.css` gives
/// `.c-<role>` the colour `var(--c-<role>)`.
fn class(role: Role) -> &'static str {
    role.style().class()
}

/// A single arrow's stroke in a thumbnail, pixels.
const THUMB_STROKE_PX: f64 = 1.5;

/// World → thumbnail pixels (uniform fit, y up): the canvas's map.
struct Map(WorldMap);

impl Map {
    fn new(view: ViewBox) -> Self {
        Self(WorldMap::fit(view, W, H))
    }

    fn px(&self, p: DVec2) -> (f64, f64) {
        let p = self.0.to_px(p);
        (p.x, p.y)
    }
}

fn points_attr(map: &Map, points: &[DVec2]) -> String {
    points
        .iter()
        .map(|p| {
            let (x, y) = map.px(*p);
            format!("{x:.1},{y:.1}")
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The SVG of one display list.
#[must_use]
pub fn svg(scene: &Scene, view: ViewBox) -> String {
    let map = Map::new(view);
    let mut out = format!(
        "<svg viewBox=\"0 0 {W} {H}\" width=\"100%\" height=\"100%\" role=\"img\" aria-hidden=\"true\" \
         class=\"thumb\" stroke-linecap=\"round\" stroke-linejoin=\"round\">"
    );
    for item in &scene.items {
        // A kept layer of segments is drawn like a plain batch.
        let layer_as_batch;
        let item = match item {
            Item::SegmentLayer {
                layer,
                width_px,
                role,
            } => {
                layer_as_batch = Item::Segments {
                    segments: layer.segments().to_vec(),
                    width_px: *width_px,
                    role: *role,
                };
                &layer_as_batch
            }
            other => other,
        };
        let _ = item_svg(&mut out, &map, item);
    }
    out.push_str("</svg>");
    out
}

/// One item of the display list, by its kind.
fn item_svg(out: &mut String, map: &Map, item: &Item) -> std::fmt::Result {
    match item {
        Item::Line { .. } | Item::Circle { .. } | Item::Dot { .. } | Item::Ellipse { .. } => {
            shape_svg(out, map, item)
        }
        Item::Points { .. }
        | Item::Polyline { .. }
        | Item::Polygon { .. }
        | Item::Rect { .. }
        | Item::Arrow { .. }
        | Item::Arrows { .. }
        | Item::Segments { .. } => path_svg(out, map, item),
        // Cell images and text are left to the live canvas.
        Item::Heatmap { .. }
        | Item::Raster { .. }
        | Item::VersionedRaster { .. }
        | Item::SegmentLayer { .. }
        | Item::Label { .. }
        | Item::ScaleBar
        | Item::OffView { .. }
        | Item::FocusRing { .. } => Ok(()),
    }
}

/// Lines, circles, dots and ellipses.
fn shape_svg(out: &mut String, map: &Map, item: &Item) -> std::fmt::Result {
    match item {
        Item::Line {
            from,
            to,
            width_px,
            role,
            dashed,
        } => {
            let ((x1, y1), (x2, y2)) = (map.px(*from), map.px(*to));
            write!(
                out,
                "<line x1=\"{x1:.1}\" y1=\"{y1:.1}\" x2=\"{x2:.1}\" y2=\"{y2:.1}\" class=\"{}\" stroke=\"currentColor\" stroke-width=\"{:.1}\"{}/>",
                class(*role),
                (width_px * 0.6).max(0.8),
                if *dashed { " stroke-dasharray=\"4 3\"" } else { "" }
            )
        }
        Item::Circle {
            center,
            radius_m,
            role,
            fill,
            dashed,
        } => {
            let (x, y) = map.px(*center);
            let paint = if *fill {
                "fill=\"currentColor\" fill-opacity=\".18\""
            } else {
                "fill=\"none\" stroke=\"currentColor\""
            };
            write!(
                out,
                "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"{:.1}\" class=\"{}\" {paint}{}/>",
                radius_m * map.0.scale_px_per_m,
                class(*role),
                if *dashed {
                    " stroke-dasharray=\"4 3\""
                } else {
                    ""
                }
            )
        }
        Item::Dot {
            center,
            radius_px,
            role,
        } => {
            let (x, y) = map.px(*center);
            write!(
                out,
                "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"{:.1}\" class=\"{}\" fill=\"currentColor\"/>",
                radius_px * 0.6,
                class(*role)
            )
        }
        Item::Ellipse {
            center,
            semi_axis_a,
            semi_axis_b,
            role,
        } => {
            let (x, y) = map.px(*center);
            let angle = -semi_axis_a.y.atan2(semi_axis_a.x).to_degrees();
            write!(
                out,
                "<ellipse cx=\"{x:.1}\" cy=\"{y:.1}\" rx=\"{:.1}\" ry=\"{:.1}\" transform=\"rotate({angle:.1} {x:.1} {y:.1})\" \
                 class=\"{c}\" fill=\"currentColor\" fill-opacity=\".18\" stroke=\"currentColor\"/>",
                semi_axis_a.length() * map.0.scale_px_per_m,
                semi_axis_b.length() * map.0.scale_px_per_m,
                c = class(*role)
            )
        }
        _ => Ok(()),
    }
}

/// Point clouds, polylines, polygons, rectangles, arrows and segment batches.
fn path_svg(out: &mut String, map: &Map, item: &Item) -> std::fmt::Result {
    match item {
        Item::Points { points, role, .. } => {
            let stride = points.len().div_ceil(POINTS_MAX).max(1);
            let mut d = String::new();
            for p in points.iter().step_by(stride) {
                let (x, y) = map.px(*p);
                let _ = write!(d, "M{x:.0} {y:.0}h1");
            }
            write!(
                out,
                "<path d=\"{d}\" class=\"{}\" stroke=\"currentColor\" stroke-opacity=\".6\" stroke-width=\"1.5\"/>",
                class(*role)
            )
        }
        Item::Polyline {
            points,
            role,
            dashed,
            closed,
            ..
        } => write!(
            out,
            "<{tag} points=\"{}\" class=\"{}\" fill=\"none\" stroke=\"currentColor\"{}/>",
            points_attr(map, points),
            class(*role),
            if *dashed {
                " stroke-dasharray=\"4 3\""
            } else {
                ""
            },
            tag = if *closed { "polygon" } else { "polyline" }
        ),
        Item::Polygon { points, role } => write!(
            out,
            "<polygon points=\"{}\" class=\"{}\" fill=\"currentColor\" fill-opacity=\".35\" stroke=\"currentColor\"/>",
            points_attr(map, points),
            class(*role)
        ),
        Item::Rect {
            min,
            max,
            role,
            fill,
        } => {
            let ((x1, y1), (x2, y2)) = (map.px(*min), map.px(*max));
            write!(
                out,
                "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" class=\"{}\" fill=\"{}\" stroke=\"currentColor\"/>",
                x1.min(x2),
                y1.min(y2),
                (x2 - x1).abs(),
                (y2 - y1).abs(),
                class(*role),
                if *fill { "currentColor" } else { "none" }
            )
        }
        // A shaft and the canvas's head, at the thumbnail's stroke width.
        Item::Arrow { from, to, role, .. } => {
            let (a, b) = (map.0.to_px(*from), map.0.to_px(*to));
            let Some([l, tip, r]) = arrow_head(a, b, THUMB_STROKE_PX) else {
                return Ok(());
            };
            write!(
                out,
                "<path d=\"M{:.1} {:.1}L{:.1} {:.1}M{:.1} {:.1}L{:.1} {:.1}L{:.1} {:.1}\" class=\"{}\" fill=\"none\" stroke=\"currentColor\" stroke-width=\"{THUMB_STROKE_PX}\"/>",
                a.x, a.y, tip.x, tip.y, l.x, l.y, tip.x, tip.y, r.x, r.y,
                class(*role)
            )
        }
        Item::Arrows {
            arrows: pairs,
            role,
            ..
        }
        | Item::Segments {
            segments: pairs,
            role,
            ..
        } => {
            let stride = pairs.len().div_ceil(SEGMENTS_MAX).max(1);
            let mut d = String::new();
            for (a, b) in pairs.iter().step_by(stride) {
                let ((x1, y1), (x2, y2)) = (map.px(*a), map.px(*b));
                let _ = write!(d, "M{x1:.0} {y1:.0}L{x2:.0} {y2:.0}");
            }
            write!(
                out,
                "<path d=\"{d}\" class=\"{}\" stroke=\"currentColor\" stroke-width=\".7\"/>",
                class(*role)
            )
        }
        _ => Ok(()),
    }
}

/// The card picture of a registered experiment: its preview state as SVG.
#[must_use]
pub fn thumbnail(id: &str) -> String {
    let Some(entry) = labcore::find(id) else {
        return String::new();
    };
    let mut exp = (entry.make)();
    exp.preview();
    let mut scene = Scene::default();
    exp.scene(&mut scene);
    svg(&scene, exp.view())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_experiment_has_a_small_well_formed_picture() {
        for entry in labcore::registry() {
            let s = thumbnail(entry.id);
            assert!(
                s.starts_with("<svg") && s.ends_with("</svg>"),
                "{}",
                entry.id
            );
            assert!(!s.contains("NaN") && !s.contains("inf"), "{}", entry.id);
            assert!(s.len() < 40_000, "{}: {} bytes", entry.id, s.len());
            assert!(!s.contains("style="), "{}: no style attribute", entry.id);
        }
    }

    #[test]
    fn every_role_class_has_its_colour_rule_in_the_stylesheet() {
        let css = std::fs::read_to_string(crate::util::root().join("web/style.css")).unwrap();
        assert!(
            css.contains(".thumb {") || css.contains(".thumb{"),
            "svg.thumb background"
        );
        for role in Role::ALL.iter().copied() {
            let c = class(role);
            let rule = format!(".{c} {{ color: var(--{c}); }}");
            assert!(css.contains(&rule), "web/style.css lacks `{rule}`");
        }
    }

    #[test]
    fn world_points_map_like_the_canvas() {
        let map = Map::new(ViewBox::centered(1.0));
        assert_eq!(map.px(DVec2::ZERO), (W / 2.0, H / 2.0));
        // y up in the world is up on screen; the scale fits the height.
        assert_eq!(map.px(DVec2::new(0.0, 1.0)), (W / 2.0, 0.0));
    }

    /// A single arrow has the canvas's head: world (−1, 0) → (0, 0) in the
    /// ±1 m view is 80 px long (80 px/m, the height fits), at 1.5 px the
    /// head is 4 + 3.75 = 7.75 px long, barbs 3.875 px either side.
    #[test]
    fn an_arrow_has_the_canvas_head() {
        let mut scene = Scene::default();
        scene.push(Item::Arrow {
            from: DVec2::new(-1.0, 0.0),
            to: DVec2::ZERO,
            width_px: 3.0,
            role: Role::Link,
        });
        let svg = svg(&scene, ViewBox::centered(1.0));
        assert!(
            svg.contains("d=\"M40.0 80.0L120.0 80.0M112.2 83.9L120.0 80.0L112.2 76.1\""),
            "{svg}"
        );
    }
}
