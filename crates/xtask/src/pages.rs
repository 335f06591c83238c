//! Build-time pages: validates every content file, writes the home page and
//! each experiment's article (reading tabs filled in) as reading pages of
//! their own (`dist/pages/<id>.<hash>.html`, which `main.js` fetches and
//! shows before any wasm loads), and fills `dist/index.html`, the shell.

use std::fs;
use std::path::Path;

/// Where the template wants the navigation and the pages.
const NAV_SLOT: &str = "<!--NAV-->";
const PAGES_SLOT: &str = "<!--PAGES-->";
/// What `#app` holds until `main.js` has fetched the page the link names.
const LOADING: &str = "<p class=\"loading\">Loading…</p>";
const MODULES_SLOT: &str = "<!--MODULES-->";
const CSP_SLOT: &str = "<!--CSP-->";

/// The pages a browser opens by their address, the shell and "Check a
/// report": their references carry the site's `?v=` stamp, and the service
/// worker caches the files under those addresses.
pub const STAMPED_PAGES: [&str; 2] = ["index.html", "check.html"];

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

/// The home page's HTML (what `index.html` carries besides the navigation).
#[must_use]
pub fn home_html() -> String {
    labpage::content_html::home(crate::thumbs::thumbnail)
}

/// One experiment's article (six tabs, reading tabs filled in), as its
/// reading page `pages/<id>.<hash>.html` holds it; `main.js` inserts it.
/// Its formulas were written as MathML from LaTeX when labcore was built,
/// accents in the form every browser engine draws over their letter (see
/// `labtex::accents`).
#[must_use]
pub fn article_html(entry: &labcore::Entry) -> String {
    labpage::content_html::article(entry.id, entry.content().map_err(|e| e.to_string()))
}

