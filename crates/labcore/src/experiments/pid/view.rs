//! What experiment 7 shows: the scene, the readouts and the status. It only reads the state.

use super::words::{at_setpoint, percent, quantity, seconds};
use super::{
    NoMetrics, PidControl, Pin, RunState, MARKER_TOP_M, MAX_PINS, MIN_STEP_M, PARAMS, QUIET_MIN_M,
    TRACK_END_M,
};
use crate::control::pid::SecondOrder;
use crate::control::step_info::StepInfo;
use crate::control::{Complex, Stability};
use crate::experiment::{Experiment, Notice, Presentation, Readout, Status, Tone};
use crate::live_math::{Equation, Expr, Quantity};
use crate::scene::{Item, Role, Scene, ViewBox};
use crate::units::{format_fixed, format_length, format_magnitude, format_metres, format_number};
use glam::DVec2;

/// World rectangle of the canvas (metres): the whole track, its end stops
/// and a cart standing at either end.
const VIEW_MIN: DVec2 = DVec2::new(-2.8, -0.7);
const VIEW_MAX: DVec2 = DVec2::new(2.8, 1.3);
/// Cart body half-width and height, metres.
pub(super) const CART_HALF_W_M: f64 = 0.22;
const CART_BOTTOM_M: f64 = 0.08;
const CART_TOP_M: f64 = 0.34;
/// Force arrow length per newton, metres, and its longest drawn length.
const ARROW_M_PER_N: f64 = 0.04;
const ARROW_MAX_M: f64 = 1.2;

/// The PID law `u = Kp e + Ki ∫e dt + Kd ė` (Åström & Murray, *Feedback
/// Systems*, §10.1), with the actuator limit when it is on.
const PI_TERMS: Expr = Expr::Add(
    &Expr::Mul(&Expr::Var("kp"), &Expr::Var("e")),
    &Expr::Mul(&Expr::Var("ki"), &Expr::Var("ie")),
);
/// Derivative on the error: `+ Kd ė`.
const PID_ON_ERROR: Expr = Expr::Add(&PI_TERMS, &Expr::Mul(&Expr::Var("kd"), &Expr::Var("de")));
/// Derivative on the measurement: `− Kd ẋ` (no kick when the setpoint jumps).
const PID_ON_MEASUREMENT: Expr =
    Expr::Sub(&PI_TERMS, &Expr::Mul(&Expr::Var("kd"), &Expr::Var("dy")));
const SUM_CAPTION: &str =
    "The controller's force: proportional, integral and derivative terms added.";
const LIMIT_CAPTION: &str =
    "The controller's force: the three terms added, then held within the actuator limit.";
/// With `Ki = 0` the loop is the second-order system `m s² + (c + Kd) s + Kp`
/// (Åström & Murray, *Feedback Systems*, §7.3): its natural frequency
/// `ωn = √(Kp/m)` …
/// What ωn and ζ say where Ki ≠ 0, in place of their numbers.
const SECOND_ORDER_ONLY: &str = "Only with Ki = 0: integral action makes the loop third order, and ωn and ζ no longer describe it. Set Ki to 0 to see them.";
const NATURAL_FREQUENCY: Equation = Equation {
    key: "omega_n",
    symbol: "ω_n",
    expr: Expr::Sqrt(&Expr::Div(&Expr::Var("kp"), &Expr::Var("m"))),
    readout: "wn",
    caption: "With Ki = 0, the natural frequency: the gain Kp as a spring against the mass.",
    absent: SECOND_ORDER_ONLY,
};
/// … and its damping ratio `ζ = (c + Kd) / (2√(m Kp))`.
const DAMPING_RATIO: Equation = Equation {
    key: "zeta",
    symbol: "ζ",
    expr: Expr::Div(
        &Expr::Add(&Expr::Var("c"), &Expr::Var("kd")),
        &Expr::Mul(
            &Expr::Num(2.0, "2"),
            &Expr::Sqrt(&Expr::Mul(&Expr::Var("m"), &Expr::Var("kp"))),
        ),
    ),
    readout: "zeta",
    caption: "With Ki = 0, the damping ratio: drag and Kd against twice √(m Kp).",
    absent: SECOND_ORDER_ONLY,
};
/// The force law `u` with its caption.
const fn law(expr: Expr, caption: &'static str) -> [Equation; 3] {
    [
        Equation {
            key: "u",
            symbol: "u",
            expr,
            readout: "force",
            caption,
            absent: "",
        },
        NATURAL_FREQUENCY,
        DAMPING_RATIO,
    ]
}
/// `[derivative on error, on measurement]`, without and with the limit.
const PID_LAWS: [[&[Equation]; 2]; 2] = [
    [
        &law(PID_ON_ERROR, SUM_CAPTION),
        &law(PID_ON_MEASUREMENT, SUM_CAPTION),
    ],
    [
        &law(
            Expr::Clamp(&PID_ON_ERROR, &Expr::Var("umax")),
            LIMIT_CAPTION,
        ),
        &law(
            Expr::Clamp(&PID_ON_MEASUREMENT, &Expr::Var("umax")),
            LIMIT_CAPTION,
        ),
    ],
];

