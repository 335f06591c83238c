//! Path planning: grid search and sampling-based planning.
//!
//! - [`grid`]: the occupancy grid and the neighbour rule (diagonals cost `√2`, no corner cutting).
//! - [`maze`]: seeded maze and random-fill generators.
//! - [`heuristic`]: Manhattan, octile, Euclidean and zero heuristics.
//! - [`astar`]: incremental A*, Dijkstra, weighted A* and greedy best-first search
//!   (Hart, Nilsson & Raphael 1968; Dijkstra 1959; Pohl 1970).
//! - [`movingai`]: the Moving AI `.map` and `.scen` formats (Sturtevant 2012).

pub mod astar;
pub mod grid;
pub mod heuristic;
pub mod maze;
pub mod movingai;
