//! Experiment content as data: one JSON file per experiment under `assets/`.
//!
//! Text fields may hold a small, trusted subset of inline HTML (`<em>`,
//! `<strong>`, `<code>`, `<sub>`, `<sup>`) and formulas in LaTeX (`$…$`,
//! `$$…$$`), which `build.rs` (and [`Content::parse`]) write as MathML
//! (`<math>…</math>`) with the `labtex` crate; the files are ours and are
//! compiled into the bundle, never user input.

#[cfg(feature = "reading")]
use crate::json::{Fields, Json};
use std::fmt;

/// Decimals with which numeric answers are shown (`{answer}`, “Expected …”).
pub const ANSWER_DECIMALS: usize = 3;

/// Smallest tolerance a numeric question may have: half a unit of the last
/// decimal the answer is shown with, so the shown answer is always accepted.
pub const MIN_TOLERANCE: f64 = 0.0005;

/// Everything the reading tabs and the quiz show for one experiment.
#[derive(Clone, Debug, PartialEq)]
pub struct Content {
    /// Must equal the experiment's [`crate::Experiment::id`].
    pub id: String,
    /// Position in the lab (1–11).
    pub number: u32,
    pub title: String,
    /// One line for the home-page card.
    pub summary: String,
    /// Paragraphs.
    pub aim: Vec<String>,
    pub theory: Vec<Block>,
    /// Ordered steps.
    pub procedure: Vec<String>,
    pub quiz: Vec<Question>,
    pub references: Vec<Reference>,
    /// The keys of the equations "The math" panel shows, in the order shown
    /// ([`MATH_EQUATIONS`] of them, each one of the experiment's
    /// [`crate::live_math::Equation`]s; empty for an experiment without
    /// equations).
    pub math: Vec<String>,
}

/// A block of the Theory tab.
#[derive(Clone, Debug, PartialEq)]
pub enum Block {
    /// A sub-heading.
    Heading(String),
    /// A paragraph (inline formulas allowed; MathML once built).
    Paragraph(String),
    /// A display formula: `$$…$$` in the file, a complete
    /// `<math display="block">…</math>` element once built.
    Formula(String),
    /// A highlighted aside.
    Note(String),
}

impl Block {
    /// One theory block: an object with exactly one of the keys `heading`,
    /// `paragraph`, `formula`, `note`, holding a string.
    #[cfg(feature = "reading")]
    fn from_json(value: &Json, index: usize) -> Result<Self, String> {
        let place = format!("theory block {}", index + 1);
        let Json::Object(fields) = value else {
            return Err(format!(
                "{place}: expected an object, found {}",
                value.kind()
            ));
        };
        let [(kind, Json::String(text))] = fields.as_slice() else {
            return Err(format!("{place}: expected one key holding a string"));
        };
        let text = text.clone();
        match kind.as_str() {
            "heading" => Ok(Block::Heading(text)),
            "paragraph" => Ok(Block::Paragraph(text)),
            "formula" => Ok(Block::Formula(text)),
            "note" => Ok(Block::Note(text)),
            other => Err(format!(
                "{place}: unknown variant `{other}`, expected heading, paragraph, formula or note"
            )),
        }
    }
}

/// A bibliographic reference.
#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    pub authors: String,
    pub title: String,
    /// Publisher, journal or site.
    pub venue: String,
    pub year: Option<u32>,
    /// Chapter, pages or section.
    pub detail: Option<String>,
    /// The Digital Object Identifier, without a resolver (`10.1115/1.3143764`).
    pub doi: Option<String>,
    /// A stable address of the work (publisher's or author's page), `https://…`.
    pub url: Option<String>,
}

impl Reference {
    #[cfg(feature = "reading")]
    fn from_json(value: &Json, index: usize) -> Result<Self, String> {
        let mut f = Fields::of(value, format!("reference {}", index + 1))?;
        let reference = Reference {
            authors: f.string("authors")?,
            title: f.string("title")?,
            venue: f.string("venue")?,
            year: f.opt_count("year")?,
            detail: f.opt_string("detail")?,
            doi: f.opt_string("doi")?,
            url: f.opt_string("url")?,
        };
        f.done()?;
        Ok(reference)
    }

    /// Where a reader can find the work: `https://doi.org/<doi>` when a DOI is
    /// given, else the stable URL.
    #[must_use]
    pub fn link(&self) -> Option<String> {
        match (&self.doi, &self.url) {
            (Some(doi), _) => Some(format!("https://doi.org/{doi}")),
            (None, Some(url)) => Some(url.clone()),
            (None, None) => None,
        }
    }
}

/// One self-assessment question.
#[derive(Clone, Debug, PartialEq)]
pub enum Question {
    /// Multiple choice with exactly one correct option.
    Choice {
        prompt: String,
        options: Vec<String>,
        /// Index of the correct option.
        answer: usize,
        explanation: String,
    },
    /// A fixed numeric answer checked within `tolerance` (absolute).
    Numeric {
        prompt: String,
        answer: f64,
        tolerance: f64,
        unit: String,
        /// The answer is an angle in degrees, compared modulo 360°.
        angle_degrees: bool,
        explanation: String,
    },
    /// A parameterised numeric question: `generator` names a function of the
    /// experiment's quiz module that draws the numbers from a seed and computes
    /// the answer. `{name}` placeholders in `prompt` and `explanation` are
    /// filled from the draw; `{answer}` is the computed answer.
    Generated {
        generator: String,
        prompt: String,
        tolerance: f64,
        unit: String,
        /// The answer is an angle in degrees, compared modulo 360°.
        angle_degrees: bool,
        explanation: String,
    },
}

