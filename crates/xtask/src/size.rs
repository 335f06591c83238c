//! `cargo xtask size`: raw and gzip -9 size of every file in dist/.

use crate::util::{self, files_below, human, slash_path};
use std::path::Path;

/// Most gzip bytes the home page may download (index.html and everything it
/// loads before any interaction).
pub const FIRST_PAGE_BUDGET_GZIP: u64 = 150 * 1024;
use flate2::write::GzEncoder;
use flate2::Compression;
use std::io::Write;

pub fn gzip_len(bytes: &[u8]) -> u64 {
    let mut enc = GzEncoder::new(Vec::new(), Compression::best());
    enc.write_all(bytes).expect("writing to a Vec cannot fail");
    enc.finish().expect("writing to a Vec cannot fail").len() as u64
}

pub fn size() -> Result<(), String> {
    let dist = util::root().join("dist");
    if !dist.join("pkg").is_dir() {
        return Err("dist/ is not built: run `cargo xtask dist` first".into());
    }
    let mut rows = Vec::new();
    for rel in files_below(&dist)? {
        // The .gz/.br siblings are other encodings of the same files.
        if crate::precompress::is_sibling(&rel) {
            continue;
        }
        let bytes = std::fs::read(dist.join(&rel))
            .map_err(|e| format!("cannot read dist/{}: {e}", rel.display()))?;
        rows.push((slash_path(&rel), bytes.len() as u64, gzip_len(&bytes)));
    }
    let width = rows.iter().map(|r| r.0.len()).max().unwrap_or(4).max(5);
    println!("{:<width$}  {:>12}  {:>12}", "file", "raw", "gzip -9");
    println!("{:-<width$}  {:->12}  {:->12}", "", "", "");
    let (mut raw, mut gz) = (0, 0);
    for (name, r, g) in &rows {
        println!("{name:<width$}  {:>12}  {:>12}", human(*r), human(*g));
        raw += r;
        gz += g;
    }
    println!("{:-<width$}  {:->12}  {:->12}", "", "", "");
    println!(
        "{:<width$}  {:>12}  {:>12}",
        format!("total ({} files)", rows.len()),
        human(raw),
        human(gz)
    );
    println!("(exact bytes: raw {raw}, gzip {gz})");
    let (files, first) = first_page(&dist)?;
    println!(
        "first page (home): {} gzip in {} files ({}); budget {}",
        human(first),
        files.len(),
        files.join(", "),
        human(FIRST_PAGE_BUDGET_GZIP)
    );
    Ok(())
}

/// The files the home page loads — `index.html`, what its `<link>` and
/// `<script>` tags name, those scripts' static imports (not the `import()`
/// of a wasm module's glue, which waits for an experiment) and the home's
/// reading page — and their total gzip size.
pub fn first_page(dist: &Path) -> Result<(Vec<String>, u64), String> {
    let read = |name: &str| {
        std::fs::read(dist.join(name)).map_err(|e| format!("cannot read dist/{name}: {e}"))
    };
    let html = String::from_utf8_lossy(&read("index.html")?).into_owned();
    let mut files = vec!["index.html".to_owned()];
    // ` href=` and ` src=` only: a `data-href` (where `main.js` finds the
    // reading pages) is not something the page loads by itself.
    let mut queue: Vec<String> = referenced(&html, &[" href=\"", " src=\""]);
    while let Some(name) = queue.pop() {
        if files.contains(&name) || !dist.join(&name).is_file() {
            continue;
        }
        if name.ends_with(".js") {
            let text = String::from_utf8_lossy(&read(&name)?).into_owned();
            let dir = name.rsplit_once('/').map_or("", |(d, _)| d);
            for dep in referenced(&text, &["from \"", "import \""]) {
                queue.push(if dir.is_empty() {
                    dep
                } else {
                    format!("{dir}/{dep}")
                });
            }
        }
        files.push(name);
    }
    // main.js fetches the home page's own reading page.
    if let Some(home) = reading_page(&html, "home") {
        files.push(home);
    }
    let mut total = 0;
    for f in &files {
        total += gzip_len(&read(f)?);
    }
    Ok((files, total))
}

/// The reading page `main.js` fetches for `id` (`<meta name="lab-page">`).
fn reading_page(html: &str, id: &str) -> Option<String> {
    let tag = format!("<meta name=\"lab-page\" content=\"{id}\" data-href=\"");
    let rest = &html[html.find(&tag)? + tag.len()..];
    Some(rest[..rest.find('"')?].to_owned())
}

/// Relative file names after any of `prefixes` (`./` and `?v=…` removed;
/// fragments, hashes and other origins skipped).
fn referenced(text: &str, prefixes: &[&str]) -> Vec<String> {
    let mut out = Vec::new();
    for prefix in prefixes {
        let mut rest = text;
        while let Some(i) = rest.find(prefix) {
            rest = &rest[i + prefix.len()..];
            let Some(end) = rest.find('"') else { break };
            let value = &rest[..end];
            let path = value.split(['?', '#']).next().unwrap_or("");
            let path = path.strip_prefix("./").unwrap_or(path);
            if !path.is_empty() && !path.contains(':') && !path.starts_with('/') {
                out.push(path.to_owned());
            }
        }
    }
    out
}

/// Fails when the home page downloads more than [`FIRST_PAGE_BUDGET_GZIP`].
pub fn check_first_page_budget() -> Result<(), String> {
    let (files, total) = first_page(&util::root().join("dist"))?;
    println!(
        "first page: {} gzip ({} bytes) in {}; budget {}",
        human(total),
        total,
        files.join(", "),
        human(FIRST_PAGE_BUDGET_GZIP)
    );
    if total > FIRST_PAGE_BUDGET_GZIP {
        return Err(format!(
            "the home page downloads {} gzip, over its budget of {}",
            human(total),
            human(FIRST_PAGE_BUDGET_GZIP)
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_data_href_is_not_a_reference() {
        let html = r#"<link rel="stylesheet" href="style.css"><meta name="lab-page" content="fk" data-href="pages/fk.0a1b2c3d.html"><script type="module" src="main.js"></script>"#;
        assert_eq!(
            referenced(html, &[" href=\"", " src=\""]),
            ["style.css", "main.js"]
        );
    }

    #[test]
    fn finds_the_reading_page_of_an_id() {
        let html = r#"<meta name="lab-page" content="home" data-href="pages/home.0a1b2c3d.html">"#;
        assert_eq!(
            reading_page(html, "home").as_deref(),
            Some("pages/home.0a1b2c3d.html")
        );
        assert_eq!(reading_page(html, "fk"), None);
    }

    #[test]
    fn finds_static_references_only() {
        let html = r##"<link href="style.css?v=1"><script src="./main.js?v=2"></script><a href="#/fk/aim">x</a><a href="https://x.org/">y</a>"##;
        assert_eq!(
            referenced(html, &["href=\"", "src=\""]),
            ["style.css", "main.js"]
        );
        let js = r#"import a from "./a.js"; import "./b.js"; const g = await import("./pkg/labweb.js");"#;
        assert_eq!(referenced(js, &["from \"", "import \""]), ["a.js", "b.js"]);
    }
}
