//! An arrow's head, in pixels: the same two strokes on the canvas, in the
//! report's figure and in the thumbnails.

use glam::DVec2;

/// Shafts shorter than this many pixels get no arrow (and no head).
pub const ARROW_MIN_PX: f64 = 0.5;

/// The head of an arrow from pixel `a` to pixel `b` drawn `width_px` wide:
/// `[left, tip, right]`, two strokes from the barbs to the tip `b`. The
/// head is `4 + 2.5 × width_px` pixels long (a thicker shaft needs a bigger
/// head to read), at most half the shaft, and half as wide as long. `None`
/// when the shaft is shorter than [`ARROW_MIN_PX`] or not finite.
#[must_use]
pub fn arrow_head(a: DVec2, b: DVec2, width_px: f64) -> Option<[DVec2; 3]> {
    let d = b - a;
    let len = d.length();
    if !len.is_finite() || len <= ARROW_MIN_PX {
        return None;
    }
    let head = (4.0 + 2.5 * width_px).min(len * 0.5);
    let u = d / len;
    let n = DVec2::new(-u.y, u.x);
    let back = b - u * head;
    Some([back + n * head * 0.5, b, back - n * head * 0.5])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_head_of_a_rightward_arrow() {
        // 100 px long, 2 px wide: the head is 4 + 5 = 9 px long, 4.5 px
        // to each side, its barbs at x = 91.
        let [l, tip, r] = arrow_head(DVec2::ZERO, DVec2::new(100.0, 0.0), 2.0).unwrap();
        assert_eq!(tip, DVec2::new(100.0, 0.0));
        assert_eq!(l, DVec2::new(91.0, 4.5));
        assert_eq!(r, DVec2::new(91.0, -4.5));
    }

    #[test]
    fn a_short_arrow_has_a_head_of_half_its_length() {
        // 6 px long, 2 px wide: 9 px would overrun; 3 px instead.
        let [l, _, r] = arrow_head(DVec2::ZERO, DVec2::new(0.0, 6.0), 2.0).unwrap();
        assert_eq!(l, DVec2::new(-1.5, 3.0));
        assert_eq!(r, DVec2::new(1.5, 3.0));
    }

    #[test]
    fn no_head_for_a_dot_or_a_point_at_infinity() {
        assert_eq!(arrow_head(DVec2::ZERO, DVec2::new(0.3, 0.3), 1.0), None);
        assert_eq!(
            arrow_head(DVec2::ZERO, DVec2::new(f64::NAN, 1.0), 1.0),
            None
        );
        assert_eq!(
            arrow_head(DVec2::ZERO, DVec2::new(f64::INFINITY, 1.0), 1.0),
            None
        );
    }
}
