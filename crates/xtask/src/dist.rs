//! `cargo xtask dist`: builds the static site into `dist/`.
//!
//! 1. adds the `wasm32-unknown-unknown` rustup target when it is missing;
//! 2. runs `npm ci` when `node_modules/` is missing or older than `package-lock.json`;
//! 3. builds `labweb` for wasm (release);
//! 4. generates the JS glue with the wasm-bindgen library (target `web`);
//! 5. optimises the module with npm binaryen's `wasm-opt` (see
//!    [`crate::modules::WASM_OPT_LEVEL`]);
//! 6. copies `web/` into `dist/` and the glue + module into `dist/pkg/`, and
//!    writes the navigation, home page and reading tabs into `index.html`
//!    (after validating every content file);
//! 7. checks that the site only uses relative URLs and stamps a content hash
//!    (`?v=…`) on the references in `dist/index.html` and on the scripts'
//!    import of the wasm glue (no inline script: see
//!    [`crate::pages::CONTENT_SECURITY_POLICY`]).

use crate::util::{self, files_below, slash_path};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use crate::modules::{build_modules, ship_modules, WASM_TARGET};
use crate::util::{remove_dir, step};

/// Builds `dist/` and returns its path.
pub fn dist() -> Result<PathBuf, String> {
    let started = Instant::now();
    let root = util::root();
    step("validate content (assets/*.json)");
    crate::pages::validate_content()?;
    ensure_wasm_target()?;
    ensure_node_modules(&root)?;

    let modules = build_modules(&root)?;

    step("assemble dist/");
    let dist = root.join("dist");
    remove_dir(&dist)?;
    let web = root.join("web");
    if web.is_dir() {
        copy_tree(&web, &dist)?;
    } else {
        println!("warning: web/ does not exist; dist/ holds only pkg/");
    }
    step("minify main.js, did-not-start.js, style.css and instructor.js");
    for file in ["main.js", DID_NOT_START_JS, "style.css", INSTRUCTOR_JS] {
        if dist.join(file).is_file() {
            crate::minify::minify_in_place(&root, &dist.join(file))?;
        }
    }
    let instructor_js = name_by_content(&dist, INSTRUCTOR_JS)?;
    let shipped = ship_modules(&modules, &dist.join("pkg"))?;
    step("pages (navigation, home, one reading page per experiment)");
    crate::pages::render_site(&dist, &shipped, instructor_js.as_deref())?;
    check_relative_urls(&dist)?;
    let version = stamp_version(&dist)?;
    step("service worker (offline cache)");
    let (files, bytes) = crate::offline::write_service_worker(&dist, &version)?;
    println!(
        "sw.js caches {files} files, {} raw, as version {version}",
        util::human(bytes)
    );
    step("precompressed siblings (.gz, .br)");
    let (n, raw, gz, br) = crate::precompress::write_siblings(&dist)?;
    println!(
        "{n} files: {} raw, {} gzip -9, {} brotli -q 11",
        util::human(raw),
        util::human(gz),
        util::human(br)
    );

    println!(
        "dist/ ready ({} files) in {:.1} s",
        files_below(&dist)?.len(),
        started.elapsed().as_secs_f64()
    );
    Ok(dist)
}

/// Adds the wasm target through rustup when it is not installed.
pub fn ensure_wasm_target() -> Result<(), String> {
    let listed = Command::new("rustup")
        .args(["target", "list", "--installed"])
        .current_dir(util::root())
        .output();
    let listed = match listed {
        Ok(out) if out.status.success() => String::from_utf8_lossy(&out.stdout).into_owned(),
        _ => {
            // No rustup: the toolchain is managed some other way; cargo will
            // say clearly if the target's standard library is missing.
            println!("note: rustup not found; assuming the {WASM_TARGET} target is installed");
            return Ok(());
        }
    };
    if listed.lines().any(|l| l.trim() == WASM_TARGET) {
        return Ok(());
    }
    step(&format!("rustup target add {WASM_TARGET}"));
    util::run(
        Command::new("rustup")
            .args(["target", "add", WASM_TARGET])
            .current_dir(util::root()),
    )
}

