//! `cargo xtask test`: every check and test, in order, stopping at the first
//! failure, with a timing line per step and a summary at the end.

use crate::{dist, util};
use std::cell::Cell;
use std::path::Path;
use std::process::Command;
use std::rc::Rc;
use std::time::{Duration, Instant};

const CHROMIUM: &str = "/usr/bin/chromium";
const CHROMEDRIVER: &str = "/usr/bin/chromedriver";
const INSTALL_HINT: &str =
    "install the Debian packages chromium and chromium-driver (sudo apt-get install chromium chromium-driver)";
/// `node --test` flags for the browser suites: a test fails after 10 min
/// (the longest, axe over every tab, takes about 1 min), and a test file
/// exits once its tests are done, whatever child process is left running.
const NODE_TEST_WATCHDOG: [&str; 2] = ["--test-timeout=600000", "--test-force-exit"];
/// The Debian packages of the real servers `tests/hosts/` runs docs/hosting.md's recipes on.
const SERVER_PACKAGES: [&str; 5] = [
    "nginx",
    "libnginx-mod-http-brotli-static",
    "apache2",
    "caddy",
    "lighttpd",
];
/// What those packages install that the suite uses.
const SERVER_FILES: [&str; 5] = [
    "/usr/sbin/nginx",
    "/usr/share/nginx/modules/ngx_http_brotli_static_module.so",
    "/usr/sbin/apache2",
    "/usr/bin/caddy",
    "/usr/sbin/lighttpd",
];

pub struct Options {
    quick: bool,
}

pub fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut opts = Options { quick: false };
    for a in args {
        match a.as_str() {
            "--quick" => opts.quick = true,
            other => {
                return Err(format!(
                    "unknown option `{other}` (test takes --quick, which skips fmt and clippy)"
                ))
            }
        }
    }
    Ok(opts)
}

type Step = (&'static str, Box<dyn Fn() -> Result<(), String>>);

fn cargo_step(args: &'static [&'static str]) -> Box<dyn Fn() -> Result<(), String>> {
    Box::new(move || util::run(util::cargo().args(args)))
}

