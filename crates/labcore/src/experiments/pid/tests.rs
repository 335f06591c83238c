//! Tests of experiment 7 (its Procedure is played by `tests/procedures/`).

use super::quiz::*;
use super::view::CART_HALF_W_M;
use super::words::{percent, quantity, seconds};
use super::*;
use crate::experiment::{Phase, Presentation, Status};
use crate::route::restore;
use crate::scene::{Item, Role};
use crate::testkit::{self, readout, reopen, scene_of, set_params, steps};

fn run_to_end(e: &mut PidControl) -> usize {
    let mut frames = 0;
    while e.animating() && frames < 10_000 {
        e.step(1.0 / 60.0);
        frames += 1;
    }
    frames
}

/// `Kp = 25, Kd = 5, c = 1, m = 1, Ki = 0`: `s² + 6 s + 25`, poles
/// `−3 ± 4i`, `ωn = 5`, `ζ = 0.6`.
fn underdamped() -> PidControl {
    let mut e = PidControl::default();
    e.set_param("kp", 25.0).unwrap();
    e.set_param("ki", 0.0).unwrap();
    e.set_param("kd", 5.0).unwrap();
    e
}

#[test]
fn readouts_by_hand_at_the_start() {
    let e = underdamped();
    assert_eq!(readout(&e, "x"), "0.000 m");
    assert_eq!(readout(&e, "error"), "1.000 m");
    assert_eq!(readout(&e, "poles"), "-3.000 ± 4.000i");
    assert_eq!(readout(&e, "stability"), "stable");
    assert_eq!(readout(&e, "wn"), "5.000 rad/s");
    assert_eq!(readout(&e, "zeta"), "0.600");
    assert_eq!(readout(&e, "sse"), "0.000 m (predicted)");
    // Default gains: m s³ + (c + Kd) s² + Kp s + Ki = s³ + 7 s² + 12 s + 2,
    // three real poles, the slowest near −0.187.
    let d = PidControl::default();
    let poles = readout(&d, "poles");
    assert!(poles.starts_with("-0.18"), "{poles}");
    assert_eq!(poles.split(", ").count(), 3, "{poles}");
    assert_eq!(readout(&d, "wn"), "--");
    assert_eq!(readout(&d, "zeta"), "--");
}

/// With `Ki = 0` and the derivative on the measurement the loop is the
/// textbook second-order system `ωn²/(s² + 2ζωn s + ωn²)`: its metrics
/// match the analytic formulas and `step_info` of the exact response.
#[test]
fn second_order_metrics_and_markers_match_the_analytic_response() {
    let mut e = underdamped();
    run_to_end(&mut e);
    let info = e.metrics().expect("metrics");
    let (wn, zeta) = (5.0_f64, 0.6_f64);
    let wd = wn * (1.0 - zeta * zeta).sqrt();
    let overshoot = 100.0 * (-zeta * std::f64::consts::PI / (1.0 - zeta * zeta).sqrt()).exp();
    assert!((info.overshoot_pct - overshoot).abs() < 0.1, "{info:?}");
    assert!(
        (info.peak_time_s - std::f64::consts::PI / wd).abs() <= 0.011,
        "{info:?}"
    );
    // The exact response sampled at the record period.
    let t: Vec<f64> = (0..=3000).map(|k| k as f64 * RECORD_PERIOD_S).collect();
    let y: Vec<f64> = t
        .iter()
        .map(|t| {
            1.0 - (-zeta * wn * t).exp()
                * ((wd * t).cos() + zeta / (1.0 - zeta * zeta).sqrt() * (wd * t).sin())
        })
        .collect();
    let exact = step_info(&t, &y, 0.0, 1.0, Some(1.0)).unwrap();
    let close = |a: Option<f64>, b: Option<f64>| (a.unwrap() - b.unwrap()).abs() <= 0.021;
    assert!(
        close(info.rise_time_s, exact.rise_time_s),
        "{info:?} vs {exact:?}"
    );
    assert!(
        close(info.settling_time_s, exact.settling_time_s),
        "{info:?} vs {exact:?}"
    );
    // Markers sit on the curve at the rise, peak and settling times.
    let markers = &e.plots()[0].markers;
    assert_eq!(markers.len(), 3, "{markers:?}");
    let series = &e.plots()[0].series[0];
    for m in markers {
        let k = series.nearest(m.x).unwrap();
        assert!((series.x[k] - m.x).abs() < 1e-12 && (series.y[k] - m.y).abs() < 1e-12);
    }
    let first_90 = series.y.iter().position(|y| *y >= 0.9).unwrap();
    assert_eq!(markers[0].x, series.x[first_90]);
    assert!(markers[0].label.starts_with("rise "));
    assert_eq!((markers[1].x, markers[1].y), (info.peak_time_s, info.peak));
    assert_eq!(
        markers[1].label,
        format!("peak {}%", format_fixed(info.overshoot_pct, 1))
    );
    assert!((markers[2].x - info.settling_time_s.unwrap()).abs() < 1e-9);
    assert_eq!(
        readout(&e, "overshoot"),
        format!("{}%", format_fixed(info.overshoot_pct, 1))
    );
    assert_eq!(e.status().tone, Tone::Good);
    assert!(e.status().text.starts_with("settled within 2 % after"));
}

