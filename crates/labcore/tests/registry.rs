//! Walks the registry: every experiment steps 1,000 times at default
//! parameters with finite output, every content file is complete, and every
//! parameterised question draws finite answers.

use labcore::quiz::{prepare, PreparedKind};
use labcore::{registry, Content, Input, ParamKind, Scene};
use std::path::Path;

#[test]
fn every_experiment_steps_1000_times_with_finite_values() {
    for entry in registry() {
        let mut exp = (entry.make)();
        assert_eq!(exp.id(), entry.id);
        let mut scene = Scene::default();
        for i in 0..1000 {
            exp.step(1.0 / 60.0);
            if i % 100 == 0 {
                scene.clear();
                exp.scene(&mut scene);
                assert!(
                    scene.is_finite(),
                    "{}: non-finite scene at step {i}",
                    entry.id
                );
            }
        }
        scene.clear();
        exp.scene(&mut scene);
        assert!(scene.is_finite(), "{}", entry.id);
        assert!(!scene.items.is_empty(), "{} draws nothing", entry.id);
        for r in exp.readouts() {
            assert!(
                !r.value.contains("NaN") && !r.value.contains("inf"),
                "{}: {r:?}",
                entry.id
            );
        }
        for spec in exp.params() {
            assert!(spec.min <= spec.default && spec.default <= spec.max);
            // Only optional fields may be unset.
            let Some(v) = exp.param(spec.key) else {
                assert_eq!(
                    spec.kind,
                    ParamKind::OptionalNumber,
                    "{}.{} has no value",
                    entry.id,
                    spec.key
                );
                continue;
            };
            assert!(
                v.is_finite() && v >= spec.min && v <= spec.max,
                "{}.{}",
                entry.id,
                spec.key
            );
        }
    }
}

#[test]
fn experiments_survive_hostile_input() {
    for entry in registry() {
        let mut exp = (entry.make)();
        let specs = exp.params();
        for spec in specs {
            for v in [f64::NAN, f64::INFINITY, -1e300, 1e300, spec.min, spec.max] {
                let _ = exp.set_param(spec.key, v);
                exp.step(1.0 / 60.0);
            }
        }
        for action in exp.actions() {
            exp.action(action.key).expect("declared actions run");
        }
        for p in [
            glam::DVec2::new(f64::NAN, 0.0),
            glam::DVec2::new(1e9, -1e9),
            glam::DVec2::ZERO,
        ] {
            exp.input(Input::PointerDown(p));
            exp.input(Input::PointerMove {
                pos: p,
                pressed: true,
            });
            exp.input(Input::PointerUp(p));
            exp.input(Input::Nudge(p));
            for _ in 0..50 {
                exp.step(1.0 / 60.0);
            }
        }
        let mut scene = Scene::default();
        exp.scene(&mut scene);
        assert!(scene.is_finite(), "{} after hostile input", entry.id);
    }
}

#[test]
fn every_registered_experiment_has_complete_content_and_generators() {
    for entry in registry() {
        let content = entry
            .content()
            .unwrap_or_else(|e| panic!("{}: {e}", entry.id));
        for seed in 0..50 {
            let attempt = prepare(content, entry.generators, seed).unwrap();
            for q in &attempt {
                assert!(
                    !q.prompt.contains('{'),
                    "{}: unfilled placeholder in {}",
                    entry.id,
                    q.prompt
                );
                assert!(
                    !q.explanation.contains("{"),
                    "{}: unfilled placeholder in {}",
                    entry.id,
                    q.explanation
                );
                if let PreparedKind::Numeric { answer, .. } = q.kind {
                    assert!(answer.is_finite(), "{}: {}", entry.id, q.prompt);
                }
            }
        }
        // Choice options are shuffled per attempt and still mark the same correct text.
        let mut positions = std::collections::HashSet::new();
        for seed in 0..40 {
            let attempt = prepare(content, entry.generators, seed).unwrap();
            for (q, original) in attempt.iter().zip(&content.quiz) {
                if let (
                    PreparedKind::Choice { options, answer },
                    labcore::content::Question::Choice {
                        options: source,
                        answer: source_answer,
                        ..
                    },
                ) = (&q.kind, original)
                {
                    assert_eq!(options[*answer], source[*source_answer]);
                    assert_eq!(options.len(), source.len());
                    positions.insert(*answer);
                }
            }
        }
        assert!(
            positions.len() > 1,
            "{}: the correct option moves between attempts",
            entry.id
        );
        let a = prepare(content, entry.generators, 1).unwrap();
        let b = prepare(content, entry.generators, 2).unwrap();
        assert_ne!(a, b, "{}: a new attempt draws new numbers", entry.id);
        assert_eq!(
            a,
            prepare(content, entry.generators, 1).unwrap(),
            "deterministic"
        );
    }
}

/// Every JSON file under `assets/` parses and is complete, registered or not.
#[test]
fn every_content_file_in_assets_is_complete() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            let text = std::fs::read_to_string(&path).unwrap();
            Content::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            seen += 1;
        }
    }
    assert!(seen >= registry().len());
}

