//! The generated quiz questions of experiment 5, each answered by the
//! solver itself.

use crate::mobile::potential_field::{CircleObstacle, PotentialField};
use crate::quiz::{Draw, Generator};
use crate::rng::Lcg64;
use crate::units::format_number;
use glam::DVec2;

/// `|F_rep| = k_r (d₀ − d)/d₀` at clearance `d < d₀` (linear law).
pub(super) fn quiz_repulsion(rng: &mut Lcg64) -> Draw {
    let kr = rng.int(5, 30) as f64 / 10.0;
    let d0 = rng.int(5, 20) as f64 / 10.0;
    let d = rng.int(1, (d0 * 10.0) as i64 - 1) as f64 / 10.0;
    let mut field = PotentialField::new(
        DVec2::new(100.0, 0.0),
        vec![CircleObstacle::new(DVec2::ZERO, 0.0)],
    );
    field.params.k_rep = kr;
    field.params.influence_m = d0;
    Draw {
        vars: vec![
            ("kr", format_number(kr, 1)),
            ("d0", format_number(d0, 1)),
            ("d", format_number(d, 1)),
        ],
        answer: field.repulsive_force(DVec2::new(d, 0.0)).length(),
    }
}

/// `F_x` on the robot at the origin, goal far ahead on +x, an obstacle of
/// radius `r` centred `s` ahead: `k_a − k_r (d₀ − d)/d₀` with `d = s − r`
/// (or just `k_a` when `d ≥ d₀`).
pub(super) fn quiz_net_force(rng: &mut Lcg64) -> Draw {
    let ka = rng.int(5, 15) as f64 / 10.0;
    let kr = rng.int(10, 30) as f64 / 10.0;
    let d0 = rng.int(8, 15) as f64 / 10.0;
    let r = rng.int(3, 8) as f64 / 10.0;
    let s = r + rng.int(1, (d0 * 10.0) as i64) as f64 / 10.0;
    let field = quiz_field(
        DVec2::new(10.0, 0.0),
        CircleObstacle::new(DVec2::new(s, 0.0), r),
        (ka, kr, d0),
    );
    Draw {
        vars: vec![
            ("ka", format_number(ka, 1)),
            ("kr", format_number(kr, 1)),
            ("d0", format_number(d0, 1)),
            ("r", format_number(r, 1)),
            ("s", format_number(s, 1)),
        ],
        answer: field.force(DVec2::ZERO).x,
    }
}

/// The field of a quiz question: one goal, one obstacle and the gains
/// `(k_a, k_r, d₀)` the question names.
pub(super) fn quiz_field(
    goal: DVec2,
    obstacle: CircleObstacle,
    (ka, kr, d0): (f64, f64, f64),
) -> PotentialField {
    let mut field = PotentialField::new(goal, vec![obstacle]);
    field.params.k_att = ka;
    field.params.k_rep = kr;
    field.params.influence_m = d0;
    field
}

/// The potential `U = k_a |goal − p| + k_r (d₀ − d)²/(2 d₀)` at a point.
pub(super) fn quiz_potential(rng: &mut Lcg64) -> Draw {
    let ka = rng.int(5, 20) as f64 / 10.0;
    let kr = rng.int(5, 30) as f64 / 10.0;
    let d0 = rng.int(5, 20) as f64 / 10.0;
    let g = rng.int(10, 50) as f64 / 10.0;
    let d = rng.int(1, (d0 * 10.0) as i64 - 1) as f64 / 10.0;
    let field = quiz_field(
        DVec2::new(g, 0.0),
        CircleObstacle::new(DVec2::new(0.0, -d), 0.0),
        (ka, kr, d0),
    );
    Draw {
        vars: vec![
            ("ka", format_number(ka, 1)),
            ("kr", format_number(kr, 1)),
            ("d0", format_number(d0, 1)),
            ("g", format_number(g, 1)),
            ("d", format_number(d, 1)),
        ],
        answer: field.potential(DVec2::ZERO),
    }
}

/// The quiz generators of experiment 5, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "repulsion" => Some(quiz_repulsion),
        "net_force" => Some(quiz_net_force),
        "potential" => Some(quiz_potential),
        _ => None,
    }
}
