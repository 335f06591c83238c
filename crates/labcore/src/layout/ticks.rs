//! Tick labels and the decimals a step needs: one text for a tick on the
//! page's plots, in the report's plots and for a slider's value.

use crate::math;
use crate::units::{format_number, power_of_ten, superscript};

/// Most decimals any label gets: beyond a dozen places a number is no
/// longer read but counted, and axes that small switch to powers of ten.
pub const MAX_DECIMALS: usize = 12;

/// The number of decimals that shows every multiple of `step` exactly:
/// 0.1 → 1, 0.05 → 2, 0.25 → 2, 2.5 → 1, 5 → 0, 2.5e-5 → 6, 1e-7 → 7.
/// Capped at [`MAX_DECIMALS`]; 0 for a step that is zero or not finite.
///
/// The test for "no digits left" is relative (one part in a million of the
/// scaled step): a tick step comes from differences of tick values and
/// carries their rounding error (1e6 + 0.2 − (1e6 + 0.1) is 0.0999999999767),
/// which must not ask for ten more decimals; a step that is not a decimal
/// at all (1/3) stops after about seven.
#[must_use]
pub fn step_decimals(step: f64) -> usize {
    let mut s = step.abs();
    if !(s.is_finite() && s > 0.0) {
        return 0;
    }
    let mut d = 0;
    while d < MAX_DECIMALS && (s - s.round()).abs() > 1e-6 * s {
        s *= 10.0;
        d += 1;
    }
    d
}

/// Labels for the ticks of one axis; never two alike.
///
/// A linear axis: every label with the decimals of the tick step, `0.00`,
/// `0.05`, `0.10`; values past 10⁵ or below 10⁻³ share one exponent,
/// `2e5`. A log axis: see [`log_tick_labels`].
#[must_use]
pub fn tick_labels(ticks: &[f64], log: bool) -> Vec<String> {
    if log {
        return log_tick_labels(ticks);
    }
    let step = ticks
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(f64::INFINITY, f64::min);
    let biggest = ticks.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let scientific = biggest >= 1e5 || (biggest > 0.0 && biggest < 1e-3);
    let exp = if scientific {
        math::log10(biggest).floor() as i32
    } else {
        0
    };
    let scale = power_of_ten(exp);
    let base = if step.is_finite() {
        step_decimals(step / scale)
    } else {
        1
    };
    for extra in 0..8 {
        let d = base + extra;
        let labels: Vec<String> = ticks
            .iter()
            .map(|v| {
                let mut t = format!("{:.d$}", v / scale);
                if t.starts_with('-') && t[1..].chars().all(|c| c == '0' || c == '.') {
                    t.remove(0);
                }
                if scientific {
                    format!("{t}e{exp}")
                } else {
                    t
                }
            })
            .collect();
        let distinct = labels
            .iter()
            .enumerate()
            .all(|(i, a)| labels[i + 1..].iter().all(|b| a != b));
        if distinct {
            return labels;
        }
    }
    ticks.iter().map(|v| format!("{v:e}")).collect()
}

/// Labels for a log axis, one form per axis: plain numbers when every tick
/// lies in [0.01, 1000] (`0.1`, `1`, `10`: read without decoding), else
/// powers of ten as a textbook writes them, `10⁻⁶` … `10⁰`, and `2.5 × 10³`
/// for a tick that is not a power. Never `1e3`: an exponent is a
/// programmer's notation, not a student's.
#[must_use]
pub fn log_tick_labels(ticks: &[f64]) -> Vec<String> {
    let plain = ticks
        .iter()
        .all(|v| (0.01 * (1.0 - 1e-9)..=1000.0 * (1.0 + 1e-9)).contains(v));
    ticks
        .iter()
        .map(|&v| {
            if plain {
                format_number(v, step_decimals(v))
            } else {
                power_label(v)
            }
        })
        .collect()
}

