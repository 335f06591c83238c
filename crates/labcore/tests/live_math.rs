//! "The math" panel's promise, for every experiment that has one: each
//! equation's substituted form, evaluated from the numbers as the panel
//! shows them, is the readout it names, within the display rounding (half a
//! digit of the readout, plus half a digit of each number put in, carried
//! through the expression).

use labcore::live_math::{rounding_bound, shown};
use labcore::testkit::{leading_number, steps};
use labcore::{registry, Lab, Lcg64};

/// Half a unit of the last digit of a readout's number (`0.749 m` → 0.0005,
/// `2.4 × 10⁵` → 5000).
fn half_digit(text: &str) -> f64 {
    let number: String = text
        .trim_start()
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.' || *c == '-' || *c == '\u{2212}')
        .collect();
    let decimals = number.split_once('.').map_or(0, |(_, d)| d.len());
    0.5 * 10f64.powi(power_of_ten(text) - decimals as i32)
}

/// The power of ten of a readout in the magnitude form (`2.4 × 10⁻⁵ m` → −5), else 0.
fn power_of_ten(text: &str) -> i32 {
    let Some((_, exponent)) = text.split_once("× 10") else {
        return 0;
    };
    let mut power = 0;
    let mut sign = 1;
    for c in exponent.chars() {
        match c {
            '⁻' => sign = -1,
            '⁰' => power *= 10,
            '¹' => power = power * 10 + 1,
            '²' | '³' => power = power * 10 + 2 + i32::from(c == '³'),
            '⁴'..='⁹' => power = power * 10 + (c as i32 - '⁴' as i32 + 4),
            _ => break,
        }
    }
    sign * power
}

/// The number a readout shows, in the magnitude form too (`2.4 × 10⁵` → 240000).
fn readout_number(text: &str) -> Option<f64> {
    leading_number(text).map(|v| v * 10f64.powi(power_of_ten(text)))
}

/// Checks every equation of `e` against its readout; returns the keys of
/// those that had a number to compare.
fn check_equations(e: &dyn Lab, context: &str) -> Vec<&'static str> {
    let quantities = e.quantities();
    let readouts = e.readouts();
    let mut compared = Vec::new();
    for eq in e.equations() {
        for key in eq.expr.keys() {
            assert!(
                quantities.iter().any(|q| q.key == key),
                "{} {context}: equation {} reads {key:?}, which is not among its quantities",
                e.id(),
                eq.symbol
            );
        }
        let readout = readouts
            .iter()
            .find(|r| r.key == eq.readout)
            .unwrap_or_else(|| {
                panic!(
                    "{}: equation {} names no readout {:?}",
                    e.id(),
                    eq.symbol,
                    eq.readout
                )
            });
        let Some(shown_result) = readout_number(&readout.value) else {
            continue; // "--": nothing to compare
        };
        let value = eq.expr.eval(&|k| shown(&quantities, k));
        let tolerance = rounding_bound(&eq.expr, &quantities) + half_digit(&readout.value) + 1e-12;
        assert!(
            (value - shown_result).abs() <= tolerance,
            "{} {context}: {} = {value} from the shown numbers, readout {:?} (tolerance {tolerance}) {quantities:?}",
            e.id(),
            eq.symbol,
            readout.value
        );
        compared.push(eq.key);
    }
    compared
}

/// Random values of every parameter inside its range; now and then its
/// minimum or its default instead (a gain of 0 chooses other equations).
fn randomise(e: &mut dyn Lab, rng: &mut Lcg64) {
    for spec in e.params() {
        let pick = rng.next_f64();
        let value = if pick < 0.15 {
            spec.min
        } else if pick < 0.3 {
            spec.default
        } else {
            spec.min + (spec.max - spec.min) * rng.next_f64()
        };
        let _ = e.set_param(spec.key, value);
    }
}

