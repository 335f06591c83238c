//! Workspace of a planar 3R arm by sampling the joint space.
//!
//! The reachable workspace is the image of the joint space under forward
//! kinematics, `W = { p(θ) : θ ∈ [-π, π)³ }` (Siciliano, Sciavicco, Villani &
//! Oriolo, *Robotics: Modelling, Planning and Control*, Ch. 2, §2.11; Lynch &
//! Park, *Modern Robotics*, Ch. 4). With unlimited joints it is the annulus
//! `r ≤ |p| ≤ R`, `R = L1 + L2 + L3`, `r = max(0, L_max − (R − L_max))`
//! ([`Annulus::of_chain`]). Sampling recovers it empirically:
//!
//! - [`SamplingMode::MonteCarlo`]: joint triples uniform in `[-π, π)³`, drawn
//!   from [`Lcg64`] in the order `θ1, θ2, θ3` per sample.
//! - [`SamplingMode::Grid`]: the `N³` triples `θᵢ = −π + 2π kᵢ / N`,
//!   `kᵢ = 0 … N−1`, with `θ3` varying fastest.
//!
//! The tip *density* is not uniform over the annulus: for three similar links
//! it is highest well inside the disc and thins out towards the outer rim
//! (few joint triples reach near-straight poses), which [`DensityGrid`] makes
//! visible. Sampling is progressive ([`WorkspaceSampler::sample_batch`]) so an
//! animation can add a few thousand points per frame.

use glam::DVec2;
use std::f64::consts::PI;

use super::chain::{tip, Annulus};
use crate::rng::Lcg64;

/// How joint triples are chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplingMode {
    /// Uniform random triples from `Lcg64::new(seed)`.
    MonteCarlo { seed: u64 },
    /// `per_joint` evenly spaced angles per joint, every combination (`per_joint³` samples).
    Grid { per_joint: usize },
}

/// Radii of the sampled tips, metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeasuredRadii {
    /// Smallest `|tip|` seen so far.
    pub inner_m: f64,
    /// Largest `|tip|` seen so far.
    pub outer_m: f64,
}

/// Progressive sampler of a 3R arm's workspace.
#[derive(Clone, Debug, PartialEq)]
pub struct WorkspaceSampler {
    lengths_m: [f64; 3],
    mode: SamplingMode,
    rng: Lcg64,
    total: usize,
    produced: usize,
    measured: Option<MeasuredRadii>,
}

impl WorkspaceSampler {
    /// A sampler of the arm with links `lengths_m` (metres).
    ///
    /// Monte-Carlo: `total` uniform joint triples in `[-π, π)³` from
    /// `Lcg64::new(seed)`. Grid: `per_joint³` evenly spaced triples (`total` is
    /// then `per_joint³`, saturating at `usize::MAX`; the `total` argument is
    /// ignored). A length that is NaN, infinite or negative is taken as 0.
    ///
    /// # Example
    /// ```
    /// use labcore::kinematics::workspace::{SamplingMode, WorkspaceSampler};
    /// let mut s = WorkspaceSampler::new([1.0, 1.0, 1.0], SamplingMode::Grid { per_joint: 10 }, 0);
    /// assert_eq!(s.total(), 1000);
    /// let mut tips = Vec::new();
    /// while !s.is_done() {
    ///     s.sample_batch(256, &mut tips);
    /// }
    /// assert_eq!(tips.len(), 1000);
    /// let r = s.measured().unwrap();
    /// assert!((r.outer_m - 3.0).abs() < 1e-12); // the straight pose θ = (0, 0, 0) is on the grid
    /// ```
    #[must_use]
    pub fn new(lengths_m: [f64; 3], mode: SamplingMode, total: usize) -> Self {
        let lengths_m = lengths_m.map(|l| if l.is_finite() && l > 0.0 { l } else { 0.0 });
        let (rng, total) = match mode {
            SamplingMode::MonteCarlo { seed } => (Lcg64::new(seed), total),
            SamplingMode::Grid { per_joint } => (
                Lcg64::new(0),
                per_joint
                    .saturating_mul(per_joint)
                    .saturating_mul(per_joint),
            ),
        };
        Self {
            lengths_m,
            mode,
            rng,
            total,
            produced: 0,
            measured: None,
        }
    }

    /// The (sanitised) link lengths, metres.
    #[must_use]
    pub fn lengths_m(&self) -> [f64; 3] {
        self.lengths_m
    }