impl Question {
    /// One quiz question, tagged by its `kind`: `choice`, `numeric` or
    /// `generated`.
    #[cfg(feature = "reading")]
    fn from_json(value: &Json, index: usize) -> Result<Self, String> {
        let mut f = Fields::of(value, format!("question {}", index + 1))?;
        let kind = f.string("kind")?;
        let question = match kind.as_str() {
            "choice" => Question::Choice {
                prompt: f.string("prompt")?,
                options: f.strings("options")?,
                answer: f.count("answer")? as usize,
                explanation: f.string("explanation")?,
            },
            "numeric" => Question::Numeric {
                prompt: f.string("prompt")?,
                answer: f.number("answer")?,
                tolerance: f.number("tolerance")?,
                unit: f.opt_string("unit")?.unwrap_or_default(),
                angle_degrees: f.flag("angle_degrees")?,
                explanation: f.string("explanation")?,
            },
            "generated" => Question::Generated {
                generator: f.string("generator")?,
                prompt: f.string("prompt")?,
                tolerance: f.number("tolerance")?,
                unit: f.opt_string("unit")?.unwrap_or_default(),
                angle_degrees: f.flag("angle_degrees")?,
                explanation: f.string("explanation")?,
            },
            other => {
                return Err(format!(
                    "question {}: unknown kind `{other}`, expected choice, numeric or generated",
                    index + 1
                ))
            }
        };
        f.done()?;
        Ok(question)
    }

    #[must_use]
    pub fn prompt(&self) -> &str {
        match self {
            Question::Choice { prompt, .. }
            | Question::Numeric { prompt, .. }
            | Question::Generated { prompt, .. } => prompt,
        }
    }
}

/// Why a content file was refused.
#[derive(Clone, Debug, PartialEq)]
pub enum ContentError {
    Parse(String),
    /// A formula that does not convert from LaTeX: its field's JSON path,
    /// the position in the formula and what is wrong there. Only content
    /// read at run time (`reading`) is converted here; the compiled-in files
    /// were converted by `build.rs`.
    #[cfg(feature = "reading")]
    Latex(String),
    /// A reference whose DOI or URL is malformed.
    BadReference {
        reference: usize,
        reason: String,
    },
    Missing {
        section: &'static str,
    },
    TooFewQuestions {
        found: usize,
    },
    TooFewGenerated {
        found: usize,
    },
    BadChoice {
        question: usize,
        reason: String,
    },
    BadTolerance {
        question: usize,
    },
    /// A tolerance finer than the decimals the answer is shown with
    /// ([`MIN_TOLERANCE`]): the shown answer could be marked wrong.
    ToleranceTooFine {
        question: usize,
        tolerance: f64,
    },
    /// A prepared question that cannot be graded fairly (see `quiz::Prepared::validate`).
    BadQuestion {
        question: usize,
        reason: String,
    },
    TooFewReferences {
        found: usize,
    },
    BadFormula {
        block: usize,
    },
    UnknownGenerator {
        question: usize,
        name: String,
    },
    WrongId {
        expected: String,
        found: String,
    },
    /// The `math` list names fewer or more equations than
    /// [`MATH_EQUATIONS`] allows, or one twice, or any for an experiment
    /// without equations.
    #[cfg(feature = "reading")]
    MathCount {
        found: usize,
        /// The experiment's equation keys.
        known: String,
    },
    /// The `math` list names an equation the experiment does not have.
    #[cfg(feature = "reading")]
    UnknownEquation {
        key: String,
        /// The experiment's equation keys.
        known: String,
    },
    /// A `\\live{key}{…}` symbol whose key is not among the experiment's
    /// quantities.
    #[cfg(feature = "reading")]
    UnknownLiveKey {
        /// Where: "theory block 3", "question 2 prompt", …
        field: String,
        key: String,
        /// The experiment's quantity keys.
        known: String,
    },
    /// A text field whose inline markup does not nest (`<em>unclosed`), so
    /// the page built from it would come out unbalanced.
    UnbalancedMarkup {
        /// Where: "aim paragraph 2", "question 5 option 3", …
        field: String,
    },
}