/// Runs `npm ci` when `node_modules/` is missing or older than the lock file.
pub fn ensure_node_modules(root: &Path) -> Result<(), String> {
    let lock = root.join("package-lock.json");
    let lock_time = fs::metadata(&lock)
        .and_then(|m| m.modified())
        .map_err(|e| format!("cannot read {}: {e}", lock.display()))?;
    // npm rewrites node_modules/.package-lock.json on every install.
    let installed = [
        root.join("node_modules/.package-lock.json"),
        root.join("node_modules"),
    ]
    .iter()
    .find_map(|p| fs::metadata(p).and_then(|m| m.modified()).ok());
    let fresh = matches!(installed, Some(t) if t >= lock_time)
        && root.join("node_modules/.bin/wasm-opt").exists()
        && root.join("node_modules/.bin/esbuild").exists();
    if fresh {
        return Ok(());
    }
    let modules = root.join("node_modules");
    if fs::symlink_metadata(&modules).is_ok_and(|m| m.file_type().is_symlink()) {
        // `npm ci` empties the folder first: through a link it would empty
        // another checkout's node_modules (a git worktree sharing main's).
        return Err(format!(
            "{} is a symbolic link and looks older than package-lock.json: \
             refusing to run `npm ci` through it; replace the link with a copy \
             (or run `npm ci` where it points)",
            modules.display()
        ));
    }
    if !util::has_program("npm") {
        return Err(
            "npm is not installed: install Node.js 20 or newer with npm \
                    (Debian: apt-get install nodejs npm), then rerun"
                .into(),
        );
    }
    step("npm ci");
    util::run(
        Command::new("npm")
            .args(["ci", "--no-audit", "--no-fund"])
            .current_dir(root),
    )
}

/// The Instructor panel's code (`web/instructor.js`): not part of any
/// page's download; `main.js` fetches it the first time a panel is opened,
/// under the content-hashed name `index.html`'s `<meta name="lab-instructor">`
/// gives (see [`name_by_content`]).
pub const INSTRUCTOR_JS: &str = "instructor.js";

/// Renames `dist/<name>` (`stem.ext`) to `stem.<content hash>.ext`, so a host
/// may cache it for good and the service worker caches it by that name;
/// returns the new name, `None` when the file is not there.
fn name_by_content(dist: &Path, name: &str) -> Result<Option<String>, String> {
    let path = dist.join(name);
    if !path.is_file() {
        return Ok(None);
    }
    let bytes = fs::read(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let (stem, ext) = name.rsplit_once('.').unwrap_or((name, ""));
    let hashed = format!("{stem}.{}.{ext}", crate::modules::content_hash(&[&bytes]));
    fs::rename(&path, dist.join(&hashed))
        .map_err(|e| format!("cannot rename {} to {hashed}: {e}", path.display()))?;
    Ok(Some(hashed))
}

fn copy_tree(from: &Path, to: &Path) -> Result<(), String> {
    for rel in files_below(from)? {
        let dst = to.join(&rel);
        if let Some(parent) = dst.parent() {
            fs::create_dir_all(parent)
                .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
        }
        fs::copy(from.join(&rel), &dst).map_err(|e| {
            format!(
                "cannot copy {} to {}: {e}",
                from.join(&rel).display(),
                dst.display()
            )
        })?;
    }
    Ok(())
}

/// A URL found in a file: byte range of the value, the tag it sits in (HTML)
/// and the attribute or syntax that holds it.
#[derive(Debug, PartialEq)]
struct UrlRef {
    start: usize,
    end: usize,
    tag: String,
    kind: &'static str,
}

/// `src=`, `href=`, `action=`, `poster=` attribute values in HTML/SVG.
fn html_urls(text: &str) -> Vec<UrlRef> {
    let mut out = Vec::new();
    for attr in ["src", "href", "action", "poster"] {
        let pat = format!("{attr}=");
        let mut from = 0;
        while let Some(i) = text[from..].find(&pat) {
            let at = from + i;
            from = at + pat.len();
            // A whole attribute name: preceded by whitespace (not `data-src=`).
            let before = text[..at].chars().next_back();
            if !matches!(before, Some(c) if c.is_whitespace()) {
                continue;
            }
            let Some((start, end)) = attr_value(text, from) else {
                continue;
            };
            let tag_start = text[..at].rfind('<').map_or(at, |p| p + 1);
            let tag: String = text[tag_start..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric())
                .collect::<String>()
                .to_ascii_lowercase();
            out.push(UrlRef {
                start,
                end,
                tag,
                kind: attr_kind(attr),
            });
        }
    }
    out.sort_by_key(|u| u.start);
    out
}

fn attr_kind(attr: &str) -> &'static str {
    match attr {
        "src" => "src",
        "href" => "href",
        "action" => "action",
        _ => "poster",
    }
}