    /// The sampling mode.
    #[must_use]
    pub fn mode(&self) -> SamplingMode {
        self.mode
    }

    /// The analytic annulus `[r, R]` the samples must fall in.
    #[must_use]
    pub fn analytic(&self) -> Annulus {
        Annulus::of_chain(&self.lengths_m)
    }

    /// Samples this sampler will produce in all.
    #[must_use]
    pub fn total(&self) -> usize {
        self.total
    }

    /// Samples produced so far.
    #[must_use]
    pub fn produced(&self) -> usize {
        self.produced
    }

    /// True once `produced() == total()`.
    #[must_use]
    pub fn is_done(&self) -> bool {
        self.produced >= self.total
    }

    /// Fraction produced, in `[0, 1]` (1 when `total` is 0).
    #[must_use]
    pub fn progress(&self) -> f64 {
        if self.total == 0 {
            1.0
        } else {
            self.produced as f64 / self.total as f64
        }
    }

    /// The joint triple (radians) of sample number `index` in grid mode.
    fn grid_angles(per_joint: usize, index: usize) -> [f64; 3] {
        let n = per_joint.max(1);
        let k3 = index % n;
        let k2 = (index / n) % n;
        let k1 = (index / n / n) % n;
        let step = 2.0 * PI / n as f64;
        [
            -PI + step * k1 as f64,
            -PI + step * k2 as f64,
            -PI + step * k3 as f64,
        ]
    }

    /// The next joint triple, radians.
    fn next_angles(&mut self) -> [f64; 3] {
        match self.mode {
            SamplingMode::MonteCarlo { .. } => [
                self.rng.range(-PI, PI),
                self.rng.range(-PI, PI),
                self.rng.range(-PI, PI),
            ],
            SamplingMode::Grid { per_joint } => Self::grid_angles(per_joint, self.produced),
        }
    }

    /// Appends up to `max` more tips (metres) to `out`; returns how many were
    /// appended (0 once done). Batches of any sizes concatenate to the same
    /// cloud as one big batch.
    ///
    /// # Example
    /// ```
    /// use labcore::kinematics::workspace::{SamplingMode, WorkspaceSampler};
    /// let mut s = WorkspaceSampler::new([1.0, 0.5, 0.25], SamplingMode::MonteCarlo { seed: 1 }, 5);
    /// let mut tips = Vec::new();
    /// assert_eq!(s.sample_batch(3, &mut tips), 3);
    /// assert_eq!(s.sample_batch(3, &mut tips), 2);
    /// assert_eq!(s.sample_batch(3, &mut tips), 0);
    /// assert!(s.is_done() && tips.len() == 5);
    /// ```
    pub fn sample_batch(&mut self, max: usize, out: &mut Vec<DVec2>) -> usize {
        let count = max.min(self.total - self.produced);
        out.reserve(count);
        for _ in 0..count {
            let angles = self.next_angles();
            let p = tip(&self.lengths_m, &angles);
            let d = p.length();
            self.measured = Some(match self.measured {
                None => MeasuredRadii {
                    inner_m: d,
                    outer_m: d,
                },
                Some(m) => MeasuredRadii {
                    inner_m: m.inner_m.min(d),
                    outer_m: m.outer_m.max(d),
                },
            });
            out.push(p);
            self.produced += 1;
        }
        count
    }

    /// Radii measured from the samples so far: min and max `|tip|`, metres.
    /// `None` before the first sample.
    #[must_use]
    pub fn measured(&self) -> Option<MeasuredRadii> {
        self.measured
    }
}

/// Counts of tips on a square grid of `cols × rows` cells centred on the origin.
///
/// Cell `(col, row)` covers `[min.x + col·cell, min.x + (col+1)·cell) ×
/// [min.y + row·cell, …)`; the square is closed on its far edges, so a point
/// exactly on `x = +half_extent` falls in the last column.
#[derive(Clone, Debug, PartialEq)]
pub struct DensityGrid {
    /// Lower-left corner `(−h, −h)`, metres.
    pub min: DVec2,
    /// Cell side, metres (`2h / cols`; 0 for an empty grid).
    pub cell_m: f64,
    pub cols: usize,
    /// Equal to `cols` (square).
    pub rows: usize,
    counts: Vec<u32>,
    total: u64,
    max: u32,
}

