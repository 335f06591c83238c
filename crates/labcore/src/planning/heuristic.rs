//! Grid heuristics: estimates `h(n)` of the cost from a cell to the goal.
//!
//! With `dx = |x − x_goal|`, `dy = |y − y_goal|`:
//!
//! | heuristic | `h` | admissible with |
//! |---|---|---|
//! | [`Heuristic::Manhattan`] | `dx + dy` | 4-connected (exact on an open grid) |
//! | [`Heuristic::Octile`] | `max(dx, dy) + (√2 − 1) · min(dx, dy)` | 4- and 8-connected (exact for 8 on an open grid) |
//! | [`Heuristic::Euclidean`] | `√(dx² + dy²)` | 4- and 8-connected |
//! | [`Heuristic::Zero`] | `0` | always: A* becomes Dijkstra's algorithm |
//!
//! A heuristic is *admissible* when it never exceeds the true cost to the
//! goal, and *consistent* when `h(n) ≤ c(n, n') + h(n')` for every move; a
//! consistent heuristic makes A* optimal without re-expanding any cell (Hart,
//! Nilsson & Raphael, "A Formal Basis for the Heuristic Determination of
//! Minimum Cost Paths", *IEEE Trans. SSC* 4(2), 1968, pp. 100–107, Theorems 1
//! and 3). Every heuristic above that is admissible for a connectivity is also
//! consistent for it: each is a norm-like distance that a single move changes by
//! at most the move's cost. Manhattan with 8-connected moves overestimates (a
//! diagonal costs `√2 < 2`), so A* may then return a longer path.

use super::grid::{Cell, Connectivity};

/// `√2 − 1`, the extra cost of a diagonal over an orthogonal step.
const SQRT2_MINUS_1: f64 = std::f64::consts::SQRT_2 - 1.0;

/// An estimate of the cost from a cell to the goal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Heuristic {
    /// `dx + dy`.
    Manhattan,
    /// `max(dx, dy) + (√2 − 1) · min(dx, dy)`, the exact 8-connected distance on an open grid.
    #[default]
    Octile,
    /// `√(dx² + dy²)`.
    Euclidean,
    /// `0`: A* with it is Dijkstra's algorithm (Dijkstra, "A note on two
    /// problems in connexion with graphs", *Numer. Math.* 1, 1959, pp. 269–271).
    Zero,
}

impl Heuristic {
    /// Every heuristic, in the order of the page's selector.
    pub const ALL: [Heuristic; 4] = [
        Heuristic::Manhattan,
        Heuristic::Octile,
        Heuristic::Euclidean,
        Heuristic::Zero,
    ];

    /// `h` for offsets `dx, dy ≥ 0` (cells).
    #[inline]
    #[must_use]
    pub fn of_offsets(self, dx: f64, dy: f64) -> f64 {
        match self {
            Heuristic::Manhattan => dx + dy,
            Heuristic::Octile => {
                let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
                hi + SQRT2_MINUS_1 * lo
            }
            Heuristic::Euclidean => (dx * dx + dy * dy).sqrt(),
            Heuristic::Zero => 0.0,
        }
    }

    /// `h` from `from` to `to`.
    ///
    /// # Example
    /// ```
    /// use labcore::planning::grid::Cell;
    /// use labcore::planning::heuristic::Heuristic;
    /// let (a, b) = (Cell::new(0, 0), Cell::new(3, 1));
    /// assert_eq!(Heuristic::Manhattan.between(a, b), 4.0);
    /// assert!((Heuristic::Octile.between(a, b) - (2.0 + 2f64.sqrt())).abs() < 1e-15);
    /// assert!((Heuristic::Euclidean.between(a, b) - 10f64.sqrt()).abs() < 1e-15);
    /// assert_eq!(Heuristic::Zero.between(a, b), 0.0);
    /// ```
    #[must_use]
    pub fn between(self, from: Cell, to: Cell) -> f64 {
        let dx = from.x.abs_diff(to.x) as f64;
        let dy = from.y.abs_diff(to.y) as f64;
        self.of_offsets(dx, dy)
    }

    /// Whether `h` never overestimates (and, for these heuristics, is
    /// consistent) with the given moves: all but Manhattan with 8-connectivity.
    #[must_use]
    pub fn is_admissible(self, connectivity: Connectivity) -> bool {
        !(self == Heuristic::Manhattan && connectivity == Connectivity::Eight)
    }

    /// Short name for tables and the page (`"manhattan"`, `"octile"`, `"euclidean"`, `"zero"`).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Heuristic::Manhattan => "manhattan",
            Heuristic::Octile => "octile",
            Heuristic::Euclidean => "euclidean",
            Heuristic::Zero => "zero",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::grid::{OccupancyGrid, DIAGONAL_COST};

    /// Consistency `h(n) ≤ c(n, n') + h(n')` on every move of an open grid, for
    /// every admissible (heuristic, connectivity) pair, towards several goals.
    #[test]
    fn admissible_heuristics_are_consistent_on_every_move() {
        let g = OccupancyGrid::new(9, 7).unwrap();
        for conn in [Connectivity::Four, Connectivity::Eight] {
            for h in Heuristic::ALL {
                let mut violated = false;
                for goal in [Cell::new(0, 0), Cell::new(4, 3), Cell::new(8, 6)] {
                    for i in 0..63 {
                        let n = g.cell_of(i).unwrap();
                        for (m, cost) in g.neighbours(n, conn) {
                            if h.between(n, goal) > cost + h.between(m, goal) + 1e-12 {
                                violated = true;
                            }
                        }
                    }
                }
                assert_eq!(violated, !h.is_admissible(conn), "{h:?} {conn:?}");
            }
        }
    }

    #[test]
    fn octile_is_exact_on_an_open_grid() {
        // 5 right, 2 down: 2 diagonals + 3 straight.
        let h = Heuristic::Octile.between(Cell::new(1, 1), Cell::new(6, 3));
        assert!((h - (3.0 + 2.0 * DIAGONAL_COST)).abs() < 1e-12);
        assert_eq!(Heuristic::Octile.of_offsets(4.0, 0.0), 4.0);
    }
}