/// What the overshoot readout and a pin say when the step is under [`MIN_STEP_M`].
pub(super) const STEP_TOO_SMALL: &str = "— (step under 1 mm)";

/// The force as the readout and the canvas show it: two decimals in newtons
/// (a tiny force reads `0.00 N`, as at rest), the magnitude form only beyond
/// the everyday range (`3.5 × 10¹⁵⁰ N`, from an extreme link).
pub(super) fn force_text(u_n: f64) -> String {
    if u_n.abs() < 1e3 || !u_n.is_finite() {
        format!("{} N", format_fixed(u_n, 2))
    } else {
        format!("{} N", format_magnitude(u_n))
    }
}

/// `-0.187` or `-1.000 ± 2.000i` (one entry per conjugate pair).
pub(super) fn format_poles(poles: &[Complex]) -> String {
    let mut parts = Vec::new();
    // Dominant (slowest) pole first.
    for p in poles.iter().rev() {
        if p.im < 0.0 {
            continue;
        }
        if p.im == 0.0 {
            parts.push(quantity(p.re, 3));
        } else {
            parts.push(format!("{} ± {}i", quantity(p.re, 3), quantity(p.im, 3)));
        }
    }
    parts.join(", ")
}

/// Where the run settles against the setpoint: `None` at the setpoint,
/// else `0.880 m, 12 % short of the setpoint` (or `past`).
fn final_against_setpoint(e: &PidControl, y: f64) -> Option<String> {
    let r = e.setpoint_m;
    if at_setpoint(y, r) {
        return None;
    }
    // Short: the cart stopped between the start (0) and the setpoint.
    let short = (r - y) * r.signum() > 0.0 && r != 0.0;
    let off = if r.abs() >= MIN_STEP_M {
        format!("{} %", format_number(100.0 * (y - r).abs() / r.abs(), 1))
    } else {
        format_length((y - r).abs())
    };
    Some(format!(
        "{}, {off} {} the setpoint",
        format_length(y),
        if short { "short of" } else { "past" }
    ))
}

/// The badge of a settled run, or `None` while it is not (yet) inside its
/// ±2 % band: "settled within 2 % after 10.20 s" when it settles at the
/// setpoint, "settled at 0.880 m, 12 % short of the setpoint (within 2 %
/// after 1.39 s)" when a push leaves an offset.
fn settled_text(e: &PidControl) -> Option<String> {
    let ts = e.info.ok()?.settling_time_s?;
    let y = e.final_value_m()?;
    Some(match final_against_setpoint(e, y) {
        None => format!("settled within 2 % after {}", seconds(Some(ts))),
        Some(at) => format!("settled at {at} (within 2 % after {})", seconds(Some(ts))),
    })
}

impl Presentation for PidControl {
    fn view(&self) -> ViewBox {
        ViewBox {
            min: VIEW_MIN,
            max: VIEW_MAX,
        }
    }

