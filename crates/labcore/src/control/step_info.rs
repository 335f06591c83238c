//! Step-response metrics of a sampled response, with the definitions of
//! python-control's `step_info` (python-control 0.10, `control.timeresp.step_info`;
//! the same as MATLAB's `stepinfo`):
//!
//! With `y∞` the steady-state value and the response normalised as
//! `z(t) = (y(t) − y₀) / (y∞ − y₀)` (python-control assumes `y₀ = 0`; a lab step starts
//! wherever the cart was, so the start value is subtracted first — identical when
//! `y₀ = 0`):
//!
//! - **rise time** — from the first sample with `z ≥ 0.1` to the first with `z ≥ 0.9`;
//! - **settling time** — the first sample after the last one with `|z − 1| ≥ 0.02`
//!   (the response then stays inside the ±2 % band to the end of the record);
//! - **overshoot** — `100 · (max z − 1)` percent, 0 when the response never exceeds `y∞`;
//! - **peak** — the value of `y` at the largest `z` (the extreme in the step's
//!   direction) and the time it is reached;
//! - **steady-state error** — `setpoint − y∞` (not in python-control; shown by the lab).
//!
//! Times are measured from the first sample. Like python-control, times are sample
//! times, not interpolated between samples, so they carry an error of up to one sample
//! interval.

/// Default settling band, a fraction of the step size (2 %).
pub const SETTLING_THRESHOLD: f64 = 0.02;
/// Default rise-time limits, fractions of the step size (10 % → 90 %).
pub const RISE_TIME_LIMITS: (f64, f64) = (0.1, 0.9);

/// Metrics of one step response. Times in seconds from the first sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepInfo {
    /// 10 % → 90 % rise time, `None` if the response never reached 90 %.
    pub rise_time_s: Option<f64>,
    /// ±2 % settling time, `None` if the response was still outside the band at the
    /// last sample.
    pub settling_time_s: Option<f64>,
    /// Overshoot in percent of the step size (`≥ 0`).
    pub overshoot_pct: f64,
    /// `y` at the peak (the extreme in the step's direction).
    pub peak: f64,
    /// Time of that peak.
    pub peak_time_s: f64,
    /// The steady-state value `y∞` the metrics are relative to.
    pub steady_state_value: f64,
    /// `setpoint − y∞`.
    pub steady_state_error: f64,
}

/// Metrics of the response `values` sampled at `times_s` (same length, at least two
/// samples, times non-decreasing), for a step that started at `y_start` toward
/// `setpoint`. `y_final` is the steady-state value; `None` takes the last sample (what
/// python-control does for data).
///
/// Returns `None` when the slices are unusable (different lengths, fewer than two
/// samples, a non-finite value), when the step size `y∞ − y₀` is zero, or when it is
/// so small that the normalised response `z` overflows (a step of `5·10⁻³²⁴` would
/// otherwise give an infinite overshoot). A caller that shows the metrics should also
/// refuse steps below its display resolution, where `z` is finite but meaningless.
///
/// # Example
/// ```
/// use labcore::control::step_info::step_info;
/// // A first-order response 1 − e^(−t), sampled every 1 ms for 10 s.
/// let t: Vec<f64> = (0..=10_000).map(|k| k as f64 * 1e-3).collect();
/// let y: Vec<f64> = t.iter().map(|t| 1.0 - (-t).exp()).collect();
/// let info = step_info(&t, &y, 0.0, 1.0, Some(1.0)).unwrap();
/// // Rise time ln 9 ≈ 2.197 s, settling time ln 50 ≈ 3.912 s, no overshoot.
/// assert!((info.rise_time_s.unwrap() - 9f64.ln()).abs() < 2e-3);
/// assert!((info.settling_time_s.unwrap() - 50f64.ln()).abs() < 2e-3);
/// assert_eq!(info.overshoot_pct, 0.0);
/// ```
#[must_use]
pub fn step_info(
    times_s: &[f64],
    values: &[f64],
    y_start: f64,
    setpoint: f64,
    y_final: Option<f64>,
) -> Option<StepInfo> {
    step_info_with(
        times_s,
        values,
        y_start,
        setpoint,
        y_final,
        SETTLING_THRESHOLD,
        RISE_TIME_LIMITS,
    )
}

