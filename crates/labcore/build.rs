//! Reads every content file `assets/<id>.json` once, at build time, and writes
//! it as Rust into `$OUT_DIR/content.rs`: one function per experiment this
//! build holds that builds its [`Content`](src/content.rs) from string
//! literals, and `compiled(id)`, which [`crate::Entry::content`] calls. So no
//! content is parsed at run time, in the browser or natively.
//!
//! Which experiments a build holds: every one that has a content file, or,
//! when the environment variable `LAB_EXPERIMENTS` is set (`cargo xtask
//! dist` sets it for each wasm module), the ids it lists, comma-separated.
//! For each, this script sets `cfg(lab_experiment = "<id>")`, which the
//! registry (`src/experiments/mod.rs`) reads; so adding an experiment needs
//! no cargo feature of its own.
//!
//! Without the `reading` feature (the shipped wasm modules, whose reading
//! tabs are pages of their own) the reading sections (theory, procedure,
//! references) come out empty: only the id, number, title, summary, aim (the
//! lab report quotes it) and quiz are compiled in.
//!
//! Every text field's formulas (LaTeX between dollars) are written as MathML
//! here, by [`labtex::render`], so the compiled strings (the quiz text the
//! wasm modules show and the reading pages alike) hold MathML and no module
//! carries a converter. A formula that does not convert stops the build with
//! the file, the field's JSON path and the position in the formula.
//!
//! serde_json is a build-dependency only: nothing of it reaches the crate.
//! The fields are read as strictly as `Content::from_json` reads them (no
//! field missing, none unknown, each of its type); a file that fails is
//! compiled in as its error, which `Entry::content` returns.

use serde_json::{Map, Value};

#[path = "src/step_numbers.rs"]
#[allow(dead_code)]
mod step_numbers;
use std::fmt::Write as _;
use std::path::Path;

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    println!("cargo:rerun-if-changed={}", assets.display());
    println!("cargo::rerun-if-env-changed={SELECTION_VAR}");
    let reading = std::env::var_os("CARGO_FEATURE_READING").is_some();
    let mut files: Vec<_> = std::fs::read_dir(&assets)
        .map(|dir| dir.filter_map(Result::ok).map(|e| e.path()).collect())
        .unwrap_or_default();
    files.retain(|p| p.extension().is_some_and(|e| e == "json"));
    files.sort();
    let ids: Vec<String> = files
        .iter()
        .filter_map(|p| p.file_stem().and_then(|s| s.to_str()))
        .filter(|id| is_identifier(id))
        .map(str::to_owned)
        .collect();
    let selection = std::env::var(SELECTION_VAR).ok();
    let held = held_experiments(&ids, selection.as_deref());
    let values: Vec<String> = ids.iter().map(|id| format!("{id:?}")).collect();
    println!(
        "cargo::rustc-check-cfg=cfg(lab_experiment, values({}))",
        values.join(", ")
    );
    for id in &held {
        println!("cargo::rustc-cfg=lab_experiment={id:?}");
    }
    let mut arms = String::new();
    let mut bodies = String::new();
    for path in files {
        let Some(id) = path.file_stem().and_then(|s| s.to_str()) else {
            continue;
        };
        println!("cargo:rerun-if-changed={}", path.display());
        // An experiment left out of this build leaves its content out too.
        if !held.iter().any(|h| h == id) {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        let body = serde_json::from_str::<Value>(&text)
            .map_err(|e| e.to_string())
            .and_then(|mut v| {
                if let Err(e) = render_formulas(&mut v, String::new()) {
                    eprintln!("error: assets/{id}.json: {e}");
                    std::process::exit(1);
                }
                content(&v, reading)
            })
            .unwrap_or_else(|e| {
                format!(
                    "Err(ContentError::Parse(String::from({:?})))",
                    format!("assets/{id}.json: {e}")
                )
            });
        writeln!(arms, "        {id:?} => Some(content_{id}()),").unwrap();
        writeln!(
            bodies,
            "\nfn content_{id}() -> Result<Content, ContentError> {{\n    {body}\n}}"
        )
        .unwrap();
    }
    let code = format!(
        "// Written by build.rs from assets/*.json; do not edit.\n\n\
         /// The content file of experiment `id` as compiled into this build, or\n\
         /// `None` when the build does not hold that experiment.\n\
         pub(crate) fn compiled(id: &str) -> Option<Result<Content, ContentError>> {{\n    \
         match id {{\n{arms}        _ => None,\n    }}\n}}\n{bodies}"
    );
    std::fs::write(Path::new(&out).join("content.rs"), code).expect("OUT_DIR is writable");
}

