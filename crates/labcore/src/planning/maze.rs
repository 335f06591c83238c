//! Seeded grid generators: a perfect maze and random fill.
//!
//! - [`recursive_backtracker`]: a depth-first-search maze (the "recursive
//!   backtracker" of Buck, *Mazes for Programmers*, 2015, Ch. 8; a randomised
//!   DFS spanning tree of the room lattice). Rooms are the cells with odd `x`
//!   and odd `y`; carving removes the wall between a room and a random unvisited
//!   room two cells away. Every pair of rooms is joined by exactly one path.
//! - [`random_fill`]: each cell, row by row, is a wall when `100 u < p` for the
//!   next draw `u` of the generator — the world of the A* benchmark in
//!   `shared/BENCHMARKS.md` with `p = 20` and `Lcg64::new(42)`.
//!
//! All randomness comes from [`Lcg64`], so the same seed gives the same grid
//! natively and in wasm.

use super::grid::{Cell, GridError, OccupancyGrid};
use crate::rng::Lcg64;

/// A perfect maze of `width × height` cells from `Lcg64::new(seed)`.
///
/// Every cell starts blocked; the rooms `(x, y)` with `x` and `y` odd and
/// `x ≤ width − 2`, `y ≤ height − 2` are carved, starting from room `(1, 1)`,
/// by an iterative depth-first search (an explicit stack: no recursion, so
/// 4096 × 4096 is safe). At each step the unvisited neighbouring rooms are
/// taken in the order right, left, down, up and one is picked with
/// `rng.int(0, k − 1)`. Odd sizes give a closed outer wall; a grid smaller than
/// 3 × 3 has no room and stays all blocked. Rooms `(1, 1)` and the last room
/// (largest odd `x`, `y`) are good start and goal cells.
///
/// # Example
/// ```
/// use labcore::planning::grid::Cell;
/// use labcore::planning::maze::recursive_backtracker;
/// let m = recursive_backtracker(21, 15, 7).unwrap();
/// assert!(m.is_free(Cell::new(1, 1)) && m.is_free(Cell::new(19, 13)));
/// assert!(m.is_blocked(Cell::new(0, 0)) && m.is_blocked(Cell::new(2, 2)));
/// assert_eq!(m, recursive_backtracker(21, 15, 7).unwrap()); // seeded
/// ```
pub fn recursive_backtracker(
    width: usize,
    height: usize,
    seed: u64,
) -> Result<OccupancyGrid, GridError> {
    // `new` checks the size, so `width · height` cannot overflow below.
    OccupancyGrid::new(width, height)?;
    let mut grid = OccupancyGrid::from_cells(width, height, vec![true; width * height])?;
    // Rooms: odd coordinates up to width − 2 / height − 2.
    let rooms_x = width.saturating_sub(1) / 2;
    let rooms_y = height.saturating_sub(1) / 2;
    if rooms_x == 0 || rooms_y == 0 {
        return Ok(grid);
    }
    let mut rng = Lcg64::new(seed);
    let mut visited = vec![false; rooms_x * rooms_y];
    let room_cell = |rx: usize, ry: usize| Cell::new(2 * rx + 1, 2 * ry + 1);
    let mut stack = vec![(0usize, 0usize)];
    visited[0] = true;
    grid.set_blocked(room_cell(0, 0), false);
    let mut options: Vec<(usize, usize)> = Vec::with_capacity(4);
    while let Some(&(rx, ry)) = stack.last() {
        options.clear();
        if rx + 1 < rooms_x && !visited[ry * rooms_x + rx + 1] {
            options.push((rx + 1, ry));
        }
        if rx > 0 && !visited[ry * rooms_x + rx - 1] {
            options.push((rx - 1, ry));
        }
        if ry + 1 < rooms_y && !visited[(ry + 1) * rooms_x + rx] {
            options.push((rx, ry + 1));
        }
        if ry > 0 && !visited[(ry - 1) * rooms_x + rx] {
            options.push((rx, ry - 1));
        }
        if options.is_empty() {
            stack.pop();
            continue;
        }
        let pick = rng.int(0, options.len() as i64 - 1) as usize;
        let (nx, ny) = options[pick.min(options.len() - 1)];
        visited[ny * rooms_x + nx] = true;
        let (a, b) = (room_cell(rx, ry), room_cell(nx, ny));
        grid.set_blocked(Cell::new((a.x + b.x) / 2, (a.y + b.y) / 2), false);
        grid.set_blocked(b, false);
        stack.push((nx, ny));
    }
    Ok(grid)
}

