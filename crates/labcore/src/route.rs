//! URL state: `#/fk/simulation?t1=35&t2=60` ↔ experiment, tab and parameters.
//!
//! Parsing never fails: anything malformed falls back to a default and adds a
//! short notice for the page to show.

use crate::experiment::{Experiment, Lab, ParamError, Sanitized};
use crate::units::format_number;

/// The six tabs of an experiment page, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tab {
    Aim,
    Theory,
    Procedure,
    Simulation,
    Quiz,
    References,
}

impl Tab {
    pub const ALL: [Tab; 6] = [
        Tab::Aim,
        Tab::Theory,
        Tab::Procedure,
        Tab::Simulation,
        Tab::Quiz,
        Tab::References,
    ];

    /// The slug used in the URL.
    #[must_use]
    pub fn slug(self) -> &'static str {
        match self {
            Tab::Aim => "aim",
            Tab::Theory => "theory",
            Tab::Procedure => "procedure",
            Tab::Simulation => "simulation",
            Tab::Quiz => "quiz",
            Tab::References => "references",
        }
    }

    /// The tab's visible title.
    #[must_use]
    pub fn title(self) -> &'static str {
        match self {
            Tab::Aim => "Aim",
            Tab::Theory => "Theory",
            Tab::Procedure => "Procedure",
            Tab::Simulation => "Simulation",
            Tab::Quiz => "Self-assessment",
            Tab::References => "References",
        }
    }

    #[must_use]
    pub fn from_slug(slug: &str) -> Option<Tab> {
        Tab::ALL.into_iter().find(|t| t.slug() == slug)
    }
}

/// Which page the hash names.
#[derive(Clone, Debug, PartialEq)]
pub enum Page {
    Home,
    Experiment {
        id: String,
        tab: Tab,
        /// Raw `key=value` pairs, checked later by [`apply_params`].
        params: Vec<(String, String)>,
    },
}

/// A parsed hash and what was wrong with it.
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    pub page: Page,
    pub notices: Vec<String>,
    /// The quiz attempt seed fixed by the link (`?quiz=123`), e.g. by an
    /// instructor so a whole class draws the same numbers. Taken out of
    /// [`Page::Experiment::params`]; `None` when absent or unreadable.
    pub quiz_seed: Option<u64>,
    /// Locks, hidden controls and the note of an instructor's link
    /// (`lock=kp,ki&hide=noise&note=…`), taken out of the parameters; not
    /// yet checked against the experiment (see [`Instructor::resolve`]).
    pub instructor: Instructor,
}

impl Route {
    /// Whether the link sets an instructor's settings: a lock, a hidden
    /// control, a note, an answer-key choice, a grading rule or a quiz seed.
    /// Not the Self-assessment tab's own link, which carries the grading
    /// rules in force and the student's seed (a lock, a hide, a note or an
    /// answer key there still count).
    #[must_use]
    pub fn carries_instructor(&self) -> bool {
        match &self.page {
            Page::Experiment { tab: Tab::Quiz, .. } => !self.instructor.holds_only_quiz_rules(),
            Page::Experiment { .. } => !self.instructor.is_empty() || self.quiz_seed.is_some(),
            Page::Home => false,
        }
    }

    /// Gives a link that sets no instructor's settings those of the
    /// instructor's link for the same experiment opened earlier in the
    /// visit (`kept`), so they hold until another instructor's link or
    /// until the student leaves them. In a page `fresh`ly mounted (back
    /// from another experiment, a reload), a link without parameters (the
    /// menu's `#/pid/aim`, a tab) opens the kept link's state; a link with
    /// parameters (a preset) keeps its own state under the kept settings.
    /// In a page that shows the experiment already, a link without
    /// parameters (a tab switch) changes nothing. Returns the kept link's
    /// quiz seed (the class's, for the page's link and the report) when its
    /// settings were taken; the route's own seed, a Self-assessment's
    /// attempt, stays when it has one.
    pub fn keep_instructor(&mut self, kept: &str, fresh: bool) -> Option<Option<u64>> {
        if self.carries_instructor() {
            return None;
        }
        let Page::Experiment { id, params, .. } = &mut self.page else {
            return None;
        };
        if params.is_empty() && !fresh {
            return None;
        }
        let from = parse(kept, &[id.as_str()]);
        if let (true, Page::Experiment { params: state, .. }) = (params.is_empty(), from.page) {
            *params = state;
        }
        self.instructor = from.instructor;
        self.quiz_seed = self.quiz_seed.or(from.quiz_seed);
        Some(from.quiz_seed)
    }
}

/// The query key that fixes the quiz attempt's seed (`#/ik/quiz?quiz=123`).
pub const QUIZ_KEY: &str = "quiz";

/// How many notices the page shows before summarising the rest (see [`summarize_notices`]).
pub const NOTICE_LIMIT: usize = 3;

/// The notices to show: the first `limit`, then one line “… and N more
/// problems with the link.” so a hostile 100 KB hash cannot flood the bar.
/// Each shown notice is already short (values are truncated when parsed).
#[must_use]
pub fn summarize_notices(notices: &[String], limit: usize) -> Vec<String> {
    if notices.len() <= limit {
        return notices.to_vec();
    }
    let rest = notices.len() - limit;
    let mut shown = notices[..limit].to_vec();
    shown.push(format!(
        "… and {rest} more problem{} with the link.",
        if rest == 1 { "" } else { "s" }
    ));
    shown
}

