//! The "A* on a grid" scenario of `shared/BENCHMARKS.md`.
//!
//! - Grid 1000 × 1000; cell `(x, y)` at index `y · 1000 + x`, filled row by
//!   row; a cell is a wall when `100 u < 20` (one [`Lcg64`] seeded with 42):
//!   [`random_fill`].
//! - Queries: the corner `(0, 0) → (999, 999)`, then 19 random pairs drawn from
//!   the same generator right after the fill, in the order `sx, sy, gx, gy`,
//!   each with `rng.int(0, 999)`. Every query's start and goal are forced free
//!   (all of them, before any search runs, so every query sees the same grid).
//! - 8-connected, octile costs (1 and `√2`), no corner cutting.
//!
//! Peer: `pathfinding::prelude::astar` (4.x) with integer costs 1000 / 1414
//! and the matching integer octile heuristic `1000 · max + 414 · min`
//! (admissible and consistent for those costs), successors from a closure
//! applying the same no-corner-cutting rule on a flat wall array, returned
//! without allocating.

use labcore::planning::astar::{Search, SearchConfig};
use labcore::planning::grid::{Cell, Connectivity, OccupancyGrid};
use labcore::planning::heuristic::Heuristic;
use labcore::planning::maze::random_fill;
use labcore::Lcg64;
use pathfinding::prelude::astar;

/// Grid side, cells.
pub const SIZE: usize = 1000;
/// Seed of the scenario's LCG.
pub const SEED: u64 = 42;
/// A cell is a wall when `100 u <` this.
pub const WALL_PERCENT: f64 = 20.0;
/// Random query pairs after the corner query.
pub const RANDOM_QUERIES: usize = 19;
/// Integer cost of an orthogonal move for the peer.
pub const PEER_STRAIGHT: u32 = 1000;
/// Integer cost of a diagonal move for the peer.
pub const PEER_DIAGONAL: u32 = 1414;

/// The grid and its 20 queries.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    pub grid: OccupancyGrid,
    /// `(start, goal)`; the corner query first.
    pub queries: Vec<(Cell, Cell)>,
}

impl Scenario {
    /// Builds the scenario exactly as the module docs describe.
    ///
    /// # Panics
    /// Never for the fixed sizes used here.
    #[must_use]
    pub fn new() -> Self {
        let mut rng = Lcg64::new(SEED);
        let mut grid = random_fill(SIZE, SIZE, WALL_PERCENT, &mut rng).expect("1000 × 1000 fits");
        let hi = SIZE as i64 - 1;
        let mut queries = vec![(Cell::new(0, 0), Cell::new(SIZE - 1, SIZE - 1))];
        for _ in 0..RANDOM_QUERIES {
            let mut cell = || Cell::new(rng.int(0, hi) as usize, rng.int(0, hi) as usize);
            let s = cell();
            let g = cell();
            queries.push((s, g));
        }
        for &(s, g) in &queries {
            grid.set_blocked(s, false);
            grid.set_blocked(g, false);
        }
        Self { grid, queries }
    }
}

impl Default for Scenario {
    fn default() -> Self {
        Self::new()
    }
}

/// The lab's configuration for the scenario: A*, 8-connected, octile.
#[must_use]
pub fn our_config() -> SearchConfig {
    SearchConfig::astar(Connectivity::Eight, Heuristic::Octile)
}

/// One query with ours on the grid `search` already holds (made with
/// [`Search::new`] on the scenario grid), reusing its memory:
/// `(cost, expanded, path)` or `None`.
pub fn run_ours(search: &mut Search, start: Cell, goal: Cell) -> Option<(f64, usize, Vec<Cell>)> {
    search.restart(start, goal, our_config()).ok()?;
    search.run();
    search
        .result()
        .map(|r| (r.cost, r.expanded, r.path.clone()))
}

/// The peer's view of the grid: walls as bytes, row-major.
#[derive(Clone, Debug)]
pub struct PeerGrid {
    pub width: u32,
    pub height: u32,
    pub walls: Vec<u8>,
}

