//! # labcore — solvers and experiment state of the robotics virtual lab
//!
//! Pure Rust: no DOM, no JavaScript. Builds and tests natively and for
//! `wasm32-unknown-unknown`. Angles are radians and lengths metres inside this
//! crate; degrees appear only in [`ParamSpec`]s shown on the page.
//!
//! ## Solvers and their references
//! - [`kinematics::chain`] — planar serial-chain forward kinematics
//!   (Spong, Hutchinson & Vidyasagar, *Robot Modeling and Control*, Ch. 3).
//! - [`kinematics::two_link_ik`] — closed-form 2-link IK by the law of cosines
//!   (Spong et al. 2006, Ch. 3; Craig, *Introduction to Robotics*, Ch. 4).
//! - [`kinematics::workspace`] — Monte-Carlo and grid workspace sampling of a 3R arm
//!   (Siciliano et al., *Robotics: Modelling, Planning and Control*, Ch. 2).
//! - [`kinematics::jacobian`], [`kinematics::dls`] — planar geometric Jacobian,
//!   manipulability and damped-least-squares IK (Buss 2004; Nakamura & Hanafusa 1986;
//!   Wampler 1986).
//! - [`planning::astar`] — incremental A*, Dijkstra, weighted A* and greedy
//!   best-first search on an occupancy grid (Hart, Nilsson & Raphael 1968;
//!   Dijkstra 1959; Pohl 1970); [`planning::movingai`] reads the Moving AI
//!   benchmark maps (Sturtevant 2012).
//! - [`planning::rrt_star`] — RRT, RRT* and Informed RRT* with a growing-bin
//!   spatial index (LaValle 1998; Karaman & Frazzoli, IJRR 2011; Gammell,
//!   Srinivasa & Barfoot, IROS 2014).
//!
//! ## The seam
//! Every experiment implements [`Experiment`]; [`registry`] lists them with
//! their content file and quiz generators.

pub mod content;
pub mod experiment;
pub mod experiments;
pub mod kinematics;
pub mod math;
pub mod planning;
pub mod quiz;
pub mod rng;
pub mod route;
pub mod scene;

pub use content::Content;
pub use experiment::{
    ActionSpec, Experiment, Input, ParamError, ParamKind, ParamSpec, Readout, Sanitized, Status,
    Tone,
};
pub use experiments::{find, registry, Entry};
pub use rng::Lcg64;
pub use scene::{Item, Role, Scene, ViewBox};