#[test]
fn the_cart_reaches_the_setpoint_and_the_run_goes_quiet() {
    let mut e = PidControl::default();
    let frames = run_to_end(&mut e);
    assert!(!e.animating());
    assert!(frames < 10_000);
    assert!((e.position_m() - 1.0).abs() < 2e-3, "{}", e.position_m());
    // Bounded records: at most RECORD_S of samples.
    let n = e.plots()[0].series[0].len();
    assert!(n <= (RECORD_S / RECORD_PERIOD_S) as usize + 1, "{n}");
    // Finished runs ignore further steps.
    let before = e.position_m();
    e.step(1.0 / 60.0);
    assert_eq!(e.position_m(), before);
}

#[test]
fn integral_action_removes_the_offset_of_a_constant_push() {
    let mut p_only = PidControl::default();
    p_only.set_param("ki", 0.0).unwrap();
    p_only.set_param("d", -3.0).unwrap();
    run_to_end(&mut p_only);
    // Kp·e = 3 N → e = 3/12 = 0.25 m.
    assert!(
        (p_only.position_m() - 0.75).abs() < 1e-3,
        "{}",
        p_only.position_m()
    );
    assert_eq!(readout(&p_only, "sse"), "0.250 m");
    let mut pid = PidControl::default();
    pid.set_param("d", -3.0).unwrap();
    run_to_end(&mut pid);
    assert!(
        (pid.position_m() - 1.0).abs() < 2e-3,
        "{}",
        pid.position_m()
    );
    assert_eq!(readout(&pid, "sse"), "0.000 m");
}

/// With `Ki = 0.5` a 5 N push needs `∫e = 10 m·s`, but the clamp stops the
/// integral at 5: the last 2.5 N are left to `Kp`, `e = 2.5/12`.
#[test]
fn the_integral_clamp_bounds_the_integral_and_leaves_the_predicted_offset() {
    let mut e = PidControl::default();
    e.set_param("ki", 0.5).unwrap();
    e.set_param("d", -5.0).unwrap();
    let predicted = 1.0 - 2.5 / 12.0;
    assert!((e.final_value_m().unwrap() - predicted).abs() < 1e-12);
    run_to_end(&mut e);
    assert!(e.run.controller.integral_m_s().abs() <= 5.0 + 1e-12);
    assert!(
        (e.position_m() - predicted).abs() < 2e-3,
        "{}",
        e.position_m()
    );
}

#[test]
fn saturation_is_shaded_and_limits_the_force() {
    let mut e = PidControl::default();
    e.set_param("sat", 1.0).unwrap();
    e.set_param("umax", 5.0).unwrap();
    run_to_end(&mut e);
    let effort = &e.plots()[1];
    assert!(effort.series[0].y.iter().all(|u| u.abs() <= 5.0 + 1e-9));
    assert!(!effort.bands.is_empty());
    let band = &effort.bands[0];
    assert_eq!(band.axis, Axis::X);
    // Saturated from the start: a 1 m error asks Kp·e = 12 N > 5 N.
    assert!(band.lo.abs() < 1e-9 && band.hi > 0.1, "{band:?}");
    assert_eq!(effort.ref_lines.len(), 2);
    // The applied force is the sum of the terms wherever it is not cut.
    let s = &effort.series;
    let inside = |t: f64| {
        effort
            .bands
            .iter()
            .any(|b| t >= b.lo - 1e-9 && t <= b.hi + 1e-9)
    };
    for k in 0..s[0].len() {
        if !inside(s[0].x[k]) {
            let sum = s[1].y[k] + s[2].y[k] + s[3].y[k];
            assert!((s[0].y[k] - sum).abs() < 1e-9, "t = {}", s[0].x[k]);
        }
    }
}

#[test]
fn derivative_on_the_error_kicks_and_on_the_measurement_does_not() {
    let mut on_error = PidControl::default();
    on_error.set_param("dmeas", 0.0).unwrap();
    on_error.step(1.0 / 60.0);
    // The first record period holds the impulse Kd·r = 6 N·s, a mean of
    // 6 N·s / 0.01 s = 600 N, less the damping −Kd·ẋ of the five updates
    // after the kick (ẋ ≈ 6 m/s: about −30 N on average).
    let d0 = on_error.plots()[1].series[3].y[0];
    assert!(d0 > 550.0 && d0 < 600.0, "{d0}");
    let mut on_measurement = PidControl::default();
    on_measurement.step(1.0 / 60.0);
    let d0 = on_measurement.plots()[1].series[3].y[0];
    assert!(d0.abs() < 1.0, "{d0}");
}

#[test]
fn unstable_gains_diverge_and_say_so() {
    let mut e = PidControl::default();
    // m s³ + 0·s² + s + 5: no damping at all, poles in the right half-plane.
    for (k, v) in [("c", 0.0), ("kd", 0.0), ("kp", 1.0), ("ki", 5.0)] {
        e.set_param(k, v).unwrap();
    }
    assert_eq!(readout(&e, "stability"), "unstable");
    run_to_end(&mut e);
    assert_eq!(e.status().tone, Tone::Bad);
    assert!(e.position_m().abs() > TRACK_END_M);
    // Issue 23: what it reached, against the setpoint (it has no final value).
    assert!(readout(&e, "overshoot").ends_with("% past the setpoint"));
    let scene = scene_of(&e);
    assert!(scene.is_finite());
}

