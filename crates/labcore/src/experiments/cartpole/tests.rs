use super::quiz::*;
use super::view::gains_text;
use super::*;
use crate::control::count_right_half_plane;
use crate::route::{format, restore, Tab};

fn run(e: &mut CartPoleBalance, seconds: f64) {
    for _ in 0..(seconds * 60.0).round() as usize {
        e.step(1.0 / 60.0);
    }
}

fn readout(e: &CartPoleBalance, key: &str) -> String {
    crate::experiment::readout_value(e, key).unwrap_or_else(|| panic!("no readout {key}"))
}

#[test]
fn readouts_by_hand_at_the_start() {
    let e = CartPoleBalance::default();
    assert_eq!(readout(&e, "theta"), "6.0°");
    assert_eq!(readout(&e, "x"), "0.000 m");
    assert_eq!(readout(&e, "status"), "up");
    // √(g/D), D = l(4/3 − m/(M + m)) = 0.5·(4/3 − 0.1/1.1) = 0.62121…
    let d = 0.5 * (4.0 / 3.0 - 0.1 / 1.1);
    let unstable = (9.8_f64 / d).sqrt();
    assert_eq!(
        readout(&e, "open_eig"),
        format!(
            "{}, 0.000, 0.000, -{}",
            format_fixed(unstable, 3),
            format_fixed(unstable, 3)
        )
    );
    // Energy at rest with the pole at 6°: m g l cos θ.
    let energy = 0.1 * 9.8 * 0.5 * 6f64.to_radians().cos();
    assert_eq!(
        readout(&e, "energy"),
        format!("{} J", format_fixed(energy, 4))
    );
    assert_eq!(readout(&e, "closed_verdict"), "stable");
    assert_eq!(e.status().tone, Tone::Neutral);
}

#[test]
fn the_default_gains_catch_the_pole_and_recover_from_a_nudge() {
    let mut e = CartPoleBalance::default();
    run(&mut e, 2.0);
    assert!(e.state().theta_rad.abs() < 1f64.to_radians());
    e.action("nudge").unwrap();
    assert!(e.state().omega_rad_s > 0.4);
    run(&mut e, 10.0);
    assert_eq!(readout(&e, "status"), "up");
    assert!(
        e.state().theta_rad.abs() < 0.2f64.to_radians(),
        "{:?}",
        e.state()
    );
    assert!(e.state().x_m.abs() < 0.5, "{:?}", e.state());
}

/// The linearised open loop has exactly one right-half-plane eigenvalue;
/// the LQR button puts gains on the sliders whose closed loop has none,
/// and the pole is then held.
#[test]
fn lqr_gains_give_a_stable_closed_loop() {
    let mut e = CartPoleBalance::default();
    let open = open_loop_eigenvalues(&e.sim.params).unwrap();
    assert_eq!(count_right_half_plane(&open), 1);
    let proposal = e.lqr_proposal().unwrap();
    assert_eq!(readout(&e, "lqr"), gains_text(&proposal));
    e.set_param("kth", 0.0).unwrap();
    assert_eq!(readout(&e, "closed_verdict"), "unstable");
    e.action("lqr").unwrap();
    assert_eq!(e.gains(), proposal);
    for (key, v) in [("kth", proposal.k_theta), ("kx", proposal.k_x)] {
        assert_eq!(e.param(key), Some(v));
        assert_eq!(v, (v * 100.0).round() / 100.0, "rounded like the slider");
    }
    let closed = closed_loop_eigenvalues(&e.sim.params, &e.gains()).unwrap();
    assert!(closed.iter().all(|z| z.re < 0.0), "{closed:?}");
    assert_eq!(readout(&e, "closed_verdict"), "stable");
    // Heavier weight on θ gives a stiffer angle loop.
    e.set_param("qth", 100.0).unwrap();
    assert!(e.lqr_proposal().unwrap().k_theta > proposal.k_theta);
    e.restart();
    run(&mut e, 20.0);
    assert_eq!(e.status().text, "balanced");
    assert!(!e.animating(), "a balanced pole lets the page idle");
}

/// The closed-loop polynomial of the default cart gains is
/// s⁴ + a₃s³ + a₂s² + a₁s + a₀ with a₂ = 1.4634·kθ − 18.70 (by hand from
/// A + B k); Hurwitz's a₃a₂a₁ > a₁² + a₃²a₀ needs kθ > 22.65 N/rad, well
/// above the (M + m)·g = 10.78 N/rad of angle feedback alone. The
/// procedure quotes "about 23".
#[test]
fn the_default_cart_gains_need_k_theta_above_about_23() {
    let mut e = CartPoleBalance::default();
    e.set_param("kth", 23.5).unwrap();
    assert_eq!(readout(&e, "closed_verdict"), "stable");
    e.set_param("kth", 22.0).unwrap();
    assert_eq!(readout(&e, "closed_verdict"), "unstable");
}

