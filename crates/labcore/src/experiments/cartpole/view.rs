//! What experiment 8 shows: the scene, the readouts, the status badge.

use super::{gains_text, wrap_deg, CartPoleBalance, Run, DRIFT_M, PIVOT_Y_M, SWING_DEG};
use crate::control::cartpole::{
    closed_loop_eigenvalues, open_loop_eigenvalues, CartPoleState, PoleStatus,
};
use crate::control::{Complex, Stability};
use crate::experiment::{Experiment, Notice, Presentation, Readout, Status, Tone};
use crate::live_math::{Equation, Expr, Quantity};
use crate::scene::{Item, Role, Scene, ViewBox};
use crate::units::format_fixed;
use crate::units::{format_degrees, format_metres};
use glam::DVec2;

/// The drawn cart body: its half-width and its bottom edge above the track, metres.
const CART_HALF_W_M: f64 = 0.25;
const CART_BOTTOM_M: f64 = 0.06;
/// Low enough for a pole hanging below the rail (the "never" fall rule), and
/// wide enough for a pole lying flat from a cart at an end stop
/// (2.4 m + 1 m pole + its tip's dot).
const VIEW_MIN: DVec2 = DVec2::new(-3.6, -0.8);
const VIEW_MAX: DVec2 = DVec2::new(3.6, 1.5);
/// Force arrow length per newton (m).
const ARROW_M_PER_N: f64 = 0.02;

/// The state feedback `F = kx x + kv ẋ + kθ θ + kω θ̇` (that is `u = −Kx`
/// with `K = −k`; Ogata, *Modern Control Engineering*, §10.2), on the state
/// the step started from, held within the force limit.
const FEEDBACK: Expr = Expr::Clamp(
    &Expr::Add(
        &Expr::Add(
            &Expr::Add(
                &Expr::Mul(&Expr::Var("kx"), &Expr::Var("xk")),
                &Expr::Mul(&Expr::Var("kv"), &Expr::Var("vk")),
            ),
            &Expr::Mul(&Expr::Var("kth"), &Expr::Var("thk")),
        ),
        &Expr::Mul(&Expr::Var("kom"), &Expr::Var("omk")),
    ),
    &Expr::Var("flim"),
);
/// The energy of cart and pole, the pole a uniform rod of half-length `l`
/// (Barto, Sutton & Anderson 1983's model): kinetic plus potential.
const ENERGY: Equation = Equation {
    key: "energy",
    symbol: "E",
    expr: Expr::Add(
        &Expr::Add(
            &Expr::Add(
                &Expr::Mul(
                    &Expr::Mul(
                        &Expr::Num(0.5, "½"),
                        &Expr::Add(&Expr::Var("mc"), &Expr::Var("mp")),
                    ),
                    &Expr::Sq(&Expr::Var("v")),
                ),
                &Expr::Mul(
                    &Expr::Mul(
                        &Expr::Mul(
                            &Expr::Mul(&Expr::Var("mp"), &Expr::Var("l")),
                            &Expr::Var("v"),
                        ),
                        &Expr::Var("om"),
                    ),
                    &Expr::Cos(&Expr::Var("th")),
                ),
            ),
            &Expr::Mul(
                &Expr::Mul(
                    &Expr::Mul(&Expr::Num(2.0 / 3.0, "⅔"), &Expr::Var("mp")),
                    &Expr::Sq(&Expr::Var("l")),
                ),
                &Expr::Sq(&Expr::Var("om")),
            ),
        ),
        &Expr::Mul(
            &Expr::Mul(
                &Expr::Mul(&Expr::Var("mp"), &Expr::Var("g")),
                &Expr::Var("l"),
            ),
            &Expr::Cos(&Expr::Var("th")),
        ),
    ),
    readout: "energy",
    caption: "The energy now: the cart's and the pole's motion plus the pole's height; with control off and no friction the equations conserve it, so any drift is the integrator's.",
    absent: "",
};
/// With the controller acting, and with no force (control off, or no step yet).
const EQUATIONS: [&[Equation]; 2] = [
    &[
        Equation {
            key: "force",
            symbol: "F",
            expr: FEEDBACK,
            readout: "force",
            caption: "The controller's force, from the state the last step started from (subscript k), held within the limit.",
            absent: "",
        },
        ENERGY,
    ],
    &[
        Equation {
            key: "force",
            symbol: "F",
            expr: Expr::Num(0.0, "0"),
            readout: "force",
            caption: "No force: control is off (or no step has run yet).",
            absent: "",
        },
        ENERGY,
    ],
];