#[test]
fn incomplete_content_is_rejected() {
    let good = registry()[0].content_json;
    let mut v: serde_json::Value = serde_json::from_str(good).unwrap();
    let check = |v: &serde_json::Value| Content::parse(&v.to_string());
    assert!(check(&v).is_ok());
    let mut no_refs = v.clone();
    no_refs["references"].as_array_mut().unwrap().truncate(2);
    assert!(check(&no_refs).is_err());
    let mut few = v.clone();
    few["quiz"].as_array_mut().unwrap().truncate(7);
    assert!(check(&few).is_err());
    let mut empty_aim = v.clone();
    empty_aim["aim"] = serde_json::json!([]);
    assert!(check(&empty_aim).is_err());
    let mut bad_choice = v.clone();
    let q = bad_choice["quiz"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|q| q["kind"] == "choice")
        .unwrap();
    q["answer"] = serde_json::json!(99);
    assert!(check(&bad_choice).is_err());
    let mut dup = v.clone();
    let q = dup["quiz"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|q| q["kind"] == "choice")
        .unwrap();
    let correct = q["options"][q["answer"].as_u64().unwrap() as usize].clone();
    q["options"].as_array_mut().unwrap().push(correct);
    assert!(check(&dup).is_err());
    v.as_object_mut().unwrap().remove("procedure");
    assert!(check(&v).is_err());
    assert!(Content::parse("not json").is_err());
}

/// Regression: `set_param("n", 2.5)` on DLS returned `InRange(2.5)` but stored
/// 3 (the workspace sample count likewise). Whatever is set, the returned
/// value is the stored one and `param()` stays inside its spec's range.
#[test]
fn set_param_returns_exactly_the_stored_value() {
    let mut rng = labcore::Lcg64::new(77);
    for entry in registry() {
        let mut exp = (entry.make)();
        for _ in 0..2000 {
            let spec = exp.params()[rng.int(0, exp.params().len() as i64 - 1) as usize];
            let span = spec.max - spec.min;
            let value = match rng.int(0, 3) {
                0 => rng.range(spec.min, spec.max),
                1 => rng.range(spec.min - span, spec.max + span),
                2 => (rng.range(spec.min, spec.max) * 2.0).round() / 2.0 + 0.5,
                _ => rng.int(spec.min as i64, spec.max as i64) as f64 + 0.5,
            };
            let applied = exp
                .set_param(spec.key, value)
                .unwrap_or_else(|e| panic!("{}.{}: {e}", entry.id, spec.key));
            assert_eq!(
                exp.param(spec.key),
                Some(applied.value()),
                "{}.{} set to {value}",
                entry.id,
                spec.key
            );
            if spec.integer {
                assert_eq!(applied.value().fract(), 0.0, "{}.{}", entry.id, spec.key);
            }
            exp.step(1.0 / 60.0);
            for s in exp.params() {
                if let Some(v) = exp.param(s.key) {
                    assert!(
                        v >= s.min && v <= s.max,
                        "{}.{} = {v} outside [{}, {}]",
                        entry.id,
                        s.key,
                        s.min,
                        s.max
                    );
                }
            }
        }
    }
}

/// Regression: a click near the edge of a wide canvas or a few arrow-key
/// nudges set an IK/DLS target beyond the typed range (`tx=3.24`), and the
/// link then reloaded clamped, with a notice. Property: after any seeded
/// sequence of pointer and keyboard input, the link formatted from the state,
/// parsed and applied to a fresh experiment gives the same state — the same
/// link and every parameter within the link's precision (3 decimals) — and
/// no notice.
/// Drives an experiment the way a student can: pointer presses, drags and
/// releases with and without Shift/Ctrl, keyboard nudges, typed parameter
/// values (any value the field accepts, clamped or not), buttons, and time.
fn random_session(exp: &mut dyn labcore::Lab, seed: u64) {
    random_session_with(exp, seed, &mut |exp, op| op(exp));
}

/// A student's input as an operation on the experiment; the shell runs it
/// through `run` (e.g. [`labcore::route::keep_locked`]).
type Op<'a> = &'a mut dyn FnMut(&mut dyn labcore::Lab);

