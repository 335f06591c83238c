//! `cargo xtask dist --scorm`: the built site as a SCORM 1.2 content package,
//! `dist-scorm/` (a copy of `dist/` with `imsmanifest.xml` at its root) and
//! `dist-scorm.zip` beside it, the file an instructor uploads to an LMS.
//!
//! **One SCO per experiment.** Each experiment is its own `<item>` with its
//! own launch URL (`index.html?sco=<id>`: a query, which LMSs keep, where
//! some drop a `#` fragment; `web/main.js` opens the experiment's Aim tab
//! and `web/scorm.js` reports that experiment's quiz only). An LMS keeps the SCORM data
//! model per SCO, so each experiment gets its own `lesson_status`, score and
//! `suspend_data`: every experiment's quiz is recorded beside the others
//! and a relaunch resumes the right attempt. One SCO for the whole lab would
//! have one score and one 4,096-character `suspend_data` for every quiz. Every SCO launches
//! the same `index.html`; the files are listed once, in a shared `asset`
//! resource that each SCO depends on.
//!
//! **No `parameters` attribute.** SCORM 1.2 lets an `<item>` carry
//! `parameters` that the LMS joins to the resource's href. The package puts
//! the query in the href instead: every LMS launches an href as written,
//! while LMSs join `parameters` each their own way (some ignore it, some
//! add it after a second `?`). What a mangled or lost launch query does is
//! handled at run time: `labcore::lms::launch` and `web/scorm.js` read the
//! leading id of `sco=` and treat a later `?` as `&`, and a launch inside
//! an LMS that names no SCO says on the page, and in `cmi.comments`, that
//! no score will be recorded.
//!
//! **Grading rules.** `--attempts N|unlimited` and `--score best|last|first`
//! go into every launch URL (`index.html?sco=pid&attempts=2&score=last`),
//! with the meaning of an instructor link's keys (`labcore::route`); the
//! page holds them for the whole SCO session, whatever link is opened in
//! it. Left out: any number of attempts, the best one counts.
//!
//! The package holds no precompressed `.gz`/`.br` siblings: an LMS serves
//! the plain files, so they would only make the upload bigger.
//!
//! Reference: ADL, *SCORM Version 1.2 Content Aggregation Model* (2001),
//! §2.3.5 (manifest, `adlcp:scormtype`, `adlcp:masteryscore`).

use crate::util;
use labcore::layout::html::escape;
use labcore::route::{Instructor, QuizRules};
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The IMS Content Packaging 1.1.2 namespace (the SCORM 1.2 manifest root).
pub const IMSCP_NS: &str = "http://www.imsproject.org/xsd/imscp_rootv1p1p2";
/// The ADL SCORM 1.2 extension namespace (`adlcp:scormtype`, `adlcp:masteryscore`).
pub const ADLCP_NS: &str = "http://www.adlnet.org/xsd/adlcp_rootv1p2";
/// Percentage of the quiz a student needs to pass (`adlcp:masteryscore`);
/// `web/scorm.js` reads it back as `cmi.student_data.mastery_score` and
/// falls back to the same 70 when an LMS does not pass it on.
pub const MASTERY_PERCENT: u32 = 70;
/// The package manifest's file name, at the package root.
pub const MANIFEST: &str = "imsmanifest.xml";

/// One SCO: an experiment's id (its route) and title.
#[derive(Clone, Debug)]
pub struct Sco {
    pub id: String,
    pub title: String,
}

/// Every registered experiment, in registry order, with its content title.
pub fn experiments() -> Vec<Sco> {
    labcore::registry()
        .iter()
        .map(|e| Sco {
            id: e.id.to_owned(),
            title: e
                .content()
                .map_or_else(|_| e.id.to_owned(), |c| c.title.clone()),
        })
        .collect()
}