impl fmt::Display for ContentError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ContentError::Parse(e) => write!(f, "content is not valid JSON: {e}"),
            #[cfg(feature = "reading")]
            ContentError::Latex(e) => f.write_str(e),
            ContentError::Missing { section } => write!(f, "section “{section}” is empty"),
            ContentError::TooFewQuestions { found } => {
                write!(
                    f,
                    "quiz has {found} questions; at least {MIN_QUESTIONS} are needed"
                )
            }
            ContentError::TooFewGenerated { found } => write!(
                f,
                "quiz has {found} parameterised questions; at least {MIN_GENERATED} are needed"
            ),
            ContentError::BadChoice { question, reason } => {
                write!(f, "question {}: {reason}", question + 1)
            }
            ContentError::BadTolerance { question } => {
                write!(f, "question {}: tolerance must be positive", question + 1)
            }
            ContentError::ToleranceTooFine { question, tolerance } => write!(
                f,
                "question {}: tolerance {tolerance} is finer than the {} decimals the answer is shown with (at least {} needed)",
                question + 1,
                ANSWER_DECIMALS,
                MIN_TOLERANCE
            ),
            ContentError::BadReference { reference, reason } => {
                write!(f, "reference {}: {reason}", reference + 1)
            }
            ContentError::BadQuestion { question, reason } => {
                write!(f, "question {}: {reason}", question + 1)
            }
            ContentError::TooFewReferences { found } => {
                write!(
                    f,
                    "{found} references; at least {MIN_REFERENCES} are needed"
                )
            }
            ContentError::BadFormula { block } => write!(
                f,
                "theory block {}: a formula must be one display formula, $$…$$, and nothing else",
                block + 1
            ),
            ContentError::UnknownGenerator { question, name } => {
                write!(f, "question {}: no generator named “{name}”", question + 1)
            }
            ContentError::UnbalancedMarkup { field } => write!(
                f,
                "{field}: its inline markup does not nest (an unclosed or stray tag, or a bare “<” that should be written &lt;)"
            ),
            #[cfg(feature = "reading")]
            ContentError::MathCount { found, known } if known.is_empty() => write!(
                f,
                "math: names {found} equations, but the experiment has none (write \"math\": [])"
            ),
            #[cfg(feature = "reading")]
            ContentError::MathCount { found, known } => write!(
                f,
                "math: names {found} equations; the panel shows {} to {} different ones of the experiment's equations ({known})",
                MATH_EQUATIONS.start(),
                MATH_EQUATIONS.end()
            ),
            #[cfg(feature = "reading")]
            ContentError::UnknownEquation { key, known } => write!(
                f,
                "math: no equation with key “{key}” (the experiment's equations: {known})"
            ),
            #[cfg(feature = "reading")]
            ContentError::UnknownLiveKey { field, key, known } => write!(
                f,
                "{field}: \\live{{{key}}}: no quantity with key “{key}” (the experiment's quantities: {known})"
            ),
            ContentError::WrongId { expected, found } => {
                write!(
                    f,
                    "content id “{found}” does not match experiment “{expected}”"
                )
            }
        }
    }
}

impl std::error::Error for ContentError {}

pub const MIN_QUESTIONS: usize = 8;
pub const MIN_GENERATED: usize = 2;
pub const MIN_REFERENCES: usize = 3;
/// How many equations "The math" panel shows (the content's `math` list).
pub const MATH_EQUATIONS: std::ops::RangeInclusive<usize> = 1..=4;

/// Every number of a machine part (`play`, `given`): its JSON numbers and
/// the numbers written in its strings.
#[cfg(feature = "reading")]
fn machine_values(v: &Json, out: &mut Vec<f64>) {
    match v {
        Json::Number(n) => out.push(*n),
        Json::String(s) => out.extend(
            crate::step_numbers::numbers_in(s)
                .into_iter()
                .map(|(_, n)| n),
        ),
        Json::Array(items) => items.iter().for_each(|i| machine_values(i, out)),
        Json::Object(fields) => fields.iter().for_each(|(_, i)| machine_values(i, out)),
        Json::Null | Json::Bool(_) => {}
    }
}

/// The prose (`prose_key`) of an object with a machine part (`play`,
/// optionally `given`), as `build.rs` reads it: a number of the prose that
/// is none of its values is an error ([`crate::step_numbers`]).
#[cfg(feature = "reading")]
fn checked_prose(item: &Json, place: &str, prose_key: &'static str) -> Result<String, String> {
    let mut f = Fields::of(item, place)?;
    let text = f.string(prose_key)?;
    let mut found = Vec::new();
    machine_values(&Json::Array(f.array("play")?.to_vec()), &mut found);
    if let Some(given) = f.optional("given") {
        machine_values(given, &mut found);
    }
    f.done()?;
    if let Some(n) = crate::step_numbers::stray_number(&text, &found) {
        let (prose, whose) = if prose_key == "quote" {
            ("quoted sentence", "claim")
        } else {
            ("prose", "step")
        };
        return Err(format!(
            "{place}: the {prose} writes {n}, which is none of the {whose}'s values (its play, or `given`)"
        ));
    }
    Ok(text)
}

/// The prose of each Procedure step (`{"text", "play", "given"}`), as
/// `build.rs` reads it: a number of the prose that is none of the step's
/// values is an error ([`crate::step_numbers`]).
#[cfg(feature = "reading")]
fn procedure_texts(steps: &[Json]) -> Result<Vec<String>, String> {
    steps
        .iter()
        .enumerate()
        .map(|(i, step)| checked_prose(step, &format!("procedure step {}", i + 1), "text"))
        .collect()
}

/// The claims beyond the Procedure (`{"quote", "play", "given"}`), checked
/// as `build.rs` checks them and then dropped: they are the runner's only.
#[cfg(feature = "reading")]
fn check_claims(claims: Option<&Json>) -> Result<(), String> {
    let Some(claims) = claims else {
        return Ok(());
    };
    let Json::Array(items) = claims else {
        return Err("content: field `claims` should be an array".into());
    };
    for (i, claim) in items.iter().enumerate() {
        checked_prose(claim, &format!("claim {}", i + 1), "quote")?;
    }
    Ok(())
}