/// [`random_session`] with every input, action, reset and run of steps
/// passed through `run`.
fn random_session_with(
    exp: &mut dyn labcore::Lab,
    seed: u64,
    run: &mut dyn FnMut(&mut dyn labcore::Lab, Op),
) {
    let view = exp.view();
    let mut rng = labcore::Lcg64::new(seed);
    for _ in 0..40 {
        // Up to twice the view's half-size: a wide canvas shows more than the view.
        let p = glam::DVec2::new(
            rng.range(2.0 * view.min.x, 2.0 * view.max.x),
            rng.range(2.0 * view.min.y, 2.0 * view.max.y),
        );
        let modifiers = labcore::Modifiers {
            shift: rng.next_f64() < 0.2,
            ctrl: rng.next_f64() < 0.1,
        };
        run(exp, &mut |exp| match rng.int(0, 7) {
            0 => exp.input_with(Input::PointerDown(p), modifiers),
            1 => exp.input_with(
                Input::PointerMove {
                    pos: p,
                    pressed: true,
                },
                modifiers,
            ),
            2 => exp.input_with(
                Input::PointerMove {
                    pos: p,
                    pressed: false,
                },
                modifiers,
            ),
            3 => exp.input_with(Input::PointerUp(p), modifiers),
            4 => exp.input_with(Input::Nudge(p * 0.1), modifiers),
            5 => {
                let specs = exp.params();
                if !specs.is_empty() {
                    let spec = specs[rng.int(0, specs.len() as i64 - 1) as usize];
                    // A typed value: anywhere in (a little beyond) the range,
                    // with as many decimals as a student cares to type.
                    let span = (spec.max - spec.min).max(1e-9);
                    let v = rng.range(spec.min - 0.1 * span, spec.max + 0.1 * span);
                    let v = match rng.int(0, 2) {
                        0 => v,
                        1 => (v * 1e4).round() / 1e4,
                        _ => spec.default,
                    };
                    let _ = exp.set_param(spec.key, v);
                }
            }
            6 => {
                let actions = exp.actions();
                if !actions.is_empty() {
                    let a = actions[rng.int(0, actions.len() as i64 - 1) as usize];
                    let _ = exp.action(a.key);
                }
            }
            _ => exp.reset(),
        });
        let steps = rng.int(0, 30);
        run(exp, &mut |exp| {
            for _ in 0..steps {
                exp.step(1.0 / 60.0);
            }
        });
    }
}

/// Every state a student reaches by pointer, keyboard, typed values and
/// buttons reloads exactly from its link: format, parse, apply gives the
/// same link, every parameter exactly, and no notice.
#[test]
fn permalinks_reproduce_every_state_reachable_by_pointer_and_keyboard() {
    use labcore::route::{apply_params, format, parse, Page, Tab};
    let ids: Vec<&str> = registry().iter().map(|e| e.id).collect();
    for entry in registry() {
        for seed in 0..60 {
            let mut exp = (entry.make)();
            random_session(exp.as_mut(), seed);
            let link = format(exp.as_ref(), Tab::Simulation);
            // Issue 26 §3: the run's marks travel beside the state
            // (`marks=1.20,3.45`, read by the shell) and come back exactly.
            let mut marks = labcore::marks::Marks::default();
            let mut rng = labcore::Lcg64::new(seed);
            for _ in 0..rng.int(0, 5) {
                marks.add(rng.int(0, 36_000) as u64);
            }
            let marked_link = if exp.animated() && !marks.is_empty() {
                let sep = if link.contains('?') { '&' } else { '?' };
                format!("{link}{sep}marks={}", marks.link_value())
            } else {
                link.clone()
            };
            let route = parse(&marked_link, &ids);
            assert!(
                route.notices.is_empty(),
                "{marked_link}: {:?}",
                route.notices
            );
            let Page::Experiment { mut params, .. } = route.page else {
                panic!("{link} is not an experiment page");
            };
            let linked_marks = match params.iter().position(|(k, _)| k == "marks") {
                Some(i) => labcore::marks::Marks::parse(&params.remove(i).1).unwrap(),
                None => labcore::marks::Marks::default(),
            };
            if exp.animated() {
                assert_eq!(linked_marks, marks, "{marked_link}");
            }
            let mut fresh = (entry.make)();
            let notices = apply_params(fresh.as_mut(), &params);
            assert!(
                notices.is_empty(),
                "{} seed {seed}: {link}: {notices:?}",
                entry.id
            );
            assert_eq!(format(fresh.as_ref(), Tab::Simulation), link, "seed {seed}");
            for spec in exp.params() {
                let (a, b) = (exp.param(spec.key), fresh.param(spec.key));
                // Exact equality (−0 and 0 are one value).
                assert!(
                    a == b,
                    "{}.{}: {a:?} became {b:?} via {link}",
                    entry.id,
                    spec.key
                );
            }
        }
    }
}

