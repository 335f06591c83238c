//! Drawing pieces shared by the wheeled-robot experiments (diffdrive,
//! potential): a differential-drive robot and the metre grid of its field.
//! World coordinates in metres, y up, like the rest of the display list.

use super::{Item, Role, Scene};
use crate::mobile::unicycle::Pose;
use glam::DVec2;

/// Drawn body radius of a wheeled robot, metres.
pub const BODY_RADIUS_M: f64 = 0.18;
/// The nose line runs from the centre to this many body radii ahead.
pub const NOSE_REACH: f64 = 1.35;
/// Corners of the round body's polygon.
const BODY_CORNERS: u32 = 20;
/// A wheel is drawn `2 × 0.09 m` long and `2 × 0.025 m` wide.
const WHEEL_HALF_LENGTH_M: f64 = 0.09;
const WHEEL_HALF_WIDTH_M: f64 = 0.025;
/// The nose line's width, CSS px.
const NOSE_WIDTH_PX: f64 = 3.0;

/// Draws a differential-drive robot at `pose`: a round body of
/// [`BODY_RADIUS_M`] (a 20-gon whose first corner lies on the heading), two
/// wheels `track_m` apart (clamped to 0.05–1 m) and a nose line showing the
/// heading. A pose with a non-finite number draws nothing.
pub fn draw_robot(out: &mut Scene, pose: Pose, track_m: f64) {
    if !pose.is_finite() {
        return;
    }
    let c = pose.position();
    let f = pose.heading();
    let left = f.perp();
    let body: Vec<DVec2> = (0..BODY_CORNERS)
        .map(|i| {
            let a =
                pose.theta_rad + core::f64::consts::TAU * f64::from(i) / f64::from(BODY_CORNERS);
            let (s, co) = crate::math::sin_cos(a);
            c + DVec2::new(co, s) * BODY_RADIUS_M
        })
        .collect();
    out.push(Item::Polygon {
        points: body,
        role: Role::Robot,
    });
    let half = 0.5 * track_m.clamp(0.05, 1.0);
    for side in [1.0, -1.0] {
        let w = c + left * side * half;
        let (along, across) = (f * WHEEL_HALF_LENGTH_M, left * WHEEL_HALF_WIDTH_M);
        out.push(Item::Polygon {
            points: vec![
                w - along - across,
                w + along - across,
                w + along + across,
                w - along + across,
            ],
            role: Role::Base,
        });
    }
    out.push(Item::Line {
        from: c,
        to: c + f * BODY_RADIUS_M * NOSE_REACH,
        width_px: NOSE_WIDTH_PX,
        role: Role::Base,
        dashed: false,
    });
}

/// A light 1 m grid over `[0, w_m] × [0, h_m]` as one batch of segments:
/// the vertical lines `x = 0, 1, …` first, then the horizontal ones.
pub fn draw_field(out: &mut Scene, w_m: f64, h_m: f64) {
    let mut segments = Vec::new();
    let mut x = 0.0;
    while x <= w_m + 1e-9 {
        segments.push((DVec2::new(x, 0.0), DVec2::new(x, h_m)));
        x += 1.0;
    }
    let mut y = 0.0;
    while y <= h_m + 1e-9 {
        segments.push((DVec2::new(0.0, y), DVec2::new(w_m, y)));
        y += 1.0;
    }
    out.push(Item::Segments {
        segments,
        width_px: 1.0,
        role: Role::Grid,
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DVec2, b: DVec2) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn a_robot_facing_plus_y_has_its_body_nose_and_wheels_where_hand_placed() {
        // At (1, 2) facing +y (θ = 90°): the nose runs 0.18 × 1.35 = 0.243 m
        // up; with a 0.3 m track the left wheel centre is 0.15 m to the left
        // (−x), the right one 0.15 m to the right.
        let mut s = Scene::default();
        draw_robot(
            &mut s,
            Pose::new(1.0, 2.0, core::f64::consts::FRAC_PI_2),
            0.3,
        );
        assert_eq!(s.items.len(), 4, "body, two wheels, nose");
        let Item::Polygon { points, role } = &s.items[0] else {
            panic!("body first: {:?}", s.items[0]);
        };
        assert_eq!(*role, Role::Robot);
        assert_eq!(points.len(), 20);
        assert!(close(points[0], DVec2::new(1.0, 2.18)), "{:?}", points[0]);
        // A quarter turn on (corner 5) points to −x.
        assert!(close(points[5], DVec2::new(0.82, 2.0)), "{:?}", points[5]);
        assert!(points
            .iter()
            .all(|p| ((*p - DVec2::new(1.0, 2.0)).length() - 0.18).abs() < 1e-12));
        let Item::Polygon { points: left, .. } = &s.items[1] else {
            panic!("left wheel: {:?}", s.items[1]);
        };
        // Centre (0.85, 2): along = (0, 0.09), across = (−0.025, 0).
        let want = [
            DVec2::new(0.875, 1.91),
            DVec2::new(0.875, 2.09),
            DVec2::new(0.825, 2.09),
            DVec2::new(0.825, 1.91),
        ];
        for (p, w) in left.iter().zip(want) {
            assert!(close(*p, w), "{p:?} vs {w:?}");
        }
        let Item::Polygon { points: right, .. } = &s.items[2] else {
            panic!("right wheel: {:?}", s.items[2]);
        };
        assert!(close(right[0], DVec2::new(1.175, 1.91)), "{:?}", right[0]);
        let Item::Line {
            from, to, width_px, ..
        } = &s.items[3]
        else {
            panic!("nose: {:?}", s.items[3]);
        };
        assert!(close(*from, DVec2::new(1.0, 2.0)));
        assert!(close(*to, DVec2::new(1.0, 2.243)), "{to:?}");
        assert_eq!(*width_px, 3.0);
    }

    #[test]
    fn a_robot_track_is_clamped_and_a_broken_pose_draws_nothing() {
        let mut s = Scene::default();
        draw_robot(&mut s, Pose::new(0.0, 0.0, 0.0), 5.0);
        // Track clamped to 1 m: the left wheel's centre is at (0, 0.5), so
        // its first corner is (−0.09, 0.475).
        let Item::Polygon { points, .. } = &s.items[1] else {
            panic!("left wheel: {:?}", s.items[1]);
        };
        assert!(
            close(points[0], DVec2::new(-0.09, 0.475)),
            "{:?}",
            points[0]
        );
        let mut broken = Scene::default();
        draw_robot(&mut broken, Pose::new(f64::NAN, 0.0, 0.0), 0.3);
        assert!(broken.items.is_empty());
    }

    #[test]
    fn an_8_by_6_field_has_9_vertical_and_7_horizontal_grid_lines() {
        let mut s = Scene::default();
        draw_field(&mut s, 8.0, 6.0);
        let [Item::Segments {
            segments,
            width_px,
            role,
        }] = s.items.as_slice()
        else {
            panic!("one batch: {:?}", s.items);
        };
        assert_eq!((*width_px, *role), (1.0, Role::Grid));
        assert_eq!(segments.len(), 9 + 7);
        assert_eq!(segments[0], (DVec2::new(0.0, 0.0), DVec2::new(0.0, 6.0)));
        assert_eq!(segments[8], (DVec2::new(8.0, 0.0), DVec2::new(8.0, 6.0)));
        assert_eq!(segments[9], (DVec2::new(0.0, 0.0), DVec2::new(8.0, 0.0)));
        assert_eq!(segments[15], (DVec2::new(0.0, 6.0), DVec2::new(8.0, 6.0)));
    }
}
