//! Issue 25 ("The house"): where things live, checked on the source tree.
//!
//! These read the crates' source as text; they guard the layout, not
//! behaviour (the other tests do that).

use std::fs;
use std::path::{Path, PathBuf};

/// Every `.rs` file below `dir`, in a stable order.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = fs::read_dir(&d) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The workspace's `crates/` folder.
fn crates_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("labcore sits in crates/")
        .to_path_buf()
}

/// Step 4, "one home for numbers": the functions that write and read
/// numbers with units are defined in `labcore::units` and nowhere else, and
/// no caller reaches them through their old homes (`quiz`, `experiment`).
#[test]
fn one_home_for_numbers_every_number_formatter_and_reader_lives_in_units() {
    const DEFINITIONS: [&str; 11] = [
        "fn format_number(",
        "fn format_fixed(",
        "fn format_metres(",
        "fn format_degrees(",
        "fn format_magnitude(",
        "fn format_point(",
        "fn read_answer(",
        "fn read_number(",
        "fn parse_answer(",
        "fn parse_number(",
        "fn with_unit(number: &str",
    ];
    const OLD_PATHS: [&str; 6] = [
        "quiz::format_number",
        "quiz::read_answer",
        "quiz::parse_",
        "experiment::format_",
        "quiz::{format_number",
        "quiz::ReadError",
    ];
    let units = crates_dir().join("labcore/src/units.rs");
    assert!(
        units.is_file(),
        "labcore/src/units.rs is the home of numbers"
    );
    let mut misplaced = Vec::new();
    for file in rust_files(&crates_dir()) {
        if file.ends_with("labcore/tests/house.rs") {
            continue; // this file names the old paths to look for them
        }
        let text = fs::read_to_string(&file).unwrap_or_default();
        for (n, line) in text.lines().enumerate() {
            let here = format!("{}:{}", file.display(), n + 1);
            if file != units && DEFINITIONS.iter().any(|d| line.contains(d)) {
                misplaced.push(format!("{here}: {}", line.trim()));
            }
            if OLD_PATHS.iter().any(|p| line.contains(p)) {
                misplaced.push(format!("{here}: {}", line.trim()));
            }
        }
    }
    assert!(
        misplaced.is_empty(),
        "outside units.rs:\n{}",
        misplaced.join("\n")
    );
}

