//! A small, strict JSON reader and writer (RFC 8259) for the lab's own data:
//! in the wasm modules, the saved quiz attempt (local storage) and the
//! attempt an LMS keeps (`lms::Suspended`, SCORM `suspend_data`); natively
//! (the `reading` feature), content files being checked ([`Fields`]). The
//! content compiled into a build is read at build time instead (`build.rs`,
//! with serde_json as a build-dependency).
//!
//! Why not serde: serde's derived deserializers and `serde_json` were about
//! 90 KB of each wasm module (twiggy, Rust 1.95) for two small formats; this
//! file is a few KB. Errors give the line and column, as `serde_json` did.
//! Objects keep their keys in order; a repeated key is an error.

use std::fmt::Write as _;

/// A JSON value.
#[derive(Clone, Debug, PartialEq)]
pub enum Json {
    Null,
    Bool(bool),
    Number(f64),
    String(String),
    Array(Vec<Json>),
    Object(Vec<(String, Json)>),
}

/// Deepest nesting accepted (hostile input cannot overflow the stack).
const MAX_DEPTH: usize = 64;

impl Json {
    /// Parses one JSON text (surrounding whitespace allowed, nothing else).
    pub fn parse(text: &str) -> Result<Json, String> {
        let mut p = Parser {
            bytes: text.as_bytes(),
            at: 0,
        };
        p.space();
        let value = p.value(0)?;
        p.space();
        if p.at < p.bytes.len() {
            return Err(p.error("trailing characters"));
        }
        Ok(value)
    }

    /// What kind of value this is, for error messages.
    #[must_use]
    pub fn kind(&self) -> &'static str {
        match self {
            Json::Null => "null",
            Json::Bool(_) => "a boolean",
            Json::Number(_) => "a number",
            Json::String(_) => "a string",
            Json::Array(_) => "an array",
            Json::Object(_) => "an object",
        }
    }

    /// The compact text of this value (numbers in Rust's shortest round-trip
    /// form; integers without a fraction).
    #[must_use]
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        self.write(&mut out);
        out
    }

    fn write(&self, out: &mut String) {
        match self {
            Json::Null => out.push_str("null"),
            Json::Bool(b) => out.push_str(if *b { "true" } else { "false" }),
            Json::Number(n) if n.is_finite() => {
                let _ = write!(out, "{n}");
            }
            Json::Number(_) => out.push_str("null"),
            Json::String(s) => write_string(s, out),
            Json::Array(items) => {
                out.push('[');
                for (i, item) in items.iter().enumerate() {
                    if i > 0 {
                        out.push(',');
                    }
                    item.write(out);
                }
                out.push(']');
            }
            Json::Object(fields) => {
                out.push('{');
                for (i, (k, v)) in fields.iter().enumerate() {
                    if i > 0 {
                        out.push(',');
                    }
                    write_string(k, out);
                    out.push(':');
                    v.write(out);
                }
                out.push('}');
            }
        }
    }
}

fn write_string(s: &str, out: &mut String) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

