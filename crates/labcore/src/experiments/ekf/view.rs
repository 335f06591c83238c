//! What experiment 11 shows: the scene, the readouts and the status.
//! Only reads the state.

use super::{
    position_trace, EkfExperiment, Filter, FILTER_DT_S, INSIDE_NEEDED, LOOP_RADIUS_M, TRAIL_DR,
    TRAIL_EKF, TRAIL_TRUTH,
};
use crate::estimation::consistency::{
    covariance_ellipse, heading_error_rad, pose_error, position_block, position_error_m,
};
use crate::experiment::{Notice, Presentation, Readout, Status, Tone};
use crate::live_math::{four_significant, Equation, Expr, Quantity};
use crate::scene::{Item, Role, Scene, ViewBox};
use crate::units::{format_fixed, format_magnitude};
use glam::{DMat2, DMat3, DVec2, DVec3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The canvas shows a square of this half-width around the loop's centre,
/// metres, ...
const VIEW_HALF_M: f64 = 4.7;
/// ... and this much more above it, metres.
const VIEW_HEADROOM_M: f64 = 1.2;

const EX: Expr = Expr::Var("ex");
const EY: Expr = Expr::Var("ey");
const ETH: Expr = Expr::Var("eth");
const TWO: Expr = Expr::Num(2.0, "2");
/// `2 Λ_ij e_i e_j`, the off-diagonal terms of the quadratic form.
const CROSS_XY: Expr = Expr::Mul(&Expr::Mul(&Expr::Mul(&TWO, &Expr::Var("lxy")), &EX), &EY);
const CROSS_XT: Expr = Expr::Mul(&Expr::Mul(&Expr::Mul(&TWO, &Expr::Var("lxt")), &EX), &ETH);
const CROSS_YT: Expr = Expr::Mul(&Expr::Mul(&Expr::Mul(&TWO, &Expr::Var("lyt")), &EY), &ETH);
/// The position error, the position uncertainty and the normalised
/// estimation error squared `eᵀ P⁻¹ e` (Bar-Shalom, Li & Kirubarajan,
/// *Estimation with Applications to Tracking and Navigation*, §5.4),
/// written out with the information matrix `Λ = P⁻¹` as the filter inverts it.
/// Where no reading has been folded in (or the filter maps as it goes).
const NO_READING: &str = "No reading folded in yet, or the filter maps as it goes (SLAM), where the panel follows no single reading.";
const EQUATIONS: &[Equation] = &[
    Equation {
        key: "innovation_range",
        symbol: "ν_r",
        expr: Expr::Sub(&Expr::Var("zr"), &Expr::Var("zhr")),
        readout: "innov_r",
        caption: "The innovation of the last observation folded in: the range measured less the range the estimate predicted …",
        absent: NO_READING,
    },
    Equation {
        key: "innovation_bearing",
        symbol: "ν_φ",
        expr: Expr::Sub(&Expr::Var("zb"), &Expr::Var("zhb")),
        readout: "innov_b",
        caption: "… and the same for its bearing φ (the prediction taken within half a turn of the measurement).",
        absent: NO_READING,
    },
    Equation {
        key: "error",
        symbol: "|e|",
        expr: Expr::Sqrt(&Expr::Add(&Expr::Sq(&EX), &Expr::Sq(&EY))),
        readout: "error",
        caption: "The position error: how far the estimate sits from the truth, e = truth − estimate.",
        absent: "",
    },
    Equation {
        key: "trace",
        symbol: "σ²",
        expr: Expr::Add(&Expr::Var("pxx"), &Expr::Var("pyy")),
        readout: "trace",
        caption: "The position uncertainty: the variances in x and y from the covariance P added.",
        absent: "",
    },
    Equation {
        key: "nees",
        symbol: "ε",
        expr: Expr::Add(
            &Expr::Add(
                &Expr::Add(
                    &Expr::Add(
                        &Expr::Add(
                            &Expr::Mul(&Expr::Var("lxx"), &Expr::Sq(&EX)),
                            &Expr::Mul(&Expr::Var("lyy"), &Expr::Sq(&EY)),
                        ),
                        &Expr::Mul(&Expr::Var("ltt"), &Expr::Sq(&ETH)),
                    ),
                    &CROSS_XY,
                ),
                &CROSS_XT,
            ),
            &CROSS_YT,
        ),
        readout: "nees",
        caption: "The NEES ε = eᵀP⁻¹e over the pose error e = (ex, ey, eθ), with Λ = P⁻¹: about 3 on average when the filter is honest about its uncertainty.",
        absent: "No NEES: the covariance P cannot be inverted.",
    },
];

/// Position error readouts and the 3σ ellipse come from this.
fn ellipse(center: DVec2, cov: DMat2) -> Item {
    let (a, b, phi) = covariance_ellipse(cov, 3.0);
    let (s, c) = crate::math::sin_cos(phi);
    Item::Ellipse {
        center,
        semi_axis_a: DVec2::new(c, s) * a,
        semi_axis_b: DVec2::new(-s, c) * b,
        role: Role::Estimate,
    }
}

/// A robot outline at `pose`: a dart 0.36 m long.
pub(super) fn robot_outline(pose: DVec3) -> Vec<DVec2> {
    let (s, c) = crate::math::sin_cos(pose.z);
    let at = |x: f64, y: f64| pose.truncate() + DVec2::new(c * x - s * y, s * x + c * y);
    vec![
        at(0.22, 0.0),
        at(-0.14, 0.13),
        at(-0.07, 0.0),
        at(-0.14, -0.13),
    ]
}

/// A five-pointed star of outer radius `r` at `c` (a landmark).
fn star(c: DVec2, r: f64) -> Vec<DVec2> {
    (0..10)
        .map(|k| {
            let a = FRAC_PI_2 + k as f64 * PI / 5.0;
            let rr = if k % 2 == 0 { r } else { 0.45 * r };
            let (s, co) = crate::math::sin_cos(a);
            c + DVec2::new(co, s) * rr
        })
        .collect()
}

impl Presentation for EkfExperiment {
    /// The landmarks with a margin, and headroom at the top for the status
    /// badge that overlays the canvas there.
    fn view(&self) -> ViewBox {
        ViewBox {
            min: DVec2::splat(-VIEW_HALF_M),
            max: DVec2::new(VIEW_HALF_M, VIEW_HALF_M + VIEW_HEADROOM_M),
        }
    }

    fn scene(&self, out: &mut Scene) {
        let run = &self.live;
        out.push(Item::Circle {
            center: DVec2::ZERO,
            radius_m: LOOP_RADIUS_M,
            role: Role::Grid,
            fill: false,
            dashed: true,
        });
        // The sensor's field of view from the true pose.
        let settings = self.settings();
        let sensor = settings.sensor;
        let truth = run.truth;
        let fov = sensor.fov_rad.min(TAU);
        let arc_points = 24;
        let mut wedge = Vec::with_capacity(arc_points + 2);
        if fov < TAU - 1e-9 {
            wedge.push(truth.truncate());
        }
        for k in 0..=arc_points {
            let a = truth.z - 0.5 * fov + fov * k as f64 / arc_points as f64;
            let (s, c) = crate::math::sin_cos(a);
            wedge.push(truth.truncate() + DVec2::new(c, s) * sensor.max_range_m);
        }
        out.push(Item::Polyline {
            points: wedge,
            width_px: 1.0,
            role: Role::Bound,
            dashed: true,
            closed: true,
        });
        let trail_style = [
            (TRAIL_TRUTH, Role::Robot, false),
            (TRAIL_EKF, Role::Estimate, false),
            (TRAIL_DR, Role::Ghost, true),
        ];
        for (k, role, dashed) in trail_style {
            out.push(Item::Polyline {
                points: self.trails[k].iter().copied().collect(),
                width_px: 1.5,
                role,
                dashed,
                closed: false,
            });
        }
        for &m in &self.landmarks {
            out.push(Item::Polygon {
                points: star(m, 0.18),
                role: Role::Accent,
            });
        }
        if let Filter::Slam(slam) = &run.filter {
            for &id in slam.landmark_ids() {
                if let Some((m, cov)) = slam.landmark(id) {
                    out.push(ellipse(m, cov));
                    out.push(Item::Dot {
                        center: m,
                        radius_px: 3.0,
                        role: Role::Estimate,
                    });
                }
            }
        }
        for z in run.flashing() {
            let (s, c) = crate::math::sin_cos(truth.z + z.bearing_rad);
            out.push(Item::Line {
                from: truth.truncate(),
                to: truth.truncate() + DVec2::new(c, s) * z.range_m,
                width_px: 2.0,
                role: Role::Path,
                dashed: false,
            });
        }
        out.push(Item::Polyline {
            points: robot_outline(run.dead_reckoning),
            width_px: 1.5,
            role: Role::Ghost,
            dashed: true,
            closed: true,
        });
        let est = run.estimate();
        let uncertainty = ellipse(est.truncate(), position_block(run.pose_cov()));
        // What the innovation, σ² and NEES name (issue 27 §3): P's 3σ
        // ellipse; the error e from the estimate to the truth, across (e_x),
        // up (e_y) and in heading (e_θ); and the landmark the last
        // observation folded in saw: measured from the truth (z), predicted
        // from the estimate (ẑ), range and bearing.
        if let Item::Ellipse {
            center,
            semi_axis_a,
            semi_axis_b,
            ..
        } = uncertainty
        {
            out.tag_ellipse("pxx", center, semi_axis_a, semi_axis_b);
            out.tag_ellipse("pyy", center, semi_axis_a, semi_axis_b);
        }
        out.push(uncertainty);
        let (at, seen) = (est.truncate(), truth.truncate());
        let corner = DVec2::new(seen.x, at.y);
        out.tag_lines(&[("ex", at, corner), ("ey", corner, seen)]);
        out.tag_arc("eth", at, 0.5, est.z, est.z + pose_error(truth, est).z);
        if let Some((z, u)) = run.last_update() {
            let sighted = run
                .observations
                .iter()
                .find(|o| o.z() == z)
                .and_then(|o| self.landmarks.get(o.id));
            if let Some(&m) = sighted {
                out.tag_lines(&[("zr", seen, m), ("zhr", at, m)]);
                out.tag_arc("zb", seen, 0.5, truth.z, truth.z + z.y);
                out.tag_arc("zhb", at, 0.7, est.z, est.z + z.y - u.innovation.y);
            }
        }
        out.push(Item::Polygon {
            points: robot_outline(est),
            role: Role::Estimate,
        });
        out.push(Item::Polygon {
            points: robot_outline(truth),
            role: Role::Robot,
        });
    }

    fn readouts(&self) -> Vec<Readout> {
        let run = &self.live;
        let (truth, est, cov) = (run.truth, run.estimate(), run.pose_cov());
        let per_loop = match run.obs_last_lap {
            Some(n) => n.to_string(),
            None => format!("{} so far", run.obs_this_lap),
        };
        let mapped = match &run.filter {
            Filter::Localisation(_) => format!("{} (known map)", self.landmarks.len()),
            Filter::Slam(s) => format!("{} of {}", s.landmark_count(), self.landmarks.len()),
        };
        let anees = self
            .check_result()
            .map_or("--".into(), |r| format_fixed(r.mean_anees, 2));
        let verdict = match &self.check {
            Some(c) if c.finished() && c.result.is_some() => self.status().text,
            _ => "--".into(),
        };
        vec![
            Readout::metres("error", "Position error", position_error_m(truth, est)),
            Readout::degrees(
                "heading_error",
                "Heading error",
                heading_error_rad(truth, est).to_degrees(),
            ),
            Readout::metres(
                "innov_r",
                "Innovation ν, range",
                run.last_update().map_or(f64::NAN, |(_, u)| u.innovation.x),
            ),
            Readout::degrees(
                "innov_b",
                "Innovation ν, bearing",
                run.last_update()
                    .map_or(f64::NAN, |(_, u)| u.innovation.y.to_degrees()),
            ),
            Readout::new(
                "trace",
                "Position uncertainty σx² + σy²",
                trace_text(position_trace(cov)),
            ),
            Readout::new(
                "nees",
                "NEES",
                run.nees().map_or("--".into(), |v| format_fixed(v, 2)),
            ),
            Readout::new("obs_per_loop", "Observations per loop", per_loop),
            Readout::metres(
                "dr_error",
                "Dead-reckoning error",
                position_error_m(truth, run.dead_reckoning),
            ),
            Readout::new("landmarks", "Landmarks", mapped),
            Readout::new("anees", "Average NEES (check)", anees),
            // The check's verdict with its band, in full: the badge cuts it
            // on a narrow screen (issue 53 §5).
            Readout::new("verdict", "Consistency verdict", verdict),
        ]
    }

    /// The pose error, the covariance's position variances and the
    /// information matrix `Λ = P⁻¹`, each to four significant digits.
    fn quantities(&self) -> Vec<Quantity> {
        let run = &self.live;
        let e = crate::estimation::consistency::pose_error(run.truth, run.estimate());
        let cov = run.pose_cov();
        let info = if cov.determinant() > 0.0 {
            cov.inverse()
        } else {
            DMat3::from_diagonal(DVec3::NAN)
        };
        let q =
            |key, symbol, v: f64, unit| Quantity::new(key, symbol, v, four_significant(v), unit);
        // ẑ's bearing as z − ν: the same angle, within half a turn of z.
        let (z, predicted) = run
            .last_update()
            .map_or((DVec2::NAN, DVec2::NAN), |(z, u)| {
                (z, DVec2::new(u.predicted.x, z.y - u.innovation.y))
            });
        vec![
            Quantity::new("zr", "z_r", z.x, 3, "m"),
            Quantity::new("zhr", "z\u{302}_r", predicted.x, 3, "m"),
            Quantity::new("zb", "z_φ", z.y.to_degrees(), 2, "°"),
            Quantity::new("zhb", "z\u{302}_φ", predicted.y.to_degrees(), 2, "°"),
            q("ex", "e_x", e.x, "m"),
            q("ey", "e_y", e.y, "m"),
            q("eth", "e_θ", e.z, "rad"),
            q("pxx", "σ_x²", cov.x_axis.x, "m²"),
            q("pyy", "σ_y²", cov.y_axis.y, "m²"),
            q("lxx", "Λ_xx", info.x_axis.x, "m⁻²"),
            q("lyy", "Λ_yy", info.y_axis.y, "m⁻²"),
            q("ltt", "Λ_θθ", info.z_axis.z, "rad⁻²"),
            q("lxy", "Λ_xy", info.y_axis.x, "m⁻²"),
            q("lxt", "Λ_xθ", info.z_axis.x, "m⁻¹·rad⁻¹"),
            q("lyt", "Λ_yθ", info.z_axis.y, "m⁻¹·rad⁻¹"),
        ]
    }

    /// The Procedure's steps read these beside the main plot.
    fn watched_plots(&self) -> &'static [&'static str] {
        &["nees", "anees"]
    }

    fn equations(&self) -> &'static [Equation] {
        EQUATIONS
    }

    fn status(&self) -> Status {
        if let Some(check) = &self.check {
            if !check.finished() {
                return Status::new(
                    format!("consistency check… {}/{} runs", check.done, check.runs),
                    Tone::Neutral,
                );
            }
            let Some(r) = check.result else {
                return Status::new(
                    "consistency check failed: every run lost its covariance",
                    Tone::Bad,
                );
            };
            let (lo, hi) = r.band;
            let pct = (r.inside * 100.0).round();
            let n = check.counted();
            let detail = format!(
                "average NEES {:.2}, {pct:.0} % of steps inside [{lo:.2}, {hi:.2}] over {n} runs",
                r.mean_anees
            );
            return if r.inside >= INSIDE_NEEDED {
                Status::new(format!("consistent: {detail}"), Tone::Good)
            } else if r.mean_anees > hi {
                Status::new(format!("over-confident: {detail}"), Tone::Bad)
            } else if r.mean_anees < lo {
                Status::new(format!("under-confident: {detail}"), Tone::Warning)
            } else {
                Status::new(format!("inconsistent at times: {detail}"), Tone::Warning)
            };
        }
        match &self.live.filter {
            Filter::Localisation(_) => Status::new("EKF localisation, known map", Tone::Neutral),
            Filter::Slam(s) => Status::new(
                format!(
                    "EKF-SLAM: {} of {} landmarks mapped",
                    s.landmark_count(),
                    self.landmarks.len()
                ),
                Tone::Neutral,
            ),
        }
    }

    fn notice(&self) -> Option<Notice> {
        self.notices.current()
    }

    /// "Robot at (…) m heading 12.0°; the estimate is 0.057 m and -0.8° off
    /// (dead reckoning alone: 0.210 m), its 3σ ellipse has semi-axes 0.093 m
    /// and 0.041 m; landmarks 6 (known map); EKF localisation, known map."
    /// In SLAM, after the landmarks: the widest 3σ semi-axis of the map's
    /// ellipses.
    fn describe(&self) -> String {
        let run = &self.live;
        let truth = run.truth;
        let value = |key| crate::experiment::readout_value(self, key).unwrap_or_default();
        let (a, b, _) = covariance_ellipse(position_block(run.pose_cov()), 3.0);
        let map = match &run.filter {
            Filter::Slam(slam) => slam
                .landmark_ids()
                .iter()
                .filter_map(|&id| slam.landmark(id))
                .map(|(_, cov)| covariance_ellipse(cov, 3.0).0)
                .reduce(f64::max)
                .map_or(String::new(), |w| {
                    format!(
                        ", the widest map ellipse has a semi-axis of {}",
                        crate::units::format_metres(w)
                    )
                }),
            Filter::Localisation(_) => String::new(),
        };
        format!(
            "Robot at {} heading {}; the estimate is {} and {} off (dead reckoning alone: {}), its 3σ ellipse has semi-axes {} and {}; landmarks {}{map}; {}.",
            crate::units::format_point(truth.truncate()),
            crate::units::format_degrees(
                crate::kinematics::two_link_ik::wrap_pi(truth.z).to_degrees()
            ),
            value("error"),
            value("heading_error"),
            value("dr_error"),
            crate::units::format_metres(a),
            crate::units::format_metres(b),
            value("landmarks"),
            self.status().text
        )
    }

    fn hint(&self) -> &'static str {
        "Watch the 3σ ellipse grow between landmark sightings and shrink at each fix; press Consistency check to average NEES over N seeded runs."
    }

    fn preview(&mut self) {
        for _ in 0..(24.0 / FILTER_DT_S) as usize {
            self.advance_live();
        }
    }
}

/// The position uncertainty σx² + σy² with four significant digits
/// (`0.01034 m²`), enough to show the rise of one predict step (step 3 of
/// the Procedure); the magnitude form outside 10⁻³…10³ m².
pub(super) fn trace_text(trace_m2: f64) -> String {
    if (1e-3..1e3).contains(&trace_m2) {
        let decimals = (3 - crate::math::log10(trace_m2).floor() as i32).max(0) as usize;
        format!("{} m²", format_fixed(trace_m2, decimals))
    } else {
        format!("{} m²", format_magnitude(trace_m2))
    }
}