#[test]
fn energy_stays_flat_under_rk4_with_control_off() {
    let drift = |integrator: f64| {
        let mut e = CartPoleBalance::default();
        e.set_param("integ", integrator).unwrap();
        e.set_param("th0", 10.0).unwrap();
        e.action("drop").unwrap();
        assert_eq!(e.param("ctl"), Some(0.0));
        run(&mut e, 5.0);
        assert_eq!(e.status().tone, Tone::Bad, "the dropped pole falls");
        let energy = &e.plots()[3].series[0].y;
        assert!(energy.len() > 20);
        let (lo, hi) = energy
            .iter()
            .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(*v), hi.max(*v)));
        (hi - lo) / energy[0].abs()
    };
    let rk4 = drift(1.0);
    let euler = drift(0.0);
    assert!(rk4 < 1e-6, "RK4 relative drift {rk4}");
    assert!(euler > 100.0 * rk4, "Euler {euler} vs RK4 {rk4}");
}

#[test]
fn the_linear_model_agrees_at_2_degrees_and_parts_at_30() {
    let relative_gap = |deg: f64| {
        let mut e = CartPoleBalance::default();
        e.set_param("th0", deg).unwrap();
        run(&mut e, 5.0);
        let angle = &e.plots()[0];
        assert_eq!(angle.series[0].len(), angle.series[1].len());
        let gap = angle.series[0]
            .y
            .iter()
            .zip(&angle.series[1].y)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!((gap - e.max_gap_rad().to_degrees()).abs() < 1e-9);
        gap / deg
    };
    let small = relative_gap(2.0);
    let large = relative_gap(30.0);
    assert!(small < 1e-3, "2°: {small}");
    assert!(large > 0.02, "30°: {large}");
    // Nudges reach both models, so they stay together at small angles.
    let mut e = CartPoleBalance::default();
    e.set_param("th0", 2.0).unwrap();
    e.input(Input::Nudge(DVec2::new(-0.1, 0.0)));
    assert_eq!(e.state().omega_rad_s, e.linear_state().omega_rad_s);
    assert!(e.state().omega_rad_s < 0.0);
}

#[test]
fn drop_and_catch() {
    let mut e = CartPoleBalance::default();
    run(&mut e, 3.0);
    e.action("drop").unwrap();
    assert_eq!(e.status().tone, Tone::Warning);
    e.action("nudge").unwrap();
    run(&mut e, 0.3);
    let leaning = e.state().theta_rad;
    assert!(leaning > 4f64.to_radians(), "{leaning}");
    assert!(
        e.linear_state().theta_rad > 4f64.to_radians(),
        "the linear model falls too"
    );
    e.action("catch").unwrap();
    run(&mut e, 8.0);
    assert_eq!(readout(&e, "status"), "up");
    assert!(e.state().theta_rad.abs() < 1f64.to_radians());
}

#[test]
fn the_fall_criterion_is_selectable_and_ends_the_run() {
    let fall_time = |choice: f64| {
        let mut e = CartPoleBalance::default();
        e.set_param("fall", choice).unwrap();
        e.action("drop").unwrap();
        run(&mut e, 5.0);
        assert!(!e.animating());
        let Run::Ended { status, time_s } = e.run else {
            panic!("still going")
        };
        assert_eq!(status, PoleStatus::Fallen);
        let frozen = e.state();
        run(&mut e, 1.0);
        assert_eq!(e.state(), frozen, "a fallen run stays put");
        (time_s, e.state().theta_rad.to_degrees())
    };
    let (t90, th90) = fall_time(0.0);
    let (t12, th12) = fall_time(1.0);
    assert!(th90 > 90.0 && th90 < 100.0, "{th90}");
    assert!(th12 > 12.0 && th12 < 15.0, "{th12}");
    assert!(t12 < t90);
    let mut e = CartPoleBalance::default();
    e.set_param("fall", 1.0).unwrap();
    e.action("drop").unwrap();
    run(&mut e, 5.0);
    assert!(readout(&e, "status").starts_with("fallen at "));
    assert!(e.status().text.starts_with("pole fallen at t = "));
}

#[test]
fn force_is_limited_and_shaded() {
    let mut e = CartPoleBalance::default();
    e.set_param("flim", 5.0).unwrap();
    e.set_param("th0", 8.0).unwrap();
    run(&mut e, 2.0);
    let force = &e.plots()[2];
    assert!(force.series[0].y.iter().all(|f| f.abs() <= 5.0 + 1e-12));
    assert!(!force.bands.is_empty());
    assert!(force.bands.iter().all(|b| b.axis == Axis::X && b.hi > b.lo));
    assert_eq!(force.ref_lines[0].value, 5.0);
}