/// The value starting at byte `at` (quoted or bare): its byte range.
fn attr_value(text: &str, at: usize) -> Option<(usize, usize)> {
    let rest = &text[at..];
    let q = rest.chars().next()?;
    if q == '"' || q == '\'' {
        let len = rest[1..].find(q)?;
        Some((at + 1, at + 1 + len))
    } else {
        let len = rest
            .find(|c: char| c.is_whitespace() || c == '>')
            .unwrap_or(rest.len());
        Some((at, at + len))
    }
}

/// `url(…)` in CSS and module specifiers (`from "…"`, `import("…")`, `import "…"`) in JS.
fn code_urls(text: &str) -> Vec<UrlRef> {
    let mut out = Vec::new();
    for (pat, kind) in [
        ("url(", "url()"),
        ("from ", "import"),
        ("import(", "import"),
        ("import ", "import"),
    ] {
        let mut from = 0;
        while let Some(i) = text[from..].find(pat) {
            let at = from + i + pat.len();
            from = at;
            let rest = &text[at..];
            let Some(q) = rest.chars().next() else { break };
            let (start, end) = if q == '"' || q == '\'' {
                match rest[1..].find(q) {
                    Some(len) => (at + 1, at + 1 + len),
                    None => continue,
                }
            } else if kind == "url()" {
                match rest.find(')') {
                    Some(len) => (at, at + len),
                    None => continue,
                }
            } else {
                continue;
            };
            out.push(UrlRef {
                start,
                end,
                tag: String::new(),
                kind,
            });
        }
    }
    out
}

/// Problems with a URL for a site that must work under any sub-path and load
/// nothing from another origin.
fn url_problem(value: &str, r: &UrlRef) -> Option<&'static str> {
    let v = value.trim();
    if v.starts_with("//") || (v.contains("://") && !v.starts_with("data:")) {
        // A plain link the reader may follow is fine; a resource is not.
        if r.tag == "a" && r.kind == "href" {
            return None;
        }
        return Some("loads from another origin");
    }
    if v.starts_with('/') {
        return Some("is root-absolute (breaks hosting under a sub-path)");
    }
    None
}

/// Fails when a file copied from web/ references a root-absolute URL or
/// loads a resource from another origin.
fn check_relative_urls(dist: &Path) -> Result<(), String> {
    let mut problems = Vec::new();
    for rel in files_below(dist)? {
        let name = slash_path(&rel);
        if name.starts_with("pkg/") {
            continue; // generated glue: its only URL is `new URL(…, import.meta.url)`
        }
        let ext = rel.extension().and_then(|e| e.to_str()).unwrap_or("");
        let refs_of: fn(&str) -> Vec<UrlRef> = match ext {
            "html" | "htm" | "svg" => html_urls,
            "css" | "js" | "mjs" => code_urls,
            _ => continue,
        };
        let text = fs::read_to_string(dist.join(&rel))
            .map_err(|e| format!("cannot read dist/{name}: {e}"))?;
        let mut refs = refs_of(&text);
        if ext == "html" || ext == "htm" {
            refs.extend(code_urls(&text));
        }
        for r in refs {
            let value = &text[r.start..r.end];
            if let Some(why) = url_problem(value, &r) {
                problems.push(format!("dist/{name}: `{value}` {why}"));
            }
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "dist/ must use relative URLs only:\n  {}",
            problems.join("\n  ")
        ))
    }
}

