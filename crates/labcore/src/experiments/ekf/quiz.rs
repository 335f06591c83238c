//! The quiz generators of experiment 11, each checked against the filter.

use super::*;

/// Predicted spread across the track: a robot heading along x with
/// `σ_y`, `σ_θ` moves `d = v·Δt` metres; without process noise
/// `σ_y' = √(σ_y² + d² σ_θ²)` (the `F P Fᵀ` term of the predict step).
pub(super) fn quiz_predicted_sigma(rng: &mut Lcg64) -> Draw {
    let sigma_y = rng.int(5, 30) as f64 / 100.0;
    let sigma_theta_deg = rng.int(2, 15) as f64;
    let v = rng.int(2, 10) as f64 / 10.0;
    let dt = rng.int(2, 8) as f64 / 2.0;
    let p = DMat3::from_diagonal(DVec3::new(
        0.01,
        sigma_y * sigma_y,
        sigma_theta_deg.to_radians().powi(2),
    ));
    let no_noise = MotionNoise {
        sigma_v_mps: 0.0,
        sigma_omega_radps: 0.0,
    };
    let answer = ekf_predict(DVec3::ZERO, p, Control::new(v, 0.0), dt, &no_noise)
        .map_or(f64::NAN, |b| b.cov.y_axis.y.sqrt());
    Draw {
        vars: vec![
            ("sy", format_number(sigma_y, 2)),
            ("st", format_number(sigma_theta_deg, 0)),
            ("v", format_number(v, 1)),
            ("dt", format_number(dt, 1)),
        ],
        answer,
    }
}

/// Scalar Kalman update: prior `σ_p`, measurement `σ_z` of the same quantity;
/// posterior `σ = σ_p σ_z / √(σ_p² + σ_z²)`.
pub(super) fn quiz_posterior_sigma(rng: &mut Lcg64) -> Draw {
    let sp = rng.int(10, 60) as f64 / 100.0;
    let sz = rng.int(5, 50) as f64 / 100.0;
    let k = sp * sp / (sp * sp + sz * sz);
    Draw {
        vars: vec![("sp", format_number(sp, 2)), ("sz", format_number(sz, 2))],
        answer: ((1.0 - k) * sp * sp).sqrt(),
    }
}

/// Expected bearing `wrap(atan2(dy, dx) − θ)` in degrees, from `h(x)`.
pub(super) fn quiz_expected_bearing(rng: &mut Lcg64) -> Draw {
    let (x, y) = (
        rng.int(-20, 20) as f64 / 10.0,
        rng.int(-20, 20) as f64 / 10.0,
    );
    let theta = rng.int(-17, 18) as f64 * 10.0;
    let (mut mx, mut my) = (
        rng.int(-40, 40) as f64 / 10.0,
        rng.int(-40, 40) as f64 / 10.0,
    );
    if (mx - x).abs() + (my - y).abs() < 0.5 {
        mx = x + 2.0;
        my = y + 1.0;
    }
    let z = observation_model(DVec3::new(x, y, theta.to_radians()), DVec2::new(mx, my));
    Draw {
        vars: vec![
            ("x", format_number(x, 1)),
            ("y", format_number(y, 1)),
            ("t", format_number(theta, 0)),
            ("mx", format_number(mx, 1)),
            ("my", format_number(my, 1)),
        ],
        answer: z.y.to_degrees(),
    }
}

/// NEES `eᵀ P⁻¹ e` with a diagonal `P`: a sum of squared standardised errors.
pub(super) fn quiz_nees_diagonal(rng: &mut Lcg64) -> Draw {
    let ex = rng.int(-30, 30) as f64 / 100.0;
    let ey = rng.int(-30, 30) as f64 / 100.0;
    let et = rng.int(-10, 10) as f64;
    let sx = rng.int(5, 20) as f64 / 100.0;
    let sy = rng.int(5, 20) as f64 / 100.0;
    let st = rng.int(2, 8) as f64;
    let cov = DMat3::from_diagonal(DVec3::new(sx * sx, sy * sy, st.to_radians().powi(2)));
    let answer = nees(DVec3::new(ex, ey, et.to_radians()), DVec3::ZERO, cov).unwrap_or(f64::NAN);
    Draw {
        vars: vec![
            ("ex", format_number(ex, 2)),
            ("ey", format_number(ey, 2)),
            ("et", format_number(et, 0)),
            ("sx", format_number(sx, 2)),
            ("sy", format_number(sy, 2)),
            ("st", format_number(st, 0)),
        ],
        answer,
    }
}

/// The quiz generators of experiment 11, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "predicted_sigma" => Some(quiz_predicted_sigma),
        "posterior_sigma" => Some(quiz_posterior_sigma),
        "expected_bearing" => Some(quiz_expected_bearing),
        "nees_diagonal" => Some(quiz_nees_diagonal),
        _ => None,
    }
}
