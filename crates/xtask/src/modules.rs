//! The shipped wasm modules: one per experiment or per few experiments of a
//! group ([`modules`]).
//!
//! A page downloads only the module of the experiment it shows: `labweb` is
//! built once per module with `--no-default-features` and
//! `LAB_EXPERIMENTS=<id>,…` naming its experiments (labcore's `build.rs`
//! turns that into `cfg(lab_experiment = …)`), so the registry of that build
//! — and, through dead-code elimination, their code and compiled-in content —
//! holds only them. Each module is shipped as `pkg/<key>.<hash>.wasm` and
//! `pkg/<key>.<hash>.js`, named by a hash of both files, so a host may cache
//! them for good and a redeployment changes the names of exactly the modules
//! that changed. `index.html` lists them in `<meta name="lab-module">` tags,
//! which `main.js` reads.

use crate::util::{self, file_len, remove_dir, step};
use labcore::catalogue::{wasm_module, Group, CATALOGUE};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

pub const WASM_TARGET: &str = "wasm32-unknown-unknown";

/// `wasm-opt` level. Measured first on labweb's wasm-bindgen output (fk + ik
/// experiments, Rust 1.95, binaryen 132, 2-core machine):
///
/// | level | wasm bytes | gzip -9 bytes | wasm-opt time |
/// | ----- | ---------- | ------------- | ------------- |
/// | none  | 540,688    | 189,180       | –             |
/// | -O2   | 431,004    | 162,993       | 6.4 s         |
/// | -O3   | 429,875    | 162,983       | 8.3 s         |
/// | -Os   | 427,886    | 162,680       | 6.8 s         |
/// | -Oz   | 427,204    | 162,665       | 7.4 s         |
///
/// `-O3` was kept then, for 318 bytes. Measured again on the astar module
/// once the timeline, marks and live math were in (issues 26 and 27), the
/// page being within 4 KB of its 250 KiB budget:
///
/// | level            | wasm bytes | gzip -9 bytes | wasm-opt time |
/// | ---------------- | ---------- | ------------- | ------------- |
/// | -O3              | 541,104    | 240,829       | 7.1 s         |
/// | -Oz              | 530,276    | 239,065       | 6.6 s         |
/// | -Oz --converge   | 530,276    | 238,363       | 13.3 s        |
/// | the level below  | 522,026    | 235,828       | 24 s          |
///
/// (the last row on a later build whose `-Oz --converge` gave 237,414).
/// `-Oz --converge` repeats the passes until the module stops shrinking;
/// before it, functions that are duplicates or differ only in constants are
/// merged, common code tails folded, and the control flow flattened and
/// rebuilt (`--flatten --rereloop`), which lets `-Oz` find more: 5 KB gzip
/// off every module against `-O3`, with no assumption about the program
/// (no `--low-memory-unused`, no `--ignore-implicit-traps`). rustc already
/// builds the modules at opt-level "z" (`[profile.wasm-release]`); the
/// solvers' speed is measured natively (`cargo xtask bench`), which this
/// does not touch. The browser benchmark's frame times under `-O3` and this
/// level have not been compared in one run yet: do so with `XTASK_WASM_OPT`
/// before trading bytes back for speed. The time runs beside the next
/// module's cargo build. Re-measure with `XTASK_WASM_OPT=-O3 cargo xtask
/// dist && cargo xtask size`.
///
/// `--generate-global-effects` first (what each function may touch, so
/// calls to pure ones can be moved or dropped) and a round of GUFA (whole-
/// program flow analysis: values a location can only ever hold become
/// constants) after `-Oz`, then `-Oz` again: both sound, no assumption
/// about the program. Measured on the astar module: 232,672 -> 231,752 B
/// gzip (-920 B, about as much on every module); wasm-opt takes about 50 s
/// a module instead of 30 here.
pub const WASM_OPT_LEVEL: &str = "--generate-global-effects --duplicate-function-elimination \
     --merge-similar-functions --code-folding --flatten --rereloop -Oz --gufa-optimizing -Oz \
     --converge";

/// Features of the Rust 1.95 `wasm32-unknown-unknown` output: exactly those
/// LLVM's default "generic" CPU enables (and lists in the module's
/// `target_features` section). Validation without them fails today on
/// bulk memory (`memory.copy`/`fill`), non-trapping float-to-int
/// (`trunc_sat`), sign-ext and reference types (wasm-bindgen's externref
/// table); the rest are listed so that wasm-opt may keep whatever rustc emits.
/// Every current browser supports all of them.
const WASM_FEATURES: &[&str] = &[
    "--enable-bulk-memory",
    "--enable-bulk-memory-opt",
    "--enable-call-indirect-overlong",
    "--enable-multivalue",
    "--enable-mutable-globals",
    "--enable-nontrapping-float-to-int",
    "--enable-reference-types",
    "--enable-sign-ext",
];

