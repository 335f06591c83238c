//! # labbench — the benchmark scenarios of `shared/BENCHMARKS.md`
//!
//! Native only and outside the workspace's default members: it pulls in the
//! peers the lab's solvers are measured against (the `k` and `pathfinding` crates), which never
//! reach the wasm bundle. Each scenario is built here as plain data so a test
//! can check it and the `benches/` programs only time it.
//!
//! - [`planar_ik`]: n-link planar arm, 2,000 reachable targets, our
//!   [`labcore::kinematics::dls::DlsSolver`] against `k::JacobianIkSolver`.
//! - [`ekf`]: one EKF localisation step (predict + one landmark update) and
//!   one EKF-SLAM update at N = 20, 100, 200 landmarks.
//! - [`grid_astar`]: A* on a 1000 × 1000 random grid, our
//!   [`labcore::planning::astar::Search`] against `pathfinding::prelude::astar`.
//! - [`rrt_star`]: RRT* on the 30-circle world at 10,000 and 100,000 iterations,
//!   against OMPL's `RRTstar` (C++ peer `peers/ompl_rrtstar.cpp`, compiled by the
//!   bench with `g++ … -lompl` when `libompl-dev` is installed, skipped otherwise).
//!
//! Run with `cargo bench -p labbench`.

pub mod ekf;
pub mod grid_astar;
pub mod planar_ik;
pub mod rrt_star;
