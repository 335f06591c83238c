//! Every experiment's Procedure, played as a student (issue 52).
//!
//! Each step of `assets/<id>.json`'s `procedure` is its prose (`text`) and
//! its machine part (`play`): what the student does and what the text says
//! they will see, by the labels the page shows. One runner plays each
//! experiment's whole Procedure in order from a freshly opened page, every
//! step on the state the earlier ones left; a claim that does not hold names
//! the experiment, the step, its prose, the claim and what the page showed.
//! A mutation test proves the claims bite: altered by 20 %, or "larger"
//! swapped for "smaller", a claim must fail.
//!
//! The browser runner (`tests/e2e/procedures.mjs`, in three test files)
//! plays the same data on the built site.

mod page;
mod play;

use labcore::rng::Lcg64;
use serde_json::Value;

/// The `procedure` array of experiment `id`'s content file.
fn procedure(entry: &labcore::Entry) -> Vec<Value> {
    let file: Value = serde_json::from_str(entry.content_json).expect("content is JSON");
    file["procedure"].as_array().expect("a procedure").clone()
}

#[test]
fn every_procedure_holds_played_as_a_student() {
    let failures: Vec<String> = std::thread::scope(|scope| {
        let runs: Vec<_> = labcore::registry()
            .iter()
            .map(|entry| scope.spawn(move || play::play(entry.id, &procedure(entry), None)))
            .collect();
        runs.into_iter()
            .filter_map(|run| run.join().expect("the runner does not panic").err())
            .map(|f| f.to_string())
            .collect()
    });
    assert!(failures.is_empty(), "\n{}", failures.join("\n\n"));
}

/// One way to falsify a claim: the item `item` of step `step` (both from
/// 0) replaced by `mutated`.
#[derive(Clone, Debug)]
struct Mutant {
    step: usize,
    item: usize,
    mutated: Value,
    what: String,
}

/// The claim keys whose number a mutant moves by 20 % (a bound, `above`
/// or `below`, is mutated by swapping it instead: moving it outwards could
/// never fail, moving it inwards only tells how loose it is).
const SCALED: [&str; 2] = ["is", "about"];

/// The comparisons a mutant swaps.
const SWAPPED: [(&str, &str); 4] = [
    ("larger_than", "smaller_than"),
    ("smaller_than", "larger_than"),
    ("above", "below"),
    ("below", "above"),
];

/// Every mutant of one step's claims (`rng` picks whether a number grows or
/// shrinks by 20 %).
fn mutants_of(step: usize, items: &[Value], rng: &mut Lcg64) -> Vec<Mutant> {
    let mut out = Vec::new();
    for (i, item) in items.iter().enumerate() {
        let Some(o) = item.as_object() else { continue };
        let is_claim = ["see", "plot", "time"].iter().any(|k| o.contains_key(*k));
        if !is_claim {
            continue;
        }
        for key in SCALED {
            if let Some(n) = o.get(key).and_then(Value::as_f64).filter(|n| *n != 0.0) {
                let factor = if rng.next_f64() < 0.5 { 1.2 } else { 0.8 };
                let mut m = o.clone();
                m.insert(key.into(), (n * factor).into());
                out.push(Mutant {
                    step,
                    item: i,
                    mutated: Value::Object(m),
                    what: format!("{key} {n} → {}", n * factor),
                });
            }
        }
        for (from, to) in SWAPPED {
            if let Some(r) = o.get(from) {
                let mut m = o.clone();
                m.remove(from);
                m.insert(to.into(), r.clone());
                out.push(Mutant {
                    step,
                    item: i,
                    mutated: Value::Object(m),
                    what: format!("{from} → {to}"),
                });
            }
        }
        if let Some(range) = o.get("between").and_then(Value::as_array) {
            let mut m = o.clone();
            let moved: Vec<Value> = range
                .iter()
                .filter_map(Value::as_f64)
                .map(|n| (n * 1.2).into())
                .collect();
            m.insert("between".into(), moved.into());
            out.push(Mutant {
                step,
                item: i,
                mutated: Value::Object(m),
                what: "between ×1.2".into(),
            });
        }
        if let Some(words) = o.get("says").and_then(Value::as_str) {
            if let Some(changed) = scale_first_number(words, 1.2) {
                let mut m = o.clone();
                m.insert("says".into(), changed.clone().into());
                out.push(Mutant {
                    step,
                    item: i,
                    mutated: Value::Object(m),
                    what: format!("says “{words}” → “{changed}”"),
                });
            }
        }
    }
    out
}