/// Parses a location hash (with or without the leading `#`).
#[must_use]
pub fn parse(hash: &str, known_ids: &[&str]) -> Route {
    let mut notices = Vec::new();
    let hash = hash.strip_prefix('#').unwrap_or(hash);
    let (path, query) = match hash.split_once('?') {
        Some((p, q)) => (p, Some(q)),
        None => (hash, None),
    };
    let segments: Vec<&str> = path.split('/').filter(|s| !s.is_empty()).collect();
    let Some(&first) = segments.first() else {
        if query.is_some_and(|q| !q.is_empty()) {
            notices.push("Ignored parameters on the home page.".into());
        }
        return Route {
            page: Page::Home,
            notices,
            quiz_seed: None,
            instructor: Instructor::default(),
        };
    };
    let id = decode(first);
    if !known_ids.contains(&id.as_str()) {
        notices.push(format!(
            "No experiment called “{}”; showing the list instead.",
            truncate(&id, 40)
        ));
        return Route {
            page: Page::Home,
            notices,
            quiz_seed: None,
            instructor: Instructor::default(),
        };
    }
    let tab = match segments.get(1) {
        None => Tab::Aim,
        Some(slug) => Tab::from_slug(&decode(slug)).unwrap_or_else(|| {
            notices.push(format!(
                "No tab called “{}”; opened Aim.",
                truncate(&decode(slug), 40)
            ));
            Tab::Aim
        }),
    };
    if segments.len() > 2 {
        notices.push("Ignored extra parts of the link.".into());
    }
    let mut params = Vec::new();
    let mut quiz_seed = None;
    let mut instructor = Instructor::default();
    for pair in query.unwrap_or("").split('&').filter(|p| !p.is_empty()) {
        match pair.split_once('=') {
            Some((k, v)) if decode(k) == QUIZ_KEY => match decode(v).trim().parse::<u64>() {
                Ok(seed) => quiz_seed = Some(seed),
                Err(_) => notices.push(format!(
                    "Quiz seed “{}” is not a whole number; drew fresh questions.",
                    truncate(&decode(v), 30)
                )),
            },
            Some((k, v)) if decode(k) == LOCK_KEY => instructor.locked.extend(key_list(v)),
            Some((k, v)) if decode(k) == HIDE_KEY => instructor.hidden.extend(key_list(v)),
            Some((k, v)) if decode(k) == ANSWER_KEY_KEY => {
                match AnswerKey::from_slug(decode(v).trim()) {
                    Some(choice) => instructor.answer_key = Some(choice),
                    None => notices.push(format!(
                        "Answer key “{}” is not never, submitted or always; ignored.",
                        truncate(&decode(v), 30)
                    )),
                }
            }
            Some((k, v)) if decode(k) == NOTE_KEY => {
                let (note, notice) = clean_note(&decode(v));
                instructor.note = note;
                notices.extend(notice);
            }
            Some((k, v)) if [ATTEMPTS_KEY, SCORE_KEY].contains(&decode(k).as_str()) => {
                if !instructor.quiz.set(&decode(k), &decode(v)) {
                    notices.push(format!(
                        "Ignored “{}”: attempts takes a whole number from 1 or unlimited, score takes best, last or first.",
                        truncate(&decode(pair), 30)
                    ));
                }
            }
            Some((k, v)) if decode(k) == VEILED_KEY => match unveil(&decode(v)) {
                Some(text) => {
                    for (k, v) in text.split('&').filter_map(|p| p.split_once('=')) {
                        params.push((decode(k), decode(v)));
                    }
                }
                None => notices.push(
                    "The link's hidden settings are damaged; they keep their defaults.".into(),
                ),
            },
            Some((k, v)) if !k.is_empty() => params.push((decode(k), decode(v))),
            _ => notices.push(format!(
                "Ignored “{}” in the link.",
                truncate(&decode(pair), 40)
            )),
        }
    }
    Route {
        page: Page::Experiment { id, tab, params },
        notices,
        quiz_seed,
        instructor,
    }
}

/// Applies raw URL parameters to an experiment: unknown keys and unreadable
/// numbers are skipped, out-of-range values are clamped; each problem becomes
/// a notice. Keys that are not numeric parameters go to
/// [`Experiment::set_extra_state`] first (a grid before the start cell that
/// must lie in it), then the numeric parameters in link order. Returns the
/// notices in link order.
pub fn apply_params(experiment: &mut dyn Experiment, params: &[(String, String)]) -> Vec<String> {
    let is_numeric = |exp: &dyn Experiment, key: &str| exp.params().iter().any(|s| s.key == key);
    // Each loop notes in link order; the two lists are merged at the end.
    let mut extra: Vec<(usize, String)> = Vec::new();
    let mut notices: Vec<(usize, String)> = Vec::new();
    for (i, (key, raw)) in params.iter().enumerate() {
        if is_numeric(experiment, key) {
            continue;
        }
        match experiment.set_extra_state(key, raw) {
            Ok(()) => {}
            Err(ParamError::UnknownKey { .. }) => extra.push((
                i,
                format!("Unknown setting “{}” ignored.", truncate(key, 30)),
            )),
            Err(e) => extra.push((
                i,
                format!(
                    "{}: {}; kept the current value.",
                    truncate(key, 30),
                    truncate(&e.to_string(), 120)
                ),
            )),
        }
    }
    for (i, (key, raw)) in params.iter().enumerate() {
        let Some(spec) = experiment.params().iter().find(|s| s.key == key) else {
            continue;
        };
        let label = spec.label;
        let value = match raw.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => v,
            // "1e999" is a number, just far out of range: clamp it like one.
            Ok(v) if v.is_infinite() => {
                if v > 0.0 {
                    f64::MAX
                } else {
                    f64::MIN
                }
            }
            _ => {
                notices.push((
                    i,
                    format!(
                        "{label}: “{}” is not a number; kept the current value.",
                        truncate(raw, 30)
                    ),
                ));
                continue;
            }
        };
        match experiment.set_param(key, value) {
            Ok(Sanitized::InRange(_)) => {}
            Ok(Sanitized::Clamped(v)) => notices.push((
                i,
                format!(
                    "{label}: “{}” is out of range; using {}.",
                    truncate(raw.trim(), 30),
                    format_number(v, 3)
                ),
            )),
            Err(e) => notices.push((i, format!("{label}: {e}."))),
        }
    }
    // A merge, not a sort: both lists are in link order already, and a
    // stable sort would add about 1 KB to every wasm module's gzip bytes.
    let mut merged = Vec::with_capacity(extra.len() + notices.len());
    let (mut extra, mut numeric) = (extra.into_iter().peekable(), notices.into_iter().peekable());
    loop {
        let from_extra = match (extra.peek(), numeric.peek()) {
            (Some((i, _)), Some((j, _))) => i <= j,
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (None, None) => break,
        };
        let next = if from_extra {
            extra.next()
        } else {
            numeric.next()
        };
        merged.extend(next.map(|(_, n)| n));
    }
    merged
}

/// Rebuilds an experiment from a link: `fresh` (usually at its defaults)
/// with the link's parameters applied. Returns it with every notice — about
/// the link itself and about its parameters; none means the link reproduced
/// a state exactly as written.
pub fn restore<E: Experiment>(link: &str, mut fresh: E) -> (E, Vec<String>) {
    let route = parse(link, &[fresh.id()]);
    let mut notices = route.notices;
    match route.page {
        Page::Experiment { params, .. } => notices.extend(apply_params(&mut fresh, &params)),
        Page::Home => notices.push("The link names no experiment.".into()),
    }
    (fresh, notices)
}

/// [`restore`] for an instructor's link: also returns its locks, hidden
/// controls and note, checked against the experiment (an unknown key is
/// dropped with a notice).
pub fn restore_instructor<E: Experiment>(link: &str, fresh: E) -> (E, Instructor, Vec<String>) {
    let mut instructor = parse(link, &[fresh.id()]).instructor;
    let (exp, mut notices) = restore(link, fresh);
    notices.extend(instructor.resolve(exp.params()));
    (exp, instructor, notices)
}

/// Opens a link's parameters in a tab that may already show the experiment.
/// A link with parameters describes a whole state, so the experiment is
/// rebuilt from `make` (its defaults) before the link is applied: whatever
/// the link leaves out takes its default, never a value kept from before.
/// A link without parameters (`#/id/tab`) keeps the current state. Returns
/// the notices of [`apply_params`].
pub fn open_in_tab(
    current: &mut Box<dyn Lab>,
    make: fn() -> Box<dyn Lab>,
    params: &[(String, String)],
) -> Vec<String> {
    if params.is_empty() {
        return Vec::new();
    }
    *current = make();
    apply_params(current.as_mut(), params)
}

