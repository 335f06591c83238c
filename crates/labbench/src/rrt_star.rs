//! The "RRT* in 2D" scenario of `shared/BENCHMARKS.md`.
//!
//! - World `[0, 100] × [0, 100]` with 30 circles, each `(10 + 80u, 10 + 80u,
//!   3 + 5u)` for `(x, y, radius)`, drawn in that order from one [`Lcg64`]
//!   whose state is `1 · 6364136223846793005 + 1442695040888963407 (mod 2⁶⁴)`
//!   before the first draw (the text's "seeded with …": the state is advanced
//!   before each draw, as always);
//! - start `(2, 2)`, goal `(98, 98)` with goal radius 1;
//! - steer step `η = 5`, edge checks every 0.5;
//! - exactly 10,000 and 100,000 iterations (one sample each).
//!
//! The planner's own random stream is [`labcore::planning::rrt_star::RrtConfig::seed`]
//! ([`PLANNER_SEED`]); goal bias 5 %, the default `γ`.
//!
//! ## The peer: OMPL 1.5.2 `RRTstar`, in the same run
//!
//! [`ompl`] builds and drives `crates/labbench/peers/ompl_rrtstar.cpp`, a
//! small C++ program on OMPL (Debian: `apt-get install libompl-dev`; headers
//! in `/usr/include/ompl-1.5`, `libompl.so`). The bench compiles it once with
//! `g++ -O2 -std=c++17 -I<ompl include> peers/ompl_rrtstar.cpp -o
//! <target>/tmp/ompl_rrtstar -lompl` (again only when the source is newer)
//! and feeds it this module's [`obstacles`] on stdin, one `x y r` line each in
//! Rust's round-trip float format, so both planners see bit-identical circles
//! and the LCG lives only here. The program sets up the same problem
//! (`RealVectorStateSpace(2)` on `[0, 100]²`, a validity checker for bounds
//! and circles, motion checks every 0.5 via
//! `setLongestValidSegmentFraction(0.5 / diagonal)`, `GoalState` (98, 98) with
//! threshold 1, path-length objective, `RRTstar` with range 5 and goal bias
//! 0.05) in its radius mode (`setKNearest(false)`) or its default k-nearest
//! mode, and runs exactly N iterations through a termination condition that
//! reads `numIterations()`. OMPL's RNG is seeded once per process
//! (`RNG::setSeed`); its logging is off. Without `g++` or the headers the
//! bench prints how to install them and skips the peer.

use glam::DVec2;
use labcore::planning::rrt_star::{Planner, RrtConfig, RrtStar};
use labcore::planning::world::{Obstacle, World};
use labcore::Lcg64;

/// The LCG state before the first obstacle draw.
pub const WORLD_STATE: u64 = 6_364_136_223_846_793_005u64.wrapping_add(1_442_695_040_888_963_407);
/// Circles in the world.
pub const OBSTACLES: usize = 30;
pub const START: DVec2 = DVec2::new(2.0, 2.0);
pub const GOAL: DVec2 = DVec2::new(98.0, 98.0);
pub const GOAL_RADIUS: f64 = 1.0;
/// Steer step `η`.
pub const ETA: f64 = 5.0;
/// Edge collision check spacing.
pub const CHECK_RESOLUTION: f64 = 0.5;
/// Seed of the planner's sampling stream.
pub const PLANNER_SEED: u64 = 1;
/// The iteration counts the scenario runs.
pub const ITERATIONS: [usize; 2] = [10_000, 100_000];

/// The 30 circles, in draw order.
#[must_use]
pub fn obstacles() -> Vec<Obstacle> {
    let mut rng = Lcg64::new(WORLD_STATE);
    (0..OBSTACLES)
        .map(|_| {
            let x = 10.0 + 80.0 * rng.next_f64();
            let y = 10.0 + 80.0 * rng.next_f64();
            let r = 3.0 + 5.0 * rng.next_f64();
            Obstacle::Circle {
                center: DVec2::new(x, y),
                radius: r,
            }
        })
        .collect()
}

/// The scenario's world.
///
/// # Panics
/// Never: the bounds and circles are valid by construction.
#[must_use]
pub fn world() -> World {
    World::new(DVec2::ZERO, DVec2::splat(100.0), obstacles()).expect("valid world")
}

