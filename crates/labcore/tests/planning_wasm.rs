//! The planners under wasm32 (run in Node by wasm-bindgen-test) and natively:
//! the same seed gives bit-identical searches and trees on both.

#[cfg(not(target_arch = "wasm32"))]
use std::prelude::v1::test as wasm_bindgen_test;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test;

use glam::DVec2;
use labcore::planning::astar::{astar_path, SearchConfig};
use labcore::planning::grid::{Cell, Connectivity};
use labcore::planning::heuristic::Heuristic;
use labcore::planning::maze::{random_fill, recursive_backtracker};
use labcore::planning::movingai::{parse_map, parse_scen, ARENA_MAP, ARENA_SCEN};
use labcore::planning::rrt_star::{Planner, RrtConfig, RrtStar};
use labcore::planning::world::{Obstacle, World};
use labcore::Lcg64;

struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
    fn mix(&mut self, x: u64) {
        for byte in x.to_le_bytes() {
            self.0 = (self.0 ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn mix_f(&mut self, x: f64) {
        self.mix(x.to_bits());
    }
}

/// FNV-1a over grid searches (random fill, maze) and the three sampling planners.
fn planning_fingerprint() -> u64 {
    let mut h = Fnv::new();
    let mut rng = Lcg64::new(99);
    let mut grid = random_fill(64, 48, 25.0, &mut rng).unwrap();
    grid.set_blocked(Cell::new(0, 0), false);
    grid.set_blocked(Cell::new(63, 47), false);
    for config in [
        SearchConfig::astar(Connectivity::Eight, Heuristic::Octile),
        SearchConfig::astar(Connectivity::Four, Heuristic::Euclidean),
        SearchConfig::weighted(Connectivity::Eight, Heuristic::Euclidean, 2.5),
        SearchConfig::greedy(Connectivity::Eight, Heuristic::Octile),
    ] {
        if let Some(r) = astar_path(&grid, Cell::new(0, 0), Cell::new(63, 47), config).unwrap() {
            h.mix_f(r.cost);
            h.mix(r.expanded as u64);
            r.path.iter().for_each(|c| h.mix((c.y * 64 + c.x) as u64));
        } else {
            h.mix(u64::MAX);
        }
    }
    let maze = recursive_backtracker(31, 21, 4).unwrap();
    let r = astar_path(
        &maze,
        Cell::new(1, 1),
        Cell::new(29, 19),
        SearchConfig::default(),
    )
    .unwrap()
    .unwrap();
    h.mix_f(r.cost);
    h.mix(r.expanded as u64);

    let world = World::new(
        DVec2::ZERO,
        DVec2::splat(50.0),
        vec![
            Obstacle::Circle {
                center: DVec2::new(25.0, 25.0),
                radius: 8.0,
            },
            Obstacle::rect(DVec2::new(5.0, 30.0), DVec2::new(20.0, 34.0)),
        ],
    )
    .unwrap();
    for planner in [Planner::Rrt, Planner::RrtStar, Planner::InformedRrtStar] {
        let config = RrtConfig {
            planner,
            step_eta: 3.0,
            seed: 17,
            ..RrtConfig::default()
        };
        let mut t =
            RrtStar::new(world.clone(), DVec2::splat(2.0), DVec2::splat(48.0), config).unwrap();
        t.iterate(1500);
        for (p, &parent) in t.nodes().iter().zip(t.parents()) {
            h.mix_f(p.x);
            h.mix_f(p.y);
            h.mix(u64::from(parent));
        }
        t.costs().iter().for_each(|c| h.mix_f(*c));
        h.mix(t.rewire_count() as u64);
        h.mix_f(t.best_cost().unwrap_or(-1.0));
    }
    h.0
}

/// Computed natively; must come out the same in wasm.
const FINGERPRINT: u64 = 0x8d79_5019_a39d_b111;

#[wasm_bindgen_test]
fn planners_are_bit_identical_natively_and_in_wasm() {
    let f = planning_fingerprint();
    assert_eq!(f, planning_fingerprint(), "deterministic within a run");
    assert_eq!(f, FINGERPRINT, "fingerprint {f:#018x}");
}

#[wasm_bindgen_test]
fn arena_scenarios_are_optimal_in_wasm_too() {
    let grid = parse_map(ARENA_MAP).unwrap();
    for s in parse_scen(ARENA_SCEN).unwrap() {
        let r = astar_path(&grid, s.start, s.goal, SearchConfig::default())
            .unwrap()
            .unwrap();
        assert!((r.cost - s.optimal_length).abs() < 1e-6);
    }
}