/// A `width × height` grid whose cells, row by row (index `y · width + x`), are
/// walls when `100 · rng.next_f64() < wall_percent`. Draws exactly
/// `width · height` numbers from `rng`, which the caller can keep using (the A*
/// benchmark draws its query cells next). `wall_percent` is clamped to
/// `[0, 100]`; NaN counts as 0.
///
/// # Example
/// ```
/// use labcore::planning::maze::random_fill;
/// use labcore::Lcg64;
/// let g = random_fill(100, 100, 20.0, &mut Lcg64::new(42)).unwrap();
/// let walls = g.blocked_count();
/// assert!((1800..2200).contains(&walls)); // about 20 %
/// ```
pub fn random_fill(
    width: usize,
    height: usize,
    wall_percent: f64,
    rng: &mut Lcg64,
) -> Result<OccupancyGrid, GridError> {
    OccupancyGrid::new(width, height)?; // size check first
    let p = if wall_percent.is_nan() {
        0.0
    } else {
        wall_percent.clamp(0.0, 100.0)
    };
    let cells: Vec<bool> = (0..width * height)
        .map(|_| 100.0 * rng.next_f64() < p)
        .collect();
    OccupancyGrid::from_cells(width, height, cells)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::grid::Connectivity;

    /// Free cells reachable from `from` with 4-connected moves.
    fn reachable(g: &OccupancyGrid, from: Cell) -> usize {
        let mut seen = vec![false; g.width() * g.height()];
        let mut stack = vec![from];
        seen[g.index(from).unwrap()] = true;
        let mut n = 0;
        while let Some(c) = stack.pop() {
            n += 1;
            for (to, _) in g.neighbours(c, Connectivity::Four) {
                let i = g.index(to).unwrap();
                if !seen[i] {
                    seen[i] = true;
                    stack.push(to);
                }
            }
        }
        n
    }

    #[test]
    fn maze_is_a_spanning_tree_of_the_rooms() {
        for (w, h, seed) in [(21, 15, 1), (31, 31, 2), (20, 16, 3), (5, 3, 4)] {
            let m = recursive_backtracker(w, h, seed).unwrap();
            let rooms = ((w - 1) / 2) * ((h - 1) / 2);
            // A tree on `rooms` rooms has rooms − 1 carved walls: 2·rooms − 1 free cells.
            let free = w * h - m.blocked_count();
            assert_eq!(free, 2 * rooms - 1, "{w}×{h}");
            // All of them connected.
            assert_eq!(reachable(&m, Cell::new(1, 1)), free);
            // Every room is free; every even-even cell is a wall.
            for y in 0..h {
                for x in 0..w {
                    let c = Cell::new(x, y);
                    if x % 2 == 1 && y % 2 == 1 && x + 1 < w && y + 1 < h {
                        assert!(m.is_free(c));
                    }
                    if x % 2 == 0 && y % 2 == 0 {
                        assert!(m.is_blocked(c));
                    }
                }
            }
        }
    }

    #[test]
    fn maze_depends_on_the_seed_and_tiny_sizes_do_not_panic() {
        let a = recursive_backtracker(41, 41, 1).unwrap();
        assert_ne!(a, recursive_backtracker(41, 41, 2).unwrap());
        assert_eq!(a, recursive_backtracker(41, 41, 1).unwrap());
        for (w, h) in [(1, 1), (2, 2), (1, 9), (9, 2), (3, 3)] {
            let m = recursive_backtracker(w, h, 0).unwrap();
            assert_eq!(m.width() * m.height(), w * h);
        }
        assert_eq!(recursive_backtracker(3, 3, 0).unwrap().blocked_count(), 8);
        assert!(recursive_backtracker(0, 3, 0).is_err());
        assert!(recursive_backtracker(1 << 20, 1 << 20, 0).is_err());
    }

    #[test]
    fn random_fill_follows_the_benchmark_rule() {
        let mut rng = Lcg64::new(42);
        let g = random_fill(50, 40, 20.0, &mut rng).unwrap();
        let mut check = Lcg64::new(42);
        for i in 0..2000 {
            assert_eq!(g.cells()[i], 100.0 * check.next_f64() < 20.0);
        }
        // Exactly 2000 draws were used.
        assert_eq!(rng.next_u64(), check.next_u64());
        assert_eq!(
            random_fill(10, 10, f64::NAN, &mut rng)
                .unwrap()
                .blocked_count(),
            0
        );
        assert_eq!(
            random_fill(10, 10, 1e9, &mut rng).unwrap().blocked_count(),
            100
        );
    }
}