/// The scenario's settings for `planner`.
#[must_use]
pub fn config(planner: Planner) -> RrtConfig {
    RrtConfig {
        planner,
        step_eta: ETA,
        check_resolution: CHECK_RESOLUTION,
        goal_radius: GOAL_RADIUS,
        seed: PLANNER_SEED,
        ..RrtConfig::default()
    }
}

/// A fresh tree for `planner` in the scenario.
///
/// # Panics
/// Never: start and goal are free in this world (checked by a test).
#[must_use]
pub fn tree(planner: Planner) -> RrtStar {
    RrtStar::new(world(), START, GOAL, config(planner)).expect("start and goal are free")
}

pub mod ompl {
    //! Building and running the OMPL peer (module docs of [`super`]).

    use super::obstacles;
    use labcore::planning::world::Obstacle;
    use std::fmt::Write as _;
    use std::io::Write as _;
    use std::path::{Path, PathBuf};
    use std::process::{Command, Stdio};

    /// The peer's C++ source.
    pub const SOURCE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/peers/ompl_rrtstar.cpp");
    /// What to do when OMPL or `g++` is missing.
    pub const INSTALL_HINT: &str =
        "install it with `apt-get install -y g++ libompl-dev` (Debian/Ubuntu; OMPL 1.5.2 on bookworm) or set OMPL_INCLUDE_DIR";

