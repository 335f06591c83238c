//! The quiz generators of experiment 10, each checked against the planner.

use super::*;

/// `r = min(γ √(ln n / n), η)`, with `η` on the *Step η* slider's range
/// and `n` no more than the largest iteration budget allows.
pub(super) fn quiz_radius(rng: &mut Lcg64) -> Draw {
    let gamma = rng.int(20, 80) as f64 / 2.0;
    let n = [100, 200, 500, 1000, 2000, 5000, 10000, 20000][rng.int(0, 7) as usize];
    // 0.10 … 2.00 m in steps of 0.05 m, like the slider.
    let eta = rng.int(2, 40) as f64 / 20.0;
    let r = (gamma * (crate::math::ln(n as f64) / n as f64).sqrt()).min(eta);
    Draw {
        vars: vec![
            ("gamma", format_number(gamma, 1)),
            ("n", n.to_string()),
            ("eta", format_number(eta, 2)),
        ],
        answer: r,
    }
}

/// The x coordinate of `x_new` after steering by `η` from `x_near` to
/// `x_rand`, both in the field, with `η` on the slider's range.
pub(super) fn quiz_steer_x(rng: &mut Lcg64) -> Draw {
    let in_field = |rng: &mut Lcg64| {
        DVec2::new(
            rng.int(0, (FIELD_M.x * 10.0) as i64) as f64 / 10.0,
            rng.int(0, (FIELD_M.y * 10.0) as i64) as f64 / 10.0,
        )
    };
    let eta = rng.int(4, 40) as f64 / 20.0;
    let near = in_field(rng);
    // Further than η (so the step is cut short); after a few tries, the
    // field's far corner, which is always further than 2.5 m away.
    let mut rand = in_field(rng);
    for _ in 0..16 {
        if (rand - near).length() > eta + 0.5 {
            break;
        }
        rand = in_field(rng);
    }
    if (rand - near).length() <= eta + 0.5 {
        rand = DVec2::new(
            if near.x < FIELD_M.x / 2.0 {
                FIELD_M.x
            } else {
                0.0
            },
            if near.y < FIELD_M.y / 2.0 {
                FIELD_M.y
            } else {
                0.0
            },
        );
    }
    let d = (rand - near).length();
    let new = near + (rand - near) * (eta.min(d) / d);
    Draw {
        vars: vec![
            ("nx", format_number(near.x, 1)),
            ("ny", format_number(near.y, 1)),
            ("rx", format_number(rand.x, 1)),
            ("ry", format_number(rand.y, 1)),
            ("eta", format_number(eta, 2)),
        ],
        answer: new.x,
    }
}

/// The conjugate (short) diameter `√((c_best + r_goal)² − c_min²)` of the
/// ellipse the lab's Informed RRT* samples (the goal is a disc of radius
/// [`GOAL_RADIUS_M`]); `c_min` fits in the field.
pub(super) fn quiz_ellipse(rng: &mut Lcg64) -> Draw {
    let c_min = rng.int(40, 110) as f64 / 10.0;
    let c_best = c_min + rng.int(2, 40) as f64 / 10.0;
    let c = c_best + GOAL_RADIUS_M;
    Draw {
        vars: vec![
            ("cmin", format_number(c_min, 1)),
            ("cbest", format_number(c_best, 1)),
            ("rgoal", format_number(GOAL_RADIUS_M, 2)),
        ],
        answer: (c * c - c_min * c_min).sqrt(),
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
