//! "EKF" of `shared/BENCHMARKS.md`: one localisation step (predict + one
//! landmark update) and one EKF-SLAM update at N = 20, 100, 200 landmarks.
//!
//! Each timed pass runs a fixed number of operations; one warm-up pass, then
//! [`REPS`] passes, median reported.

use labbench::ekf::{slam_filter, slam_observations, LocalisationStep, SLAM_SIZES};
use labcore::estimation::models::SensorNoise;
use std::hint::black_box;
use std::time::Instant;

const REPS: usize = 7;
const LOCALISATION_STEPS: usize = 1_000_000;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Median over [`REPS`] passes (after one warm-up) of µs per operation.
fn time_pass(ops: usize, mut pass: impl FnMut()) -> f64 {
    pass();
    let times: Vec<f64> = (0..REPS)
        .map(|_| {
            let t0 = Instant::now();
            pass();
            t0.elapsed().as_secs_f64() * 1e6 / ops as f64
        })
        .collect();
    median(times)
}

fn main() {
    println!("EKF (shared/BENCHMARKS.md)");
    let step = LocalisationStep::new();
    let us = time_pass(LOCALISATION_STEPS, || {
        for _ in 0..LOCALISATION_STEPS {
            black_box(black_box(&step).run());
        }
    });
    println!(
        "  localisation: predict + 1 landmark update   {us:>9.4} µs/step  (PythonRobotics ≈ 32 µs: {:.0}x)",
        32.0 / us
    );
    let r = SensorNoise::default().r();
    let mut previous: Option<(usize, f64)> = None;
    for n in SLAM_SIZES {
        let (mut slam, _) = slam_filter(n);
        let obs = slam_observations(&slam);
        // Enough updates for ~0.1 s a pass.
        let updates = (4_000_000 / (n * n)).max(obs.len());
        let us = time_pass(updates, || {
            for i in 0..updates {
                let _ = black_box(slam.observe(black_box(&obs[i % obs.len()]), r));
            }
        });
        let growth = previous
            .map(|(pn, pus)| {
                format!(
                    "  x{:.2} vs N={pn} (N² predicts x{:.2})",
                    us / pus,
                    ((2 * n + 3) as f64 / (2 * pn + 3) as f64).powi(2)
                )
            })
            .unwrap_or_default();
        println!(
            "  EKF-SLAM update, N = {n:>3} (n = {:>3})       {us:>9.3} µs/update{growth}",
            3 + 2 * n
        );
        previous = Some((n, us));
    }
}