impl Content {
    /// Reads the fields of a content file's JSON (no field missing, none
    /// unknown, each of its type); [`Content::validate`] then checks the rest.
    /// Only with the `reading` feature: the compiled-in files were read at
    /// build time (`build.rs`); this reads other texts (edited files, tests).
    #[cfg(feature = "reading")]
    pub fn from_json(value: &Json) -> Result<Self, String> {
        let mut f = Fields::of(value, "content")?;
        let content = Content {
            id: f.string("id")?,
            number: f.count("number")?,
            title: f.string("title")?,
            summary: f.string("summary")?,
            aim: f.strings("aim")?,
            theory: f
                .array("theory")?
                .iter()
                .enumerate()
                .map(|(i, b)| Block::from_json(b, i))
                .collect::<Result<_, _>>()?,
            procedure: procedure_texts(f.array("procedure")?)?,
            quiz: f
                .array("quiz")?
                .iter()
                .enumerate()
                .map(|(i, q)| Question::from_json(q, i))
                .collect::<Result<_, _>>()?,
            references: f
                .array("references")?
                .iter()
                .enumerate()
                .map(|(i, r)| Reference::from_json(r, i))
                .collect::<Result<_, _>>()?,
            math: f.strings("math")?,
        };
        // Test-only, like a step's `play`: checked, never kept.
        check_claims(f.optional("claims"))?;
        f.done()?;
        Ok(content)
    }

    /// Parses a content file, writes its formulas (LaTeX between dollars) as
    /// MathML as `build.rs` does for the compiled-in files, and checks it is
    /// complete (see [`Content::validate`]).
    #[cfg(feature = "reading")]
    pub fn parse(json: &str) -> Result<Self, ContentError> {
        let mut value = Json::parse(json).map_err(ContentError::Parse)?;
        render_formulas(&mut value, String::new()).map_err(ContentError::Latex)?;
        let content = Content::from_json(&value).map_err(ContentError::Parse)?;
        content.validate()?;
        Ok(content)
    }

    /// Rejects a file that lacks a section, has fewer than 8 questions or fewer
    /// than 2 parameterised ones, has a choice question with fewer than two
    /// options or without exactly one correct answer among them, a
    /// non-positive tolerance or one finer than the answer's shown precision,
    /// a malformed display formula, or fewer than 3 references.
    pub fn validate(&self) -> Result<(), ContentError> {
        let empty = |s: &str| s.trim().is_empty();
        if empty(&self.id) {
            return Err(ContentError::Missing { section: "id" });
        }
        if empty(&self.title) {
            return Err(ContentError::Missing { section: "title" });
        }
        if empty(&self.summary) {
            return Err(ContentError::Missing { section: "summary" });
        }
        if self.aim.is_empty() || self.aim.iter().any(|p| empty(p)) {
            return Err(ContentError::Missing { section: "aim" });
        }
        if self.theory.is_empty() {
            return Err(ContentError::Missing { section: "theory" });
        }
        if !self.theory.iter().any(|b| matches!(b, Block::Formula(_))) {
            return Err(ContentError::Missing {
                section: "theory formula",
            });
        }
        for (i, block) in self.theory.iter().enumerate() {
            if let Block::Formula(f) = block {
                if !is_block_math(f) {
                    return Err(ContentError::BadFormula { block: i });
                }
            }
        }
        if self.procedure.is_empty() || self.procedure.iter().any(|p| empty(p)) {
            return Err(ContentError::Missing {
                section: "procedure",
            });
        }
        if self.quiz.len() < MIN_QUESTIONS {
            return Err(ContentError::TooFewQuestions {
                found: self.quiz.len(),
            });
        }
        let generated = self
            .quiz
            .iter()
            .filter(|q| matches!(q, Question::Generated { .. }))
            .count();
        if generated < MIN_GENERATED {
            return Err(ContentError::TooFewGenerated { found: generated });
        }
        for (i, q) in self.quiz.iter().enumerate() {
            if empty(q.prompt()) {
                return Err(ContentError::Missing {
                    section: "question",
                });
            }
            match q {
                Question::Choice {
                    options, answer, ..
                } => {
                    if options.len() < 2 {
                        return Err(ContentError::BadChoice {
                            question: i,
                            reason: "a choice needs at least two options".into(),
                        });
                    }
                    if *answer >= options.len() {
                        return Err(ContentError::BadChoice {
                            question: i,
                            reason: "the correct answer is not one of the options".into(),
                        });
                    }
                    let correct = &options[*answer];
                    if options.iter().filter(|o| *o == correct).count() != 1 {
                        return Err(ContentError::BadChoice {
                            question: i,
                            reason: "the correct option appears more than once".into(),
                        });
                    }
                }
                Question::Numeric {
                    tolerance, answer, ..
                } => {
                    if !is_positive(*tolerance) || !answer.is_finite() {
                        return Err(ContentError::BadTolerance { question: i });
                    }
                    check_precision(i, *tolerance)?;
                }
                Question::Generated { tolerance, .. } => {
                    if !is_positive(*tolerance) {
                        return Err(ContentError::BadTolerance { question: i });
                    }
                    check_precision(i, *tolerance)?;
                }
            }
        }
        for (i, r) in self.references.iter().enumerate() {
            if r.doi.as_deref().is_some_and(|d| {
                !d.starts_with("10.") || !d.contains('/') || d.contains(char::is_whitespace)
            }) {
                return Err(ContentError::BadReference {
                    reference: i,
                    reason: "a DOI looks like 10.1115/1.3143764 (no resolver, no spaces)".into(),
                });
            }
            if r.url.as_deref().is_some_and(|u| {
                !(u.starts_with("https://") || u.starts_with("http://"))
                    || u.contains(|c: char| c.is_whitespace() || c == '"' || c == '<')
            }) {
                return Err(ContentError::BadReference {
                    reference: i,
                    reason: "a URL must be an absolute http(s) address".into(),
                });
            }
        }
        if self.references.len() < MIN_REFERENCES {
            return Err(ContentError::TooFewReferences {
                found: self.references.len(),
            });
        }
        for (field, text) in self.text_fields() {
            if !tags_balanced(text) {
                return Err(ContentError::UnbalancedMarkup { field });
            }
        }
        Ok(())
    }