/// The environment variable that narrows a build to some experiments.
const SELECTION_VAR: &str = "LAB_EXPERIMENTS";

/// The experiments a build holds: those of `ids` (every content file's) that
/// `selection` lists, or all of them when there is no selection. An id the
/// selection names without a content file stops the build, so a typo in
/// `cargo xtask dist` cannot ship an empty module.
fn held_experiments(ids: &[String], selection: Option<&str>) -> Vec<String> {
    let Some(selection) = selection else {
        return ids.to_vec();
    };
    let wanted: Vec<&str> = selection
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .collect();
    for id in &wanted {
        assert!(
            ids.iter().any(|known| known == id),
            "{SELECTION_VAR} names {id:?}, which has no content file assets/{id}.json"
        );
    }
    ids.iter()
        .filter(|id| wanted.contains(&id.as_str()))
        .cloned()
        .collect()
}

/// Every string in `value` with its formulas written as MathML
/// ([`labtex::render`]); an error names the string's JSON path
/// (`theory[2].formula`), `path` being `value`'s own.
fn render_formulas(value: &mut Value, path: String) -> Result<(), String> {
    match value {
        Value::String(s) => *s = labtex::render_field(&path, s)?,
        Value::Array(items) => {
            for (i, item) in items.iter_mut().enumerate() {
                render_formulas(item, format!("{path}[{i}]"))?;
            }
        }
        Value::Object(map) => {
            for (key, item) in map.iter_mut() {
                let inner = if path.is_empty() {
                    key.clone()
                } else {
                    format!("{path}.{key}")
                };
                render_formulas(item, inner)?;
            }
        }
        Value::Null | Value::Bool(_) | Value::Number(_) => {}
    }
    Ok(())
}

/// The id names a Rust function (`content_<id>`).
fn is_identifier(id: &str) -> bool {
    !id.is_empty() && id.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The fields of one JSON object, taken by name; any left over is an error.
struct Fields<'a> {
    map: &'a Map<String, Value>,
    taken: Vec<&'a str>,
    place: String,
}

impl<'a> Fields<'a> {
    fn of(value: &'a Value, place: String) -> Result<Self, String> {
        match value {
            Value::Object(map) => Ok(Fields {
                map,
                taken: Vec::new(),
                place,
            }),
            _ => Err(format!("{place}: expected an object")),
        }
    }

