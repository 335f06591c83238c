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
//! A sentence of the reading beyond the Procedure that says what this lab
//! shows (theory, aim, a caption of "The math", a hint, a status) is a claim
//! too: the content file's `claims`, each `{quote, play, given}`, where
//! `quote` is that sentence word for word and `play` its machine part,
//! played from a freshly opened page. A failure names the experiment, the
//! quoted sentence, the claim and what the page showed; a quote that is no
//! longer the text's own fails too. The mutation test samples these claims
//! as well.
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

/// The `claims` array of experiment `id`'s content file (none when absent).
fn claims(entry: &labcore::Entry) -> Vec<Value> {
    let file: Value = serde_json::from_str(entry.content_json).expect("content is JSON");
    file["claims"].as_array().cloned().unwrap_or_default()
}

/// A claim as a one-step Procedure: its quote is the step's prose.
fn as_step(claim: &Value) -> Vec<Value> {
    vec![serde_json::json!({"text": claim["quote"], "play": claim["play"]})]
}

/// The texts a claim may quote: the content file's summary, aim and theory
/// as written (LaTeX and all), and what the page shows in words: the
/// captions of "The math", the hints, the status, the notice and the tables'
/// captions.
fn quotable(entry: &labcore::Entry, page: &dyn labcore::experiment::Lab) -> Vec<String> {
    let file: Value = serde_json::from_str(entry.content_json).expect("content is JSON");
    let mut out = vec![file["summary"].as_str().unwrap_or_default().to_owned()];
    for v in file["aim"].as_array().into_iter().flatten() {
        out.extend(v.as_str().map(str::to_owned));
    }
    for block in file["theory"].as_array().into_iter().flatten() {
        out.extend(
            block
                .as_object()
                .into_iter()
                .flat_map(|o| o.values())
                .filter_map(Value::as_str)
                .map(str::to_owned),
        );
    }
    out.extend(page.equations().iter().map(|e| e.caption.to_owned()));
    out.push(page.hint().to_owned());
    out.push(page.touch_hint().to_owned());
    out.push(page.status().text);
    out.push(labcore::testkit::notice_text(page));
    out.extend(page.tables().into_iter().map(|t| t.caption));
    out
}

/// Plays each claim of experiment `entry` from a fresh page: the failures,
/// one per claim that does not hold or whose quote is not in the text it
/// quotes (on the fresh page or on the page the claim's play left).
fn check_claims(entry: &labcore::Entry) -> Vec<String> {
    let fresh = page::Page::open(entry.id);
    let before = quotable(entry, fresh.exp.as_ref());
    claims(entry)
        .iter()
        .enumerate()
        .filter_map(|(k, claim)| {
            let quote = claim["quote"].as_str().unwrap_or_default();
            let head = format!("{} claim {}: “{quote}”", entry.id, k + 1);
            match play::play_to(entry.id, &as_step(claim), None) {
                Err(f) => Some(format!(
                    "{head}\n    claim: {}\n    the page showed: {}",
                    f.item, f.shown
                )),
                Ok(page) => {
                    let after = quotable(entry, page.exp.as_ref());
                    let found = before.iter().chain(&after).any(|t| t.contains(quote));
                    (!found).then(|| {
                        format!(
                            "{head}\n    is not written in the summary, aim, theory, a caption of the math, a hint, the status, the notice or a table's caption"
                        )
                    })
                }
            }
        })
        .collect()
}