#[test]
fn pinned_runs_keep_their_gains_and_metrics() {
    let mut e = underdamped();
    // The slot series exist from the start (the page's legend is fixed).
    let labels: Vec<&str> = e.plots()[0]
        .series
        .iter()
        .map(|s| s.label.as_str())
        .collect();
    assert_eq!(
        labels,
        [
            "position x",
            "pinned run A",
            "pinned run B",
            "pinned run C",
            "pinned run D"
        ]
    );
    assert!(e.plots()[0].series[1..].iter().all(Series::is_empty));
    run_to_end(&mut e);
    let first = e.metrics().unwrap();
    let curve = e.plots()[0].series[0].clone();
    e.action("pin").unwrap();
    e.set_param("kd", 10.0).unwrap();
    run_to_end(&mut e);
    e.action("pin").unwrap();
    let response = &e.plots()[0];
    assert_eq!(
        (&response.series[1].x, &response.series[1].y),
        (&curve.x, &curve.y)
    );
    assert_eq!(response.series[2].len(), response.series[0].len());
    assert_eq!(response.series[1].role, SeriesRole::Secondary);
    assert_eq!(response.series[2].role, SeriesRole::Tertiary);
    assert_eq!(e.pins()[0].info, Ok(first));
    assert_eq!(
        readout(&e, "pinA"),
        format!(
            "Kp 25 · Ki 0 · Kd 5, overshoot {}, rise {}, settling {}",
            percent(first.overshoot_pct),
            seconds(first.rise_time_s),
            seconds(first.settling_time_s)
        )
    );
    assert!(readout(&e, "pinB").starts_with("Kp 25 · Ki 0 · Kd 10, overshoot "));
    // More damping, less overshoot.
    assert!(e.pins()[1].info.unwrap().overshoot_pct < first.overshoot_pct);
    // A replayed step keeps the pins; the fifth pin replaces the oldest (slot A).
    e.action("step").unwrap();
    assert_eq!(e.plots()[0].series[1].x, curve.x);
    e.set_param("kd", 1.0).unwrap();
    for _ in 0..3 {
        e.action("pin").unwrap();
    }
    assert_eq!(e.pins().len(), MAX_PINS);
    let numbers: Vec<(usize, usize)> = e.pins().iter().map(|p| (p.number, p.slot)).collect();
    assert_eq!(numbers, [(2, 1), (3, 2), (4, 3), (5, 0)]);
    assert!(readout(&e, "pinA").starts_with("Kp 25 · Ki 0 · Kd 1, "));
    // Pinned mid-run: the metrics are marked as those so far.
    assert!(
        readout(&e, "pinA").ends_with(", so far (pinned at 0.00 s)"),
        "{}",
        readout(&e, "pinA")
    );
    assert!(!readout(&e, "pinB").contains("so far"));
    let keys: Vec<&str> = e
        .readouts()
        .iter()
        .map(|r| r.key)
        .filter(|k| k.starts_with("pin"))
        .collect();
    assert_eq!(keys, ["pinA", "pinB", "pinC", "pinD"]);
    e.action("clear_pins").unwrap();
    assert_eq!(e.plots()[0].series.len(), 1 + MAX_PINS);
    assert!(e.plots()[0].series[1..].iter().all(Series::is_empty));
    assert!(e.readouts().iter().all(|r| !r.key.starts_with("pin")));
}

#[test]
fn dragging_the_marker_sets_the_setpoint_to_the_centimetre() {
    let mut e = PidControl::default();
    assert!(e.handle_at(DVec2::new(1.0, 0.5), 0.1));
    assert!(!e.handle_at(DVec2::new(0.0, 0.5), 0.1));
    e.step(0.05);
    e.input(Input::PointerDown(DVec2::new(-1.234, 0.4)));
    assert_eq!(e.param("r"), Some(-1.23));
    assert_eq!(e.time_s(), 0.0, "the step restarts");
    e.input(Input::Nudge(DVec2::new(0.05, 0.0)));
    assert!((e.param("r").unwrap() + 1.18).abs() < 1e-12);
    e.input(Input::PointerMove {
        pos: DVec2::new(9.0, 0.0),
        pressed: true,
    });
    assert_eq!(e.param("r"), Some(2.0), "kept in the slider's range");
    e.input(Input::PointerMove {
        pos: DVec2::new(f64::NAN, 0.0),
        pressed: true,
    });
    assert_eq!(e.param("r"), Some(2.0));
}

#[test]
fn every_parameter_round_trips_through_the_link() {
    let mut e = PidControl::default();
    for (k, v) in [
        ("kp", 30.5),
        ("ki", 0.3),
        ("kd", 2.2),
        ("r", -0.75),
        ("c", 0.4),
        ("m", 2.5),
        ("d", 1.5),
        ("dmeas", 0.0),
        ("sat", 1.0),
        ("umax", 40.0),
        ("ilim", 2.5),
        ("noise", 0.004),
        ("tf", 0.05),
        ("seed", 42.0),
    ] {
        e.set_param(k, v).unwrap();
    }
    let mut fresh = reopen(&e);
    // The same settings replay the same (noisy) run.
    for _ in 0..120 {
        e.step(1.0 / 60.0);
        fresh.step(1.0 / 60.0);
    }
    assert_eq!(e.position_m(), fresh.position_m());
}

#[test]
fn noise_is_seeded_and_the_filter_calms_the_derivative() {
    let spread = |tf: f64, seed: f64| {
        let mut e = PidControl::default();
        e.set_param("noise", 0.005).unwrap();
        e.set_param("seed", seed).unwrap();
        e.set_param("tf", tf).unwrap();
        steps(&mut e, 600);
        let d = &e.plots()[1].series[3].y;
        let tail = &d[d.len() - 300..];
        let mean = tail.iter().sum::<f64>() / tail.len() as f64;
        (tail.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / tail.len() as f64).sqrt()
    };
    let raw = spread(0.0, 1.0);
    let filtered = spread(0.05, 1.0);
    assert!(filtered < raw / 3.0, "raw {raw}, filtered {filtered}");
    assert_eq!(spread(0.0, 1.0), raw, "same seed, same noise");
    assert_ne!(spread(0.0, 2.0), raw);
}

