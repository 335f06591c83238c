//! The project's Markdown (issue 54 §4): README.md stays short, every
//! relative link of README.md, ARCHITECTURE.md and docs/*.md resolves (its
//! file, and its `#anchor` to a heading of that file), ARCHITECTURE.md's
//! crate graph is the one `cargo metadata` reads from the manifests,
//! README's Layout names every crate, and the counts the text writes in
//! words (wasm modules, groups) are the registry's.

use labcore::catalogue::{wasm_module, Group, CATALOGUE};
use labcore::json::Json;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

/// README's length at most: what the lab is, the two commands, the table of
/// the experiments and links; the rest lives in docs/.
const README_MAX_LINES: usize = 250;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// README.md, ARCHITECTURE.md and every docs/*.md.
fn markdown_files() -> Vec<PathBuf> {
    let root = root();
    let mut files = vec![root.join("README.md"), root.join("ARCHITECTURE.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    assert!(!docs.is_empty(), "docs/ holds no .md file");
    files.extend(docs);
    files
}

/// The text of a Markdown file outside fenced code blocks and inline code
/// spans, line by line (code is not Markdown: `[a](b)` there is no link).
fn prose_lines(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        out.push(without_code_spans(line));
    }
    out
}

/// `line` with its code spans (`` `…` ``, ``` ``…`` ```) left out.
fn without_code_spans(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(start) = rest.find('`') {
        out.push_str(&rest[..start]);
        let ticks = rest[start..].chars().take_while(|&c| c == '`').count();
        let fence = "`".repeat(ticks);
        let after = &rest[start + ticks..];
        match after.find(&fence) {
            Some(end) => rest = &after[end + ticks..],
            None => {
                // An unmatched backtick is a literal one.
                out.push_str(&fence);
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// The targets of the inline links `[text](target)` in `text`.
fn link_targets(text: &str) -> Vec<String> {
    let mut targets = Vec::new();
    for line in prose_lines(text) {
        let mut rest = line.as_str();
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let Some(end) = after.find(')') else { break };
            let target = after[..end].split_whitespace().next().unwrap_or("");
            targets.push(target.to_owned());
            rest = &after[end..];
        }
    }
    targets
}

/// The anchors of a Markdown file's headings, as GitHub makes them:
/// lower case, punctuation dropped, spaces as hyphens; a repeated one gets
/// `-1`, `-2`, ….
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = BTreeSet::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced || !line.starts_with('#') {
            continue;
        }
        let title = line.trim_start_matches('#');
        if !title.starts_with(' ') {
            continue;
        }
        let slug: String = title
            .trim()
            .to_lowercase()
            .chars()
            .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
            .map(|c| if c == ' ' { '-' } else { c })
            .collect();
        let n = seen.entry(slug.clone()).or_insert(0);
        out.insert(if *n == 0 {
            slug.clone()
        } else {
            format!("{slug}-{n}")
        });
        *n += 1;
    }
    out
}

#[test]
fn docs_readme_is_at_most_250_lines() {
    let lines = read(&root().join("README.md")).lines().count();
    assert!(
        lines <= README_MAX_LINES,
        "README.md has {lines} lines, more than {README_MAX_LINES}: move what is for instructors, \
         authors or developers to a page of docs/ and link it"
    );
}

/// CI and a newcomer run what README's quick start says: one command that
/// builds and serves the lab, one that runs every test.
#[test]
fn docs_readme_quick_start_has_the_two_commands() {
    assert_eq!(quick_start(), ["cargo xtask serve", "cargo xtask test"]);
}

/// The commands of README's quick start (its first ```sh block), without
/// their comments.
fn quick_start() -> Vec<String> {
    let text = read(&root().join("README.md"));
    let block = text
        .split("```sh\n")
        .nth(1)
        .and_then(|b| b.split("\n```").next())
        .expect("README.md has a ```sh block");
    block
        .lines()
        .map(|l| l.split('#').next().unwrap_or("").trim().to_owned())
        .filter(|l| !l.is_empty())
        .collect()
}

/// CI (`.ci/run`) runs README's test command as written, and nothing else
/// as a test: what passes in CI is what a newcomer's command runs.
#[test]
fn docs_ci_runs_readme_s_test_command() {
    let test_command = quick_start().pop().expect("README's test command");
    let script = read(&root().join(".ci/run"));
    let runs: Vec<&str> = script
        .lines()
        .map(str::trim)
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.strip_prefix("time ").unwrap_or(l))
        .filter(|l| l.starts_with("cargo xtask"))
        .collect();
    assert_eq!(runs, [test_command.as_str()], ".ci/run's xtask commands");
}

#[test]
fn docs_every_relative_link_resolves() {
    let root = root();
    let mut broken = Vec::new();
    let mut checked = 0;
    for file in markdown_files() {
        let text = read(&file);
        let name = file.strip_prefix(&root).unwrap().display().to_string();
        for target in link_targets(&text) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            checked += 1;
            let (path, anchor) = match target.split_once('#') {
                Some((p, a)) => (p, Some(a)),
                None => (target.as_str(), None),
            };
            let linked = if path.is_empty() {
                file.clone()
            } else {
                file.parent().unwrap().join(path)
            };
            if !linked.exists() {
                broken.push(format!("{name}: ({target}): no file {}", linked.display()));
                continue;
            }
            if let Some(anchor) = anchor {
                if linked.extension().is_some_and(|e| e == "md")
                    && !anchors(&read(&linked)).contains(anchor)
                {
                    broken.push(format!("{name}: ({target}): no heading #{anchor} there"));
                }
            }
        }
    }
    assert!(checked >= 10, "only {checked} relative links found");
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn docs_every_page_of_docs_is_linked_from_readme() {
    let root = root();
    let readme = read(&root.join("README.md"));
    let linked: BTreeSet<String> = link_targets(&readme).into_iter().collect();
    for file in markdown_files().iter().skip(2) {
        let rel = file.strip_prefix(&root).unwrap().display().to_string();
        assert!(linked.contains(&rel), "README.md does not link {rel}");
    }
}

/// Each crate's workspace dependencies as ARCHITECTURE.md's table between
/// its markers writes them: (normal and build, dev-only).
type Graph = BTreeMap<String, (BTreeSet<String>, BTreeSet<String>)>;

fn names_in(cell: &str) -> BTreeSet<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect()
}