/// The grading rules of `--attempts N|unlimited` and `--score
/// best|last|first` (each at most once) in `args`, read as an instructor
/// link's `attempts=`/`score=`; any other argument is an error.
pub fn parse_rules(args: &[String]) -> Result<QuizRules, String> {
    let mut pairs = Vec::new();
    let mut rest = args.iter();
    while let Some(flag) = rest.next() {
        let key = match flag.as_str() {
            "--attempts" => labcore::route::ATTEMPTS_KEY,
            "--score" => labcore::route::SCORE_KEY,
            other => return Err(format!("unknown option `{other}`")),
        };
        let value = rest.next().ok_or_else(|| format!("{flag} needs a value"))?;
        if pairs.iter().any(|(k, _)| *k == key) {
            return Err(format!("{flag} given twice"));
        }
        pairs.push((key, labcore::route::encode(value)));
    }
    let query: Vec<String> = pairs.iter().map(|(k, v)| format!("{k}={v}")).collect();
    let route = labcore::route::parse(&format!("#/x?{}", query.join("&")), &["x"]);
    match route.notices.first() {
        Some(problem) => Err(problem.clone()),
        None => Ok(route.instructor.quiz),
    }
}

/// Builds `dist-scorm/` and `dist-scorm.zip` next to `dist` from it, every
/// SCO launched with `rules`. Returns (folder, zip).
pub fn package(dist: &Path, rules: &QuizRules) -> Result<(PathBuf, PathBuf), String> {
    let parent = dist.parent().unwrap_or(Path::new("."));
    let folder = parent.join("dist-scorm");
    let zip = parent.join("dist-scorm.zip");
    let files = write_package(dist, &folder, &zip, &experiments(), rules)?;
    let raw: u64 = files
        .iter()
        .filter_map(|f| fs::metadata(folder.join(f)).ok())
        .map(|m| m.len())
        .sum();
    let zipped = fs::metadata(&zip)
        .map_err(|e| format!("cannot stat {}: {e}", zip.display()))?
        .len();
    let launch = launch_href("<id>", rules);
    println!(
        "dist-scorm/ ready: {} files, {} unzipped; dist-scorm.zip {} (SCORM 1.2, {} SCOs, launched as {launch})",
        files.len(),
        util::human(raw),
        util::human(zipped),
        experiments().len()
    );
    Ok((folder, zip))
}

/// Copies `dist` into `folder` (without precompressed siblings), writes the
/// manifest for `scos` (launched with `rules`) and zips the folder into
/// `zip`. Returns every file of the package (slash paths, manifest first).
pub fn write_package(
    dist: &Path,
    folder: &Path,
    zip: &Path,
    scos: &[Sco],
    rules: &QuizRules,
) -> Result<Vec<String>, String> {
    if !dist.join("index.html").is_file() {
        return Err(format!("{} has no index.html", dist.display()));
    }
    if folder.exists() {
        fs::remove_dir_all(folder)
            .map_err(|e| format!("cannot remove {}: {e}", folder.display()))?;
    }
    let mut site = Vec::new();
    for rel in util::files_below(dist)? {
        if crate::precompress::is_sibling(&rel) {
            continue;
        }
        let to = folder.join(&rel);
        if let Some(p) = to.parent() {
            fs::create_dir_all(p).map_err(|e| format!("cannot create {}: {e}", p.display()))?;
        }
        fs::copy(dist.join(&rel), &to)
            .map_err(|e| format!("cannot copy to {}: {e}", to.display()))?;
        site.push(util::slash_path(&rel));
    }
    site.sort();
    let manifest = manifest_xml(scos, &site, rules);
    fs::write(folder.join(MANIFEST), &manifest)
        .map_err(|e| format!("cannot write {MANIFEST}: {e}"))?;
    let mut all = vec![MANIFEST.to_owned()];
    all.extend(site);
    write_zip(folder, &all, zip)?;
    Ok(all)
}