/// Builds the hash for an experiment, its tab, every parameter's current
/// value and then its [`Experiment::extra_state`].
#[must_use]
pub fn format(experiment: &dyn Experiment, tab: Tab) -> String {
    format_veiled(experiment, tab, &[])
}

/// [`format`] with the values of the `hidden` parameters veiled together
/// ([`veil`]) in one `hv=…` where the first of them stands, so the address
/// bar and a report's link do not show them; [`parse`] puts them back in
/// that place.
#[must_use]
pub fn format_veiled(experiment: &dyn Experiment, tab: Tab, hidden: &[String]) -> String {
    let (mut query, mut veiled) = (Vec::new(), Vec::new());
    for s in experiment.params() {
        let Some(v) = experiment.param(s.key) else {
            continue;
        };
        let pair = format!("{}={}", s.key, link_number(v));
        if hidden.iter().any(|k| k == s.key) {
            if veiled.is_empty() {
                // The veil's place, written once every hidden pair is known.
                query.push(String::new());
            }
            veiled.push(pair);
        } else {
            query.push(pair);
        }
    }
    if let Some(slot) = query.iter_mut().find(|p| p.is_empty()) {
        *slot = format!("{VEILED_KEY}={}", veil(&veiled.join("&")));
    }
    for (k, v) in experiment.extra_state() {
        query.push(format!("{}={}", encode(k), encode(&v)));
    }
    if query.is_empty() {
        format!("#/{}/{}", experiment.id(), tab.slug())
    } else {
        format!("#/{}/{}?{}", experiment.id(), tab.slug(), query.join("&"))
    }
}

/// A parameter value as the link writes it: the shortest text that parses
/// back to exactly the same `f64` (`12.3456`, `1e-9`, `2`), so a link keeps
/// whatever a field or a pointer set. Whole numbers print without a point;
/// very large or small magnitudes use an exponent (`1e300`, `5e-324`).
#[must_use]
pub fn link_number(value: f64) -> String {
    if value == 0.0 {
        return "0".into();
    }
    // `{:?}` is Rust's shortest round-trip form, switching to an exponent
    // outside 1e-5..1e16; drop its trailing ".0" on whole numbers.
    let text = format!("{value:?}");
    match text.strip_suffix(".0") {
        Some(whole) => whole.to_owned(),
        None => text,
    }
}

/// Percent-encodes every byte outside RFC 3986's unreserved characters
/// (`A–Z a–z 0–9 - . _ ~`), so a text value survives [`parse`] unchanged.
#[must_use]
pub fn encode(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for b in s.bytes() {
        if b.is_ascii_alphanumeric() || matches!(b, b'-' | b'.' | b'_' | b'~') {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// [`format`] plus `quiz=<seed>` when the attempt's seed is fixed by the link,
/// so a reload (or a link shared with a class) keeps the same questions.
#[must_use]
pub fn format_with_quiz(experiment: &dyn Experiment, tab: Tab, quiz_seed: Option<u64>) -> String {
    let hash = format(experiment, tab);
    match quiz_seed {
        None => hash,
        Some(seed) if hash.contains('?') => format!("{hash}&{QUIZ_KEY}={seed}"),
        Some(seed) => format!("{hash}?{QUIZ_KEY}={seed}"),
    }
}

/// The query key listing locked parameters (`lock=kp,ki`).
pub const LOCK_KEY: &str = "lock";
/// The query key listing hidden parameters (`hide=noise`).
pub const HIDE_KEY: &str = "hide";
/// The query key of the instructor's note (`note=Find+the+smallest+Kp…`).
pub const NOTE_KEY: &str = "note";
/// The longest note kept, in characters (a longer one is shortened).
pub const NOTE_MAX_CHARS: usize = 280;
/// The query key of how many graded attempts the quiz allows (`attempts=2`,
/// or `attempts=unlimited`, the default).
pub const ATTEMPTS_KEY: &str = "attempts";
/// The query key of which graded attempt's score counts (`score=best`,
/// `last` or `first`; best when absent).
pub const SCORE_KEY: &str = "score";

/// Which graded attempt gives the quiz's score, the one an LMS records.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ScoreRule {
    /// The highest percentage of all graded attempts.
    #[default]
    Best,
    /// The latest graded attempt's, even when lower than before.
    Last,
    /// The first graded attempt's; later ones are practice.
    First,
}

impl ScoreRule {
    /// Every rule, default first.
    pub const ALL: [ScoreRule; 3] = [ScoreRule::Best, ScoreRule::Last, ScoreRule::First];

    /// The word in a link (`score=last`) and in messages.
    #[must_use]
    pub fn slug(self) -> &'static str {
        match self {
            ScoreRule::Best => "best",
            ScoreRule::Last => "last",
            ScoreRule::First => "first",
        }
    }

    /// The rule a link's word names (`best`, `last`, `first`, trimmed).
    #[must_use]
    pub fn from_slug(slug: &str) -> Option<ScoreRule> {
        Self::ALL.into_iter().find(|r| r.slug() == slug.trim())
    }

    /// The percentage that counts once an attempt scoring `percent` is
    /// graded, `counted` being what counted before (`None` before the
    /// first graded attempt).
    #[must_use]
    pub fn fold(self, counted: Option<usize>, percent: usize) -> usize {
        match (self, counted) {
            (ScoreRule::Best, Some(c)) => c.max(percent),
            (ScoreRule::First, Some(c)) => c,
            _ => percent,
        }
    }
}

/// An instructor's rules for grading the quiz (`attempts=2&score=first`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuizRules {
    /// Graded attempts allowed; `None`: no limit.
    pub attempts: Option<u32>,
    /// Which graded attempt's score counts.
    pub score: ScoreRule,
}

impl QuizRules {
    /// Sets the rule of a link's `key` ([`ATTEMPTS_KEY`]: a whole number
    /// from 1 or `unlimited`; [`SCORE_KEY`]: a [`ScoreRule`] word) from its
    /// `value`. False, with the rule kept, for a value that is neither.
    pub fn set(&mut self, key: &str, value: &str) -> bool {
        let value = value.trim();
        if key == SCORE_KEY {
            let rule = ScoreRule::from_slug(value);
            self.score = rule.unwrap_or(self.score);
            return rule.is_some();
        }
        match value.parse::<u64>() {
            _ if value == "unlimited" => self.attempts = None,
            Ok(n @ 1..=999_999) => self.attempts = Some(n as u32),
            _ => return false,
        }
        true
    }

    /// Whether another attempt may be graded after `graded` of them.
    #[must_use]
    pub fn allows(&self, graded: u32) -> bool {
        self.attempts.is_none_or(|n| graded < n)
    }
}

/// The query key choosing whether a lab report shows each question's
/// expected answer (`key=never|submitted|always`, see [`AnswerKey`]).
pub const ANSWER_KEY_KEY: &str = "key";

/// Whether a lab report prints the expected answer beside each question.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AnswerKey {
    /// Never: the report shows the answers given and whether each was right.
    Never,
    /// Once the Self-assessment was submitted (the report then shows it).
    Submitted,
    /// Always: a report made before submitting lists the questions with
    /// their expected answers too (a worked example).
    Always,
}

