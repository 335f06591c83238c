//! The world → CSS-pixel mapping of a canvas, and segment clipping in pixels.

use glam::DVec2;

/// The world → CSS-pixel mapping of one frame: the map the report's figure
/// and the thumbnails use too.
pub use labcore::layout::map::WorldMap as Viewport;

/// Liang–Barsky clipping of segment `a`–`b` to `[0, max_x] × [0, max_y]`.
pub(crate) fn clip_segment(a: DVec2, b: DVec2, max_x: f64, max_y: f64) -> Option<(DVec2, DVec2)> {
    if !(a.is_finite() && b.is_finite()) {
        return None;
    }
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-d.x, a.x),
        (d.x, max_x - a.x),
        (-d.y, a.y),
        (d.y, max_y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return None;
            }
        }
    }
    Some((a + d * t0, a + d * t1))
}

/// The pixel a point falls in, for [`labcore::bresenham::line`] (rounded
/// to the nearest whole pixel, see [`nearest_px`]).
pub(crate) fn round_px(p: DVec2) -> (i64, i64) {
    (nearest_px(p.x), nearest_px(p.y))
}

/// The nearest whole pixel to `v`, a half rounded up: `⌊v + 0.5⌋`. For the
/// canvas's coordinates (zero or more) this is `f64::round`, but in wasm
/// `round` is a call into the software maths library (no instruction rounds
/// halves away from zero), where `floor` is one instruction. The pixel loops
/// round every endpoint and dot: a scrub frame of RRT* rounds about 12,000
/// times, the workspace sweep 10,000.
#[inline]
pub(crate) fn nearest_px(v: f64) -> i64 {
    (v + 0.5).floor() as i64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_keeps_inside_parts_only() {
        let c =
            |a: (f64, f64), b: (f64, f64)| clip_segment(DVec2::from(a), DVec2::from(b), 10.0, 10.0);
        assert_eq!(
            c((1.0, 1.0), (5.0, 5.0)),
            Some((DVec2::new(1.0, 1.0), DVec2::new(5.0, 5.0)))
        );
        assert_eq!(
            c((-10.0, 5.0), (20.0, 5.0)),
            Some((DVec2::new(0.0, 5.0), DVec2::new(10.0, 5.0)))
        );
        assert_eq!(c((-5.0, -5.0), (-1.0, 20.0)), None);
        assert_eq!(c((f64::NAN, 0.0), (1.0, 1.0)), None);
        // A far-away endpoint is clipped, not walked pixel by pixel.
        let (a, b) = c((5.0, 5.0), (1e300, 5.0)).expect("crosses the canvas");
        assert_eq!((a.x, b.x), (5.0, 10.0));
    }

    /// From 0 up, the nearest pixel is `f64::round`'s, halves included.
    #[test]
    fn the_nearest_pixel_is_f64_round_for_canvas_coordinates() {
        for i in 0..40_000u32 {
            let v = f64::from(i) * 0.125 + [0.0, 1e-9, -1e-9][i as usize % 3];
            let v = v.max(0.0);
            assert_eq!(nearest_px(v), v.round() as i64, "{v}");
        }
        assert_eq!(round_px(DVec2::new(2.5, 3.49)), (3, 3));
        assert_eq!(nearest_px(1e300), i64::MAX, "saturates like `round`");
        assert_eq!(nearest_px(f64::NAN), 0);
    }
}
