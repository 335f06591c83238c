//! What a SCORM 1.2 LMS keeps for one experiment between launches.
//!
//! The lab's quiz attempt (seed and answers, see [`SavedAttempt`]) plus
//! whether it was submitted, as the text the page stores in
//! `cmi.suspend_data`. SCORM 1.2 caps that element at 4,096 characters
//! (ADL, *SCORM 1.2 Run-Time Environment*, §3.4.4, `CMIString4096`), so
//! [`Suspended::encode`] never returns more: it shortens long typed answers
//! first, then leaves trailing answers out, and the seed and the submitted
//! flag are always kept (a relaunch rebuilds the same questions).
//!
//! "Characters" are counted differently by Rust (Unicode scalar values),
//! JavaScript and LMS runtimes (UTF-16 units) and some LMS databases
//! (bytes). The text is therefore plain ASCII: every other character is
//! written as a JSON `\uXXXX` escape, so all of them count the same length.
//! The quiz caps a typed answer at [`ANSWER_MAX_UNITS`] UTF-16 units (the
//! page's `maxlength`), so a whole attempt always fits.
//!
//! [`launch`] reads a SCO's launch query (`index.html?sco=pid&attempts=2`),
//! also when an LMS mangled it.
//! It also keeps the [`Tally`] of graded attempts, so an instructor's
//! attempts limit and score rule ([`QuizRules`]) hold across launches.

use crate::json::Json;
use crate::quiz::{
    answers_from_json, answers_json, seed_from_json, seed_json, Response, SavedAttempt,
};
use crate::route::{Instructor, QuizRules};
use std::fmt::Write as _;

/// The most characters `cmi.suspend_data` holds in SCORM 1.2.
pub const SUSPEND_DATA_MAX_CHARS: usize = 4096;

/// The longest typed answer, in UTF-16 code units (what an HTML
/// `maxlength` counts; the quiz's inputs carry it): a unit takes at most 6
/// characters once escaped, so 12 answers of it fit `suspend_data` with
/// room to spare. A longer text (an old attempt) is cut to it when the
/// whole would not fit.
pub const ANSWER_MAX_UNITS: usize = 40;

/// What a SCO's launch query says: the experiment the SCO is for and the
/// instructor's settings the package put there.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Launch {
    /// The experiment (`pid`): the leading id of `sco=`.
    pub sco: String,
    /// The package's grading rules and answer-key choice (`attempts=`,
    /// `score=`, `key=`); a fragment's never replace them.
    pub instructor: Instructor,
}

/// Reads a launch query (`?sco=pid&attempts=2`, the `?` optional). An LMS
/// that appends its own query with a second `?`
/// (`?sco=pid?scorm_launch=1&…`) is read as if it had used `&`, and `sco=`
/// names its leading id (letters, digits, `-`, `_`). `None` when no SCO is
/// named (the query was dropped).
#[must_use]
pub fn launch(search: &str) -> Option<Launch> {
    let query = search.strip_prefix('?').unwrap_or(search).replace('?', "&");
    let sco: String = query
        .split('&')
        .find_map(|pair| pair.strip_prefix("sco="))?
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '-' || *c == '_')
        .collect();
    if sco.is_empty() {
        return None;
    }
    let instructor = crate::route::parse(&format!("#/x?{query}"), &["x"]).instructor;
    Some(Launch { sco, instructor })
}

/// One experiment's quiz attempt as kept by the LMS.
#[derive(Clone, Debug, PartialEq)]
pub struct Suspended {
    /// The experiment (`pid`, `astar`, …) the attempt belongs to.
    pub id: String,
    pub seed: u64,
    /// One per question, in order.
    pub answers: Vec<Response>,
    /// True once the attempt was graded (a relaunch shows the score again).
    pub submitted: bool,
    /// The quiz's graded attempts so far (this one and earlier ones).
    pub tally: Tally,
}