#[test]
fn bad_steps_and_inputs_change_nothing() {
    let mut e = PidControl::default();
    e.step(0.1);
    let before = (e.position_m(), e.time_s(), e.plots()[0].clone());
    for dt in [f64::NAN, -1.0, 0.0, 0.2, f64::INFINITY] {
        e.step(dt);
    }
    assert_eq!((e.position_m(), e.time_s(), e.plots()[0].clone()), before);
    assert!(e.set_param("kp", f64::NAN).is_err());
    assert!(e.set_param("nope", 1.0).is_err());
    assert!(e.action("nope").is_err());
    assert_eq!(e.time_s(), before.1);
}

#[test]
fn quiz_generators_agree_with_the_formulas() {
    let mut rng = Lcg64::new(5);
    for _ in 0..200 {
        let d = quiz_offset(&mut rng);
        let (kp, push) = (d.var("kp").unwrap(), d.var("d").unwrap());
        assert!((d.answer - push / kp).abs() < 1e-12);
        let d = quiz_damping_ratio(&mut rng);
        let (m, c, kp, kd) = (
            d.var("m").unwrap(),
            d.var("c").unwrap(),
            d.var("kp").unwrap(),
            d.var("kd").unwrap(),
        );
        assert!((d.answer - (c + kd) / (2.0 * (m * kp).sqrt())).abs() < 1e-12);
        assert!(d.answer > 0.0 && d.answer < 1.0, "{}", d.answer);
        let d = quiz_natural_frequency(&mut rng);
        assert!((d.answer - (d.var("kp").unwrap() / d.var("m").unwrap()).sqrt()).abs() < 1e-12);
        let d = quiz_overshoot(&mut rng);
        let z = d.var("zeta").unwrap();
        let expected = 100.0 * (-z * std::f64::consts::PI / (1.0 - z * z).sqrt()).exp();
        assert!((d.answer - expected).abs() < 1e-9);
    }
}

/// Every text a student can read: readouts, status, notice, marker labels,
/// legend names and scene labels.
fn all_texts(e: &PidControl) -> Vec<String> {
    let mut texts: Vec<String> = e.readouts().into_iter().map(|r| r.value).collect();
    texts.push(e.status().text);
    texts.extend(e.notice().map(|n| n.text));
    for plot in e.plots() {
        texts.extend(plot.markers.iter().map(|m| m.label.clone()));
        texts.extend(plot.series.iter().map(|s| s.label.clone()));
    }
    let scene = scene_of(e);
    for item in &scene.items {
        if let Item::Label { text, .. } | Item::OffView { label: text, .. } = item {
            texts.push(text.clone());
        }
    }
    texts
}

/// Issue 14: with sensor noise, a setpoint of `−5·10⁻³²⁴` m made the
/// overshoot "inf%" and `10⁻⁹` m made it "776555891.3%" (readout, peak
/// marker, pinned runs). A step under 1 mm has no overshoot to speak of.
#[test]
fn the_overshoot_of_a_step_near_zero_reads_step_under_1_mm() {
    for r in [-5e-324, 1e-9, -4e-4] {
        let mut e = PidControl::default();
        e.set_param("noise", 0.05).unwrap();
        e.set_param("r", r).unwrap();
        steps(&mut e, 120);
        e.action("pin").unwrap();
        run_to_end(&mut e);
        e.action("pin").unwrap();
        assert_eq!(readout(&e, "overshoot"), view::STEP_TOO_SMALL, "r = {r}");
        assert_eq!(e.metrics(), None);
        assert!(
            e.plots()[0].markers.is_empty(),
            "{:?}",
            e.plots()[0].markers
        );
        assert!(e.plots()[0].bands.is_empty(), "no ±2 % band around 0");
        for pin in ["pinA", "pinB"] {
            assert!(
                readout(&e, pin).contains(view::STEP_TOO_SMALL),
                "{}",
                readout(&e, pin)
            );
        }
        for text in all_texts(&e) {
            assert!(!text.contains("inf") && text.len() < 120, "r = {r}: {text}");
        }
    }
    // A millimetre step is measured as before.
    let mut e = PidControl::default();
    e.set_param("r", 0.01).unwrap();
    run_to_end(&mut e);
    assert!(readout(&e, "overshoot").ends_with('%'));
}

/// Issue 14: ζ was printed with 150 digits at `kp = 1e-300`. Every computed
/// quantity uses the shared magnitude form beyond the everyday range.
#[test]
fn extreme_gains_print_every_quantity_in_a_few_characters() {
    let mut e = PidControl::default();
    for (k, v) in [("kp", 1e-300), ("ki", 0.0), ("d", -3.0)] {
        e.set_param(k, v).unwrap();
    }
    assert_eq!(readout(&e, "wn"), "1.0 × 10⁻¹⁵⁰ rad/s");
    assert_eq!(readout(&e, "zeta"), "3.5 × 10¹⁵⁰");
    assert!(readout(&e, "sse").chars().count() < 20);
    e.action("pin").unwrap();
    assert!(e.plots()[0].series[1]
        .label
        .starts_with("A: Kp 1.0 × 10⁻³⁰⁰, Kd 6"));
    run_to_end(&mut e);
    for (k, v) in [("kp", 1e-300), ("ki", 1e-300), ("kd", 40.0), ("m", 10.0)] {
        e.set_param(k, v).unwrap();
        steps(&mut e, 60);
        for text in all_texts(&e) {
            assert!(text.chars().count() < 120, "{k}: {text}");
        }
    }
    assert_eq!(quantity(0.6, 3), "0.600");
    assert_eq!(quantity(-3.0, 3), "-3.000");
    assert_eq!(quantity(0.0, 3), "0.000");
    assert_eq!(quantity(3.5e150, 3), "3.5 × 10¹⁵⁰");
    assert_eq!(percent(776_555_891.3), "7.8 × 10⁸%");
}