/// `imsmanifest.xml` for `scos`, every one launching `index.html?sco=<id>`
/// (with `rules`) and depending on one asset resource that lists `files`.
#[must_use]
pub fn manifest_xml(scos: &[Sco], files: &[String], rules: &QuizRules) -> String {
    let mut x = String::new();
    x.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    x.push_str(&format!(
        "<manifest identifier=\"robotics-virtual-lab\" version=\"1.0\" xmlns=\"{IMSCP_NS}\" xmlns:adlcp=\"{ADLCP_NS}\">\n"
    ));
    x.push_str("  <metadata>\n    <schema>ADL SCORM</schema>\n    <schemaversion>1.2</schemaversion>\n  </metadata>\n");
    x.push_str("  <organizations default=\"lab\">\n    <organization identifier=\"lab\">\n");
    x.push_str("      <title>Robotics virtual lab</title>\n");
    for s in scos {
        let id = xml_id(&s.id);
        x.push_str(&format!(
            "      <item identifier=\"item-{id}\" identifierref=\"sco-{id}\" isvisible=\"true\">\n        <title>{}</title>\n        <adlcp:masteryscore>{MASTERY_PERCENT}</adlcp:masteryscore>\n      </item>\n",
            escape(&s.title)
        ));
    }
    x.push_str("    </organization>\n  </organizations>\n  <resources>\n");
    for s in scos {
        x.push_str(&format!(
            "    <resource identifier=\"sco-{}\" type=\"webcontent\" adlcp:scormtype=\"sco\" href=\"{}\">\n      <file href=\"index.html\"/>\n      <dependency identifierref=\"lab-files\"/>\n    </resource>\n",
            xml_id(&s.id),
            escape(&launch_href(&s.id, rules))
        ));
    }
    x.push_str(
        "    <resource identifier=\"lab-files\" type=\"webcontent\" adlcp:scormtype=\"asset\">\n",
    );
    for f in files {
        x.push_str(&format!("      <file href=\"{}\"/>\n", escape(f)));
    }
    x.push_str("    </resource>\n  </resources>\n</manifest>\n");
    x
}

/// The launch URL of an experiment's SCO: the experiment in the query (no
/// fragment, which some LMSs drop), then the grading rules that are not
/// the defaults (`index.html?sco=pid&attempts=2&score=last`).
#[must_use]
pub fn launch_href(id: &str, rules: &QuizRules) -> String {
    let rules = Instructor {
        quiz: *rules,
        ..Instructor::default()
    };
    let mut href = format!("index.html?sco={id}");
    for pair in rules.query() {
        href.push('&');
        href.push_str(&pair);
    }
    href
}