impl PeerGrid {
    #[must_use]
    pub fn new(grid: &OccupancyGrid) -> Self {
        Self {
            width: grid.width() as u32,
            height: grid.height() as u32,
            walls: grid.cells().iter().map(|&b| u8::from(b)).collect(),
        }
    }

    #[inline]
    fn free(&self, x: i64, y: i64) -> bool {
        x >= 0
            && y >= 0
            && x < i64::from(self.width)
            && y < i64::from(self.height)
            && self.walls[(y as usize) * self.width as usize + x as usize] == 0
    }

    /// Successors of cell index `i` with the lab's rule, as a fixed array and a count.
    #[inline]
    pub fn successors(&self, i: u32) -> impl Iterator<Item = (u32, u32)> {
        let w = i64::from(self.width);
        let (x, y) = (i64::from(i) % w, i64::from(i) / w);
        let mut out = [(0u32, 0u32); 8];
        let mut n = 0;
        let (fe, fw, fs, fnn) = (
            self.free(x + 1, y),
            self.free(x - 1, y),
            self.free(x, y + 1),
            self.free(x, y - 1),
        );
        let mut push = |dx: i64, dy: i64, c: u32| {
            out[n] = (((y + dy) * w + x + dx) as u32, c);
            n += 1;
        };
        if fe {
            push(1, 0, PEER_STRAIGHT);
        }
        if fw {
            push(-1, 0, PEER_STRAIGHT);
        }
        if fs {
            push(0, 1, PEER_STRAIGHT);
        }
        if fnn {
            push(0, -1, PEER_STRAIGHT);
        }
        if fs && fe && self.free(x + 1, y + 1) {
            push(1, 1, PEER_DIAGONAL);
        }
        if fs && fw && self.free(x - 1, y + 1) {
            push(-1, 1, PEER_DIAGONAL);
        }
        if fnn && fe && self.free(x + 1, y - 1) {
            push(1, -1, PEER_DIAGONAL);
        }
        if fnn && fw && self.free(x - 1, y - 1) {
            push(-1, -1, PEER_DIAGONAL);
        }
        out.into_iter().take(n)
    }

    /// The integer octile heuristic `1000 · max + 414 · min` from `i` to `goal`.
    #[inline]
    #[must_use]
    pub fn heuristic(&self, i: u32, goal: u32) -> u32 {
        let w = self.width;
        let dx = (i % w).abs_diff(goal % w);
        let dy = (i / w).abs_diff(goal / w);
        PEER_STRAIGHT * dx.max(dy) + (PEER_DIAGONAL - PEER_STRAIGHT) * dx.min(dy)
    }

    #[must_use]
    pub fn index(&self, c: Cell) -> u32 {
        c.y as u32 * self.width + c.x as u32
    }
}

/// One query with `pathfinding::astar`: `(integer cost, path as cell indices)`.
pub fn run_peer(peer: &PeerGrid, start: Cell, goal: Cell) -> Option<(u32, Vec<u32>)> {
    let g = peer.index(goal);
    astar(
        &peer.index(start),
        |&i| peer.successors(i),
        |&i| peer.heuristic(i, g),
        |&i| i == g,
    )
    .map(|(path, cost)| (cost, path))
}

/// The same as [`run_peer`], also counting expansions (successor calls + the goal).
pub fn run_peer_counted(peer: &PeerGrid, start: Cell, goal: Cell) -> Option<(u32, usize)> {
    let g = peer.index(goal);
    let mut calls = 0usize;
    astar(
        &peer.index(start),
        |&i| {
            calls += 1;
            peer.successors(i)
        },
        |&i| peer.heuristic(i, g),
        |&i| i == g,
    )
    .map(|(_, cost)| (cost, calls + 1))
}

/// Orthogonal and diagonal moves of a path given as cells.
#[must_use]
pub fn move_counts(path: &[Cell]) -> (u64, u64) {
    let mut straight = 0;
    let mut diagonal = 0;
    for w in path.windows(2) {
        if w[0].x != w[1].x && w[0].y != w[1].y {
            diagonal += 1;
        } else {
            straight += 1;
        }
    }
    (straight, diagonal)
}

