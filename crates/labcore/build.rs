//! Writes, for every content file `assets/<id>.json`, the part a wasm module
//! needs at run time into `$OUT_DIR/<id>.quiz.json`: the id, number, title,
//! summary, aim (the lab report quotes it) and quiz, with the other reading
//! sections (theory, procedure, references) emptied. The reading tabs are rendered at build time into
//! their own pages, so a module built without the `reading` feature carries
//! only this (a quarter of the bytes; see `experiments/mod.rs`).

#[allow(dead_code)]
#[path = "src/json.rs"]
mod json;

use json::Json;
use std::path::Path;

const IDS: [&str; 11] = [
    "fk",
    "ik",
    "workspace",
    "diffdrive",
    "potential",
    "astar",
    "pid",
    "cartpole",
    "dls",
    "rrtstar",
    "ekf",
];
const READING: [&str; 3] = ["theory", "procedure", "references"];

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    println!("cargo:rerun-if-changed=src/json.rs");
    for id in IDS {
        let path = assets.join(format!("{id}.json"));
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