/// [`step_info`] with a chosen settling band (fraction, e.g. `0.05`) and rise-time
/// limits (fractions, `lo < hi`).
#[must_use]
pub fn step_info_with(
    times_s: &[f64],
    values: &[f64],
    y_start: f64,
    setpoint: f64,
    y_final: Option<f64>,
    settling_threshold: f64,
    rise_limits: (f64, f64),
) -> Option<StepInfo> {
    let n = values.len();
    if n < 2 || times_s.len() != n {
        return None;
    }
    let y_inf = y_final.unwrap_or(values[n - 1]);
    let finite = times_s.iter().chain(values).all(|v| v.is_finite())
        && y_start.is_finite()
        && setpoint.is_finite()
        && y_inf.is_finite()
        && settling_threshold.is_finite()
        && settling_threshold > 0.0
        && rise_limits.0.is_finite()
        && rise_limits.1.is_finite()
        && rise_limits.0 < rise_limits.1;
    let span = y_inf - y_start;
    if !finite || span == 0.0 {
        return None;
    }
    let t0 = times_s[0];
    let z = |k: usize| (values[k] - y_start) / span;
    if !(0..n).all(|k| z(k).is_finite()) {
        return None;
    }

    let lo = (0..n).find(|&k| z(k) >= rise_limits.0);
    let hi = (0..n).find(|&k| z(k) >= rise_limits.1);
    let rise_time_s = match (lo, hi) {
        (Some(lo), Some(hi)) => Some(times_s[hi] - times_s[lo]),
        _ => None,
    };

    let settling_time_s = match (0..n)
        .rev()
        .find(|&k| (z(k) - 1.0).abs() >= settling_threshold)
    {
        None => Some(0.0),
        Some(last_out) if last_out + 1 < n => Some(times_s[last_out + 1] - t0),
        Some(_) => None,
    };

    let mut peak_k = 0;
    for k in 1..n {
        if z(k) > z(peak_k) {
            peak_k = k;
        }
    }
    let overshoot_pct = (100.0 * (z(peak_k) - 1.0)).max(0.0);

    Some(StepInfo {
        rise_time_s,
        settling_time_s,
        overshoot_pct,
        peak: values[peak_k],
        peak_time_s: times_s[peak_k] - t0,
        steady_state_value: y_inf,
        steady_state_error: setpoint - y_inf,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_computed_samples() {
        // z: 0, 0.05, 0.5, 0.95, 1.1, 1.03, 0.99, 1.0 (y₀ = 0, y∞ = 1)
        let t = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];
        let y = [0.0, 0.05, 0.5, 0.95, 1.1, 1.03, 0.99, 1.0];
        let info = step_info(&t, &y, 0.0, 1.0, Some(1.0)).unwrap();
        // First ≥ 0.1 at t = 2, first ≥ 0.9 at t = 3.
        assert_eq!(info.rise_time_s, Some(1.0));
        // Last |z − 1| ≥ 0.02 is t = 5 (0.03), so settled from t = 6.
        assert_eq!(info.settling_time_s, Some(6.0));
        assert!((info.overshoot_pct - 10.0).abs() < 1e-12);
        assert_eq!((info.peak, info.peak_time_s), (1.1, 4.0));
        assert_eq!(info.steady_state_error, 0.0);
    }

    #[test]
    fn downward_step_offset_start_and_final_from_last_sample() {
        // A step from 2 toward setpoint 0 that stops at 0.5: span −1.5.
        let t = [10.0, 10.5, 11.0, 11.5];
        let y = [2.0, 1.0, 0.4, 0.5];
        let info = step_info(&t, &y, 2.0, 0.0, None).unwrap();
        assert_eq!(info.steady_state_value, 0.5);
        assert_eq!(info.steady_state_error, -0.5);
        // z = 0, 2/3, 16/15, 1 → overshoot 6.67 %, peak 0.4 at 1.0 s after the start.
        assert!((info.overshoot_pct - 100.0 / 15.0).abs() < 1e-9);
        assert_eq!((info.peak, info.peak_time_s), (0.4, 1.0));
        assert_eq!(info.rise_time_s, Some(0.5));
        assert_eq!(info.settling_time_s, Some(1.5));
    }

    #[test]
    fn unsettled_and_unusable_inputs() {
        let t = [0.0, 1.0, 2.0];
        // Still outside the band at the end.
        let info = step_info(&t, &[0.0, 0.5, 0.8], 0.0, 1.0, Some(1.0)).unwrap();
        assert_eq!(info.settling_time_s, None);
        assert_eq!(info.rise_time_s, None);
        assert_eq!(info.overshoot_pct, 0.0);
        assert!(step_info(&t, &[0.0, 1.0], 0.0, 1.0, None).is_none());
        assert!(step_info(&t, &[0.0, f64::NAN, 1.0], 0.0, 1.0, None).is_none());
        assert!(step_info(&t, &[1.0, 1.0, 1.0], 1.0, 1.0, None).is_none());
    }

    /// Issue 14: a subnormal step made the overshoot infinite.
    #[test]
    fn a_step_too_small_to_divide_by_has_no_metrics() {
        let t = [0.0, 1.0, 2.0];
        let y = [0.0, 1e-3, -5e-324];
        assert!(step_info(&t, &y, 0.0, -5e-324, Some(-5e-324)).is_none());
        // Small but representable: finite metrics.
        let info = step_info(&t, &[0.0, 2e-9, 1e-9], 0.0, 1e-9, Some(1e-9)).unwrap();
        assert!((info.overshoot_pct - 100.0).abs() < 1e-9);
    }
}