/// `text` with its first non-zero number times `factor`, written with as
/// many decimals (or the next such number, when that rounds back).
fn scale_first_number(text: &str, factor: f64) -> Option<String> {
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() {
            let from = i;
            while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
                i += 1;
            }
            let written = &text[from..i];
            let n: f64 = written.parse().ok()?;
            if n == 0.0 {
                continue;
            }
            let decimals = written.split_once('.').map_or(0, |(_, d)| d.len());
            let mut changed = format!("{:.*}", decimals, n * factor);
            if changed == written {
                // 20 % of a small whole number rounds back to it ("1 of 1"):
                // the next number written with as many digits instead.
                changed = format!("{:.*}", decimals, n + 10f64.powi(-(decimals as i32)));
            }
            return Some(format!("{}{changed}{}", &text[..from], &text[i..]));
        }
        i += 1;
    }
    None
}

/// How many mutants the sample takes from each experiment.
const PER_EXPERIMENT: usize = 4;

#[test]
fn a_mutated_claim_makes_the_runner_fail() {
    let mut rng = Lcg64::new(52);
    let mut sample: Vec<(&'static str, Vec<Value>, Mutant)> = Vec::new();
    for entry in labcore::registry() {
        let steps = procedure(entry);
        let mut all: Vec<Mutant> = steps
            .iter()
            .enumerate()
            .flat_map(|(k, s)| {
                mutants_of(
                    k,
                    s["play"].as_array().map_or(&[][..], Vec::as_slice),
                    &mut rng,
                )
            })
            .collect();
        assert!(!all.is_empty(), "{}: no claim to mutate", entry.id);
        for _ in 0..PER_EXPERIMENT.min(all.len()) {
            let pick = rng.int(0, all.len() as i64 - 1) as usize;
            sample.push((entry.id, steps.clone(), all.swap_remove(pick)));
        }
    }
    let survivors: Vec<String> = std::thread::scope(|scope| {
        let runs: Vec<_> = sample
            .iter()
            .map(|(id, steps, m)| {
                scope.spawn(move || {
                    let mut steps = steps.clone();
                    steps[m.step]["play"][m.item] = m.mutated.clone();
                    match play::play(id, &steps, Some(m.step + 1)) {
                        Err(f) if f.step == m.step + 1 => None,
                        Err(f) => Some(format!(
                            "{id} step {}: {} failed elsewhere: {f}",
                            m.step + 1,
                            m.what
                        )),
                        Ok(()) => Some(format!(
                            "{id} step {}, item {}: {} survives",
                            m.step + 1,
                            m.item + 1,
                            m.what
                        )),
                    }
                })
            })
            .collect();
        runs.into_iter()
            .filter_map(|r| r.join().expect("the runner does not panic"))
            .collect()
    });
    let total = sample.len();
    println!("mutants killed: {} of {total}", total - survivors.len());
    assert!(survivors.is_empty(), "\n{}", survivors.join("\n"));
}

/// The whole population of mutants, not a sample: slow (every mutant
/// replays its Procedure up to its step), so run it with `--ignored` when
/// writing a Procedure.
#[test]
#[ignore = "slow: every mutant of every claim"]
fn every_claim_of_every_step_is_killed_by_its_mutants() {
    let mut survivors = Vec::new();
    let mut total = 0;
    let mut rng = Lcg64::new(52);
    for entry in labcore::registry() {
        let steps = procedure(entry);
        for (k, s) in steps.iter().enumerate() {
            for m in mutants_of(
                k,
                s["play"].as_array().map_or(&[][..], Vec::as_slice),
                &mut rng,
            ) {
                total += 1;
                let mut steps = steps.clone();
                steps[m.step]["play"][m.item] = m.mutated.clone();
                if !matches!(play::play(entry.id, &steps, Some(m.step + 1)), Err(f) if f.step == m.step + 1)
                {
                    survivors.push(format!("{} step {}: {}", entry.id, m.step + 1, m.what));
                }
            }
        }
    }
    println!("mutants killed: {} of {total}", total - survivors.len());
    assert!(survivors.is_empty(), "\n{}", survivors.join("\n"));
}
