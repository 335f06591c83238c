//! A one-entry cache of a pure function's last result.
//!
//! An experiment's step may need a quantity that depends only on its
//! parameters (whether a closed loop is stable: the roots of its
//! characteristic polynomial), which the parameters change far more rarely
//! than the clock steps. Computing it once per distinct input keeps a step,
//! and so a timeline's replay of hundreds of them, cheap; the result is the
//! same as computing it every time, bit for bit, because the function is
//! pure and its input is compared exactly.

use std::cell::Cell;

/// The last input and result of a pure function (see the module).
#[derive(Clone, Debug, Default)]
pub struct Memo<K: Copy, V: Copy>(Cell<Option<(K, V)>>);

impl<K: Copy + PartialEq, V: Copy> Memo<K, V> {
    /// `f(key)`, computed only when `key` differs from the last one asked
    /// (`PartialEq`: a NaN in the key never matches, so it is recomputed).
    pub fn get(&self, key: K, f: impl FnOnce(K) -> V) -> V {
        if let Some((k, v)) = self.0.get() {
            if k == key {
                return v;
            }
        }
        let v = f(key);
        self.0.set(Some((key, v)));
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn computes_once_per_distinct_key_and_returns_what_the_function_returns() {
        let memo = Memo::<(f64, f64), f64>::default();
        let calls = Cell::new(0);
        let f = |k: (f64, f64)| {
            calls.set(calls.get() + 1);
            k.0 * k.1
        };
        assert_eq!(memo.get((2.0, 3.0), f), 6.0);
        assert_eq!(memo.get((2.0, 3.0), f), 6.0);
        assert_eq!(memo.get((2.0, 4.0), f), 8.0);
        assert_eq!(memo.get((2.0, 3.0), f), 6.0);
        assert_eq!(calls.get(), 3);
        // A NaN key is never taken for the last one.
        assert!(memo.get((f64::NAN, 1.0), f).is_nan());
        assert!(memo.get((f64::NAN, 1.0), f).is_nan());
        assert_eq!(calls.get(), 5);
    }
}