impl AnswerKey {
    /// Every choice, in the order the Instructor panel offers them.
    pub const ALL: [AnswerKey; 3] = [AnswerKey::Never, AnswerKey::Submitted, AnswerKey::Always];

    /// The value in a link: `never`, `submitted` or `always`.
    #[must_use]
    pub fn slug(self) -> &'static str {
        match self {
            AnswerKey::Never => "never",
            AnswerKey::Submitted => "submitted",
            AnswerKey::Always => "always",
        }
    }

    /// The choice a link's value names, if any.
    #[must_use]
    pub fn from_slug(slug: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.slug() == slug)
    }

    /// The choice in force: the link's, else [`AnswerKey::Never`] when the
    /// link fixes a quiz seed (the whole class draws the same questions, so
    /// one report would hand everyone the key), else
    /// [`AnswerKey::Submitted`].
    #[must_use]
    pub fn in_force(chosen: Option<Self>, quiz_seed: Option<u64>) -> Self {
        chosen.unwrap_or(if quiz_seed.is_some() {
            AnswerKey::Never
        } else {
            AnswerKey::Submitted
        })
    }
}

/// What an instructor's link adds to a state: parameters shown but not
/// changeable (**locked**), parameters not shown (**hidden**), a short
/// **note** shown above the simulation and the quiz's grading **rules**
/// (attempts allowed, which score counts). A teaching aid, not security: a
/// student may edit the URL (inside an LMS the package's rules hold). The
/// quiz seed travels beside it as [`Route::quiz_seed`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Instructor {
    /// Keys of locked parameters, in link order, without repeats once resolved.
    pub locked: Vec<String>,
    /// Keys of hidden parameters.
    pub hidden: Vec<String>,
    /// Plain text (no control characters, at most [`NOTE_MAX_CHARS`]); the
    /// page shows it as text, never as HTML.
    pub note: Option<String>,
    /// Attempts allowed and which score counts (`attempts=2&score=best`).
    pub quiz: QuizRules,
    /// Whether a lab report shows the expected answers (`key=`); `None`
    /// takes the default of [`AnswerKey::in_force`].
    pub answer_key: Option<AnswerKey>,
}

impl Instructor {
    /// Nothing locked, hidden or noted.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.quiz == QuizRules::default() && self.holds_only_quiz_rules()
    }

    /// Nothing locked, hidden, noted or chosen for the report: at most the
    /// quiz's grading rules, as the Self-assessment tab's own link carries.
    #[must_use]
    pub fn holds_only_quiz_rules(&self) -> bool {
        self.locked.is_empty()
            && self.hidden.is_empty()
            && self.note.is_none()
            && self.answer_key.is_none()
    }

    #[must_use]
    pub fn is_locked(&self, key: &str) -> bool {
        self.locked.iter().any(|k| k == key)
    }

    #[must_use]
    pub fn is_hidden(&self, key: &str) -> bool {
        self.hidden.iter().any(|k| k == key)
    }

    /// Keeps the keys that name one of `specs` (each once, in the order
    /// written) and drops the rest with a notice each, e.g. “Cannot lock
    /// “kq”: this experiment has no such setting; ignored.”.
    pub fn resolve(&mut self, specs: &[crate::ParamSpec]) -> Vec<String> {
        let mut notices = Vec::new();
        for (list, verb) in [(&mut self.locked, "lock"), (&mut self.hidden, "hide")] {
            let mut kept: Vec<String> = Vec::new();
            for key in list.drain(..) {
                if !specs.iter().any(|s| s.key == key) {
                    notices.push(format!(
                        "Cannot {verb} “{}”: this experiment has no such setting; ignored.",
                        truncate(&key, 30)
                    ));
                } else if !kept.contains(&key) {
                    kept.push(key);
                }
            }
            *list = kept;
        }
        notices
    }

    /// The link's `lock=…&hide=…&note=…&attempts=…&score=…&key=…` pairs
    /// (only those in use, a default rule left out), in that order, each
    /// already encoded.
    #[must_use]
    pub fn query(&self) -> Vec<String> {
        let list = |keys: &[String]| keys.iter().map(|k| encode(k)).collect::<Vec<_>>().join(",");
        let mut out = Vec::new();
        if !self.locked.is_empty() {
            out.push(format!("{LOCK_KEY}={}", list(&self.locked)));
        }
        if !self.hidden.is_empty() {
            out.push(format!("{HIDE_KEY}={}", list(&self.hidden)));
        }
        if let Some(note) = &self.note {
            out.push(format!("{NOTE_KEY}={}", encode(note)));
        }
        if let Some(n) = self.quiz.attempts {
            out.push(format!("{ATTEMPTS_KEY}={n}"));
        }
        if self.quiz.score != ScoreRule::Best {
            out.push(format!("{SCORE_KEY}={}", self.quiz.score.slug()));
        }
        if let Some(choice) = self.answer_key {
            out.push(format!("{ANSWER_KEY_KEY}={}", choice.slug()));
        }
        out
    }
}

/// The keys of a `lock=`/`hide=` value: comma-separated, trimmed, empties dropped.
fn key_list(raw: &str) -> Vec<String> {
    decode(raw)
        .split(',')
        .map(str::trim)
        .filter(|k| !k.is_empty())
        .map(str::to_owned)
        .collect()
}

/// A note as the page keeps it: control characters (line breaks included)
/// become spaces, the ends are trimmed, and more than [`NOTE_MAX_CHARS`]
/// characters are cut with a notice. Empty: no note.
#[must_use]
pub fn clean_note(raw: &str) -> (Option<String>, Option<String>) {
    let text: String = raw
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    let text = text.trim();
    if text.is_empty() {
        return (None, None);
    }
    if text.chars().count() > NOTE_MAX_CHARS {
        let cut: String = text.chars().take(NOTE_MAX_CHARS).collect();
        return (
            Some(cut.trim_end().to_owned()),
            Some(format!(
                "The instructor's note is longer than {NOTE_MAX_CHARS} characters; shortened."
            )),
        );
    }
    (Some(text.to_owned()), None)
}

/// Appends encoded `key=value` pairs to a hash's query.
#[must_use]
pub fn with_query(mut hash: String, pairs: &[String]) -> String {
    if !pairs.is_empty() {
        hash.push(if hash.contains('?') { '&' } else { '?' });
        hash.push_str(&pairs.join("&"));
    }
    hash
}

/// A whole instructor's link: the state ([`format`]), then the locks,
/// hidden controls and note, then the quiz seed.
#[must_use]
pub fn format_instructor(
    experiment: &dyn Experiment,
    tab: Tab,
    instructor: &Instructor,
    quiz_seed: Option<u64>,
) -> String {
    let mut pairs = instructor.query();
    pairs.extend(quiz_seed.map(|s| format!("{QUIZ_KEY}={s}")));
    with_query(format_veiled(experiment, tab, &instructor.hidden), &pairs)
}

/// The query key of the hidden parameters' values, veiled (`hv=…`, see [`veil`]).
pub const VEILED_KEY: &str = "hv";

/// The mask of byte `i` of a veiled text.
fn mask(i: usize) -> u8 {
    (i as u8).wrapping_mul(29).wrapping_add(0x5A)
}