    fn optional(&mut self, name: &'a str) -> Option<&'a Value> {
        self.taken.push(name);
        self.map.get(name)
    }

    fn required(&mut self, name: &'a str) -> Result<&'a Value, String> {
        self.optional(name)
            .ok_or_else(|| format!("{}: missing field `{name}`", self.place))
    }

    fn wrong(&self, name: &str, wanted: &str) -> String {
        format!("{}: field `{name}` should be {wanted}", self.place)
    }

    /// A string, as a Rust expression of type `String`.
    fn string(&mut self, name: &'a str) -> Result<String, String> {
        match self.required(name)? {
            Value::String(s) => Ok(string(s)),
            _ => Err(self.wrong(name, "a string")),
        }
    }

    /// An optional string (absent or `null` is `None`), as `Option<String>`.
    fn opt_string(&mut self, name: &'a str) -> Result<String, String> {
        match self.optional(name) {
            None | Some(Value::Null) => Ok("None".into()),
            Some(Value::String(s)) => Ok(format!("Some({})", string(s))),
            Some(_) => Err(self.wrong(name, "a string")),
        }
    }

    /// A number, as an `f64` literal that reads back to the same value.
    fn number(&mut self, name: &'a str) -> Result<String, String> {
        match self.required(name)?.as_f64() {
            Some(x) if x.is_finite() => Ok(format!("{x:?}")),
            _ => Err(self.wrong(name, "a number")),
        }
    }

    /// A non-negative whole number that fits in `u32`.
    fn count(&mut self, name: &'a str) -> Result<String, String> {
        let v = self.required(name)?;
        self.as_count(name, v)
    }

    fn opt_count(&mut self, name: &'a str) -> Result<String, String> {
        match self.optional(name) {
            None | Some(Value::Null) => Ok("None".into()),
            Some(v) => Ok(format!("Some({})", self.as_count(name, v)?)),
        }
    }

    fn as_count(&self, name: &str, v: &Value) -> Result<String, String> {
        match v.as_f64() {
            Some(n) if n.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&n) => {
                Ok(format!("{}", n as u32))
            }
            _ => Err(self.wrong(name, "a whole number")),
        }
    }

    /// An optional boolean, `false` when absent.
    fn flag(&mut self, name: &'a str) -> Result<String, String> {
        match self.optional(name) {
            None => Ok("false".into()),
            Some(Value::Bool(b)) => Ok(b.to_string()),
            Some(_) => Err(self.wrong(name, "a boolean")),
        }
    }

    fn array(&mut self, name: &'a str) -> Result<&'a [Value], String> {
        match self.required(name)? {
            Value::Array(items) => Ok(items),
            _ => Err(self.wrong(name, "an array")),
        }
    }

    /// An array of strings, as a `Vec<String>` expression.
    fn strings(&mut self, name: &'a str) -> Result<String, String> {
        let items = self.array(name)?;
        let mut parts = Vec::new();
        for item in items {
            match item {
                Value::String(s) => parts.push(format!("{s:?}")),
                _ => return Err(self.wrong(name, "an array of strings")),
            }
        }
        Ok(format!("strings(&[{}])", parts.join(", ")))
    }

    fn done(self) -> Result<(), String> {
        match self.map.keys().find(|k| !self.taken.contains(&k.as_str())) {
            Some(k) => Err(format!("{}: unknown field `{k}`", self.place)),
            None => Ok(()),
        }
    }
}

/// A string literal turned into a `String`.
fn string(s: &str) -> String {
    format!("String::from({s:?})")
}

/// The whole file as an `Ok(Content { … })` expression.
fn content(value: &Value, reading: bool) -> Result<String, String> {
    let mut f = Fields::of(value, "content".into())?;
    let id = f.string("id")?;
    let number = f.count("number")?;
    let title = f.string("title")?;
    let summary = f.string("summary")?;
    let aim = f.strings("aim")?;
    let theory = list(f.array("theory")?, block)?;
    let file = value.get("id").and_then(Value::as_str).unwrap_or("?");
    let procedure = procedure(f.array("procedure")?, file)?;
    if let Some(claims) = f.optional("claims") {
        check_claims(claims, file)?;
    }
    let quiz = list(f.array("quiz")?, question)?;
    let references = list(f.array("references")?, reference)?;
    let math = f.strings("math")?;
    f.done()?;
    // Without the reading content (shipped modules), the page's own HTML
    // holds these tabs; the lab report reads the aim from the page.
    let (aim, theory, procedure, references) = if reading {
        (aim, theory, procedure, references)
    } else {
        (
            "Vec::new()".into(),
            "Vec::new()".into(),
            "Vec::new()".into(),
            "Vec::new()".into(),
        )
    };
    Ok(format!(
        "Ok(Content {{\n        id: {id},\n        number: {number},\n        title: {title},\n        \
         summary: {summary},\n        aim: {aim},\n        theory: {theory},\n        \
         procedure: {procedure},\n        quiz: {quiz},\n        references: {references},\n        \
         math: {math},\n    }})"
    ))
}

/// The steps' prose, as a `Vec<String>` expression. A step is an object:
/// its `text` (the prose the page shows), its `play` (the machine part the
/// Procedure runner plays, `crates/labcore/tests/procedures/`) and,
/// optionally, `given` (numbers of the theory the prose writes). Only the
/// text is compiled in; a number of the text that is none of the step's
/// values stops the build ([`step_numbers`]).
fn procedure(items: &[Value], id: &str) -> Result<String, String> {
    let mut parts = Vec::new();
    for (i, item) in items.iter().enumerate() {
        let place = format!("assets/{id}.json: procedure step {}", i + 1);
        let mut f = Fields::of(item, place.clone())?;
        let text = match f.required("text")? {
            Value::String(s) => s.clone(),
            _ => return Err(f.wrong("text", "a string")),
        };
        let (_, values) = play_and_given_values(f)?;
        if let Some(n) = step_numbers::stray_number(&text, &values) {
            // Like a formula that does not convert, this stops the build:
            // the prose and the machine part must say the same numbers.
            eprintln!(
                "error: {place}: the prose writes {n}, which is none of the step's values (its play, or `given`)"
            );
            std::process::exit(1);
        }
        parts.push(format!("{text:?}"));
    }
    Ok(format!("strings(&[{}])", parts.join(", ")))
}

/// The claims of the reading beyond the Procedure (`claims`: a sentence of
/// the theory, a caption, a hint or a status that says what this lab shows,
/// each `{quote, play, given}`): test-only like a step's `play`, so nothing
/// of them is compiled in. A number the quoted sentence writes that is none
/// of the claim's values stops the build, as a step's does; that the quote
/// is the text's own, word for word, the Procedure runner checks.
fn check_claims(value: &Value, id: &str) -> Result<(), String> {
    let Value::Array(items) = value else {
        return Err(format!("assets/{id}.json: `claims` should be an array"));
    };
    for (i, item) in items.iter().enumerate() {
        let place = format!("assets/{id}.json: claim {}", i + 1);
        let mut f = Fields::of(item, place.clone())?;
        let quote = match f.required("quote")? {
            Value::String(s) => s.clone(),
            _ => return Err(f.wrong("quote", "a string")),
        };
        let (play_items, values) = play_and_given_values(f)?;
        if play_items == 0 {
            return Err(format!("{place}: field `play` should be a non-empty array"));
        }
        if let Some(n) = step_numbers::stray_number(&quote, &values) {
            eprintln!(
                "error: {place}: the quoted sentence writes {n}, which is none of the claim's values (its play, or `given`)"
            );
            std::process::exit(1);
        }
    }
    Ok(())
}

/// Reads a step's or a claim's `play` and optional `given` (the last of
/// its fields) and returns how many items `play` has and every number of
/// both ([`step_values`]): the values its prose may write.
fn play_and_given_values(mut f: Fields) -> Result<(usize, Vec<f64>), String> {
    let play = f.array("play")?;
    let given = match f.optional("given") {
        None => &[][..],
        Some(Value::Array(items)) => items.as_slice(),
        Some(_) => return Err(f.wrong("given", "an array of numbers")),
    };
    f.done()?;
    let mut values = Vec::new();
    for v in play.iter().chain(given) {
        step_values(v, &mut values);
    }
    Ok((play.len(), values))
}

/// Every number of a step's machine part: its JSON numbers and the numbers
/// written in its strings (an option's label "20 × 15", a status text).
fn step_values(value: &Value, out: &mut Vec<f64>) {
    match value {
        Value::Number(n) => out.extend(n.as_f64()),
        Value::String(s) => out.extend(step_numbers::numbers_in(s).into_iter().map(|(_, n)| n)),
        Value::Array(items) => items.iter().for_each(|v| step_values(v, out)),
        Value::Object(map) => map.values().for_each(|v| step_values(v, out)),
        Value::Null | Value::Bool(_) => {}
    }
}

/// `vec![…]` of each item read by `read` (given the item and its index).
fn list(
    items: &[Value],
    read: fn(&Value, usize) -> Result<String, String>,
) -> Result<String, String> {
    let parts = items
        .iter()
        .enumerate()
        .map(|(i, v)| read(v, i))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(format!(
        "vec![\n            {}\n        ]",
        parts.join(",\n            ")
    ))
}

/// One theory block: one key (`heading`, `paragraph`, `formula`, `note`)
/// holding a string.
fn block(value: &Value, index: usize) -> Result<String, String> {
    let place = format!("theory block {}", index + 1);
    let Value::Object(map) = value else {
        return Err(format!("{place}: expected an object"));
    };
    let mut fields = map.iter();
    let (Some((kind, Value::String(text))), None) = (fields.next(), fields.next()) else {
        return Err(format!("{place}: expected one key holding a string"));
    };
    let variant = match kind.as_str() {
        "heading" => "Heading",
        "paragraph" => "Paragraph",
        "formula" => "Formula",
        "note" => "Note",
        other => {
            return Err(format!(
                "{place}: unknown variant `{other}`, expected heading, paragraph, formula or note"
            ))
        }
    };
    Ok(format!("Block::{variant}({})", string(text)))
}

/// One quiz question, tagged by its `kind`.
fn question(value: &Value, index: usize) -> Result<String, String> {
    let mut f = Fields::of(value, format!("question {}", index + 1))?;
    let kind = match f.required("kind")? {
        Value::String(s) => s.clone(),
        _ => return Err(f.wrong("kind", "a string")),
    };
    // What a numeric and a generated question share, after their own fields;
    // an absent or `null` unit is no unit.
    let measured = |f: &mut Fields| -> Result<String, String> {
        let tolerance = f.number("tolerance")?;
        let unit = match f.optional("unit") {
            None | Some(Value::Null) => "String::new()".into(),
            Some(Value::String(s)) => string(s),
            Some(_) => return Err(f.wrong("unit", "a string")),
        };
        Ok(format!(
            "tolerance: {tolerance}, unit: {unit}, angle_degrees: {}, explanation: {} }}",
            f.flag("angle_degrees")?,
            f.string("explanation")?
        ))
    };
    let code = match kind.as_str() {
        "choice" => format!(
            "Question::Choice {{ prompt: {}, options: {}, answer: {}, explanation: {} }}",
            f.string("prompt")?,
            f.strings("options")?,
            f.count("answer")?,
            f.string("explanation")?,
        ),
        "numeric" => {
            let (prompt, answer) = (f.string("prompt")?, f.number("answer")?);
            format!(
                "Question::Numeric {{ prompt: {prompt}, answer: {answer}, {}",
                measured(&mut f)?
            )
        }
        "generated" => {
            let (generator, prompt) = (f.string("generator")?, f.string("prompt")?);
            format!(
                "Question::Generated {{ generator: {generator}, prompt: {prompt}, {}",
                measured(&mut f)?
            )
        }
        other => {
            return Err(format!(
                "question {}: unknown kind `{other}`, expected choice, numeric or generated",
                index + 1
            ))
        }
    };
    f.done()?;
    Ok(code)
}

/// One bibliographic reference.
fn reference(value: &Value, index: usize) -> Result<String, String> {
    let mut f = Fields::of(value, format!("reference {}", index + 1))?;
    let code = format!(
        "Reference {{ authors: {}, title: {}, venue: {}, year: {}, detail: {}, doi: {}, url: {} }}",
        f.string("authors")?,
        f.string("title")?,
        f.string("venue")?,
        f.opt_count("year")?,
        f.opt_string("detail")?,
        f.opt_string("doi")?,
        f.opt_string("url")?,
    );
    f.done()?;
    Ok(code)
}
