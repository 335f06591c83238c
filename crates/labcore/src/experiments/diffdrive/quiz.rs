//! Experiment 4's generated quiz questions, each answered by the solver.

use crate::mobile::go_to_goal::GoToGoal;
use crate::mobile::unicycle::{wheel_speeds, Pose};
use crate::quiz::{Draw, Generator};
use crate::rng::Lcg64;
use crate::units::format_number;
use glam::DVec2;

/// A random speed in m/s with two decimals.
fn draw_speed(rng: &mut Lcg64, lo: i64, hi: i64) -> f64 {
    rng.int(lo, hi) as f64 / 100.0
}

/// `v_R = v + ω b/2` for drawn `v`, `ω` and track `b`.
pub(super) fn quiz_right_wheel(rng: &mut Lcg64) -> Draw {
    let v = draw_speed(rng, 10, 150);
    let w = rng.int(-30, 30) as f64 / 10.0;
    let b = rng.int(20, 60) as f64 / 100.0;
    Draw {
        vars: vec![
            ("v", format_number(v, 2)),
            ("w", format_number(w, 1)),
            ("b", format_number(b, 2)),
        ],
        answer: wheel_speeds(v, w, b).1,
    }
}

/// The wrapped heading error in degrees for a robot at the origin facing
/// `θ` and a goal at `(x, y)` (often across ±180°). The offset is one the
/// field allows from the start pose: `|x| ≤ 4 m`, `|y| ≤ 3 m`.
pub(super) fn quiz_heading_error(rng: &mut Lcg64) -> Draw {
    let theta = rng.int(-179, 179) as f64;
    let x = rng.int(-40, 40) as f64 / 10.0;
    let mut y = rng.int(-30, 30) as f64 / 10.0;
    if x == 0.0 && y == 0.0 {
        y = 1.0;
    }
    let cmd =
        GoToGoal::default().command(Pose::new(0.0, 0.0, theta.to_radians()), DVec2::new(x, y));
    Draw {
        vars: vec![
            ("theta", format_number(theta, 0)),
            ("x", format_number(x, 1)),
            ("y", format_number(y, 1)),
        ],
        answer: cmd.heading_error_rad.to_degrees(),
    }
}

/// The commanded speed `v = min(Kv d max(0, cos eθ), v_max)`.
pub(super) fn quiz_forward_speed(rng: &mut Lcg64) -> Draw {
    let kv = rng.int(5, 20) as f64 / 10.0;
    let d = rng.int(2, 30) as f64 / 10.0;
    let e = rng.int(-80, 80) as f64;
    let vmax = rng.int(8, 15) as f64 / 10.0;
    let controller = GoToGoal {
        k_v_per_s: kv,
        max_v_mps: vmax,
        ..GoToGoal::default()
    };
    let cmd = controller.command_for_heading(Pose::default(), e.to_radians(), d);
    Draw {
        vars: vec![
            ("kv", format_number(kv, 1)),
            ("d", format_number(d, 1)),
            ("e", format_number(e, 0)),
            ("vmax", format_number(vmax, 1)),
        ],
        answer: cmd.v_mps,
    }
}

/// The quiz generators of experiment 4, by name.
#[must_use]
pub fn quiz_generator(name: &str) -> Option<Generator> {
    match name {
        "right_wheel" => Some(quiz_right_wheel),
        "heading_error" => Some(quiz_heading_error),
        "forward_speed" => Some(quiz_forward_speed),
        _ => None,
    }
}
