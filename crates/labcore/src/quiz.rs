//! Graded self-assessment: draws parameterised questions from a seed and
//! checks answers.
//!
//! A [`Question::Generated`] names a [`Generator`]: a function of the
//! experiment's module that draws the numbers with [`Lcg64`] and computes the
//! answer with the lab's own solvers, so the quiz can never disagree with the
//! simulation.

use crate::content::{Content, ContentError, Question};
use crate::rng::Lcg64;
use crate::units::{format_number, read_answer, with_unit};

/// Numbers drawn for one parameterised question and its computed answer.
#[derive(Clone, Debug, PartialEq)]
pub struct Draw {
    /// Placeholder name (without braces) and its formatted value.
    pub vars: Vec<(&'static str, String)>,
    pub answer: f64,
}

impl Draw {
    /// The drawn value of placeholder `name`, as the student reads it.
    #[must_use]
    pub fn var(&self, name: &str) -> Option<f64> {
        self.vars
            .iter()
            .find(|(n, _)| *n == name)
            .and_then(|(_, v)| v.parse().ok())
    }
}

/// Draws one instance of a parameterised question.
pub type Generator = fn(&mut Lcg64) -> Draw;

/// Looks a generator up by name (one per experiment).
pub type GeneratorLookup = fn(&str) -> Option<Generator>;

/// A question ready to show: placeholders filled, answer known.
#[derive(Clone, Debug, PartialEq)]
pub struct Prepared {
    pub prompt: String,
    pub kind: PreparedKind,
    pub explanation: String,
    /// True for a question whose numbers change with each attempt.
    pub parameterised: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub enum PreparedKind {
    /// Options in this attempt's (shuffled) order; `answer` indexes them.
    Choice { options: Vec<String>, answer: usize },
    Numeric {
        answer: f64,
        tolerance: f64,
        unit: String,
        /// Compare modulo 360° (the answer is an angle in degrees).
        angle_degrees: bool,
    },
}

/// What the student gave.
#[derive(Clone, Debug, PartialEq)]
pub enum Response {
    Choice(Option<usize>),
    Text(String),
}

impl Response {
    /// True when nothing was given (no option picked, or only spaces typed).
    #[must_use]
    pub fn is_blank(&self) -> bool {
        match self {
            Response::Choice(picked) => picked.is_none(),
            Response::Text(text) => text.trim().is_empty(),
        }
    }
}

/// The verdict on one answer.
#[derive(Clone, Debug, PartialEq)]
pub struct Grade {
    pub correct: bool,
    /// The expected answer, formatted for display.
    pub expected: String,
    /// Set when the text could not be read as a number in the question's unit.
    pub unreadable: bool,
    /// Set when nothing was given.
    pub blank: bool,
    /// How a numeric answer was read, in the question's unit (`8000 m` for
    /// “8 km” or “8,000 m”), so the student sees what was graded.
    pub read_as: Option<String>,
    /// Why a numeric answer could not be read (see [`ReadError`](crate::units::ReadError)).
    pub problem: Option<String>,
}

/// Percentage of `score` out of `total`, rounded half up (8 / 12 → 67).
/// 0 when `total` is 0.
#[must_use]
pub fn score_percent(score: usize, total: usize) -> usize {
    if total == 0 {
        return 0;
    }
    let score = score.min(total) as u128;
    let total = total as u128;
    ((200 * score + total) / (2 * total)) as usize
}

pub use crate::content::{ANSWER_DECIMALS, MIN_TOLERANCE};

impl Prepared {
    /// Checks that this question can be graded fairly: a choice has at least
    /// two options and its answer is one of them; a numeric answer is finite
    /// and its tolerance finite and no finer than [`MIN_TOLERANCE`] (half the
    /// last decimal the answer is shown with).
    pub fn validate(&self) -> Result<(), String> {
        match &self.kind {
            PreparedKind::Choice { options, answer } => {
                if options.len() < 2 {
                    return Err("a choice needs at least two options".into());
                }
                if *answer >= options.len() {
                    return Err("the correct answer is not one of the options".into());
                }
            }
            PreparedKind::Numeric {
                answer, tolerance, ..
            } => {
                if !answer.is_finite() {
                    return Err("the answer is not a finite number".into());
                }
                if !(tolerance.is_finite() && *tolerance >= MIN_TOLERANCE) {
                    return Err(format!(
                        "tolerance {tolerance} is finer than the {ANSWER_DECIMALS} decimals the answer is shown with (at least {MIN_TOLERANCE} needed)"
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Largest seed a JSON number holds exactly (2⁵³).
const EXACT_SEED: u64 = 1 << 53;

/// A seed as JSON: a number up to 2⁵³ (exact), a larger one (a link may fix
/// any u64) as a string of digits.
pub(crate) fn seed_json(seed: u64) -> crate::json::Json {
    use crate::json::Json;
    if seed <= EXACT_SEED {
        Json::Number(seed as f64)
    } else {
        Json::String(seed.to_string())
    }
}

/// Reads [`seed_json`]'s value.
pub(crate) fn seed_from_json(value: &crate::json::Json) -> Option<u64> {
    use crate::json::Json;
    match value {
        Json::Number(n) if n.fract() == 0.0 && (0.0..=EXACT_SEED as f64).contains(n) => {
            Some(*n as u64)
        }
        Json::String(digits) if digits.bytes().all(|b| b.is_ascii_digit()) => {
            digits.parse().ok().filter(|s| *s > EXACT_SEED)
        }
        _ => None,
    }
}

/// Answers as JSON: `[{"Choice":1},{"Choice":null},{"Text":"2.5 m"}]`.
pub(crate) fn answers_json(answers: &[Response]) -> crate::json::Json {
    use crate::json::Json;
    Json::Array(
        answers
            .iter()
            .map(|a| {
                let (tag, value) = match a {
                    Response::Choice(Some(i)) => ("Choice", Json::Number(*i as f64)),
                    Response::Choice(None) => ("Choice", Json::Null),
                    Response::Text(t) => ("Text", Json::String(t.clone())),
                };
                Json::Object(vec![(tag.into(), value)])
            })
            .collect(),
    )
}

/// Reads [`answers_json`]'s value.
pub(crate) fn answers_from_json(value: &crate::json::Json) -> Option<Vec<Response>> {
    use crate::json::Json;
    let Json::Array(items) = value else {
        return None;
    };
    items
        .iter()
        .map(|item| match item {
            Json::Object(f) => match f.as_slice() {
                [(tag, Json::Null)] if tag == "Choice" => Some(Response::Choice(None)),
                [(tag, Json::Number(i))] if tag == "Choice" && i.fract() == 0.0 && *i >= 0.0 => {
                    Some(Response::Choice(Some(*i as usize)))
                }
                [(tag, Json::String(t))] if tag == "Text" => Some(Response::Text(t.clone())),
                _ => None,
            },
            _ => None,
        })
        .collect()
}

/// One saved attempt: its seed and the answers given so far, so an attempt
/// survives a reload (the page keeps [`SavedAttempt::encode`] in local
/// storage or the URL) and an instructor's `?quiz=<seed>` fixes the numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct SavedAttempt {
    pub seed: u64,
    /// One per question, in order.
    pub answers: Vec<Response>,
}

impl SavedAttempt {
    /// A compact text form (JSON): `{"seed":7,"answers":[{"Choice":1},
    /// {"Choice":null},{"Text":"2.5 m"}]}`.
    #[must_use]
    pub fn encode(&self) -> String {
        use crate::json::Json;
        Json::Object(vec![
            ("seed".into(), seed_json(self.seed)),
            ("answers".into(), answers_json(&self.answers)),
        ])
        .to_text()
    }

    /// Reads [`SavedAttempt::encode`]'s text; `None` for anything else.
    #[must_use]
    pub fn decode(text: &str) -> Option<Self> {
        use crate::json::Json;
        let value = Json::parse(text).ok()?;
        let Json::Object(fields) = &value else {
            return None;
        };
        let [(s, seed), (a, answers)] = fields.as_slice() else {
            return None;
        };
        if s != "seed" || a != "answers" {
            return None;
        }
        Some(SavedAttempt {
            seed: seed_from_json(seed)?,
            answers: answers_from_json(answers)?,
        })
    }

    /// The saved answers fitted to `questions`: one per question, a saved
    /// answer of the wrong kind or an option index out of range becomes blank.
    #[must_use]
    pub fn answers_for(&self, questions: &[Prepared]) -> Vec<Response> {
        questions
            .iter()
            .enumerate()
            .map(|(i, q)| match (&q.kind, self.answers.get(i)) {
                (PreparedKind::Choice { options, .. }, Some(Response::Choice(Some(k))))
                    if *k < options.len() =>
                {
                    Response::Choice(Some(*k))
                }
                (PreparedKind::Numeric { .. }, Some(Response::Text(t))) => {
                    Response::Text(t.chars().take(200).collect())
                }
                (PreparedKind::Choice { .. }, _) => Response::Choice(None),
                (PreparedKind::Numeric { .. }, _) => Response::Text(String::new()),
            })
            .collect()
    }
}

/// Builds one attempt: every question of `content`, the generated ones drawn
/// from `seed` and every choice question's options shuffled from it
/// (question `i` uses its own stream, so editing one question does not change
/// the others).
pub fn prepare(
    content: &Content,
    lookup: GeneratorLookup,
    seed: u64,
) -> Result<Vec<Prepared>, ContentError> {
    content
        .quiz
        .iter()
        .enumerate()
        .map(|(i, q)| {
            let prepared = prepare_one(q, i, lookup, seed)?;
            prepared
                .validate()
                .map_err(|reason| ContentError::BadQuestion {
                    question: i,
                    reason,
                })?;
            Ok(prepared)
        })
        .collect()
}

fn prepare_one(
    q: &Question,
    index: usize,
    lookup: GeneratorLookup,
    seed: u64,
) -> Result<Prepared, ContentError> {
    Ok(match q {
        Question::Choice {
            prompt,
            options,
            answer,
            explanation,
        } => {
            // Fisher–Yates from the question's own stream.
            let mut order: Vec<usize> = (0..options.len()).collect();
            let mut rng = Lcg64::new(question_seed(seed ^ SHUFFLE_SALT, index));
            for i in (1..order.len()).rev() {
                let j = rng.int(0, i as i64) as usize;
                order.swap(i, j);
            }
            Prepared {
                prompt: prompt.clone(),
                kind: PreparedKind::Choice {
                    options: order.iter().map(|&k| options[k].clone()).collect(),
                    answer: order.iter().position(|&k| k == *answer).unwrap_or(0),
                },
                explanation: explanation.clone(),
                parameterised: false,
            }
        }
        Question::Numeric {
            prompt,
            answer,
            tolerance,
            unit,
            angle_degrees,
            explanation,
        } => Prepared {
            prompt: prompt.clone(),
            kind: PreparedKind::Numeric {
                answer: *answer,
                tolerance: *tolerance,
                unit: unit.clone(),
                angle_degrees: *angle_degrees,
            },
            explanation: explanation.clone(),
            parameterised: false,
        },
        Question::Generated {
            generator,
            prompt,
            tolerance,
            unit,
            angle_degrees,
            explanation,
        } => {
            let gen = lookup(generator).ok_or_else(|| ContentError::UnknownGenerator {
                question: index,
                name: generator.clone(),
            })?;
            let mut rng = Lcg64::new(question_seed(seed, index));
            let draw = gen(&mut rng);
            let answer_text = format_number(draw.answer, ANSWER_DECIMALS);
            let fill = |template: &str| {
                let mut s = template.to_owned();
                for (name, value) in &draw.vars {
                    s = s.replace(&format!("{{{name}}}"), value);
                }
                s.replace("{answer}", &answer_text)
            };
            Prepared {
                prompt: fill(prompt),
                kind: PreparedKind::Numeric {
                    answer: draw.answer,
                    tolerance: *tolerance,
                    unit: unit.clone(),
                    angle_degrees: *angle_degrees,
                },
                explanation: fill(explanation),
                parameterised: true,
            }
        }
    })
}

/// Separates the option-shuffle stream from the number-drawing stream.
const SHUFFLE_SALT: u64 = 0x5DEE_CE66_D1CE_5EED;

/// Mixes the attempt seed with the question index (SplitMix64 finaliser).
fn question_seed(seed: u64, index: usize) -> u64 {
    let mut z = seed ^ (index as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Grades one response. Numeric answers must be within the stated absolute
/// tolerance, read in the question's unit (see [`read_answer`]); angles in
/// degrees are compared modulo 360°. Never panics, whatever the [`Prepared`]
/// value (an invalid question is simply never correct).
#[must_use]
pub fn grade(q: &Prepared, response: &Response) -> Grade {
    let blank = response.is_blank();
    if let Err(problem) = q.validate() {
        // An invalid question (one option, an answer outside the options, an
        // infinite or too fine tolerance) is never correct, whatever is given.
        return Grade {
            correct: false,
            expected: expected_text(q),
            unreadable: false,
            blank,
            read_as: None,
            problem: Some(format!("this question cannot be graded: {problem}")),
        };
    }
    let verdict = |correct, expected, unreadable| Grade {
        correct,
        expected,
        unreadable,
        blank,
        read_as: None,
        problem: None,
    };
    match (&q.kind, response) {
        (PreparedKind::Choice { options, answer }, Response::Choice(picked)) => verdict(
            options.get(*answer).is_some() && *picked == Some(*answer),
            options.get(*answer).cloned().unwrap_or_else(|| "--".into()),
            false,
        ),
        (
            PreparedKind::Numeric {
                answer,
                tolerance,
                unit,
                angle_degrees,
            },
            Response::Text(text),
        ) => {
            let expected = with_unit(&format_number(*answer, ANSWER_DECIMALS), unit);
            match read_answer(text, unit) {
                Ok(reading) => {
                    let mut error = (reading.value - answer).abs();
                    if *angle_degrees {
                        error = error.rem_euclid(360.0);
                        error = error.min(360.0 - error);
                    }
                    Grade {
                        read_as: Some(reading.read_as),
                        ..verdict(error <= *tolerance, expected, false)
                    }
                }
                Err(e) => Grade {
                    problem: (!blank).then(|| e.to_string()),
                    ..verdict(false, expected, !blank)
                },
            }
        }
        (PreparedKind::Choice { options, answer }, Response::Text(_)) => verdict(
            false,
            options.get(*answer).cloned().unwrap_or_else(|| "--".into()),
            !blank,
        ),
        (PreparedKind::Numeric { answer, unit, .. }, Response::Choice(_)) => verdict(
            false,
            with_unit(&format_number(*answer, ANSWER_DECIMALS), unit),
            !blank,
        ),
    }
}

/// What a question expects, as shown after grading.
fn expected_text(q: &Prepared) -> String {
    match &q.kind {
        PreparedKind::Choice { options, answer } => {
            options.get(*answer).cloned().unwrap_or_else(|| "--".into())
        }
        PreparedKind::Numeric { answer, unit, .. } => {
            with_unit(&format_number(*answer, ANSWER_DECIMALS), unit)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::{parse_answer, parse_number, read_number, ReadError};

    /// Regression: “51/m” was read as 5 for an answer in 1/m (the suffix
    /// “1/m” was stripped from “51/m”), and “21/m” as 2.
    #[test]
    fn per_metre_answers_keep_every_digit() {
        assert_eq!(parse_answer("51/m", "1/m"), Some(51.0));
        assert_eq!(parse_answer("21/m", "1/m"), Some(21.0));
        assert_eq!(parse_answer("5 1/m", "1/m"), Some(5.0));
        assert_eq!(parse_answer("5 m⁻¹", "1/m"), Some(5.0));
        assert_eq!(parse_answer("5 per metre", "1/m"), Some(5.0));
        assert_eq!(parse_answer("5", "1/m"), Some(5.0));
        let q = numeric(5.0, 0.05, "1/m");
        let g = grade(&q, &Response::Text("51/m".into()));
        assert!(!g.correct);
        assert_eq!(g.read_as.as_deref(), Some("51 m⁻¹"));
        assert!(!grade(&q, &Response::Text("21/m".into())).correct);
    }

    /// Regression: “1,000” was read as 1 and “8,000” as 8. The rule: a comma
    /// only separates thousands, in groups of exactly three digits; any other
    /// comma is refused with a message, never guessed.
    #[test]
    fn commas_separate_thousands_only() {
        assert_eq!(parse_number("1,000"), Some(1000.0));
        assert_eq!(parse_number("8,000"), Some(8000.0));
        assert_eq!(parse_number("-1,234,567.25"), Some(-1_234_567.25));
        assert_eq!(parse_answer("8,000 m", "m"), Some(8000.0));
        for ambiguous in [
            "1,5", "0,25", "12,34", "1,0000", "1,000,00", "1.000,5", ",5", "1,",
        ] {
            assert_eq!(parse_number(ambiguous), None, "{ambiguous}");
            assert!(
                matches!(
                    read_number(ambiguous),
                    Err(ReadError::AmbiguousComma { .. })
                ),
                "{ambiguous}: {:?}",
                read_number(ambiguous)
            );
        }
        let e = read_number("1,5").unwrap_err().to_string();
        assert!(e.contains("thousands") && e.contains("1.5"), "{e}");
        let q = numeric(8000.0, 0.5, "");
        let g = grade(&q, &Response::Text("8,000".into()));
        assert!(g.correct);
        assert_eq!(g.read_as.as_deref(), Some("8000"));
        let g = grade(&q, &Response::Text("8,0".into()));
        assert!(g.unreadable && !g.correct);
        assert!(g.problem.unwrap().contains("thousands"));
    }

    /// Unit words and abbreviations, converted where the unit allows, and the
    /// grade says how the answer was read.
    #[test]
    fn unit_words_convert_and_grading_reports_the_reading() {
        assert_eq!(parse_answer("8 km", "m"), Some(8000.0));
        assert_eq!(parse_answer("150 cm", "m"), Some(1.5));
        assert_eq!(parse_answer("150 mm", "m"), Some(0.15));
        assert_eq!(parse_answer("1.5 metres", "m"), Some(1.5));
        assert_eq!(parse_answer("1.5 Meters", "m"), Some(1.5));
        assert_eq!(parse_answer("45 degrees", "°"), Some(45.0));
        let rad = parse_answer("1 rad", "°").unwrap();
        assert!((rad - 57.295_779_513_082_32).abs() < 1e-9);
        let deg = parse_answer("180 deg", "rad").unwrap();
        assert!((deg - std::f64::consts::PI).abs() < 1e-12);
        assert_eq!(parse_answer("0.08 radians", "rad"), Some(0.08));
        assert_eq!(parse_answer("70.7 percent", "%"), Some(70.7));
        assert_eq!(parse_answer("1.2 m/rad", "m/rad"), Some(1.2));
        assert_eq!(parse_answer("3 s", "m"), None);
        let q = numeric(8000.0, 0.5, "m");
        let g = grade(&q, &Response::Text("8 km".into()));
        assert!(g.correct);
        assert_eq!(g.read_as.as_deref(), Some("8000 m"));
        let g = grade(&q, &Response::Text("8,000".into()));
        assert_eq!(g.read_as.as_deref(), Some("8000 m"));
        let g = grade(&q, &Response::Text("3 s".into()));
        assert!(g.unreadable && g.problem.unwrap().contains("“s”"));
    }

    #[test]
    fn percentages_round_half_up() {
        assert_eq!(score_percent(8, 12), 67);
        assert_eq!(score_percent(1, 8), 13); // 12.5 → 13
        assert_eq!(score_percent(1, 3), 33);
        assert_eq!(score_percent(12, 12), 100);
        assert_eq!(score_percent(0, 12), 0);
        assert_eq!(score_percent(3, 0), 0);
    }

    #[test]
    fn saved_attempts_round_trip_and_fit_the_questions() {
        let saved = SavedAttempt {
            seed: 123,
            answers: vec![
                Response::Choice(Some(1)),
                Response::Text("8,000 m \"quoted\" | ; ".into()),
                Response::Choice(Some(9)),
            ],
        };
        let text = saved.encode();
        assert_eq!(SavedAttempt::decode(&text), Some(saved.clone()));
        assert_eq!(SavedAttempt::decode("garbage"), None);
        // The text serde_json wrote before is still read.
        assert_eq!(
            SavedAttempt::decode(
                r#"{"seed":7,"answers":[{"Choice":1},{"Choice":null},{"Text":"2 m"}]}"#
            ),
            Some(SavedAttempt {
                seed: 7,
                answers: vec![
                    Response::Choice(Some(1)),
                    Response::Choice(None),
                    Response::Text("2 m".into())
                ]
            })
        );
        for seed in [0, 1 << 53, (1 << 53) + 1, u64::MAX] {
            let s = SavedAttempt {
                seed,
                answers: vec![Response::Text("é\n\"".into())],
            };
            assert_eq!(SavedAttempt::decode(&s.encode()), Some(s));
        }
        for bad in [
            r#"{"seed":-1,"answers":[]}"#,
            r#"{"seed":1.5,"answers":[]}"#,
            r#"{"seed":"12","answers":[]}"#,
            r#"{"seed":1,"answers":[{"Choice":-1}]}"#,
            r#"{"seed":1,"answers":[{"Other":1}]}"#,
            r#"{"answers":[],"seed":1}"#,
        ] {
            assert_eq!(SavedAttempt::decode(bad), None, "{bad}");
        }
        let questions = vec![
            choice(vec!["a", "b"], 0),
            numeric(1.0, 0.01, "m"),
            choice(vec!["a", "b"], 0),
            numeric(1.0, 0.01, "m"),
        ];
        assert_eq!(
            saved.answers_for(&questions),
            vec![
                Response::Choice(Some(1)),
                Response::Text("8,000 m \"quoted\" | ; ".into()),
                Response::Choice(None),
                Response::Text(String::new()),
            ]
        );
    }

    /// Regression: a choice with no options indexed out of bounds in `grade`.
    #[test]
    fn validation_rejects_questions_that_cannot_be_graded_fairly() {
        assert!(choice(vec!["a", "b"], 1).validate().is_ok());
        assert!(choice(vec!["a"], 0).validate().is_err());
        assert!(choice(vec![], 0).validate().is_err());
        assert!(choice(vec!["a", "b"], 2).validate().is_err());
        assert!(numeric(1.0, 0.01, "m").validate().is_ok());
        assert!(numeric(1.0, MIN_TOLERANCE, "m").validate().is_ok());
        assert!(numeric(1.0, 0.0001, "m").validate().is_err());
        assert!(numeric(1.0, f64::NAN, "m").validate().is_err());
        assert!(numeric(f64::INFINITY, 0.1, "m").validate().is_err());
        let g = grade(&choice(vec![], 0), &Response::Choice(Some(0)));
        assert!(!g.correct);
        let g = grade(&choice(vec!["a"], 5), &Response::Choice(Some(5)));
        assert!(!g.correct);
    }

    /// Property: `grade` never panics, whatever the question and the response.
    #[test]
    fn grade_never_panics_on_any_prepared_value() {
        let mut rng = Lcg64::new(2718);
        let units = [
            "", "m", "°", "rad", "%", "m²", "1/m", "m/rad", "weird", "1", "/", "é",
        ];
        let pieces = [
            "1", "5", ",", ".", "e", "-", "+", "−", "°", "m", "/", "²", "^", " ", "é", "∞", "NaN",
            "inf", "1,000", "km", "rad", "9e999", "\u{0}", "%",
        ];
        let numbers = [
            0.0,
            -1.0,
            1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            5e-324,
        ];
        for _ in 0..50_000 {
            let kind = if rng.next_f64() < 0.5 {
                let n = rng.int(0, 4) as usize;
                PreparedKind::Choice {
                    options: (0..n).map(|k| k.to_string()).collect(),
                    answer: match rng.int(0, 2) {
                        0 => rng.int(0, 6) as usize,
                        1 => usize::MAX,
                        _ => 0,
                    },
                }
            } else {
                PreparedKind::Numeric {
                    answer: numbers[rng.int(0, 6) as usize] * rng.range(-2.0, 2.0),
                    tolerance: numbers[rng.int(0, 6) as usize],
                    unit: units[rng.int(0, units.len() as i64 - 1) as usize].into(),
                    angle_degrees: rng.next_f64() < 0.5,
                }
            };
            let q = Prepared {
                prompt: String::new(),
                kind,
                explanation: String::new(),
                parameterised: false,
            };
            let response = if rng.next_f64() < 0.3 {
                Response::Choice(match rng.int(0, 2) {
                    0 => None,
                    1 => Some(usize::MAX),
                    _ => Some(rng.int(0, 5) as usize),
                })
            } else {
                let n = rng.int(0, 6);
                Response::Text(
                    (0..n)
                        .map(|_| pieces[rng.int(0, pieces.len() as i64 - 1) as usize])
                        .collect(),
                )
            };
            let g = grade(&q, &response);
            if q.validate().is_err() {
                assert!(!g.correct, "an invalid question was graded correct: {q:?}");
            }
            assert_eq!(g.blank, response.is_blank());
        }
    }

    fn numeric(answer: f64, tolerance: f64, unit: &str) -> Prepared {
        Prepared {
            prompt: String::new(),
            kind: PreparedKind::Numeric {
                answer,
                tolerance,
                unit: unit.into(),
                angle_degrees: false,
            },
            explanation: String::new(),
            parameterised: false,
        }
    }

    #[test]
    fn invalid_questions_are_never_graded_correct() {
        // One option, with the one answer picked.
        let g = grade(&choice(vec!["only"], 0), &Response::Choice(Some(0)));
        assert!(!g.correct);
        assert!(g.problem.unwrap().contains("at least two options"));
        // An infinite tolerance accepts anything, a 1e-9 one nothing shown:
        // both are refused, the right number included.
        for tolerance in [f64::INFINITY, 1e-9, f64::NAN] {
            let g = grade(&numeric(2.0, tolerance, "m"), &Response::Text("2 m".into()));
            assert!(!g.correct, "tolerance {tolerance}");
            assert_eq!(g.expected, "2 m");
        }
        // A valid question with the same answer is still graded correct.
        assert!(
            grade(
                &numeric(2.0, MIN_TOLERANCE, "m"),
                &Response::Text("2 m".into())
            )
            .correct
        );
        assert!(grade(&choice(vec!["a", "b"], 1), &Response::Choice(Some(1))).correct);
    }

    fn choice(options: Vec<&str>, answer: usize) -> Prepared {
        Prepared {
            prompt: String::new(),
            kind: PreparedKind::Choice {
                options: options.into_iter().map(String::from).collect(),
                answer,
            },
            explanation: String::new(),
            parameterised: false,
        }
    }

    #[test]
    fn numeric_grading_respects_tolerance() {
        let q = Prepared {
            prompt: String::new(),
            kind: PreparedKind::Numeric {
                answer: 1.0,
                tolerance: 0.01,
                unit: "m".into(),
                angle_degrees: false,
            },
            explanation: String::new(),
            parameterised: false,
        };
        assert!(grade(&q, &Response::Text("1.009".into())).correct);
        assert!(!grade(&q, &Response::Text("1.02".into())).correct);
        let g = grade(&q, &Response::Text("one".into()));
        assert!(!g.correct && g.unreadable);
        assert_eq!(g.expected, "1 m");
        let blank = grade(&q, &Response::Text("  ".into()));
        assert!(blank.blank && !blank.unreadable && !blank.correct);
        assert!(!grade(&q, &Response::Text("1 rad".into())).correct);
        assert_eq!(
            grade(&q, &Response::Text("1.009".into()))
                .read_as
                .as_deref(),
            Some("1.009 m")
        );
    }

    #[test]
    fn angles_compare_modulo_360() {
        let q = Prepared {
            prompt: String::new(),
            kind: PreparedKind::Numeric {
                answer: 179.8,
                tolerance: 0.5,
                unit: "°".into(),
                angle_degrees: true,
            },
            explanation: String::new(),
            parameterised: true,
        };
        assert!(grade(&q, &Response::Text("-180".into())).correct);
        assert!(grade(&q, &Response::Text("539.8".into())).correct);
        assert!(!grade(&q, &Response::Text("-179".into())).correct);
    }

    #[test]
    fn choice_grading() {
        let q = Prepared {
            prompt: String::new(),
            kind: PreparedKind::Choice {
                options: vec!["a".into(), "b".into()],
                answer: 1,
            },
            explanation: String::new(),
            parameterised: false,
        };
        assert!(grade(&q, &Response::Choice(Some(1))).correct);
        assert!(!grade(&q, &Response::Choice(Some(0))).correct);
        assert!(!grade(&q, &Response::Choice(None)).correct);
    }

    #[test]
    fn question_seeds_differ_per_index_and_seed() {
        assert_ne!(question_seed(1, 0), question_seed(1, 1));
        assert_ne!(question_seed(1, 0), question_seed(2, 0));
        assert_eq!(question_seed(5, 3), question_seed(5, 3));
    }
}
