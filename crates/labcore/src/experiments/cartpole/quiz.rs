//! Generated questions of experiment 8, each computed by the solver.

use super::*;

/// Draws a cart-pole: cart mass `M`, pole mass `m`, half-length `l`.
fn draw_cart_pole(rng: &mut Lcg64) -> CartPoleParams {
    CartPoleParams {
        cart_mass_kg: rng.int(2, 20) as f64 * 0.25,
        pole_mass_kg: rng.int(1, 10) as f64 * 0.05,
        half_length_m: rng.int(1, 8) as f64 * 0.125,
        ..CartPoleParams::default()
    }
}

/// The unstable open-loop eigenvalue `√(g/D)`, `D = l(4/3 − m/(M + m))`.
pub(super) fn quiz_unstable_eigenvalue(rng: &mut Lcg64) -> Draw {
    let p = draw_cart_pole(rng);
    let answer = open_loop_eigenvalues(&p)
        .ok()
        .map(|z| z.iter().fold(0.0_f64, |m, e| m.max(e.re)))
        .unwrap_or(0.0);
    Draw {
        vars: vec![
            ("cart", format_number(p.cart_mass_kg, 3)),
            ("pole", format_number(p.pole_mass_kg, 3)),
            ("half", format_number(p.half_length_m, 3)),
        ],
        answer,
    }
}

/// The feedback force `kθ·θ + kω·θ̇ + kx·x + kv·ẋ` for a drawn state.
pub(super) fn quiz_feedback_force(rng: &mut Lcg64) -> Draw {
    let k = StateFeedback {
        k_theta: rng.int(40, 200) as f64,
        k_omega: rng.int(5, 40) as f64,
        k_x: rng.int(1, 10) as f64,
        k_v: rng.int(1, 12) as f64,
    };
    let theta_deg = rng.int(-10, 10) as f64;
    let omega = rng.int(-20, 20) as f64 / 10.0;
    let x = rng.int(-10, 10) as f64 / 10.0;
    let v = rng.int(-10, 10) as f64 / 10.0;
    let s = CartPoleState {
        x_m: x,
        v_m_s: v,
        theta_rad: theta_deg.to_radians(),
        omega_rad_s: omega,
    };
    Draw {
        vars: vec![
            ("kth", format_number(k.k_theta, 2)),
            ("kom", format_number(k.k_omega, 2)),
            ("kx", format_number(k.k_x, 2)),
            ("kv", format_number(k.k_v, 2)),
            ("theta", format_number(theta_deg, 1)),
            ("omega", format_number(omega, 2)),
            ("x", format_number(x, 2)),
            ("v", format_number(v, 2)),
        ],
        answer: k.force_n(&s),
    }
}

/// How far `sin θ` falls below `θ`, in percent: `100·(θ − sin θ)/sin θ`.
pub(super) fn quiz_small_angle(rng: &mut Lcg64) -> Draw {
    let deg = rng.int(5, 60) as f64;
    let t = deg.to_radians();
    let sin = crate::math::sin(t);
    Draw {
        vars: vec![("deg", format_number(deg, 0))],
        answer: 100.0 * (t - sin) / sin,
    }
}

/// The quiz generators of experiment 8, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "unstable_eigenvalue" => Some(quiz_unstable_eigenvalue),
        "feedback_force" => Some(quiz_feedback_force),
        "small_angle" => Some(quiz_small_angle),
        _ => None,
    }
}
