//! # labbench — the benchmark scenarios of `shared/BENCHMARKS.md`
//!
//! Native only and outside the workspace's default members: it pulls in the
//! peers the lab's solvers are measured against (the `k` crate), which never
//! reach the wasm bundle. Each scenario is built here as plain data so a test
//! can check it and the `benches/` programs only time it.
//!
//! - [`planar_ik`]: n-link planar arm, 2,000 reachable targets, our
//!   [`labcore::kinematics::dls::DlsSolver`] against `k::JacobianIkSolver`.
//! - [`ekf`]: one EKF localisation step (predict + one landmark update) and
//!   one EKF-SLAM update at N = 20, 100, 200 landmarks.
//!
//! Run with `cargo bench -p labbench`.

pub mod ekf;
pub mod planar_ik;
