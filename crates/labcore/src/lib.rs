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
//! - [`linalg`] — dense row-major matrix, LU with partial pivoting, inverse, Cholesky
//!   (Golub & Van Loan, *Matrix Computations*, 4th ed., §3.4, §4.2).
//! - [`mobile::unicycle`], [`mobile::go_to_goal`] — unicycle model (Euler/RK4) and
//!   proportional go-to-goal control (Siegwart, Nourbakhsh & Scaramuzza,
//!   *Introduction to Autonomous Mobile Robots*, Ch. 3).
//! - [`mobile::potential_field`] — artificial potential fields with local-minimum
//!   detection (Khatib 1986; Koren & Borenstein 1991).
//! - [`estimation::ekf`], [`estimation::slam`] — EKF localisation with known
//!   landmarks and EKF-SLAM (Thrun, Burgard & Fox, *Probabilistic Robotics*,
//!   Ch. 7 and 10); NEES consistency checks (Bar-Shalom, Li & Kirubarajan 2001).
//!
//! ## The seam
//! Every experiment implements [`Experiment`]; [`registry`] lists them with
//! their content file and quiz generators.

pub mod content;
pub mod estimation;
pub mod experiment;
pub mod experiments;
pub mod kinematics;
pub mod linalg;
pub mod math;
pub mod mobile;
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
