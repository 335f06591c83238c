//! Writes, for every content file `assets/<id>.json` (every `.json` there),
//! the part a wasm module needs at run time into `$OUT_DIR/<id>.quiz.json`:
//! the id, number, title, summary, aim (the lab report quotes it) and quiz,
//! with the other reading sections (theory, procedure, references) emptied.
//! The reading tabs are rendered at build time into their own pages, so a
//! module built without the `reading` feature carries only this (see
//! `experiments/mod.rs`).

#[allow(dead_code)]
#[path = "src/json.rs"]
mod json;

use json::Json;
use std::path::Path;

const READING: [&str; 3] = ["theory", "procedure", "references"];

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    println!("cargo:rerun-if-changed=src/json.rs");
    println!("cargo:rerun-if-changed={}", assets.display());
    let mut files: Vec<_> = std::fs::read_dir(&assets)
        .map(|dir| dir.filter_map(Result::ok).map(|e| e.path()).collect())
        .unwrap_or_default();
    files.retain(|p| p.extension().is_some_and(|e| e == "json"));
    files.sort();
    for path in files {
        let Some(id) = path.file_stem().and_then(|s| s.to_str()) else {
            continue;
        };
        println!("cargo:rerun-if-changed={}", path.display());
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        // A file that does not parse is passed on as it is: the crate's own
        // parser reports it, with its line and column.
        let quiz_only = match Json::parse(&text) {
            Ok(Json::Object(fields)) => Json::Object(
                fields
                    .into_iter()
                    .map(|(k, v)| {
                        if READING.contains(&k.as_str()) {
                            (k, Json::Array(Vec::new()))
                        } else {
                            (k, v)
                        }
                    })
                    .collect(),
            )
            .to_text(),
            _ => text,
        };
        std::fs::write(Path::new(&out).join(format!("{id}.quiz.json")), quiz_only)
            .expect("OUT_DIR is writable");
    }
}
