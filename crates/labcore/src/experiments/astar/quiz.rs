//! Generated quiz questions of experiment 6, each checked against the solver.

use super::*;

/// The octile distance `max(dx, dy) + (√2 − 1) · min(dx, dy)` between two cells.
pub(super) fn quiz_octile(rng: &mut Lcg64) -> Draw {
    let dx = rng.int(1, 20);
    let dy = rng.int(1, 20);
    Draw {
        vars: vec![("dx", dx.to_string()), ("dy", dy.to_string())],
        answer: Heuristic::Octile.of_offsets(dx as f64, dy as f64),
    }
}

/// `f = g + h` with the octile `h`.
pub(super) fn quiz_f_value(rng: &mut Lcg64) -> Draw {
    let g = rng.int(20, 300) as f64 / 10.0;
    let dx = rng.int(0, 15);
    let dy = rng.int(1, 15);
    Draw {
        vars: vec![
            ("g", format_number(g, 1)),
            ("dx", dx.to_string()),
            ("dy", dy.to_string()),
        ],
        answer: g + Heuristic::Octile.of_offsets(dx as f64, dy as f64),
    }
}

/// Weighted A*'s bound `w · C*`.
pub(super) fn quiz_weighted_bound(rng: &mut Lcg64) -> Draw {
    let c = rng.int(100, 900) as f64 / 10.0;
    let w = rng.int(11, 30) as f64 / 10.0;
    Draw {
        vars: vec![("cost", format_number(c, 1)), ("w", format_number(w, 1))],
        answer: w * c,
    }
}

/// Cells within Manhattan distance `d` of a cell on an open grid (the
/// diamond Dijkstra expands with 4-connected moves): `2d² + 2d + 1`. The
/// diamond (`2d + 1` cells across) fits on the default 32 × 24 grid.
pub(super) fn quiz_diamond(rng: &mut Lcg64) -> Draw {
    let d = rng.int(2, 11);
    Draw {
        vars: vec![("d", d.to_string())],
        answer: (2 * d * d + 2 * d + 1) as f64,
    }
}

/// The quiz generators of experiment 6, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "octile" => Some(quiz_octile),
        "f_value" => Some(quiz_f_value),
        "weighted_bound" => Some(quiz_weighted_bound),
        "diamond" => Some(quiz_diamond),
        _ => None,
    }
}