/// Veils `text` (a hidden parameter's `key=value` pairs) so a student does
/// not read it at a glance in the address bar: each byte XOR-ed with a mask
/// that changes along the text, written as two hex digits (`m=2.5` →
/// `374AA69FFB`). Anyone may undo it with [`unveil`]: it keeps a value out
/// of sight, not secret. `web/instructor.js` writes the same.
#[must_use]
pub fn veil(text: &str) -> String {
    let mut out = String::new();
    for (i, b) in text.bytes().enumerate() {
        out.push_str(&format!("{:02X}", b ^ mask(i)));
    }
    out
}

/// The text [`veil`] veiled; `None` for a blob it cannot have written.
#[must_use]
pub fn unveil(blob: &str) -> Option<String> {
    let mut bytes = Vec::new();
    for (i, h) in blob.as_bytes().chunks(2).enumerate() {
        let [hi, lo] = *h else { return None };
        bytes.push((hex_digit(hi)? << 4 | hex_digit(lo)?) ^ mask(i));
    }
    Some(String::from_utf8_lossy(&bytes).into_owned())
}

/// Runs `op` (a pointer input, an action, a reset, a loaded file, a run of
/// steps) and puts back every locked parameter it changed, so a drag that
/// would turn a locked joint moves only the free ones. When a value cannot
/// be put back by itself (a choice an action made, such as a grid size
/// only a map file gives), the whole state before `op` is applied again
/// from its link. Returns the labels of the parameters that had to be put
/// back (the page says they are locked).
pub fn keep_locked(
    experiment: &mut dyn Lab,
    instructor: &Instructor,
    op: impl FnOnce(&mut dyn Lab),
) -> Vec<&'static str> {
    let mut op = Some(op);
    keep_locked_dyn(experiment, instructor, &mut |e| {
        if let Some(op) = op.take() {
            op(e);
        }
    })
}

/// [`keep_locked`]'s body, compiled once for every caller's `op` (each
/// caller's own copy cost the shipped modules about 800 bytes).
#[inline(never)]
fn keep_locked_dyn(
    experiment: &mut dyn Lab,
    instructor: &Instructor,
    op: &mut dyn FnMut(&mut dyn Lab),
) -> Vec<&'static str> {
    if instructor.locked.is_empty() {
        op(experiment);
        return Vec::new();
    }
    let values = |e: &dyn Experiment| -> Vec<Option<f64>> {
        instructor.locked.iter().map(|k| e.param(k)).collect()
    };
    let before = values(experiment);
    let link = format(experiment, Tab::Simulation);
    op(experiment);
    let after = values(experiment);
    if after == before {
        return Vec::new();
    }
    let mut put_back = Vec::new();
    for ((key, was), now) in instructor.locked.iter().zip(&before).zip(&after) {
        if now == was {
            continue;
        }
        if let Some(v) = was {
            let _ = experiment.set_param(key, *v);
        }
        if let Some(spec) = experiment.params().iter().find(|s| s.key == key) {
            put_back.push(spec.label);
        }
    }
    if values(experiment) != before {
        if let Page::Experiment { params, .. } = parse(&link, &[experiment.id()]).page {
            let _ = apply_params(experiment, &params);
        }
    }
    put_back
}

/// Percent-decoding of a URL component; invalid escapes are kept verbatim.
fn decode(s: &str) -> String {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            // Exactly two hex digits: `u8::from_str_radix` alone would also
            // take a sign (`%+3` → 3), turning `%+31` into a control character.
            if let (Some(hi), Some(lo)) = (hex_digit(bytes[i + 1]), hex_digit(bytes[i + 2])) {
                out.push(hi << 4 | lo);
            } else {
                // An invalid escape is kept exactly as written (`+` included).
                out.extend_from_slice(&bytes[i..i + 3]);
            }
            i += 3;
            continue;
        }
        out.push(if bytes[i] == b'+' { b' ' } else { bytes[i] });
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The value of one ASCII hex digit.
fn hex_digit(b: u8) -> Option<u8> {
    match b {
        b'0'..=b'9' => Some(b - b'0'),
        b'a'..=b'f' => Some(b - b'a' + 10),
        b'A'..=b'F' => Some(b - b'A' + 10),
        _ => None,
    }
}

fn truncate(s: &str, max_chars: usize) -> String {
    if s.chars().count() <= max_chars {
        s.to_owned()
    } else {
        let mut t: String = s.chars().take(max_chars).collect();
        t.push('…');
        t
    }
}

#[cfg(test)]
mod tests {

    #[test]
    fn link_numbers_round_trip_exactly_and_stay_short() {
        assert_eq!(link_number(12.3456), "12.3456");
        assert_eq!(link_number(2.0), "2");
        assert_eq!(link_number(-0.5), "-0.5");
        assert_eq!(link_number(0.0), "0");
        assert_eq!(link_number(-0.0), "0");
        assert_eq!(link_number(1e-9), "1e-9");
        assert_eq!(link_number(1e300), "1e300");
        assert_eq!(link_number(0.1 + 0.2), "0.30000000000000004");
        let mut rng = crate::Lcg64::new(7);
        for _ in 0..20_000 {
            let v = match rng.int(0, 3) {
                0 => rng.range(-10.0, 10.0),
                1 => rng.range(-1.0, 1.0) * 10f64.powi(rng.int(-320, 300) as i32),
                2 => (rng.range(-1000.0, 1000.0) * 1000.0).round() / 1000.0,
                _ => rng.int(-100_000, 100_000) as f64,
            };
            let text = link_number(v);
            let back: f64 = text.parse().unwrap();
            assert!(back == v, "{v:?} → {text} → {back:?}");
            assert!(text.len() <= 24, "{text}");
        }
    }

    #[test]
    fn typed_values_reload_exactly() {
        // Issue 14: "12.3456" in the Kp box reloaded as 12.346; r = 1e-9 as 0.
        use crate::experiments::fk::ForwardKinematics;
        let mut exp = ForwardKinematics::default();
        exp.set_param("t1", 12.3456).unwrap();
        exp.set_param("l1", 0.300_000_001).unwrap();
        let link = format(&exp, Tab::Simulation);
        let (back, notices) = restore(&link, ForwardKinematics::default());
        assert!(notices.is_empty(), "{notices:?}");
        assert_eq!(back.param("t1"), Some(12.3456));
        assert_eq!(back.param("l1"), Some(0.300_000_001));
    }

    use super::*;

    #[test]
    fn restore_applies_a_link_and_reports_what_it_could_not() {
        use crate::experiments::fk::ForwardKinematics;
        let (fk, notices) = restore("#/fk/simulation?t1=10&t2=20", ForwardKinematics::default());
        assert!(notices.is_empty(), "{notices:?}");
        assert_eq!((fk.param("t1"), fk.param("t2")), (Some(10.0), Some(20.0)));
        let (_, notices) = restore("#/fk/simulation?t1=abc", ForwardKinematics::default());
        assert_eq!(notices.len(), 1);
        let (_, notices) = restore("#/ik/simulation?t1=10", ForwardKinematics::default());
        assert!(notices.len() >= 2, "another experiment's link: {notices:?}");
    }