/// Step 7, "a test kit": every experiment's tests use `labcore::testkit`
/// and none writes its own copy of the kit's helpers (step, read a
/// readout, click, draw the scene, …).
#[test]
fn a_test_kit_every_experiments_tests_use_it_and_copy_none_of_its_helpers() {
    const COPIES: [&str; 9] = [
        "fn run(",
        "fn run_for(",
        "fn readout(",
        "fn click(",
        "fn scene_of(",
        "fn scene_of_field(",
        "fn notice(",
        "fn set(",
        "readout_value(",
    ];
    let experiments = crates_dir().join("labcore/src/experiments");
    // Each experiment's folder: its `tests.rs`, or the tests module at the
    // end of its `mod.rs` (the small experiments).
    let mut test_files: Vec<PathBuf> = Vec::new();
    for entry in fs::read_dir(&experiments).expect("experiments/").flatten() {
        let (tests, module) = (entry.path().join("tests.rs"), entry.path().join("mod.rs"));
        if tests.is_file() {
            test_files.push(tests);
        } else if module.is_file() {
            test_files.push(module);
        }
    }
    assert_eq!(
        test_files.len(),
        labcore::registry().len(),
        "{test_files:?}"
    );
    let mut problems = Vec::new();
    for file in &test_files {
        let text = fs::read_to_string(file).expect("readable");
        let tests = text.split("#[cfg(test)]").last().unwrap_or(&text);
        if !tests.contains("crate::testkit") {
            problems.push(format!("{}: does not use crate::testkit", file.display()));
        }
        for copy in COPIES {
            if tests.contains(copy) {
                problems.push(format!("{}: has its own `{copy}`", file.display()));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// One home for transcendental functions: the code the browser runs
/// (labcore, labweb, labpage outside their tests) calls sin, cos, atan2,
/// logarithms, exponentials and real powers through `labcore::math` (the
/// `libm` crate), never through `f64`'s methods. `f64::sin` is the
/// platform's C library natively and compiler-builtins' port in wasm: a run
/// could differ in the last bit between the two, and a module that used
/// both carried two copies of the functions (3.4 KB gzip in diffdrive and
/// potential's). `powi` (repeated multiplication) and `sqrt` (exactly
/// rounded everywhere) may stay.
#[test]
fn transcendental_functions_go_through_labcore_math() {
    const FUNCTIONS: [&str; 24] = [
        "sin", "cos", "tan", "sin_cos", "atan2", "atan", "asin", "acos", "sinh", "cosh", "tanh",
        "asinh", "acosh", "atanh", "ln", "ln_1p", "log", "log10", "log2", "exp", "exp_m1", "exp2",
        "powf", "hypot",
    ];
    let calls: Vec<String> = FUNCTIONS
        .iter()
        .flat_map(|f| [format!(".{f}("), format!("f64::{f}(")])
        .chain(std::iter::once(".cbrt(".to_owned()))
        .collect();
    let mut found = Vec::new();
    for krate in ["labcore/src", "labweb/src", "labpage/src"] {
        for file in rust_files(&crates_dir().join(krate)) {
            let name = file.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if matches!(name, "tests.rs" | "testkit.rs") {
                continue;
            }
            let text = fs::read_to_string(&file).unwrap_or_default();
            for (n, line) in shipped_lines(&text) {
                let code = line.split("//").next().unwrap_or("");
                if calls.iter().any(|c| code.contains(c.as_str())) {
                    found.push(format!("{}:{}: {}", file.display(), n + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "call these through labcore::math:\n{}",
        found.join("\n")
    );
}

/// The lines of a Rust source that are compiled outside tests, numbered
/// from 0: each `#[cfg(test)]` item (a `mod tests { … }`, a function, a
/// `mod tests;` declaration) is left out, up to its closing brace or its
/// semicolon; the code after it is kept. Braces are counted as written
/// (one in a string or character literal would throw the count off).
fn shipped_lines(text: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut lines = text.lines().enumerate();
    while let Some((n, line)) = lines.next() {
        if line.trim() != "#[cfg(test)]" {
            out.push((n, line));
            continue;
        }
        // Skip the item: attributes and doc lines, then to its end.
        let mut depth = 0i64;
        let mut opened = false;
        for (_, item) in lines.by_ref() {
            let code = item.split("//").next().unwrap_or("");
            depth += code.matches('{').count() as i64 - code.matches('}').count() as i64;
            opened |= code.contains('{');
            let attribute =
                item.trim_start().starts_with("#[") || item.trim_start().starts_with("//");
            if (opened && depth <= 0) || (!opened && !attribute && code.trim_end().ends_with(';')) {
                break;
            }
        }
    }
    out
}

#[test]
fn shipped_lines_leave_out_test_items_and_keep_what_follows() {
    let source = "fn a() {}\n#[cfg(test)]\nmod tests;\nfn b() {}\n#[cfg(test)]\n#[must_use]\nfn only_tests() -> u8 {\n    { 1 }\n}\nfn c() {}\n#[cfg(test)]\nmod tests {\n    fn t() {}\n}\n";
    let kept: Vec<&str> = shipped_lines(source).into_iter().map(|(_, l)| l).collect();
    assert_eq!(kept, ["fn a() {}", "fn b() {}", "fn c() {}"]);
}

/// Every experiment's folder below `labcore/src/experiments`, by id, in a
/// stable order.
fn experiment_folders() -> Vec<(String, PathBuf)> {
    let root = crates_dir().join("labcore/src/experiments");
    let mut out: Vec<(String, PathBuf)> = fs::read_dir(&root)
        .expect("experiments/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .filter_map(|p| Some((p.file_name()?.to_str()?.to_owned(), p)))
        .collect();
    out.sort();
    out
}

/// Whether `file` (inside an experiment's folder) is part of its view:
/// `view.rs` or a file below a `view/` folder.
fn is_view_file(file: &Path) -> bool {
    file.file_name().is_some_and(|n| n == "view.rs")
        || file.components().any(|c| c.as_os_str() == "view")
}

/// Issue 54 §3, "one-way view": the dependency runs view → model. The
/// model (an experiment's `mod.rs` and every other file of its folder that
/// is not its view) never calls into `view::` outside its tests; what both
/// need (a label's wording, a tolerance) lives on the model's side.
#[test]
fn one_way_view_no_model_file_of_an_experiment_names_its_view() {
    let folders = experiment_folders();
    assert_eq!(folders.len(), labcore::registry().len(), "{folders:?}");
    let mut found = Vec::new();
    for (_, folder) in &folders {
        for file in rust_files(folder) {
            let name = file.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if is_view_file(&file) || name == "tests.rs" {
                continue;
            }
            let text = fs::read_to_string(&file).unwrap_or_default();
            for (n, line) in shipped_lines(&text) {
                let code = line.split("//").next().unwrap_or("");
                if code.contains("view::") {
                    found.push(format!("{}:{}: {}", file.display(), n + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "the model calls into its view:\n{}",
        found.join("\n")
    );
}

/// Issue 54 §3: a view imports what it uses by name, so what the model
/// exports for it is visible; `use super::*` let every view inherit the
/// presentation names its `mod.rs` imported only for it.
#[test]
fn one_way_view_no_view_inherits_the_models_imports() {
    let mut found = Vec::new();
    for (_, folder) in experiment_folders() {
        for file in rust_files(&folder).into_iter().filter(|f| is_view_file(f)) {
            let text = fs::read_to_string(&file).unwrap_or_default();
            for (n, line) in text.lines().enumerate() {
                if line
                    .split("//")
                    .next()
                    .unwrap_or("")
                    .contains("use super::*")
                {
                    found.push(format!("{}:{}: {}", file.display(), n + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "glob imports in views:\n{}",
        found.join("\n")
    );
}

/// Issue 54 §3, "independent experiments": no experiment's folder names
/// another experiment's module (`experiments::<other>` or
/// `super::super::<other>`); what two experiments share lives in a shared
/// module (`scene`, `mobile`, `plot`, …).
#[test]
fn independent_experiments_no_experiment_imports_a_sibling() {
    let folders = experiment_folders();
    let ids: Vec<&str> = folders.iter().map(|(id, _)| id.as_str()).collect();
    let mut found = Vec::new();
    for (id, folder) in &folders {
        for file in rust_files(folder) {
            let text = fs::read_to_string(&file).unwrap_or_default();
            for (n, line) in text.lines().enumerate() {
                let code = line.split("//").next().unwrap_or("");
                let sibling = ids.iter().filter(|other| *other != id).find(|other| {
                    code.contains(&format!("experiments::{other}"))
                        || code.contains(&format!("super::super::{other}"))
                });
                if let Some(other) = sibling {
                    found.push(format!(
                        "{}:{}: imports {other}: {}",
                        file.display(),
                        n + 1,
                        line.trim()
                    ));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "experiments importing each other:\n{}",
        found.join("\n")
    );
}

/// The methods a view defines on its experiment outside a trait impl
/// (`impl AStarGrid { … }` in `view.rs`): its own helpers.
fn view_methods(view: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in view.lines() {
        if line.starts_with("impl ") && line.ends_with(" {") && !line.contains(" for ") {
            inside = true;
        } else if line == "}" {
            inside = false;
        } else if inside {
            let code = line.trim_start_matches("    ");
            let code = ["pub(super) ", "pub(crate) ", "pub "]
                .iter()
                .fold(code, |c, p| c.strip_prefix(p).unwrap_or(c));
            if let Some(name) = code.strip_prefix("fn ") {
                let name: String = name
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                out.push(name);
            }
        }
    }
    out
}

/// Issue 54 §3, "one-way view", the method form: a model file does not
/// call a method its view defines (`self.zoomed()` reaches the view as
/// surely as `view::zoomed`). astar's camera (zoom, pan, window) and its
/// raster cache are the known exception: the model's input handling pans
/// and zooms, and its edits and search steps refresh the raster. Moving
/// them out needs view state the page keeps apart from the experiment (a
/// change to the `Presentation` trait), so they are listed here; the list
/// may only shrink.
#[test]
fn one_way_view_no_model_file_calls_a_method_its_view_defines() {
    const KNOWN: [&str; 8] = [
        "astar: band_side",
        "astar: clamp_pan",
        "astar: follow",
        "astar: frame_ends",
        "astar: search_raster",
        "astar: walls_raster",
        "astar: window_cells",
        "astar: zoomed",
    ];
    let mut found = Vec::new();
    for (id, folder) in experiment_folders() {
        let view = fs::read_to_string(folder.join("view.rs")).unwrap_or_default();
        let methods = view_methods(&view);
        for file in rust_files(&folder) {
            let name = file.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if is_view_file(&file) || name == "tests.rs" {
                continue;
            }
            let text = fs::read_to_string(&file).unwrap_or_default();
            for method in &methods {
                let call = format!(".{method}(");
                let calls = shipped_lines(&text)
                    .iter()
                    .any(|(_, l)| l.split("//").next().unwrap_or("").contains(&call));
                if calls {
                    found.push(format!("{id}: {method}"));
                }
            }
        }
    }
    found.sort();
    found.dedup();
    assert_eq!(found, KNOWN, "model files calling their view's methods");
}

#[test]
fn view_methods_are_those_of_inherent_impls_only() {
    let view = "impl Presentation for A {\n    fn scene(&self) {}\n}\n\nimpl A {\n    pub(super) fn zoomed(&self) -> bool {\n        true\n    }\n\n    fn pan_2(&mut self) {}\n}\n\nfn free() {}\n";
    assert_eq!(view_methods(view), ["zoomed", "pan_2"]);
}