/// Issue 17 §2: an instructor's link carries its locks, hidden controls,
/// note and quiz seed beside the state. For random sessions and random
/// choices: format → parse → apply gives the same locks, hides, note, seed
/// and state, without a notice.
#[test]
fn instructor_links_round_trip_locks_hides_notes_and_the_quiz_seed() {
    use labcore::route::{
        apply_params, format, format_instructor, parse, AnswerKey, Instructor, Page, Tab,
    };
    let ids: Vec<&str> = registry().iter().map(|e| e.id).collect();
    // Characters a note may hold, those a URL must escape among them.
    const NOTE_CHARS: &[char] = &[
        'a', 'Z', '7', ' ', '&', '=', '?', '#', '%', '+', ',', '<', '>', '"', '\'', 'é', 'θ', '≤',
        '😀', '/', ';',
    ];
    for entry in registry() {
        for seed in 0..8 {
            let mut exp = (entry.make)();
            random_session(exp.as_mut(), seed);
            let mut rng = labcore::Lcg64::new(seed + 10_000);
            let mut keys = |p: f64| -> Vec<String> {
                exp.params()
                    .iter()
                    .filter(|_| rng.next_f64() < p)
                    .map(|s| s.key.to_owned())
                    .collect()
            };
            let locked = keys(0.3);
            let hidden = keys(0.2);
            let note: String = (0..rng.int(0, 60))
                .map(|_| NOTE_CHARS[rng.int(0, NOTE_CHARS.len() as i64 - 1) as usize])
                .collect();
            let note = Some(note.trim().to_owned()).filter(|n| !n.is_empty());
            let quiz = (rng.next_f64() < 0.5).then(|| rng.int(0, 999_999) as u64);
            // The quiz's grading rules (issue 24): attempts allowed, score rule.
            let rules = labcore::route::QuizRules {
                attempts: (rng.next_f64() < 0.5).then(|| rng.int(1, 20) as u32),
                score: labcore::route::ScoreRule::ALL[rng.int(0, 2) as usize],
            };
            let answer_key = (rng.next_f64() < 0.5).then(|| AnswerKey::ALL[rng.int(0, 2) as usize]);
            let instructor = Instructor {
                locked,
                hidden,
                note,
                quiz: rules,
                answer_key,
            };
            let link = format_instructor(exp.as_ref(), Tab::Simulation, &instructor, quiz);
            let route = parse(&link, &ids);
            assert!(route.notices.is_empty(), "{link}: {:?}", route.notices);
            assert_eq!(route.quiz_seed, quiz, "{link}");
            let mut back = route.instructor;
            let Page::Experiment { params, .. } = route.page else {
                panic!("{link}");
            };
            let mut fresh = (entry.make)();
            assert!(back.resolve(fresh.params()).is_empty(), "{link}");
            assert_eq!(back, instructor, "{link}");
            let notices = apply_params(fresh.as_mut(), &params);
            assert!(notices.is_empty(), "{link}: {notices:?}");
            assert_eq!(
                format(fresh.as_ref(), Tab::Simulation),
                format(exp.as_ref(), Tab::Simulation)
            );
        }
    }
}

/// Whatever a student does, through pointer, keyboard, typed values,
/// actions, resets and running the clock, a locked parameter keeps the value it had when the
/// link was opened (the shell runs every input through `keep_locked`).
#[test]
fn locked_parameters_survive_random_sessions() {
    use labcore::route::{keep_locked, Instructor};
    for entry in registry() {
        for seed in 0..8 {
            let mut exp = (entry.make)();
            random_session(exp.as_mut(), seed);
            let mut rng = labcore::Lcg64::new(seed + 20_000);
            let locked: Vec<String> = exp
                .params()
                .iter()
                .filter(|_| rng.next_f64() < 0.4)
                .map(|s| s.key.to_owned())
                .collect();
            let before: Vec<Option<f64>> = locked.iter().map(|k| exp.param(k)).collect();
            let instructor = Instructor {
                locked: locked.clone(),
                ..Instructor::default()
            };
            random_session_with(exp.as_mut(), seed + 1, &mut |exp, op| {
                let _ = keep_locked(exp, &instructor, |e| op(e));
            });
            for (key, was) in locked.iter().zip(before) {
                // An unset optional field a drag then sets cannot be unset
                // again by a value: only keys that had a value are held.
                if was.is_some() {
                    assert_eq!(exp.param(key), was, "{}.{key} seed {seed}", entry.id);
                }
            }
        }
    }
}

/// Issue 13 §2: a link opened in a tab that already shows the experiment
/// gives exactly what a fresh page gives: what the link leaves out takes its
/// default, nothing is kept from what the tab showed before.
#[test]
fn a_link_opened_in_a_used_tab_gives_the_fresh_page_state() {
    use labcore::route::{apply_params, format, open_in_tab, parse, Page, Tab};
    let ids: Vec<&str> = registry().iter().map(|e| e.id).collect();
    for entry in registry() {
        for seed in 0..20 {
            // The second link: another student's state, or the default link.
            let mut other = (entry.make)();
            if seed % 4 != 0 {
                random_session(other.as_mut(), 1000 + seed);
            }
            let link = format(other.as_ref(), Tab::Simulation);
            let Page::Experiment { params, .. } = parse(&link, &ids).page else {
                panic!("{link}");
            };
            let mut fresh = (entry.make)();
            let fresh_notices = apply_params(fresh.as_mut(), &params);
            // The tab: this student's own session, then the link pasted.
            let mut tab = (entry.make)();
            random_session(tab.as_mut(), seed);
            let notices = open_in_tab(&mut tab, entry.make, &params);
            assert_eq!(notices, fresh_notices);
            assert_eq!(
                snapshot(tab.as_ref()),
                snapshot(fresh.as_ref()),
                "{} seed {seed}: {link}",
                entry.id
            );
        }
    }
}