    const IDS: &[&str] = &["fk", "ik"];

    #[test]
    fn parses_full_hash() {
        let r = parse("#/fk/simulation?t1=35&t2=60", IDS);
        assert!(r.notices.is_empty());
        assert_eq!(
            r.page,
            Page::Experiment {
                id: "fk".into(),
                tab: Tab::Simulation,
                params: vec![("t1".into(), "35".into()), ("t2".into(), "60".into())]
            }
        );
    }

    #[test]
    fn empty_and_root_are_home() {
        assert_eq!(parse("", IDS).page, Page::Home);
        assert_eq!(parse("#", IDS).page, Page::Home);
        assert_eq!(parse("#/", IDS).page, Page::Home);
    }

    #[test]
    fn malformed_hashes_fall_back_with_notices() {
        let r = parse("#/nope/theory", IDS);
        assert_eq!(r.page, Page::Home);
        assert_eq!(r.notices.len(), 1);
        let r = parse("#/fk/bogus?=3&x", IDS);
        assert!(matches!(r.page, Page::Experiment { tab: Tab::Aim, .. }));
        assert_eq!(r.notices.len(), 3);
        let r = parse("#/%E2%28%A1/%zz", IDS);
        assert_eq!(r.page, Page::Home);
    }

    /// Regression: a 100 KB hash produced 17,524 notices joined into one bar.
    #[test]
    fn notice_flood_is_summarised() {
        let mut hash = String::from("#/fk/simulation?");
        while hash.len() < 100_000 {
            hash.push_str("x&=1&");
        }
        let r = parse(&hash, IDS);
        assert!(r.notices.len() > 10_000);
        let shown = summarize_notices(&r.notices, NOTICE_LIMIT);
        assert_eq!(shown.len(), NOTICE_LIMIT + 1);
        assert_eq!(shown[..NOTICE_LIMIT], r.notices[..NOTICE_LIMIT]);
        let rest = r.notices.len() - NOTICE_LIMIT;
        assert_eq!(
            shown[NOTICE_LIMIT],
            format!("… and {rest} more problems with the link.")
        );
        assert!(shown.iter().map(String::len).sum::<usize>() < 400);
        // Few notices pass through unchanged.
        let two = vec!["a".to_owned(), "b".to_owned()];
        assert_eq!(summarize_notices(&two, NOTICE_LIMIT), two);
        let four: Vec<String> = (0..4).map(|i| i.to_string()).collect();
        assert_eq!(
            summarize_notices(&four, 3)[3],
            "… and 1 more problem with the link."
        );
    }

    #[test]
    fn quiz_seed_comes_from_the_link() {
        let r = parse("#/ik/quiz?quiz=123", IDS);
        assert_eq!(r.quiz_seed, Some(123));
        assert!(r.notices.is_empty());
        assert_eq!(
            r.page,
            Page::Experiment {
                id: "ik".into(),
                tab: Tab::Quiz,
                params: vec![]
            }
        );
        let r = parse("#/ik/simulation?l1=1&quiz=7&l2=0.5", IDS);
        assert_eq!(r.quiz_seed, Some(7));
        assert!(matches!(&r.page, Page::Experiment { params, .. } if params.len() == 2));
        let r = parse("#/ik/quiz?quiz=-3", IDS);
        assert_eq!(r.quiz_seed, None);
        assert_eq!(r.notices.len(), 1);
        let exp = crate::experiments::fk::ForwardKinematics::default();
        let hash = format_with_quiz(&exp, Tab::Quiz, Some(42));
        assert!(hash.starts_with("#/fk/quiz?t1=35&") && hash.ends_with("&quiz=42"));
        assert_eq!(parse(&hash, IDS).quiz_seed, Some(42));
    }

    #[test]
    fn instructor_keys_leave_the_parameters_and_round_trip() {
        use crate::experiments::fk::ForwardKinematics;
        let r = parse(
            "#/fk/simulation?t1=10&lock=t1,l2&hide=l1&note=Find+the+reach%3A+%3Cb%3Ebold%3C%2Fb%3E&quiz=5",
            IDS,
        );
        assert!(r.notices.is_empty(), "{:?}", r.notices);
        assert_eq!(r.quiz_seed, Some(5));
        assert_eq!(r.instructor.locked, vec!["t1", "l2"]);
        assert_eq!(r.instructor.hidden, vec!["l1"]);
        // Kept as the text written: the page shows it as text, never as HTML.
        assert_eq!(
            r.instructor.note.as_deref(),
            Some("Find the reach: <b>bold</b>")
        );
        assert!(matches!(&r.page, Page::Experiment { params, .. } if params.len() == 1));
        let mut exp = ForwardKinematics::default();
        exp.set_param("t1", 10.0).unwrap();
        let link = format_instructor(&exp, Tab::Simulation, &r.instructor, r.quiz_seed);
        assert!(
            link.ends_with(
                "&lock=t1,l2&hide=l1&note=Find%20the%20reach%3A%20%3Cb%3Ebold%3C%2Fb%3E&quiz=5"
            ),
            "{link}"
        );
        let (back, instructor, notices) = restore_instructor(&link, ForwardKinematics::default());
        assert!(notices.is_empty(), "{notices:?}");
        assert_eq!(instructor, r.instructor);
        assert_eq!(back.param("t1"), Some(10.0));
    }

    /// Issue 24 §2: `attempts=` and `score=` in an instructor's link.
    #[test]
    fn attempts_and_score_rule_come_from_the_link_and_round_trip() {
        use crate::experiments::fk::ForwardKinematics;
        let r = parse("#/fk/quiz?attempts=2&score=last&quiz=9", IDS);
        assert!(r.notices.is_empty(), "{:?}", r.notices);
        let rules = QuizRules {
            attempts: Some(2),
            score: ScoreRule::Last,
        };
        assert_eq!(r.instructor.quiz, rules);
        assert!(!r.instructor.is_empty());
        assert!(matches!(&r.page, Page::Experiment { params, .. } if params.is_empty()));
        let link = format_instructor(
            &ForwardKinematics::default(),
            Tab::Quiz,
            &r.instructor,
            r.quiz_seed,
        );
        assert!(link.ends_with("&attempts=2&score=last&quiz=9"), "{link}");
        assert_eq!(parse(&link, IDS).instructor, r.instructor);
        // The defaults: any number of attempts, the best counts; left out of links.
        let r = parse("#/fk/quiz?attempts=unlimited&score=best", IDS);
        assert!(r.notices.is_empty());
        assert_eq!(r.instructor.quiz, QuizRules::default());
        assert!(r.instructor.is_empty() && r.instructor.query().is_empty());
        assert_eq!(QuizRules::default().score, ScoreRule::Best);
        // Bad values keep the default, with a notice each.
        let r = parse("#/fk/quiz?attempts=0&score=median", IDS);
        assert_eq!(r.instructor.quiz, QuizRules::default());
        assert_eq!(
            r.notices,
            vec![
                "Ignored “attempts=0”: attempts takes a whole number from 1 or unlimited, score takes best, last or first."
                    .to_owned(),
                "Ignored “score=median”: attempts takes a whole number from 1 or unlimited, score takes best, last or first."
                    .to_owned(),
            ]
        );
        assert_eq!(parse("#/fk/quiz?attempts=-1", IDS).notices.len(), 1);
        assert_eq!(parse("#/fk/quiz?attempts=2.5", IDS).notices.len(), 1);
    }

