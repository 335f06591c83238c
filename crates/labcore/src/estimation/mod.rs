//! State estimation for a planar mobile robot: EKF localisation and EKF-SLAM.
//!
//! - [`models`]: the velocity motion model `g`, its Jacobians, noisy motion
//!   sampling (the "true robot"), and a range-bearing sensor over point
//!   landmarks with maximum range and field of view.
//! - [`ekf`]: EKF localisation against known landmarks — [`ekf::ekf_predict`]
//!   (control-space noise `Q = V M Vᵀ`) or [`ekf::ekf_predict_with_q`] (a
//!   state-space `Q`), [`ekf::ekf_update`] (Joseph form), sequential updates,
//!   and a seeded simulation [`ekf::EkfLocalisation`] of truth + filter.
//! - [`slam`]: EKF-SLAM with landmarks added to the state on first sight
//!   ([`slam::EkfSlam::with_map`] / [`slam::EkfSlam::insert_landmark`] start
//!   from a prepared map), `O(N²)` updates per observation, and both forms of
//!   process noise.
//! - [`consistency`]: NEES, position/heading errors, χ² bounds and the
//!   covariance ellipse.
//!
//! The state is the pose `(x, y, θ)` in metres and radians, as a
//! [`glam::DVec3`]. Every function returns errors as values
//! ([`EstimationError`]) and leaves its inputs unchanged on error.

pub mod consistency;
pub mod ekf;
pub mod models;
pub mod slam;

use glam::{DMat2, DMat3, DVec3};
use std::f64::consts::PI;
use std::fmt;

/// Wraps an angle to `[−π, π)` (the convention of the bearing innovation).
///
/// # Example
/// ```
/// use labcore::estimation::wrap_angle;
/// use std::f64::consts::PI;
/// assert_eq!(wrap_angle(PI), -PI);
/// assert!((wrap_angle(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-15);
/// ```
#[must_use]
pub fn wrap_angle(angle_rad: f64) -> f64 {
    if (-PI..PI).contains(&angle_rad) {
        return angle_rad;
    }
    let w = (angle_rad + PI).rem_euclid(2.0 * PI) - PI;
    // rem_euclid can round up to exactly 2π for tiny negative inputs.
    if w >= PI {
        w - 2.0 * PI
    } else {
        w
    }
}

/// Why an estimation step was refused. The inputs are left as they were.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EstimationError {
    /// `dt` was NaN, infinite or negative.
    InvalidDt { dt_s: f64 },
    /// A state, covariance, control, noise setting or measurement was not
    /// finite (or a standard deviation negative).
    NonFinite,
    /// The landmark is (numerically) at the robot's position, where the
    /// bearing and its Jacobian are undefined.
    LandmarkTooClose { range_m: f64 },
    /// The innovation covariance `S` is not positive-definite.
    SingularInnovation,
    /// The observation names a landmark the map does not have.
    UnknownLandmark { id: usize },
    /// EKF-SLAM already holds its maximum number of landmarks.
    TooManyLandmarks { max: usize },
    /// A covariance given as input (a state-space process noise `Q`, a
    /// landmark's prior) is not symmetric positive semi-definite.
    NotCovariance,
    /// A landmark with this id is already in the EKF-SLAM state.
    DuplicateLandmark { id: usize },
}

impl fmt::Display for EstimationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidDt { dt_s } => {
                write!(f, "time step {dt_s} s is not a finite, non-negative number")
            }
            Self::NonFinite => write!(f, "an input was not finite"),
            Self::LandmarkTooClose { range_m } => {
                write!(f, "landmark {range_m} m from the robot: bearing undefined")
            }
            Self::SingularInnovation => write!(f, "innovation covariance is not positive-definite"),
            Self::UnknownLandmark { id } => write!(f, "no landmark with id {id}"),
            Self::TooManyLandmarks { max } => write!(f, "the map is full ({max} landmarks)"),
            Self::NotCovariance => {
                write!(f, "a covariance is not symmetric positive semi-definite")
            }
            Self::DuplicateLandmark { id } => write!(f, "landmark {id} is already in the map"),
        }
    }
}

impl std::error::Error for EstimationError {}

/// Checks that `a` is a covariance: finite, symmetric and positive
/// semi-definite (every principal minor ≥ 0), each within rounding.
pub(crate) fn check_cov3(a: DMat3) -> Result<(), EstimationError> {
    if !a.is_finite() {
        return Err(EstimationError::NonFinite);
    }
    let m = |i: usize, j: usize| a.col(j)[i];
    let scale = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .map(|(i, j)| m(i, j).abs())
        .fold(0.0, f64::max);
    let tol = 1e-12 * scale.max(f64::MIN_POSITIVE);
    let symmetric = (0..3).all(|i| (0..3).all(|j| (m(i, j) - m(j, i)).abs() <= tol));
    let minors2 = [(0, 1), (0, 2), (1, 2)]
        .iter()
        .all(|&(i, j)| m(i, i) * m(j, j) - m(i, j) * m(j, i) >= -tol * scale);
    let psd = (0..3).all(|i| m(i, i) >= 0.0) && minors2 && a.determinant() >= -tol * scale * scale;
    if symmetric && psd {
        Ok(())
    } else {
        Err(EstimationError::NotCovariance)
    }
}

/// [`check_cov3`] for a 2 × 2 covariance.
pub(crate) fn check_cov2(a: DMat2) -> Result<(), EstimationError> {
    check_cov3(DMat3::from_cols(
        a.x_axis.extend(0.0),
        a.y_axis.extend(0.0),
        DVec3::ZERO,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_angle_is_half_open() {
        assert_eq!(wrap_angle(PI), -PI);
        assert_eq!(wrap_angle(-PI), -PI);
        assert_eq!(wrap_angle(0.25), 0.25);
        assert!((wrap_angle(7.0 * PI) + PI).abs() < 1e-12);
        assert!((wrap_angle(-2.5 * PI) + 0.5 * PI).abs() < 1e-12);
        let mut rng = crate::rng::Lcg64::new(3);
        for _ in 0..10_000 {
            let a = rng.range(-100.0, 100.0);
            let w = wrap_angle(a);
            assert!((-PI..PI).contains(&w));
            let k = (a - w) / (2.0 * PI);
            assert!((k - k.round()).abs() < 1e-9);
        }
        assert!(wrap_angle(f64::NAN).is_nan());
        assert_eq!(wrap_angle(-1e-300), -1e-300);
    }
}