/// A tab link (`#/id/theory`, no parameters) keeps the state.
#[test]
fn a_tab_link_keeps_the_state() {
    use labcore::route::open_in_tab;
    for entry in registry() {
        let mut tab = (entry.make)();
        random_session(tab.as_mut(), 5);
        let before = snapshot(tab.as_ref());
        assert!(open_in_tab(&mut tab, entry.make, &[]).is_empty());
        assert_eq!(snapshot(tab.as_ref()), before, "{}", entry.id);
    }
}

/// Regression: lengths showed 3 trimmed decimals in FK/IK (`1.5 m`), 4 in the
/// workspace and 4 or `1.0e-7` in DLS; angles 1 decimal in IK, 0 in DLS; the
/// condition number as `123456.79`. Now every length has 3 decimals, every
/// angle 1, and huge or tiny magnitudes read as `2.4 × 10⁵`.
#[test]
fn readouts_use_the_same_decimals_in_every_experiment() {
    fn decimals(number: &str) -> usize {
        number.split_once('.').map_or(0, |(_, d)| d.len())
    }
    for entry in registry() {
        let mut exp = (entry.make)();
        for action in exp.actions() {
            exp.action(action.key).unwrap();
        }
        for p in [
            glam::DVec2::new(0.9, 0.8),
            glam::DVec2::new(2.0, 0.3),
            glam::DVec2::new(-0.2, 1.4),
        ] {
            exp.input(Input::PointerDown(p));
            for _ in 0..200 {
                exp.step(1.0 / 60.0);
            }
            for r in exp.readouts() {
                for part in r.value.split(", ") {
                    if part == "--" || part.contains('×') || part.contains('∞') {
                        continue;
                    }
                    if let Some(number) = part.strip_suffix(" m") {
                        assert_eq!(decimals(number), 3, "{}.{}: {part}", entry.id, r.key);
                    } else if let Some(number) = part.strip_suffix('°') {
                        assert_eq!(decimals(number), 1, "{}.{}: {part}", entry.id, r.key);
                    } else if let Some(number) = part.strip_suffix('%') {
                        assert_eq!(decimals(number), 1, "{}.{}: {part}", entry.id, r.key);
                    }
                }
                if r.key == "cond" {
                    let v = &r.value;
                    assert!(
                        v == "∞ (singular)" || v.contains(" × 10") || decimals(v) == 1,
                        "condition number {v}"
                    );
                }
            }
        }
    }
}

/// Validation rejects a choice with fewer than two options, an answer index
/// out of range and a tolerance finer than the answer's shown precision.
#[test]
fn content_validation_rejects_unfair_questions() {
    let good: serde_json::Value = serde_json::from_str(registry()[0].content_json).unwrap();
    let check = |v: &serde_json::Value| Content::parse(&v.to_string());
    let edit = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut v = good.clone();
        let q = v["quiz"]
            .as_array_mut()
            .unwrap()
            .iter_mut()
            .find(|q| q["kind"] == "choice")
            .unwrap();
        f(q);
        v
    };
    let one_option = edit(&|q| {
        q["options"] = serde_json::json!(["only"]);
        q["answer"] = serde_json::json!(0);
    });
    assert!(check(&one_option).is_err());
    let out_of_range = edit(&|q| q["answer"] = serde_json::json!(4));
    assert!(check(&out_of_range).is_err());
    let mut too_fine = good.clone();
    let q = too_fine["quiz"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|q| q["kind"] == "generated")
        .unwrap();
    q["tolerance"] = serde_json::json!(0.0001);
    let err = check(&too_fine).unwrap_err();
    assert!(
        matches!(err, labcore::content::ContentError::ToleranceTooFine { .. }),
        "{err}"
    );
    assert!(err.to_string().contains("finer than"));
}

/// References carry a DOI or a stable URL where one exists: every experiment
/// links at least one, and a malformed DOI is refused.
#[test]
fn references_carry_dois_or_stable_urls() {
    for entry in registry() {
        let content = entry.content().unwrap();
        let links: Vec<String> = content.references.iter().filter_map(|r| r.link()).collect();
        assert!(
            !links.is_empty(),
            "{}: no reference links anywhere",
            entry.id
        );
        assert!(links.iter().all(|l| l.starts_with("http")), "{links:?}");
    }
    let mut v: serde_json::Value = serde_json::from_str(registry()[0].content_json).unwrap();
    v["references"][0]["doi"] = serde_json::json!("https://doi.org/10.1/x");
    assert!(Content::parse(&v.to_string()).is_err());
}

