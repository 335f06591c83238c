//! Path planning: grid search and sampling-based planning.
//!
//! - [`grid`]: the occupancy grid and the neighbour rule (diagonals cost `√2`, no corner cutting).
//! - [`maze`]: seeded maze and random-fill generators.
//! - [`heuristic`]: Manhattan, octile, Euclidean and zero heuristics.
//! - [`astar`]: incremental A*, Dijkstra, weighted A* and greedy best-first search
//!   (Hart, Nilsson & Raphael 1968; Dijkstra 1959; Pohl 1970).
//! - [`movingai`]: the Moving AI `.map` and `.scen` formats (Sturtevant 2012).
//! - [`wall_code`]: a compact URL-safe run-length code of a grid's walls.
//! - [`world`]: a continuous 2-D field with circle and rectangle obstacles and
//!   fixed-resolution collision checks.
//! - [`spatial_grid`]: a point index with growing bins for nearest and radius queries.
//! - [`drive_path`]: a polyline with its arc length, for a robot driving it.
//! - [`rrt_star`]: RRT, RRT* and Informed RRT*, one iteration at a time
//!   (LaValle 1998; Karaman & Frazzoli 2011; Gammell, Srinivasa & Barfoot 2014).

pub mod astar;
pub mod drive_path;
pub mod grid;
pub mod heuristic;
pub mod maze;
pub mod movingai;
pub mod rrt_star;
pub mod spatial_grid;
pub mod wall_code;
pub mod world;
