//! The generated quiz questions of experiment 7, each computed by the solver.

use super::*;

/// Draws a mass and gains giving a stable, underdamped `Ki = 0` loop.
fn draw_second_order(rng: &mut Lcg64) -> (f64, PidGains, f64) {
    let m = rng.int(1, 8) as f64 * 0.5;
    let c = rng.int(0, 10) as f64 * 0.2;
    let kp = rng.int(4, 40) as f64;
    // ζ between about 0.15 and 0.8.
    let zeta = rng.range(0.15, 0.8);
    let kd = ((zeta * 2.0 * (m * kp).sqrt() - c) * 10.0).round().max(0.0) / 10.0;
    (m, PidGains { kp, ki: 0.0, kd }, c)
}

fn second_order_vars(m: f64, g: &PidGains, c: f64) -> Vec<(&'static str, String)> {
    vec![
        ("m", format_number(m, 2)),
        ("c", format_number(c, 2)),
        ("kp", format_number(g.kp, 2)),
        ("kd", format_number(g.kd, 2)),
    ]
}

/// Natural frequency `√(Kp/m)` of the `Ki = 0` loop.
pub(super) fn quiz_natural_frequency(rng: &mut Lcg64) -> Draw {
    let (m, g, c) = draw_second_order(rng);
    let plant = MassDragPlant {
        mass_kg: m,
        drag_n_s_per_m: c,
    };
    Draw {
        vars: second_order_vars(m, &g, c),
        answer: SecondOrder::of(&plant, &g).map_or(0.0, |s| s.natural_frequency_rad_s),
    }
}

/// Damping ratio `(c + Kd)/(2√(m·Kp))`.
pub(super) fn quiz_damping_ratio(rng: &mut Lcg64) -> Draw {
    let (m, g, c) = draw_second_order(rng);
    let plant = MassDragPlant {
        mass_kg: m,
        drag_n_s_per_m: c,
    };
    Draw {
        vars: second_order_vars(m, &g, c),
        answer: SecondOrder::of(&plant, &g).map_or(0.0, |s| s.damping_ratio),
    }
}

/// Percent overshoot `100·exp(−ζπ/√(1 − ζ²))` for a drawn ζ.
pub(super) fn quiz_overshoot(rng: &mut Lcg64) -> Draw {
    let zeta = rng.int(10, 85) as f64 / 100.0;
    let s = SecondOrder {
        natural_frequency_rad_s: 1.0,
        damping_ratio: zeta,
    };
    Draw {
        vars: vec![("zeta", format_number(zeta, 2))],
        answer: s.overshoot_pct(),
    }
}

/// Steady-state error `d/Kp` of a P or PD loop pushed back by a force `d`.
pub(super) fn quiz_offset(rng: &mut Lcg64) -> Draw {
    let kp = rng.int(2, 20) as f64;
    let d = rng.int(4, 40) as f64 * 0.25;
    let mut exp = PidControl::default();
    // The cart is pushed back (toward −x) while the setpoint is ahead.
    for (key, value) in [("kp", kp), ("ki", 0.0), ("kd", 5.0), ("d", -d)] {
        let _ = exp.set_param(key, value);
    }
    let answer = exp.final_value_m().map_or(d / kp, |y| exp.setpoint_m - y);
    Draw {
        vars: vec![("kp", format_number(kp, 2)), ("d", format_number(d, 2))],
        answer,
    }
}

/// The quiz generators of experiment 7, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "natural_frequency" => Some(quiz_natural_frequency),
        "damping_ratio" => Some(quiz_damping_ratio),
        "overshoot" => Some(quiz_overshoot),
        "offset" => Some(quiz_offset),
        _ => None,
    }
}
