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
    fn a_short_run_finds_a_path() {
        let mut t = tree(Planner::RrtStar);
        t.iterate(3000);
        let c = t.best_cost().expect("a path within 3000 iterations");
        assert!(c >= 96.0 * std::f64::consts::SQRT_2 - GOAL_RADIUS);
    }
}