/// Appends `?v=<hash of the whole site>` to every reference in the pages
/// a browser opens by their address ([`crate::pages::STAMPED_PAGES`]: `dist/index.html`,
/// `dist/check.html`) that names a file of dist/ (the stylesheets, `main.js`,
/// `check.js`, the icon), so a redeployed site is not served stale, and the
/// service worker caches each file under the address these pages ask for.
/// The wasm modules, their glue and the reading pages carry their own
/// content hash in their names (see [`crate::modules`]).
fn stamp_version(dist: &Path) -> Result<String, String> {
    let files: Vec<String> = files_below(dist)?
        .iter()
        .map(|p| slash_path(p))
        .filter(|p| p != "index.html")
        .collect();
    let mut hash_input = Vec::new();
    for f in &files {
        hash_input.extend_from_slice(f.as_bytes());
        hash_input.push(0);
        let bytes = fs::read(dist.join(f)).map_err(|e| format!("cannot read dist/{f}: {e}"))?;
        hash_input.extend_from_slice(&util::fnv1a(&bytes).to_le_bytes());
    }
    let version = format!("{:08x}", util::fnv1a(&hash_input) as u32);
    for page in crate::pages::STAMPED_PAGES {
        let path = dist.join(page);
        if page == "index.html" || path.is_file() {
            stamp_page(&path, &files, &version)?;
        }
    }
    println!("dist/index.html, dist/check.html: references stamped with ?v={version}");
    Ok(version)
}

/// The classic script that says so when a page's module script did not
/// run (web/did-not-start.js).
pub const DID_NOT_START_JS: &str = "did-not-start.js";

