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
//!
//! **Storage.** Every bin is a run of one shared array of entries (its start,
//! its length and its room), not a vector of its own: a bin that fills moves
//! to the array's end with twice the room, and a doubling of the grid files
//! every point afresh into runs laid end to end. Queries scan the same
//! contiguous runs as before, and copying or freeing the index (the
//! timeline's snapshots copy RRT*'s tree at every few steps, and a scrub
//! copies one and frees another) is two block copies or frees instead of one
//! per bin: 1,024 bins for a tree of 4,000 nodes.

use glam::DVec2;

/// The bins double in each direction when there are more than this many
/// points per bin on average. 8 was fastest for RRT* on the benchmark world
/// (2, 4, 8 and 16 tried): bigger bins mean fewer bins per radius query, each
/// scanned as one contiguous run.
pub const MAX_MEAN_PER_BIN: usize = 8;
/// The bins never exceed this many per side.
pub const MAX_BINS_PER_SIDE: usize = 4096;

/// A growing point index over the box `[min, max]` (see the module docs).
///
/// Two indexes are equal when they hold the same points in the same order
/// over the same box and bins: where in the shared array each bin's run
/// sits is a matter of history, not of content.
#[derive(Clone, Debug)]
pub struct SpatialGrid {
    min: DVec2,
    max: DVec2,
    nx: usize,
    ny: usize,
    /// `(nx, ny) / (max − min)`: bins per unit length.
    scale: DVec2,
    /// The smaller bin side, world units.
    side: f64,
    /// Each bin's run of `store` (row by row, `nx` bins a row).
    runs: Vec<Run>,
    /// The bins' entries: each bin's points' positions and indices side by
    /// side, so a query scans contiguous memory instead of chasing indices.
    /// Runs a bin outgrew are left behind as unused room.
    store: Vec<Entry>,
    points: Vec<DVec2>,
}

impl PartialEq for SpatialGrid {
    fn eq(&self, other: &Self) -> bool {
        // The bins' contents follow from the points (filed in index order)
        // and the grid's shape.
        (self.min, self.max, self.nx, self.ny) == (other.min, other.max, other.nx, other.ny)
            && self.points == other.points
    }
}

/// One bin's run of [`SpatialGrid::store`]: entries `start .. start + len`,
/// with room up to `start + room`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Run {
    start: u32,
    len: u32,
    room: u32,
}

/// The room a bin starts with in a fresh store, and gets at least when it
/// moves: half of the [`MAX_MEAN_PER_BIN`] points it holds on average
/// before the grid doubles.
const MIN_ROOM: u32 = 4;

#[derive(Clone, Copy, Debug, PartialEq)]
struct Entry {
    p: DVec2,
    index: u32,
}

impl Entry {
    /// What unused room holds.
    const UNUSED: Self = Self {
        p: DVec2::ZERO,
        index: u32::MAX,
    };
}

impl SpatialGrid {
    /// The heap it holds, bytes (capacities: what a copy of it costs).
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of;
        self.runs.capacity() * size_of::<Run>()
            + self.store.capacity() * size_of::<Entry>()
            + self.points.capacity() * size_of::<DVec2>()
    }

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
            runs: Vec::new(),
            store: Vec::new(),
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
        // Count each bin's points, lay the runs end to end with room for
        // twice that (at least MIN_ROOM), then file the points in index order.
        let bin_of = |p: DVec2| {
            let (bx, by) = Self::bin_xy(self.min, self.scale, nx, ny, p);
            by * nx + bx
        };
        let mut runs = vec![Run::default(); nx * ny];
        for &p in &self.points {
            runs[bin_of(p)].len += 1;
        }
        let mut start = 0u32;
        for run in &mut runs {
            run.start = start;
            run.room = (2 * run.len).max(MIN_ROOM);
            start += run.room;
            run.len = 0;
        }
        let mut store = vec![Entry::UNUSED; start as usize];
        for (i, &p) in self.points.iter().enumerate() {
            let run = &mut runs[bin_of(p)];
            store[(run.start + run.len) as usize] = Entry { p, index: i as u32 };
            run.len += 1;
        }
        self.runs = runs;
        self.store = store;
    }

    /// Bin `bin`'s entries.
    #[inline]
    fn bin(&self, bin: usize) -> &[Entry] {
        let run = self.runs[bin];
        &self.store[run.start as usize..(run.start + run.len) as usize]
    }

    /// Appends `entry` to bin `bin`, moving the bin's run to the store's end
    /// with twice the room when it is full.
    fn push_to_bin(&mut self, bin: usize, entry: Entry) {
        let run = self.runs[bin];
        if run.len == run.room {
            let (from, start) = (run.start as usize, self.store.len());
            let room = (2 * run.room).max(MIN_ROOM);
            self.store.extend_from_within(from..from + run.len as usize);
            self.store.resize(start + room as usize, Entry::UNUSED);
            self.runs[bin] = Run {
                start: start as u32,
                len: run.len,
                room,
            };
        }
        let run = &mut self.runs[bin];
        self.store[(run.start + run.len) as usize] = entry;
        run.len += 1;
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
        self.push_to_bin(by * self.nx + bx, Entry { p, index: i as u32 });
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
            for e in self.bin(by as usize * self.nx + bx as usize) {
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
                for e in self.bin(by * self.nx + bx) {
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

    /// The shared store: after any history of inserts (clustered points
    /// make bins outgrow their room and move; the grid doubles), every bin
    /// holds exactly what filing all the points afresh puts in it, in index
    /// order; a clone equals its original, and the store never holds more
    /// than four slots a point (plus the fresh room of empty bins).
    #[test]
    fn every_bin_holds_what_filing_the_points_afresh_gives_whatever_the_history() {
        let mut rng = Lcg64::new(7);
        let mut g = SpatialGrid::new(DVec2::ZERO, DVec2::new(40.0, 40.0));
        for n in 0..6000 {
            let p = if n % 2 == 0 {
                DVec2::new(rng.range(3.0, 3.5), rng.range(30.0, 30.2))
            } else {
                DVec2::new(rng.range(0.0, 40.0), rng.range(0.0, 40.0))
            };
            g.insert(p);
            if n % 97 == 0 || n == 5999 {
                let mut fresh = g.clone();
                fresh.set_bins(g.nx, g.ny);
                assert_eq!(fresh, g, "a clone equals its original");
                for b in 0..g.nx * g.ny {
                    assert_eq!(g.bin(b), fresh.bin(b), "bin {b} after {n} inserts");
                    assert!(g.bin(b).windows(2).all(|w| w[0].index < w[1].index));
                }
                let filed: usize = (0..g.nx * g.ny).map(|b| g.bin(b).len()).sum();
                assert_eq!(filed, g.len());
                assert!(
                    g.store.len() <= 4 * g.len() + MIN_ROOM as usize * g.nx * g.ny,
                    "{} slots for {} points",
                    g.store.len(),
                    g.len()
                );
            }
        }
        // A grid with other points is not equal.
        let mut other = g.clone();
        other.insert(DVec2::new(1.0, 1.0));
        assert_ne!(other, g);
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