impl DensityGrid {
    /// A `cols × cols` grid over `[−h, h]²`, `h = half_extent_m` (metres).
    /// `cols = 0` or a half extent that is not finite and positive gives an
    /// empty grid that ignores every point.
    ///
    /// # Example
    /// ```
    /// use labcore::kinematics::workspace::DensityGrid;
    /// use glam::DVec2;
    /// let mut g = DensityGrid::new(1.0, 4);
    /// g.add(DVec2::new(0.1, 0.1));
    /// g.add(DVec2::new(0.2, 0.2));
    /// g.add(DVec2::new(-0.9, -0.9));
    /// g.add(DVec2::new(5.0, 0.0)); // outside: ignored
    /// assert_eq!(g.total(), 3);
    /// let v = g.normalized();
    /// assert_eq!(v[2 * 4 + 2], 1.0);  // the fullest cell
    /// assert!((v[0] - (2f32.ln() / 3f32.ln())).abs() < 1e-6);
    /// ```
    #[must_use]
    pub fn new(half_extent_m: f64, cols: usize) -> Self {
        let valid = half_extent_m.is_finite() && half_extent_m > 0.0 && cols > 0;
        let (h, cols) = if valid {
            (half_extent_m, cols)
        } else {
            (0.0, 0)
        };
        Self {
            min: DVec2::splat(-h),
            cell_m: if cols > 0 { 2.0 * h / cols as f64 } else { 0.0 },
            cols,
            rows: cols,
            counts: vec![0; cols * cols],
            total: 0,
            max: 0,
        }
    }

    /// The cell index of `p`, row-major from `min`, or `None` outside / non-finite.
    #[must_use]
    pub fn cell_of(&self, p: DVec2) -> Option<usize> {
        if self.cols == 0 || !p.is_finite() {
            return None;
        }
        let f = (p - self.min) / self.cell_m;
        let n = self.cols as f64;
        if !(f.x >= 0.0 && f.x <= n && f.y >= 0.0 && f.y <= n) {
            return None;
        }
        let col = (f.x as usize).min(self.cols - 1);
        let row = (f.y as usize).min(self.rows - 1);
        Some(row * self.cols + col)
    }

    /// Counts `p` (metres); points outside the square or not finite are ignored.
    pub fn add(&mut self, p: DVec2) {
        if let Some(i) = self.cell_of(p) {
            let c = self.counts[i].saturating_add(1);
            self.counts[i] = c;
            self.max = self.max.max(c);
            self.total += 1;
        }
    }

    /// Counts every point of `points`.
    pub fn add_all(&mut self, points: &[DVec2]) {
        for &p in points {
            self.add(p);
        }
    }

    /// Forgets every count.
    pub fn clear(&mut self) {
        self.counts.fill(0);
        self.total = 0;
        self.max = 0;
    }

    /// Points counted so far.
    #[must_use]
    pub fn total(&self) -> u64 {
        self.total
    }

    /// The count in cell `(col, row)`; 0 outside the grid.
    #[must_use]
    pub fn count(&self, col: usize, row: usize) -> u32 {
        if col < self.cols && row < self.rows {
            self.counts[row * self.cols + col]
        } else {
            0
        }
    }

    /// The largest cell count.
    #[must_use]
    pub fn max_count(&self) -> u32 {
        self.max
    }

