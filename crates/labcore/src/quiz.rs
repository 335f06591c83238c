//! Graded self-assessment: draws parameterised questions from a seed and
//! checks answers.
//!
//! A [`Question::Generated`] names a [`Generator`]: a function of the
//! experiment's module that draws the numbers with [`Lcg64`] and computes the
//! answer with the lab's own solvers, so the quiz can never disagree with the
//! simulation.

use crate::content::{Content, ContentError, Question};
use crate::rng::Lcg64;

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
        .map(|(i, q)| prepare_one(q, i, lookup, seed))
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
            let answer_text = format_number(draw.answer, 3);
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
/// tolerance, read in the question's unit (see [`parse_answer`]); angles in
/// degrees are compared modulo 360°.
#[must_use]
pub fn grade(q: &Prepared, response: &Response) -> Grade {
    let blank = match response {
        Response::Choice(picked) => picked.is_none(),
        Response::Text(text) => text.trim().is_empty(),
    };
    match (&q.kind, response) {
        (PreparedKind::Choice { options, answer }, Response::Choice(picked)) => Grade {
            correct: *picked == Some(*answer),
            expected: options[*answer].clone(),
            unreadable: false,
            blank,
        },
        (
            PreparedKind::Numeric {
                answer,
                tolerance,
                unit,
                angle_degrees,
            },
            Response::Text(text),
        ) => {
            let expected = if unit.is_empty() {
                format_number(*answer, 3)
            } else {
                format!("{} {unit}", format_number(*answer, 3))
            };
            match parse_answer(text, unit) {
                Some(v) => {
                    let mut error = (v - answer).abs();
                    if *angle_degrees {
                        error = error.rem_euclid(360.0);
                        error = error.min(360.0 - error);
                    }
                    Grade {
                        correct: error <= *tolerance,
                        expected,
                        unreadable: false,
                        blank,
                    }
                }
                None => Grade {
                    correct: false,
                    expected,
                    unreadable: !blank,
                    blank,
                },
            }
        }
        (PreparedKind::Choice { options, answer }, Response::Text(_)) => Grade {
            correct: false,
            expected: options[*answer].clone(),
            unreadable: true,
            blank,
        },
        (PreparedKind::Numeric { answer, .. }, Response::Choice(_)) => Grade {
            correct: false,
            expected: format_number(*answer, 3),
            unreadable: true,
            blank,
        },
    }
}

/// Reads an answer given in `unit`: a number (see [`parse_number`]),
/// optionally followed by that unit (`0.6 m`, `45°`, `45 deg` for degrees).
/// Any other unit is refused, so `1.2 rad` is not taken for `1.2°`.
#[must_use]
pub fn parse_answer(text: &str, unit: &str) -> Option<f64> {
    let lower = text.trim().to_ascii_lowercase();
    let unit = unit.trim().to_ascii_lowercase();
    let mut suffixes = vec![unit.clone()];
    if unit == "°" {
        suffixes.extend(["deg".to_owned(), "degrees".to_owned()]);
    }
    for suffix in suffixes.iter().filter(|s| !s.is_empty()) {
        if let Some(number) = lower.strip_suffix(suffix.as_str()) {
            return parse_number(number);
        }
    }
    parse_number(&lower)
}

/// Reads a number the way students type it: surrounding spaces, a Unicode
/// minus (−), a decimal comma, a leading `+` and a trailing `°` are accepted. Returns `None` for anything else or a non-finite value.
#[must_use]
pub fn parse_number(text: &str) -> Option<f64> {
    let cleaned: String = text
        .trim()
        .replace(['\u{2212}', '\u{2013}'], "-")
        .replace(',', ".")
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    let numeric_end = cleaned
        .char_indices()
        .find(|(i, c)| {
            !(c.is_ascii_digit()
                || *c == '.'
                || ((*c == '-' || *c == '+') && (*i == 0 || cleaned[..*i].ends_with(['e', 'E'])))
                || ((*c == 'e' || *c == 'E') && *i > 0))
        })
        .map_or(cleaned.len(), |(i, _)| i);
    let (number, suffix) = cleaned.split_at(numeric_end);
    // Only a degree sign may follow; units are checked by `parse_answer`.
    let suffix_ok = suffix.is_empty() || suffix == "°";
    if !suffix_ok {
        return None;
    }
    number.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// Formats with at most `decimals` places, trailing zeros trimmed, `-0` as `0`.
#[must_use]
pub fn format_number(value: f64, decimals: usize) -> String {
    if !value.is_finite() {
        return "--".into();
    }
    let s = format!("{value:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    };
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_what_students_type() {
        assert_eq!(parse_number(" 1.5 "), Some(1.5));
        assert_eq!(parse_number("−0,25"), Some(-0.25));
        assert_eq!(parse_number("+3"), Some(3.0));
        assert_eq!(parse_number("45°"), Some(45.0));
        assert_eq!(parse_number("1.2 m"), None);
        assert_eq!(parse_answer("1.2 m", "m"), Some(1.2));
        assert_eq!(parse_answer("1.2M", "m"), Some(1.2));
        assert_eq!(parse_answer("0.5 m²", "m²"), Some(0.5));
        assert_eq!(parse_answer("45 deg", "°"), Some(45.0));
        assert_eq!(parse_answer("45°", "°"), Some(45.0));
        assert_eq!(parse_answer("1.2 rad", "°"), None);
        assert_eq!(parse_answer("3 cm", "m"), None);
        assert_eq!(parse_number("1e-3"), Some(0.001));
        assert_eq!(parse_number(""), None);
        assert_eq!(parse_number("abc"), None);
        assert_eq!(parse_number("1.2.3"), None);
        assert_eq!(parse_number("NaN"), None);
        assert_eq!(parse_number("inf"), None);
    }

    #[test]
    fn formats_trimmed() {
        assert_eq!(format_number(1.5, 3), "1.5");
        assert_eq!(format_number(2.0, 3), "2");
        assert_eq!(format_number(-0.0001, 3), "0");
        assert_eq!(format_number(1.23456, 3), "1.235");
        assert_eq!(format_number(f64::NAN, 3), "--");
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
