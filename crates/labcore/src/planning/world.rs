//! A continuous 2-D world for sampling-based planners: a rectangular region
//! with circle and axis-aligned rectangle obstacles, and collision checks.
//!
//! A point is in collision when it lies outside the bounds or inside (or on
//! the boundary of) any obstacle. A segment is checked at a fixed resolution,
//! the usual discrete motion check of sampling-based planners (LaValle,
//! *Planning Algorithms*, Cambridge 2006, §5.3.4): with `n = ⌈|b − a| / δ⌉`,
//! the `n + 1` points `a + (b − a) · i/n`, `i = 0 … n`, spaced at most `δ`
//! apart, must all be free. A segment can therefore clip an obstacle between
//! two check points by at most the sagitta `r − √(r² − δ²/4)` of a circle of
//! radius `r` (about 0.01 for `r = 3`, `δ = 0.5`). The check is symmetric: the
//! endpoints are put in a fixed order first, so `a → b` and `b → a` test
//! exactly the same points.
//!
//! Obstacles are binned once on a uniform grid over the bounds, so a point
//! test only looks at the few obstacles whose bounding box overlaps the
//! point's bin.

use glam::DVec2;
use std::fmt;

/// Bins per side of the obstacle index.
const OBSTACLE_BINS: usize = 32;
/// A segment is never split into more check points than this (guards against
/// a tiny resolution on a huge segment).
pub const MAX_CHECKS_PER_SEGMENT: usize = 1 << 20;

/// An obstacle; boundaries count as inside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Obstacle {
    /// A disc.
    Circle { center: DVec2, radius: f64 },
    /// An axis-aligned rectangle, `min ≤ max` component-wise.
    Rect { min: DVec2, max: DVec2 },
}

impl Obstacle {
    /// A rectangle from any two opposite corners.
    #[must_use]
    pub fn rect(a: DVec2, b: DVec2) -> Self {
        Obstacle::Rect {
            min: a.min(b),
            max: a.max(b),
        }
    }

    /// Whether `p` is inside or on the boundary.
    ///
    /// # Example
    /// ```
    /// use glam::DVec2;
    /// use labcore::planning::world::Obstacle;
    /// let c = Obstacle::Circle { center: DVec2::new(1.0, 1.0), radius: 1.0 };
    /// assert!(c.contains(DVec2::new(2.0, 1.0)) && !c.contains(DVec2::new(2.0, 2.0)));
    /// let r = Obstacle::rect(DVec2::new(3.0, 0.0), DVec2::new(0.0, 1.0));
    /// assert!(r.contains(DVec2::new(3.0, 0.5)) && !r.contains(DVec2::new(1.0, 1.5)));
    /// ```
    #[inline]
    #[must_use]
    pub fn contains(&self, p: DVec2) -> bool {
        match *self {
            Obstacle::Circle { center, radius } => (p - center).length_squared() <= radius * radius,
            Obstacle::Rect { min, max } => {
                p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y
            }
        }
    }

    /// Bounding box `(min, max)`.
    #[must_use]
    pub fn aabb(&self) -> (DVec2, DVec2) {
        match *self {
            Obstacle::Circle { center, radius } => (center - radius, center + radius),
            Obstacle::Rect { min, max } => (min, max),
        }
    }

    fn is_valid(&self) -> bool {
        match *self {
            Obstacle::Circle { center, radius } => {
                center.is_finite() && radius.is_finite() && radius >= 0.0
            }
            Obstacle::Rect { min, max } => {
                min.is_finite() && max.is_finite() && min.x <= max.x && min.y <= max.y
            }
        }
    }
}

/// Why a world could not be made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WorldError {
    /// Bounds not finite or not `min < max` in both axes.
    InvalidBounds,
    /// Obstacle `index` has a NaN or infinite value, a negative radius, or `min > max`.
    InvalidObstacle { index: usize },
}

impl fmt::Display for WorldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidBounds => write!(f, "the world bounds must be finite with min < max"),
            Self::InvalidObstacle { index } => write!(f, "obstacle {index} is not valid"),
        }
    }
}

impl std::error::Error for WorldError {}

/// The bounds, the obstacles and an index over them.
#[derive(Clone, Debug, PartialEq)]
pub struct World {
    min: DVec2,
    max: DVec2,
    obstacles: Vec<Obstacle>,
    /// Bin size, world units.
    bin: DVec2,
    /// CSR index: obstacles of bin `k` are `bin_items[bin_start[k]..bin_start[k + 1]]`.
    bin_start: Vec<u32>,
    bin_items: Vec<u32>,
}