#[test]
fn dragging_the_tip_sets_the_start_angle() {
    let mut e = CartPoleBalance::default();
    let tip = e.tip_of(&e.state());
    assert!(e.handle_at(tip, 0.05));
    e.input(Input::PointerDown(tip));
    // 45° to the left of the pivot at x = 0.
    e.input(Input::PointerMove {
        pos: DVec2::new(-0.5, PIVOT_Y_M + 0.5),
        pressed: true,
    });
    assert_eq!(e.param("th0"), Some(-45.0));
    assert_eq!(e.time_s(), 0.0);
    e.input(Input::PointerMove {
        pos: DVec2::new(-1.0, PIVOT_Y_M - 0.2),
        pressed: true,
    });
    assert_eq!(e.param("th0"), Some(-60.0), "kept in range");
    e.input(Input::PointerUp(DVec2::ZERO));
    // A tap to the right, away from the tip, nudges the pole that way.
    e.input(Input::PointerDown(DVec2::new(2.0, 0.2)));
    assert!(e.state().omega_rad_s > 0.0);
    assert_eq!(e.param("th0"), Some(-60.0));
}

/// Data older than a minute is dropped, so a long run stays bounded.
#[test]
fn plots_keep_the_last_minute() {
    let mut e = CartPoleBalance::default();
    e.set_param("integ", 1.0).unwrap();
    for _ in 0..(90 * 60) {
        if !e.animating() {
            e.action("nudge").unwrap();
        }
        e.step(1.0 / 60.0);
    }
    for plot in e.plots() {
        let x = &plot.series[0].x;
        assert!(
            x[0] >= e.time_s() - KEEP_S - 1.0 - 1e-9,
            "{} {}",
            plot.key,
            x[0]
        );
        assert!(x.len() <= ((KEEP_S + 1.0) / CONTROL_PERIOD_S) as usize + 2);
    }
}

#[test]
fn every_parameter_round_trips_through_the_link() {
    let mut e = CartPoleBalance::default();
    for (k, v) in [
        ("kth", 80.5),
        ("kom", 11.3),
        ("kx", -1.5),
        ("kv", 2.25),
        ("th0", -12.3),
        ("ctl", 0.0),
        ("integ", 1.0),
        ("fall", 1.0),
        ("flim", 12.0),
        ("qx", 2.0),
        ("qv", 0.5),
        ("qth", 40.0),
        ("qom", 3.0),
        ("r", 0.25),
    ] {
        e.set_param(k, v).unwrap();
    }
    let link = format(&e, Tab::Simulation);
    let (mut fresh, notices) = restore(&link, CartPoleBalance::default());
    assert!(notices.is_empty(), "{notices:?}");
    assert_eq!(format(&fresh, Tab::Simulation), link);
    for spec in PARAMS {
        assert_eq!(fresh.param(spec.key), e.param(spec.key), "{}", spec.key);
    }
    run(&mut e, 1.0);
    run(&mut fresh, 1.0);
    assert_eq!(e.state(), fresh.state());
}

#[test]
fn bad_steps_and_inputs_change_nothing() {
    let mut e = CartPoleBalance::default();
    run(&mut e, 0.5);
    let before = (e.state(), e.time_s(), e.plots()[0].series[0].clone());
    for dt in [f64::NAN, -1.0, 0.0, 0.5, f64::INFINITY] {
        e.step(dt);
    }
    e.input(Input::PointerDown(DVec2::new(f64::NAN, 1.0)));
    e.input(Input::Nudge(DVec2::new(f64::NAN, 0.0)));
    assert_eq!(
        (e.state(), e.time_s(), e.plots()[0].series[0].clone()),
        before
    );
    assert!(e.set_param("kth", f64::INFINITY).is_err());
    assert!(e.action("nope").is_err());
}

#[test]
fn quiz_generators_agree_with_the_formulas() {
    let mut rng = Lcg64::new(3);
    for _ in 0..200 {
        let d = quiz_unstable_eigenvalue(&mut rng);
        let (big, small, l) = (
            d.var("cart").unwrap(),
            d.var("pole").unwrap(),
            d.var("half").unwrap(),
        );
        let den = l * (4.0 / 3.0 - small / (big + small));
        assert!((d.answer - (9.8 / den).sqrt()).abs() < 1e-6, "{d:?}");
        let d = quiz_feedback_force(&mut rng);
        let v = |k: &str| d.var(k).unwrap();
        let f = v("kth") * v("theta").to_radians()
            + v("kom") * v("omega")
            + v("kx") * v("x")
            + v("kv") * v("v");
        assert!((d.answer - f).abs() < 1e-9);
        let d = quiz_small_angle(&mut rng);
        let t = v_rad(d.var("deg").unwrap());
        assert!((d.answer - 100.0 * (t - t.sin()) / t.sin()).abs() < 1e-9);
    }
}

fn v_rad(deg: f64) -> f64 {
    deg.to_radians()
}