/// `10⁵`, `10⁻⁶`, `2.5 × 10³`; `--` for a value that has no logarithm.
fn power_label(v: f64) -> String {
    if !(v.is_finite() && v > 0.0) {
        return "--".into();
    }
    let near = math::log10(v).round() as i32;
    if (v / power_of_ten(near) - 1.0).abs() < 1e-9 {
        return format!("10{}", superscript(near));
    }
    let k = math::log10(v).floor() as i32;
    format!(
        "{} × 10{}",
        format_number(v / power_of_ten(k), 1),
        superscript(k)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimals_of_a_step() {
        assert_eq!(step_decimals(0.1), 1);
        assert_eq!(step_decimals(0.05), 2);
        assert_eq!(step_decimals(0.25), 2);
        assert_eq!(step_decimals(0.001), 3);
        assert_eq!(step_decimals(1e-7), 7);
        assert_eq!(step_decimals(2.5e-5), 6);
        assert_eq!(step_decimals(2.5), 1);
        assert_eq!(step_decimals(5.0), 0);
        assert_eq!(step_decimals(20.0), 0);
        // A negative step has the decimals of its size.
        assert_eq!(step_decimals(-0.5), 1);
    }

    #[test]
    fn decimals_of_a_step_with_rounding_error_or_no_end() {
        // A step measured between two large ticks.
        assert_eq!(step_decimals((1e6 + 0.2) - (1e6 + 0.1)), 1);
        assert_eq!(step_decimals(0.30000000000000004 - 0.2), 1);
        // 1/3 never ends: it stops, within the cap.
        let third = step_decimals(1.0 / 3.0);
        assert!((6..=MAX_DECIMALS).contains(&third), "{third}");
        // Below the cap's resolution: the cap.
        assert_eq!(step_decimals(1e-15), MAX_DECIMALS);
    }

    #[test]
    fn no_step_no_decimals_and_no_panic() {
        for step in [0.0, -0.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(step_decimals(step), 0, "{step}");
        }
    }

    #[test]
    fn linear_ticks_share_the_decimals_of_their_step() {
        assert_eq!(
            tick_labels(&[0.0, 0.05, 0.1], false),
            ["0.00", "0.05", "0.10"]
        );
        assert_eq!(tick_labels(&[0.0, 5.0, 10.0], false), ["0", "5", "10"]);
        assert_eq!(tick_labels(&[-0.0, 1.0], false)[0], "0");
        assert_eq!(tick_labels(&[0.0, 2e5, 4e5], false), ["0e5", "2e5", "4e5"]);
        assert_eq!(tick_labels(&[], false), Vec::<String>::new());
        assert_eq!(tick_labels(&[f64::NAN], false).len(), 1);
    }

    #[test]
    fn log_ticks_read_as_numbers_in_the_middle_decades_and_as_powers_beyond() {
        assert_eq!(
            log_tick_labels(&[0.01, 0.1, 1.0, 10.0, 100.0, 1000.0]),
            ["0.01", "0.1", "1", "10", "100", "1000"]
        );
        assert_eq!(
            log_tick_labels(&[1e-6, 1e-4, 1e-2, 1.0]),
            ["10⁻⁶", "10⁻⁴", "10⁻²", "10⁰"]
        );
        assert_eq!(log_tick_labels(&[1e3, 1e4, 1e5]), ["10³", "10⁴", "10⁵"]);
        assert_eq!(log_tick_labels(&[2500.0, 1e5]), ["2.5 × 10³", "10⁵"]);
        // No logarithm, no number, no panic.
        assert_eq!(log_tick_labels(&[0.0, 1e5]), ["--", "10⁵"]);
        assert_eq!(tick_labels(&[1e3, 1e4], true), ["10³", "10⁴"]);
    }

    /// Regression (issue 13 §5): a 0.0002 J energy span showed four "0.4826".
    #[test]
    fn tick_labels_never_repeat_a_value() {
        let ticks = crate::plot::nice_ticks(0.48250, 0.48270, 6);
        let labels = tick_labels(&ticks, false);
        for (i, a) in labels.iter().enumerate() {
            assert!(!labels[i + 1..].contains(a), "{a} repeats in {labels:?}");
        }
        for span in [1e-9, 3e-7, 1e-4, 0.02, 7.0, 3e3, 1e8] {
            for centre in [0.0, 0.4826, -12.5, 1e6] {
                let ticks = crate::plot::nice_ticks(centre - span, centre + span, 7);
                let labels = tick_labels(&ticks, false);
                let mut sorted = labels.clone();
                sorted.sort();
                sorted.dedup();
                assert_eq!(sorted.len(), labels.len(), "{centre} ± {span}: {labels:?}");
            }
        }
    }
}