/// The cargo profile of the shipped modules (workspace `Cargo.toml`).
const PROFILE: &str = "wasm-release";

/// A built module before it is copied into dist/.
pub struct Built {
    /// The module's name ([`modules`], or with `XTASK_MODULES=per-experiment`
    /// the experiment's id).
    pub key: &'static str,
    /// Experiment ids it holds, in the lab's order.
    pub ids: Vec<&'static str>,
    /// The wasm-bindgen glue (`<group>.js`) and the optimised module
    /// (`<group>_bg.wasm`), in a directory of their own.
    pub glue_dir: PathBuf,
}

/// A module as shipped in `dist/pkg/`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Shipped {
    /// The module's key (`arms`, `pid`, …).
    pub key: &'static str,
    pub ids: Vec<&'static str>,
    /// Paths relative to dist/, with the content hash in the name.
    pub js: String,
    pub wasm: String,
    pub wasm_bytes: u64,
}

/// The shipped modules and the experiments each holds, from labcore's list
/// of experiments (`crates/labcore/src/experiments/mod.rs`, which says which
/// experiments share a module and why): by catalogue group, then in the lab's
/// order, each module where its first experiment comes.
#[must_use]
pub fn modules() -> Vec<(&'static str, Vec<&'static str>)> {
    let mut modules: Vec<(&'static str, Vec<&'static str>)> = Vec::new();
    for group in Group::ALL {
        for plan in CATALOGUE.iter().filter(|p| p.group == group) {
            let key = wasm_module(plan.id).unwrap_or(plan.id);
            match modules.iter_mut().find(|(k, _)| *k == key) {
                Some((_, ids)) => ids.push(plan.id),
                None => modules.push((key, vec![plan.id])),
            }
        }
    }
    modules
}

/// Set (to anything) for modules with the paint benchmarks' exports.
pub const BENCH_EXPORTS_VAR: &str = "XTASK_BENCH_EXPORTS";

/// The key of the report module (`pkg/report.<hash>.wasm`, crate
/// `labreport`): the lab report's code, which a page downloads only when a
/// student makes a report (`main.js`'s `labReport`). It holds no experiment.
pub const REPORT_KEY: &str = "report";

/// The environment variable labcore's `build.rs` reads: the experiments a
/// build holds, comma-separated (unset: every one).
pub const SELECTION_VAR: &str = "LAB_EXPERIMENTS";

/// The value of [`SELECTION_VAR`] that builds `ids` and nothing else.
#[must_use]
pub fn selection(ids: &[&str]) -> String {
    ids.join(",")
}