/// Issue 23 §5: values under about 10⁻³⁰⁸ printed as "inf × 10⁻³⁰⁹" in
/// the poles readout, the force readout and a pinned run's legend. The three
/// ways the issue reached it, from a link or a setting.
#[test]
fn format_magnitude_prints_no_inf_for_the_three_links_of_the_issue() {
    let no_inf = |e: &PidControl, case: &str| {
        for text in all_texts(e) {
            assert!(
                !text.contains("inf") && !text.contains("NaN"),
                "{case}: {text}"
            );
        }
    };
    let (mut e, _) = restore(
        "#/pid/simulation?ki=2.2250738585072014e-308",
        PidControl::default(),
    );
    steps(&mut e, 30);
    assert!(
        readout(&e, "poles").starts_with("-1.9 × 10⁻³⁰⁹"),
        "{}",
        readout(&e, "poles")
    );
    no_inf(&e, "ki link");
    let mut e = PidControl::default();
    e.set_param("r", 2.225_073_858_507_201e-308).unwrap();
    steps(&mut e, 30);
    no_inf(&e, "r");
    let (mut e, _) = restore("#/pid/simulation?kd=5e-324", PidControl::default());
    e.action("pin").unwrap();
    assert_eq!(
        e.plots()[0].series[1].label,
        "A: Kp 12, Ki 2, Kd 4.9 × 10⁻³²⁴"
    );
    no_inf(&e, "kd link, pinned");
}

/// Issue 13 §1 (step 8) and §4: the run stops where the drawn track ends,
/// the cart stays in view, and the status says the run is over.
#[test]
fn the_track_the_view_and_the_stop_agree() {
    let mut e = PidControl::default();
    for (k, v) in [("c", 0.0), ("kd", 0.0), ("kp", 1.0), ("ki", 5.0)] {
        e.set_param(k, v).unwrap();
    }
    assert_eq!(e.status().phase, Phase::Live);
    run_to_end(&mut e);
    let x = e.position_m();
    assert!(x.abs() > TRACK_END_M && x.abs() < TRACK_END_M + 0.05, "{x}");
    let view = e.view();
    assert!(x - CART_HALF_W_M > view.min.x && x + CART_HALF_W_M < view.max.x);
    let status = e.status();
    assert_eq!(status.phase, Phase::Ended);
    assert_eq!(status.tone, Tone::Bad);
    assert_eq!(
        status.text,
        format!(
            "off the track at {}: the loop is unstable",
            format_metres(TRACK_END_M.copysign(x))
        )
    );
    // The track drawn ends at ±TRACK_END_M.
    let scene = scene_of(&e);
    let track_ends: Vec<f64> = scene
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Line {
                from,
                to,
                role: Role::Bound,
                ..
            } if from.y == 0.0 && to.y == 0.0 => Some(to.x),
            _ => None,
        })
        .collect();
    assert_eq!(track_ends, [TRACK_END_M]);
    assert!(view.min.x < -TRACK_END_M && view.max.x > TRACK_END_M);
}

/// Issue 13 §3: a cart beyond the view is marked at the canvas edge. A run
/// stops at the track's end, inside the view, so only a cart launched at
/// more than 180 m/s could get there; the view is checked on such a state.
#[test]
fn a_cart_beyond_the_view_is_marked_at_the_edge() {
    let off_view = |e: &PidControl| {
        let scene = scene_of(e);
        scene.items.iter().find_map(|i| match i {
            Item::OffView { at, label, .. } => Some((*at, label.clone())),
            _ => None,
        })
    };
    let mut e = PidControl::default();
    assert_eq!(off_view(&e), None);
    e.run.state.x_m = 3.25;
    let (at, label) = off_view(&e).expect("an edge mark");
    assert_eq!(at.x, 3.25);
    assert_eq!(label, "cart at 3.250 m");
    e.run.state.x_m = -4e6;
    assert_eq!(off_view(&e).unwrap().1, "cart at -4.0 × 10⁶ m");
    // Extreme runs: at every frame the cart is in view or marked.
    for (kd, tf, m) in [(40.0, 0.1, 0.2), (40.0, 0.0, 0.2), (0.0, 0.0, 0.2)] {
        let mut e = PidControl::default();
        for (k, v) in [
            ("m", m),
            ("kd", kd),
            ("dmeas", 0.0),
            ("r", 2.0),
            ("kp", 100.0),
            ("ki", 50.0),
            ("c", 0.0),
            ("tf", tf),
        ] {
            e.set_param(k, v).unwrap();
        }
        while e.animating() {
            e.step(1.0 / 60.0);
            let x = e.position_m();
            let view = e.view();
            assert!((view.min.x..=view.max.x).contains(&x) || off_view(&e).is_some());
        }
        assert_eq!(e.status().phase, Phase::Ended);
    }
}

