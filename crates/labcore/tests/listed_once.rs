//! The experiments are listed once, in `src/experiments/mod.rs`
//! (`experiments!`): what cannot be generated from that list is checked
//! against it here — the cargo features, README's table — and no other file
//! spells the list out again.

use labcore::catalogue::CATALOGUE;
use labcore::registry;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn listed() -> Vec<&'static str> {
    CATALOGUE.iter().map(|p| p.id).collect()
}

#[test]
fn registry_the_default_build_holds_every_listed_experiment_in_order() {
    let built: Vec<&str> = registry().iter().map(|e| e.id).collect();
    assert_eq!(built, listed());
}

/// `crates/labcore/Cargo.toml` has one feature per experiment, named after
/// its id and enabling nothing else, and `default` turns every one on after
/// `reading` (cargo cannot take its features from the list).
#[test]
fn registry_cargo_features_are_the_listed_experiments() {
    let toml = read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml"));
    let section = toml
        .split("\n[features]\n")
        .nth(1)
        .expect("a [features] section")
        .split("\n[")
        .next()
        .unwrap_or_default();
    let mut features: Vec<(String, String)> = Vec::new();
    for line in section.lines().map(str::trim) {
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let (name, value) = line.split_once('=').expect("feature = [...]");
        features.push((name.trim().to_owned(), value.trim().to_owned()));
    }
    let quoted = |ids: &[&str]| {
        ids.iter()
            .map(|id| format!("\"{id}\""))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut expected = vec![
        (
            "default".to_owned(),
            format!("[{}]", quoted(&[&["reading"][..], &listed()].concat())),
        ),
        ("reading".to_owned(), "[\"dep:labtex\"]".to_owned()),
    ];
    expected.extend(
        listed()
            .iter()
            .map(|id| ((*id).to_owned(), "[]".to_owned())),
    );
    let lines = |f: &[(String, String)]| {
        f.iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(
        lines(&features),
        lines(&expected),
        "crates/labcore/Cargo.toml's [features] should read (comments aside):\n{}",
        lines(&expected)
    );
}

/// README's table "The experiments" has one row per experiment, in the lab's
/// order, with its number and id.
#[test]
fn registry_readme_table_is_the_listed_experiments() {
    let readme = read(&root().join("README.md"));
    let table = readme
        .split("\n## The experiments\n")
        .nth(1)
        .expect("README has a section \"The experiments\"");
    let rows: Vec<(String, String)> = table
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .skip(2) // the header and its rule
        .map(|row| {
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            (cells[1].to_owned(), cells[2].trim_matches('`').to_owned())
        })
        .collect();
    let expected: Vec<(String, String)> = CATALOGUE
        .iter()
        .map(|p| (p.number.to_string(), p.id.to_owned()))
        .collect();
    assert_eq!(rows, expected, "README's experiments table: (#, id) rows");
}

/// Source files of the project that tests and code live in.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().filter_map(Result::ok) {
        let path = entry.path();
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if path.is_dir() {
            if !name.starts_with('.') && name != "node_modules" && name != "target" {
                sources(&path, out);
            }
        } else if [".rs", ".mjs", ".js"].iter().any(|ext| name.ends_with(ext)) {
            out.push(path);
        }
    }
}

/// No file but the list itself writes the experiments out again: no run of
/// text of 1,500 characters names all the ids but one or fewer, quoted (a
/// test that reads each experiment's own presets names them far apart), and
/// no end-to-end test or bench counts the experiments by a number of its
/// own. They take the ids from the registry or from the built site.
#[test]
fn registry_no_other_file_spells_the_list_of_experiments() {
    let ids = listed();
    let list = root().join("crates/labcore/src/experiments/mod.rs");
    let mut files = Vec::new();
    for dir in ["crates", "tests", "web"] {
        sources(&root().join(dir), &mut files);
    }
    assert!(files.len() > 50, "found {} source files", files.len());
    let mut spelled = Vec::new();
    for file in files
        .iter()
        .filter(|f| f.canonicalize().ok() != list.canonicalize().ok())
    {
        let text = read(file);
        // Where each id appears quoted ("fk" or 'fk').
        let mut at: Vec<(usize, &str)> = Vec::new();
        for id in &ids {
            for quote in ['"', '\''] {
                let needle = format!("{quote}{id}{quote}");
                at.extend(text.match_indices(&needle).map(|(i, _)| (i, *id)));
            }
        }
        at.sort_unstable();
        let most = at
            .iter()
            .map(|&(start, _)| {
                let mut seen: Vec<&str> = at
                    .iter()
                    .filter(|&&(i, _)| i >= start && i < start + 1_500)
                    .map(|&(_, id)| id)
                    .collect();
                seen.sort_unstable();
                seen.dedup();
                seen.len()
            })
            .max()
            .unwrap_or(0);
        if most + 1 >= ids.len() {
            spelled.push(format!("{} names {most} ids together", file.display()));
        }
        let js = file.extension().is_some_and(|e| e == "mjs" || e == "js");
        let numbers: Vec<String> = (1..=ids.len()).map(|n| n.to_string()).collect();
        for counted in [
            format!("ids.length, {}", ids.len()),
            format!("ids.length >= {}", ids.len()),
            format!("[{}]", numbers.join(", ")),
        ] {
            if js && text.contains(&counted) {
                spelled.push(format!("{} counts them: {counted}", file.display()));
            }
        }
    }
    assert!(spelled.is_empty(), "{}", spelled.join("\n"));
}
