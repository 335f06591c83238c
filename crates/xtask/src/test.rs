//! `cargo xtask test`: every check and test, in order, stopping at the first
//! failure, with a timing line per step and a summary at the end.

use crate::{dist, util};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

const CHROMIUM: &str = "/usr/bin/chromium";
const CHROMEDRIVER: &str = "/usr/bin/chromedriver";
const INSTALL_HINT: &str =
    "install the Debian packages chromium and chromium-driver (sudo apt-get install chromium chromium-driver)";

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
        util::run(&mut cmd)
    })
}

pub fn test(opts: Options) -> Result<(), String> {
    let mut steps: Vec<Step> = Vec::new();
    if !opts.quick {
        steps.push((
            "cargo fmt --check",
            cargo_step(&["fmt", "--all", "--", "--check"]),
        ));
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
                let configs: [&[&str]; 2] = [
                    &[],
                    &["--no-default-features", "--features", "labcore/astar"],
                ];
                for features in configs {
                    util::run(
                        util::cargo()
                            .args(["clippy", "-p", "labweb", "-p", "labcore"])
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
            util::run(
                Command::new("node")
                    .args(["--test", "--test-concurrency=2", "tests/e2e/"])
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
    Ok(())
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
    if Path::new(CHROMIUM).exists() && Path::new(CHROMEDRIVER).exists() {
        return Ok(());
    }
    let uid = util::output(Command::new("id").arg("-u"))?;
    if uid.trim() != "0" {
        println!("{INSTALL_HINT}");
        return Err(INSTALL_HINT.into());
    }
    util::run(
        Command::new("apt-get")
            .arg("update")
            .env("DEBIAN_FRONTEND", "noninteractive"),
    )?;
    util::run(
        Command::new("apt-get")
            .args([
                "install",
                "-y",
                "--no-install-recommends",
                "chromium",
                "chromium-driver",
            ])
            .env("DEBIAN_FRONTEND", "noninteractive"),
    )?;
    if Path::new(CHROMIUM).exists() && Path::new(CHROMEDRIVER).exists() {
        Ok(())
    } else {
        Err(format!(
            "apt-get finished but {CHROMIUM} or {CHROMEDRIVER} is still missing"
        ))
    }
}
