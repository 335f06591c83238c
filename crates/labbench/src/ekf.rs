//! The "EKF" scenarios of `shared/BENCHMARKS.md`.
//!
//! - **Localisation step**: one [`ekf_predict`] (velocity motion model,
//!   `u = (1 m/s, 0.2 rad/s)`, `dt = 0.1 s`) followed by one [`ekf_update`]
//!   with a range-bearing observation of one known landmark. Peer figure:
//!   PythonRobotics' `extended_kalman_filter.py`, about 32 µs a step.
//! - **EKF-SLAM update**: one [`EkfSlam::observe`] of an already-mapped
//!   landmark with `N` = 20, 100 and 200 landmarks in the state (`n = 3 + 2N`).
//!   Landmarks sit on a circle of radius 5 m around the robot, drawn from one
//!   [`Lcg64`] seeded with [`SEED`]; the filter is built by initialising each
//!   from a noisy observation and predicting one step between them.
//!   Observations cycle through the landmarks, each the filter's own expected
//!   measurement plus a fixed seeded perturbation.

use glam::{DMat2, DMat3, DVec2, DVec3};
use labcore::estimation::ekf::{ekf_predict, ekf_update, Belief};
use labcore::estimation::models::{
    observation_model, Control, MotionNoise, Observation, SensorNoise,
};
use labcore::estimation::slam::EkfSlam;
use labcore::estimation::wrap_angle;
use labcore::Lcg64;
use std::f64::consts::PI;

/// Seed of the scenario's LCG.
pub const SEED: u64 = 42;
/// Control of the localisation step.
pub const CONTROL: Control = Control::new(1.0, 0.2);
/// Time step, seconds.
pub const DT_S: f64 = 0.1;
/// Landmark counts of the SLAM scenario.
pub const SLAM_SIZES: [usize; 3] = [20, 100, 200];

/// Inputs of one localisation step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalisationStep {
    pub belief: Belief,
    pub noise: MotionNoise,
    pub landmark: DVec2,
    pub observation: Observation,
    pub r: DMat2,
}

impl LocalisationStep {
    /// The fixed step: belief at (1, 2, 0.5) with a full covariance, a
    /// landmark 3 m away, an observation slightly off the prediction.
    #[must_use]
    pub fn new() -> Self {
        let mean = DVec3::new(1.0, 2.0, 0.5);
        let cov = DMat3::from_cols(
            DVec3::new(0.04, 0.01, 0.002),
            DVec3::new(0.01, 0.05, 0.003),
            DVec3::new(0.002, 0.003, 0.01),
        );
        let landmark = DVec2::new(3.5, 3.7);
        let predicted = labcore::estimation::models::motion_model(mean, CONTROL, DT_S);
        let z = observation_model(predicted, landmark);
        Self {
            belief: Belief { mean, cov },
            noise: MotionNoise::default(),
            landmark,
            observation: Observation {
                id: 0,
                range_m: z.x + 0.05,
                bearing_rad: wrap_angle(z.y - 0.02),
            },
            r: SensorNoise::default().r(),
        }
    }

    /// One predict + one update; the new belief (unchanged input on error).
    #[inline]
    #[must_use]
    pub fn run(&self) -> Belief {
        let Ok(p) = ekf_predict(
            self.belief.mean,
            self.belief.cov,
            CONTROL,
            DT_S,
            &self.noise,
        ) else {
            return self.belief;
        };
        match ekf_update(p.mean, p.cov, &self.observation, self.landmark, self.r) {
            Ok(up) => up.belief,
            Err(_) => p,
        }
    }
}

impl Default for LocalisationStep {
    fn default() -> Self {
        Self::new()
    }
}

/// An EKF-SLAM filter holding `n_landmarks` landmarks, and their true positions.
#[must_use]
pub fn slam_filter(n_landmarks: usize) -> (EkfSlam, Vec<DVec2>) {
    let mut rng = Lcg64::new(SEED);
    let mut slam = EkfSlam::new(DVec3::ZERO, DMat3::from_diagonal(DVec3::splat(1e-4)));
    slam.max_landmarks = n_landmarks.max(1);
    let noise = SensorNoise::default();
    let map: Vec<DVec2> = (0..n_landmarks)
        .map(|_| {
            let a = rng.range(-PI, PI);
            DVec2::new(5.0 * labcore::math::cos(a), 5.0 * labcore::math::sin(a))
        })
        .collect();
    for (id, &m) in map.iter().enumerate() {
        let z = observation_model(slam.pose(), m);
        let obs = Observation {
            id,
            range_m: rng.normal(z.x, noise.sigma_range_m),
            bearing_rad: wrap_angle(rng.normal(z.y, noise.sigma_bearing_rad)),
        };
        let _ = slam.observe(&obs, noise.r());
        let _ = slam.predict(Control::new(0.0, 0.01), DT_S, &MotionNoise::default());
    }
    (slam, map)
}

/// Observations for the SLAM update loop: for each landmark, its expected
/// measurement from the current filter plus a seeded perturbation.
#[must_use]
pub fn slam_observations(slam: &EkfSlam) -> Vec<Observation> {
    let mut rng = Lcg64::new(SEED + 1);
    slam.landmarks()
        .map(|(id, m)| {
            let z = observation_model(slam.pose(), m);
            Observation {
                id,
                range_m: z.x + rng.normal(0.0, 0.05),
                bearing_rad: wrap_angle(z.y + rng.normal(0.0, 0.01)),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use labcore::estimation::slam::SlamObservation;

    #[test]
    fn localisation_step_updates_and_shrinks_covariance() {
        let s = LocalisationStep::new();
        let b = s.run();
        assert_ne!(b.mean, s.belief.mean);
        let tr = |m: DMat3| m.x_axis.x + m.y_axis.y + m.z_axis.z;
        assert!(tr(b.cov) < tr(s.belief.cov));
    }

    #[test]
    fn slam_filters_have_the_requested_size_and_accept_updates() {
        for n in SLAM_SIZES {
            let (mut slam, map) = slam_filter(n);
            assert_eq!(slam.landmark_count(), n);
            assert_eq!(map.len(), n);
            let obs = slam_observations(&slam);
            assert_eq!(obs.len(), n);
            for z in obs.iter().take(5) {
                assert!(matches!(
                    slam.observe(z, SensorNoise::default().r()),
                    Ok(SlamObservation::Updated { .. })
                ));
            }
            assert!(slam.cov().is_symmetric(0.0));
        }
    }
}
