//! What a SCORM 1.2 LMS keeps for one experiment between launches.
//!
//! The lab's quiz attempt (seed and answers, see [`SavedAttempt`]) plus
//! whether it was submitted, as the text the page stores in
//! `cmi.suspend_data`. SCORM 1.2 caps that element at 4,096 characters
//! (ADL, *SCORM 1.2 Run-Time Environment*, §3.4.4, `CMIString4096`), so
//! [`Suspended::encode`] never returns more: it shortens long typed answers
//! first, then leaves trailing answers out, and the seed and the submitted
//! flag are always kept (a relaunch rebuilds the same questions).

use crate::json::Json;
use crate::quiz::{
    answers_from_json, answers_json, seed_from_json, seed_json, Response, SavedAttempt,
};

/// The most characters `cmi.suspend_data` holds in SCORM 1.2.
pub const SUSPEND_DATA_MAX_CHARS: usize = 4096;

/// A typed answer longer than this is cut when the whole would not fit
/// (numbers with units are far shorter).
const SHORT_TEXT_CHARS: usize = 40;

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

    /// JSON of at most [`SUSPEND_DATA_MAX_CHARS`] characters. When the full
    /// form is longer, typed answers are cut to 40 characters, then answers
    /// are left out from the end until it fits.
    #[must_use]
    pub fn encode(&self) -> String {
        let fits = |s: &String| s.chars().count() <= SUSPEND_DATA_MAX_CHARS;
        let text = json(self);
        if fits(&text) {
            return text;
        }
        let mut short = self.clone();
        for a in &mut short.answers {
            if let Response::Text(t) = a {
                *t = t.chars().take(SHORT_TEXT_CHARS).collect();
            }
        }
        // Each answer is at most ~6 characters per char of its text (JSON
        // escapes), so this loop ends well before the answers run out.
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
        Some(Suspended {
            id: id.clone(),
            seed: seed_from_json(field("seed")?)?,
            answers: answers_from_json(field("answers")?)?,
            submitted,
        })
    }
}

/// `{"id":"pid","seed":42,"answers":[…],"submitted":true}`.
fn json(s: &Suspended) -> String {
    Json::Object(vec![
        ("id".into(), Json::String(s.id.clone())),
        ("seed".into(), seed_json(s.seed)),
        ("answers".into(), answers_json(&s.answers)),
        ("submitted".into(), Json::Bool(s.submitted)),
    ])
    .to_text()
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

    /// Property: whatever the answers (many, long, full of characters JSON
    /// escapes), the text fits SCORM's 4,096 characters, decodes, keeps the
    /// id, seed and submitted flag, and keeps a prefix of the answers; when
    /// the full form fits it is kept exactly.
    #[test]
    fn encoded_text_always_fits_suspend_data() {
        let alphabet: Vec<char> = "0123456789.,- mé\"\\\n\u{1}π<>&".chars().collect();
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
            };
            let text = s.encode();
            assert!(
                text.chars().count() <= SUSPEND_DATA_MAX_CHARS,
                "case {case}"
            );
            let back = Suspended::decode(&text).expect("decodes");
            assert_eq!(
                (&back.id, back.seed, back.submitted),
                (&s.id, s.seed, s.submitted)
            );
            assert!(back.answers.len() <= s.answers.len());
            if json(&s).chars().count() <= SUSPEND_DATA_MAX_CHARS {
                assert_eq!(back, s, "case {case}: a text that fits is kept whole");
            } else {
                cut += 1;
                for (b, a) in back.answers.iter().zip(&s.answers) {
                    match (b, a) {
                        (Response::Text(b), Response::Text(a)) => {
                            assert!(a.starts_with(b.as_str()));
                            assert!(b.chars().count() <= SHORT_TEXT_CHARS);
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
