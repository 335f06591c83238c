//! Import circles between a crate's modules (issue 25 step 6): module `a`
//! naming `crate::b` and `b` naming `crate::a` (or a longer ring) means
//! neither can be read, changed or tested without the other. The graph is
//! read from the source: an edge `a -> b` for every `crate::b` outside
//! comments in `a`'s files (a folder module's files count as one).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The top-level modules of the crate at `src` and, for each, the
/// top-level modules it names through `crate::`.
fn module_graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in rust_files(src) {
        let rel = file.strip_prefix(src).unwrap();
        let first = rel.components().next().unwrap().as_os_str();
        let module = Path::new(first)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        if matches!(module.as_str(), "lib" | "main") {
            continue;
        }
        // Test code may reach anywhere: a file of tests, and a file's tests
        // module (the `#[cfg(test)]` at its end), are not imports of the
        // module.
        if rel.file_name().is_some_and(|n| n == "tests.rs") {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        let code = text.split("\n#[cfg(test)]").next().unwrap_or("");
        let edges = graph.entry(module.clone()).or_default();
        for line in code.lines() {
            let code = line.split("//").next().unwrap_or("");
            for target in named_modules(code) {
                if target != module {
                    edges.insert(target);
                }
            }
        }
    }
    graph
}

/// `crate::x` and `use crate::{x, y::…}` in one line of code.
fn named_modules(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        let before = rest[..at].chars().next_back();
        rest = &rest[at + "crate::".len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue; // `labcore::` or `mycrate::`, not this crate
        }
        if let Some(group) = rest.strip_prefix('{') {
            // The group's top-level names: `{a::{x, y}, b}` names a and b.
            let (mut depth, mut item_start) = (0, true);
            for (i, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => item_start = true,
                    c if item_start && (c.is_alphanumeric() || c == '_') => {
                        item_start = false;
                        let name: String = group[i..]
                            .chars()
                            .take_while(|c| c.is_alphanumeric() || *c == '_')
                            .collect();
                        out.push(name);
                    }
                    _ => {}
                }
            }
        } else {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                out.push(name);
            }
        }
    }
    out
}

fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            out.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out.sort();
    out
}

/// Every module pair `(a, b)`, `a < b`, that reach each other: both lie on
/// one circle.
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<(String, String)> {
    let reach = |from: &str| {
        let mut seen = BTreeSet::new();
        let mut todo = vec![from.to_owned()];
        while let Some(m) = todo.pop() {
            for next in graph.get(&m).into_iter().flatten() {
                if seen.insert(next.clone()) {
                    todo.push(next.clone());
                }
            }
        }
        seen
    };
    let mut out = Vec::new();
    for a in graph.keys() {
        let from_a = reach(a);
        for b in graph.keys().filter(|b| *b > a) {
            if from_a.contains(b) && reach(b).contains(a) {
                out.push((a.clone(), b.clone()));
            }
        }
    }
    out
}

fn crate_src(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(name)
        .join("src")
}

#[test]
fn the_reader_sees_a_circle_and_a_one_way_edge() {
    let graph = BTreeMap::from([
        ("a".to_owned(), BTreeSet::from(["b".to_owned()])),
        ("b".to_owned(), BTreeSet::from(["c".to_owned()])),
        ("c".to_owned(), BTreeSet::from(["a".to_owned()])),
        ("d".to_owned(), BTreeSet::from(["a".to_owned()])),
    ]);
    assert_eq!(
        circles(&graph),
        [("a", "b"), ("a", "c"), ("b", "c")].map(|(a, b)| (a.to_owned(), b.to_owned()))
    );
    assert_eq!(
        named_modules("use crate::{dom::{a, b}, quiz_view}; x(crate::lms::f); labcore::y"),
        ["dom", "quiz_view", "lms"]
    );
}

/// `dist` builds the site from `modules` and `pages`; neither calls back.
#[test]
fn xtask_dist_modules_and_pages_import_no_circle() {
    let graph = module_graph(&crate_src("xtask"));
    let found = circles(&graph);
    assert!(
        !found
            .iter()
            .any(|(a, b)| ["dist", "modules", "pages"].contains(&a.as_str())
                || ["dist", "modules", "pages"].contains(&b.as_str())),
        "{found:?}"
    );
    assert_eq!(found, Vec::<(String, String)>::new(), "xtask has no circle");
}

/// The quiz tab (`quiz_view`) tells the LMS bridge (`lms`) what happened;
/// the bridge knows nothing of the quiz tab's types.
#[test]
fn labweb_lms_and_quiz_view_import_no_circle() {
    let graph = module_graph(&crate_src("labweb"));
    let found = circles(&graph);
    assert!(
        !found.iter().any(|(a, b)| a == "lms" || b == "lms"),
        "{found:?}"
    );
}

/// No crate of the workspace has a circle of module imports (issue 25 §6):
/// each module's dependencies can be read without coming back to it.
#[test]
fn no_crate_has_an_import_circle() {
    for krate in ["labcore", "labweb", "labpage", "xtask"] {
        let found = circles(&module_graph(&crate_src(krate)));
        assert_eq!(found, Vec::<(String, String)>::new(), "{krate}");
    }
}