    /// Issue 24 §2: with attempts=2 a third attempt is not graded; best
    /// keeps the higher of 8 → 17 → 8, last and first do as named.
    #[test]
    fn attempts_limit_and_score_rules_fold_as_named() {
        let two = QuizRules {
            attempts: Some(2),
            ..QuizRules::default()
        };
        assert!(two.allows(0) && two.allows(1) && !two.allows(2) && !two.allows(3));
        assert!(QuizRules::default().allows(u32::MAX - 1));
        let run = |rule: ScoreRule| {
            [8, 17, 8]
                .into_iter()
                .scan(None, |counted, p| {
                    *counted = Some(rule.fold(*counted, p));
                    *counted
                })
                .collect::<Vec<_>>()
        };
        assert_eq!(run(ScoreRule::Best), [8, 17, 17]);
        assert_eq!(run(ScoreRule::Last), [8, 17, 8]);
        assert_eq!(run(ScoreRule::First), [8, 8, 8]);
        for rule in ScoreRule::ALL {
            assert_eq!(ScoreRule::from_slug(rule.slug()), Some(rule));
        }
    }

    /// Issue 51 §4, hidden means hidden: a hidden value leaves the link's
    /// plain pairs for one veiled `hv=…` in its place, and comes back
    /// exactly.
    #[test]
    fn hidden_means_hidden_in_the_link_and_the_value_round_trips_exactly() {
        use crate::experiments::fk::ForwardKinematics;
        let mut exp = ForwardKinematics::default();
        exp.set_param("l1", 0.723_456_789).unwrap();
        let r = parse("#/fk/simulation?hide=l1,t2", IDS);
        let link = format_instructor(&exp, Tab::Simulation, &r.instructor, Some(4));
        assert!(link.starts_with("#/fk/simulation?t1=35&hv="), "{link}");
        assert!(!link.contains("l1=") && !link.contains("t2=") && !link.contains("723"));
        assert!(link.ends_with("&l2=0.7&hide=l1,t2&quiz=4"), "{link}");
        let (back, instructor, notices) = restore_instructor(&link, ForwardKinematics::default());
        assert!(notices.is_empty(), "{notices:?}");
        assert_eq!(back.param("l1"), Some(0.723_456_789));
        assert_eq!(instructor, r.instructor);
        assert_eq!(
            format_instructor(&back, Tab::Simulation, &instructor, Some(4)),
            link
        );
        // The pairs keep their place: the veil stands where the first was.
        let Page::Experiment { params, .. } = parse(&link, IDS).page else {
            panic!("{link}");
        };
        let keys: Vec<&str> = params.iter().map(|(k, _)| k.as_str()).collect();
        assert_eq!(keys, ["t1", "t2", "l1", "l2"]);
        // Any text comes back; the blob is plain URL text.
        assert_eq!(veil("m=2.5"), "374AA69FFB");
        let mut rng = crate::Lcg64::new(51);
        for n in 0..300 {
            let text: String = (0..n % 40)
                .map(|_| char::from_u32(rng.int(32, 0x3000) as u32).unwrap_or('x'))
                .collect();
            let blob = veil(&text);
            assert!(blob.bytes().all(|b| hex_digit(b).is_some()), "{blob}");
            assert_eq!(unveil(&blob).as_deref(), Some(text.as_str()));
        }
        // A damaged veil: a notice, and the values keep their defaults.
        let (back, notices) = restore("#/fk/simulation?hv=3G&t1=3", ForwardKinematics::default());
        assert_eq!(
            notices,
            ["The link's hidden settings are damaged; they keep their defaults."]
        );
        assert_eq!((back.param("t1"), back.param("l1")), (Some(3.0), Some(1.0)));
    }

    /// Issue 51 §4: an instructor's link holds for the whole visit.
    #[test]
    fn an_instructors_link_holds_for_the_visit_until_another() {
        let kept = "#/ik/simulation?l1=1.2&l2=0.5&lock=l1,l2&note=Hi&quiz=7";
        let pairs = |r: &Route| match &r.page {
            Page::Experiment { params, .. } => params.clone(),
            Page::Home => Vec::new(),
        };
        let owned = |v: &[(&str, &str)]| -> Vec<(String, String)> {
            v.iter().map(|(k, v)| ((*k).into(), (*v).into())).collect()
        };
        // The menu's link, in a page mounted afresh: the kept state and settings.
        let mut r = parse("#/ik/aim", IDS);
        assert!(!r.carries_instructor());
        assert_eq!(r.keep_instructor(kept, true), Some(Some(7)));
        assert_eq!(pairs(&r), owned(&[("l1", "1.2"), ("l2", "0.5")]));
        assert_eq!(r.instructor.locked, ["l1", "l2"]);
        assert_eq!(
            (r.instructor.note.as_deref(), r.quiz_seed),
            (Some("Hi"), Some(7))
        );
        // A tab of the page that shows it: nothing to do.
        let mut r = parse("#/ik/theory", IDS);
        assert_eq!(r.keep_instructor(kept, false), None);
        assert!(pairs(&r).is_empty() && r.instructor.is_empty());
        // A preset: its own state, under the instructor's settings.
        let mut r = parse("#/ik/simulation?l1=0.3&tx=0.4", IDS);
        assert_eq!(r.keep_instructor(kept, false), Some(Some(7)));
        assert_eq!(pairs(&r), owned(&[("l1", "0.3"), ("tx", "0.4")]));
        assert_eq!(r.instructor.locked, ["l1", "l2"]);
        // Another instructor's link is its own (the page keeps it instead).
        for link in [
            "#/ik/simulation?hide=l2",
            "#/ik/aim?quiz=5",
            "#/ik/quiz?note=x",
        ] {
            let mut r = parse(link, IDS);
            assert!(r.carries_instructor(), "{link}");
            assert_eq!(r.keep_instructor(kept, true), None);
        }
        // The Self-assessment tab's own link keeps its attempt's seed.
        let mut r = parse("#/ik/quiz?attempts=2&quiz=99", IDS);
        assert!(!r.carries_instructor());
        assert_eq!(r.keep_instructor(kept, true), Some(Some(7)));
        assert_eq!(r.quiz_seed, Some(99));
    }

    #[test]
    fn unknown_locks_and_hides_are_ignored_with_a_notice() {
        use crate::experiments::fk::ForwardKinematics;
        let (_, instructor, notices) = restore_instructor(
            "#/fk/simulation?lock=t1,kp,t1,,%20l1%20&hide=zz",
            ForwardKinematics::default(),
        );
        assert_eq!(
            instructor.locked,
            vec!["t1", "l1"],
            "repeats and blanks dropped"
        );
        assert!(instructor.hidden.is_empty());
        assert_eq!(
            notices,
            vec![
                "Cannot lock “kp”: this experiment has no such setting; ignored.".to_owned(),
                "Cannot hide “zz”: this experiment has no such setting; ignored.".to_owned(),
            ]
        );
    }