/// Writes the home page and each experiment's reading page into
/// `dist/pages/` and fills the slots of `dist/index.html`: the navigation,
/// the policy and the `<meta>` tags that tell `main.js` where each reading
/// page and wasm module are. `index.html` itself is the shell every page
/// shares, so an experiment page does not download the home page's pictures.
///
/// `instructor_js` is the Instructor panel's code (a name in dist/), which
/// `main.js` finds in `<meta name="lab-instructor" data-js="…">`.
pub fn render_site(
    dist: &Path,
    modules: &[crate::modules::Shipped],
    instructor_js: Option<&str>,
) -> Result<(), String> {
    let pages = dist.join("pages");
    fs::create_dir_all(&pages).map_err(|e| format!("cannot create {}: {e}", pages.display()))?;
    let mut metas = String::new();
    let reading = std::iter::once(("home", home_html()))
        .chain(labcore::registry().iter().map(|e| (e.id, article_html(e))));
    for (id, html) in reading {
        let name = format!(
            "{id}.{}.html",
            crate::modules::content_hash(&[html.as_bytes()])
        );
        fs::write(pages.join(&name), &html)
            .map_err(|e| format!("cannot write pages/{name}: {e}"))?;
        metas.push_str(&format!(
            "<meta name=\"lab-page\" content=\"{id}\" data-href=\"pages/{name}\">\n"
        ));
    }
    if let Some(js) = instructor_js {
        metas.push_str(&format!(
            "<meta name=\"lab-instructor\" data-js=\"{js}\">\n"
        ));
    }
    let mut module_metas = String::new();
    for m in modules {
        if m.key == crate::modules::REPORT_KEY {
            metas.push_str(&format!(
                "<meta name=\"lab-report\" data-js=\"{}\" data-wasm=\"{}\">\n",
                m.js, m.wasm
            ));
            continue;
        }
        module_metas.push_str(&format!(
            "<meta name=\"lab-module\" content=\"{}\" data-experiments=\"{}\" data-js=\"{}\" \
             data-wasm=\"{}\" data-bytes=\"{}\">\n",
            m.key,
            m.ids.join(" "),
            m.js,
            m.wasm,
            m.wasm_bytes
        ));
    }
    metas.push_str(&module_metas);
    // The "Check a report" page: the same policy, and the module list (it
    // loads only the module of the report's experiment).
    let check = dist.join("check.html");
    if check.is_file() {
        let template = fs::read_to_string(&check)
            .map_err(|e| format!("cannot read {}: {e}", check.display()))?;
        for slot in [CSP_SLOT, MODULES_SLOT] {
            if !template.contains(slot) {
                return Err(format!("web/check.html has no {slot} slot"));
            }
        }
        let html = template
            .replace(MODULES_SLOT, module_metas.trim_end())
            .replace(CSP_SLOT, &csp_meta());
        fs::write(&check, html).map_err(|e| format!("cannot write {}: {e}", check.display()))?;
    }
    let index = dist.join("index.html");
    let template =
        fs::read_to_string(&index).map_err(|e| format!("cannot read {}: {e}", index.display()))?;
    for slot in [NAV_SLOT, PAGES_SLOT, CSP_SLOT, MODULES_SLOT] {
        if !template.contains(slot) {
            return Err(format!("web/index.html has no {slot} slot"));
        }
    }
    let html = template
        .replace(NAV_SLOT, &labpage::content_html::nav())
        .replace(PAGES_SLOT, LOADING)
        .replace(MODULES_SLOT, metas.trim_end())
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

    /// WebKit draws a `<mover>` accent with a plain `<mo>˙</mo>` well above
    /// and to the left of its letter: every accent on a reading page must be
    /// in the portable form (issue 24; `tests/e2e/browsers.test.mjs` checks
    /// where the engines draw it).
    #[test]
    fn webkit_accents_every_accent_on_the_reading_pages_is_in_the_portable_form() {
        let mut portable = 0;
        for entry in labcore::registry() {
            let html = article_html(entry);
            assert_eq!(
                labtex::accents::non_portable(&html),
                Vec::<String>::new(),
                "{}",
                entry.id
            );
            portable += html.matches("<mover accent=\"true\">").count();
        }
        // θ̇, θ̈, μ̄, P̄, x̂ … on the cartpole, ekf, pid, dls, diffdrive and
        // workspace pages.
        assert!(portable >= 49, "{portable} accents");
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

    /// Issue 27 §3: the build fails naming the file and the key when the
    /// content names an equation the experiment lacks, or marks a symbol
    /// `\live{key}{…}` whose key is none of its quantities.
    #[test]
    fn live_an_unknown_equation_or_live_key_fails_naming_the_file_and_key() {
        let entry = labcore::find("fk").expect("fk");
        let good = entry.content_json;
        let e = check_one(
            entry,
            &good.replacen("\"math\": [\"x\"", "\"math\": [\"z\"", 1),
        )
        .unwrap_err();
        assert!(
            e.starts_with("assets/fk.json: math: no equation with key “z”"),
            "{e}"
        );
        let e = check_one(
            entry,
            &good.replacen(
                "\"aim\": [\n    \"",
                "\"aim\": [\n    \"$\\\\live{tip}{p}$ ",
                1,
            ),
        )
        .unwrap_err();
        assert!(
            e.starts_with(
                "assets/fk.json: aim paragraph 1: \\live{tip}: no quantity with key “tip”"
            ),
            "{e}"
        );
    }

    /// Issue 27 §1: a formula that does not convert from LaTeX fails the
    /// build's content check naming the file, the field and the position.
    #[test]
    fn latex_a_broken_formula_is_named_with_file_field_and_position() {
        let entry = labcore::find("fk").expect("fk");
        let broken = entry
            .content_json
            .replacen("$\\\\theta_1$", "$\\\\theta_1 + \\\\frac{1}$", 1);
        assert_ne!(broken, entry.content_json);
        let e = check_one(entry, &broken).unwrap_err();
        assert!(
            e.starts_with("assets/fk.json: theory[")
                && e.contains("].paragraph: LaTeX error at character ")
                && e.contains("`\\theta_1 + \\frac{1}`"),
            "{e}"
        );
    }

    #[test]
    fn every_experiment_has_a_reading_page_and_the_home_page_links_it() {
        let home = home_html();
        assert!(home.contains("data-page=\"home\""));
        assert!(
            !home.contains("<article"),
            "the home page carries no article"
        );
        for entry in labcore::registry() {
            assert!(
                home.contains(&format!("href=\"#/{}/aim\"", entry.id)),
                "{}",
                entry.id
            );
            let article = article_html(entry);
            assert!(article.starts_with(&format!(
                "<article class=\"exp\" data-experiment=\"{}\"",
                entry.id
            )));
            for tab in [
                "aim",
                "theory",
                "procedure",
                "simulation",
                "quiz",
                "references",
            ] {
                assert!(
                    article.contains(&format!("data-panel=\"{tab}\"")),
                    "{} {tab}",
                    entry.id
                );
            }
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