/// A path's length with exact octile costs.
#[must_use]
pub fn octile_length(straight: u64, diagonal: u64) -> f64 {
    straight as f64 + diagonal as f64 * std::f64::consts::SQRT_2
}

#[cfg(test)]
mod tests {
    use super::*;
    use labcore::planning::grid::DIAGONAL_COST;

    #[test]
    fn scenario_matches_the_benchmark_text() {
        let s = Scenario::new();
        assert_eq!((s.grid.width(), s.grid.height()), (SIZE, SIZE));
        assert_eq!(s.queries.len(), 1 + RANDOM_QUERIES);
        assert_eq!(s.queries[0], (Cell::new(0, 0), Cell::new(999, 999)));
        // Walls follow the LCG rule except at the forced-free query cells.
        let mut rng = Lcg64::new(SEED);
        let forced: Vec<usize> = s
            .queries
            .iter()
            .flat_map(|&(a, b)| [a, b])
            .map(|c| c.y * SIZE + c.x)
            .collect();
        for (i, &wall) in s.grid.cells().iter().enumerate() {
            let expected = 100.0 * rng.next_f64() < WALL_PERCENT;
            if forced.contains(&i) {
                assert!(!wall);
            } else {
                assert_eq!(wall, expected, "cell {i}");
            }
        }
        // The first random query is the next four draws.
        let q = Cell::new(rng.int(0, 999) as usize, rng.int(0, 999) as usize);
        assert_eq!(s.queries[1].0, q);
        let walls = s.grid.blocked_count() as f64 / (SIZE * SIZE) as f64;
        assert!((0.19..0.21).contains(&walls));
    }

    #[test]
    fn peer_successors_follow_the_lab_rule() {
        let grid = OccupancyGrid::from_ascii("..#\n.#.\n...").unwrap();
        let peer = PeerGrid::new(&grid);
        for i in 0..9u32 {
            let c = grid.cell_of(i as usize).unwrap();
            let mut ours: Vec<(u32, u32)> = grid
                .neighbours(c, Connectivity::Eight)
                .map(|(m, cost)| {
                    let k = if cost == DIAGONAL_COST { 1414 } else { 1000 };
                    (peer.index(m), k)
                })
                .collect();
            let mut theirs: Vec<(u32, u32)> = if grid.is_free(c) {
                peer.successors(i).collect()
            } else {
                Vec::new()
            };
            ours.sort_unstable();
            theirs.sort_unstable();
            assert_eq!(ours, theirs, "cell {c}");
        }
    }

    #[test]
    fn both_agree_on_a_small_random_grid() {
        let mut rng = Lcg64::new(9);
        let grid = random_fill(60, 60, 20.0, &mut rng).unwrap();
        let peer = PeerGrid::new(&grid);
        let free = (0..3600)
            .find_map(|i| grid.cell_of(i).filter(|&c| grid.is_free(c)))
            .unwrap();
        let mut search = Search::new(&grid, free, free, our_config()).unwrap();
        let mut compared = 0;
        for _ in 0..50 {
            let s = Cell::new(rng.int(0, 59) as usize, rng.int(0, 59) as usize);
            let g = Cell::new(rng.int(0, 59) as usize, rng.int(0, 59) as usize);
            if grid.is_blocked(s) || grid.is_blocked(g) {
                continue;
            }
            let ours = run_ours(&mut search, s, g);
            let theirs = run_peer(&peer, s, g);
            assert_eq!(ours.is_some(), theirs.is_some());
            if let (Some((cost, _, path)), Some((icost, _))) = (ours, theirs) {
                let (a, b) = move_counts(&path);
                assert_eq!(a * 1000 + b * 1414, u64::from(icost));
                assert!((octile_length(a, b) - cost).abs() < 1e-9);
                compared += 1;
            }
        }
        assert!(compared > 20);
    }
}
