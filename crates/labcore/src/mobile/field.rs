//! The rectangular field `[0, w] × [0, h]` (metres) a wheeled robot drives
//! on: clicked points snapped into it, and the robot's bounded trail.
//! Shared by the wheeled-robot experiments (diffdrive, potential).

use glam::DVec2;

/// The trail keeps at most this many points (older ones are dropped).
pub const MAX_TRAIL_POINTS: usize = 6000;
/// A trail point closer than this to the last one is not kept, metres.
const TRAIL_STEP_M: f64 = 0.005;

/// Rounds a coordinate to whole centimetres (metres in and out), so a link
/// shows short numbers (it reproduces any value exactly).
#[must_use]
pub fn snap_cm(v_m: f64) -> f64 {
    (v_m * 100.0).round() / 100.0
}

/// A clicked point clamped into `[0, w_m] × [0, h_m]` and snapped to
/// centimetres.
#[must_use]
pub fn snap_into(p: DVec2, w_m: f64, h_m: f64) -> DVec2 {
    DVec2::new(snap_cm(p.x.clamp(0.0, w_m)), snap_cm(p.y.clamp(0.0, h_m)))
}

/// Appends `p` to a trail unless it is not finite or within 5 mm of the
/// last point; past [`MAX_TRAIL_POINTS`] the oldest quarter is dropped.
pub fn push_trail(trail: &mut Vec<DVec2>, p: DVec2) {
    if !p.is_finite()
        || trail
            .last()
            .is_some_and(|q| (*q - p).length() < TRAIL_STEP_M)
    {
        return;
    }
    trail.push(p);
    if trail.len() > MAX_TRAIL_POINTS {
        trail.drain(..MAX_TRAIL_POINTS / 4);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_click_is_clamped_into_the_field_and_rounded_to_centimetres() {
        assert_eq!(snap_cm(1.234_9), 1.23);
        assert_eq!(snap_cm(1.235_1), 1.24);
        assert_eq!(
            snap_into(DVec2::new(2.716, 3.152), 8.0, 6.0),
            DVec2::new(2.72, 3.15)
        );
        assert_eq!(
            snap_into(DVec2::new(-0.4, 9.0), 8.0, 6.0),
            DVec2::new(0.0, 6.0)
        );
        assert_eq!(
            snap_into(DVec2::new(8.004, 0.004), 8.0, 6.0),
            DVec2::new(8.0, 0.0)
        );
    }

    #[test]
    fn a_trail_skips_steps_under_5_mm_and_non_finite_points() {
        let mut trail = Vec::new();
        push_trail(&mut trail, DVec2::new(1.0, 1.0));
        push_trail(&mut trail, DVec2::new(1.006, 1.008)); // 10 mm: kept
        push_trail(&mut trail, DVec2::new(1.009, 1.008)); // 3 mm: skipped
        push_trail(&mut trail, DVec2::new(f64::NAN, 1.0));
        push_trail(&mut trail, DVec2::new(1.0, f64::INFINITY));
        assert_eq!(trail, [DVec2::new(1.0, 1.0), DVec2::new(1.006, 1.008)]);
    }

    #[test]
    fn a_trail_past_6000_points_drops_the_oldest_1500() {
        let mut trail = Vec::new();
        for k in 0..6001 {
            push_trail(&mut trail, DVec2::new(0.01 * f64::from(k), 0.0));
        }
        assert_eq!(trail.len(), 4501);
        assert_eq!(trail[0], DVec2::new(0.01 * 1500.0, 0.0));
    }
}
