//! The experiments are listed once, in `src/experiments/mod.rs`
//! (`experiments!`): the build holds what it lists, no cargo feature names
//! them again, and no other file spells the list out again. README's table is
//! written from the list by `cargo xtask readme` (its test is there).

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

/// The experiments are not cargo features (`build.rs` holds every one with a
/// content file, or those `LAB_EXPERIMENTS` names), so no Cargo.toml of the
/// workspace names them as features again.
#[test]
fn registry_no_cargo_manifest_lists_the_experiments_as_features() {
    let mut manifests = vec![root().join("Cargo.toml")];
    for dir in std::fs::read_dir(root().join("crates"))
        .unwrap()
        .filter_map(Result::ok)
    {
        let manifest = dir.path().join("Cargo.toml");
        if manifest.is_file() {
            manifests.push(manifest);
        }
    }
    assert!(manifests.len() >= 4, "found {} manifests", manifests.len());
    for manifest in manifests {
        let toml = read(&manifest);
        let Some(section) = toml.split("\n[features]\n").nth(1) else {
            continue;
        };
        let section = section.split("\n[").next().unwrap_or_default();
        for id in listed() {
            for spelled in [format!("\n{id} ="), format!("\"{id}\""), format!("/{id}\"")] {
                assert!(
                    !section.contains(&spelled),
                    "{}: experiment {id:?} appears among the [features]",
                    manifest.display()
                );
            }
        }
    }
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