/// `3.972, -3.972, 0, 0` or `-1.234 ± 5.678i`, slowest first.
pub(super) fn format_eigenvalues(z: &[Complex]) -> String {
    let mut sorted: Vec<Complex> = z.iter().copied().filter(|p| p.im >= 0.0).collect();
    sorted.sort_by(|a, b| b.re.total_cmp(&a.re));
    sorted
        .iter()
        .map(|p| {
            if p.im == 0.0 {
                format_fixed(p.re, 3)
            } else {
                format!("{} ± {}i", format_fixed(p.re, 3), format_fixed(p.im, 3))
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The canvas's legend for the grey dashed pole: the linearised model.
pub(super) const GHOST_LEGEND: &str = "linear model (dashed)";
/// The legend shows once the two tips are this far apart (m).
const GHOST_APART_M: f64 = 0.15;

/// The force as every readout and label shows it: `-9.10 N`, `0.00 N`.
pub(super) fn force_text(force_n: f64) -> String {
    format!("{} N", format_fixed(force_n, 2))
}

impl Presentation for CartPoleBalance {
    fn view(&self) -> ViewBox {
        ViewBox {
            min: VIEW_MIN,
            max: VIEW_MAX,
        }
    }

    fn scene(&self, out: &mut Scene) {
        let track = self.sim.params.track_limit_m;
        out.push(Item::Line {
            from: DVec2::new(VIEW_MIN.x, 0.0),
            to: DVec2::new(VIEW_MAX.x, 0.0),
            width_px: 2.0,
            role: Role::Bound,
            dashed: false,
        });
        if track.is_finite() {
            for side in [-1.0, 1.0] {
                let x = side * (track + CART_HALF_W_M);
                out.push(Item::Rect {
                    min: DVec2::new(x - 0.04, 0.0),
                    max: DVec2::new(x + 0.04, 0.35),
                    role: Role::Obstacle,
                    fill: true,
                });
            }
        }
        for k in -2..=2 {
            let x = f64::from(k);
            out.push(Item::Line {
                from: DVec2::new(x, 0.0),
                to: DVec2::new(x, -0.08),
                width_px: 1.0,
                role: Role::Grid,
                dashed: false,
            });
            out.push(Item::Label {
                pos: DVec2::new(x, -0.08),
                text: format!("{k} m"),
                role: Role::Text,
                offset_px: DVec2::new(-8.0, 12.0),
            });
        }
        // The linear model as a ghost.
        let lin = self.linear;
        let lin_x = lin.x_m.clamp(-100.0, 100.0);
        out.push(Item::Rect {
            min: DVec2::new(lin_x - CART_HALF_W_M, CART_BOTTOM_M),
            max: DVec2::new(lin_x + CART_HALF_W_M, PIVOT_Y_M),
            role: Role::Ghost,
            fill: false,
        });
        let lin_tip = self.tip_of(&CartPoleState { x_m: lin_x, ..lin });
        out.push(Item::Line {
            from: DVec2::new(lin_x, PIVOT_Y_M),
            to: lin_tip,
            width_px: 3.0,
            role: Role::Ghost,
            dashed: true,
        });
        // Its legend, once it stands apart from the real pole (it hides behind
        // the real one while the two agree).
        if (lin_tip - self.tip_of(&self.sim.state)).length() > GHOST_APART_M {
            out.push(Item::Label {
                pos: lin_tip,
                text: GHOST_LEGEND.into(),
                role: Role::Ghost,
                offset_px: DVec2::new(8.0, -12.0),
            });
        }
        // A cart whose centre is outside the view gets a mark at the canvas edge.
        for (x, what, role) in [
            (lin.x_m, "linear model", Role::Ghost),
            (self.sim.state.x_m, "cart", Role::Robot),
        ] {
            if x.is_finite() && !(VIEW_MIN.x..=VIEW_MAX.x).contains(&x) {
                out.push(Item::OffView {
                    at: DVec2::new(x.clamp(-1e6, 1e6), PIVOT_Y_M),
                    label: format!("{what} at x = {}", format_metres(x)),
                    role,
                });
            }
        }
        // Where the chosen criterion calls the pole fallen (12°).
        let limit = self.criterion().angle_limit_rad;
        let pivot = self.pivot();
        if limit < 1.0 {
            for side in [-1.0, 1.0] {
                let (sin, cos) = crate::math::sin_cos(side * limit);
                out.push(Item::Line {
                    from: pivot,
                    to: pivot + DVec2::new(sin, cos) * 1.1,
                    width_px: 1.0,
                    role: Role::Warning,
                    dashed: true,
                });
            }
        }
        // The cart, wheels, pole and force.
        let x = pivot.x;
        out.push(Item::Rect {
            min: DVec2::new(x - CART_HALF_W_M, CART_BOTTOM_M),
            max: DVec2::new(x + CART_HALF_W_M, PIVOT_Y_M),
            role: Role::Robot,
            fill: true,
        });
        for dx in [-0.15, 0.15] {
            out.push(Item::Circle {
                center: DVec2::new(x + dx, 0.035),
                radius_m: 0.035,
                role: Role::Joint,
                fill: true,
                dashed: false,
            });
        }
        let tip = self.tip_of(&self.sim.state);
        let fallen = matches!(self.run, Run::Ended { .. });
        out.push(Item::Line {
            from: pivot,
            to: tip,
            width_px: 7.0,
            role: if fallen { Role::Warning } else { Role::Link },
            dashed: false,
        });
        out.push(Item::Dot {
            center: pivot,
            radius_px: 6.0,
            role: Role::Joint,
        });
        out.push(Item::Dot {
            center: tip,
            radius_px: 8.0,
            role: Role::Tip,
        });
        let f = self.sim.last_force_n();
        if f.abs() > 0.05 {
            let y = 0.5 * (CART_BOTTOM_M + PIVOT_Y_M);
            let start = x + CART_HALF_W_M.copysign(f);
            out.push(Item::Arrow {
                from: DVec2::new(start, y),
                // Inside the view even from a cart at an end stop.
                to: DVec2::new((start + f * ARROW_M_PER_N).clamp(VIEW_MIN.x, VIEW_MAX.x), y),
                width_px: 3.0,
                role: Role::Accent,
            });
        }
        out.push(Item::Label {
            pos: DVec2::new(x, 0.0),
            text: format!("F = {}", force_text(f)),
            role: Role::Text,
            offset_px: DVec2::new(-24.0, 44.0),
        });
        // What the feedback's and the energy's quantities name (issue 27
        // §3): the pole's angle θ from the upright, now and at the last
        // step's start (subscript k), the cart's position x_k along the
        // track from 0, and the half-length l up the pole.
        let at = self.sim.last_inputs().map_or(self.sim.state, |i| i.state);
        let up = std::f64::consts::FRAC_PI_2;
        out.tag_arc("th", pivot, 0.4, up, up - self.sim.state.theta_rad);
        out.tag_arc("thk", pivot, 0.4, up, up - at.theta_rad);
        let ground = DVec2::new(at.x_m.clamp(VIEW_MIN.x, VIEW_MAX.x), 0.0);
        out.tag_lines(&[
            ("xk", DVec2::ZERO, ground),
            ("l", pivot, pivot.midpoint(tip)),
        ]);
    }

    /// The gains and the state the last force came from (subscript k), and
    /// the cart-pole's masses, length and state now for the energy.
    fn quantities(&self) -> Vec<Quantity> {
        let inputs = self.sim.last_inputs();
        let k = inputs.map_or(self.sim.gains, |i| i.gains);
        let at = inputs.map(|i| i.state).unwrap_or_default();
        let p = &self.sim.params;
        let s = self.sim.state;
        vec![
            Quantity::new("kx", "k_x", k.k_x, 1, "N/m"),
            Quantity::new("xk", "x_k", at.x_m, 4, "m"),
            Quantity::new("kv", "k_v", k.k_v, 1, "N·s/m"),
            Quantity::new("vk", "x\u{307}_k", at.v_m_s, 4, "m/s"),
            Quantity::new("kth", "k_θ", k.k_theta, 1, "N/rad"),
            Quantity::new("thk", "θ_k", at.theta_rad, 5, "rad"),
            Quantity::new("kom", "k_ω", k.k_omega, 1, "N·s/rad"),
            Quantity::new("omk", "θ̇_k", at.omega_rad_s, 4, "rad/s"),
            Quantity::new(
                "flim",
                "F_max",
                inputs.map_or(p.force_limit_n, |i| i.force_limit_n),
                0,
                "N",
            ),
            Quantity::new("mc", "M", p.cart_mass_kg, 2, "kg"),
            Quantity::new("mp", "m", p.pole_mass_kg, 2, "kg"),
            Quantity::new("l", "l", p.half_length_m, 2, "m"),
            Quantity::new("g", "g", p.gravity_m_s2, 2, "m/s²"),
            Quantity::new("v", "x\u{307}", s.v_m_s, 4, "m/s"),
            Quantity::new("om", "θ̇", s.omega_rad_s, 4, "rad/s"),
            Quantity::new("th", "θ", s.theta_rad.to_degrees(), 3, "°"),
        ]
    }

    /// The Procedure's steps read these beside the main plot.
    fn watched_plots(&self) -> &'static [&'static str] {
        &["energy"]
    }

    fn equations(&self) -> &'static [Equation] {
        let acting = self.sim.last_inputs().is_some_and(|i| i.control_enabled);
        EQUATIONS[usize::from(!acting)]
    }

    fn readouts(&self) -> Vec<Readout> {
        let s = self.sim.state;
        let verdict = |z: &[Complex]| match Stability::of(z) {
            Stability::Stable => "stable",
            Stability::MarginallyStable => "marginally stable",
            Stability::Unstable => "unstable",
        };
        let closed = closed_loop_eigenvalues(&self.sim.params, &self.sim.gains).ok();
        let open = open_loop_eigenvalues(&self.sim.params).ok();
        let status = match self.run {
            Run::Going => self.status().text,
            Run::Ended { status, time_s } => format!(
                "{} at {} s",
                if status == PoleStatus::OutOfBounds {
                    "off the track"
                } else {
                    "fallen"
                },
                format_fixed(time_s, 2)
            ),
        };
        vec![
            Readout::degrees("theta", "Pole angle θ", s.theta_rad.to_degrees()),
            Readout::new(
                "omega",
                "Angular velocity θ̇",
                format!("{}°/s", format_fixed(s.omega_rad_s.to_degrees(), 1)),
            ),
            Readout::metres("x", "Cart position x", s.x_m),
            Readout::new("force", "Force F", force_text(self.sim.last_force_n())),
            Readout::new("status", "Status", status),
            Readout::new(
                "energy",
                "Energy E",
                format!("{} J", format_fixed(self.sim.energy_j(), 4)),
            ),
            Readout::new(
                "closed_eig",
                "Closed-loop eigenvalues (1/s)",
                closed.as_deref().map_or("--".into(), format_eigenvalues),
            ),
            Readout::new(
                "closed_verdict",
                "Closed loop (linearised)",
                closed.as_deref().map_or("--", verdict),
            ),
            Readout::new(
                "open_eig",
                "Open-loop eigenvalues (1/s)",
                open.as_deref().map_or("--".into(), format_eigenvalues),
            ),
            Readout::new(
                "lqr",
                "LQR proposal for Q, R",
                self.lqr_proposal().map_or(
                    "no stabilising solution: weight the cart position (q_x > 0)".into(),
                    |k| gains_text(&k),
                ),
            ),
            Readout::degrees(
                "gap",
                "Linear model gap, max |Δθ|",
                self.max_gap_rad.to_degrees(),
            ),
        ]
    }

    fn status(&self) -> Status {
        let s = self.sim.state;
        match self.run {
            Run::Ended { status, time_s } => Status::ended(
                format!(
                    "{} at t = {} s: press Reset",
                    if status == PoleStatus::OutOfBounds {
                        "cart off the track"
                    } else {
                        "pole fallen"
                    },
                    format_fixed(time_s, 2)
                ),
                Tone::Bad,
            ),
            Run::Going if !self.sim.control_enabled => {
                let lean = wrap_deg(s.theta_rad.to_degrees());
                let text = if self.at_rest() {
                    "control off: upright and still, an unstable equilibrium (nudge it)"
                } else if lean.abs() > 90.0 {
                    "control off: the pole swings below the rail"
                } else if lean * s.omega_rad_s >= 0.0 {
                    "control off: the pole is falling"
                } else {
                    "control off: the pole swings back up"
                };
                Status::new(text, Tone::Warning)
            }
            Run::Going if self.at_rest() => Status::new("balanced", Tone::Good),
            Run::Going => {
                let (theta_deg, x_m, catching) = self.recent_peaks();
                if catching && x_m <= DRIFT_M {
                    Status::new(
                        format!(
                            "catching the pole from θ₀ = {}",
                            format_degrees(self.start_deg)
                        ),
                        Tone::Neutral,
                    )
                } else if theta_deg > SWING_DEG {
                    Status::new(
                        format!("swinging: |θ| up to {}", format_degrees(theta_deg)),
                        Tone::Warning,
                    )
                } else if x_m > DRIFT_M {
                    Status::new(
                        format!("drifting: |x| up to {}", format_metres(x_m)),
                        Tone::Warning,
                    )
                } else {
                    Status::new("balancing", Tone::Neutral)
                }
            }
        }
    }

    fn notice(&self) -> Option<Notice> {
        self.notices.current()
    }

    /// The run's state from what the pole and cart have done over the last
    /// [`STATUS_WINDOW_S`]: "balancing" only while |θ| and |x| stay small.
    /// "Pole at -0.5° from upright, turning 0.2°/s; cart at 0.164 m pushed with
    /// -0.09 N; balancing."
    fn describe(&self) -> String {
        let value = |key| crate::experiment::readout_value(self, key).unwrap_or_default();
        format!(
            "Pole at {} from upright, turning {}; cart at {} pushed with {}; {}.",
            value("theta"),
            value("omega"),
            value("x"),
            value("force"),
            self.status().text
        )
    }

    fn hint(&self) -> &'static str {
        "Click beside the pole (or press ← → on the canvas) to nudge it; drag its tip to set the start angle. Drop pole switches control off."
    }

    fn touch_hint(&self) -> &'static str {
        "Tap beside the pole to nudge it; drag its tip to set the start angle. Drop pole switches control off."
    }

    /// A pole caught from its start angle, a second into the run.
    fn preview(&mut self) {
        for _ in 0..60 {
            self.step(1.0 / 60.0);
        }
    }
}