/// labcore re-exports glam, so users of its `DVec2` API need no separate,
/// version-matched dependency; every returned angle is wrapped to [-π, π].
#[test]
fn glam_is_reexported_and_returned_angles_are_wrapped() {
    use labcore::glam::DVec2;
    use labcore::kinematics::{chain, dls::DlsSolver, two_link_ik};
    use std::f64::consts::PI;
    let pose = chain::forward(&[1.0, 1.0], &[3.0, 3.0]);
    let tip: DVec2 = pose.tip();
    assert!(tip.is_finite());
    assert!((-PI..=PI).contains(&pose.tip_angle_rad));
    let mut rng = labcore::Lcg64::new(9);
    for _ in 0..500 {
        let mut q = [
            rng.range(-20.0, 20.0),
            rng.range(-20.0, 20.0),
            rng.range(-20.0, 20.0),
        ];
        let target = DVec2::new(rng.range(-3.5, 3.5), rng.range(-3.5, 3.5));
        let lengths = [1.0, 0.8, 0.6];
        DlsSolver::default()
            .solve(&lengths, &mut q, target)
            .unwrap();
        assert!(q.iter().all(|a| (-PI..=PI).contains(a)), "{q:?}");
        let mut q = [
            rng.range(-20.0, 20.0),
            rng.range(-20.0, 20.0),
            rng.range(-20.0, 20.0),
        ];
        DlsSolver::default().step(&lengths, &mut q, target).unwrap();
        assert!(q.iter().all(|a| (-PI..=PI).contains(a)), "{q:?}");
        if let Ok(sol) = two_link_ik::solve(1.0, 0.8, target) {
            for a in [sol.elbow_up, sol.elbow_down] {
                assert!((-PI..=PI).contains(&a.theta1_rad) && (-PI..=PI).contains(&a.theta2_rad));
            }
        }
    }
}

/// Everything observable about an experiment: its link, display list,
/// readouts, status and plots.
fn snapshot(exp: &dyn labcore::Lab) -> String {
    let mut scene = Scene::default();
    exp.scene(&mut scene);
    format!(
        "{}\n{:?}\n{:?}\n{:?}\n{:?}",
        labcore::route::format(exp, labcore::route::Tab::Simulation),
        scene,
        exp.readouts(),
        exp.status(),
        // The revision counter only tells the page what to redraw.
        exp.plots()
            .iter()
            .map(|p| labcore::Plot {
                revision: 0,
                ..p.clone()
            })
            .collect::<Vec<_>>()
    )
}

/// Puts an experiment in motion: a click near the middle of its view and its
/// first action (a sweep, a solve).
fn set_in_motion(exp: &mut dyn labcore::Lab) {
    let view = exp.view();
    let p = view.min + (view.max - view.min) * glam::DVec2::new(0.62, 0.58);
    exp.input(Input::PointerDown(p));
    exp.input(Input::PointerUp(p));
    if let Some(action) = exp
        .actions()
        .iter()
        .find(|a| a.key != "clear" && a.key != "reset")
    {
        exp.action(action.key).expect("listed action runs");
    }
}

#[test]
fn a_bad_dt_is_refused_and_changes_nothing() {
    for entry in registry() {
        let mut exp = (entry.make)();
        set_in_motion(exp.as_mut());
        exp.step(labcore::Clock::DT_S);
        let before = snapshot(exp.as_ref());
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -0.01, 0.0, 1.0] {
            exp.step(bad);
            assert_eq!(snapshot(exp.as_ref()), before, "{}: dt {bad}", entry.id);
        }
    }
}

#[test]
fn n_single_steps_equal_running_for_n_steps() {
    let mut rng = labcore::Lcg64::new(2024);
    for entry in registry() {
        let mut running = (entry.make)();
        set_in_motion(running.as_mut());
        let mut stepped = (entry.make)();
        set_in_motion(stepped.as_mut());
        // Run with ragged frame times, as a browser delivers them.
        let mut clock = labcore::Clock::default();
        clock.set_speed([0.25, 0.5, 1.0, 2.0, 4.0][rng.int(0, 4) as usize]);
        while clock.steps() < 200 {
            let n = clock.advance(rng.range(0.004, 0.05));
            for _ in 0..n {
                running.step(labcore::Clock::DT_S);
            }
        }
        let mut pause = labcore::Clock::default();
        for _ in 0..clock.steps() {
            pause.single_step(1, || {
                stepped.step(labcore::Clock::DT_S);
                true
            });
        }
        assert_eq!(pause.steps(), clock.steps());
        assert_eq!(
            snapshot(running.as_ref()),
            snapshot(stepped.as_ref()),
            "{}",
            entry.id
        );
    }
}

#[test]
fn reset_replays_the_same_run() {
    for entry in registry() {
        let mut exp = (entry.make)();
        set_in_motion(exp.as_mut());
        exp.reset();
        let start = snapshot(exp.as_ref());
        for _ in 0..120 {
            exp.step(labcore::Clock::DT_S);
        }
        let first = snapshot(exp.as_ref());
        exp.reset();
        assert_eq!(snapshot(exp.as_ref()), start, "{}: reset state", entry.id);
        for _ in 0..120 {
            exp.step(labcore::Clock::DT_S);
        }
        assert_eq!(snapshot(exp.as_ref()), first, "{}: replay", entry.id);
    }
}