/// Builds, binds and optimises the experiments' modules, one per key of
/// [`modules`] (experiments that share their solvers share one, the others
/// have their own), then the lab report's ([`REPORT_KEY`]).
pub fn build_modules(root: &Path) -> Result<Vec<Built>, String> {
    let target = util::target_dir();
    let out_root = target.join("xtask").join("modules");
    remove_dir(&out_root)?;
    let mut built = Vec::new();
    // XTASK_MODULES=per-experiment builds one module per experiment (to
    // measure what sharing a module costs).
    let per_experiment = std::env::var("XTASK_MODULES").as_deref() == Ok("per-experiment");
    // XTASK_BENCH_EXPORTS=1 (`cargo xtask bench --browser`) adds the paint
    // benchmarks' exports to every module; shipped modules go without.
    let bench_exports = std::env::var_os(BENCH_EXPORTS_VAR).is_some();
    let profile_names = std::env::var("XTASK_WASM_OPT")
        .is_ok_and(|level| level.split_whitespace().any(|flag| flag == "-g"));
    let parts: Vec<(&'static str, Vec<&'static str>)> = if per_experiment {
        CATALOGUE
            .iter()
            .filter(|p| labcore::find(p.id).is_some())
            .map(|p| (p.id, vec![p.id]))
            .collect()
    } else {
        modules()
    };
    let mut finishing = Vec::new();
    // The experiments' modules, then the report module (no experiment).
    let packages = parts
        .into_iter()
        .map(|(key, ids)| ("labweb", key, ids))
        .chain(std::iter::once(("labreport", REPORT_KEY, Vec::new())));
    for (package, key, ids) in packages {
        step(&format!(
            "cargo build (wasm, release) — module '{key}': {}",
            if ids.is_empty() {
                "the lab report".to_owned()
            } else {
                ids.join(", ")
            }
        ));
        let t = Instant::now();
        let mut build = util::cargo();
        build.env(SELECTION_VAR, selection(&ids)).args([
            "build",
            "-p",
            package,
            "--profile",
            PROFILE,
            "--target",
            WASM_TARGET,
            "--no-default-features",
        ]);
        if bench_exports && package == "labweb" {
            build.args(["--features", "bench-exports"]);
        }
        util::run(&mut build)?;
        let input = target
            .join(WASM_TARGET)
            .join(PROFILE)
            .join(format!("{package}.wasm"));
        let glue_dir = out_root.join(key);
        wasm_bindgen_cli_support::Bindgen::new()
            .input_path(&input)
            .web(true)
            .map_err(|e| format!("wasm-bindgen: {e:#}"))?
            .out_name(key)
            .typescript(false)
            // The library defaults this to `true` (the CLI to `false`): without the
            // default URL, `init()` has nothing to fetch (TOOLCHAIN.md, trap 2).
            .omit_default_module_path(false)
            // Names kept for a profile (`XTASK_WASM_OPT="-O3 -g"`): without
            // this wasm-bindgen drops the name section before wasm-opt sees it.
            .keep_debug(profile_names)
            .generate(&glue_dir)
            .map_err(|e| format!("wasm-bindgen on {}: {e:#}", input.display()))?;
        // wasm-opt and the minifier run beside the next module's cargo
        // build: on a 2-core machine the two overlap well (cargo's last
        // step, linking with LTO, is single-threaded).
        let (root, dir) = (root.to_path_buf(), glue_dir.clone());
        finishing.push(std::thread::spawn(move || -> Result<(), String> {
            optimise(&root, &dir.join(format!("{key}_bg.wasm")))?;
            shorten_imports(
                &dir.join(format!("{key}_bg.wasm")),
                &dir.join(format!("{key}.js")),
            )?;
            crate::minify::minify_in_place(&root, &dir.join(format!("{key}.js")))?;
            println!("module '{key}' built in {:.1} s", t.elapsed().as_secs_f64());
            Ok(())
        }));
        built.push(Built { key, ids, glue_dir });
    }
    for handle in finishing {
        handle
            .join()
            .map_err(|_| "a module's wasm-opt thread panicked".to_owned())??;
    }
    Ok(built)
}

/// Gives the imports of `wasm` short names, in the module and in its glue
/// `js`, in place ([`crate::import_names`]).
fn shorten_imports(wasm: &Path, js: &Path) -> Result<(), String> {
    let read = |p: &Path| fs::read(p).map_err(|e| format!("cannot read {}: {e}", p.display()));
    let (module, renames) = crate::import_names::shorten(&read(wasm)?)
        .map_err(|e| format!("{}: {e}", wasm.display()))?;
    let glue =
        String::from_utf8(read(js)?).map_err(|_| format!("{} is not UTF-8", js.display()))?;
    let glue = crate::import_names::rename_in_glue(&glue, &renames)
        .map_err(|e| format!("{}: {e}", js.display()))?;
    fs::write(wasm, module).map_err(|e| format!("cannot write {}: {e}", wasm.display()))?;
    fs::write(js, glue).map_err(|e| format!("cannot write {}: {e}", js.display()))?;
    println!("{}: {} imports renamed", wasm.display(), renames.len());
    Ok(())
}