    /// The track, the setpoint marker, the cart and its force arrow.
    fn scene(&self, out: &mut Scene) {
        // Track with a tick every 0.5 m, labels at whole metres and an end stop
        // at each end (the run stops when the cart passes one).
        out.push(Item::Line {
            from: DVec2::new(-TRACK_END_M, 0.0),
            to: DVec2::new(TRACK_END_M, 0.0),
            width_px: 2.0,
            role: Role::Bound,
            dashed: false,
        });
        for end in [-TRACK_END_M, TRACK_END_M] {
            out.push(Item::Line {
                from: DVec2::new(end, -0.1),
                to: DVec2::new(end, 0.2),
                width_px: 4.0,
                role: Role::Bound,
                dashed: false,
            });
        }
        for k in -5..=5 {
            let x = f64::from(k) * 0.5;
            out.push(Item::Line {
                from: DVec2::new(x, 0.0),
                to: DVec2::new(x, -0.08),
                width_px: 1.0,
                role: Role::Grid,
                dashed: false,
            });
            if k % 2 == 0 {
                out.push(Item::Label {
                    pos: DVec2::new(x, -0.08),
                    text: format!("{} m", k / 2),
                    role: Role::Text,
                    offset_px: DVec2::new(-8.0, 12.0),
                });
            }
        }
        // The ±2 % band around the final value, on the track; named below the
        // track's metre labels when it is not around the setpoint.
        if let Some(band) = self.plots[0].bands.first() {
            out.push(Item::Rect {
                min: DVec2::new(band.lo, -0.02),
                max: DVec2::new(band.hi, 0.02),
                role: Role::Accent,
                fill: true,
            });
            if band.label != "±2 % band" {
                out.push(Item::Label {
                    pos: DVec2::new(0.5 * (band.lo + band.hi), -0.08),
                    text: band.label.clone(),
                    role: Role::Accent,
                    offset_px: DVec2::new(-60.0, 30.0),
                });
            }
        }
        // Setpoint marker (the draggable handle).
        let r = self.setpoint_m;
        out.push(Item::Line {
            from: DVec2::new(r, 0.0),
            to: DVec2::new(r, MARKER_TOP_M),
            width_px: 2.0,
            role: Role::Target,
            dashed: true,
        });
        out.push(Item::Polygon {
            points: vec![
                DVec2::new(r, MARKER_TOP_M - 0.12),
                DVec2::new(r - 0.08, MARKER_TOP_M),
                DVec2::new(r + 0.08, MARKER_TOP_M),
            ],
            role: Role::Target,
        });
        out.push(Item::Label {
            pos: DVec2::new(r, MARKER_TOP_M),
            text: format!("r = {}", format_metres(r)),
            role: Role::Target,
            offset_px: DVec2::new(10.0, -12.0),
        });
        // The cart, its wheels and the control force; the canvas edge is marked
        // when the cart is beyond the view.
        let x = self.run.state.x_m.clamp(-1e3, 1e3);
        if x.is_finite() && !(VIEW_MIN.x..=VIEW_MAX.x).contains(&x) {
            out.push(Item::OffView {
                at: DVec2::new(x, 0.5 * (CART_BOTTOM_M + CART_TOP_M)),
                label: format!("cart at {}", format_length(self.run.state.x_m)),
                role: Role::Robot,
            });
        }
        out.push(Item::Rect {
            min: DVec2::new(x - CART_HALF_W_M, CART_BOTTOM_M),
            max: DVec2::new(x + CART_HALF_W_M, CART_TOP_M),
            role: Role::Robot,
            fill: true,
        });
        for dx in [-0.13, 0.13] {
            out.push(Item::Circle {
                center: DVec2::new(x + dx, 0.045),
                radius_m: 0.045,
                role: Role::Joint,
                fill: true,
                dashed: false,
            });
        }
        // The error e = r − x: from the cart to the setpoint, above the cart.
        let above = CART_TOP_M + 0.06;
        out.tag("e", vec![DVec2::new(x, above), DVec2::new(r, above)]);
        let u = self.run.last_terms().output;
        let len = (u * ARROW_M_PER_N).clamp(-ARROW_MAX_M, ARROW_MAX_M);
        if len.abs() > 0.01 {
            let y = 0.5 * (CART_BOTTOM_M + CART_TOP_M);
            let start = x + CART_HALF_W_M.copysign(len);
            out.push(Item::Arrow {
                from: DVec2::new(start, y),
                to: DVec2::new(start + len, y),
                width_px: 3.0,
                role: Role::Accent,
            });
        }
        out.push(Item::Label {
            pos: DVec2::new(x, CART_TOP_M),
            text: format!("u = {}", force_text(u)),
            role: Role::Text,
            offset_px: DVec2::new(-24.0, -14.0),
        });
    }

