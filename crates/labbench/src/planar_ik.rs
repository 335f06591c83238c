//! The "Planar IK" scenario of `shared/BENCHMARKS.md`.
//!
//! - n-link planar arm, links of length 1 m, unlimited joints, position-only
//!   target `(x, y)`;
//! - 2,000 targets from forward kinematics of random configurations: one
//!   [`Lcg64`] seeded with 42 per arm size, angles uniform in `[-π, π)`, drawn
//!   `θ1 … θn` per target (so every target is reachable);
//! - start pose 0.3 rad on every joint, reset before each target;
//! - success when `|error| < 1e-5` m; n = 3 and n = 7.
//!
//! Peer: `k` 0.32's `JacobianIkSolver` on the equivalent chain — `n` revolute
//! joints about z, joint `i > 0` translated 1 m along x from joint `i − 1`, and
//! a fixed end link 1 m further along x — with only `position_x` and
//! `position_y` constrained.

use glam::DVec2;
use k::nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use k::{InverseKinematicsSolver, JacobianIkSolver, SerialChain};
use labcore::kinematics::chain::tip;
use labcore::kinematics::dls::{AdaptiveDamping, DlsSolver};
use labcore::Lcg64;
use std::f64::consts::PI;

/// Targets per arm size.
pub const TARGET_COUNT: usize = 2000;
/// Seed of the scenario's LCG.
pub const SEED: u64 = 42;
/// Every link, metres.
pub const LINK_M: f64 = 1.0;
/// Start angle of every joint, radians.
pub const START_ANGLE_RAD: f64 = 0.3;
/// A solve succeeds when the tip error is below this, metres.
pub const SUCCESS_M: f64 = 1e-5;
/// The arm sizes the scenario runs.
pub const ARM_SIZES: [usize; 2] = [3, 7];

/// One arm size of the scenario.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Number of joints.
    pub n: usize,
    /// `n` links of [`LINK_M`].
    pub lengths_m: Vec<f64>,
    /// The joint angles each target was made from, radians.
    pub configurations: Vec<Vec<f64>>,
    /// [`TARGET_COUNT`] reachable targets, metres.
    pub targets: Vec<DVec2>,
}

impl Scenario {
    /// Builds the scenario for an `n`-joint arm.
    #[must_use]
    pub fn new(n: usize) -> Self {
        let lengths_m = vec![LINK_M; n];
        let mut rng = Lcg64::new(SEED);
        let configurations: Vec<Vec<f64>> = (0..TARGET_COUNT)
            .map(|_| (0..n).map(|_| rng.range(-PI, PI)).collect())
            .collect();
        let targets = configurations.iter().map(|q| tip(&lengths_m, q)).collect();
        Self {
            n,
            lengths_m,
            configurations,
            targets,
        }
    }

    /// The start pose, [`START_ANGLE_RAD`] on every joint.
    #[must_use]
    pub fn start(&self) -> Vec<f64> {
        vec![START_ANGLE_RAD; self.n]
    }
}

/// Success count and iterations of one pass over a scenario.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassStats {
    pub solves: usize,
    pub successes: usize,
    /// Sum of iterations over all solves.
    pub iterations: usize,
    /// Largest final tip error, metres.
    pub worst_error_m: f64,
}

impl PassStats {
    #[must_use]
    pub fn success_rate(&self) -> f64 {
        self.successes as f64 / self.solves.max(1) as f64
    }
    #[must_use]
    pub fn mean_iterations(&self) -> f64 {
        self.iterations as f64 / self.solves.max(1) as f64
    }
}

/// The lab's [`DlsSolver`] as the benchmark runs it: the default settings
/// with the scenario's success tolerance.
#[must_use]
pub fn our_solver() -> DlsSolver {
    DlsSolver {
        tolerance_m: SUCCESS_M,
        ..DlsSolver::default()
    }
}

/// Variants of our solver worth comparing in the same run (name, settings).
#[must_use]
pub fn our_variants() -> Vec<(&'static str, DlsSolver)> {
    vec![
        ("default (bench tolerance)", our_solver()),
        (
            "adaptive w0=0.1 λmax=0.2",
            DlsSolver {
                adaptive: Some(AdaptiveDamping {
                    w_threshold: 0.1,
                    lambda_max: 0.2,
                }),
                ..our_solver()
            },
        ),
    ]
}

/// Solves one target with ours from the start pose; returns (error m, iterations).
#[inline]
pub fn solve_ours(solver: &DlsSolver, lengths_m: &[f64], target: DVec2) -> (f64, usize) {
    let mut q = [START_ANGLE_RAD; 8];
    let q = &mut q[..lengths_m.len()];
    match solver.solve(lengths_m, q, target) {
        Ok(out) => (out.error_m, out.iterations),
        Err(_) => (f64::INFINITY, 0),
    }
}

/// One pass of ours over the scenario.
#[must_use]
pub fn pass_ours(solver: &DlsSolver, scenario: &Scenario) -> PassStats {
    let mut stats = PassStats::default();
    for &target in &scenario.targets {
        let (err, it) = solve_ours(solver, &scenario.lengths_m, target);
        stats.solves += 1;
        stats.iterations += it;
        stats.worst_error_m = stats.worst_error_m.max(err);
        if err < SUCCESS_M {
            stats.successes += 1;
        }
    }
    stats
}

