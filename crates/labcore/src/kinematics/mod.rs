//! Planar arm kinematics.
//!
//! - [`chain`]: forward kinematics of an n-link chain and its reach annulus.
//! - [`two_link_ik`]: closed-form 2-link inverse kinematics, both elbow branches.
//! - [`workspace`]: seeded Monte-Carlo and grid sampling of a 3R arm's workspace.
//! - [`jacobian`]: the planar geometric Jacobian and manipulability.
//! - [`dls`]: damped-least-squares (Levenberg–Marquardt) inverse kinematics.

pub mod chain;
pub mod dls;
pub mod jacobian;
pub mod two_link_ik;
pub mod workspace;