struct Parser<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Parser<'_> {
    fn error(&self, what: &str) -> String {
        let before = &self.bytes[..self.at.min(self.bytes.len())];
        let line = before.iter().filter(|b| **b == b'\n').count() + 1;
        let line_start = before
            .iter()
            .rposition(|b| *b == b'\n')
            .map_or(0, |i| i + 1);
        let column = String::from_utf8_lossy(&before[line_start..])
            .chars()
            .count()
            + 1;
        format!("{what} at line {line} column {column}")
    }

    fn peek(&self) -> Option<u8> {
        self.bytes.get(self.at).copied()
    }

    fn space(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\n' | b'\r')) {
            self.at += 1;
        }
    }

    fn expect(&mut self, word: &str, value: Json) -> Result<Json, String> {
        if self.bytes[self.at..].starts_with(word.as_bytes()) {
            self.at += word.len();
            Ok(value)
        } else {
            Err(self.error("expected a value"))
        }
    }

    fn value(&mut self, depth: usize) -> Result<Json, String> {
        if depth > MAX_DEPTH {
            return Err(self.error("nested too deeply"));
        }
        match self.peek() {
            None => Err(self.error("EOF while parsing a value")),
            Some(b'n') => self.expect("null", Json::Null),
            Some(b't') => self.expect("true", Json::Bool(true)),
            Some(b'f') => self.expect("false", Json::Bool(false)),
            Some(b'"') => self.string().map(Json::String),
            Some(b'[') => {
                self.at += 1;
                let mut items = Vec::new();
                self.space();
                if self.peek() == Some(b']') {
                    self.at += 1;
                    return Ok(Json::Array(items));
                }
                loop {
                    self.space();
                    items.push(self.value(depth + 1)?);
                    self.space();
                    match self.peek() {
                        Some(b',') => self.at += 1,
                        Some(b']') => {
                            self.at += 1;
                            return Ok(Json::Array(items));
                        }
                        None => return Err(self.error("EOF while parsing a list")),
                        _ => return Err(self.error("expected `,` or `]`")),
                    }
                }
            }
            Some(b'{') => {
                self.at += 1;
                let mut fields: Vec<(String, Json)> = Vec::new();
                self.space();
                if self.peek() == Some(b'}') {
                    self.at += 1;
                    return Ok(Json::Object(fields));
                }
                loop {
                    self.space();
                    match self.peek() {
                        Some(b'"') => {}
                        None => return Err(self.error("EOF while parsing an object")),
                        _ => return Err(self.error("expected a key in quotes")),
                    }
                    let key_at = self.at;
                    let key = self.string()?;
                    if fields.iter().any(|(k, _)| *k == key) {
                        self.at = key_at;
                        return Err(self.error(&format!("duplicate field `{key}`")));
                    }
                    self.space();
                    if self.peek() != Some(b':') {
                        return Err(self.error("expected `:`"));
                    }
                    self.at += 1;
                    self.space();
                    let value = self.value(depth + 1)?;
                    fields.push((key, value));
                    self.space();
                    match self.peek() {
                        Some(b',') => self.at += 1,
                        Some(b'}') => {
                            self.at += 1;
                            return Ok(Json::Object(fields));
                        }
                        None => return Err(self.error("EOF while parsing an object")),
                        _ => return Err(self.error("expected `,` or `}`")),
                    }
                }
            }
            Some(b'-' | b'0'..=b'9') => self.number(),
            Some(_) => Err(self.error("expected a value")),
        }
    }

    fn number(&mut self) -> Result<Json, String> {
        let start = self.at;
        let digits = |p: &mut Self| {
            let from = p.at;
            while matches!(p.peek(), Some(b'0'..=b'9')) {
                p.at += 1;
            }
            p.at > from
        };
        if self.peek() == Some(b'-') {
            self.at += 1;
        }
        if self.peek() == Some(b'0') {
            self.at += 1;
        } else if !digits(self) {
            return Err(self.error("invalid number"));
        }
        if self.peek() == Some(b'.') {
            self.at += 1;
            if !digits(self) {
                return Err(self.error("invalid number"));
            }
        }
        if matches!(self.peek(), Some(b'e' | b'E')) {
            self.at += 1;
            if matches!(self.peek(), Some(b'+' | b'-')) {
                self.at += 1;
            }
            if !digits(self) {
                return Err(self.error("invalid number"));
            }
        }
        let text = std::str::from_utf8(&self.bytes[start..self.at]).unwrap_or("");
        match text.parse::<f64>() {
            Ok(n) if n.is_finite() => Ok(Json::Number(n)),
            _ => Err(self.error("number out of range")),
        }
    }

    fn hex4(&mut self) -> Result<u32, String> {
        let Some(hex) = self.bytes.get(self.at..self.at + 4) else {
            return Err(self.error("EOF while parsing a string"));
        };
        // Exactly four hex digits (RFC 8259 §7): `u32::from_str_radix` alone
        // would also take a sign, `\u+041`.
        let mut n = 0;
        for b in hex {
            let digit = char::from(*b)
                .to_digit(16)
                .ok_or_else(|| self.error("invalid escape"))?;
            n = n * 16 + digit;
        }
        self.at += 4;
        Ok(n)
    }

    fn string(&mut self) -> Result<String, String> {
        self.at += 1; // the opening quote
        let mut out = String::new();
        loop {
            let start = self.at;
            while !matches!(self.peek(), None | Some(b'"' | b'\\' | 0..=0x1f)) {
                self.at += 1;
            }
            // The input is a &str and the run stops at ASCII bytes: valid UTF-8.
            out.push_str(std::str::from_utf8(&self.bytes[start..self.at]).unwrap_or(""));
            match self.peek() {
                None => return Err(self.error("EOF while parsing a string")),
                Some(b'"') => {
                    self.at += 1;
                    return Ok(out);
                }
                Some(b'\\') => {
                    self.at += 1;
                    let c = match self.peek() {
                        Some(b'"') => '"',
                        Some(b'\\') => '\\',
                        Some(b'/') => '/',
                        Some(b'b') => '\u{8}',
                        Some(b'f') => '\u{c}',
                        Some(b'n') => '\n',
                        Some(b'r') => '\r',
                        Some(b't') => '\t',
                        Some(b'u') => {
                            self.at += 1;
                            let hi = self.hex4()?;
                            let code = if (0xd800..0xdc00).contains(&hi) {
                                if !self.bytes[self.at..].starts_with(b"\\u") {
                                    return Err(self.error("lone leading surrogate"));
                                }
                                self.at += 2;
                                let lo = self.hex4()?;
                                if !(0xdc00..0xe000).contains(&lo) {
                                    return Err(self.error("invalid surrogate pair"));
                                }
                                0x10000 + ((hi - 0xd800) << 10) + (lo - 0xdc00)
                            } else {
                                hi
                            };
                            let c =
                                char::from_u32(code).ok_or_else(|| self.error("invalid escape"))?;
                            out.push(c);
                            continue;
                        }
                        _ => return Err(self.error("invalid escape")),
                    };
                    self.at += 1;
                    out.push(c);
                }
                Some(_) => return Err(self.error("control character in a string")),
            }
        }
    }
}

