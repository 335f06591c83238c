//! Issue 53 §6, "The math speaks the Theory's language": in every state a
//! student can reach, each equation of the Simulation tab's "The math"
//! panel either has its numbers or says in words why not (never a row of
//! numbers that ends in `= --`), puts every number in with its unit, and
//! writes each symbol as the experiment's Theory tab writes it.

use labcore::content::Block;
use labcore::live_math::{named, Equation, Quantity};
use labcore::testkit::steps;
use labcore::{registry, Lab, Lcg64};
use labpage::math_panel::{live_parts, symbol_mathml};

/// The equations "The math" panel shows for `e` (its content's list).
fn panel(e: &dyn Lab) -> Vec<Equation> {
    let math = labcore::find(e.id())
        .and_then(|x| x.content().ok())
        .map(|c| c.math.clone())
        .unwrap_or_default();
    named(e.equations(), &math)
}

/// `e` at its defaults with `params` set.
fn lab(id: &str, params: &[(&str, f64)]) -> Box<dyn Lab> {
    let entry = registry().iter().find(|e| (e.make)().id() == id).expect(id);
    let mut e = (entry.make)();
    for (k, v) in params {
        e.set_param(k, *v)
            .unwrap_or_else(|err| panic!("{id} {k}: {err:?}"));
    }
    e
}

/// Calls `check` with every experiment in the states a student meets: as
/// the page opens, after a run of steps, its preview, after each of its
/// actions and a run, and with random parameters (now and then a
/// minimum, which chooses other equations), then stepped. Also the
/// states issue 53 §6 named: ekf in SLAM mode, before and after a run.
fn each_state(check: &mut dyn FnMut(&dyn Lab, &str)) {
    for entry in registry() {
        let mut e = (entry.make)();
        check(e.as_ref(), "as opened");
        steps(e.as_mut(), 40);
        check(e.as_ref(), "after 40 steps");
        let mut e = (entry.make)();
        e.preview();
        check(e.as_ref(), "previewed");
        for action in (entry.make)().actions() {
            let mut e = (entry.make)();
            if e.action(action.key).is_ok() {
                check(e.as_ref(), &format!("after {}", action.key));
                steps(e.as_mut(), 30);
                check(e.as_ref(), &format!("after {} and 30 steps", action.key));
            }
        }
        let mut rng = Lcg64::new(53);
        let mut e = (entry.make)();
        for trial in 0..40 {
            for spec in e.params() {
                let pick = rng.next_f64();
                let value = if pick < 0.2 {
                    spec.min
                } else {
                    spec.min + (spec.max - spec.min) * rng.next_f64()
                };
                let _ = e.set_param(spec.key, value);
            }
            check(e.as_ref(), &format!("random parameters #{trial}"));
            steps(e.as_mut(), 1 + trial % 5 * 7);
            check(e.as_ref(), &format!("random parameters #{trial}, stepped"));
        }
    }
    let mut slam = lab("ekf", &[("mode", 1.0)]);
    check(slam.as_ref(), "SLAM as opened");
    steps(slam.as_mut(), 200);
    check(slam.as_ref(), "SLAM after 200 steps");
}

