//! The lab's one random generator: a 64-bit linear congruential generator.
//!
//! `s ← s · 6364136223846793005 + 1442695040888963407 (mod 2⁶⁴)`, then
//! `u = (s >> 11) / 2⁵³` is uniform in `[0, 1)` (Knuth's MMIX constants).
//! The state is advanced before each draw. It is the generator named in
//! `shared/BENCHMARKS.md`, so any implementation in any language builds the
//! identical world from the same seed. Integer arithmetic only: the same seed
//! gives the same stream natively and in wasm.

/// Seeded 64-bit LCG. Cheap to copy; every experiment owns one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Lcg64 {
    state: u64,
}

const MULTIPLIER: u64 = 6_364_136_223_846_793_005;
const INCREMENT: u64 = 1_442_695_040_888_963_407;

impl Lcg64 {
    /// A generator whose state starts at `seed`.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// Advances the state and returns it.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_mul(MULTIPLIER).wrapping_add(INCREMENT);
        self.state
    }

    /// Uniform in `[0, 1)` with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    /// Uniform integer in `[lo, hi]` (inclusive). `hi < lo` returns `lo`.
    pub fn int(&mut self, lo: i64, hi: i64) -> i64 {
        if hi <= lo {
            return lo;
        }
        let span = (hi - lo + 1) as f64;
        lo + ((self.next_f64() * span) as i64).min(hi - lo)
    }

    /// Standard normal draw, `N(0, 1)`, by Marsaglia's polar method
    /// (Marsaglia & Bray, "A convenient method for generating normal
    /// variables", *SIAM Review* 6(3), 1964; Knuth, *TAOCP* Vol. 2, §3.4.1,
    /// Algorithm P): draw `u, v` uniform in `(-1, 1)` until
    /// `0 < s = u² + v² < 1`, then return `u · √(−2 ln s / s)`.
    ///
    /// The second normal of the pair is discarded so the generator stays a
    /// plain `u64` state (a draw consumes two or more uniforms; the loop
    /// accepts with probability π/4). Only `ln` and `sqrt` are used — `ln`
    /// through [`crate::math`] — so the stream is bit-identical natively and in
    /// wasm.
    ///
    /// # Example
    /// ```
    /// let mut rng = labcore::Lcg64::new(1);
    /// let z = rng.gaussian();
    /// assert!(z.is_finite());
    /// ```
    pub fn gaussian(&mut self) -> f64 {
        loop {
            let u = 2.0 * self.next_f64() - 1.0;
            let v = 2.0 * self.next_f64() - 1.0;
            let s = u * u + v * v;
            if s > 0.0 && s < 1.0 {
                return u * (-2.0 * crate::math::ln(s) / s).sqrt();
            }
        }
    }

    /// Normal draw with mean `mean` and standard deviation `std_dev`
    /// (`mean + std_dev · z`, `z` from [`Lcg64::gaussian`]). A negative
    /// `std_dev` acts as its absolute value.
    pub fn normal(&mut self, mean: f64, std_dev: f64) -> f64 {
        mean + std_dev.abs() * self.gaussian()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_draws_match_hand_computed_lcg() {
        let mut rng = Lcg64::new(42);
        let s1 = 42u64
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        assert_eq!(rng.next_u64(), s1);
        let mut rng = Lcg64::new(0);
        // s = 1442695040888963407; (s >> 11) / 2^53
        let expected = (1442695040888963407u64 >> 11) as f64 / 9007199254740992.0;
        assert_eq!(rng.next_f64(), expected);
    }

    #[test]
    fn same_seed_same_stream_and_unit_interval() {
        let mut a = Lcg64::new(7);
        let mut b = Lcg64::new(7);
        for _ in 0..10_000 {
            let u = a.next_f64();
            assert_eq!(u, b.next_f64());
            assert!((0.0..1.0).contains(&u));
        }
    }

    /// Sample moments of 200,000 draws: mean 0 and variance 1 within about
    /// five standard errors, and the tail shares of a normal (|z| > 1: 31.7 %,
    /// |z| > 2: 4.55 %).
    #[test]
    fn gaussian_has_normal_moments_and_tails() {
        let mut rng = Lcg64::new(2024);
        let n = 200_000;
        let (mut sum, mut sum_sq, mut beyond1, mut beyond2) = (0.0, 0.0, 0usize, 0usize);
        for _ in 0..n {
            let z = rng.gaussian();
            assert!(z.is_finite());
            sum += z;
            sum_sq += z * z;
            beyond1 += usize::from(z.abs() > 1.0);
            beyond2 += usize::from(z.abs() > 2.0);
        }
        let nf = n as f64;
        let mean = sum / nf;
        let var = sum_sq / nf - mean * mean;
        assert!(mean.abs() < 5.0 / nf.sqrt(), "mean {mean}");
        assert!(
            (var - 1.0).abs() < 5.0 * (2.0 / nf).sqrt(),
            "variance {var}"
        );
        assert!((beyond1 as f64 / nf - 0.3173).abs() < 0.005);
        assert!((beyond2 as f64 / nf - 0.0455).abs() < 0.002);
        // Same seed, same stream; `normal` scales and shifts.
        let (mut a, mut b) = (Lcg64::new(9), Lcg64::new(9));
        let z = a.gaussian();
        assert_eq!(b.normal(3.0, 2.0), 3.0 + 2.0 * z);
    }

    #[test]
    fn int_stays_inclusive_and_hits_both_ends() {
        let mut rng = Lcg64::new(3);
        let mut seen = [false; 5];
        for _ in 0..1000 {
            let k = rng.int(-2, 2);
            assert!((-2..=2).contains(&k));
            seen[(k + 2) as usize] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }
}
