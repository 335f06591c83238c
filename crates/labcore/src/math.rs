//! Portable transcendental functions.
//!
//! `f64::sin`, `cos` and `atan2` call the platform's C library natively
//! (glibc, macOS libm, …) but a musl-derived port in wasm; they may differ in
//! the last bit, so the same seed could give slightly different runs. labcore
//! routes every transcendental call through the `libm` crate instead — the
//! same pure-Rust code on every target — so a run is bit-identical natively
//! and in the browser. (`sqrt` is exactly rounded by IEEE 754 everywhere and
//! stays as it is.)
//!
//! In wasm each function stays one function (`inline(never)`): inlined,
//! libm's argument reduction was copied into every caller, and the module
//! grew by kilobytes.

/// `(sin x, cos x)`, x in radians.
#[cfg_attr(target_arch = "wasm32", inline(never))]
#[cfg_attr(not(target_arch = "wasm32"), inline)]
#[must_use]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

#[cfg_attr(target_arch = "wasm32", inline(never))]
#[cfg_attr(not(target_arch = "wasm32"), inline)]
#[must_use]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}

#[cfg_attr(target_arch = "wasm32", inline(never))]
#[cfg_attr(not(target_arch = "wasm32"), inline)]
#[must_use]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// Four-quadrant arctangent of `y / x`, in `[-π, π]`.
#[cfg_attr(target_arch = "wasm32", inline(never))]
#[cfg_attr(not(target_arch = "wasm32"), inline)]
#[must_use]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// `√(x² + y²)` without overflow.
#[cfg_attr(target_arch = "wasm32", inline(never))]
#[cfg_attr(not(target_arch = "wasm32"), inline)]
#[must_use]
pub fn hypot(x: f64, y: f64) -> f64 {
    libm::hypot(x, y)
}

/// Natural logarithm.
#[cfg_attr(target_arch = "wasm32", inline(never))]
#[cfg_attr(not(target_arch = "wasm32"), inline)]
#[must_use]
pub fn ln(x: f64) -> f64 {
    libm::log(x)
}

/// `ln(1 + x)`, accurate for small `x`.
#[cfg_attr(target_arch = "wasm32", inline(never))]
#[cfg_attr(not(target_arch = "wasm32"), inline)]
#[must_use]
pub fn ln_1p(x: f64) -> f64 {
    libm::log1p(x)
}

/// Base-10 logarithm.
#[cfg_attr(target_arch = "wasm32", inline(never))]
#[cfg_attr(not(target_arch = "wasm32"), inline)]
#[must_use]
pub fn log10(x: f64) -> f64 {
    libm::log10(x)
}

/// `eˣ`.
#[cfg_attr(target_arch = "wasm32", inline(never))]
#[cfg_attr(not(target_arch = "wasm32"), inline)]
#[must_use]
pub fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// Cube root.
#[cfg_attr(target_arch = "wasm32", inline(never))]
#[cfg_attr(not(target_arch = "wasm32"), inline)]
#[must_use]
pub fn cbrt(x: f64) -> f64 {
    libm::cbrt(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agrees_with_std_to_an_ulp_or_two() {
        let mut rng = crate::rng::Lcg64::new(1);
        for _ in 0..10_000 {
            let x = rng.range(-10.0, 10.0);
            let y = rng.range(-10.0, 10.0);
            let (s, c) = sin_cos(x);
            assert!((s - x.sin()).abs() <= 4.0 * f64::EPSILON);
            assert!((c - x.cos()).abs() <= 4.0 * f64::EPSILON);
            assert!((atan2(y, x) - y.atan2(x)).abs() <= 8.0 * f64::EPSILON);
        }
        assert_eq!(atan2(0.0, -1.0), std::f64::consts::PI);
        assert_eq!(cbrt(27.0), 3.0);
        for k in -300..=300 {
            // Exact at powers of ten: plots and readouts take floor/ceil of it.
            let x: f64 = format!("1e{k}").parse().unwrap();
            assert_eq!(log10(x), f64::from(k), "log10(1e{k})");
        }
        assert!((ln(10.0) - 10f64.ln()).abs() <= f64::EPSILON);
        assert_eq!(ln_1p(0.0), 0.0);
        assert!((ln_1p(1e-12) - 1e-12).abs() <= 1e-24);
        assert!((ln_1p(9.0) - 10f64.ln()).abs() <= 2.0 * f64::EPSILON);
    }
}