/// Writes `?v=<version>` after every reference of the page at `page` to one
/// of `files` (paths relative to dist/).
fn stamp_page(page: &Path, files: &[String], version: &str) -> Result<(), String> {
    let html =
        fs::read_to_string(page).map_err(|e| format!("cannot read {}: {e}", page.display()))?;
    let mut out = String::with_capacity(html.len() + 256);
    let mut last = 0;
    for r in html_urls(&html) {
        let value = &html[r.start..r.end];
        let (path, fragment) = match value.find('#') {
            Some(i) => (&value[..i], &value[i..]),
            None => (value, ""),
        };
        let clean = path.strip_prefix("./").unwrap_or(path);
        if clean.is_empty() || clean.contains('?') || !files.iter().any(|f| f == clean) {
            continue;
        }
        out.push_str(&html[last..r.start]);
        out.push_str(path);
        out.push_str("?v=");
        out.push_str(version);
        out.push_str(fragment);
        last = r.end;
    }
    out.push_str(&html[last..]);
    fs::write(page, out).map_err(|e| format!("cannot write {}: {e}", page.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A worktree whose node_modules links to another checkout's must not
    /// run `npm ci` (which empties the folder) through the link.
    #[cfg(unix)]
    #[test]
    fn a_stale_node_modules_link_is_refused_not_reinstalled_through() {
        let dir = std::env::temp_dir().join(format!("xtask-npm-link-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        let elsewhere = dir.join("elsewhere");
        let checkout = dir.join("checkout");
        fs::create_dir_all(elsewhere.join("kept")).unwrap();
        fs::create_dir_all(&checkout).unwrap();
        std::os::unix::fs::symlink(&elsewhere, checkout.join("node_modules")).unwrap();
        fs::write(checkout.join("package-lock.json"), "{}").unwrap();
        let refused = ensure_node_modules(&checkout).unwrap_err();
        assert!(refused.contains("symbolic link"), "{refused}");
        assert!(elsewhere.join("kept").is_dir());
        fs::remove_dir_all(&dir).unwrap();
    }

    /// `web/instructor.js` writes the links labcore's `route::parse` reads:
    /// the same key names and note length (it cannot import them).
    #[test]
    fn instructor_js_uses_labcores_link_keys() {
        use labcore::route;
        let js = fs::read_to_string(util::root().join("web").join(INSTRUCTOR_JS)).unwrap();
        for line in [
            format!("const NOTE_MAX_CHARS = {};", route::NOTE_MAX_CHARS),
            format!("const LOCK_KEY = \"{}\";", route::LOCK_KEY),
            format!("const HIDE_KEY = \"{}\";", route::HIDE_KEY),
            format!("const NOTE_KEY = \"{}\";", route::NOTE_KEY),
            format!("const ANSWER_KEY_KEY = \"{}\";", route::ANSWER_KEY_KEY),
            format!("const QUIZ_KEY = \"{}\";", route::QUIZ_KEY),
            format!("const VEILED_KEY = \"{}\";", route::VEILED_KEY),
            format!(
                "const RULE_KEYS = [\"{}\", \"{}\"];",
                route::ATTEMPTS_KEY,
                route::SCORE_KEY
            ),
        ] {
            assert!(js.contains(&line), "web/instructor.js lacks `{line}`");
        }
        for choice in route::AnswerKey::ALL {
            assert!(
                js.contains(&format!("<option value=\"{}\">", choice.slug())),
                "{choice:?}"
            );
        }
    }

    /// A file named by its content: a hash in the name, the old name gone.
    #[test]
    fn name_by_content_puts_the_hash_in_the_name() {
        let dir = std::env::temp_dir().join(format!("xtask-hash-name-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join("instructor.js"), "export {};").unwrap();
        let name = name_by_content(&dir, "instructor.js").unwrap().unwrap();
        assert!(
            crate::modules::is_content_hashed(Path::new(&name)),
            "{name}"
        );
        assert!(name.starts_with("instructor.") && name.ends_with(".js"));
        assert!(dir.join(&name).is_file() && !dir.join("instructor.js").exists());
        assert_eq!(name_by_content(&dir, "missing.js").unwrap(), None);
        fs::remove_dir_all(&dir).unwrap();
    }

    fn values(text: &str, refs: &[UrlRef]) -> Vec<String> {
        refs.iter()
            .map(|r| text[r.start..r.end].to_string())
            .collect()
    }

    #[test]
    fn finds_html_attribute_urls() {
        let html = r#"<link rel="icon" href="favicon.svg"><img data-src="x" src='a.png'><use href="f.svg#m"/><a href=https://x.org/>x</a>"#;
        let refs = html_urls(html);
        assert_eq!(
            values(html, &refs),
            ["favicon.svg", "a.png", "f.svg#m", "https://x.org/"]
        );
        assert_eq!(refs[0].tag, "link");
        assert_eq!(refs[3].tag, "a");
    }

    #[test]
    fn finds_code_urls() {
        let js = r#"import init from "./pkg/labweb.js"; const m = import('./x.js'); body { background: url(img/a.png) }"#;
        assert_eq!(
            values(js, &code_urls(js)),
            ["img/a.png", "./pkg/labweb.js", "./x.js"]
        );
    }

    #[test]
    fn flags_absolute_and_foreign_urls() {
        let r = |tag: &str, kind| UrlRef {
            start: 0,
            end: 0,
            tag: tag.into(),
            kind,
        };
        assert!(url_problem("/style.css", &r("link", "href")).is_some());
        assert!(url_problem("//cdn.x/a.js", &r("script", "src")).is_some());
        assert!(url_problem("https://cdn.x/a.js", &r("script", "src")).is_some());
        assert!(url_problem("https://doi.org/10.1/x", &r("a", "href")).is_none());
        assert!(url_problem("style.css", &r("link", "href")).is_none());
        assert!(url_problem("#/fk/aim", &r("a", "href")).is_none());
        assert!(url_problem("data:image/png;base64,AA", &r("img", "src")).is_none());
    }
}
