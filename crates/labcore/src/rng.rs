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
