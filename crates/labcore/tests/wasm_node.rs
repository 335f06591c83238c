//! labcore under wasm32 (run in Node by wasm-bindgen-test): the generator
//! stream is bit-identical to native, the registry walk holds, and the
//! kinematics invariants hold in wasm too. Natively these are plain tests.

#[cfg(not(target_arch = "wasm32"))]
use std::prelude::v1::test as wasm_bindgen_test;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test;

use glam::DVec2;
use labcore::kinematics::chain::tip;
use labcore::kinematics::two_link_ik::{solve, Elbow};
use labcore::{registry, Lcg64, Scene};

/// First draws of `Lcg64::new(42)`, computed natively with u64 arithmetic.
#[wasm_bindgen_test]
fn lcg_stream_is_identical_to_native() {
    let mut rng = Lcg64::new(42);
    let mut s: u64 = 42;
    for _ in 0..1000 {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        assert_eq!(rng.next_u64(), s);
    }
    // u = (s >> 11) / 2^53 for the first draw of seed 0: s = 1442695040888963407.
    let mut rng = Lcg64::new(0);
    assert_eq!(rng.next_f64(), 704440937934064.0 / 9_007_199_254_740_992.0);
}

#[wasm_bindgen_test]
fn every_experiment_steps_with_finite_scenes() {
    for entry in registry() {
        let mut exp = (entry.make)();
        let mut scene = Scene::default();
        for _ in 0..200 {
            exp.step(1.0 / 60.0);
        }
        exp.scene(&mut scene);
        assert!(scene.is_finite(), "{}", entry.id);
        entry.content().unwrap();
    }
}

#[wasm_bindgen_test]
fn fk_of_ik_returns_the_target_in_wasm() {
    let mut rng = Lcg64::new(7);
    for _ in 0..2000 {
        let (l1, l2) = (rng.range(0.2, 1.5), rng.range(0.2, 1.5));
        let p = tip(&[l1, l2], &[rng.range(-3.0, 3.0), rng.range(-3.0, 3.0)]);
        if let Ok(sol) = solve(l1, l2, p) {
            for elbow in [Elbow::Up, Elbow::Down] {
                let a = sol.branch(elbow);
                assert!((tip(&[l1, l2], &[a.theta1_rad, a.theta2_rad]) - p).length() < 1e-9);
            }
        }
    }
    assert!(solve(1.0, 1.0, DVec2::new(5.0, 0.0)).is_err());
}

/// FNV-1a over the exact bits of a seeded 3R workspace sweep and a DLS solve.
fn run_fingerprint() -> u64 {
    use labcore::kinematics::dls::DlsSolver;
    use labcore::kinematics::workspace::{SamplingMode, WorkspaceSampler};
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut mix = |x: f64| {
        for byte in x.to_bits().to_le_bytes() {
            hash = (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
        }
    };
    let mut sampler =
        WorkspaceSampler::new([1.0, 0.8, 0.7], SamplingMode::MonteCarlo { seed: 1 }, 5000);
    let mut tips = Vec::new();
    sampler.sample_batch(5000, &mut tips);
    for p in &tips {
        mix(p.x);
        mix(p.y);
    }
    let mut q = [0.3; 7];
    let out = DlsSolver::default()
        .solve(&[1.0; 7], &mut q, DVec2::new(2.5, 3.1))
        .unwrap();
    q.iter().for_each(|a| mix(*a));
    mix(out.error_m);
    hash
}

/// The same seed gives bit-identical runs natively and in wasm: the
/// fingerprint was computed natively and must come out the same everywhere.
#[wasm_bindgen_test]
fn seeded_runs_are_bit_identical_on_every_target() {
    assert_eq!(
        run_fingerprint(),
        EXPECTED_FINGERPRINT,
        "{:#x}",
        run_fingerprint()
    );
}

const EXPECTED_FINGERPRINT: u64 = 0xef83_bbfd_1833_ec16;
