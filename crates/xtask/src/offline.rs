//! Offline after one visit: fills in the service worker (`dist/sw.js`, from
//! `web/sw.js`) with the site's version and the list of every file it
//! caches on install.

use crate::util::{files_below, slash_path};
use std::fs;
use std::path::Path;

/// The files the worker caches, by the URL the site asks for them:
/// `name?v=<version>` where a page opened by its address (`index.html`,
/// `check.html`: [`crate::pages::STAMPED_PAGES`]) references the file with
/// the version stamp (the stylesheets, `main.js`, `check.js`, the manifest,
/// the icon), the plain name otherwise (content-hashed modules and pages,
/// icons, maps, the pages themselves). Leaves out the
/// worker itself and the `.gz`/`.br` siblings (the browser asks for the
/// file; a host picks the encoding).
pub fn cached_urls(dist: &Path, version: &str) -> Result<Vec<String>, String> {
    let mut pages = String::new();
    for page in crate::pages::STAMPED_PAGES {
        let path = dist.join(page);
        if page == "index.html" || path.is_file() {
            pages.push_str(
                &fs::read_to_string(&path).map_err(|e| format!("cannot read dist/{page}: {e}"))?,
            );
        }
    }
    let mut urls = Vec::new();
    for rel in files_below(dist)? {
        let name = slash_path(&rel);
        if name == "sw.js" || crate::precompress::is_sibling(&rel) {
            continue;
        }
        let stamped = format!("{name}?v={version}");
        if pages.contains(&format!("\"{stamped}\"")) {
            urls.push(stamped);
        } else {
            urls.push(name);
        }
    }
    urls.sort();
    Ok(urls)
}

/// Writes the version and the file list into `dist/sw.js`; returns how many
/// files and how many bytes (raw) the cache will hold.
pub fn write_service_worker(dist: &Path, version: &str) -> Result<(usize, u64), String> {
    let path = dist.join("sw.js");
    let template =
        fs::read_to_string(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    if !template.contains("\"__VERSION__\"") || !template.contains("__FILES__") {
        return Err("web/sw.js has no \"__VERSION__\" or __FILES__ slot".into());
    }
    let urls = cached_urls(dist, version)?;
    let mut bytes = 0;
    for u in &urls {
        let file = u.split('?').next().unwrap_or(u);
        bytes += fs::metadata(dist.join(file))
            .map_err(|e| format!("cannot stat dist/{file}: {e}"))?
            .len();
    }
    let list = format!(
        "[\n  {}\n]",
        urls.iter()
            .map(|u| format!("\"{u}\""))
            .collect::<Vec<_>>()
            .join(",\n  ")
    );
    let text = template
        .replace("\"__VERSION__\"", &format!("\"{version}\""))
        .replace("__FILES__", &list);
    fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok((urls.len(), bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_worker_caches_every_file_by_the_url_the_site_asks_for() {
        let dir = std::env::temp_dir().join(format!("lab-sw-test-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(dir.join("pkg")).unwrap();
        fs::write(
            dir.join("index.html"),
            "<link href=\"style.css?v=abc12345\"><script src=\"main.js?v=abc12345\"></script>",
        )
        .unwrap();
        for f in [
            "style.css",
            "style.css.gz",
            "main.js",
            "main.js.br",
            "pkg/control.0a1b2c3d.wasm",
        ] {
            fs::write(dir.join(f), "x").unwrap();
        }
        fs::write(
            dir.join("sw.js"),
            "const VERSION = \"__VERSION__\";\nconst FILES = __FILES__;\n",
        )
        .unwrap();
        let (n, bytes) = write_service_worker(&dir, "abc12345").unwrap();
        assert_eq!((n, bytes), (4, 4 + "<link href=\"style.css?v=abc12345\"><script src=\"main.js?v=abc12345\"></script>".len() as u64 - 1));
        let sw = fs::read_to_string(dir.join("sw.js")).unwrap();
        assert!(sw.contains("const VERSION = \"abc12345\";"));
        for u in [
            "\"index.html\"",
            "\"main.js?v=abc12345\"",
            "\"style.css?v=abc12345\"",
            "\"pkg/control.0a1b2c3d.wasm\"",
        ] {
            assert!(sw.contains(u), "{u} in {sw}");
        }
        assert!(!sw.contains(".gz\"") && !sw.contains(".br\"") && !sw.contains("\"sw.js\""));
        let _ = fs::remove_dir_all(&dir);
    }

    /// Issue 51 §5: "Check a report" offline lost its styles (check.html
    /// asks for `style.css?v=…`, cached only as the address index.html asks
    /// for, or not at all): the files check.html references stamped are
    /// cached under those addresses, and check.html itself is cached.
    #[test]
    fn check_html_offline_its_stamped_files_and_the_page_are_cached() {
        let dir = std::env::temp_dir().join(format!("lab-sw-check-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        fs::write(
            dir.join("index.html"),
            "<link href=\"style.css?v=abc12345\"><script src=\"main.js?v=abc12345\"></script>",
        )
        .unwrap();
        fs::write(
            dir.join("check.html"),
            "<link href=\"style.css?v=abc12345\"><link href=\"check.css?v=abc12345\">\
             <script src=\"check.js?v=abc12345\"></script>",
        )
        .unwrap();
        for f in ["style.css", "main.js", "check.css", "check.js"] {
            fs::write(dir.join(f), "x").unwrap();
        }
        let urls = cached_urls(&dir, "abc12345").unwrap();
        assert_eq!(
            urls,
            [
                "check.css?v=abc12345",
                "check.html",
                "check.js?v=abc12345",
                "index.html",
                "main.js?v=abc12345",
                "style.css?v=abc12345",
            ]
        );
        let _ = fs::remove_dir_all(&dir);
    }
}
