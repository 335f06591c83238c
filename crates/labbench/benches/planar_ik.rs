//! "Planar IK" of `shared/BENCHMARKS.md`: the lab's `DlsSolver` against
//! `k::JacobianIkSolver` on the same 2,000 targets, n = 3 and n = 7.
//!
//! Each timed pass solves all targets from the 0.3 rad start pose; one warm-up
//! pass, then [`REPS`] passes, median reported. Success rate and iterations
//! come from separate untimed passes.

use labbench::planar_ik::{
    k_chain, k_constraints, k_solver, k_target, our_variants, pass_k, pass_ours, solve_k,
    solve_ours, PassStats, Scenario, ARM_SIZES, TARGET_COUNT,
};
use std::hint::black_box;
use std::time::Instant;

const REPS: usize = 7;
/// `k`'s iteration budget: generous.
const K_MAX_TRY: usize = 1000;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Median over [`REPS`] passes (after one warm-up) of the mean µs per solve.
fn time_pass(mut pass: impl FnMut()) -> f64 {
    pass();
    let times: Vec<f64> = (0..REPS)
        .map(|_| {
            let t0 = Instant::now();
            pass();
            t0.elapsed().as_secs_f64() * 1e6 / TARGET_COUNT as f64
        })
        .collect();
    median(times)
}

fn row(name: &str, us: f64, stats: &PassStats) {
    println!(
        "  {name:<34} {us:>9.3} µs/solve  success {:>6.2} %  mean iterations {:>7.2}  worst error {:.1e} m",
        100.0 * stats.success_rate(),
        stats.mean_iterations(),
        stats.worst_error_m
    );
}

fn main() {
    println!("Planar IK (shared/BENCHMARKS.md): {TARGET_COUNT} targets, unit links, start 0.3 rad, success |e| < 1e-5 m");
    for (name, solver) in our_variants() {
        println!("  ours `{name}`: {solver:?}");
    }
    for n in ARM_SIZES {
        let scenario = Scenario::new(n);
        println!("\nn = {n}");
        let mut ours_us = f64::NAN;
        for (i, (name, solver)) in our_variants().into_iter().enumerate() {
            let us = time_pass(|| {
                for &p in &scenario.targets {
                    black_box(solve_ours(
                        &solver,
                        black_box(&scenario.lengths_m),
                        black_box(p),
                    ));
                }
            });
            if i == 0 {
                ours_us = us;
            }
            row(&format!("ours: {name}"), us, &pass_ours(&solver, &scenario));
        }
        let arm = k_chain(n);
        let constraints = k_constraints();
        let start = scenario.start();
        let targets: Vec<_> = scenario.targets.iter().map(|&p| k_target(p)).collect();
        for multiplier in [1.0, 0.5] {
            let solver = k_solver(multiplier, K_MAX_TRY);
            let us = time_pass(|| {
                for t in &targets {
                    black_box(solve_k(&solver, &arm, &constraints, &start, black_box(t)));
                }
            });
            let stats = pass_k(multiplier, K_MAX_TRY, &scenario);
            row(
                &format!("k JacobianIkSolver (mult {multiplier})"),
                us,
                &stats,
            );
            println!("    ratio k/ours = {:.1}x", us / ours_us);
        }
    }
}