/// Issue 13 §4: a run that has settled, recorded in full, or left the
/// track has ended; a running one is live.
#[test]
fn a_finished_run_has_ended_and_a_running_one_is_live() {
    let mut e = PidControl::default();
    e.step(1.0 / 60.0);
    assert_eq!(e.status().phase, Phase::Live);
    assert!(e.status().text.starts_with("stepping to 1.000 m"));
    run_to_end(&mut e);
    assert_eq!(e.status().phase, Phase::Ended);
    assert_eq!(e.status().tone, Tone::Good);
    // A noisy run records its full 30 s, then ends.
    e.set_param("noise", 0.01).unwrap();
    assert_eq!(e.status().phase, Phase::Live);
    run_to_end(&mut e);
    assert!((e.time_s() - RECORD_S).abs() < 1e-9);
    assert_eq!(e.status().phase, Phase::Ended);
    // Nothing holds the cart (Kp = Ki = 0): it ends at rest.
    let mut e = PidControl::default();
    e.set_param("kp", 0.0).unwrap();
    e.set_param("ki", 0.0).unwrap();
    run_to_end(&mut e);
    assert_eq!(e.status(), Status::ended("at rest", Tone::Neutral));
}

/// Issue 13 §4: messages about a pin are notices, not the status.
#[test]
fn pin_messages_are_notices_beside_the_status() {
    let mut e = PidControl::default();
    assert_eq!(e.notice(), None);
    e.step(0.1);
    let status = e.status();
    e.action("pin").unwrap();
    assert_eq!(e.status(), status, "the status stays the run's state");
    let notice = e.notice().expect("a notice");
    assert_eq!(
        notice.text,
        "pinned at 0.10 s: its metrics are those of the response so far"
    );
    run_to_end(&mut e);
    for _ in 0..3 {
        e.action("pin").unwrap();
    }
    // Finished runs pinned into free slots: nothing to warn about.
    assert_eq!(e.notice(), None);
    e.action("pin").unwrap();
    let replaced = e.notice().expect("a notice");
    assert_eq!(
        replaced.text,
        "pinned as run A: it replaces the oldest pin, in slot A"
    );
    assert!(replaced.serial > notice.serial);
    e.action("clear_pins").unwrap();
    assert_eq!(e.notice(), None);
}

/// Issue 13 §5: pinned runs are comparison series named after their gains.
#[test]
fn pinned_runs_name_their_gains_in_the_legend() {
    let mut e = underdamped();
    assert!(e.plots()[0].series[1..].iter().all(|s| s.comparison));
    assert!(!e.plots()[0].series[0].comparison);
    run_to_end(&mut e);
    e.action("pin").unwrap();
    e.set_param("ki", 1.5).unwrap();
    e.action("pin").unwrap();
    e.set_param("ki", 0.0).unwrap();
    e.set_param("kd", 0.0).unwrap();
    e.action("pin").unwrap();
    let labels: Vec<&str> = e.plots()[0]
        .series
        .iter()
        .map(|s| s.label.as_str())
        .collect();
    assert_eq!(
        labels,
        [
            "position x",
            "A: Kp 25, Kd 5",
            "B: Kp 25, Ki 1.5, Kd 5",
            "C: Kp 25",
            "pinned run D"
        ]
    );
    let csv = e.plots()[0].to_csv();
    assert!(
        csv.starts_with(
            "position x Time since step (s),position x (m),\"A: Kp 25, Kd 5 Time since step (s)\""
        ),
        "{}",
        &csv[..200]
    );
    e.action("clear_pins").unwrap();
    assert_eq!(e.plots()[0].series[1].label, "pinned run A");
}

/// Issue 13 §5: the time column is the sample number over 100 Hz, so the
/// CSV reads 0.07, never 0.07000000000000001.
#[test]
fn the_time_column_reads_in_hundredths() {
    let mut e = PidControl::default();
    e.set_param("sat", 1.0).unwrap();
    run_to_end(&mut e);
    for plot in e.plots() {
        for s in &plot.series {
            for x in &s.x {
                assert_eq!(*x, (x * 100.0).round() / 100.0);
                let text = format!("{x}");
                assert!(
                    text.split('.').nth(1).is_none_or(|d| d.len() <= 2),
                    "{text}"
                );
            }
        }
        for band in &plot.bands {
            assert_eq!(band.lo, (band.lo * 100.0).round() / 100.0);
            assert_eq!(band.hi, (band.hi * 100.0).round() / 100.0);
        }
    }
    let csv = e.plots()[1].to_csv();
    assert!(csv.contains("\r\n0.07,"), "{}", &csv[..300]);
}

// ---------------------------------------------------------------------------
// ---------------------------------------------------------------------------
// Content and quiz (issue 15).

/// The generators draw only what the sliders can set, so a student can set
/// up every generated question in the simulation.
#[test]
fn quiz_generators_draw_inside_the_sliders_ranges() {
    let spec = |key: &str| crate::experiment::find_spec(PARAMS, key).unwrap();
    let mut rng = Lcg64::new(11);
    for name in ["natural_frequency", "damping_ratio", "overshoot", "offset"] {
        let generate = quiz_generator(name).unwrap();
        for _ in 0..2000 {
            let d = generate(&mut rng);
            assert!(d.answer.is_finite(), "{name}");
            for (key, _) in &d.vars {
                let v = d.var(key).unwrap();
                // The offset question names the push backwards as a positive
                // number: the slider's d is its negative.
                let (slider, value) = match (name, *key) {
                    ("offset", "d") => ("d", -v),
                    (_, "zeta") => continue,
                    _ => (*key, v),
                };
                let s = spec(slider);
                assert!(
                    (s.min..=s.max).contains(&value),
                    "{name}: {key} = {v} outside [{}, {}]",
                    s.min,
                    s.max
                );
            }
        }
    }
    assert!(quiz_generator("nope").is_none());
}

