//! "RRT* in 2D" of `shared/BENCHMARKS.md`: the lab's RRT* (and, for
//! comparison, RRT and Informed RRT*) at exactly 10,000 and 100,000
//! iterations on the 30-circle world.
//!
//! Each configuration builds a fresh tree and runs all iterations in one
//! `iterate` call; one warm-up, then [`REPS`] runs, the fastest reported (the
//! machines are shared: the fastest run is the one least disturbed, and the
//! 100k run, 20× longer, is otherwise far more likely to be interrupted,
//! which would inflate the growth ratio).
//! The peer (OMPL 1.5.2 `RRTstar`) is not in this run; its figures from the
//! benchmark text are printed for reference.

use labbench::rrt_star::{tree, ITERATIONS};
use labcore::planning::rrt_star::Planner;
use std::hint::black_box;
use std::time::Instant;

const REPS: usize = 5;

fn fastest(v: Vec<f64>) -> f64 {
    v.into_iter().fold(f64::INFINITY, f64::min)
}

fn main() {
    println!("RRT* in 2D (shared/BENCHMARKS.md): 100 × 100, 30 circles, (2, 2) → (98, 98) r 1, η 5, checks every 0.5");
    println!(
        "  OMPL RRTstar (benchmark text): 134,000 it/s at 10k and 69,000 at 100k (radius mode)"
    );
    for planner in [Planner::RrtStar, Planner::InformedRrtStar, Planner::Rrt] {
        println!("\n{}", planner.name());
        let mut per_iteration = Vec::new();
        for n in ITERATIONS {
            let mut t = tree(planner);
            t.iterate(n);
            let times: Vec<f64> = (0..REPS)
                .map(|_| {
                    let mut t = tree(planner);
                    let t0 = Instant::now();
                    black_box(t.iterate(black_box(n)));
                    t0.elapsed().as_secs_f64()
                })
                .collect();
            let s = fastest(times);
            per_iteration.push(s / n as f64);
            let first = t.cost_history().first().map_or(0, |h| h.iteration);
            println!(
                "  {:>7} iterations: {:>8.1} ms  {:>9.0} it/s  best path {:>9.4}  nodes {:>6}  rewires {:>7}  first path at iteration {}",
                n,
                s * 1e3,
                n as f64 / s,
                t.best_cost().unwrap_or(f64::NAN),
                t.len(),
                t.rewire_count(),
                first
            );
        }
        println!(
            "  time per iteration 100k ÷ 10k: {:.2}x (target < 2x)",
            per_iteration[1] / per_iteration[0]
        );
    }
}