    /// OMPL's two neighbourhood modes.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum Mode {
        /// `setKNearest(false)`: all nodes within `r(n)`, like ours.
        Radius,
        /// OMPL's default: the `k(n)` nearest nodes.
        KNearest,
    }

    impl Mode {
        #[must_use]
        pub fn arg(self) -> &'static str {
            match self {
                Mode::Radius => "radius",
                Mode::KNearest => "knearest",
            }
        }
    }

    /// One run of the peer (a fresh planner).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct PeerRun {
        pub iterations: u64,
        pub seconds: f64,
        /// Best path length; NaN if no path was found.
        pub best: f64,
    }

    /// The circles as the peer reads them: `x y r` per line, round-trip floats.
    #[must_use]
    pub fn circles_text() -> String {
        let mut s = String::new();
        for o in obstacles() {
            if let Obstacle::Circle { center, radius } = o {
                let _ = writeln!(s, "{} {} {}", center.x, center.y, radius);
            }
        }
        s
    }

    /// OMPL's include directory (the one holding `ompl/geometric/…`):
    /// `$OMPL_INCLUDE_DIR`, else `/usr/include/ompl-*` or `/usr/local/include/ompl-*`.
    #[must_use]
    pub fn include_dir() -> Option<PathBuf> {
        let has = |d: &Path| d.join("ompl/geometric/planners/rrt/RRTstar.h").is_file();
        if let Some(d) = std::env::var_os("OMPL_INCLUDE_DIR").map(PathBuf::from) {
            return has(&d).then_some(d);
        }
        let mut found: Vec<PathBuf> = ["/usr/include", "/usr/local/include"]
            .iter()
            .filter_map(|root| std::fs::read_dir(root).ok())
            .flatten()
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("ompl"))
                    && has(p)
            })
            .collect();
        found.sort();
        found.pop()
    }

    fn gxx_available() -> bool {
        Command::new("g++")
            .arg("--version")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    }

    fn newer(a: &Path, b: &Path) -> bool {
        let t = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified()).ok();
        match (t(a), t(b)) {
            (Some(a), Some(b)) => a > b,
            _ => true,
        }
    }

    /// Compiles the peer into `out_dir` (once: again only when the source is
    /// newer than the binary) and returns the binary.
    ///
    /// # Errors
    /// `g++` or the OMPL headers are missing (the message says how to install
    /// them), or the compile fails (its output).
    pub fn build(out_dir: &Path) -> Result<PathBuf, String> {
        if !gxx_available() {
            return Err(format!("g++ not found; {INSTALL_HINT}"));
        }
        let Some(include) = include_dir() else {
            return Err(format!("OMPL headers not found; {INSTALL_HINT}"));
        };
        let bin = out_dir.join("ompl_rrtstar");
        if bin.is_file() && !newer(Path::new(SOURCE), &bin) {
            return Ok(bin);
        }
        std::fs::create_dir_all(out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
        let mut cmd = Command::new("g++");
        cmd.args(["-O2", "-std=c++17"])
            .arg(format!("-I{}", include.display()));
        if Path::new("/usr/include/eigen3").is_dir() {
            cmd.arg("-I/usr/include/eigen3");
        }
        let out = cmd
            .arg(SOURCE)
            .arg("-o")
            .arg(&bin)
            .arg("-lompl")
            .output()
            .map_err(|e| format!("g++: {e}"))?;
        if !out.status.success() {
            let _ = std::fs::remove_file(&bin);
            return Err(format!(
                "compiling {SOURCE} failed ({INSTALL_HINT}):\n{}",
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        Ok(bin)
    }

    /// Parses one `run <i> iterations <n> seconds <s> it_per_s <r> best <l>` line.
    #[must_use]
    pub fn parse_run(line: &str) -> Option<PeerRun> {
        let w: Vec<&str> = line.split_whitespace().collect();
        if w.len() != 10
            || w[0] != "run"
            || w[2] != "iterations"
            || w[4] != "seconds"
            || w[8] != "best"
        {
            return None;
        }
        Some(PeerRun {
            iterations: w[3].parse().ok()?,
            seconds: w[5].parse().ok()?,
            best: w[9].parse().ok()?,
        })
    }

    /// Runs the peer `runs` times (fresh planner each, one process) for
    /// exactly `iterations` iterations in `mode`.
    ///
    /// # Errors
    /// The program cannot start, fails, or prints something unexpected.
    pub fn run(
        bin: &Path,
        mode: Mode,
        iterations: usize,
        runs: usize,
    ) -> Result<Vec<PeerRun>, String> {
        let mut child = Command::new(bin)
            .args([mode.arg(), &iterations.to_string(), &runs.to_string()])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| format!("{}: {e}", bin.display()))?;
        child
            .stdin
            .take()
            .ok_or("no stdin")?
            .write_all(circles_text().as_bytes())
            .map_err(|e| format!("writing circles: {e}"))?;
        let out = child.wait_with_output().map_err(|e| e.to_string())?;
        if !out.status.success() {
            return Err(format!(
                "{} exited with {}: {}",
                bin.display(),
                out.status,
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        let text = String::from_utf8_lossy(&out.stdout);
        let v: Vec<PeerRun> = text.lines().filter_map(parse_run).collect();
        if v.len() != runs {
            return Err(format!("expected {runs} runs, got: {text}"));
        }
        if let Some(r) = v.iter().find(|r| r.iterations != iterations as u64) {
            return Err(format!("ran {} iterations, not {iterations}", r.iterations));
        }
        Ok(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn world_matches_the_benchmark_text() {
        let obs = obstacles();
        assert_eq!(obs.len(), OBSTACLES);
        // The first circle is the first three draws after the stated state.
        let s1 = WORLD_STATE
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let u1 = (s1 >> 11) as f64 / (1u64 << 53) as f64;
        match obs[0] {
            Obstacle::Circle { center, radius } => {
                assert_eq!(center.x, 10.0 + 80.0 * u1);
                assert!((10.0..90.0).contains(&center.y));
                assert!((3.0..8.0).contains(&radius));
            }
            Obstacle::Rect { .. } => panic!("circles only"),
        }
        let w = world();
        assert!(w.point_free(START) && w.point_free(GOAL));
    }

    #[test]
    fn the_peer_reads_bit_identical_circles_and_its_output_parses() {
        let text = ompl::circles_text();
        let parsed: Vec<Vec<f64>> = text
            .lines()
            .map(|l| l.split(' ').map(|w| w.parse().unwrap()).collect())
            .collect();
        assert_eq!(parsed.len(), OBSTACLES);
        for (p, o) in parsed.iter().zip(obstacles()) {
            let Obstacle::Circle { center, radius } = o else {
                panic!("circles only")
            };
            assert_eq!(p, &vec![center.x, center.y, radius]);
        }
        let r =
            ompl::parse_run("run 0 iterations 10000 seconds 0.0750 it_per_s 133333.3 best 139.5")
                .unwrap();
        assert_eq!(r.iterations, 10_000);
        assert_eq!(r.seconds, 0.075);
        assert_eq!(r.best, 139.5);
        assert!(ompl::parse_run("run 0 iterations x seconds 1 it_per_s 1 best 1").is_none());
    }

    #[test]
    fn a_short_run_finds_a_path() {
        let mut t = tree(Planner::RrtStar);
        t.iterate(3000);
        let c = t.best_cost().expect("a path within 3000 iterations");
        assert!(c >= 96.0 * std::f64::consts::SQRT_2 - GOAL_RADIUS);
    }
}