/// How many attempts of one experiment's quiz were graded, and the
/// percentage that counts under the instructor's [`QuizRules`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// Graded attempts so far.
    pub graded: u32,
    /// The percentage that counts (`None` before the first grading).
    pub counted: Option<usize>,
}

impl Tally {
    /// Records an attempt graded at `percent`; returns the percentage that
    /// counts now (see [`crate::route::ScoreRule::fold`]).
    pub fn record(&mut self, percent: usize, rules: &QuizRules) -> usize {
        let counted = rules.score.fold(self.counted, percent);
        self.graded = self.graded.saturating_add(1);
        self.counted = Some(counted);
        counted
    }

    /// What the score line says after a grading (how many attempts are
    /// graded, the score that counts, whether another may be), e.g. “2 of
    /// 2 attempts graded. The best score counts: 17%. No attempts left.”;
    /// or, `refused`, why an attempt is not graded: “No attempts left: 2 of
    /// 2 attempts graded. The best score counts: 17%.”
    #[must_use]
    pub fn line(&self, rules: &QuizRules, refused: bool) -> String {
        let graded = rules.attempts.map_or(String::new(), |n| {
            format!("{} of {n} attempts graded. ", self.graded)
        });
        let counts = match self.counted {
            Some(c) if *rules != QuizRules::default() || self.graded > 1 => {
                format!("The {} score counts: {c}%.", rules.score.slug())
            }
            _ => String::new(),
        };
        let next = match (refused, rules.allows(self.graded)) {
            (true, _) => return format!("No attempts left: {graded}{counts}"),
            (_, true) => "Press New attempt for fresh questions.",
            _ => "No attempts left.",
        };
        format!("{graded}{counts} {next}").trim_start().to_owned()
    }
}

impl Suspended {
    /// The attempt part, as the quiz restores it.
    #[must_use]
    pub fn attempt(&self) -> SavedAttempt {
        SavedAttempt {
            seed: self.seed,
            answers: self.answers.clone(),
        }
    }

    /// ASCII JSON of at most [`SUSPEND_DATA_MAX_CHARS`] characters (so as
    /// many bytes and UTF-16 units). When the full form is longer, typed
    /// answers are cut to [`ANSWER_MAX_UNITS`], then answers are left out
    /// from the end until it fits.
    #[must_use]
    pub fn encode(&self) -> String {
        let fits = |s: &String| s.len() <= SUSPEND_DATA_MAX_CHARS;
        let text = json(self);
        if fits(&text) {
            return text;
        }
        let mut short = self.clone();
        for a in &mut short.answers {
            if let Response::Text(t) = a {
                let mut units = 0;
                *t = t
                    .chars()
                    .take_while(|c| {
                        units += c.len_utf16();
                        units <= ANSWER_MAX_UNITS
                    })
                    .collect();
            }
        }
        // Each answer is at most 6 characters per UTF-16 unit of its text
        // (JSON escapes), so this loop ends well before the answers run out.
        loop {
            let text = json(&short);
            if fits(&text) || short.answers.is_empty() {
                return text;
            }
            short.answers.pop();
        }
    }

    /// Reads [`Suspended::encode`]'s text; `None` for anything else
    /// (an LMS may hand back an empty string or another package's data).
    #[must_use]
    pub fn decode(text: &str) -> Option<Self> {
        let value = Json::parse(text).ok()?;
        let Json::Object(fields) = &value else {
            return None;
        };
        let field = |name: &str| fields.iter().find(|(k, _)| k == name).map(|(_, v)| v);
        let Some(Json::String(id)) = field("id") else {
            return None;
        };
        let submitted = match field("submitted") {
            None => false,
            Some(Json::Bool(b)) => *b,
            Some(_) => return None,
        };
        // Written from the first grading on; a count that is not a whole
        // number means none.
        let whole = |name| match field(name) {
            Some(Json::Number(n)) if *n >= 0.0 && n.fract() == 0.0 => Some(*n as usize),
            _ => None,
        };
        Some(Suspended {
            id: id.clone(),
            seed: seed_from_json(field("seed")?)?,
            answers: answers_from_json(field("answers")?)?,
            submitted,
            tally: match (whole("graded"), whole("counted")) {
                // A percentage: an edited `suspend_data` cannot count more.
                (Some(graded), Some(counted)) => Tally {
                    graded: graded.min(u32::MAX as usize) as u32,
                    counted: Some(counted.min(100)),
                },
                _ => Tally::default(),
            },
        })
    }
}

