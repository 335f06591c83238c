//! A uniform-bin point index for nearest-neighbour and radius queries, whose
//! bins grow with the number of points.
//!
//! Points are filed in an `nx × ny` grid of bins over fixed bounds. When the
//! average bin holds more than [`MAX_MEAN_PER_BIN`] points the grid doubles in
//! each direction and every point is refiled — `O(n)` work after `n` inserts,
//! so insertion stays amortised `O(1)` and a bin keeps holding a handful of
//! points whether the tree has 100 or 1,000,000 nodes (fixed bins degrade to a
//! linear scan as they fill: `shared/BENCHMARKS.md` measures that for RRT*).
//!
//! **Nearest** visits rings of bins around the query's bin, the square ring at
//! Chebyshev distance `k` after ring `k − 1`. A point in ring `k + 1` or
//! beyond is at least `k · s` away (`s` the smaller bin side), even for a query
//! or point outside the bounds (projection onto the box does not increase
//! distances), so the search stops once the best distance found is at most
//! `k · s`. The result is exact; ties go to the lower index.
//!
//! **Radius** queries visit the bins overlapping the disc's bounding box and
//! return indices in a fixed order (bins row by row, each in insertion order).

use glam::DVec2;

/// The bins double in each direction when there are more than this many
/// points per bin on average. 8 was fastest for RRT* on the benchmark world
/// (2, 4, 8 and 16 tried): bigger bins mean fewer bins per radius query, each
/// scanned as one contiguous run.
pub const MAX_MEAN_PER_BIN: usize = 8;
/// The bins never exceed this many per side.
pub const MAX_BINS_PER_SIDE: usize = 4096;

/// A growing point index over the box `[min, max]` (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct SpatialGrid {
    min: DVec2,
    max: DVec2,
    nx: usize,
    ny: usize,
    /// `(nx, ny) / (max − min)`: bins per unit length.
    scale: DVec2,
    /// The smaller bin side, world units.
    side: f64,
    /// Each bin holds its points' positions and indices side by side, so a
    /// query scans contiguous memory instead of chasing indices.
    bins: Vec<Vec<Entry>>,
    points: Vec<DVec2>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Entry {
    p: DVec2,
    index: u32,
}

impl SpatialGrid {
    /// An empty index over `[min, max]`; a degenerate or non-finite box is
    /// replaced by the unit square around `min` (or the origin).
    #[must_use]
    pub fn new(min: DVec2, max: DVec2) -> Self {
        let (min, max) = if min.is_finite() && max.is_finite() && min.x < max.x && min.y < max.y {
            (min, max)
        } else if min.is_finite() {
            (min, min + DVec2::ONE)
        } else {
            (DVec2::ZERO, DVec2::ONE)
        };
        let mut g = Self {
            min,
            max,
            nx: 0,
            ny: 0,
            scale: DVec2::ZERO,
            side: 0.0,
            bins: Vec::new(),
            points: Vec::new(),
        };
        g.set_bins(1, 1);
        g
    }

    fn set_bins(&mut self, nx: usize, ny: usize) {
        self.nx = nx;
        self.ny = ny;
        let size = self.max - self.min;
        self.scale = DVec2::new(nx as f64 / size.x, ny as f64 / size.y);
        self.side = (size.x / nx as f64).min(size.y / ny as f64);
        self.bins = vec![Vec::new(); nx * ny];
        for (i, &p) in self.points.iter().enumerate() {
            let (bx, by) = Self::bin_xy(self.min, self.scale, nx, ny, p);
            self.bins[by * nx + bx].push(Entry { p, index: i as u32 });
        }
    }

    #[inline]
    fn bin_xy(min: DVec2, scale: DVec2, nx: usize, ny: usize, p: DVec2) -> (usize, usize) {
        // For x ≥ 0, `x as usize` is ⌊x⌋ (and a single instruction, unlike
        // `floor` without SSE4.1); NaN and negatives become 0 (saturating casts).
        let bx = (((p.x - min.x) * scale.x).max(0.0) as usize).min(nx - 1);
        let by = (((p.y - min.y) * scale.y).max(0.0) as usize).min(ny - 1);
        (bx, by)
    }

    #[inline]
    fn bin_of(&self, p: DVec2) -> (usize, usize) {
        Self::bin_xy(self.min, self.scale, self.nx, self.ny, p)
    }

    /// Adds `p` and returns its index (`0, 1, 2, …` in insertion order).
    ///
    /// # Example
    /// ```
    /// use glam::DVec2;
    /// use labcore::planning::spatial_grid::SpatialGrid;
    /// let mut g = SpatialGrid::new(DVec2::ZERO, DVec2::splat(10.0));
    /// for i in 0..100 {
    ///     g.insert(DVec2::new((i % 10) as f64 + 0.5, (i / 10) as f64 + 0.5));
    /// }
    /// assert_eq!(g.nearest(DVec2::new(3.4, 7.6)), Some(73));
    /// let mut near = Vec::new();
    /// g.within(DVec2::new(0.5, 0.5), 1.0, &mut near);
    /// assert_eq!(near, vec![0, 1, 10]);
    /// ```
    pub fn insert(&mut self, p: DVec2) -> usize {
        let i = self.points.len();
        self.points.push(p);
        let (bx, by) = self.bin_of(p);
        self.bins[by * self.nx + bx].push(Entry { p, index: i as u32 });
        if self.points.len() > MAX_MEAN_PER_BIN * self.nx * self.ny
            && self.nx < MAX_BINS_PER_SIDE
            && self.ny < MAX_BINS_PER_SIDE
        {
            self.set_bins(2 * self.nx, 2 * self.ny);
        }
        i
    }