/// The correct option must not give itself away by its length: it is the
/// strictly longest option in at most a quarter of the choice questions.
#[test]
fn the_correct_option_is_seldom_the_longest() {
    testkit::assert_the_correct_option_is_seldom_the_longest("pid");
}

/// Issue 23 §3: with a push of −3 N and no integral action the badge said
/// "settled within 2 % after 1.39 s" while the band sat around 0.88 m and
/// Error read 0.120 m. The badge, the band and the settling readout now say
/// what the settling is measured against.
#[test]
fn pid_settling_and_its_band_name_the_value_they_are_measured_against() {
    let (mut e, _) = restore(
        "#/pid/simulation?kp=25&ki=0&kd=10&d=-3",
        PidControl::default(),
    );
    run_to_end(&mut e);
    let status = e.status();
    assert_eq!(
        status.text,
        "settled at 0.880 m, 12 % short of the setpoint (within 2 % after 1.39 s)"
    );
    assert_eq!((status.tone, status.phase), (Tone::Good, Phase::Ended));
    let band = &e.plots()[0].bands[0];
    assert_eq!(band.label, "±2 % band around 0.880 m");
    // The scene names the band on the track too.
    assert!(all_texts(&e).contains(&"±2 % band around 0.880 m".to_owned()));
    assert!((0.5 * (band.lo + band.hi) - 0.88).abs() < 1e-9);
    assert_eq!(readout(&e, "settling"), "1.39 s (around 0.880 m)");
    assert_eq!(readout(&e, "error"), "0.120 m");
    assert_eq!(readout(&e, "sse"), "0.120 m");
    // A push forward leaves the cart past the setpoint; none at all, at it.
    let (mut e, _) = restore(
        "#/pid/simulation?kp=20&ki=0&kd=6&d=5",
        PidControl::default(),
    );
    run_to_end(&mut e);
    assert!(
        e.status()
            .text
            .starts_with("settled at 1.250 m, 25 % past the setpoint"),
        "{}",
        e.status().text
    );
    let mut e = PidControl::default();
    run_to_end(&mut e);
    assert!(e.status().text.starts_with("settled within 2 % after "));
    assert_eq!(e.plots()[0].bands[0].label, "±2 % band");
}

/// Issue 23 §3: with Ki = 2 and the cart at 0.966 m, still moving, the
/// steady-state error read 0.000 m: a prediction, now labelled as one until
/// the run has settled.
#[test]
fn pid_steady_state_error_is_labelled_predicted_until_the_run_settles() {
    let mut e = PidControl::default();
    while e.position_m() < 0.966 {
        e.step(1.0 / 60.0);
    }
    assert!(e.run.state.v_m_s.abs() > 1e-3, "still moving");
    assert_eq!(readout(&e, "sse"), "0.000 m (predicted)");
    run_to_end(&mut e);
    assert_eq!(readout(&e, "sse"), "0.000 m");
}

/// Issue 23 §3: the default run kept "stepping to 1.000 m" after Settling
/// read 10.20 s. Once the settling readout has a time, the badge says the
/// run has settled (the run itself goes on until the cart is at rest). Both
/// wait until the response has stayed in its band for [`SETTLE_DWELL_S`]:
/// it crosses the band at 1.2 s on its way to the overshoot.
#[test]
fn pid_the_badge_follows_the_default_run_to_settled() {
    let mut e = PidControl::default();
    while readout(&e, "settling") == "--" {
        assert!(e.status().text.starts_with("stepping to 1.000 m"));
        e.step(1.0 / 60.0);
    }
    let ts = readout(&e, "settling");
    assert_eq!(ts, "10.20 s");
    assert!(e.time_s() >= 10.2 + SETTLE_DWELL_S - 1e-9 && e.time_s() < 11.25);
    let status = e.status();
    assert_eq!(status.phase, Phase::Live, "still running");
    assert_eq!(status.text, format!("settled within 2 % after {ts}"));
    assert_eq!(status.tone, Tone::Good);
    run_to_end(&mut e);
    assert_eq!(e.status().text, format!("settled within 2 % after {ts}"));
    assert_eq!(e.status().phase, Phase::Ended);
}

/// Issue 23 §3: "Move a point" offered "Setpoint y" in a one-dimensional
/// experiment. The setpoint handle moves along x only.
#[test]
fn pid_the_setpoint_handle_moves_along_x_only() {
    let mut e = PidControl::default();
    let handles = e.handles();
    assert_eq!(handles.len(), 1);
    assert!(handles[0].x_only, "{:?}", handles[0]);
    e.move_handle("setpoint", DVec2::new(0.5, 3.0));
    assert_eq!(e.param("r"), Some(0.5));
    assert_eq!(e.handles()[0].at.y, handles[0].at.y);
}