/// `{"id":"pid","seed":42,"answers":[…],"submitted":true}`, then
/// `"graded":2,"counted":17` once an attempt was graded; ASCII only.
fn json(s: &Suspended) -> String {
    let mut fields = vec![
        ("id".into(), Json::String(s.id.clone())),
        ("seed".into(), seed_json(s.seed)),
        ("answers".into(), answers_json(&s.answers)),
        ("submitted".into(), Json::Bool(s.submitted)),
    ];
    if let Some(c) = s.tally.counted {
        fields.push(("graded".into(), Json::Number(f64::from(s.tally.graded))));
        fields.push(("counted".into(), Json::Number(c as f64)));
    }
    ascii(&Json::Object(fields).to_text())
}

/// JSON text with every non-ASCII character as `\uXXXX` (UTF-16 units, a
/// surrogate pair for those beyond the BMP); they occur only in strings.
fn ascii(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_ascii() {
            out.push(c);
        } else {
            for unit in c.encode_utf16(&mut [0; 2]) {
                let _ = write!(out, "\\u{:04x}", u32::from(*unit));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Lcg64;

    fn sample() -> Suspended {
        Suspended {
            id: "pid".into(),
            seed: 42,
            answers: vec![
                Response::Choice(Some(2)),
                Response::Text("1.5 m".into()),
                Response::Choice(None),
            ],
            submitted: true,
            tally: Tally::default(),
        }
    }

    #[test]
    fn encodes_as_compact_json_and_round_trips() {
        let s = sample();
        let text = s.encode();
        assert_eq!(
            text,
            r#"{"id":"pid","seed":42,"answers":[{"Choice":2},{"Text":"1.5 m"},{"Choice":null}],"submitted":true}"#
        );
        assert_eq!(Suspended::decode(&text), Some(s.clone()));
        assert_eq!(s.attempt().seed, 42);
        assert_eq!(s.attempt().answers, s.answers);
    }

    #[test]
    fn decode_refuses_what_is_not_an_attempt_and_defaults_submitted() {
        assert_eq!(Suspended::decode(""), None);
        assert_eq!(Suspended::decode("garbage"), None);
        assert_eq!(Suspended::decode(r#"{"seed":1}"#), None);
        let old = Suspended::decode(r#"{"id":"fk","seed":7,"answers":[]}"#).unwrap();
        assert!(!old.submitted);
    }

    /// Issue 24 §2: the graded attempts and the score that counts travel in
    /// `suspend_data`, so a relaunch keeps the attempts limit and the rule.
    #[test]
    fn attempts_tally_is_kept_in_suspend_data() {
        let mut s = sample();
        s.tally = Tally {
            graded: 2,
            counted: Some(17),
        };
        let text = s.encode();
        assert!(
            text.ends_with(r#","submitted":true,"graded":2,"counted":17}"#),
            "{text}"
        );
        assert_eq!(Suspended::decode(&text), Some(s));
        // Before the first grading nothing is written, and bad counts are none.
        assert!(!sample().encode().contains("graded"));
        let odd = r#"{"id":"fk","seed":7,"answers":[],"graded":-1,"counted":5}"#;
        assert_eq!(Suspended::decode(odd).unwrap().tally, Tally::default());
        let odd = r#"{"id":"fk","seed":7,"answers":[],"graded":2}"#;
        assert_eq!(Suspended::decode(odd).unwrap().tally, Tally::default());
        // A percentage counts at most 100, whatever an edited text says.
        let odd = r#"{"id":"fk","seed":7,"answers":[],"graded":1,"counted":1e300}"#;
        assert_eq!(Suspended::decode(odd).unwrap().tally.counted, Some(100));
    }

    /// Issue 24 §2: with attempts=2 the third attempt is refused with a
    /// clear message; the score line names the attempt and the score that
    /// counts (best keeps 17 of 8 → 17 → 8).
    #[test]
    fn attempts_limit_refuses_a_third_grading_with_a_clear_message() {
        use crate::route::ScoreRule;
        let rules = QuizRules {
            attempts: Some(2),
            score: ScoreRule::Best,
        };
        let mut t = Tally::default();
        assert!(rules.allows(t.graded));
        assert_eq!(t.record(8, &rules), 8);
        assert_eq!(
            t.line(&rules, false),
            "1 of 2 attempts graded. The best score counts: 8%. Press New attempt for fresh questions."
        );
        assert_eq!(t.record(17, &rules), 17);
        assert_eq!(
            t.line(&rules, false),
            "2 of 2 attempts graded. The best score counts: 17%. No attempts left."
        );
        assert!(!rules.allows(t.graded));
        assert_eq!(
            t.line(&rules, true),
            "No attempts left: 2 of 2 attempts graded. The best score counts: 17%."
        );
        // Unlimited, best (the defaults): nothing added to one grading; from
        // the second on the line says which score counts.
        let free = QuizRules::default();
        let mut t = Tally::default();
        t.record(8, &free);
        assert_eq!(
            t.line(&free, false),
            "Press New attempt for fresh questions."
        );
        t.record(17, &free);
        t.record(8, &free);
        assert_eq!(
            t.line(&free, false),
            "The best score counts: 17%. Press New attempt for fresh questions."
        );
        assert!(free.allows(t.graded));
        let last = QuizRules {
            score: ScoreRule::Last,
            ..free
        };
        let mut t = Tally::default();
        for p in [8, 17, 8] {
            t.record(p, &last);
        }
        assert_eq!(t.counted, Some(8));
    }

    /// Issue 51 §3: 2,100 × "𝑥" in one answer are 2,100 Unicode scalars
    /// but 4,200 UTF-16 units, which the LMS's side counted and refused.
    /// The text is ASCII, so both sides count the same units, it fits, and
    /// the answer comes back (cut to the page's `maxlength`).
    #[test]
    fn suspend_data_counts_the_same_units_on_both_sides() {
        let mut s = sample();
        s.answers[1] = Response::Text("𝑥".repeat(2100));
        let text = s.encode();
        assert!(text.is_ascii(), "{}", &text[..80]);
        assert!(text.encode_utf16().count() <= SUSPEND_DATA_MAX_CHARS);
        let back = Suspended::decode(&text).unwrap();
        assert_eq!(back.answers.len(), 3, "no answer is left out");
        assert_eq!(back.answers[1], Response::Text("𝑥".repeat(20)));
        // Twelve answers at the page's cap, each of the characters that
        // escape longest, fit whole: nothing is cut or left out.
        for worst in ["𝑥", "é", "\"", "\u{1}"] {
            let units = worst.encode_utf16().count();
            let full = Suspended {
                id: "workspace".into(),
                seed: u64::MAX,
                answers: vec![Response::Text(worst.repeat(ANSWER_MAX_UNITS / units)); 12],
                submitted: true,
                tally: Tally {
                    graded: u32::MAX,
                    counted: Some(100),
                },
            };
            let text = full.encode();
            assert!(text.len() <= SUSPEND_DATA_MAX_CHARS, "{worst:?}");
            assert_eq!(Suspended::decode(&text), Some(full), "{worst:?}");
        }
    }

    /// Issue 51 §3: a launch query an LMS dropped or mangled.
    #[test]
    fn launch_query_lost_or_mangled_reads_the_leading_sco_id() {
        let pid = |q| launch(q).map(|l| l.sco);
        assert_eq!(pid("?sco=pid"), Some("pid".into()));
        assert_eq!(pid("sco=pid"), Some("pid".into()));
        assert_eq!(pid("?sco=pid?scorm_launch=1&x=2"), Some("pid".into()));
        assert_eq!(pid("?lms=1&sco=ik&attempts=2"), Some("ik".into()));
        assert_eq!(pid("?sco=pid%3Fx"), Some("pid".into()));
        assert_eq!(pid(""), None, "the query was dropped");
        assert_eq!(pid("?scorm_launch=1"), None);
        assert_eq!(pid("?sco=%3Cx%3E"), None);
        // The package's rules survive the LMS's `?`.
        let l = launch("?sco=pid&attempts=1&key=never?scorm_launch=1&y=2").unwrap();
        assert_eq!(l.instructor.quiz.attempts, Some(1));
        assert_eq!(
            l.instructor.answer_key,
            Some(crate::route::AnswerKey::Never)
        );
        let l = launch("?sco=pid?scorm_launch=1&attempts=2").unwrap();
        assert_eq!(l.instructor.quiz.attempts, Some(2));
    }

    /// Property: whatever the answers (many, long, full of characters JSON
    /// escapes), the text fits SCORM's 4,096 characters, decodes, keeps the
    /// id, seed and submitted flag, and keeps a prefix of the answers; when
    /// the full form fits it is kept exactly.
    #[test]
    fn encoded_text_always_fits_suspend_data() {
        let alphabet: Vec<char> = "0123456789.,- mé\"\\\n\u{1}π<>&𝑥".chars().collect();
        let mut rng = Lcg64::new(2024);
        let mut cut = 0;
        for case in 0..300 {
            let n = rng.int(0, 60) as usize;
            let answers: Vec<Response> = (0..n)
                .map(|_| {
                    if rng.next_f64() < 0.4 {
                        Response::Choice((rng.next_f64() < 0.8).then(|| rng.int(0, 9) as usize))
                    } else {
                        let len = rng.int(0, 220) as usize;
                        Response::Text(
                            (0..len)
                                .map(|_| alphabet[rng.int(0, alphabet.len() as i64 - 1) as usize])
                                .collect(),
                        )
                    }
                })
                .collect();
            let s = Suspended {
                id: "rrtstar".into(),
                seed: rng.next_u64(),
                answers,
                submitted: case % 2 == 0,
                tally: Tally {
                    graded: case,
                    counted: (case > 0).then_some(case as usize % 101),
                },
            };
            let text = s.encode();
            assert!(
                text.is_ascii() && text.len() <= SUSPEND_DATA_MAX_CHARS,
                "case {case}"
            );
            let back = Suspended::decode(&text).expect("decodes");
            assert_eq!(
                (&back.id, back.seed, back.submitted, back.tally),
                (&s.id, s.seed, s.submitted, s.tally)
            );
            assert!(back.answers.len() <= s.answers.len());
            if json(&s).len() <= SUSPEND_DATA_MAX_CHARS {
                assert_eq!(back, s, "case {case}: a text that fits is kept whole");
            } else {
                cut += 1;
                for (b, a) in back.answers.iter().zip(&s.answers) {
                    match (b, a) {
                        (Response::Text(b), Response::Text(a)) => {
                            assert!(a.starts_with(b.as_str()));
                            assert!(b.encode_utf16().count() <= ANSWER_MAX_UNITS);
                        }
                        _ => assert_eq!(b, a),
                    }
                }
            }
        }
        assert!(
            cut > 20,
            "the property must also see texts that are cut ({cut})"
        );
    }
}