    /// Values in `[0, 1]` per cell (row-major from `min`, row 0 at `min.y`),
    /// log-scaled: `ln(1 + c) / ln(1 + c_max)`; all 0 when empty.
    ///
    /// Counts are small whole numbers (a few dozen per cell for the default
    /// sweep), so each distinct count's value is worked out once, in a table
    /// indexed by the count, rather than a logarithm per cell: the same
    /// values, and a scrub frame of the sweep no longer spends 0.05 ms
    /// (unthrottled) on 10,000 logarithms.
    #[must_use]
    pub fn normalized(&self) -> Vec<f32> {
        if self.max == 0 {
            return vec![0.0; self.counts.len()];
        }
        let denom = crate::math::ln_1p(f64::from(self.max));
        let value = |c: u32| (crate::math::ln_1p(f64::from(c)) / denom).clamp(0.0, 1.0) as f32;
        if self.max as usize > self.counts.len() {
            // More distinct counts possible than cells: no table.
            return self.counts.iter().map(|&c| value(c)).collect();
        }
        let table: Vec<f32> = (0..=self.max).map(value).collect();
        self.counts.iter().map(|&c| table[c as usize]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LINK_SETS: [[f64; 3]; 4] = [
        [1.0, 1.0, 1.0], // inner = 0
        [3.0, 1.0, 0.5], // inner hole: r = 1.5
        [1.0, 0.8, 0.5], // inner = 0
        [0.4, 1.5, 0.3], // hole from the middle link: r = 0.8
    ];

    fn run_all(sampler: &mut WorkspaceSampler, batch: usize) -> Vec<DVec2> {
        let mut tips = Vec::new();
        while !sampler.is_done() {
            let added = sampler.sample_batch(batch, &mut tips);
            assert!(added > 0);
        }
        tips
    }

    #[test]
    fn same_seed_same_tips_and_different_seeds_differ() {
        let mode = |seed| SamplingMode::MonteCarlo { seed };
        let a = run_all(
            &mut WorkspaceSampler::new([1.0, 0.8, 0.5], mode(7), 2000),
            100,
        );
        let b = run_all(
            &mut WorkspaceSampler::new([1.0, 0.8, 0.5], mode(7), 2000),
            100,
        );
        let c = run_all(
            &mut WorkspaceSampler::new([1.0, 0.8, 0.5], mode(8), 2000),
            100,
        );
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert!(a.iter().zip(&c).filter(|(p, q)| p != q).count() > 1990);
    }

    #[test]
    fn first_tip_matches_hand_drawn_lcg_angles() {
        let mut rng = Lcg64::new(42);
        let q = [rng.range(-PI, PI), rng.range(-PI, PI), rng.range(-PI, PI)];
        let mut s =
            WorkspaceSampler::new([1.0, 0.8, 0.5], SamplingMode::MonteCarlo { seed: 42 }, 1);
        let mut tips = Vec::new();
        s.sample_batch(10, &mut tips);
        assert_eq!(tips, vec![tip(&[1.0, 0.8, 0.5], &q)]);
    }

    #[test]
    fn batches_concatenate_to_one_big_batch() {
        for mode in [
            SamplingMode::MonteCarlo { seed: 3 },
            SamplingMode::Grid { per_joint: 13 },
        ] {
            let mut whole = WorkspaceSampler::new([1.0, 0.7, 0.4], mode, 2197);
            let mut one = Vec::new();
            assert_eq!(whole.sample_batch(usize::MAX, &mut one), 2197);
            let mut pieces = WorkspaceSampler::new([1.0, 0.7, 0.4], mode, 2197);
            let mut cloud = Vec::new();
            for size in [1, 0, 7, 100, 3, 1000].iter().cycle() {
                if pieces.is_done() {
                    break;
                }
                pieces.sample_batch(*size, &mut cloud);
            }
            assert_eq!(one, cloud, "{mode:?}");
            assert_eq!(whole.measured(), pieces.measured());
            assert_eq!(pieces.produced(), 2197);
            assert_eq!(pieces.sample_batch(10, &mut cloud), 0);
        }
    }

    #[test]
    fn measured_is_none_before_the_first_sample() {
        let mut s =
            WorkspaceSampler::new([1.0, 1.0, 1.0], SamplingMode::MonteCarlo { seed: 1 }, 10);
        assert_eq!(s.measured(), None);
        assert_eq!(s.progress(), 0.0);
        let mut tips = Vec::new();
        s.sample_batch(0, &mut tips);
        assert_eq!(s.measured(), None);
        s.sample_batch(1, &mut tips);
        let m = s.measured().unwrap();
        assert_eq!(m.inner_m, m.outer_m);
        assert_eq!(m.inner_m, tips[0].length());
        let empty = WorkspaceSampler::new([1.0, 1.0, 1.0], SamplingMode::Grid { per_joint: 0 }, 99);
        assert!(empty.is_done() && empty.total() == 0 && empty.progress() == 1.0);
    }

    fn assert_converged(lengths: [f64; 3], m: MeasuredRadii, inner_tol_rel: f64, what: &str) {
        let a = Annulus::of_chain(&lengths);
        assert!(
            (m.outer_m - a.outer_m).abs() <= 0.01 * a.outer_m,
            "{what} {lengths:?}: outer {} vs {}",
            m.outer_m,
            a.outer_m
        );
        assert!(
            (m.inner_m - a.inner_m).abs() <= inner_tol_rel * a.outer_m,
            "{what} {lengths:?}: inner {} vs {}",
            m.inner_m,
            a.inner_m
        );
        // Sampling never leaves the annulus, so the measured annulus sits inside the analytic one.
        assert!(m.outer_m <= a.outer_m + 1e-12 && m.inner_m >= a.inner_m - 1e-12);
    }

    /// Monte-Carlo radii converge to the analytic annulus: outer within 1 %,
    /// inner within 3 % of the outer radius.
    #[test]
    fn monte_carlo_radii_converge_to_analytic() {
        for (i, lengths) in LINK_SETS.iter().enumerate() {
            let mode = SamplingMode::MonteCarlo {
                seed: 100 + i as u64,
            };
            let mut s = WorkspaceSampler::new(*lengths, mode, 100_000);
            run_all(&mut s, 4096);
            assert_converged(*lengths, s.measured().unwrap(), 0.03, "monte carlo");
        }
    }

    /// Grid radii converge too; 36 angles per joint (10° apart) include 0, ±π and ±120°.
    #[test]
    fn grid_radii_converge_to_analytic() {
        for lengths in LINK_SETS {
            let mut s = WorkspaceSampler::new(lengths, SamplingMode::Grid { per_joint: 36 }, 0);
            run_all(&mut s, 5000);
            assert_converged(lengths, s.measured().unwrap(), 0.03, "grid");
        }
        // A coarse grid still brackets the analytic annulus from inside.
        let mut s = WorkspaceSampler::new([3.0, 1.0, 0.5], SamplingMode::Grid { per_joint: 4 }, 0);
        run_all(&mut s, 5);
        let m = s.measured().unwrap();
        assert!((m.outer_m - 4.5).abs() < 1e-12 && (m.inner_m - 1.5).abs() < 1e-12);
    }

    /// Property: every tip lies in the analytic annulus, for random link sets.
    #[test]
    fn every_tip_lies_in_the_analytic_annulus() {
        let mut rng = Lcg64::new(55);
        for round in 0..200 {
            let lengths = [
                rng.range(0.05, 3.0),
                rng.range(0.05, 3.0),
                rng.range(0.05, 3.0),
            ];
            let mode = if round % 2 == 0 {
                SamplingMode::MonteCarlo { seed: round }
            } else {
                SamplingMode::Grid { per_joint: 9 }
            };
            let mut s = WorkspaceSampler::new(lengths, mode, 500);
            let annulus = s.analytic();
            for p in run_all(&mut s, 128) {
                assert!(p.is_finite());
                assert!(annulus.contains(p, 1e-9), "{lengths:?} {p}");
            }
        }
    }

    #[test]
    fn grid_covers_per_joint_cubed_exactly() {
        for n in [1usize, 2, 3, 5, 8] {
            let mut s =
                WorkspaceSampler::new([1.0, 0.5, 0.25], SamplingMode::Grid { per_joint: n }, 7);
            assert_eq!(s.total(), n * n * n);
            let tips = run_all(&mut s, 10);
            assert_eq!(tips.len(), n * n * n);
            assert_eq!(s.produced(), n * n * n);
            // Every triple appears once: the angle indices enumerate the cube.
            let mut seen = vec![false; n * n * n];
            for (i, p) in tips.iter().enumerate() {
                let q = WorkspaceSampler::grid_angles(n, i);
                let k = q.map(|a| ((a + PI) / (2.0 * PI / n as f64)).round() as usize);
                assert!(k.iter().all(|&k| k < n));
                let idx = (k[0] * n + k[1]) * n + k[2];
                assert!(!seen[idx]);
                seen[idx] = true;
                assert_eq!(*p, tip(&[1.0, 0.5, 0.25], &q));
            }
            assert!(seen.iter().all(|&s| s));
        }
        // Angles stay in [-π, π).
        for i in 0..1000 {
            for a in WorkspaceSampler::grid_angles(10, i) {
                assert!((-PI..PI).contains(&a));
            }
        }
    }

    #[test]
    fn invalid_lengths_are_sanitised() {
        let mut s = WorkspaceSampler::new(
            [f64::NAN, -1.0, 2.0],
            SamplingMode::MonteCarlo { seed: 1 },
            100,
        );
        assert_eq!(s.lengths_m(), [0.0, 0.0, 2.0]);
        for p in run_all(&mut s, 50) {
            assert!(p.is_finite() && (p.length() - 2.0).abs() < 1e-12);
        }
    }

    #[test]
    fn density_normalized_is_in_unit_interval_with_max_one() {
        let lengths = [1.0, 0.8, 0.5];
        let mut s = WorkspaceSampler::new(lengths, SamplingMode::MonteCarlo { seed: 9 }, 50_000);
        let tips = run_all(&mut s, 10_000);
        let mut g = DensityGrid::new(2.3, 64);
        assert_eq!((g.cols, g.rows), (64, 64));
        assert!((g.cell_m - 4.6 / 64.0).abs() < 1e-15);
        assert!(g.normalized().iter().all(|&v| v == 0.0));
        g.add_all(&tips);
        assert_eq!(g.total(), 50_000); // every tip is within 2.3 m
        let v = g.normalized();
        assert_eq!(v.len(), 64 * 64);
        assert!(v.iter().all(|&x| (0.0..=1.0).contains(&x)));
        assert_eq!(v.iter().cloned().fold(0.0f32, f32::max), 1.0);
        // Corners of the square lie outside the reach: empty.
        assert_eq!(v[0], 0.0);
        assert_eq!(g.count(0, 0), 0);
        let sum: u64 = (0..64)
            .flat_map(|r| (0..64).map(move |c| (c, r)))
            .map(|(c, r)| u64::from(g.count(c, r)))
            .sum();
        assert_eq!(sum, 50_000);
        g.clear();
        assert_eq!(g.total(), 0);
        assert!(g.normalized().iter().all(|&v| v == 0.0));
    }

    /// `normalized`'s table (one logarithm per distinct count) gives each
    /// cell exactly `ln(1 + c) / ln(1 + c_max)`, in a grid with more cells
    /// than its largest count and in one with fewer (no table).
    #[test]
    fn density_normalized_is_the_log_formula_per_cell_with_or_without_its_table() {
        let lengths = [1.0, 0.8, 0.5];
        let mut s = WorkspaceSampler::new(lengths, SamplingMode::MonteCarlo { seed: 4 }, 20_000);
        let tips = run_all(&mut s, 5_000);
        for cells in [64, 2] {
            let mut g = DensityGrid::new(2.3, cells);
            g.add_all(&tips);
            assert_eq!(
                g.max_count() as usize > cells * cells,
                cells == 2,
                "the 2 × 2 grid's counts outnumber its cells"
            );
            let denom = crate::math::ln_1p(f64::from(g.max_count()));
            let v = g.normalized();
            for row in 0..cells {
                for col in 0..cells {
                    let c = f64::from(g.count(col, row));
                    let want = (crate::math::ln_1p(c) / denom).clamp(0.0, 1.0) as f32;
                    assert_eq!(
                        v[row * cells + col].to_bits(),
                        want.to_bits(),
                        "cell ({col}, {row})"
                    );
                }
            }
        }
    }

    #[test]
    fn density_cells_edges_and_bad_points() {
        let mut g = DensityGrid::new(1.0, 2);
        // Row 0 is at min.y; the far edges are closed.
        assert_eq!(g.cell_of(DVec2::new(-0.5, -0.5)), Some(0));
        assert_eq!(g.cell_of(DVec2::new(0.5, -0.5)), Some(1));
        assert_eq!(g.cell_of(DVec2::new(-0.5, 0.5)), Some(2));
        assert_eq!(g.cell_of(DVec2::new(1.0, 1.0)), Some(3));
        assert_eq!(g.cell_of(DVec2::new(-1.0, -1.0)), Some(0));
        assert_eq!(g.cell_of(DVec2::new(1.0 + 1e-9, 0.0)), None);
        for bad in [
            DVec2::new(f64::NAN, 0.0),
            DVec2::new(0.0, f64::INFINITY),
            DVec2::new(-3.0, 0.0),
        ] {
            g.add(bad);
        }
        assert_eq!(g.total(), 0);
        assert!(g.normalized().iter().all(|&v| v == 0.0));
        for bad in [
            DensityGrid::new(0.0, 10),
            DensityGrid::new(f64::NAN, 10),
            DensityGrid::new(1.0, 0),
        ] {
            let mut bad = bad;
            bad.add(DVec2::ZERO);
            assert_eq!(bad.total(), 0);
            assert!(bad.normalized().is_empty());
            assert_eq!(bad.count(0, 0), 0);
        }
    }
}