#[test]
fn math_no_equation_shows_dashes_it_says_in_words_why_it_has_no_numbers() {
    let mut in_words: Vec<(String, &'static str)> = Vec::new();
    each_state(&mut |e, when| {
        let quantities = e.quantities();
        let readouts = e.readouts();
        for eq in panel(e) {
            let (numbers, result, text) = live_parts(&eq, &quantities, &readouts);
            let at = format!("{} {when}: {}", e.id(), eq.key);
            assert!(
                !text.contains("--") && !numbers.contains("--") && !result.contains("--"),
                "{at}: {text}"
            );
            if result.is_empty() {
                assert!(
                    !eq.absent.is_empty(),
                    "{at}: no numbers and no words: {text}"
                );
                assert_eq!(
                    numbers,
                    format!("<span class=\"equation-absent\">{}</span>", eq.absent),
                    "{at}"
                );
                assert!(text.ends_with(eq.absent), "{at}: {text}");
                in_words.push((e.id().to_owned(), eq.key));
            } else {
                assert!(
                    result.starts_with("= ") && numbers.contains("<mn>"),
                    "{at}: {result}"
                );
            }
        }
    });
    // The states the issue found dashes in now say why in words.
    for (id, key) in [
        ("pid", "omega_n"),
        ("pid", "zeta"),
        ("astar", "h"),
        ("astar", "f"),
        ("dls", "error"),
        ("ik", "theta2"),
        ("ekf", "innovation_range"),
        ("ekf", "innovation_bearing"),
        ("potential", "goal_distance"),
        ("rrtstar", "radius"),
    ] {
        assert!(
            in_words.iter().any(|(i, k)| i == id && *k == key),
            "{id} {key} never said why it had no numbers"
        );
    }
}

/// pid with Ki ≠ 0 (its default): "ωn = √(12.0/1.0) = --" put numbers in
/// and then had no result. Now the symbols and why, in words.
#[test]
fn math_pid_omega_n_with_integral_action_says_it_holds_for_ki_zero_only() {
    let e = lab("pid", &[]);
    let eq = panel(e.as_ref())
        .into_iter()
        .find(|eq| eq.key == "omega_n")
        .unwrap();
    let (numbers, result, text) = live_parts(&eq, &e.quantities(), &e.readouts());
    assert_eq!(result, "");
    assert!(numbers.contains("Only with Ki = 0"), "{numbers}");
    assert!(!numbers.contains("12.0"), "{numbers}");
    assert_eq!(text, format!("ωn = √((Kp) / (m)). {}", eq.absent));
    // With Ki = 0 its numbers, with their units, and the readout.
    let e = lab("pid", &[("ki", 0.0), ("kp", 25.0)]);
    let eq = panel(e.as_ref())
        .into_iter()
        .find(|eq| eq.key == "omega_n")
        .unwrap();
    let (_, result, text) = live_parts(&eq, &e.quantities(), &e.readouts());
    assert_eq!(result, "= 5.000 rad/s");
    assert_eq!(
        text,
        "ωn = √((Kp) / (m)) = √((25.0 N/m) / (1.0 kg)) = 5.000 rad/s"
    );
}

/// Quantities that are pure numbers, by name: no unit to write.
const DIMENSIONLESS: [(&str, &str); 4] = [
    // Weighted A*'s weight: the heuristic counts w times.
    ("astar", "w"),
    // RRT*'s node count.
    ("rrtstar", "n"),
    // The potential field's strengths: the robot steers by the force's
    // direction, and the Theory gives the pull and push no unit.
    ("potential", "ka"),
    ("potential", "kr"),
];

/// The substituted form of an equation's text twin
/// (`symbol = symbols = numbers = result`).
fn numbers_of(text: &str) -> &str {
    text.split(" = ").nth(2).unwrap_or_default()
}

#[test]
fn math_every_number_put_in_carries_its_unit_or_is_a_pure_number_by_name() {
    let mut checked = 0;
    each_state(&mut |e, when| {
        let quantities = e.quantities();
        let readouts = e.readouts();
        for eq in panel(e) {
            let (_, result, text) = live_parts(&eq, &quantities, &readouts);
            if result.is_empty() {
                continue;
            }
            let numbers = numbers_of(&text);
            for key in eq.expr.keys() {
                let q: &Quantity = quantities.iter().find(|q| q.key == key).unwrap();
                let at = format!("{} {when}: {} reads {key}", e.id(), eq.key);
                let shown = q.number_text();
                let shown = shown.strip_prefix('-').unwrap_or(&shown);
                match q.unit {
                    "" => assert!(
                        DIMENSIONLESS.contains(&(e.id(), key)),
                        "{at}: {} has no unit and is not a pure number by name",
                        q.symbol
                    ),
                    "°" => assert!(numbers.contains(&format!("{shown}°")), "{at}: {numbers}"),
                    unit => assert!(
                        numbers.contains(&format!("{shown} {unit}")),
                        "{at}: {shown} without {unit}: {numbers}"
                    ),
                }
                checked += 1;
            }
        }
    });
    assert!(checked > 1000, "{checked} numbers checked");
}

/// cartpole: the force law's angle is in radians beside a readout in
/// degrees; "15.0·0.22906" read as 13.1 (the readout's degrees) gave a
/// student 197 N for 3.4 N. The number says its unit.
#[test]
fn math_cartpole_force_law_marks_the_angle_in_radians() {
    let mut e = lab("cartpole", &[]);
    steps(e.as_mut(), 5);
    let eq = panel(e.as_ref())
        .into_iter()
        .find(|eq| eq.key == "force")
        .unwrap();
    let quantities = e.quantities();
    let theta = quantities.iter().find(|q| q.key == "thk").unwrap();
    let (_, _, text) = live_parts(&eq, &quantities, &e.readouts());
    assert!(
        text.contains(&format!("120.0 N/rad × {} rad", theta.number_text())),
        "{text}"
    );
}

/// MathML with what two writers may write differently for the same symbol
/// taken out: attributes, `<mrow>` groups and spaces, and `<mtext>` read as
/// `<mi>` (the Theory's `L_{\text{max}}` and the panel's `L_max` are both
/// an upright "max").
fn normal(markup: &str) -> String {
    let mut out = String::new();
    let mut rest = markup;
    while let Some(at) = rest.find('<') {
        out.push_str(&rest[..at]);
        let end = rest[at..].find('>').map_or(rest.len(), |i| at + i + 1);
        let tag = &rest[at..end];
        let name: String = tag[1..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '/')
            .collect();
        match name.trim_matches('/') {
            "mrow" | "mspace" => {}
            "mtext" => out.push_str(if name.starts_with('/') {
                "</mi>"
            } else {
                "<mi>"
            }),
            _ => {
                out.push('<');
                out.push_str(&name);
                out.push('>');
            }
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// The symbols the Theory marks `\live{key}{…}`, each as its MathML.
fn live_symbols<'a>(theory: &'a str, key: &str) -> Vec<&'a str> {
    let open = format!("<mrow data-live=\"{key}\" tabindex=\"0\">");
    let mut out = Vec::new();
    let mut rest = theory;
    while let Some(at) = rest.find(&open) {
        let body = &rest[at + open.len()..];
        // To the `</mrow>` that closes this one.
        let (mut depth, mut i) = (1, 0);
        while depth > 0 {
            let next_open = body[i..].find("<mrow").map(|j| i + j);
            let next_close = body[i..].find("</mrow>").map(|j| i + j).expect("closed");
            match next_open {
                Some(o) if o < next_close => {
                    depth += 1;
                    i = o + 5;
                }
                _ => {
                    depth -= 1;
                    i = next_close + 7;
                }
            }
        }
        out.push(&body[..i - 7]);
        rest = &body[i..];
    }
    out
}

fn theory_of(id: &str) -> String {
    let content = labcore::find(id).unwrap().content().unwrap();
    content
        .theory
        .iter()
        .map(|b| match b {
            Block::Heading(s) | Block::Paragraph(s) | Block::Formula(s) | Block::Note(s) => {
                s.as_str()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn math_every_symbol_in_the_panel_is_written_as_its_theory_writes_it() {
    let theories: Vec<(String, String)> = registry()
        .iter()
        .map(|entry| {
            let id = (entry.make)().id().to_owned();
            let theory = theory_of(&id);
            (id, theory)
        })
        .collect();
    let mut wrong: Vec<String> = Vec::new();
    each_state(&mut |e, when| {
        let theory = &theories.iter().find(|(id, _)| id == e.id()).unwrap().1;
        let normal_theory = normal(theory);
        let quantities = e.quantities();
        for eq in panel(e) {
            let mut symbols = vec![(eq.symbol, None)];
            for key in eq.expr.keys() {
                let q = quantities.iter().find(|q| q.key == key).unwrap();
                symbols.push((q.symbol, Some(key)));
            }
            for (symbol, key) in symbols {
                let mine = normal(&symbol_mathml(symbol));
                let problem = if !normal_theory.contains(&mine) {
                    Some("is not in the Theory".to_owned())
                } else {
                    // Where the Theory marks the quantity live, it writes it
                    // so at least once.
                    key.map(|k| live_symbols(theory, k))
                        .filter(|live| !live.is_empty())
                        .filter(|live| live.iter().all(|l| normal(l) != mine))
                        .map(|live| format!("is not the Theory's live symbol for it: {live:?}"))
                };
                if let Some(problem) = problem {
                    let line = format!(
                        "{}: {} ({}) in {} {problem}",
                        e.id(),
                        symbol,
                        key.unwrap_or("result"),
                        eq.key
                    );
                    if !wrong.contains(&line) {
                        wrong.push(line);
                        eprintln!("{when}");
                    }
                }
            }
        }
    });
    assert!(
        wrong.is_empty(),
        "symbols unlike the Theory's:\n{}",
        wrong.join("\n")
    );
}

/// ik: x and y silently meant the wrist centre once a tool link was set.
/// The panel says which point: the target (x, y), or the wrist centre
/// (w_x, w_y), as the Theory names it.
#[test]
fn math_ik_says_which_point_its_x_and_y_are() {
    let mut e = lab("ik", &[("tx", 1.1), ("ty", 0.9)]);
    let named = |e: &dyn Lab| -> (Vec<&'static str>, &'static str) {
        let q = e.quantities();
        let symbols = ["px", "py"]
            .iter()
            .map(|k| q.iter().find(|q| q.key == *k).unwrap().symbol)
            .collect();
        (symbols, panel(e)[0].caption)
    };
    let (symbols, caption) = named(e.as_ref());
    assert_eq!(symbols, ["x", "y"]);
    assert!(caption.contains("for the target (x, y)"), "{caption}");
    e.set_param("l3", 0.3).unwrap();
    let (symbols, caption) = named(e.as_ref());
    assert_eq!(symbols, ["w_x", "w_y"]);
    assert!(caption.contains("for the wrist centre w"), "{caption}");
}