fn architecture_graph() -> Graph {
    let text = read(&root().join("ARCHITECTURE.md"));
    let table = text
        .split("<!-- crate graph: begin -->")
        .nth(1)
        .and_then(|t| t.split("<!-- crate graph: end -->").next())
        .expect("ARCHITECTURE.md marks its crate graph");
    let mut graph = Graph::new();
    for row in table.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        assert_eq!(cells.len(), 5, "a row of three cells: {row}");
        let name = cells[1].trim_matches('`').to_owned();
        let previous = graph.insert(name.clone(), (names_in(cells[2]), names_in(cells[3])));
        assert!(previous.is_none(), "{name} is listed twice");
    }
    graph
}

fn field<'a>(value: &'a Json, key: &str) -> Option<&'a Json> {
    match value {
        Json::Object(fields) => fields.iter().find(|(k, _)| k == key).map(|(_, v)| v),
        _ => None,
    }
}

fn text_of<'a>(value: &'a Json, key: &str) -> Option<&'a str> {
    match field(value, key) {
        Some(Json::String(s)) => Some(s),
        _ => None,
    }
}

/// `cargo metadata --no-deps` of the workspace, parsed.
fn metadata() -> Json {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args([
            "metadata",
            "--no-deps",
            "--format-version",
            "1",
            "--offline",
        ])
        .current_dir(root())
        .output()
        .expect("cargo metadata runs");
    assert!(
        out.status.success(),
        "cargo metadata: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    Json::parse(&String::from_utf8(out.stdout).unwrap()).unwrap()
}

/// The workspace's packages as `cargo metadata` lists them.
fn packages(metadata: &Json) -> &[Json] {
    let Some(Json::Array(packages)) = field(metadata, "packages") else {
        panic!("cargo metadata has no packages")
    };
    packages
}

fn metadata_graph() -> Graph {
    let metadata = metadata();
    let packages = packages(&metadata);
    let members: BTreeSet<&str> = packages.iter().filter_map(|p| text_of(p, "name")).collect();
    let mut graph = Graph::new();
    for package in packages {
        let name = text_of(package, "name").unwrap().to_owned();
        let Some(Json::Array(deps)) = field(package, "dependencies") else {
            panic!("{name} has no dependencies list")
        };
        let (mut built, mut dev) = (BTreeSet::new(), BTreeSet::new());
        for dep in deps {
            let dep_name = text_of(dep, "name").unwrap();
            if !members.contains(dep_name) {
                continue;
            }
            match text_of(dep, "kind") {
                Some("dev") => dev.insert(dep_name.to_owned()),
                _ => built.insert(dep_name.to_owned()),
            };
        }
        let dev = dev.difference(&built).cloned().collect();
        graph.insert(name, (built, dev));
    }
    graph
}

#[test]
fn docs_architecture_crate_graph_is_cargo_metadata_s() {
    assert_eq!(
        architecture_graph(),
        metadata_graph(),
        "ARCHITECTURE.md's crate graph (left) differs from the manifests' (right)"
    );
}

#[test]
fn docs_link_and_anchor_reading() {
    assert_eq!(
        link_targets("see [a](docs/a.md#x) and `[b](c)` and [d](https://e)"),
        ["docs/a.md#x", "https://e"]
    );
    assert_eq!(link_targets("```\n[a](b)\n```\n"), Vec::<String>::new());
    let found = anchors("# Hosting the lab\n## File types\n## LMS (SCORM 1.2)\n## File types\n");
    for a in [
        "hosting-the-lab",
        "file-types",
        "lms-scorm-12",
        "file-types-1",
    ] {
        assert!(found.contains(a), "{a} in {found:?}");
    }
}

/// A newcomer finds every crate in README's Layout: one row per workspace
/// member, named by its folder (`crates/<name>`).
#[test]
fn docs_readme_layout_names_every_crate() {
    let root = root();
    let readme = read(&root.join("README.md"));
    let layout = readme
        .split("## Layout")
        .nth(1)
        .expect("README.md has a Layout section");
    let rows: BTreeSet<String> = layout
        .lines()
        .filter_map(|l| l.strip_prefix("| `"))
        .filter_map(|l| l.split('`').next())
        .map(|p| p.trim_end_matches('/').to_owned())
        .collect();
    let metadata = metadata();
    let mut missing = Vec::new();
    for package in packages(&metadata) {
        let manifest = PathBuf::from(text_of(package, "manifest_path").unwrap());
        let folder = manifest.parent().unwrap().canonicalize().unwrap();
        let folder = folder.strip_prefix(&root).unwrap().display().to_string();
        if !rows.contains(&folder) {
            missing.push(folder);
        }
    }
    assert!(rows.len() >= 7, "README's Layout has {} rows", rows.len());
    assert!(
        missing.is_empty(),
        "README's Layout has no row for {missing:?}"
    );
}

/// The number written as a word just before `noun` in `text` (`"eight wasm
/// modules"`), for every place it is written.
fn counts_before(text: &str, noun: &str) -> Vec<usize> {
    const WORDS: [&str; 13] = [
        "zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten",
        "eleven", "twelve",
    ];
    let flat = text.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut found = Vec::new();
    let mut rest = flat.as_str();
    while let Some(at) = rest.find(&format!(" {noun}")) {
        let word = rest[..at].rsplit(' ').next().unwrap_or("").to_lowercase();
        if let Some(n) = WORDS.iter().position(|w| *w == word) {
            found.push(n);
        }
        rest = &rest[at + noun.len() + 1..];
    }
    found
}

/// The counts the docs write in words are the registry's: ARCHITECTURE's
/// wasm modules (one per key of `experiments!`, as `cargo xtask dist` builds
/// them) and the groups of README and the platform page. A thirteenth
/// experiment with a module of its own, or a sixth group, fails here until
/// the text says so.
#[test]
fn docs_counts_in_words_are_the_registry_s() {
    let root = root();
    let modules: BTreeSet<&str> = CATALOGUE
        .iter()
        .map(|p| wasm_module(p.id).unwrap_or(p.id))
        .collect();
    let groups: BTreeSet<&str> = CATALOGUE.iter().map(|p| p.group.key()).collect();
    assert_eq!(
        groups.len(),
        Group::ALL.len(),
        "every group has an experiment"
    );
    let written = |page: &str, noun: &str, count: usize| {
        let found = counts_before(&read(&root.join(page)), noun);
        assert!(!found.is_empty(), "{page} writes no count of {noun}");
        assert!(
            found.iter().all(|&n| n == count),
            "{page} writes {found:?} {noun}; the registry has {count}"
        );
    };
    written("ARCHITECTURE.md", "wasm modules", modules.len());
    written("README.md", "groups", Group::ALL.len());
    written("docs/platform.md", "groups", Group::ALL.len());
}

#[test]
fn docs_count_reading() {
    assert_eq!(
        counts_before(
            "and eight wasm\n  modules, each; one wasm modules",
            "wasm modules"
        ),
        [8, 1]
    );
    assert_eq!(counts_before("in five groups", "groups"), [5]);
    assert_eq!(
        counts_before("in many groups", "groups"),
        Vec::<usize>::new()
    );
}
