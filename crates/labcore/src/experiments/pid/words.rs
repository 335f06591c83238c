//! How experiment 7 words its numbers: shared by the model's plot labels
//! (a peak's overshoot, a pin's time, "at setpoint") and the view's
//! readouts, so the two always read alike. The view depends on this file,
//! never the other way round.

use crate::units::{format_fixed, format_magnitude, format_metres};

/// A computed quantity: `decimals` places in the everyday range, else the
/// shared magnitude form (`3.5 × 10¹⁵⁰`), so an extreme link never prints
/// 150 digits.
pub(super) fn quantity(v: f64, decimals: usize) -> String {
    if v == 0.0 || (1e-3..1e3).contains(&v.abs()) {
        format_fixed(v, decimals)
    } else {
        format_magnitude(v)
    }
}

/// An overshoot, `9.5%`.
pub(super) fn percent(v: f64) -> String {
    format!("{}%", quantity(v, 1))
}

/// A time, `1.39 s`, or `--` when there is none.
pub(super) fn seconds(v: Option<f64>) -> String {
    v.map_or("--".into(), |t| format!("{} s", format_fixed(t, 2)))
}

/// Whether the final value `y` reads as the setpoint `r` at the readouts'
/// millimetre.
pub(super) fn at_setpoint(y: f64, r: f64) -> bool {
    format_metres(y) == format_metres(r)
}