/// Issue 23 §3 (numbers): "Force u = −9.1 × 10⁻⁵ N" showed where the other
/// readouts show "0.00 N". The force has one format all run long, in the
/// readout and on the canvas: two decimals and N.
#[test]
fn pid_force_u_has_one_format_a_tiny_force_reads_0_00_n() {
    let mut e = PidControl::default();
    let mut tiny = 0;
    for _ in 0..(40 * 60) {
        e.step(1.0 / 60.0);
        let u = e.run.last_terms().output;
        let shown = readout(&e, "force");
        assert_eq!(shown, format!("{} N", format_fixed(u, 2)), "u = {u}");
        let scene = scene_of(&e);
        let label = scene.items.iter().find_map(|item| match item {
            Item::Label { text, .. } => text.strip_prefix("u = ").map(str::to_owned),
            _ => None,
        });
        assert_eq!(label.as_deref(), Some(shown.as_str()));
        if u != 0.0 && u.abs() < 1e-3 {
            tiny += 1;
        }
    }
    assert!(tiny > 0, "the run passes through tiny forces");
}

/// The timeline's replay leaves the step metrics (a scan of the whole
/// response) to its end (`Experiment::end_replay`): the state it rebuilds at
/// any step, before, at and after the run goes quiet, still has the live
/// run's metrics (its readouts and status), markers and plots, bit for bit.
#[test]
fn a_replayed_state_has_the_live_runs_metrics_and_markers_before_and_after_the_run_goes_quiet() {
    use crate::timeline::Timeline;
    use crate::Lab;
    let mut e = PidControl::default();
    set_params(
        &mut e,
        &[
            ("kp", 25.0),
            ("ki", 0.0),
            ("kd", 2.0),
            ("c", 1.0),
            ("noise", 0.0),
            ("tf", 0.0),
        ],
    );
    let mut timeline = Timeline::new(&e as &dyn Lab, 0);
    let mut live = Vec::new();
    let mut quiet_at = None;
    for k in 1..=1500u64 {
        e.step(1.0 / 60.0);
        timeline.stepped(&e as &dyn Lab);
        live.push((e.status(), e.plots().to_vec(), e.readouts()));
        if quiet_at.is_none() && !e.animating() {
            quiet_at = Some(k);
        }
    }
    let quiet_at = quiet_at.expect("the run goes quiet within 25 s");
    let step_once = &mut |lab: &mut dyn Lab| lab.step(1.0 / 60.0);
    for k in (1..=1500u64).filter(|k| k % 7 == 3 || k.abs_diff(quiet_at) <= 40) {
        let (_, lab) = timeline.state_at(k, step_once);
        let (status, plots, readouts) = &live[k as usize - 1];
        assert_eq!(&lab.status(), status, "step {k}: status");
        assert_eq!(lab.plots(), plots.as_slice(), "step {k}: plots and markers");
        assert_eq!(&lab.readouts(), readouts, "step {k}: readouts");
    }
}

/// Issue 53 §7: while the cart rises, "Peak" read less than "Position x"
/// beside it ("x 0.869 m, Peak 0.866 m"): the peak was that of the samples
/// recorded every 10 ms, and a frame of 1/60 s ends between samples. The
/// peak is the largest position so far, the one shown now included.
#[test]
fn the_peak_is_never_below_the_position_shown_beside_it() {
    let mut e = underdamped();
    let mut largest_shown_m = f64::NEG_INFINITY;
    let mut passed_a_sample = 0;
    for frame in 0..120 {
        e.step(1.0 / 60.0);
        let x = testkit::readout_number(&e, "x");
        let peak = readout(&e, "peak");
        if peak == "--" {
            continue;
        }
        largest_shown_m = largest_shown_m.max(x);
        let peak_m = testkit::leading_number(&peak).unwrap();
        assert!(
            peak_m >= largest_shown_m,
            "frame {frame}: x {x} m shown so far, Peak {peak}"
        );
        // The frames that ended past the last recorded sample while rising:
        // there the peak is the position now, at the time now.
        let last_sample_m = *e.plots()[0].series[0].y.last().unwrap();
        if e.run.state.x_m > last_sample_m && e.run.state.v_m_s > 0.0 && frame < 30 {
            passed_a_sample += 1;
            assert_eq!(
                peak,
                format!(
                    "{} at {} s",
                    format_metres(e.run.state.x_m),
                    format_fixed(e.time_s(), 2)
                )
            );
        }
    }
    assert!(
        passed_a_sample > 5,
        "{passed_a_sample} frames ended between samples"
    );
    // At the end the peak is the recorded one, as the plot's marker says.
    run_to_end(&mut e);
    let info = e.metrics().unwrap();
    assert_eq!(
        readout(&e, "peak"),
        format!(
            "{} at {} s",
            format_metres(info.peak),
            format_fixed(info.peak_time_s, 2)
        )
    );
}

/// Issue 53 §7: after Clear pins the step response's text summary (what a
/// screen reader reads for the plot) still listed the pin slots, and the
/// page's empty slots for kept runs, which the legend hides.
#[test]
fn after_clear_pins_the_summary_names_no_pinned_run() {
    let mut e = underdamped();
    for _ in 0..30 {
        e.step(1.0 / 60.0);
    }
    e.action("pin").unwrap();
    let shown = |e: &PidControl| crate::timeline::with_kept(e.plots(), &[], 0)[0].summary();
    assert!(shown(&e).contains("A: Kp 25, Kd 5: "), "{}", shown(&e));
    e.action("clear_pins").unwrap();
    let summary = shown(&e);
    assert!(
        !summary.contains("pinned run") && !summary.contains("A: "),
        "{summary}"
    );
    assert!(!summary.contains("kept run"), "{summary}");
    assert!(summary.contains("position x: "), "{summary}");
}