#[test]
fn every_claim_beyond_the_procedure_holds() {
    let failures: Vec<String> = std::thread::scope(|scope| {
        let runs: Vec<_> = labcore::registry()
            .iter()
            .map(|entry| scope.spawn(move || check_claims(entry)))
            .collect();
        runs.into_iter()
            .flat_map(|run| run.join().expect("the runner does not panic"))
            .collect()
    });
    assert!(failures.is_empty(), "\n{}", failures.join("\n\n"));
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

/// The browser runner reads the scene as a student does, from what
/// Describe says of it: so every claim of a Procedure about the scene says
/// where Describe puts it into words (`words`, with `#` for the number), and
/// the native runner checks the claim on those words as well as on the
/// scene as drawn. No step uses a plot property the page never shows
/// (`play::BROWSER_UNREAD`: those are for claims beyond the Procedure).
#[test]
fn every_scene_claim_of_a_procedure_says_its_words() {
    let unsaid: Vec<String> = labcore::registry()
        .iter()
        .flat_map(|entry| {
            procedure(entry)
                .into_iter()
                .enumerate()
                .flat_map(move |(k, step)| {
                    let items = step["play"].as_array().cloned().unwrap_or_default();
                    items
                        .into_iter()
                        .filter(|o| {
                            let unsaid = o.get("scene").is_some()
                                && !o["words"].as_str().is_some_and(|w| w.contains('#'));
                            let unread = o["of"]
                                .as_str()
                                .is_some_and(|of| play::BROWSER_UNREAD.contains(&of));
                            unsaid || unread
                        })
                        .map(move |o| format!("{} step {}: {o}", entry.id, k + 1))
                })
        })
        .collect();
    assert!(
        unsaid.is_empty(),
        "scene claims without `words` (Describe's words, # for the number), or of what the page never shows:\n{}",
        unsaid.join("\n")
    );
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
        let is_claim = ["see", "plot", "time", "scene"]
            .iter()
            .any(|k| o.contains_key(*k));
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

/// How many mutants the sample takes from each experiment's Procedure, and
/// from its claims beyond the Procedure.
const PER_EXPERIMENT: usize = 4;
const PER_EXPERIMENT_CLAIMS: usize = 2;

/// Every mutant of each claim beyond the Procedure of `entry`: the claim as
/// a one-step Procedure, its place ("claim 2") and the mutant.
fn claim_mutants(entry: &labcore::Entry, rng: &mut Lcg64) -> Vec<(Vec<Value>, String, Mutant)> {
    let mut out = Vec::new();
    for (k, claim) in claims(entry).iter().enumerate() {
        let steps = as_step(claim);
        let items = claim["play"].as_array().map_or(&[][..], Vec::as_slice);
        for m in mutants_of(0, items, rng) {
            out.push((steps.clone(), format!("claim {}", k + 1), m));
        }
    }
    out
}

/// Whether the runner fails a mutant at its own step: `None` if so, else
/// why not.
fn killed(id: &str, steps: &[Value], place: &str, m: &Mutant) -> Option<String> {
    let mut steps = steps.to_vec();
    steps[m.step]["play"][m.item] = m.mutated.clone();
    match play::play(id, &steps, Some(m.step + 1)) {
        Err(f) if f.step == m.step + 1 => None,
        Err(f) => Some(format!("{id} {place}: {} failed elsewhere: {f}", m.what)),
        Ok(()) => Some(format!(
            "{id} {place}, item {}: {} survives",
            m.item + 1,
            m.what
        )),
    }
}

#[test]
fn a_mutated_claim_makes_the_runner_fail() {
    let mut rng = Lcg64::new(52);
    // (experiment, its steps or a claim as one, where, the mutant)
    let mut sample: Vec<(&'static str, Vec<Value>, String, Mutant)> = Vec::new();
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
            let m = all.swap_remove(pick);
            let place = format!("step {}", m.step + 1);
            sample.push((entry.id, steps.clone(), place, m));
        }
        let mut beyond = claim_mutants(entry, &mut rng);
        for _ in 0..PER_EXPERIMENT_CLAIMS.min(beyond.len()) {
            let pick = rng.int(0, beyond.len() as i64 - 1) as usize;
            let (steps, place, m) = beyond.swap_remove(pick);
            sample.push((entry.id, steps, place, m));
        }
    }
    let survivors: Vec<String> = std::thread::scope(|scope| {
        let runs: Vec<_> = sample
            .iter()
            .map(|(id, steps, place, m)| scope.spawn(move || killed(id, steps, place, m)))
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
                let place = format!("step {}", m.step + 1);
                survivors.extend(killed(entry.id, &steps, &place, &m));
            }
        }
        for (steps, place, m) in claim_mutants(entry, &mut rng) {
            total += 1;
            survivors.extend(killed(entry.id, &steps, &place, &m));
        }
    }
    println!("mutants killed: {} of {total}", total - survivors.len());
    assert!(survivors.is_empty(), "\n{}", survivors.join("\n"));
}

/// Issue 53 §2, "what is shown is one run": the page model, as the page,
/// shows one run at one moment. PID's default step run to rest (27.27 s),
/// its response pinned there, then the slider back to t = 0.67 s (step
/// 40): the readouts say that moment (x = 0.697 m, no settling time yet),
/// the pinned run stays (its readout as at the end: overshoot 7.8 %,
/// settling 10.20 s, values read off the page at the end), and the plots
/// show the whole run with the cursor at the moment, where the curve is
/// the moment's own last sample (0.66 s, the control period's).
#[test]
fn scrubbed_back_the_page_shows_one_run_at_one_moment() {
    let mut page = page::Page::open("pid");
    page.wait_for_rest().unwrap();
    let end_s = page.time_s();
    assert_eq!(format!("{end_s:.2}"), "27.27");
    page.press("Pin run").unwrap();
    let pinned = page.readout("Pinned run A").unwrap();
    assert_eq!(
        pinned,
        "Kp 12 · Ki 2 · Kd 6, overshoot 7.8%, rise 0.82 s, settling 10.20 s"
    );
    page.scrub_to(0.67).unwrap();
    assert_eq!(page.readout("Position x").unwrap(), "0.697 m");
    assert_eq!(page.readout("Settling time (±2 %)").unwrap(), "--");
    assert_eq!(
        page.readout("Pinned run A").unwrap(),
        pinned,
        "the pin stays"
    );
    let plots = page.plots();
    let response = &plots[0];
    let own = response.series.iter().find(|s| !s.comparison).unwrap();
    // The whole run: its last sample is the run's end (every 0.01 s).
    assert!(
        (own.x.last().unwrap() - end_s).abs() < 0.01,
        "{:?}",
        own.x.last()
    );
    assert!(response
        .series
        .iter()
        .any(|s| s.label == "A: Kp 12, Ki 2, Kd 6" && s.len() == own.len()));
    let cursor = page.cursor("Step response").unwrap();
    assert_eq!(format!("{cursor:.2}"), "0.66");
    // Under the cursor, the curve is this run's at the moment shown.
    let k = own.nearest(cursor).unwrap();
    let moment = page.exp.plots()[0].series[0].y.last().copied().unwrap();
    assert_eq!(own.y[k], moment);
    assert_eq!(format!("{moment:.4}"), "0.6917");
    // Back at the end, no cursor: the page shows the run's end.
    page.scrub_to(end_s).unwrap();
    assert_eq!(page.cursor("Step response"), None);
}