    #[test]
    fn notes_are_plain_short_text() {
        assert_eq!(clean_note("  a\nb\tc\u{0}  "), (Some("a b c".into()), None));
        assert_eq!(clean_note(" \n "), (None, None));
        let long = "é".repeat(NOTE_MAX_CHARS + 50);
        let (note, notice) = clean_note(&long);
        assert_eq!(note.unwrap().chars().count(), NOTE_MAX_CHARS);
        assert!(notice.unwrap().contains("shortened"));
        let r = parse(&format!("#/fk/simulation?note={}", encode(&long)), IDS);
        assert_eq!(r.notices.len(), 1);
        assert_eq!(r.instructor.note.unwrap().chars().count(), NOTE_MAX_CHARS);
        // An empty note is no note, and the link leaves it out.
        let r = parse("#/fk/simulation?note=", IDS);
        assert!(r.instructor.is_empty() && r.notices.is_empty());
        assert!(r.instructor.query().is_empty());
    }

    #[test]
    fn keep_locked_puts_back_what_an_input_changed() {
        use crate::experiments::fk::ForwardKinematics;
        use glam::DVec2;
        let mut exp = ForwardKinematics::default();
        let instructor = Instructor {
            locked: vec!["t1".into()],
            ..Instructor::default()
        };
        // Dragging the tip turns both joints; θ₁ is locked, so only θ₂ moves.
        let put_back = keep_locked(&mut exp, &instructor, |e| {
            e.input(crate::Input::PointerDown(DVec2::new(0.2, 1.2)));
            e.input(crate::Input::PointerMove {
                pos: DVec2::new(-0.5, 1.0),
                pressed: true,
            });
        });
        assert_eq!(put_back, vec!["θ₁"]);
        assert_eq!(exp.param("t1"), Some(35.0));
        assert_ne!(exp.param("t2"), Some(60.0), "the free joint followed");
        // Nothing locked: nothing put back.
        let put_back = keep_locked(&mut exp, &Instructor::default(), |e| {
            let _ = e.set_param("t1", 0.0);
        });
        assert!(put_back.is_empty());
        assert_eq!(exp.param("t1"), Some(0.0));
    }

    #[test]
    fn decodes_percent_escapes() {
        assert_eq!(decode("a%20b"), "a b");
        assert_eq!(decode("%zz"), "%zz");
        assert_eq!(decode("100%"), "100%");
        assert_eq!(decode("%4"), "%4");
    }

    /// Regression: a leading `+` passed the hex parse (`u8::from_str_radix`
    /// accepts a sign), so `%+31` decoded to the control character U+0003.
    #[test]
    fn invalid_percent_escapes_stay_verbatim() {
        assert_eq!(decode("%+31"), "%+31");
        assert_eq!(decode("%+1"), "%+1");
        assert_eq!(decode("%-1x"), "%-1x");
        assert_eq!(decode("%1g"), "%1g");
        assert_eq!(decode("%41%2b+x"), "A+ x");
        for s in ["%+31", "%+0", "%+a%+f", "%-0"] {
            assert!(!decode(s).chars().any(char::is_control), "{s}");
        }
    }

    /// A minimal experiment with one numeric parameter that must fit the
    /// text-valued "grid" (its width), to test [`Experiment::extra_state`].
    struct Texty {
        width: usize,
        x: f64,
    }

    impl Experiment for Texty {
        fn id(&self) -> &'static str {
            "fk"
        }
        fn params(&self) -> &'static [crate::ParamSpec] {
            const P: &[crate::ParamSpec] = &[crate::ParamSpec::number("x", "X", 0.0, 100.0, 0.0)];
            P
        }
        fn param(&self, key: &str) -> Option<f64> {
            (key == "x").then_some(self.x)
        }
        fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
            let applied = crate::experiment::check_param(self.params(), key, value)?;
            // Clamped to the grid the text state describes.
            let limit = (self.width - 1) as f64;
            if applied.value() > limit {
                self.x = limit;
                return Ok(Sanitized::Clamped(limit));
            }
            self.x = applied.value();
            Ok(applied)
        }
        fn extra_state(&self) -> Vec<(&'static str, String)> {
            vec![("grid", format!("{}x1 é&", self.width))]
        }
        fn set_extra_state(&mut self, key: &str, value: &str) -> Result<(), ParamError> {
            if key != "grid" {
                return Err(ParamError::UnknownKey { key: key.into() });
            }
            let bad = || ParamError::BadText {
                key: key.into(),
                reason: "not a grid".into(),
            };
            let w = value.split_once('x').ok_or_else(bad)?.0;
            self.width = w.parse().ok().filter(|w| *w > 0).ok_or_else(bad)?;
            Ok(())
        }
        fn input(&mut self, _input: crate::Input) {}
        fn step(&mut self, _dt_s: f64) {}
    }

    impl crate::experiment::Presentation for Texty {
        fn view(&self) -> crate::ViewBox {
            crate::ViewBox::centered(1.0)
        }
        fn scene(&self, _out: &mut crate::Scene) {}
        fn readouts(&self) -> Vec<crate::Readout> {
            Vec::new()
        }
        fn status(&self) -> crate::Status {
            crate::Status::new("", crate::experiment::Tone::Neutral)
        }
        fn hint(&self) -> &'static str {
            ""
        }
    }

    #[test]
    fn text_state_round_trips_and_is_applied_before_numbers() {
        let exp = Texty { width: 50, x: 42.0 };
        let link = format(&exp, Tab::Simulation);
        assert_eq!(link, "#/fk/simulation?x=42&grid=50x1%20%C3%A9%26");
        let Page::Experiment { params, .. } = parse(&link, IDS).page else {
            panic!("{link}");
        };
        assert_eq!(params[1], ("grid".to_owned(), "50x1 é&".to_owned()));
        // x=42 only fits once the 50-wide grid is applied, though it comes first.
        let mut fresh = Texty { width: 10, x: 0.0 };
        assert!(apply_params(&mut fresh, &params).is_empty());
        assert_eq!((fresh.width, fresh.x), (50, 42.0));
        assert_eq!(format(&fresh, Tab::Simulation), link);
        // A bad text value keeps the state and says why; notices stay in link order.
        let raw = |pairs: &[(&str, &str)]| -> Vec<(String, String)> {
            pairs
                .iter()
                .map(|(k, v)| ((*k).into(), (*v).into()))
                .collect()
        };
        let notices = apply_params(
            &mut fresh,
            &raw(&[("x", "nope"), ("grid", "zz"), ("what", "1")]),
        );
        assert_eq!(
            notices,
            vec![
                "X: “nope” is not a number; kept the current value.".to_owned(),
                "grid: not a grid; kept the current value.".to_owned(),
                "Unknown setting “what” ignored.".to_owned(),
            ]
        );
        assert_eq!((fresh.width, fresh.x), (50, 42.0));
        assert_eq!(encode("a-b.c_d~e09AZ"), "a-b.c_d~e09AZ");
        assert_eq!(decode(&encode("x y/z%")), "x y/z%");
    }
}