    /// Checks the names this content gives its experiment's live math: every
    /// key of `math` is one of `equations` (the experiment's equation keys),
    /// and every `\\live{key}{…}` symbol of every text field names one of
    /// `quantities` (its quantity keys).
    #[cfg(feature = "reading")]
    pub fn check_live_names(
        &self,
        equations: &[&str],
        quantities: &[&str],
    ) -> Result<(), ContentError> {
        // An experiment without equations has no panel, and its list is
        // empty; one with equations names some of them, each once.
        let distinct = |i: usize, key: &String| !self.math[..i].contains(key);
        let wanted = if equations.is_empty() {
            0..=0
        } else {
            MATH_EQUATIONS
        };
        if !wanted.contains(&self.math.len())
            || !self.math.iter().enumerate().all(|(i, k)| distinct(i, k))
        {
            return Err(ContentError::MathCount {
                found: self.math.len(),
                known: equations.join(", "),
            });
        }
        if let Some(key) = self.math.iter().find(|k| !equations.contains(&k.as_str())) {
            return Err(ContentError::UnknownEquation {
                key: key.clone(),
                known: equations.join(", "),
            });
        }
        for (field, text) in self.text_fields() {
            if let Some(key) = labtex::live_keys(text)
                .into_iter()
                .find(|k| !quantities.contains(k))
            {
                return Err(ContentError::UnknownLiveKey {
                    field,
                    key: key.to_owned(),
                    known: quantities.join(", "),
                });
            }
        }
        Ok(())
    }

    /// Every text field that goes into the page, named as an author finds it.
    fn text_fields(&self) -> Vec<(String, &str)> {
        let mut out: Vec<(String, &str)> = vec![
            ("title".into(), self.title.as_str()),
            ("summary".into(), self.summary.as_str()),
        ];
        for (i, p) in self.aim.iter().enumerate() {
            out.push((format!("aim paragraph {}", i + 1), p));
        }
        for (i, b) in self.theory.iter().enumerate() {
            let (Block::Heading(t) | Block::Paragraph(t) | Block::Formula(t) | Block::Note(t)) = b;
            out.push((format!("theory block {}", i + 1), t));
        }
        for (i, p) in self.procedure.iter().enumerate() {
            out.push((format!("procedure step {}", i + 1), p));
        }
        for (i, q) in self.quiz.iter().enumerate() {
            let n = i + 1;
            out.push((format!("question {n} prompt"), q.prompt()));
            match q {
                Question::Choice {
                    options,
                    explanation,
                    ..
                } => {
                    for (k, o) in options.iter().enumerate() {
                        out.push((format!("question {n} option {}", k + 1), o));
                    }
                    out.push((format!("question {n} explanation"), explanation));
                }
                Question::Numeric { explanation, .. } | Question::Generated { explanation, .. } => {
                    out.push((format!("question {n} explanation"), explanation));
                }
            }
        }
        for (i, r) in self.references.iter().enumerate() {
            let n = i + 1;
            out.push((format!("reference {n} authors"), &r.authors));
            out.push((format!("reference {n} title"), &r.title));
            out.push((format!("reference {n} venue"), &r.venue));
            if let Some(d) = &r.detail {
                out.push((format!("reference {n} detail"), d));
            }
        }
        out
    }
}

/// How option lengths could give answers away (issue 15: test-wise students
/// pick the longest option), counted over a quiz's choice questions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LengthTells {
    /// Choice questions counted.
    pub choices: usize,
    /// Questions whose correct option is strictly the longest (in characters).
    pub longest: usize,
    /// Questions whose correct option is strictly the shortest.
    pub shortest: usize,
    /// `by_rank[r]`: questions where exactly `r` other options are strictly
    /// longer than the correct one (0: longest or tied for it; 3: the
    /// shortest of four). Ranks past 3 count in `by_rank[3]`.
    pub by_rank: [usize; 4],
}

impl LengthTells {
    /// Whether at most `1/n` of the questions have either tell.
    #[must_use]
    pub fn at_most_one_in(self, n: usize) -> bool {
        n * self.longest <= self.choices && n * self.shortest <= self.choices
    }
}