impl World {
    /// The heap it holds, bytes (capacities: what a copy of it costs).
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of;
        self.obstacles.capacity() * size_of::<Obstacle>()
            + (self.bin_start.capacity() + self.bin_items.capacity()) * size_of::<u32>()
    }

    /// A world `[min.x, max.x] × [min.y, max.y]` with `obstacles`.
    ///
    /// # Errors
    /// [`WorldError`] for non-finite or empty bounds, or an invalid obstacle.
    ///
    /// # Example
    /// ```
    /// use glam::DVec2;
    /// use labcore::planning::world::{Obstacle, World};
    /// let w = World::new(
    ///     DVec2::ZERO,
    ///     DVec2::splat(10.0),
    ///     vec![Obstacle::Circle { center: DVec2::splat(5.0), radius: 2.0 }],
    /// ).unwrap();
    /// assert!(w.point_free(DVec2::new(1.0, 1.0)));
    /// assert!(!w.point_free(DVec2::new(5.0, 6.0)));
    /// assert!(!w.point_free(DVec2::new(-0.1, 1.0))); // outside the bounds
    /// assert!(!w.segment_free(DVec2::new(1.0, 5.0), DVec2::new(9.0, 5.0), 0.5));
    /// assert!(w.segment_free(DVec2::new(1.0, 1.0), DVec2::new(9.0, 1.0), 0.5));
    /// ```
    pub fn new(min: DVec2, max: DVec2, obstacles: Vec<Obstacle>) -> Result<Self, WorldError> {
        if !(min.is_finite() && max.is_finite() && min.x < max.x && min.y < max.y) {
            return Err(WorldError::InvalidBounds);
        }
        if let Some(index) = obstacles.iter().position(|o| !o.is_valid()) {
            return Err(WorldError::InvalidObstacle { index });
        }
        let bin = (max - min) / OBSTACLE_BINS as f64;
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); OBSTACLE_BINS * OBSTACLE_BINS];
        for (k, o) in obstacles.iter().enumerate() {
            let (lo, hi) = o.aabb();
            let (x0, y0) = Self::bin_of_raw(min, bin, lo);
            let (x1, y1) = Self::bin_of_raw(min, bin, hi);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    lists[y * OBSTACLE_BINS + x].push(k as u32);
                }
            }
        }
        let mut bin_start = Vec::with_capacity(lists.len() + 1);
        let mut bin_items = Vec::new();
        bin_start.push(0);
        for l in &lists {
            bin_items.extend_from_slice(l);
            bin_start.push(bin_items.len() as u32);
        }
        Ok(Self {
            min,
            max,
            obstacles,
            bin,
            bin_start,
            bin_items,
        })
    }

    /// Bin of `p`, clamped to the grid (so obstacles reaching outside the
    /// bounds are filed in the border bins).
    #[inline]
    fn bin_of_raw(min: DVec2, bin: DVec2, p: DVec2) -> (usize, usize) {
        let last = (OBSTACLE_BINS - 1) as f64;
        // For x ≥ 0, `x as usize` is ⌊x⌋; NaN and negatives become 0.
        let fx = ((p.x - min.x) / bin.x).clamp(0.0, last);
        let fy = ((p.y - min.y) / bin.y).clamp(0.0, last);
        (fx as usize, fy as usize)
    }

    /// Lower corner of the bounds.
    #[must_use]
    pub fn min(&self) -> DVec2 {
        self.min
    }

    /// Upper corner of the bounds.
    #[must_use]
    pub fn max(&self) -> DVec2 {
        self.max
    }

    /// Area of the bounds, `μ(X)` (obstacles included).
    #[must_use]
    pub fn area(&self) -> f64 {
        let d = self.max - self.min;
        d.x * d.y
    }

    #[must_use]
    pub fn obstacles(&self) -> &[Obstacle] {
        &self.obstacles
    }

    /// Whether `p` is inside the bounds (boundary included).
    #[inline]
    #[must_use]
    pub fn in_bounds(&self, p: DVec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    /// Whether `p` is inside the bounds and outside every obstacle.
    #[inline]
    #[must_use]
    pub fn point_free(&self, p: DVec2) -> bool {
        if !self.in_bounds(p) {
            return false;
        }
        let (x, y) = Self::bin_of_raw(self.min, self.bin, p);
        let k = y * OBSTACLE_BINS + x;
        let (a, b) = (self.bin_start[k] as usize, self.bin_start[k + 1] as usize);
        !self.bin_items[a..b]
            .iter()
            .any(|&o| self.obstacles[o as usize].contains(p))
    }

    /// Whether the segment `a–b` is free when checked every `resolution` units
    /// (module docs). A resolution that is not a positive number checks the
    /// two endpoints only.
    #[must_use]
    pub fn segment_free(&self, a: DVec2, b: DVec2, resolution: f64) -> bool {
        // A fixed order of the endpoints makes the check symmetric.
        let (a, b) = if (a.x, a.y) <= (b.x, b.y) {
            (a, b)
        } else {
            (b, a)
        };
        let d = b - a;
        let len = d.length();
        let n = if resolution > 0.0 && len.is_finite() {
            ((len / resolution).ceil() as usize).clamp(1, MAX_CHECKS_PER_SEGMENT)
        } else {
            1
        };
        if !self.point_free(b) {
            return false;
        }
        let inv = 1.0 / n as f64;
        (0..n).all(|i| self.point_free(a + d * (i as f64 * inv)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn world() -> World {
        World::new(
            DVec2::ZERO,
            DVec2::splat(100.0),
            vec![
                Obstacle::Circle {
                    center: DVec2::new(50.0, 50.0),
                    radius: 10.0,
                },
                Obstacle::rect(DVec2::new(10.0, 70.0), DVec2::new(30.0, 80.0)),
                // Reaches outside the bounds.
                Obstacle::Circle {
                    center: DVec2::new(100.0, 0.0),
                    radius: 5.0,
                },
            ],
        )
        .unwrap()
    }

    #[test]
    fn point_tests_match_a_linear_scan() {
        let w = world();
        let mut rng = crate::rng::Lcg64::new(3);
        for _ in 0..20_000 {
            let p = DVec2::new(rng.range(-5.0, 105.0), rng.range(-5.0, 105.0));
            let expected = w.in_bounds(p) && !w.obstacles().iter().any(|o| o.contains(p));
            assert_eq!(w.point_free(p), expected, "{p}");
        }
    }

    #[test]
    fn segments_are_checked_at_the_resolution_and_symmetrically() {
        let w = world();
        let (a, b) = (DVec2::new(35.0, 50.0), DVec2::new(65.0, 50.0));
        assert!(!w.segment_free(a, b, 0.5));
        assert!(!w.segment_free(b, a, 0.5));
        // The same segment with a resolution coarser than the circle is missed
        // (only the endpoints are checked) — the documented discrete check.
        assert!(w.segment_free(a, b, 100.0));
        assert!(w.segment_free(DVec2::new(1.0, 1.0), DVec2::new(1.0, 99.0), 0.5));
        // An endpoint in collision.
        assert!(!w.segment_free(DVec2::new(1.0, 1.0), DVec2::new(50.0, 50.0), 0.5));
        assert!(!w.segment_free(DVec2::new(1.0, 1.0), DVec2::new(101.0, 1.0), 0.5));
        // Bad resolutions do not hang or panic.
        for r in [0.0, -1.0, f64::NAN, 1e-300] {
            let _ = w.segment_free(DVec2::new(1.0, 1.0), DVec2::new(1.0, 99.0), r);
        }
        let mut rng = crate::rng::Lcg64::new(11);
        for _ in 0..2000 {
            let p = DVec2::new(rng.range(0.0, 100.0), rng.range(0.0, 100.0));
            let q = p + DVec2::new(rng.range(-8.0, 8.0), rng.range(-8.0, 8.0));
            assert_eq!(w.segment_free(p, q, 0.5), w.segment_free(q, p, 0.5));
        }
    }

    #[test]
    fn invalid_worlds_are_errors() {
        assert_eq!(
            World::new(DVec2::ZERO, DVec2::new(0.0, 1.0), vec![]),
            Err(WorldError::InvalidBounds)
        );
        assert_eq!(
            World::new(DVec2::ZERO, DVec2::new(f64::NAN, 1.0), vec![]),
            Err(WorldError::InvalidBounds)
        );
        let bad = Obstacle::Circle {
            center: DVec2::ONE,
            radius: -1.0,
        };
        assert_eq!(
            World::new(
                DVec2::ZERO,
                DVec2::ONE,
                vec![Obstacle::rect(DVec2::ZERO, DVec2::ONE), bad]
            ),
            Err(WorldError::InvalidObstacle { index: 1 })
        );
        assert!(WorldError::InvalidObstacle { index: 1 }
            .to_string()
            .contains('1'));
    }
}