#[test]
fn plots_hold_finite_data_and_export_every_sample() {
    for entry in registry() {
        let mut exp = (entry.make)();
        set_in_motion(exp.as_mut());
        for _ in 0..300 {
            exp.step(labcore::Clock::DT_S);
        }
        for plot in exp.plots() {
            let csv = plot.to_csv();
            let rows = csv.lines().count() - 1;
            let longest = plot.series.iter().map(|s| s.len()).max().unwrap_or(0);
            assert_eq!(rows, longest, "{}.{}", entry.id, plot.key);
            assert!(plot
                .series
                .iter()
                .all(|s| s.x.len() == s.y.len() && s.x.iter().chain(&s.y).all(|v| v.is_finite())));
            if plot.log_y {
                assert!(plot.y_label.len() + plot.title.len() > 0);
            }
            assert!(!plot.summary().is_empty());
        }
    }
    // The experiments named in the platform issues plot something once in motion.
    for (id, keys) in [
        ("dls", &["error", "manipulability"][..]),
        ("workspace", &["radii"][..]),
        ("diffdrive", &["motion"][..]),
        ("potential", &["run"][..]),
        ("ekf", &["error_x", "error_y", "nees", "trace", "anees"][..]),
    ] {
        let mut exp = (labcore::find(id).expect("registered").make)();
        set_in_motion(exp.as_mut());
        for _ in 0..300 {
            exp.step(labcore::Clock::DT_S);
        }
        let got: Vec<&str> = exp.plots().iter().map(|p| p.key).collect();
        assert_eq!(got, keys, "{id}");
        assert!(
            exp.plots().iter().all(|p| p.sample_count() > 1),
            "{id} plots data"
        );
    }
}

/// Issue 15: the correct option was the longest in 42 of 63 choice questions
/// (67 %), so a test-wise student could guess it. The first fix overshot: it
/// was then strictly the longest in 1 of 63 and the third longest in 26, so
/// "never pick the longest" and "pick the third longest" became tells. Across
/// the lab the correct option must be strictly the longest in 10–25 % of the
/// choice questions (chance with four options is 25 %), strictly the shortest
/// in at most 35 %, and each length rank (how many options are strictly
/// longer than the correct one) must hold 12.5–37.5 % of them.
#[test]
fn option_lengths_do_not_give_the_answer_away() {
    let mut lab = labcore::content::LengthTells::default();
    for entry in registry() {
        let tells = entry.content().expect("content parses").length_tells();
        lab.choices += tells.choices;
        lab.longest += tells.longest;
        lab.shortest += tells.shortest;
        for (sum, n) in lab.by_rank.iter_mut().zip(tells.by_rank) {
            *sum += n;
        }
    }
    println!(
        "{} choice questions; correct option strictly longest in {}, strictly shortest in {}; \
         by rank (0 = longest or tied, 3 = shortest): {:?}",
        lab.choices, lab.longest, lab.shortest, lab.by_rank
    );
    assert!(lab.choices >= 50, "{lab:?}");
    assert_eq!(lab.by_rank.iter().sum::<usize>(), lab.choices, "{lab:?}");
    // 10 % ≤ longest ≤ 25 %: 10 × longest ≥ choices, 4 × longest ≤ choices.
    assert!(10 * lab.longest >= lab.choices, "{lab:?}");
    assert!(4 * lab.longest <= lab.choices, "{lab:?}");
    // At most 35 %: 20 × count ≤ 7 × choices.
    assert!(20 * lab.shortest <= 7 * lab.choices, "{lab:?}");
    // Every rank within 12.5 points of chance (25 %): 1/8 … 3/8.
    for (rank, &n) in lab.by_rank.iter().enumerate() {
        assert!(
            8 * n >= lab.choices && 8 * n <= 3 * lab.choices,
            "rank {rank}: {lab:?}"
        );
    }
}