#[test]
fn live_math_every_equation_is_its_readout_within_the_display_rounding() {
    let mut with_equations = 0;
    for entry in registry() {
        let mut e = (entry.make)();
        if e.equations().is_empty() {
            continue;
        }
        with_equations += 1;
        let mut compared = check_equations(e.as_ref(), "at defaults");
        let mut rng = Lcg64::new(27);
        for trial in 0..200 {
            randomise(e.as_mut(), &mut rng);
            compared.extend(check_equations(
                e.as_ref(),
                &format!("after random parameters #{trial}"),
            ));
            // An action now and then (grow, run, plan …), so runs happen.
            let actions = e.actions();
            if !actions.is_empty() && trial % 3 == 0 {
                let pick = actions
                    [rng.next_f64().mul_add(actions.len() as f64, 0.0) as usize % actions.len()];
                let _ = e.action(pick.key);
                compared.extend(check_equations(
                    e.as_ref(),
                    &format!("after action {} #{trial}", pick.key),
                ));
            }
            if e.animated() {
                steps(e.as_mut(), 1 + (trial % 7) * 10);
                compared.extend(check_equations(
                    e.as_ref(),
                    &format!("after steps, trial {trial}"),
                ));
            }
        }
        // Every equation met a number to compare with, in some variant.
        let mut keys: Vec<&str> = Vec::new();
        let mut fresh = (entry.make)();
        let mut rng = Lcg64::new(2727);
        for _ in 0..60 {
            keys.extend(fresh.equations().iter().map(|eq| eq.key));
            randomise(fresh.as_mut(), &mut rng);
        }
        for key in keys {
            assert!(
                compared.contains(&key),
                "{}: equation {key} was never compared with a number",
                e.id()
            );
        }
    }
    assert!(with_equations > 0, "no experiment has equations yet");
}

#[test]
fn live_math_every_quantity_key_is_unique_and_every_symbol_is_written() {
    for entry in registry() {
        let e = (entry.make)();
        // An equation names its readout by key: one readout per key.
        let readouts = e.readouts();
        for (i, r) in readouts.iter().enumerate() {
            assert!(
                readouts[..i].iter().all(|o| o.key != r.key),
                "{}: readout {} twice",
                e.id(),
                r.key
            );
        }
        let quantities = e.quantities();
        // A symbol spec is a base and at most one subscript after `_`.
        let symbols = quantities
            .iter()
            .map(|q| q.symbol)
            .chain(e.equations().iter().map(|eq| eq.symbol));
        for symbol in symbols {
            assert!(
                symbol.matches('_').count() <= 1 && !symbol.contains('/'),
                "{}: symbol {symbol:?} is not a base with one subscript",
                e.id()
            );
        }
        for (i, q) in quantities.iter().enumerate() {
            assert!(
                !q.symbol.is_empty(),
                "{}: quantity {} has no symbol",
                e.id(),
                q.key
            );
            assert!(
                quantities[..i].iter().all(|p| p.key != q.key),
                "{}: quantity {} twice",
                e.id(),
                q.key
            );
        }
    }
}

#[test]
fn live_math_a_readout_in_the_magnitude_form_is_read_whole() {
    assert_eq!(readout_number("2.4 × 10⁵"), Some(240_000.0));
    assert!((readout_number("5.6 × 10⁻⁷ m").unwrap() - 5.6e-7).abs() < 1e-20);
    assert_eq!(power_of_ten("1.0 × 10¹⁵⁰ rad/s"), 150);
    assert_eq!(power_of_ten("0.749 m"), 0);
    assert!((half_digit("2.4 × 10⁵") - 5000.0).abs() < 1e-9);
    assert_eq!(readout_number("∞ (singular)"), None);
}

#[test]
fn live_math_every_equation_has_a_stable_key_unique_in_its_experiment() {
    for entry in registry() {
        let mut e = (entry.make)();
        // Every variant of the equation set the parameters can choose.
        let mut rng = Lcg64::new(2727);
        let mut seen: Vec<(&'static str, &'static str)> = Vec::new();
        for _ in 0..60 {
            let equations = e.equations();
            for (i, eq) in equations.iter().enumerate() {
                assert!(
                    !eq.key.is_empty()
                        && eq
                            .key
                            .chars()
                            .all(|c| c.is_ascii_alphanumeric() || c == '_'),
                    "{}: equation {} has key {:?} (want ASCII letters, digits, _)",
                    e.id(),
                    eq.symbol,
                    eq.key
                );
                assert!(
                    equations[..i].iter().all(|other| other.key != eq.key),
                    "{}: equation key {} twice",
                    e.id(),
                    eq.key
                );
                // A key names one result in every variant.
                if let Some((_, readout)) = seen.iter().find(|(k, _)| *k == eq.key) {
                    assert_eq!(
                        *readout,
                        eq.readout,
                        "{}: equation {} changed its readout",
                        e.id(),
                        eq.key
                    );
                } else {
                    seen.push((eq.key, eq.readout));
                }
            }
            randomise(e.as_mut(), &mut rng);
        }
    }
}