/// The `k` chain equivalent to `n` unit links.
#[must_use]
pub fn k_chain(n: usize) -> SerialChain<f64> {
    let mut nodes: Vec<k::Node<f64>> = (0..n)
        .map(|i| {
            k::NodeBuilder::new()
                .name(&format!("joint{i}"))
                .joint_type(k::JointType::Rotational {
                    axis: Vector3::z_axis(),
                })
                .translation(Translation3::new(
                    if i == 0 { 0.0 } else { LINK_M },
                    0.0,
                    0.0,
                ))
                .into_node()
        })
        .collect();
    nodes.push(
        k::NodeBuilder::new()
            .name("tip")
            .joint_type(k::JointType::Fixed)
            .translation(Translation3::new(LINK_M, 0.0, 0.0))
            .into_node(),
    );
    for i in 1..nodes.len() {
        nodes[i].set_parent(&nodes[i - 1]);
    }
    SerialChain::from_end(nodes.last().expect("n + 1 nodes"))
}

/// Position-only (x, y) constraints for `k`.
#[must_use]
pub fn k_constraints() -> k::Constraints {
    k::Constraints {
        position_x: true,
        position_y: true,
        position_z: false,
        rotation_x: false,
        rotation_y: false,
        rotation_z: false,
        ignored_joint_names: Vec::new(),
    }
}

/// `k`'s solver with the scenario's tolerance and generous iterations.
/// `jacobian_multiplier` 1.0 takes full Gauss–Newton steps (the crate's
/// default is 0.5).
#[must_use]
pub fn k_solver(jacobian_multiplier: f64, num_max_try: usize) -> JacobianIkSolver<f64> {
    JacobianIkSolver::new(SUCCESS_M, 1.0, jacobian_multiplier, num_max_try)
}

/// The k target pose: translation (x, y, 0), identity rotation (ignored).
#[must_use]
pub fn k_target(p: DVec2) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::new(p.x, p.y, 0.0), UnitQuaternion::identity())
}

/// Solves one target with `k` from the start pose; returns the final error (m).
/// (k restores the start pose when it fails.)
pub fn solve_k(
    solver: &JacobianIkSolver<f64>,
    arm: &SerialChain<f64>,
    constraints: &k::Constraints,
    start: &[f64],
    target: &Isometry3<f64>,
) -> f64 {
    arm.set_joint_positions_unchecked(start);
    let _ = solver.solve_with_constraints(arm, target, constraints);
    let t = arm.end_transform().translation.vector;
    let d = DVec2::new(
        t.x - target.translation.vector.x,
        t.y - target.translation.vector.y,
    );
    d.length()
}

/// Iterations `k` needs for one target: the smallest `num_max_try` that
/// succeeds (k is deterministic and stops at its first success, so this is its
/// iteration count); `max_try` when it never succeeds.
pub fn k_iterations(
    multiplier: f64,
    max_try: usize,
    arm: &SerialChain<f64>,
    constraints: &k::Constraints,
    start: &[f64],
    target: &Isometry3<f64>,
) -> usize {
    let ok = |tries: usize| {
        solve_k(
            &k_solver(multiplier, tries),
            arm,
            constraints,
            start,
            target,
        ) < SUCCESS_M
    };
    if !ok(max_try) {
        return max_try;
    }
    let (mut lo, mut hi) = (0, max_try); // ok(hi), !ok(lo) (0 tries never succeeds)
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if ok(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// One pass of `k` over the scenario, with iteration counts (slow: not timed).
#[must_use]
pub fn pass_k(multiplier: f64, max_try: usize, scenario: &Scenario) -> PassStats {
    let arm = k_chain(scenario.n);
    let constraints = k_constraints();
    let solver = k_solver(multiplier, max_try);
    let start = scenario.start();
    let mut stats = PassStats::default();
    for &p in &scenario.targets {
        let target = k_target(p);
        let err = solve_k(&solver, &arm, &constraints, &start, &target);
        stats.solves += 1;
        stats.worst_error_m = stats.worst_error_m.max(err);
        if err < SUCCESS_M {
            stats.successes += 1;
        }
        stats.iterations += k_iterations(multiplier, max_try, &arm, &constraints, &start, &target);
    }
    stats
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scenario_is_deterministic_and_reachable() {
        for n in ARM_SIZES {
            let s = Scenario::new(n);
            assert_eq!(s.targets.len(), TARGET_COUNT);
            assert_eq!(s, Scenario::new(n));
            assert!(s.targets.iter().all(|p| p.length() <= n as f64 + 1e-12));
            assert!(s
                .configurations
                .iter()
                .flatten()
                .all(|a| (-PI..PI).contains(a)));
        }
        // The first configuration is the first n draws of Lcg64(42).
        let mut rng = Lcg64::new(SEED);
        let q: Vec<f64> = (0..3).map(|_| rng.range(-PI, PI)).collect();
        assert_eq!(Scenario::new(3).targets[0], tip(&[1.0; 3], &q));
    }

    #[test]
    fn k_chain_matches_labcore_forward_kinematics() {
        for n in ARM_SIZES {
            let s = Scenario::new(n);
            let arm = k_chain(n);
            assert_eq!(arm.dof(), n);
            for (q, p) in s.configurations.iter().zip(&s.targets).take(50) {
                arm.set_joint_positions(q).unwrap();
                let t = arm.end_transform().translation.vector;
                assert!((DVec2::new(t.x, t.y) - *p).length() < 1e-12);
                assert!(t.z.abs() < 1e-12);
            }
        }
    }

    #[test]
    fn both_solvers_solve_a_few_targets() {
        for n in ARM_SIZES {
            let s = Scenario::new(n);
            let solver = our_solver();
            let arm = k_chain(n);
            let ks = k_solver(1.0, 500);
            for &p in s.targets.iter().take(20) {
                let (err, _) = solve_ours(&solver, &s.lengths_m, p);
                assert!(err < SUCCESS_M);
                let kerr = solve_k(&ks, &arm, &k_constraints(), &s.start(), &k_target(p));
                assert!(kerr.is_finite());
            }
        }
    }
}