/// An experiment id as an XML `ID` (letters, digits, `-`, `_`, `.`; the
/// registry's ids already are).
fn xml_id(id: &str) -> String {
    id.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Zips `files` of `folder` (deflate) into `out`, in the order given.
fn write_zip(folder: &Path, files: &[String], out: &Path) -> Result<(), String> {
    let file =
        fs::File::create(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let mut zip = zip::ZipWriter::new(std::io::BufWriter::new(file));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .compression_level(Some(9));
    for f in files {
        let bytes = fs::read(folder.join(f)).map_err(|e| format!("cannot read {f}: {e}"))?;
        zip.start_file(f.as_str(), options)
            .map_err(|e| format!("zip {f}: {e}"))?;
        zip.write_all(&bytes).map_err(|e| format!("zip {f}: {e}"))?;
    }
    zip.finish()
        .map_err(|e| format!("cannot finish {}: {e}", out.display()))?
        .flush()
        .map_err(|e| format!("cannot write {}: {e}", out.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("xtask-scorm-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// A small built site: index, script, wasm and precompressed siblings.
    fn fake_dist(dir: &Path) {
        for (f, body) in [
            ("index.html", "<!doctype html><title>lab</title>"),
            ("main.js", "console.log(1);"),
            ("scorm.js", "export {};"),
            ("pkg/labweb_bg.wasm", "\0asm"),
            ("main.js.gz", "gz"),
            ("main.js.br", "br"),
        ] {
            let p = dir.join(f);
            fs::create_dir_all(p.parent().unwrap()).unwrap();
            fs::write(p, body).unwrap();
        }
    }

    #[test]
    fn manifest_is_scorm_1_2_with_one_sco_per_experiment() {
        let scos = experiments();
        assert_eq!(scos.len(), labcore::registry().len());
        let text = manifest_xml(
            &scos,
            &["index.html".into(), "main.js".into()],
            &QuizRules::default(),
        );
        let doc = roxmltree::Document::parse(&text).expect("well-formed XML");
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "manifest");
        assert_eq!(root.tag_name().namespace(), Some(IMSCP_NS));
        let version = doc
            .descendants()
            .find(|n| n.has_tag_name("schemaversion"))
            .and_then(|n| n.text());
        assert_eq!(version, Some("1.2"));
        let schema = doc.descendants().find(|n| n.has_tag_name("schema"));
        assert_eq!(schema.and_then(|n| n.text()), Some("ADL SCORM"));

        let items: Vec<_> = doc
            .descendants()
            .filter(|n| n.has_tag_name((IMSCP_NS, "item")))
            .collect();
        let scormtype = (ADLCP_NS, "scormtype");
        let sco_resources: Vec<_> = doc
            .descendants()
            .filter(|n| n.has_tag_name((IMSCP_NS, "resource")))
            .filter(|n| n.attribute(scormtype) == Some("sco"))
            .collect();
        assert_eq!(items.len(), scos.len());
        assert_eq!(sco_resources.len(), scos.len());
        for (s, item) in scos.iter().zip(&items) {
            let resource = sco_resources
                .iter()
                .find(|r| r.attribute("identifier") == item.attribute("identifierref"))
                .unwrap_or_else(|| panic!("item of {} names no SCO resource", s.id));
            assert_eq!(
                resource.attribute("href"),
                Some(format!("index.html?sco={}", s.id).as_str())
            );
            let title = item.children().find(|n| n.has_tag_name("title"));
            assert_eq!(title.and_then(|n| n.text()), Some(s.title.as_str()));
            let mastery = item
                .children()
                .find(|n| n.has_tag_name((ADLCP_NS, "masteryscore")));
            assert_eq!(mastery.and_then(|n| n.text()), Some("70"));
            // Each SCO reaches the shared files through its dependency.
            let dep = resource
                .children()
                .find(|n| n.has_tag_name("dependency"))
                .and_then(|n| n.attribute("identifierref"));
            assert_eq!(dep, Some("lab-files"));
        }
        // Identifiers are unique (xs:ID).
        let mut ids: Vec<_> = doc
            .descendants()
            .filter_map(|n| n.attribute("identifier"))
            .collect();
        let n = ids.len();
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(ids.len(), n);
        // A default organization that exists.
        let orgs = doc
            .descendants()
            .find(|n| n.has_tag_name("organizations"))
            .unwrap();
        assert_eq!(orgs.attribute("default"), Some("lab"));
    }

    #[test]
    fn titles_are_escaped() {
        let text = manifest_xml(
            &[Sco {
                id: "a b".into(),
                title: "Forces & <moments> \"quoted\"".into(),
            }],
            &["x&y.html".into()],
            &QuizRules::default(),
        );
        let doc = roxmltree::Document::parse(&text).unwrap();
        let title = doc
            .descendants()
            .filter(|n| n.has_tag_name("title"))
            .nth(1)
            .and_then(|n| n.text());
        assert_eq!(title, Some("Forces & <moments> \"quoted\""));
        assert!(doc
            .descendants()
            .any(|n| n.attribute("identifier") == Some("sco-a_b")));
    }

    #[test]
    fn package_references_only_files_it_holds_and_zips_them_all() {
        let dir = temp("pkg");
        let dist = dir.join("dist");
        fake_dist(&dist);
        let folder = dir.join("dist-scorm");
        let zip_path = dir.join("dist-scorm.zip");
        let scos = experiments();
        let files = write_package(&dist, &folder, &zip_path, &scos, &QuizRules::default()).unwrap();
        assert_eq!(
            files,
            [
                "imsmanifest.xml",
                "index.html",
                "main.js",
                "pkg/labweb_bg.wasm",
                "scorm.js"
            ]
        );
        // Every file the manifest names exists in the package.
        let text = fs::read_to_string(folder.join(MANIFEST)).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let hrefs: Vec<&str> = doc
            .descendants()
            .filter(|n| n.has_tag_name("file"))
            .filter_map(|n| n.attribute("href"))
            .collect();
        assert!(hrefs.len() > scos.len());
        for h in &hrefs {
            assert!(folder.join(h).is_file(), "{h} is named but missing");
        }
        // Launch URLs name an existing file before their query, and carry
        // no fragment (some LMSs drop it).
        for r in doc.descendants().filter(|n| n.has_tag_name("resource")) {
            if let Some(href) = r.attribute("href") {
                assert!(!href.contains('#'), "{href}");
                let file = href.split('?').next().unwrap();
                assert!(folder.join(file).is_file(), "{href}");
            }
        }
        // No precompressed sibling is shipped, and every site file is listed.
        assert!(!folder.join("main.js.gz").exists());
        assert!(!folder.join("main.js.br").exists());
        for f in files.iter().filter(|f| *f != MANIFEST) {
            assert!(hrefs.contains(&f.as_str()), "{f} not in the manifest");
        }

        // The zip lists every file of the folder, deflated, with its bytes.
        let mut archive = zip::ZipArchive::new(fs::File::open(&zip_path).unwrap()).unwrap();
        let names: Vec<String> = (0..archive.len())
            .map(|i| archive.by_index(i).unwrap().name().unwrap().into_owned())
            .collect();
        let mut on_disk: Vec<String> = util::files_below(&folder)
            .unwrap()
            .iter()
            .map(|p| util::slash_path(p))
            .collect();
        on_disk.sort();
        let mut sorted = names.clone();
        sorted.sort();
        assert_eq!(sorted, on_disk);
        assert_eq!(names[0], MANIFEST, "manifest first");
        for name in &names {
            let mut entry = archive.by_name(name).unwrap();
            assert_eq!(entry.compression(), zip::CompressionMethod::Deflated);
            let mut bytes = Vec::new();
            std::io::Read::read_to_end(&mut entry, &mut bytes).unwrap();
            assert_eq!(bytes, fs::read(folder.join(name)).unwrap(), "{name}");
        }

        // A second run replaces the package (no stale file survives).
        fs::remove_file(dist.join("scorm.js")).unwrap();
        let again = write_package(&dist, &folder, &zip_path, &scos, &QuizRules::default()).unwrap();
        assert!(!again.contains(&"scorm.js".to_owned()));
        assert!(!folder.join("scorm.js").exists());
        let archive = zip::ZipArchive::new(fs::File::open(&zip_path).unwrap()).unwrap();
        assert_eq!(archive.len(), again.len());
        fs::remove_dir_all(&dir).unwrap();
    }

    /// Issue 24 §2: a SCO's launch does not depend on the `#` fragment.
    #[test]
    fn launch_without_fragment_names_the_sco_in_the_query() {
        let scos = experiments();
        let text = manifest_xml(&scos, &["index.html".into()], &QuizRules::default());
        let doc = roxmltree::Document::parse(&text).unwrap();
        let hrefs: Vec<&str> = doc
            .descendants()
            .filter(|n| n.attribute((ADLCP_NS, "scormtype")) == Some("sco"))
            .filter_map(|n| n.attribute("href"))
            .collect();
        assert_eq!(hrefs.len(), scos.len());
        for (s, href) in scos.iter().zip(&hrefs) {
            assert_eq!(*href, format!("index.html?sco={}", s.id));
        }
    }

    /// Issue 24 §2: `--attempts` and `--score` reach every launch URL, with
    /// the instructor link's meaning; bad values are clear errors.
    #[test]
    fn attempts_and_score_options_reach_every_launch() {
        let args = |a: &[&str]| a.iter().map(|s| (*s).to_owned()).collect::<Vec<_>>();
        let rules = parse_rules(&args(&["--attempts", "2", "--score", "last"])).unwrap();
        assert_eq!(rules.attempts, Some(2));
        assert_eq!(rules.score, labcore::route::ScoreRule::Last);
        assert_eq!(
            launch_href("pid", &rules),
            "index.html?sco=pid&attempts=2&score=last"
        );
        let text = manifest_xml(&experiments(), &["index.html".into()], &rules);
        assert!(text.contains("href=\"index.html?sco=pid&amp;attempts=2&amp;score=last\""));
        roxmltree::Document::parse(&text).expect("well-formed with the rules");
        // The defaults write nothing.
        let default = parse_rules(&args(&["--attempts", "unlimited", "--score", "best"])).unwrap();
        assert_eq!(default, QuizRules::default());
        assert_eq!(launch_href("pid", &default), "index.html?sco=pid");
        assert_eq!(parse_rules(&[]).unwrap(), QuizRules::default());
        for (bad, says) in [
            (&["--attempts", "0"][..], "Ignored “attempts=0”"),
            (&["--score", "median"], "Ignored “score=median”"),
            (&["--attempts"], "--attempts needs a value"),
            (
                &["--score", "best", "--score", "last"],
                "--score given twice",
            ),
            (&["--retakes", "2"], "unknown option `--retakes`"),
        ] {
            let err = parse_rules(&args(bad)).unwrap_err();
            assert!(err.contains(says), "{bad:?}: {err}");
        }
    }

    #[test]
    fn a_missing_dist_is_a_clear_error() {
        let dir = temp("missing");
        let err = write_package(
            &dir.join("nope"),
            &dir.join("out"),
            &dir.join("out.zip"),
            &[],
            &QuizRules::default(),
        )
        .unwrap_err();
        assert!(err.contains("has no index.html"), "{err}");
        fs::remove_dir_all(&dir).unwrap();
    }
}
