//! Cross-checks of the grid planners on thousands of seeded random grids.
//!
//! The oracle is a textbook Dijkstra written here from the public neighbour
//! rule (`OccupancyGrid::neighbours`), independent of the search engine.

use labcore::planning::astar::{astar_path, Search, SearchConfig, StepOutcome};
use labcore::planning::grid::{Cell, Connectivity, OccupancyGrid};
use labcore::planning::heuristic::Heuristic;
use labcore::planning::maze::{random_fill, recursive_backtracker};
use labcore::Lcg64;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Min-heap entry for the oracle.
struct Entry(f64, usize);
impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    fn cmp(&self, o: &Self) -> Ordering {
        o.0.total_cmp(&self.0).then(o.1.cmp(&self.1))
    }
}

/// Shortest cost from `s` to `g`, or None.
fn oracle(grid: &OccupancyGrid, s: Cell, g: Cell, conn: Connectivity) -> Option<f64> {
    let mut dist = vec![f64::INFINITY; grid.width() * grid.height()];
    let mut heap = BinaryHeap::new();
    let si = grid.index(s)?;
    dist[si] = 0.0;
    heap.push(Entry(0.0, si));
    while let Some(Entry(d, i)) = heap.pop() {
        if d > dist[i] {
            continue;
        }
        let c = grid.cell_of(i)?;
        if c == g {
            return Some(d);
        }
        for (m, cost) in grid.neighbours(c, conn) {
            let j = grid.index(m)?;
            if d + cost < dist[j] {
                dist[j] = d + cost;
                heap.push(Entry(d + cost, j));
            }
        }
    }
    None
}

/// A random grid with random free start and goal.
fn random_case(rng: &mut Lcg64) -> (OccupancyGrid, Cell, Cell) {
    let w = rng.int(1, 24) as usize;
    let h = rng.int(1, 24) as usize;
    let density = rng.range(0.0, 45.0);
    let mut grid = random_fill(w, h, density, rng).unwrap();
    let pick = |rng: &mut Lcg64| {
        Cell::new(
            rng.int(0, w as i64 - 1) as usize,
            rng.int(0, h as i64 - 1) as usize,
        )
    };
    let (s, g) = (pick(rng), pick(rng));
    grid.set_blocked(s, false);
    grid.set_blocked(g, false);
    (grid, s, g)
}

const CASES: usize = 3000;

#[test]
fn astar_equals_dijkstra_and_the_oracle_on_random_grids() {
    let mut rng = Lcg64::new(2024);
    let (mut found, mut none) = (0, 0);
    for case in 0..CASES {
        let (grid, s, g) = random_case(&mut rng);
        for conn in [Connectivity::Four, Connectivity::Eight] {
            let expected = oracle(&grid, s, g, conn);
            let dijkstra = astar_path(&grid, s, g, SearchConfig::dijkstra(conn)).unwrap();
            for h in Heuristic::ALL {
                if !h.is_admissible(conn) {
                    continue;
                }
                let r = astar_path(&grid, s, g, SearchConfig::astar(conn, h)).unwrap();
                match (&r, &dijkstra, expected) {
                    (Some(a), Some(d), Some(e)) => {
                        assert!((a.cost - e).abs() < 1e-9, "case {case} {conn:?} {h:?}");
                        assert!((a.cost - d.cost).abs() < 1e-9);
                        if h == Heuristic::Octile {
                            assert!(
                                a.expanded <= d.expanded,
                                "case {case} {conn:?}: octile {} > dijkstra {}",
                                a.expanded,
                                d.expanded
                            );
                        }
                    }
                    (None, None, None) => {}
                    _ => panic!("case {case} {conn:?} {h:?}: disagreement on reachability"),
                }
            }
            if expected.is_some() {
                found += 1;
            } else {
                none += 1;
            }
        }
    }
    // Both kinds of case occur often enough for the check to mean something.
    assert!(found > CASES / 2 && none > CASES / 20, "{found} / {none}");
}

#[test]
fn weighted_astar_stays_within_w_times_optimal_and_greedy_finds_a_path() {
    let mut rng = Lcg64::new(77);
    let mut worse = 0;
    for case in 0..CASES {
        let (grid, s, g) = random_case(&mut rng);
        let conn = if case % 2 == 0 {
            Connectivity::Eight
        } else {
            Connectivity::Four
        };
        let optimal = oracle(&grid, s, g, conn);
        for h in [Heuristic::Octile, Heuristic::Euclidean] {
            for w in [1.0, 1.2, 2.0, 5.0] {
                let r = astar_path(&grid, s, g, SearchConfig::weighted(conn, h, w)).unwrap();
                assert_eq!(r.is_some(), optimal.is_some(), "case {case}");
                if let (Some(r), Some(o)) = (r, optimal) {
                    assert!(
                        r.cost <= w * o + 1e-9,
                        "case {case} w {w}: {} > {w}·{o}",
                        r.cost
                    );
                    assert!(r.cost >= o - 1e-9);
                    if r.cost > o + 1e-9 {
                        worse += 1;
                    }
                }
            }
            let greedy = astar_path(&grid, s, g, SearchConfig::greedy(conn, h)).unwrap();
            assert_eq!(greedy.is_some(), optimal.is_some(), "case {case} greedy");
            if let (Some(r), Some(o)) = (greedy, optimal) {
                assert!(r.cost >= o - 1e-9);
            }
        }
    }
    // The weight does make some paths longer (otherwise the bound test is vacuous).
    assert!(worse > 0);
}

#[test]
fn step_by_step_equals_run_and_counters_stay_consistent() {
    let mut rng = Lcg64::new(5);
    for _ in 0..300 {
        let (grid, s, g) = random_case(&mut rng);
        let config = SearchConfig::default();
        let mut stepped = Search::new(&grid, s, g, config).unwrap();
        let mut expansions = 0;
        let end = loop {
            match stepped.step() {
                StepOutcome::Expanded { cell } => {
                    expansions += 1;
                    assert!(grid.is_free(cell));
                    assert_eq!(stepped.expanded(), expansions);
                    // The open list's head is what the next step expands.
                    if let Some(top) = stepped.open_top(1).first() {
                        assert!(top.f >= 0.0 && (top.f - (top.g + top.h)).abs() < 1e-9);
                    }
                    let mut states = Vec::new();
                    stepped.write_cell_states(&mut states);
                    assert_eq!(
                        states.iter().filter(|&&v| v == 1).count(),
                        stepped.frontier_len()
                    );
                    assert_eq!(states.iter().filter(|&&v| v == 2).count(), expansions);
                }
                end => break end,
            }
        };
        let mut whole = Search::new(&grid, s, g, config).unwrap();
        assert_eq!(whole.run(), end);
        assert_eq!(whole.result(), stepped.result());
        assert_eq!(whole.expanded(), stepped.expanded());
    }
}

#[test]
fn mazes_are_solvable_corner_to_corner() {
    for seed in 0..20 {
        let (w, h) = (41 + 2 * (seed as usize % 5), 31);
        let maze = recursive_backtracker(w, h, seed).unwrap();
        let (s, g) = (Cell::new(1, 1), Cell::new(w - 2, h - 2));
        let r = astar_path(&maze, s, g, SearchConfig::default())
            .unwrap()
            .expect("a perfect maze connects every room");
        assert_eq!(Some(r.cost), oracle(&maze, s, g, Connectivity::Eight));
        // In a perfect maze of 1-wide corridors every move is orthogonal.
        assert_eq!(r.cost, (r.path.len() - 1) as f64);
    }
}