/// The experiment `id` at its defaults with `params` set.
fn lab(id: &str, params: &[(&str, f64)]) -> Box<dyn Lab> {
    let entry = registry().iter().find(|e| (e.make)().id() == id).expect(id);
    let mut e = (entry.make)();
    for (k, v) in params {
        e.set_param(k, *v)
            .unwrap_or_else(|err| panic!("{id} {k}: {err:?}"));
    }
    e
}

/// Equation `key` of `e` evaluated from the numbers as shown, and the text of
/// the readout it names.
fn equation(e: &dyn Lab, key: &str) -> (f64, String) {
    let quantities = e.quantities();
    let eq = e
        .equations()
        .iter()
        .find(|eq| eq.key == key)
        .unwrap_or_else(|| panic!("{}: no equation {key}", e.id()));
    let value = eq.expr.eval(&|k| shown(&quantities, k));
    let readout = e
        .readouts()
        .into_iter()
        .find(|r| r.key == eq.readout)
        .map(|r| r.value)
        .unwrap_or_default();
    (value, readout)
}

/// The value of quantity `key` as shown.
fn quantity(e: &dyn Lab, key: &str) -> f64 {
    shown(&e.quantities(), key).unwrap_or_else(|| panic!("{}: no quantity {key}", e.id()))
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn live_math_pid_omega_n_and_zeta_by_hand() {
    // Kp = 25 N/m, Ki = 0, Kd = 5 N·s/m, m = 1.0 kg, c = 1.0 N·s/m:
    // ωn = √(25 / 1.0) = 5.000 rad/s, ζ = (1.0 + 5.0) / (2·√(1.0·25.0)) = 0.600.
    let e = lab("pid", &[("kp", 25.0), ("ki", 0.0), ("kd", 5.0)]);
    assert_eq!(
        (quantity(e.as_ref(), "m"), quantity(e.as_ref(), "c")),
        (1.0, 1.0)
    );
    let (wn, text) = equation(e.as_ref(), "omega_n");
    assert!(close(wn, 5.0, 1e-12), "{wn}");
    assert_eq!(text, "5.000 rad/s");
    let (zeta, text) = equation(e.as_ref(), "zeta");
    assert!(close(zeta, 0.6, 1e-12), "{zeta}");
    assert_eq!(text, "0.600");
    // With Ki ≠ 0 the loop is third order: no readout to compare with.
    let e = lab("pid", &[]);
    assert_eq!(equation(e.as_ref(), "zeta").1, "--");
}

#[test]
fn live_math_rrtstar_neighbour_radius_by_hand() {
    // The 10 m × 6 m field: γ = 1.1·2·√1.5·√(60/π) = 11.775 m.
    let mut e = lab("rrtstar", &[("eta", 2.0)]);
    assert_eq!(quantity(e.as_ref(), "gamma"), 11.775);
    e.action("grow").unwrap();
    while quantity(e.as_ref(), "n") < 300.0 {
        steps(e.as_mut(), 1);
    }
    // r(n) = min(11.775·√(ln n / n), 2.00); at n = 300 that is 1.624 m.
    let n = quantity(e.as_ref(), "n");
    let by_hand = (11.775 * (n.ln() / n).sqrt()).min(2.0);
    let (r, text) = equation(e.as_ref(), "radius");
    assert!(close(r, by_hand, 1e-12), "{r} vs {by_hand}");
    assert!(
        close(leading_number(&text).unwrap(), by_hand, 0.0015),
        "{text} vs {by_hand}"
    );
    assert!(close(11.775 * (300f64.ln() / 300.0).sqrt(), 1.624, 0.0005));
    // With few nodes the step η caps it: r(10) = 11.775·√(ln 10 / 10) = 5.65 > η.
    let mut e = lab("rrtstar", &[("eta", 0.5)]);
    e.action("grow").unwrap();
    steps(e.as_mut(), 1);
    assert_eq!(equation(e.as_ref(), "radius"), (0.5, "0.500 m".into()));
}

#[test]
fn live_math_potential_pull_clearance_and_push_by_hand() {
    // Robot at the start (0.60, 3.00) m, goal (8.00, 3.00) m, one obstacle of
    // radius 0.50 m at (2.00, 3.00) m, kₐ = 1.00, kᵣ = 1.60, d₀ = 1.00 m.
    let e = lab(
        "potential",
        &[
            ("gx", 8.0),
            ("gy", 3.0),
            ("nobs", 1.0),
            ("o1x", 2.0),
            ("o1y", 3.0),
        ],
    );
    // d_g = √((8.00 − 0.60)² + (3.00 − 3.00)²) = 7.400 m.
    assert_eq!(
        equation(e.as_ref(), "goal_distance"),
        (7.4, "7.400 m".into())
    );
    // The conic pull: F_att = kₐ = 1.000, whatever the distance.
    assert_eq!(equation(e.as_ref(), "f_att"), (1.0, "1.000".into()));
    // d = √((0.60 − 2.00)² + 0) − 0.50 = 0.900 m.
    let (d, text) = equation(e.as_ref(), "clearance");
    assert!(close(d, 0.9, 1e-12) && text == "0.900 m", "{d} {text}");
    // F_rep = 1.60·max(0, 1.00 − 0.900)/1.00 = 0.160.
    let (push, text) = equation(e.as_ref(), "f_rep");
    assert!(close(push, 0.16, 1e-12) && text == "0.160", "{push} {text}");
}

#[test]
fn live_math_diffdrive_control_law_and_unicycle_by_hand() {
    // From the start (4, 3) m heading 0° toward a first waypoint at (6, 4) m:
    // d = √(2² + 1²) = 2.236 m, eθ = atan2(1, 2) = 0.464 rad.
    let mut e = lab("diffdrive", &[("w1x", 6.0), ("w1y", 4.0)]);
    steps(e.as_mut(), 1);
    assert!(close(quantity(e.as_ref(), "d"), 2.236, 1e-12));
    assert!(close(quantity(e.as_ref(), "e"), 0.464, 1e-12));
    // ω = clamp(3.50·0.464, ±1.40) = clamp(1.624, ±1.40) = 1.400 rad/s.
    assert_eq!(equation(e.as_ref(), "omega"), (1.4, "1.400 rad/s".into()));
    // v = min(1.20·2.236·max(0, cos 0.464), 1.10) = min(2.400, 1.10) = 1.100 m/s.
    assert_eq!(equation(e.as_ref(), "v"), (1.1, "1.100 m/s".into()));
    // ẋ = 1.100·cos 0° = 1.100 m/s, ẏ = 1.100·sin 0° = 0.000 m/s.
    assert_eq!(equation(e.as_ref(), "xdot"), (1.1, "1.100 m/s".into()));
    assert_eq!(equation(e.as_ref(), "ydot"), (0.0, "0.000 m/s".into()));
    // A step later the robot has turned left: ẏ = v sin θ > 0.
    steps(e.as_mut(), 1);
    let (ydot, text) = equation(e.as_ref(), "ydot");
    assert!(
        ydot > 0.0 && close(ydot, leading_number(&text).unwrap(), 0.0015),
        "{ydot} {text}"
    );
}

#[test]
fn live_math_astar_f_is_g_plus_h_for_the_last_cell_expanded_by_hand() {
    // The default grid: the start is 25 cells across and 1 up from the goal.
    let mut e = lab("astar", &[]);
    e.action("plan").unwrap();
    steps(e.as_mut(), 1);
    assert_eq!(
        (quantity(e.as_ref(), "dx"), quantity(e.as_ref(), "dy")),
        (25.0, 1.0)
    );
    // Octile: h = max(25, 1) + (√2 − 1)·min(25, 1) = 25.414 m; f = 0.000 + 25.414.
    let (h, text) = equation(e.as_ref(), "h");
    assert!(
        close(h, 25.0 + 2f64.sqrt() - 1.0, 1e-12) && text == "25.414 m",
        "{h} {text}"
    );
    assert_eq!(equation(e.as_ref(), "f"), (25.414, "25.414 m".into()));
    // Two expansions on, the diagonal neighbour: g = √2 = 1.414, Δx = 24,
    // Δy = 0, h = 24.000, f = 1.414 + 24.000 = 25.414 m (an octile h is consistent).
    steps(e.as_mut(), 2);
    assert_eq!(
        (quantity(e.as_ref(), "dx"), quantity(e.as_ref(), "dy")),
        (24.0, 0.0)
    );
    assert_eq!(equation(e.as_ref(), "h"), (24.0, "24.000 m".into()));
    assert_eq!(equation(e.as_ref(), "f"), (25.414, "25.414 m".into()));
    // Manhattan from the start: h = 25 + 1 = 26.000 m.
    let mut e = lab("astar", &[("h", 0.0)]);
    e.action("plan").unwrap();
    steps(e.as_mut(), 1);
    assert_eq!(equation(e.as_ref(), "h"), (26.0, "26.000 m".into()));
    // Weighted, w = 2: f = 0.000 + 2.0·25.414 = 50.828 m.
    let mut e = lab("astar", &[("w", 2.0)]);
    e.action("plan").unwrap();
    steps(e.as_mut(), 1);
    let (f, text) = equation(e.as_ref(), "f");
    assert!(close(f, 50.828, 1e-12) && text == "50.828 m", "{f} {text}");
}

#[test]
fn live_math_dls_error_manipulability_and_condition_by_hand() {
    // Two links of 1.20 m, both joints at 0.3 rad: the tip sits at
    // (1.2 cos 0.3 + 1.2 cos 0.6, 1.2 sin 0.3 + 1.2 sin 0.6) = (2.137, 1.032) m.
    let e = lab("dls", &[("n", 2.0), ("tx", 1.0), ("ty", 1.0)]);
    // |e| = √((1.000 − 2.137)² + (1.000 − 1.032)²) = 1.137 m.
    let (error, text) = equation(e.as_ref(), "error");
    assert!(
        close(error, 1.137_450_5, 1e-6) && text == "1.137 m",
        "{error} {text}"
    );
    // JJᵀ = [[1.5245, −2.8767], [−2.8767, 5.5468]] m²:
    // w = √(1.5245·5.5468 − 2.8767²) = 0.4251, and in closed form for two
    // links L₁L₂|sin θ₂| = 1.44·sin 0.3 = 0.4255: the readout 0.426.
    assert_eq!(quantity(e.as_ref(), "a"), 1.5245);
    assert_eq!(quantity(e.as_ref(), "b"), -2.8767);
    assert_eq!(quantity(e.as_ref(), "c"), 5.5468);
    let (w, text) = equation(e.as_ref(), "w");
    assert!(close(w, 0.425_08, 1e-5) && text == "0.426 m²", "{w} {text}");
    assert!(close(1.44 * 0.3f64.sin(), 0.4255, 1e-4));
    // σmax/σmin = 2.654 / 0.1603 = 16.6.
    let (kappa, text) = equation(e.as_ref(), "condition");
    assert!(
        close(kappa, 2.654 / 0.1603, 1e-9) && text == "16.6",
        "{kappa} {text}"
    );
}

#[test]
fn live_math_cartpole_force_from_the_state_it_came_from_and_energy_by_hand() {
    let mut e = lab("cartpole", &[]);
    // At the start, the pole at θ = 6°, at rest: E = m g l cos θ =
    // 0.10·9.80·0.50·cos 6° = 0.4873 J; no step yet, so no force.
    assert_eq!(equation(e.as_ref(), "energy").1, "0.4873 J");
    assert!(close(
        equation(e.as_ref(), "energy").0,
        0.49 * 6f64.to_radians().cos(),
        1e-12
    ));
    assert_eq!(equation(e.as_ref(), "force"), (0.0, "0.00 N".into()));
    // The first step's force comes from that start: F = 3.0·0 + 6.0·0 +
    // 120.0·0.10472 + 18.0·0 = 12.57 N (under the 30 N limit) …
    while quantity(e.as_ref(), "thk") == 0.0 {
        steps(e.as_mut(), 1);
    }
    assert_eq!(quantity(e.as_ref(), "thk"), 0.10472);
    let (f, text) = equation(e.as_ref(), "force");
    assert!(
        close(f, 120.0 * 0.10472, 1e-12) && text == "12.57 N",
        "{f} {text}"
    );
    // … while the state has moved on since: the next force comes from the new one.
    assert_ne!(
        e.quantities().iter().find(|q| q.key == "th").unwrap().value,
        6.0,
        "the pole has moved"
    );
    // Control off: no force.
    let mut e = lab("cartpole", &[("ctl", 0.0)]);
    steps(e.as_mut(), 10);
    assert_eq!(equation(e.as_ref(), "force"), (0.0, "0.00 N".into()));
    assert!(e.equations()[0].caption.starts_with("No force"));
}

#[test]
fn live_math_ekf_error_trace_and_nees_by_hand() {
    // At the start P = diag(0.05², 0.05², (2°)²): Λ = P⁻¹ = diag(400, 400,
    // 820.7), and the seeded start error e = (−0.05831 m, −0.005542 m, 0.07941 rad).
    let e = lab("ekf", &[]);
    let shown: Vec<f64> = ["ex", "ey", "eth", "lxx", "lyy", "ltt", "lxy"]
        .iter()
        .map(|k| quantity(e.as_ref(), k))
        .collect();
    assert_eq!(
        shown,
        [-0.05831, -0.005542, 0.07941, 400.0, 400.0, 820.7, 0.0]
    );
    // |e| = √(0.05831² + 0.005542²) = 0.0586 m, shown 0.059 m.
    let (error, text) = equation(e.as_ref(), "error");
    assert!(
        close(error, 0.058_573, 1e-6) && text == "0.059 m",
        "{error} {text}"
    );
    // σ² = 0.002500 + 0.002500 = 0.005000 m².
    assert_eq!(equation(e.as_ref(), "trace"), (0.005, "0.005000 m²".into()));
    // NEES = 400·0.05831² + 400·0.005542² + 820.7·0.07941² = 1.360 + 0.012 + 5.175 = 6.55.
    let (nees, text) = equation(e.as_ref(), "nees");
    assert!(close(nees, 6.5476, 1e-4) && text == "6.55", "{nees} {text}");
}

#[test]
fn live_math_ekf_innovation_of_the_last_observation_by_hand() {
    let mut e = lab("ekf", &[]);
    // Before any reading there is no innovation to show.
    assert_eq!(equation(e.as_ref(), "innovation_range").1, "--");
    while quantity(e.as_ref(), "zr").is_nan() {
        steps(e.as_mut(), 1);
    }
    // The first reading's last landmark: z = (2.281 m, 59.05°), predicted
    // ẑ = (2.330 m, 59.87°): ν = (2.281 − 2.330, 59.05° − 59.87°) = (−0.049 m, −0.8°).
    let z: Vec<f64> = ["zr", "zhr", "zb", "zhb"]
        .iter()
        .map(|k| quantity(e.as_ref(), k))
        .collect();
    assert_eq!(z, [2.281, 2.33, 59.05, 59.87]);
    let (nu_r, text) = equation(e.as_ref(), "innovation_range");
    assert!(
        close(nu_r, -0.049, 1e-12) && text == "-0.049 m",
        "{nu_r} {text}"
    );
    let (nu_b, text) = equation(e.as_ref(), "innovation_bearing");
    assert!(
        close(nu_b, -0.82, 1e-12) && text == "-0.8°",
        "{nu_b} {text}"
    );
}

/// Issue 53 §8: pid with Ki = 0, c = 0, Kd = 0 and a tiny Kp (1.146e-256,
/// typed, in range): the panel wrote Kp as "0.0", and ζ = (0.0 + 0.0) /
/// (2·√(1.0·0.0)) evaluates to NaN from the numbers shown while it
/// printed 0.000. A number that is not zero is never written as zero, so
/// the printed result follows from the numbers shown.
#[test]
fn live_math_a_tiny_gain_is_not_written_as_zero() {
    let e = lab(
        "pid",
        &[("ki", 0.0), ("c", 0.0), ("kd", 0.0), ("kp", 1.146e-256)],
    );
    let kp = e.quantities().into_iter().find(|q| q.key == "kp").unwrap();
    assert_eq!(kp.number_text(), "1.1 × 10⁻²⁵⁶");
    assert_eq!(kp.shown_value(), 1.1e-256);
    let (zeta, text) = equation(e.as_ref(), "zeta");
    assert_eq!(text, "0.000");
    assert_eq!(zeta, 0.0, "ζ from the numbers shown");
    check_equations(e.as_ref(), "with a tiny Kp");
}

/// Issue 53 §8: potential, the goal moved onto the robot (two arrow-key
/// nudges, +0.16 and −0.16, did it): the pull has no direction there and
/// the readout says |F_att| = 0.000, while the equation read kₐ = 1.00.
#[test]
fn live_math_potential_pull_with_the_goal_on_the_robot() {
    let mut e = lab("potential", &[]);
    labcore::testkit::click(e.as_mut(), labcore::glam::DVec2::new(6.0, 3.0));
    let start = e
        .handles()
        .into_iter()
        .find(|h| h.id == "start")
        .unwrap()
        .at;
    assert!(e.move_handle("goal", start));
    let (pull, text) = equation(e.as_ref(), "f_att");
    assert_eq!(text, "0.000");
    assert_eq!(pull, 0.0, "F_att from the numbers shown");
    check_equations(e.as_ref(), "with the goal on the robot");
    // Off the robot, the pull is kₐ again.
    let mut e = lab("potential", &[]);
    labcore::testkit::click(e.as_mut(), labcore::glam::DVec2::new(6.0, 3.0));
    assert_eq!(equation(e.as_ref(), "f_att"), (1.0, "1.000".to_owned()));
}
