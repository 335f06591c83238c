//! Build-time pages: validates every content file and writes the
//! navigation, the home page and each experiment's article (reading tabs
//! filled in) into `dist/index.html`, so they show before the wasm loads.

use std::fs;
use std::path::Path;

/// Where the template wants the navigation and the pages.
const NAV_SLOT: &str = "<!--NAV-->";
const PAGES_SLOT: &str = "<!--PAGES-->";
const WASM_BYTES_SLOT: &str = "<!--WASM-BYTES-->";
const CSP_SLOT: &str = "<!--CSP-->";

/// The site's Content-Security-Policy: nothing inline (no `<script>` body, no
/// `on…=` handler, no `style="…"` attribute), nothing from another origin;
/// `'wasm-unsafe-eval'` lets the page compile its own wasm module, and
/// `data:`/`blob:` images are the canvas exports. `dist/index.html` carries
/// it as a `<meta http-equiv>` (for hosts that cannot set headers) and
/// `cargo xtask serve` sends it as a header. `frame-ancestors` is left out:
/// a meta policy cannot carry it.
pub const CONTENT_SECURITY_POLICY: &str = "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; \
     style-src 'self'; img-src 'self' data: blob:; worker-src 'self'; object-src 'none'; base-uri 'self'";

/// Every registered experiment's content file, read from `assets/` as it is
/// on disk now, parsed and validated; the error names the file and what is
/// wrong in it (the section, question or field).
pub fn validate_content() -> Result<(), String> {
    let mut problems = Vec::new();
    for entry in labcore::registry() {
        let path = crate::util::root().join(format!("assets/{}.json", entry.id));
        let text = fs::read_to_string(&path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        if let Err(e) = check_one(entry, &text) {
            problems.push(e);
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "content files are not valid:\n  {}",
            problems.join("\n  ")
        ))
    }
}

/// One content file's problem, prefixed with its path.
fn check_one(entry: &labcore::Entry, text: &str) -> Result<(), String> {
    entry
        .parse_content_text(text)
        .map(|_| ())
        .map_err(|e| format!("assets/{}.json: {e}", entry.id))
}

/// The HTML of every page: the home page, then one hidden article per
/// experiment (`main.js` shows the one the link names).
#[must_use]
pub fn pages_html() -> String {
    let mut html = labcore::content_html::home(crate::thumbs::thumbnail);
    for entry in labcore::registry() {
        let article =
            labcore::content_html::article(entry.id, entry.content().map_err(|e| e.to_string()));
        html.push_str(&article.replacen("<article ", "<article hidden ", 1));
    }
    html
}

/// Fills the slots of `dist/index.html`.
pub fn render_index(dist: &Path, wasm_bytes: Option<u64>) -> Result<(), String> {
    let index = dist.join("index.html");
    let template =
        fs::read_to_string(&index).map_err(|e| format!("cannot read {}: {e}", index.display()))?;
    for slot in [NAV_SLOT, PAGES_SLOT, CSP_SLOT] {
        if !template.contains(slot) {
            return Err(format!("web/index.html has no {slot} slot"));
        }
    }
    let meta = wasm_bytes.map_or(String::new(), |n| {
        format!("<meta name=\"lab-wasm-bytes\" content=\"{n}\">")
    });
    let html = template
        .replace(NAV_SLOT, &labcore::content_html::nav())
        .replace(PAGES_SLOT, &pages_html())
        .replace(WASM_BYTES_SLOT, &meta)
        .replace(CSP_SLOT, &csp_meta());
    fs::write(&index, html).map_err(|e| format!("cannot write {}: {e}", index.display()))
}

/// The policy as a `<meta http-equiv>` (first in `<head>`, so it covers
/// everything the page loads).
#[must_use]
pub fn csp_meta() -> String {
    format!("<meta http-equiv=\"Content-Security-Policy\" content=\"{CONTENT_SECURITY_POLICY}\">")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_content_file_is_valid() {
        validate_content().expect("content validates");
    }

    #[test]
    fn a_broken_content_file_is_named_with_its_field() {
        let entry = labcore::find("fk").expect("fk");
        let good = entry.content_json;
        assert!(check_one(entry, good).is_ok());
        let no_aim = good.replacen("\"aim\"", "\"aims\"", 1);
        let e = check_one(entry, &no_aim).unwrap_err();
        assert!(
            e.starts_with("assets/fk.json: ") && e.contains("aim"),
            "{e}"
        );
        let bad_json = &good[..good.len() / 2];
        let e = check_one(entry, bad_json).unwrap_err();
        assert!(
            e.starts_with("assets/fk.json: ") && e.contains("line"),
            "{e}"
        );
        let no_refs = good.replace("\"references\": [", "\"references\": [] , \"x\": [");
        assert!(check_one(entry, &no_refs).is_err());
    }

    #[test]
    fn pages_hold_every_experiment_hidden_and_the_home_page() {
        let html = pages_html();
        assert!(html.contains("data-page=\"home\""));
        for entry in labcore::registry() {
            assert!(html.contains(&format!(
                "<article hidden class=\"exp\" data-experiment=\"{}\"",
                entry.id
            )));
        }
    }

    #[test]
    fn the_policy_allows_nothing_inline_and_nothing_foreign() {
        let p = CONTENT_SECURITY_POLICY;
        assert!(!p.contains("unsafe-inline") && !p.contains("'unsafe-eval'"));
        assert!(
            !p.contains("frame-ancestors"),
            "a meta policy cannot carry it"
        );
        assert!(!p.contains('"') && !p.contains("  "));
        assert!(csp_meta().contains(&format!("content=\"{p}\"")));
    }
}
