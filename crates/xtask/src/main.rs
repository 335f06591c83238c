//! `cargo xtask <command>` — the lab's build, serve, size, test and bench tasks.
//!
//! Run `cargo xtask help` for the list. Only `std::process::Command`, the
//! wasm-bindgen library (same exact version as the workspace's `wasm-bindgen`)
//! and `flate2` are used: no other build tool has to be installed by hand.

mod dist;
mod import_names;
mod minify;
mod modules;
mod offline;
mod pages;
mod precompress;
mod readme;
mod scorm;
mod serve;
mod size;
mod test;
mod thumbs;
mod util;

use std::process::ExitCode;

const HELP: &str = "\
usage: cargo xtask <command> [options]

commands:
  dist [--scorm [--attempts N|unlimited] [--score best|last|first]]
                            build the site into dist/ (wasm, JS glue, web/ files);
                            --scorm also writes dist-scorm/ and dist-scorm.zip
                            (a SCORM 1.2 package, one SCO per experiment), its
                            quizzes graded N times at most (default unlimited),
                            the best, last or first attempt counting (default best)
  serve [--port N] [--host H] [--base /prefix/] [--dir PATH] [--no-compression]
                            build dist/, then serve it (default http://127.0.0.1:8000/);
                            --dir serves that folder as it is (no build), --port 0
                            a free port, --no-compression every file as it is
  size                      raw and gzip -9 size of every file in dist/
  test [--quick]            every check and test, stopping at the first failure
                            (--quick skips cargo fmt and clippy)
  bench [args...]           run `cargo bench -p labbench` (solver benchmarks
                            against their peers, same run)
  bench --browser           build dist/ and print the page's frame times, paint
                            costs and long tasks against their budgets
                            (tests/bench/; never pass/fail)
  readme                    write README.md's table of the experiments from the
                            registry and the content files
  help                      this text
";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (cmd, rest) = match args.split_first() {
        Some((c, r)) => (c.as_str(), r),
        None => ("help", &[][..]),
    };
    let result = match cmd {
        "dist" => dist_cmd(rest),
        "serve" => serve::parse_args(rest).and_then(serve::serve),
        "size" => no_args(cmd, rest).and_then(|()| size::size()),
        "test" => test::parse_args(rest).and_then(test::test),
        "bench" => bench(rest),
        "readme" => no_args(cmd, rest).and_then(|()| readme::readme()),
        "help" | "--help" | "-h" => {
            print!("{HELP}");
            Ok(())
        }
        other => Err(format!("unknown command `{other}`\n\n{HELP}")),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(msg) => {
            eprintln!("xtask {cmd}: error: {msg}");
            ExitCode::FAILURE
        }
    }
}

/// `dist`, and with `--scorm` (then `--attempts`, `--score`) the LMS
/// package made from it.
fn dist_cmd(rest: &[String]) -> Result<(), String> {
    let rules = match rest.split_first() {
        None => None,
        Some((flag, options)) if flag == "--scorm" => Some(
            scorm::parse_rules(options).map_err(|e| format!("`dist --scorm`: {e}"))?,
        ),
        Some((other, _)) => {
            return Err(format!(
                "`dist` takes only --scorm [--attempts N|unlimited] [--score best|last|first] (got `{other}`)"
            ))
        }
    };
    let dist = dist::dist()?;
    if let Some(rules) = rules {
        scorm::package(&dist, &rules)?;
    }
    Ok(())
}

fn no_args(cmd: &str, rest: &[String]) -> Result<(), String> {
    match rest.first() {
        None => Ok(()),
        Some(a) => Err(format!("`{cmd}` takes no arguments (got `{a}`)")),
    }
}

/// `cargo bench -p labbench` when the benchmark crate exists; with
/// `--browser`, the browser benchmark of the built site.
fn bench(rest: &[String]) -> Result<(), String> {
    let root = util::root();
    if rest.first().map(String::as_str) == Some("--browser") {
        no_args("bench --browser", &rest[1..])?;
        test::ensure_chromium()?;
        // dist() runs `npm ci` when node_modules is missing. The benchmark
        // pages call the modules' paint benchmarks, which shipped modules
        // leave out.
        std::env::set_var(modules::BENCH_EXPORTS_VAR, "1");
        dist::dist()?;
        return util::run(
            std::process::Command::new("node")
                .args(["--test", "--test-concurrency=1", "tests/bench/"])
                .current_dir(&root),
        );
    }
    if !root.join("crates/labbench/Cargo.toml").is_file() {
        println!("no benchmarks exist yet (crates/labbench is not in the workspace)");
        return Ok(());
    }
    let mut cmd = util::cargo();
    cmd.args(["bench", "-p", "labbench"]);
    if !rest.is_empty() {
        cmd.arg("--").args(rest);
    }
    util::run(&mut cmd)
}