/// Runs wasm-opt on `wasm` in place (level from `XTASK_WASM_OPT`, `none` to
/// skip; default [`WASM_OPT_LEVEL`]).
fn optimise(root: &Path, wasm: &Path) -> Result<(), String> {
    let level = std::env::var("XTASK_WASM_OPT").unwrap_or_else(|_| WASM_OPT_LEVEL.into());
    if level == "none" {
        println!("wasm-opt skipped (XTASK_WASM_OPT=none)");
        return Ok(());
    }
    let optimised = wasm.with_extension("opt.wasm");
    let before = file_len(wasm)?;
    let t = Instant::now();
    wasm_opt(root, wasm, &optimised, &level)?;
    fs::rename(&optimised, wasm).map_err(|e| format!("cannot replace {}: {e}", wasm.display()))?;
    println!(
        "wasm-opt {level}: {} -> {} ({:.1} s)",
        util::human(before),
        util::human(file_len(wasm)?),
        t.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Custom sections left out of every optimised module: rustc's
/// `producers` (its version) and `target_features` (read by tools, never by
/// a browser; wasm-opt is given [`WASM_FEATURES`] instead). About 225 bytes
/// of gzip a module, measured on the modules of `41f4345` (210–242 B).
const STRIPPED_SECTIONS: &[&str] = &["--strip-producers", "--strip-target-features"];

/// Runs npm binaryen's `wasm-opt` at `level` with [`WASM_FEATURES`] on
/// `input`, writing `output` without the [`STRIPPED_SECTIONS`].
pub fn wasm_opt(root: &Path, input: &Path, output: &Path, level: &str) -> Result<(), String> {
    let bin = root.join("node_modules/.bin/wasm-opt");
    if !bin.exists() {
        return Err(format!(
            "{} is missing: run `npm ci` (binaryen is pinned in package.json)",
            bin.display()
        ));
    }
    util::run(
        Command::new(&bin)
            // One level (`-O3`), or several flags (`-O3 -g` keeps the names,
            // for a profile).
            .args(level.split_whitespace())
            .args(WASM_FEATURES)
            .args(STRIPPED_SECTIONS)
            .arg(input)
            .arg("-o")
            .arg(output),
    )
}

/// Copies each module into `pkg` under its content-hashed names.
pub fn ship_modules(built: &[Built], pkg: &Path) -> Result<Vec<Shipped>, String> {
    fs::create_dir_all(pkg).map_err(|e| format!("cannot create {}: {e}", pkg.display()))?;
    let mut shipped = Vec::new();
    for b in built {
        let key = b.key;
        let read = |name: String| {
            let p = b.glue_dir.join(name);
            fs::read(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))
        };
        let js = read(format!("{key}.js"))?;
        let wasm = read(format!("{key}_bg.wasm"))?;
        let hash = content_hash(&[&js, &wasm]);
        let js_name = format!("{key}.{hash}.js");
        let wasm_name = format!("{key}.{hash}.wasm");
        for (name, bytes) in [(&js_name, &js), (&wasm_name, &wasm)] {
            fs::write(pkg.join(name), bytes)
                .map_err(|e| format!("cannot write pkg/{name}: {e}"))?;
        }
        shipped.push(Shipped {
            key,
            ids: b.ids.clone(),
            js: format!("pkg/{js_name}"),
            wasm: format!("pkg/{wasm_name}"),
            wasm_bytes: wasm.len() as u64,
        });
    }
    Ok(shipped)
}

/// Eight hex digits naming the content of `parts` (FNV-1a, 32 bits shown).
#[must_use]
pub fn content_hash(parts: &[&[u8]]) -> String {
    let mut input = Vec::new();
    for p in parts {
        input.extend_from_slice(&util::fnv1a(p).to_le_bytes());
    }
    format!("{:08x}", util::fnv1a(&input) as u32)
}

/// Whether a file name carries a content hash (`name.<8 hex>.ext`): such a
/// file never changes under its name, so hosts may cache it for good.
#[must_use]
pub fn is_content_hashed(path: &Path) -> bool {
    let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
        return false;
    };
    let mut parts = name.rsplit('.');
    let (Some(_ext), Some(hash), Some(stem)) = (parts.next(), parts.next(), parts.next()) else {
        return false;
    };
    !stem.is_empty() && hash.len() == 8 && hash.bytes().all(|c| c.is_ascii_hexdigit())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_experiment_is_in_exactly_one_module_of_its_own_group() {
        let modules = modules();
        let mut all: Vec<&str> = modules
            .iter()
            .flat_map(|(_, ids)| ids.iter().copied())
            .collect();
        assert_eq!(all.len(), labcore::registry().len());
        all.sort_unstable();
        all.dedup();
        assert_eq!(all.len(), labcore::registry().len());
        let group = |id: &str| labcore::catalogue::planned(id).expect("catalogued").group;
        for (key, ids) in &modules {
            assert!(
                ids.iter().all(|id| group(id) == group(ids[0])),
                "module {key} mixes groups"
            );
        }
    }

    #[test]
    fn a_selection_lists_the_ids_comma_separated() {
        assert_eq!(selection(&["pid", "cartpole"]), "pid,cartpole");
    }

    #[test]
    fn the_hash_follows_the_content() {
        let a = content_hash(&[b"js", b"wasm"]);
        assert_eq!(a.len(), 8);
        assert_eq!(a, content_hash(&[b"js", b"wasm"]));
        assert_ne!(a, content_hash(&[b"js", b"wasm!"]));
        assert_ne!(a, content_hash(&[b"jswasm", b""]));
    }

    #[test]
    fn hashed_names_are_recognised() {
        assert!(is_content_hashed(Path::new("pkg/control.0a1b2c3d.wasm")));
        assert!(is_content_hashed(Path::new("pages/pid.0a1b2c3d.html")));
        assert!(!is_content_hashed(Path::new("main.js")));
        assert!(!is_content_hashed(Path::new("pkg/control.wasm")));
        assert!(!is_content_hashed(Path::new("pkg/control.0a1b2c3x.wasm")));
        assert!(!is_content_hashed(Path::new("0a1b2c3d.wasm")));
    }
}