impl Content {
    /// Counts the choice questions whose correct option stands out by length.
    #[must_use]
    pub fn length_tells(&self) -> LengthTells {
        let mut tells = LengthTells::default();
        for q in &self.quiz {
            let Question::Choice {
                options, answer, ..
            } = q
            else {
                continue;
            };
            let Some(right) = options.get(*answer).map(|o| o.chars().count()) else {
                continue;
            };
            let others = || {
                options
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| k != answer)
                    .map(|(_, o)| o.chars().count())
            };
            tells.choices += 1;
            tells.longest += usize::from(others().all(|l| l < right));
            tells.shortest += usize::from(others().all(|l| l > right));
            let longer = others().filter(|&l| l > right).count();
            tells.by_rank[longer.min(3)] += 1;
        }
        tells
    }
}

/// Refuses a tolerance finer than the precision the answer is shown with.
fn check_precision(question: usize, tolerance: f64) -> Result<(), ContentError> {
    if tolerance < MIN_TOLERANCE {
        Err(ContentError::ToleranceTooFine {
            question,
            tolerance,
        })
    } else {
        Ok(())
    }
}

/// True for a finite number above zero (false for NaN).
fn is_positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

/// Every string in `value` with its formulas written as MathML
/// ([`labtex::render`]), as `build.rs` writes the compiled-in files; an error
/// names the string's JSON path (`theory[2].formula`), `path` being
/// `value`'s own.
#[cfg(feature = "reading")]
fn render_formulas(value: &mut Json, path: String) -> Result<(), String> {
    match value {
        Json::String(s) => *s = labtex::render_field(&path, s)?,
        Json::Array(items) => {
            for (i, item) in items.iter_mut().enumerate() {
                render_formulas(item, format!("{path}[{i}]"))?;
            }
        }
        Json::Object(fields) => {
            for (key, item) in fields.iter_mut() {
                let inner = if path.is_empty() {
                    key.clone()
                } else {
                    format!("{path}.{key}")
                };
                render_formulas(item, inner)?;
            }
        }
        Json::Null | Json::Bool(_) | Json::Number(_) => {}
    }
    Ok(())
}

/// A display formula is exactly one `<math display="block">` element with
/// balanced tags.
fn is_block_math(s: &str) -> bool {
    let s = s.trim();
    s.starts_with("<math")
        && s.contains("display=\"block\"")
        && s.ends_with("</math>")
        && tags_balanced(s)
}

/// Checks that start and end tags nest properly (self-closing tags allowed).
#[must_use]
pub fn tags_balanced(s: &str) -> bool {
    let mut stack: Vec<&str> = Vec::new();
    let mut rest = s;
    while let Some(open) = rest.find('<') {
        let after = &rest[open + 1..];
        let Some(close) = after.find('>') else {
            return false;
        };
        let tag = &after[..close];
        rest = &after[close + 1..];
        if tag.ends_with('/') {
            continue;
        }
        if let Some(name) = tag.strip_prefix('/') {
            if stack.pop() != Some(name.trim()) {
                return false;
            }
        } else {
            let name = tag.split_whitespace().next().unwrap_or("");
            if name.is_empty() {
                return false;
            }
            stack.push(name);
        }
    }
    stack.is_empty()
}

// The content files, read at build time: `compiled(id)` (see build.rs).
include!(concat!(env!("OUT_DIR"), "/content.rs"));

