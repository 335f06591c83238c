//! A path a robot drives along: its points and the arc length up to each,
//! so the path's length is read in O(1) and the point a given distance along
//! it is found in O(log n).
//!
//! The arc length to point `i` is `s_i = Σ_{j<i} |p_{j+1} − p_j|` (summed in
//! order), and the point at distance `d` (`s_i ≤ d < s_{i+1}`) is the linear
//! interpolation `p_i + (p_{i+1} − p_i) · (d − s_i) / (s_{i+1} − s_i)`: the
//! arc-length parametrisation of a polyline (e.g. LaValle, *Planning
//! Algorithms*, 2006, §8.4 on following a path).
//!
//! A* drives its robot along a path of up to a grid's cell count: stepping
//! it by summing the whole path at every step cost a replay of the timeline
//! O(steps × path) (on a 512 × 512 maze, 6 of the 9 ms of an average scrub,
//! unthrottled). RRT* drives the same way.

use glam::DVec2;

/// A polyline with the arc length up to each of its points (see the module).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DrivePath {
    points: Vec<DVec2>,
    /// `arc_m[i]`: the length from the first point to point `i`, m.
    arc_m: Vec<f64>,
}

impl DrivePath {
    /// The heap it holds, bytes (capacities: what a copy of it costs).
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        self.points.capacity() * std::mem::size_of::<DVec2>()
            + self.arc_m.capacity() * std::mem::size_of::<f64>()
    }

    /// The path through `points`, in order.
    #[must_use]
    pub fn new(points: Vec<DVec2>) -> Self {
        let mut arc_m = Vec::with_capacity(points.len());
        let mut length_m = 0.0;
        for (i, p) in points.iter().enumerate() {
            if i > 0 {
                length_m += (*p - points[i - 1]).length();
            }
            arc_m.push(length_m);
        }
        Self { points, arc_m }
    }

    /// Its points, in order.
    #[must_use]
    pub fn points(&self) -> &[DVec2] {
        &self.points
    }

    /// How many points it has.
    #[must_use]
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether it has no points.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Its length, m (0 with fewer than two points).
    #[must_use]
    pub fn length_m(&self) -> f64 {
        self.arc_m.last().copied().unwrap_or(0.0)
    }

    /// The point `distance_m` along it: the first point for a distance of
    /// 0 or less (or NaN), the last at or beyond its length; `None` when it
    /// has no points.
    #[must_use]
    pub fn at(&self, distance_m: f64) -> Option<DVec2> {
        let last = *self.points.last()?;
        if distance_m >= self.length_m() {
            return Some(last);
        }
        // The first point whose arc length is beyond the distance ends the
        // segment it lies on (a segment of zero length is never that one).
        let end = self.arc_m.partition_point(|&s| s <= distance_m);
        if end == 0 {
            return Some(self.points[0]);
        }
        let (a, b) = (self.points[end - 1], self.points[end]);
        let (s0, s1) = (self.arc_m[end - 1], self.arc_m[end]);
        Some(a + (b - a) * ((distance_m - s0) / (s1 - s0)))
    }

    /// Drops every point.
    pub fn clear(&mut self) {
        self.points.clear();
        self.arc_m.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Lcg64;

    /// The walk the experiments did before: subtract each segment's length
    /// until the distance falls inside one.
    fn walked(points: &[DVec2], distance_m: f64) -> Option<DVec2> {
        let mut left = distance_m;
        for w in points.windows(2) {
            let len = (w[1] - w[0]).length();
            if left < len && len > 0.0 {
                return Some(w[0] + (w[1] - w[0]) * (left / len));
            }
            left -= len;
        }
        points.last().copied()
    }

    #[test]
    fn an_l_shaped_path_matches_hand_computed_points() {
        // (0,0) → (3,0) → (3,4): length 3 + 4 = 7 m.
        let path = DrivePath::new(vec![
            DVec2::ZERO,
            DVec2::new(3.0, 0.0),
            DVec2::new(3.0, 4.0),
        ]);
        assert_eq!(path.length_m(), 7.0);
        assert_eq!(path.at(0.0), Some(DVec2::ZERO));
        assert_eq!(path.at(1.5), Some(DVec2::new(1.5, 0.0)));
        assert_eq!(path.at(3.0), Some(DVec2::new(3.0, 0.0)));
        assert_eq!(path.at(5.0), Some(DVec2::new(3.0, 2.0)));
        assert_eq!(path.at(7.0), Some(DVec2::new(3.0, 4.0)));
        assert_eq!(path.at(100.0), Some(DVec2::new(3.0, 4.0)));
        assert_eq!(path.at(-1.0), Some(DVec2::ZERO));
        assert_eq!(path.at(f64::NAN), Some(DVec2::ZERO));
    }

    #[test]
    fn empty_and_single_point_paths() {
        let empty = DrivePath::new(Vec::new());
        assert!(empty.is_empty());
        assert_eq!(empty.length_m(), 0.0);
        assert_eq!(empty.at(1.0), None);
        let one = DrivePath::new(vec![DVec2::new(2.0, 1.0)]);
        assert_eq!(one.length_m(), 0.0);
        assert_eq!(one.at(0.0), Some(DVec2::new(2.0, 1.0)));
        assert_eq!(one.at(0.5), Some(DVec2::new(2.0, 1.0)));
    }

    #[test]
    fn repeated_points_are_skipped() {
        let p = DVec2::new(1.0, 1.0);
        let path = DrivePath::new(vec![DVec2::ZERO, DVec2::ZERO, p, p, DVec2::new(1.0, 3.0)]);
        assert_eq!(path.at(0.0), Some(DVec2::ZERO));
        let half = path.at(0.5 * 2f64.sqrt()).unwrap();
        assert!((half - DVec2::new(0.5, 0.5)).length() < 1e-15);
        let up = path.at(2f64.sqrt() + 1.0).unwrap();
        assert!((up - DVec2::new(1.0, 2.0)).length() < 1e-15);
    }

    /// Property: on random paths (repeated points included), the point at
    /// any distance lies on the path and agrees with walking it segment by
    /// segment within rounding, and the length is the sum of the segments.
    #[test]
    fn agrees_with_walking_the_path_segment_by_segment() {
        let mut rng = Lcg64::new(26);
        for _ in 0..500 {
            let n = rng.int(1, 60) as usize;
            let mut points = Vec::with_capacity(n);
            for _ in 0..n {
                if !points.is_empty() && rng.range(0.0, 1.0) < 0.1 {
                    points.push(*points.last().unwrap());
                } else {
                    points.push(DVec2::new(rng.range(-10.0, 10.0), rng.range(-10.0, 10.0)));
                }
            }
            let path = DrivePath::new(points.clone());
            let summed: f64 = points.windows(2).map(|w| (w[1] - w[0]).length()).sum();
            assert!((path.length_m() - summed).abs() <= 1e-12 * summed.max(1.0));
            for _ in 0..20 {
                let d = rng.range(-1.0, path.length_m() + 1.0);
                let (ours, theirs) = (path.at(d).unwrap(), walked(&points, d.max(0.0)).unwrap());
                assert!(
                    (ours - theirs).length() <= 1e-9,
                    "at {d} of {}: {ours} against {theirs}",
                    path.length_m()
                );
            }
        }
    }
}