/// Issue 15: a generated question must be one a student can set up on the
/// page: every drawn value whose placeholder is named after a parameter lies
/// inside that parameter's slider range (fk drew L₁ up to 2.0 m while the
/// slider stops at 1.2 m). The experiments' own tests check the placeholders
/// with other names.
#[test]
fn generators_draw_inside_the_sliders_ranges() {
    let mut checked = 0;
    for entry in registry() {
        let exp = (entry.make)();
        let content = entry.content().expect("content parses");
        for q in &content.quiz {
            let labcore::content::Question::Generated { generator, .. } = q else {
                continue;
            };
            let draw_fn = (entry.generators)(generator).expect("generator exists");
            for seed in 0..400 {
                let draw = draw_fn(&mut labcore::Lcg64::new(seed));
                for (name, _) in &draw.vars {
                    let Some(spec) = exp.params().iter().find(|s| s.key == *name) else {
                        continue;
                    };
                    let v = draw.var(name).expect("a drawn parameter reads as a number");
                    // The shown value is rounded: half its last decimal of slack.
                    let slack = 1e-6 * (spec.max - spec.min).abs().max(1.0) + 0.005;
                    assert!(
                        v >= spec.min - slack && v <= spec.max + slack,
                        "{} generator {generator} seed {seed}: {name} = {v} outside the slider's {}…{}",
                        entry.id,
                        spec.min,
                        spec.max
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(
        checked > 1000,
        "only {checked} drawn values were named after parameters"
    );
}

/// The page stops time when a run has ended (`Phase::Ended`) and offers
/// Replay. So an ended run must have nothing left to show: stepping it
/// changes nothing a student sees. Work started after the end (a basin map, a
/// comparison, a sweep) must report its run as live until it is done.
#[test]
fn an_ended_run_has_nothing_left_to_show() {
    // A session that ends, then (for `action`) one button pressed after the end.
    let ended_session = |entry: &labcore::Entry, seed: u64, action: Option<&str>| {
        let mut exp = (entry.make)();
        random_session(exp.as_mut(), 7000 + seed);
        labcore::testkit::run_until_phase(exp.as_mut(), labcore::Phase::Ended, 600);
        let ended = exp.status().phase == labcore::Phase::Ended;
        if let Some(key) = action {
            let _ = exp.action(key);
        }
        (exp, ended)
    };
    let mut checked = 0;
    for entry in registry() {
        let actions: Vec<Option<&str>> = std::iter::once(None)
            .chain((entry.make)().actions().iter().map(|a| Some(a.key)))
            .collect();
        for seed in 0..12 {
            for &action in &actions {
                let (mut exp, ended) = ended_session(entry, seed, action);
                if !ended || exp.status().phase != labcore::Phase::Ended {
                    continue;
                }
                let before = snapshot(exp.as_ref());
                for _ in 0..30 {
                    exp.step(1.0 / 60.0);
                }
                assert_eq!(
                    snapshot(exp.as_ref()),
                    before,
                    "{} seed {seed}, {action:?} after the end: stepping an ended run changed what is shown ({:?})",
                    entry.id,
                    exp.status()
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 50, "only {checked} ended runs were checked");
}

/// Issue 14's A* sequences join the permalink property: the goal set to
/// (5, 5) and the start dragged onto the default goal's cell (28, 11); the
/// ends (31, 23) and (30, 22) and then the smallest size; a two-cell linked
/// grid. Each is followed by random student input, then the state must reload
/// exactly from its link with no notice, and the ends never share a cell.
#[test]
fn permalinks_reproduce_the_issue_14_astar_sequences() {
    use labcore::experiments::astar::AStarGrid;
    use labcore::planning::grid::Cell;
    use labcore::route::{format, restore, Tab};
    use labcore::{Experiment, Modifiers};
    let (ctrl, shift) = (labcore::testkit::CTRL, labcore::testkit::SHIFT);
    let drag = |a: &mut AStarGrid, from: Cell, to: Cell| {
        a.input(Input::PointerDown(a.cell_center(from)));
        a.input(Input::PointerMove {
            pos: a.cell_center(to),
            pressed: true,
        });
        a.input(Input::PointerUp(a.cell_center(to)));
    };
    type Sequence = fn(&mut AStarGrid, &dyn Fn(&mut AStarGrid, Cell, Cell), Modifiers, Modifiers);
    let sequences: [(&str, Sequence); 3] = [
        (
            "goal (5,5), start dragged onto (28,11)",
            |a, drag, ctrl, _| {
                a.input_with(Input::PointerDown(a.cell_center(Cell::new(5, 5))), ctrl);
                a.input(Input::PointerUp(a.cell_center(Cell::new(5, 5))));
                drag(a, a.start(), Cell::new(28, 11));
            },
        ),
        (
            "ends (31,23), (30,22), then the smallest size",
            |a, _, ctrl, shift| {
                a.input_with(Input::PointerDown(a.cell_center(Cell::new(31, 23))), shift);
                a.input_with(Input::PointerDown(a.cell_center(Cell::new(30, 22))), ctrl);
                let min = a
                    .params()
                    .iter()
                    .find(|s| s.key == "size")
                    .map_or(0.0, |s| s.min);
                let _ = a.set_param("size", min);
            },
        ),
        ("a two-cell grid from a link", |a, _, _, _| {
            let _ = labcore::route::apply_params(a, &[("walls".into(), "1x2.1.1".into())]);
        }),
    ];
    for (what, sequence) in sequences {
        for seed in 0..40 {
            let mut a = AStarGrid::default();
            sequence(&mut a, &drag, ctrl, shift);
            if seed > 0 {
                random_session(&mut a, 9000 + seed);
            }
            assert_ne!(
                a.start(),
                a.goal(),
                "{what}, seed {seed}: the ends share a cell"
            );
            let link = format(&a, Tab::Simulation);
            let (fresh, notices) = restore(&link, AStarGrid::default());
            assert!(
                notices.is_empty(),
                "{what}, seed {seed}: {link}: {notices:?}"
            );
            assert_eq!(format(&fresh, Tab::Simulation), link, "{what}, seed {seed}");
            assert_eq!(
                (fresh.start(), fresh.goal()),
                (a.start(), a.goal()),
                "{what}"
            );
        }
    }
}