/// The strings of a compiled-in list (aim, procedure, a choice's options).
#[allow(dead_code)] // a build without experiments calls it nowhere
fn strings(texts: &[&str]) -> Vec<String> {
    texts.iter().map(|t| String::from(*t)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 25 step 9: every content file is compiled in at build time
    /// (`build.rs`) as exactly what the crate's own reader reads from its
    /// text, so the entries' content is data, with nothing left to parse.
    #[test]
    fn content_is_parsed_once_at_build_time_into_the_same_content() {
        for entry in crate::registry() {
            let compiled = compiled(entry.id)
                .expect("every built experiment has its content compiled in")
                .expect("compiles");
            assert_eq!(
                compiled,
                Content::parse(entry.content_json).unwrap(),
                "{}",
                entry.id
            );
            assert_eq!(entry.content().unwrap(), &compiled, "{}", entry.id);
        }
        assert!(compiled("no-such-experiment").is_none());
    }

    #[test]
    fn references_link_to_their_doi_or_url() {
        let read = |text: &str| Reference::from_json(&Json::parse(text).unwrap(), 0);
        let r = read(r#"{"authors": "A", "title": "T", "venue": "V", "doi": "10.1115/1.3143764"}"#)
            .unwrap();
        assert_eq!(
            r.link().as_deref(),
            Some("https://doi.org/10.1115/1.3143764")
        );
        let r =
            read(r#"{"authors": "A", "title": "T", "venue": "V", "url": "https://example.org/x"}"#)
                .unwrap();
        assert_eq!(r.link().as_deref(), Some("https://example.org/x"));
        assert_eq!(
            read(r#"{"authors": "A", "title": "T", "venue": "V", "year": 1999.5}"#).unwrap_err(),
            "reference 1: field `year` should be a whole number, found a number"
        );
    }

    /// The reader agrees with serde_json on every content file (same values,
    /// keys in the same order), and both refuse the same broken variants.
    #[test]
    fn the_json_reader_agrees_with_serde_json_on_every_content_file() {
        fn same(a: &Json, b: &serde_json::Value) -> bool {
            match (a, b) {
                (Json::Null, serde_json::Value::Null) => true,
                (Json::Bool(x), serde_json::Value::Bool(y)) => x == y,
                (Json::Number(x), serde_json::Value::Number(y)) => Some(*x) == y.as_f64(),
                (Json::String(x), serde_json::Value::String(y)) => x == y,
                (Json::Array(x), serde_json::Value::Array(y)) => {
                    x.len() == y.len() && x.iter().zip(y).all(|(a, b)| same(a, b))
                }
                (Json::Object(x), serde_json::Value::Object(y)) => {
                    x.len() == y.len()
                        && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
                }
                _ => false,
            }
        }
        for entry in crate::registry() {
            let ours = Json::parse(entry.content_json).unwrap();
            let theirs: serde_json::Value = serde_json::from_str(entry.content_json).unwrap();
            assert!(same(&ours, &theirs), "{}", entry.id);
            let cut = &entry.content_json[..entry
                .content_json
                .floor_char_boundary(entry.content_json.len() / 3)];
            assert!(
                Json::parse(cut).is_err()
                    && serde_json::from_str::<serde_json::Value>(cut).is_err()
            );
        }
    }

    #[test]
    fn a_content_file_with_an_unknown_or_mistyped_field_is_refused_naming_it() {
        let entry = crate::find("fk").expect("fk");
        let good: serde_json::Value = serde_json::from_str(entry.content_json).unwrap();
        type Edit = fn(&mut serde_json::Value);
        let cases: [(Edit, &str); 5] = [
            (
                |v| v["colour"] = "red".into(),
                "content: unknown field `colour`",
            ),
            (
                |v| v["quiz"][2]["hint"] = "x".into(),
                "question 3: unknown field `hint`",
            ),
            (
                |v| v["quiz"][0]["kind"] = "essay".into(),
                "question 1: unknown kind `essay`",
            ),
            (
                |v| v["number"] = "one".into(),
                "content: field `number` should be a whole number",
            ),
            (
                |v| v["theory"][0] = serde_json::json!({"aside": "x"}),
                "theory block 1: unknown variant `aside`",
            ),
        ];
        for (edit, expected) in cases {
            let mut v = good.clone();
            edit(&mut v);
            let err = entry
                .parse_content_text(&v.to_string())
                .unwrap_err()
                .to_string();
            assert!(err.contains(expected), "{err}");
        }
    }

    /// Issue 52: the numbers of a Procedure step are one. A number its
    /// prose writes that is none of its machine part's values (nor
    /// `given`) is refused, naming the step and the number.
    #[test]
    fn a_prose_number_that_is_none_of_the_steps_values_is_refused() {
        let entry = crate::find("pid").expect("pid");
        let good: serde_json::Value = serde_json::from_str(entry.content_json).unwrap();
        assert!(entry.parse_content_text(&good.to_string()).is_ok());
        let mut v = good.clone();
        let text = v["procedure"][5]["text"]
            .as_str()
            .unwrap()
            .replace("18.16", "18.61");
        v["procedure"][5]["text"] = text.into();
        let err = entry
            .parse_content_text(&v.to_string())
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("procedure step 6") && err.contains("18.61"),
            "{err}"
        );
        let mut v = good;
        v["procedure"][0]["play"] = serde_json::json!([]);
        let err = entry
            .parse_content_text(&v.to_string())
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("procedure step 1") && err.contains("12"),
            "{err}"
        );
    }

    #[test]
    fn unbalanced_inline_markup_is_refused_naming_the_field() {
        let entry = crate::find("fk").expect("fk");
        let good: serde_json::Value = serde_json::from_str(entry.content_json).unwrap();
        type Edit = fn(&mut serde_json::Value);
        let cases: [(&str, Edit, &str); 4] = [
            (
                "aim",
                |v| v["aim"][1] = "<em>unclosed".into(),
                "aim paragraph 2",
            ),
            (
                "procedure",
                |v| v["procedure"][0]["text"] = "Drag the tip </strong>".into(),
                "procedure step 1",
            ),
            (
                "option",
                |v| v["quiz"][0]["options"][2] = "θ <sub>1".into(),
                "question 1 option 3",
            ),
            (
                "bare less-than",
                |v| v["theory"][1]["paragraph"] = "when a < b and c > d".into(),
                "theory block 2",
            ),
        ];
        for (what, edit, field) in cases {
            let mut v = good.clone();
            edit(&mut v);
            let err = entry.parse_content_text(&v.to_string()).expect_err(what);
            assert_eq!(
                err,
                ContentError::UnbalancedMarkup {
                    field: field.into()
                },
                "{what}"
            );
            assert!(err.to_string().starts_with(field));
        }
    }

    /// Issue 27 §1: every formula of every content file is LaTeX between
    /// dollars (no hand-written MathML is left) and converts: the compiled
    /// content holds one `<math>` element for each formula and no dollar.
    #[test]
    fn latex_every_formula_of_every_content_file_converts() {
        let mut formulas = 0;
        for entry in crate::registry() {
            let text = entry.content_json;
            assert!(!text.contains("<math"), "{}: hand-written MathML", entry.id);
            let content = entry.content().expect("converts");
            let mut written = 0;
            for (field, shown) in content.text_fields() {
                assert!(!shown.contains('$'), "{} {field}: {shown}", entry.id);
                // The Content-Security-Policy would block it.
                assert!(!shown.contains(" style="), "{} {field}: {shown}", entry.id);
                written += shown.matches("<math").count();
            }
            // The claims beyond the Procedure quote formulas but are not
            // compiled in (`build.rs`): they are not counted.
            let mut file: serde_json::Value = serde_json::from_str(text).unwrap();
            file.as_object_mut().unwrap().remove("claims");
            let text = file.to_string();
            let dollars = text.matches('$').count() - 2 * text.matches("$$").count();
            assert_eq!(dollars % 2, 0, "{}", entry.id);
            assert_eq!(
                written,
                dollars / 2 + text.matches("$$").count() / 2,
                "{}",
                entry.id
            );
            formulas += written;
        }
        // 458 when the formulas were moved from MathML to LaTeX.
        assert!(formulas >= 458, "{formulas} formulas");
    }

    /// Issue 27 §1: a formula that does not convert is refused naming the
    /// field (its JSON path) and the position in the formula.
    #[test]
    fn latex_a_broken_formula_is_named_with_its_field_and_position() {
        let entry = crate::find("fk").expect("fk");
        let mut v: serde_json::Value = serde_json::from_str(entry.content_json).unwrap();
        let formula = v["theory"][9]["formula"].as_str().unwrap().to_owned();
        let broken = formula.replacen("= L_1", "= \\nosuch L_1", 1);
        v["theory"][9]["formula"] = broken.clone().into();
        let err = entry
            .parse_content_text(&v.to_string())
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("theory[9].formula: LaTeX error at character ")
                && err.contains("\\nosuch"),
            "{err}"
        );
        let at: usize = err["theory[9].formula: LaTeX error at character ".len()..]
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        let latex = broken.trim_matches('$');
        assert_eq!(
            latex.chars().nth(at - 1),
            Some('\\'),
            "character {at} of {latex} starts the unknown command"
        );
        let mut v: serde_json::Value = serde_json::from_str(entry.content_json).unwrap();
        v["quiz"][0]["options"][1] = "costs $5".into();
        let err = entry
            .parse_content_text(&v.to_string())
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("quiz[0].options[1]: ") && err.contains("not closed"),
            "{err}"
        );
    }

    /// Issue 27 §3: the content names the panel's equations by key; a key
    /// the experiment has no equation for is refused naming it, as is a
    /// list of the wrong length or one with a repeat.
    #[test]
    fn live_math_a_named_equation_that_does_not_exist_is_refused_naming_its_key() {
        let entry = crate::find("fk").expect("fk");
        let good: serde_json::Value = serde_json::from_str(entry.content_json).unwrap();
        let refused = |math: serde_json::Value| {
            let mut v = good.clone();
            v["math"] = math;
            entry
                .parse_content_text(&v.to_string())
                .unwrap_err()
                .to_string()
        };
        assert_eq!(
            refused(serde_json::json!(["x", "tip_z"])),
            "math: no equation with key “tip_z” (the experiment's equations: x, y)"
        );
        assert!(refused(serde_json::json!([]))
            .starts_with("math: names 0 equations; the panel shows 1 to 4"));
        assert!(refused(serde_json::json!(["x", "x"])).starts_with("math: names 2 equations"));
        let mut v = good.clone();
        v.as_object_mut().unwrap().remove("math");
        let err = entry
            .parse_content_text(&v.to_string())
            .unwrap_err()
            .to_string();
        assert!(err.contains("missing field `math`"), "{err}");
        assert_eq!(entry.content().unwrap().math, ["x", "y"]);
    }

    /// Issue 27 §3: every `\live{key}{…}` symbol names one of the
    /// experiment's quantities; an unknown key is refused naming the field
    /// and the key.
    #[test]
    fn live_a_symbol_naming_no_quantity_is_refused_naming_the_field_and_key() {
        let entry = crate::find("fk").expect("fk");
        let mut v: serde_json::Value = serde_json::from_str(entry.content_json).unwrap();
        v["theory"][1]["paragraph"] =
            "The angle $\\live{t1}{\\theta_1}$ and $\\live{t9}{\\theta_9}$.".into();
        let err = entry
            .parse_content_text(&v.to_string())
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("theory block 2: \\live{t9}: no quantity with key “t9” (the experiment's quantities: l1, l2, t1, t2"),
            "{err}"
        );
        v["theory"][1]["paragraph"] = "The angle $\\live{t1}{\\theta_1}$.".into();
        assert!(entry.parse_content_text(&v.to_string()).is_ok());
    }

    /// An experiment without equations names none.
    #[test]
    fn live_math_an_experiment_without_equations_names_none() {
        let content = crate::find("fk").unwrap().content().unwrap();
        let mut c = content.clone();
        c.math = vec!["x".into()];
        assert_eq!(
            c.check_live_names(&[], &[]).unwrap_err().to_string(),
            "math: names 1 equations, but the experiment has none (write \"math\": [])"
        );
        c.math.clear();
        c.theory.clear();
        c.quiz.clear();
        c.aim.clear();
        c.procedure.clear();
        assert_eq!(c.check_live_names(&[], &[]), Ok(()));
    }

    #[test]
    fn balanced_tags() {
        assert!(tags_balanced("<math><mi>x</mi><mo>=</mo></math>"));
        assert!(tags_balanced("<math><mspace width=\"1em\"/></math>"));
        assert!(!tags_balanced("<math><mi>x</math>"));
        assert!(!tags_balanced("<math><mi>x</mo></math>"));
    }
}