/// Reads the fields of one JSON object by name and refuses any it was not
/// asked for, like serde's `deny_unknown_fields`.
pub struct Fields<'a> {
    fields: &'a [(String, Json)],
    taken: Vec<&'a str>,
    /// Where this object is ("question 3"), for error messages.
    place: String,
}

impl<'a> Fields<'a> {
    /// The object's fields, or an error naming `place` if `value` is no object.
    pub fn of(value: &'a Json, place: impl Into<String>) -> Result<Self, String> {
        let place = place.into();
        match value {
            Json::Object(fields) => Ok(Fields {
                fields,
                taken: Vec::new(),
                place,
            }),
            other => Err(format!(
                "{place}: expected an object, found {}",
                other.kind()
            )),
        }
    }

    /// The field `name`, if present.
    pub fn optional(&mut self, name: &'a str) -> Option<&'a Json> {
        self.taken.push(name);
        self.fields.iter().find(|(k, _)| k == name).map(|(_, v)| v)
    }

    /// The field `name`, or an error that names it.
    pub fn required(&mut self, name: &'a str) -> Result<&'a Json, String> {
        self.optional(name)
            .ok_or_else(|| format!("{}: missing field `{name}`", self.place))
    }

    pub fn string(&mut self, name: &'a str) -> Result<String, String> {
        let v = self.required(name)?;
        self.as_string(name, v)
    }

    /// An optional string; absent or `null` is `None`.
    pub fn opt_string(&mut self, name: &'a str) -> Result<Option<String>, String> {
        match self.optional(name) {
            None | Some(Json::Null) => Ok(None),
            Some(v) => self.as_string(name, v).map(Some),
        }
    }

    pub fn number(&mut self, name: &'a str) -> Result<f64, String> {
        match self.required(name)? {
            Json::Number(n) => Ok(*n),
            other => Err(self.wrong(name, "a number", other)),
        }
    }

    /// A non-negative integer that fits in `u32`.
    pub fn count(&mut self, name: &'a str) -> Result<u32, String> {
        let v = self.required(name)?;
        self.as_count(name, v)
    }

    /// An optional count; absent or `null` is `None`.
    pub fn opt_count(&mut self, name: &'a str) -> Result<Option<u32>, String> {
        match self.optional(name) {
            None | Some(Json::Null) => Ok(None),
            Some(v) => self.as_count(name, v).map(Some),
        }
    }

    /// An optional boolean, `false` when absent.
    pub fn flag(&mut self, name: &'a str) -> Result<bool, String> {
        match self.optional(name) {
            None => Ok(false),
            Some(Json::Bool(b)) => Ok(*b),
            Some(other) => Err(self.wrong(name, "a boolean", other)),
        }
    }

    pub fn array(&mut self, name: &'a str) -> Result<&'a [Json], String> {
        match self.required(name)? {
            Json::Array(items) => Ok(items),
            other => Err(self.wrong(name, "an array", other)),
        }
    }

    /// An array of strings.
    pub fn strings(&mut self, name: &'a str) -> Result<Vec<String>, String> {
        self.array(name)?
            .iter()
            .map(|v| self.as_string(name, v))
            .collect()
    }

    /// Fails on any field not asked for.
    pub fn done(self) -> Result<(), String> {
        match self
            .fields
            .iter()
            .find(|(k, _)| !self.taken.contains(&k.as_str()))
        {
            Some((k, _)) => Err(format!("{}: unknown field `{k}`", self.place)),
            None => Ok(()),
        }
    }

    fn as_string(&self, name: &str, v: &Json) -> Result<String, String> {
        match v {
            Json::String(s) => Ok(s.clone()),
            other => Err(self.wrong(name, "a string", other)),
        }
    }

    fn as_count(&self, name: &str, v: &Json) -> Result<u32, String> {
        match v {
            Json::Number(n) if n.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(n) => {
                Ok(*n as u32)
            }
            other => Err(self.wrong(name, "a whole number", other)),
        }
    }

    fn wrong(&self, name: &str, wanted: &str, found: &Json) -> String {
        format!(
            "{}: field `{name}` should be {wanted}, found {}",
            self.place,
            found.kind()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_every_kind_of_value() {
        let v = Json::parse(
            r#" {"a": [1, -2.5e2, 0.125, true, false, null], "b": "x\"\\\/\n\u00e9\ud83d\ude00"} "#,
        )
        .unwrap();
        assert_eq!(
            v,
            Json::Object(vec![
                (
                    "a".into(),
                    Json::Array(vec![
                        Json::Number(1.0),
                        Json::Number(-250.0),
                        Json::Number(0.125),
                        Json::Bool(true),
                        Json::Bool(false),
                        Json::Null
                    ])
                ),
                ("b".into(), Json::String("x\"\\/\né😀".into())),
            ])
        );
    }

    #[test]
    fn refuses_what_json_refuses_with_line_and_column() {
        for (bad, what) in [
            ("", "EOF while parsing a value"),
            ("[1,]", "expected a value"),
            ("{\"a\":1,}", "expected a key"),
            ("{\"a\" 1}", "expected `:`"),
            ("01", "trailing characters"),
            ("1.", "invalid number"),
            ("-", "invalid number"),
            ("\"a\tb\"", "control character"),
            ("\"\\x\"", "invalid escape"),
            ("\"\\ud800\"", "lone leading surrogate"),
            ("{\"a\":1,\"a\":2}", "duplicate field `a`"),
            ("[1 2]", "expected `,` or `]`"),
            ("\"abc", "EOF while parsing a string"),
            ("1e999", "number out of range"),
            ("nul", "expected a value"),
        ] {
            let e = Json::parse(bad).unwrap_err();
            assert!(
                e.contains(what) && e.contains("line 1 column"),
                "{bad:?}: {e}"
            );
        }
        let e = Json::parse("{\n  \"a\": [1,\n  2,,]\n}").unwrap_err();
        assert!(e.ends_with("line 3 column 5"), "{e}");
    }

    /// A short random text, biased toward what a JSON reader must judge
    /// carefully: escapes (`\u` with signs, hex digits of either case,
    /// surrogates), numbers (signs, leading zeros, fractions, exponents),
    /// literals, brackets and edge characters (controls, DEL, non-ASCII).
    fn random_text(rng: &mut crate::rng::Lcg64) -> String {
        const PIECES: &[&str] = &[
            "\"", "\"", "\"", "\\", "\\u", "\\u", "\\u", "\\u00", "\\ud83d", "\\ude00", "\\udc00",
            "\\ud800", "\\n", "\\/", "\\x", "+", "+", "-", "-", "0", "0", "1", "9", "00", "12",
            ".", ".5", "e", "E", "e+", "e-", "1e999", "1e-400", "a", "A", "f", "F", "g", "41",
            "0041", "{", "}", "[", "]", ":", ",", "true", "false", "null", "nul", " ", "\n", "\t",
            "\r", "\u{1}", "\u{1f}", "\u{7f}", "é", "😀", "\u{a0}", "\u{feff}", "{\"a\":", "[1,",
            "\"k\"",
        ];
        let n = rng.int(1, 8);
        let mut text = String::new();
        for _ in 0..n {
            text.push_str(PIECES[rng.int(0, PIECES.len() as i64 - 1) as usize]);
        }
        match rng.int(0, 3) {
            // A string around it, the most common home of an escape.
            0 => format!("\"{text}\""),
            // A value in an array.
            1 => format!("[{text}]"),
            _ => text,
        }
    }

    /// Our reader's value against serde_json's (numbers to the last bit or
    /// two: serde_json's fast float parser may round differently).
    fn same_value(ours: &Json, theirs: &serde_json::Value) -> bool {
        use serde_json::Value;
        match (ours, theirs) {
            (Json::Null, Value::Null) => true,
            (Json::Bool(a), Value::Bool(b)) => a == b,
            (Json::Number(a), Value::Number(b)) => b
                .as_f64()
                .is_some_and(|b| (a - b).abs() <= 1e-15 * a.abs().max(b.abs())),
            (Json::String(a), Value::String(b)) => a == b,
            (Json::Array(a), Value::Array(b)) => {
                a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same_value(x, y))
            }
            (Json::Object(a), Value::Object(b)) => {
                a.len() == b.len()
                    && a.iter()
                        .all(|(k, v)| b.get(k).is_some_and(|w| same_value(v, w)))
            }
            _ => false,
        }
    }

    /// Issue 23 §5: `"\u+041"` was read as "A". On many random short texts
    /// the reader accepts exactly what serde_json accepts, and reads the
    /// same value. The one difference by design: a repeated key, which
    /// serde_json keeps the last of and this reader refuses.
    #[test]
    fn hex4_and_the_whole_reader_accept_what_serde_json_accepts() {
        for bad in [
            "\"\\u+041\"",
            "\"\\u-041\"",
            "\"\\u 041\"",
            "\"\\ud83d\\u+e00\"",
        ] {
            assert!(Json::parse(bad).is_err(), "{bad}");
            assert!(
                serde_json::from_str::<serde_json::Value>(bad).is_err(),
                "{bad}"
            );
        }
        let mut rng = crate::rng::Lcg64::new(2023);
        let (mut accepted, mut escapes) = (0, 0);
        for _ in 0..200_000 {
            let text = random_text(&mut rng);
            let ours = Json::parse(&text);
            let theirs = serde_json::from_str::<serde_json::Value>(&text);
            match (&ours, &theirs) {
                (Ok(a), Ok(b)) => {
                    assert!(same_value(a, b), "{text:?}: {a:?} vs {b}");
                    accepted += 1;
                    escapes += usize::from(text.contains("\\u"));
                }
                (Err(e), Ok(_)) if e.contains("duplicate field") => {}
                _ => assert_eq!(
                    ours.is_ok(),
                    theirs.is_ok(),
                    "{text:?}: {ours:?} vs {theirs:?}"
                ),
            }
        }
        // The generator reaches both sides, \u escapes among the accepted.
        assert!(
            accepted > 5_000 && escapes > 100,
            "{accepted} accepted, {escapes} with \\u"
        );
    }

    #[test]
    fn deep_nesting_is_refused_not_a_stack_overflow() {
        let deep = "[".repeat(10_000);
        assert!(Json::parse(&deep)
            .unwrap_err()
            .contains("nested too deeply"));
    }

    #[test]
    fn text_round_trips() {
        let text = r#"{"seed":42,"answers":[{"Choice":1},{"Choice":null},{"Text":"3.5 \"m\"\n\u0001é"}],"x":-0.1}"#;
        let v = Json::parse(text).unwrap();
        assert_eq!(Json::parse(&v.to_text()).unwrap(), v);
        assert_eq!(
            Json::parse(r#"{"a":[1,2.5,"\u0007"]}"#).unwrap().to_text(),
            r#"{"a":[1,2.5,"\u0007"]}"#
        );
    }

    #[test]
    fn fields_refuse_unknown_missing_and_mistyped_fields() {
        let v =
            Json::parse(r#"{"name":"a","n":3,"flag":true,"list":["x","y"],"extra":1}"#).unwrap();
        let mut f = Fields::of(&v, "thing 1").unwrap();
        assert_eq!(f.string("name").unwrap(), "a");
        assert_eq!(f.count("n").unwrap(), 3);
        assert!(f.flag("flag").unwrap());
        assert!(!f.flag("absent").unwrap());
        assert_eq!(f.strings("list").unwrap(), ["x", "y"]);
        assert_eq!(f.opt_string("none").unwrap(), None);
        assert_eq!(
            f.string("missing").unwrap_err(),
            "thing 1: missing field `missing`"
        );
        assert!(f
            .number("name")
            .unwrap_err()
            .contains("should be a number, found a string"));
        assert_eq!(f.done().unwrap_err(), "thing 1: unknown field `extra`");
        assert!(Fields::of(&Json::Null, "x").is_err());
        let v = Json::parse(r#"{"n":-1,"m":1.5}"#).unwrap();
        let mut f = Fields::of(&v, "t").unwrap();
        assert!(f.count("n").is_err() && f.count("m").is_err());
    }
}
