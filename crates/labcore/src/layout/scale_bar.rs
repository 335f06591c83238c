//! The scene's scale bar: its length and its text, the same on the canvas,
//! in the report's figure and wherever else a scene is drawn.

use crate::math;
use crate::units::{format_number, power_of_ten};

/// Longest a scale bar may be, in pixels (CSS pixels on the canvas, user
/// units in the report's SVG, which has the canvas's size).
pub const SCALE_BAR_MAX_PX: f64 = 120.0;

/// A scale bar: a round length and the text that names it.
#[derive(Clone, Debug, PartialEq)]
pub struct ScaleBar {
    /// The bar's length in metres: 1, 2 or 5 × 10ᵏ.
    pub length_m: f64,
    /// The bar's text, always in metres with no trailing zeros: `0.5 m`,
    /// `2 m`, `0.02 m`. One unit everywhere: the readouts, the plots and
    /// the scene all speak metres, so a student compares the bar with a
    /// readout without converting.
    pub label: String,
}

impl ScaleBar {
    /// The largest round length (1, 2 or 5 × 10ᵏ m) that is at most `max_px`
    /// long at `scale_px_per_m`; `None` when the scale is not a positive,
    /// finite number (nothing sensible to draw).
    #[must_use]
    pub fn fit(scale_px_per_m: f64, max_px: f64) -> Option<Self> {
        if !(scale_px_per_m.is_finite() && scale_px_per_m > 0.0 && max_px > 0.0) {
            return None;
        }
        let limit_m = max_px / scale_px_per_m;
        if !limit_m.is_finite() || limit_m <= 0.0 {
            return None;
        }
        let k = math::log10(limit_m).floor() as i32;
        let decade = power_of_ten(k);
        // A relative tolerance: 120 px at 100 px/m is 1.2 m, but 120 px at
        // 240 px/m must still admit 0.5 m though 120/240 rounds either way.
        let length_m = [5.0, 2.0, 1.0]
            .iter()
            .map(|f| f * decade)
            .find(|len| *len <= limit_m * (1.0 + 1e-9))
            .unwrap_or(decade);
        // 1, 2 or 5 × 10ᵏ has no digit below 10ᵏ.
        let decimals = usize::try_from(-k).unwrap_or(0);
        Some(Self {
            length_m,
            label: format!("{} m", format_number(length_m, decimals)),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bar(scale: f64) -> ScaleBar {
        ScaleBar::fit(scale, SCALE_BAR_MAX_PX).expect("a positive scale has a bar")
    }

    #[test]
    fn the_longest_round_length_that_fits_and_its_text() {
        // 100 px/m: 1.2 m fit, so 1 m (100 px).
        assert_eq!(
            bar(100.0),
            ScaleBar {
                length_m: 1.0,
                label: "1 m".into()
            }
        );
        // 50 px/m: 2.4 m fit → 2 m; 20 px/m: 6 m fit → 5 m.
        assert_eq!(bar(50.0).label, "2 m");
        assert_eq!(bar(20.0).label, "5 m");
        // 240 px/m: exactly 0.5 m fit → 0.5 m (120 px), not 0.2 m.
        assert_eq!(bar(240.0).label, "0.5 m");
        // 400 px/m: 0.3 m fit → 0.2 m (80 px).
        assert!((bar(400.0).length_m - 0.2).abs() < 1e-12);
        assert_eq!(bar(400.0).label, "0.2 m");
        // 5000 px/m: 0.024 m fit → 0.02 m; 0.7 px/m: 171 m fit → 100 m.
        assert_eq!(bar(5000.0).label, "0.02 m");
        assert_eq!(bar(0.7).label, "100 m");
    }

    #[test]
    fn the_bar_is_never_longer_than_allowed_and_not_less_than_a_fifth() {
        for scale in [0.7, 3.0, 13.0, 77.0, 240.0, 640.0, 12_345.0] {
            let len_px = bar(scale).length_m * scale;
            assert!(len_px <= 120.0 + 1e-6 && len_px > 120.0 / 5.0, "{scale}");
        }
    }

    #[test]
    fn no_bar_for_a_scale_that_is_not_a_positive_number() {
        for scale in [0.0, -3.0, f64::NAN, f64::INFINITY] {
            assert_eq!(ScaleBar::fit(scale, 120.0), None, "{scale}");
        }
        assert_eq!(ScaleBar::fit(100.0, 0.0), None);
    }
}
