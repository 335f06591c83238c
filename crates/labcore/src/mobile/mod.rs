//! Wheeled mobile robots in the plane.
//!
//! - [`unicycle`]: the differential-drive (unicycle) model, Euler and RK4
//!   integration, wheel speeds.
//! - [`go_to_goal`]: the proportional heading + speed controller and a
//!   waypoint follower with per-goal statistics.
//! - [`field`]: the rectangular field the robot drives on: clicks snapped
//!   into it and the robot's bounded trail.
//! - [`potential_field`]: attractive/repulsive potential-field navigation with
//!   local-minimum detection and a progressive basin-of-attraction map.

pub mod field;
pub mod go_to_goal;
pub mod potential_field;
pub mod unicycle;
