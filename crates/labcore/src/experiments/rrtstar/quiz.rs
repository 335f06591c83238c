//! The quiz generators of experiment 10, each checked against the planner.

use super::*;

/// `r = min(γ √(ln n / n), η)`.
pub(super) fn quiz_radius(rng: &mut Lcg64) -> Draw {
    let gamma = rng.int(20, 80) as f64 / 2.0;
    let n = [100, 200, 500, 1000, 2000, 5000, 10000][rng.int(0, 6) as usize];
    let eta = rng.int(2, 10) as f64;
    let r = (gamma * (crate::math::ln(n as f64) / n as f64).sqrt()).min(eta);
    Draw {
        vars: vec![
            ("gamma", format_number(gamma, 1)),
            ("n", n.to_string()),
            ("eta", format_number(eta, 0)),
        ],
        answer: r,
    }
}

/// The x coordinate of `x_new` after steering by `η` from `x_near` to `x_rand`.
pub(super) fn quiz_steer_x(rng: &mut Lcg64) -> Draw {
    let near = DVec2::new(rng.int(0, 20) as f64, rng.int(0, 20) as f64);
    let rand = loop {
        let p = DVec2::new(rng.int(0, 40) as f64, rng.int(0, 40) as f64);
        if (p - near).length() > 6.0 {
            break p;
        }
    };
    let eta = rng.int(2, 5) as f64;
    let d = (rand - near).length();
    let new = near + (rand - near) * (eta.min(d) / d);
    Draw {
        vars: vec![
            ("nx", format_number(near.x, 0)),
            ("ny", format_number(near.y, 0)),
            ("rx", format_number(rand.x, 0)),
            ("ry", format_number(rand.y, 0)),
            ("eta", format_number(eta, 0)),
        ],
        answer: new.x,
    }
}

/// The informed ellipse's conjugate (short) diameter `√(c_best² − c_min²)`.
pub(super) fn quiz_ellipse(rng: &mut Lcg64) -> Draw {
    let c_min = rng.int(40, 120) as f64 / 10.0;
    let c_best = c_min + rng.int(2, 40) as f64 / 10.0;
    Draw {
        vars: vec![
            ("cmin", format_number(c_min, 1)),
            ("cbest", format_number(c_best, 1)),
        ],
        answer: (c_best * c_best - c_min * c_min).sqrt(),
    }
}

/// The quiz generators of experiment 10, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "radius" => Some(quiz_radius),
        "steer_x" => Some(quiz_steer_x),
        "ellipse" => Some(quiz_ellipse),
        _ => None,
    }
}