    /// Number of points.
    #[must_use]
    pub fn len(&self) -> usize {
        self.points.len()
    }

    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Bins per side `(nx, ny)`.
    #[must_use]
    pub fn bins(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The stored points, by index.
    #[must_use]
    pub fn points(&self) -> &[DVec2] {
        &self.points
    }

    /// Index of the point nearest to `q` (ties: lower index), `None` when empty.
    #[must_use]
    pub fn nearest(&self, q: DVec2) -> Option<usize> {
        if self.points.is_empty() {
            return None;
        }
        let (cx, cy) = self.bin_of(q);
        let (cx, cy) = (cx as isize, cy as isize);
        let (nx, ny) = (self.nx as isize, self.ny as isize);
        let mut best = (f64::INFINITY, u32::MAX);
        let visit = |bx: isize, by: isize, best: &mut (f64, u32)| {
            if bx < 0 || by < 0 || bx >= nx || by >= ny {
                return;
            }
            for e in &self.bins[by as usize * self.nx + bx as usize] {
                let d = (e.p - q).length_squared();
                if d < best.0 || (d == best.0 && e.index < best.1) {
                    *best = (d, e.index);
                }
            }
        };
        let max_ring = nx.max(ny);
        for k in 0..=max_ring {
            if k == 0 {
                visit(cx, cy, &mut best);
            } else {
                for x in cx - k..=cx + k {
                    visit(x, cy - k, &mut best);
                    visit(x, cy + k, &mut best);
                }
                for y in cy - k + 1..=cy + k - 1 {
                    visit(cx - k, y, &mut best);
                    visit(cx + k, y, &mut best);
                }
            }
            let reach = k as f64 * self.side;
            if best.1 != u32::MAX && best.0 <= reach * reach {
                break;
            }
        }
        (best.1 != u32::MAX).then_some(best.1 as usize)
    }

    /// Appends to `out` (cleared first) the indices of the points within
    /// distance `r` of `q` (`|p − q| ≤ r`).
    pub fn within(&self, q: DVec2, r: f64, out: &mut Vec<u32>) {
        out.clear();
        if r.is_nan() || r < 0.0 || self.points.is_empty() {
            return;
        }
        let (x0, y0) = self.bin_of(q - r);
        let (x1, y1) = self.bin_of(q + r);
        let r2 = r * r;
        for by in y0..=y1 {
            for bx in x0..=x1 {
                for e in &self.bins[by * self.nx + bx] {
                    if (e.p - q).length_squared() <= r2 {
                        out.push(e.index);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Lcg64;

    fn brute_nearest(points: &[DVec2], q: DVec2) -> usize {
        let mut best = (f64::INFINITY, 0);
        for (i, p) in points.iter().enumerate() {
            let d = (*p - q).length_squared();
            if d < best.0 {
                best = (d, i);
            }
        }
        best.1
    }

    #[test]
    fn nearest_and_within_match_brute_force_while_growing() {
        let mut rng = Lcg64::new(1);
        let mut g = SpatialGrid::new(DVec2::ZERO, DVec2::new(100.0, 50.0));
        let mut near = Vec::new();
        let mut last_bins = g.bins();
        let mut grew = 0;
        for n in 0..5000 {
            // Clustered and spread points, a few outside the bounds.
            let p = if n % 3 == 0 {
                DVec2::new(rng.range(10.0, 12.0), rng.range(5.0, 6.0))
            } else {
                DVec2::new(rng.range(-5.0, 105.0), rng.range(-5.0, 55.0))
            };
            assert_eq!(g.insert(p), n);
            if g.bins() != last_bins {
                grew += 1;
                last_bins = g.bins();
            }
            if n % 7 == 0 {
                let q = DVec2::new(rng.range(-20.0, 120.0), rng.range(-20.0, 70.0));
                let got = g.nearest(q).unwrap();
                let want = brute_nearest(g.points(), q);
                assert_eq!(
                    (g.points()[got] - q).length_squared(),
                    (g.points()[want] - q).length_squared()
                );
                let r = rng.range(0.0, 8.0);
                g.within(q, r, &mut near);
                let mut want: Vec<u32> = (0..g.len() as u32)
                    .filter(|&i| (g.points()[i as usize] - q).length() <= r)
                    .collect();
                let mut got = near.clone();
                got.sort_unstable();
                want.sort_unstable();
                assert_eq!(got, want);
            }
        }
        assert!(grew >= 5, "bins grew {grew} times");
        assert!(g.bins().0 * g.bins().1 * MAX_MEAN_PER_BIN >= g.len());
    }

    #[test]
    fn empty_and_degenerate_inputs() {
        let g = SpatialGrid::new(DVec2::ONE, DVec2::ONE);
        assert_eq!(g.nearest(DVec2::ZERO), None);
        let mut out = vec![7];
        g.within(DVec2::ZERO, 1.0, &mut out);
        assert!(out.is_empty());
        let mut g = SpatialGrid::new(DVec2::splat(f64::NAN), DVec2::ONE);
        g.insert(DVec2::new(0.5, 0.5));
        g.insert(DVec2::new(f64::NAN, 0.5));
        assert_eq!(g.nearest(DVec2::new(0.4, 0.4)), Some(0));
        g.within(DVec2::ZERO, f64::NAN, &mut out);
        assert!(out.is_empty());
    }
}