/// `cargo fmt --check`, and rustfmt on the experiment folders, which it never
/// reaches: their modules are declared by the `experiments!` registry macro
/// (main held unformatted lines there that `cargo fmt --check` passed).
/// rustfmt follows each folder's own `mod` lines from its `mod.rs`.
fn fmt_check() -> Result<(), String> {
    util::run(util::cargo().args(["fmt", "--all", "--", "--check"]))?;
    let folder = util::root().join("crates/labcore/src/experiments");
    let entries = std::fs::read_dir(&folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    let mut roots: Vec<_> = entries
        .filter_map(|entry| entry.ok().map(|entry| entry.path()))
        .filter_map(|path| {
            if path.is_dir() {
                Some(path.join("mod.rs")).filter(|root| root.exists())
            } else {
                // A one-file experiment (experiments/mod.rs is what cargo fmt reaches).
                (path.extension().is_some_and(|e| e == "rs") && !path.ends_with("mod.rs"))
                    .then_some(path)
            }
        })
        .collect();
    roots.sort();
    if roots.is_empty() {
        return Err(format!("no experiment modules under {}", folder.display()));
    }
    util::run(
        Command::new("rustfmt")
            .args(["--check", "--edition", "2021"])
            .args(&roots),
    )
}

/// `cargo test --target wasm32-unknown-unknown` with the runner this task built.
fn wasm_test(package: &'static str, browser: bool) -> Box<dyn Fn() -> Result<(), String>> {
    Box::new(move || {
        let mut cmd = util::cargo();
        cmd.args(["test", "-p", package, "--target", "wasm32-unknown-unknown"]);
        // .cargo/config.toml names the runner relative to the workspace; an
        // absolute path also works when CARGO_TARGET_DIR points elsewhere.
        cmd.env(
            "CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER",
            util::target_dir().join("tool/wasm-bindgen-test-runner"),
        );
        if browser && Path::new(CHROMEDRIVER).exists() {
            cmd.env("CHROMEDRIVER", CHROMEDRIVER);
        }
        // The runner gives a whole test file 20 s by default; labweb's
        // `runs` takes 8–12 s here, and once took over 20 on a loaded machine.
        if std::env::var_os("WASM_BINDGEN_TEST_TIMEOUT").is_none() {
            cmd.env("WASM_BINDGEN_TEST_TIMEOUT", "180");
        }
        util::run(&mut cmd)
    })
}

pub fn test(opts: Options) -> Result<(), String> {
    let mut steps: Vec<Step> = Vec::new();
    if !opts.quick {
        steps.push(("cargo fmt --check", Box::new(fmt_check)));
        steps.push((
            "clippy (native)",
            cargo_step(&[
                "clippy",
                "--workspace",
                "--all-targets",
                "--",
                "-D",
                "warnings",
            ]),
        ));
        steps.push((
            "clippy (wasm)",
            Box::new(|| {
                dist::ensure_wasm_target()?;
                // As the tests build it (every experiment), and as a shipped
                // module is built: one experiment, no reading content (the
                // code behind `cfg(not(feature = "reading"))`).
                let configs: [(Option<&str>, &[&str]); 2] =
                    [(None, &[]), (Some("astar"), &["--no-default-features"])];
                for (selection, features) in configs {
                    let mut clippy = util::cargo();
                    if let Some(ids) = selection {
                        clippy.env(crate::modules::SELECTION_VAR, ids);
                    }
                    util::run(
                        clippy
                            .args(["clippy", "-p", "labweb", "-p", "labreport", "-p", "labpage"])
                            .args(["-p", "labcore"])
                            .args(["--target", "wasm32-unknown-unknown"])
                            .args(features)
                            .args(["--", "-D", "warnings"]),
                    )?;
                }
                Ok(())
            }),
        ));
    }
    steps.push(("native tests", cargo_step(&["test", "--workspace"])));
    steps.push((
        "build wasm test runner",
        cargo_step(&[
            "build",
            "--profile",
            "tool",
            "-p",
            "xtask",
            "--bin",
            "wasm-bindgen-test-runner",
        ]),
    ));
    steps.push((
        "wasm tests in Node (labcore)",
        Box::new(|| {
            dist::ensure_wasm_target()?;
            wasm_test("labcore", false)()
        }),
    ));
    steps.push(("Chromium present", Box::new(ensure_chromium)));
    // Before the end-to-end step: tests/e2e/browsers.test.mjs needs them.
    steps.push((
        "Firefox ESR, WebKitGTK driver and Xvfb present",
        Box::new(ensure_other_browsers),
    ));
    steps.push((
        "wasm tests in headless Chromium (labweb)",
        wasm_test("labweb", true),
    ));
    // The SCORM package too: tests/e2e/scorm.test.mjs launches it in a test LMS.
    steps.push((
        "dist --scorm",
        Box::new(|| {
            dist::dist().and_then(|d| {
                crate::scorm::package(&d, &labcore::route::QuizRules::default()).map(|_| ())
            })
        }),
    ));
    steps.push((
        "first-page budget (gzip)",
        Box::new(crate::size::check_first_page_budget),
    ));
    steps.push((
        "end-to-end tests (node --test --test-concurrency=2 tests/e2e/)",
        Box::new(|| {
            // Two files at a time: one alone leaves about a third of two cores
            // idle (process and browser start-up, round trips); two keep them
            // busy (8 min 18 s -> 5 min 30 s here). No test asserts a time.
            // The suite serves dist/ with this very binary (`serve --dir`):
            // one server, one table of media types and cache headers.
            // A test that hangs (a browser that stops answering its driver)
            // fails after ten minutes, and a file whose tests are done exits
            // even if a child process it started lingers: a hang reads as a
            // failure with its name, not as a CI run out of time.
            util::run(
                Command::new("node")
                    .args(["--test", "--test-concurrency=2"])
                    .args(NODE_TEST_WATCHDOG)
                    .arg("tests/e2e/")
                    .env("LAB_XTASK", xtask_binary()?)
                    .current_dir(util::root()),
            )
        }),
    ));

    // The server recipes of docs/hosting.md on the real servers. Without the
    // packages and without root to install them, the suite is skipped (said
    // loudly), not failed: the rest of the tests still mean something.
    let servers_present = Rc::new(Cell::new(false));
    let present = Rc::clone(&servers_present);
    let servers_ran = Rc::clone(&servers_present);
    steps.push((
        "nginx, Apache, Caddy and lighttpd present",
        Box::new(move || {
            present.set(ensure_servers()?);
            Ok(())
        }),
    ));
    steps.push((
        "the server recipes of docs/hosting.md on nginx, Apache, Caddy and lighttpd (node --test tests/hosts/)",
        Box::new(move || {
            if !servers_present.get() {
                println!("SKIPPED: {}", servers_hint());
                return Ok(());
            }
            util::run(
                Command::new("node")
                    .arg("--test")
                    .args(NODE_TEST_WATCHDOG)
                    .arg("tests/hosts/")
                    .current_dir(util::root()),
            )
        }),
    ));

    let started = Instant::now();
    let total = steps.len();
    let mut done: Vec<(&str, Duration)> = Vec::new();
    for (i, (name, run)) in steps.iter().enumerate() {
        println!("\n==== [{}/{total}] {name}", i + 1);
        let t = Instant::now();
        let result = run();
        let took = t.elapsed();
        match result {
            Ok(()) => {
                println!("==== [{}/{total}] {name}: ok in {:.1} s", i + 1, secs(took));
                done.push((name, took));
            }
            Err(msg) => {
                println!(
                    "==== [{}/{total}] {name}: FAILED after {:.1} s",
                    i + 1,
                    secs(took)
                );
                summary(&done, started.elapsed());
                return Err(format!("step {}/{total} `{name}` failed: {msg}", i + 1));
            }
        }
    }
    summary(&done, started.elapsed());
    println!("all {total} steps passed");
    if !servers_ran.get() {
        println!(
            "but the server recipes of docs/hosting.md were not tested: {}",
            servers_hint()
        );
    }
    Ok(())
}

/// This `cargo xtask` binary, which tests/e2e/helpers.mjs starts as the
/// suite's server (`serve --dir dist --port 0`).
fn xtask_binary() -> Result<std::path::PathBuf, String> {
    std::env::current_exe().map_err(|e| format!("cannot find the xtask binary: {e}"))
}

fn secs(d: Duration) -> f64 {
    d.as_secs_f64()
}

fn summary(done: &[(&str, Duration)], total: Duration) {
    println!("\nsummary:");
    for (name, took) in done {
        println!("  ok  {:>7.1} s  {name}", secs(*took));
    }
    println!("  total {:.1} s", secs(total));
}

/// Installs Debian's chromium + chromium-driver when missing (as root), or
/// fails with the command to run.
pub fn ensure_chromium() -> Result<(), String> {
    ensure_debian_packages(
        &[CHROMIUM, CHROMEDRIVER],
        &["chromium", "chromium-driver"],
        INSTALL_HINT,
    )
}

/// Firefox ESR (driven over WebDriver BiDi by puppeteer-core), WebKitGTK's
/// WebDriver with its MiniBrowser, and the X server it draws on: what
/// `tests/e2e/browsers.test.mjs` runs the lab in besides Chromium.
const OTHER_BROWSERS: [(&str, &str); 3] = [
    ("/usr/bin/firefox-esr", "firefox-esr"),
    ("/usr/bin/WebKitWebDriver", "webkit2gtk-driver"),
    ("/usr/bin/Xvfb", "xvfb"),
];
const OTHER_BROWSERS_HINT: &str =
    "install the Debian packages firefox-esr, webkit2gtk-driver and xvfb \
     (sudo apt-get install firefox-esr webkit2gtk-driver xvfb)";

/// Installs Debian's firefox-esr, webkit2gtk-driver and xvfb when missing
/// (as root; about 141 MB of downloads, 57 packages on a machine that has
/// Chromium), or fails with the command to run.
pub fn ensure_other_browsers() -> Result<(), String> {
    let paths: Vec<&str> = OTHER_BROWSERS.iter().map(|(p, _)| *p).collect();
    let packages: Vec<&str> = OTHER_BROWSERS.iter().map(|(_, p)| *p).collect();
    ensure_debian_packages(&paths, &packages, OTHER_BROWSERS_HINT)
}

/// Installs `packages` with apt-get when any of `paths` is missing (as root),
/// or fails with `hint`.
fn ensure_debian_packages(paths: &[&str], packages: &[&str], hint: &str) -> Result<(), String> {
    if install_debian_packages(paths, packages, &["--no-install-recommends"])? {
        Ok(())
    } else {
        println!("{hint}");
        Err(hint.into())
    }
}

/// Installs `packages` with apt-get (`apt_args` added) when any of `paths`
/// is missing. `Ok(false)` when they are missing and this is not root, so
/// nothing could be installed.
fn install_debian_packages(
    paths: &[&str],
    packages: &[&str],
    apt_args: &[&str],
) -> Result<bool, String> {
    let present = || paths.iter().all(|p| Path::new(p).exists());
    if present() {
        return Ok(true);
    }
    let uid = util::output(Command::new("id").arg("-u"))?;
    if uid.trim() != "0" {
        return Ok(false);
    }
    util::run(
        Command::new("apt-get")
            .arg("update")
            .env("DEBIAN_FRONTEND", "noninteractive"),
    )?;
    util::run(
        Command::new("apt-get")
            .args(["install", "-y"])
            .args(apt_args)
            .args(packages)
            .env("DEBIAN_FRONTEND", "noninteractive"),
    )?;
    if present() {
        Ok(true)
    } else {
        Err(format!(
            "apt-get finished but one of {} is still missing",
            paths.join(", ")
        ))
    }
}

fn servers_hint() -> String {
    format!(
        "the real-server suite (tests/hosts/) needs the Debian packages {}: \
         run as root, or `sudo apt-get update && sudo apt-get install -y {}`",
        SERVER_PACKAGES.join(", "),
        SERVER_PACKAGES.join(" ")
    )
}

/// Installs Debian's nginx, its Brotli static module, Apache, Caddy and lighttpd when missing
/// (as root). `Ok(false)` when they are missing and this is not root: the
/// caller skips the suite and says why.
pub fn ensure_servers() -> Result<bool, String> {
    let installed = install_debian_packages(&SERVER_FILES, &SERVER_PACKAGES, &[])?;
    if !installed {
        println!("SKIPPING: {}", servers_hint());
    }
    Ok(installed)
}