    /// The live numbers beside the canvas.
    /// The gains and what the last control update saw: its error, the
    /// integral and the derivative.
    fn quantities(&self) -> Vec<Quantity> {
        let terms = self.run.last_terms();
        let c = &self.run.controller;
        vec![
            Quantity::new("kp", "K_p", self.gains.kp, 1, "N/m"),
            Quantity::new("ki", "K_i", self.gains.ki, 1, "N/(m·s)"),
            Quantity::new("kd", "K_d", self.gains.kd, 1, "N·s/m"),
            Quantity::new("e", "e", terms.error_m, 4, "m"),
            Quantity::new("ie", "∫e dt", c.integral_m_s(), 4, "m·s"),
            Quantity::new("de", "e\u{307}", c.derivative_m_s(), 4, "m/s"),
            // The measured speed the derivative on the measurement acts on.
            Quantity::new("dy", "x\u{307}", -c.derivative_m_s(), 4, "m/s"),
            Quantity::new("umax", "u_max", self.force_limit_n, 0, "N"),
            Quantity::new("m", "m", self.plant.mass_kg, 1, "kg"),
            Quantity::new("c", "c", self.plant.drag_n_s_per_m, 1, "N·s/m"),
        ]
    }

    fn equations(&self) -> &'static [Equation] {
        PID_LAWS[usize::from(self.saturation)][usize::from(self.derivative_on_measurement)]
    }

    fn readouts(&self) -> Vec<Readout> {
        let x = self.run.state.x_m;
        let info = self.info.ok();
        let y_final = self.final_value_m();
        let (poles, stability) = match self.poles() {
            Some((p, s)) => (
                format_poles(&p),
                match s {
                    Stability::Stable => "stable",
                    Stability::MarginallyStable => "marginally stable",
                    Stability::Unstable => "unstable",
                },
            ),
            None => ("--".into(), "--"),
        };
        let second = SecondOrder::of(&self.plant, &self.gains);
        let (wn, zeta) = second.map_or(("--".into(), "--".into()), |s| {
            (
                format!("{} rad/s", quantity(s.natural_frequency_rad_s, 3)),
                quantity(s.damping_ratio, 3),
            )
        });
        let mut out = vec![
            Readout::metres("x", "Position x", x),
            Readout::metres("error", "Error e = r − x", self.setpoint_m - x),
            Readout::new("force", "Force u", force_text(self.run.last_terms().output)),
            Readout::new(
                "overshoot",
                "Overshoot",
                match (self.info, self.setpoint_info) {
                    (Ok(i), _) => percent(i.overshoot_pct),
                    (Err(NoMetrics::StepTooSmall), _) => STEP_TOO_SMALL.into(),
                    // No final value: how far the cart went past the setpoint.
                    (Err(NoMetrics::NoFinalValue), Some(i)) if i.overshoot_pct > 0.0 => {
                        format!("{} past the setpoint", percent(i.overshoot_pct))
                    }
                    (Err(_), _) => "--".into(),
                },
            ),
            Readout::new(
                "rise",
                "Rise time (10–90 %)",
                seconds(info.or(self.setpoint_info).and_then(|i| i.rise_time_s)),
            ),
            Readout::new(
                "settling",
                "Settling time (±2 %)",
                match (info.and_then(|i| i.settling_time_s), y_final) {
                    (Some(ts), Some(y)) if !at_setpoint(y, self.setpoint_m) => {
                        format!("{} (around {})", seconds(Some(ts)), format_length(y))
                    }
                    (ts, _) => seconds(ts),
                },
            ),
            Readout::new(
                "peak",
                "Peak",
                info.or(self.setpoint_info).map_or("--".into(), |i| {
                    let (peak_m, at_s) = self.peak_so_far(&i);
                    format!("{} at {} s", format_metres(peak_m), format_fixed(at_s, 2))
                }),
            ),
            Readout::new(
                "sse",
                "Steady-state error",
                y_final.map_or("--".into(), |y| {
                    // The linear loop's prediction until the run has settled.
                    let reached = self.state == RunState::Quiet
                        || info.is_some_and(|i| i.settling_time_s.is_some());
                    if reached {
                        format_length(self.setpoint_m - y)
                    } else {
                        format!("{} (predicted)", format_length(self.setpoint_m - y))
                    }
                }),
            ),
            Readout::new("poles", "Closed-loop poles (1/s)", poles),
            Readout::new("stability", "Linear loop", stability),
            Readout::new("wn", "Natural frequency ωn (Ki = 0)", wn),
            Readout::new("zeta", "Damping ratio ζ (Ki = 0)", zeta),
        ];
        const PIN_KEYS: [&str; MAX_PINS] = ["pinA", "pinB", "pinC", "pinD"];
        const PIN_LABELS: [&str; MAX_PINS] = [
            "Pinned run A",
            "Pinned run B",
            "Pinned run C",
            "Pinned run D",
        ];
        let mut pins: Vec<&Pin> = self.pins.iter().collect();
        pins.sort_by_key(|p| p.slot);
        for pin in pins {
            let metrics = match pin.info {
                Ok(i) => format!(
                    "overshoot {}, rise {}, settling {}",
                    percent(i.overshoot_pct),
                    seconds(i.rise_time_s),
                    seconds(i.settling_time_s)
                ),
                Err(NoMetrics::NoFinalValue) => "no metrics (no final value)".into(),
                Err(NoMetrics::StepTooSmall) => format!("overshoot {STEP_TOO_SMALL}"),
                Err(NoMetrics::NotYet) => "no metrics yet".into(),
            };
            let partial = if pin.finished {
                String::new()
            } else {
                format!(", so far (pinned at {})", seconds(Some(pin.time_s)))
            };
            out.push(Readout::new(
                PIN_KEYS[pin.slot],
                PIN_LABELS[pin.slot],
                format!("{}, {metrics}{partial}", pin.gains_text()),
            ));
        }
        out
    }

    fn status(&self) -> Status {
        let why_unstable = || match self.poles().map(|(_, s)| s) {
            Some(Stability::Unstable) => "the loop is unstable",
            Some(Stability::MarginallyStable) => "the loop is only marginally stable",
            _ => "the overshoot carried it past the end",
        };
        match self.state {
            RunState::Running => match settled_text(self) {
                Some(text) => Status::new(text, Tone::Good),
                None => Status::new(
                    format!("stepping to {}", format_metres(self.setpoint_m)),
                    Tone::Neutral,
                ),
            },
            RunState::OffTrack => Status::ended(
                format!(
                    "off the track at {}: {}",
                    format_metres(TRACK_END_M.copysign(self.position_m())),
                    why_unstable()
                ),
                Tone::Bad,
            ),
            RunState::Diverged => Status::ended(format!("diverged: {}", why_unstable()), Tone::Bad),
            RunState::Quiet | RunState::Complete => match (self.info, self.final_value_m()) {
                (
                    Ok(StepInfo {
                        settling_time_s: Some(_),
                        ..
                    }),
                    Some(_),
                ) => Status::ended(settled_text(self).unwrap_or_default(), Tone::Good),
                (Err(NoMetrics::StepTooSmall), Some(_)) => {
                    Status::ended("at rest: the step is under 1 mm", Tone::Neutral)
                }
                (_, Some(_)) => Status::ended(
                    format!("not settled after {} s", format_fixed(self.time_s(), 0)),
                    Tone::Warning,
                ),
                // Recorded in full with no final value to settle at: the cart
                // may still be swinging, so no "at rest".
                (_, None) if self.run.state.v_m_s.abs() < QUIET_MIN_M => {
                    Status::ended("at rest", Tone::Neutral)
                }
                (_, None) => Status::ended(
                    format!(
                        "{} s recorded: the loop has no final value",
                        format_fixed(self.time_s(), 0)
                    ),
                    Tone::Warning,
                ),
            },
        }
    }

    fn notice(&self) -> Option<Notice> {
        self.notices.current()
    }

    /// The run's state from the model's evidence: running while the state is
    /// [`RunState::Running`], otherwise ended (settled, recorded in full, off the
    /// track or diverged), so the page offers Replay.
    /// "Cart at 1.075 m, setpoint 1.000 m, error -0.075 m; overshoot 7.8%, rise
    /// time 0.82 s, settling time --; stepping to 1.000 m."
    fn describe(&self) -> String {
        let value = |key| crate::experiment::readout_value(self, key).unwrap_or_default();
        format!(
            "Cart at {}, setpoint {}, error {}; overshoot {}, rise time {}, settling time {}; {}.",
            value("x"),
            format_metres(self.setpoint_m),
            value("error"),
            value("overshoot"),
            value("rise"),
            value("settling"),
            self.status().text
        )
    }

    fn hint(&self) -> &'static str {
        "Drag the setpoint marker or use the sliders; each change replays the step. Pin run keeps a response to compare gains."
    }

    /// A finished default step response with one pinned run for comparison.
    fn preview(&mut self) {
        self.gains.kd = 2.0;
        self.restart();
        while self.state == RunState::Running {
            self.step(0.1);
        }
        self.pin();
        self.gains.kd = PARAMS[2].default;
        self.restart();
        for _ in 0..30 {
            self.step(0.1);
        }
    }
}
