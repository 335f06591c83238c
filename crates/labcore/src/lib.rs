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
//! - [`control`] — PID on a mass with drag and its closed-loop poles, python-control
//!   step metrics, the Barto–Sutton–Anderson cart-pole, LQR by the Riccati equation
//!   (Åström & Murray, *Feedback Systems*; Barto, Sutton & Anderson 1983; Laub 1979).
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
//! - [`planning::astar`] — incremental A*, Dijkstra, weighted A* and greedy
//!   best-first search on an occupancy grid (Hart, Nilsson & Raphael 1968;
//!   Dijkstra 1959; Pohl 1970); [`planning::movingai`] reads the Moving AI
//!   benchmark maps (Sturtevant 2012).
//! - [`planning::rrt_star`] — RRT, RRT* and Informed RRT* with a growing-bin
//!   spatial index (LaValle 1998; Karaman & Frazzoli, IJRR 2011; Gammell,
//!   Srinivasa & Barfoot, IROS 2014).
//!
//! ## Angles
//! Every angle labcore returns is in radians and wrapped to `[-π, π]` by
//! [`kinematics::two_link_ik::wrap_pi`]: the tip orientation
//! [`kinematics::chain::ChainPose::tip_angle_rad`], both closed-form IK
//! branches ([`kinematics::two_link_ik::TwoLinkAngles`]: θ₁ in `[-π, π]`,
//! θ₂ in `[-π, 0]` elbow up and `[0, π]` elbow down; the wrist angle θ₃ in
//! `[-π, π]`), and the joint angles DLS writes back
//! ([`kinematics::dls::DlsSolver::step`], [`kinematics::dls::DlsSolver::solve`]).
//! Experiments show the same angles in degrees, in `[-180°, 180°]`.
//!
//! ## glam
//! The geometry API takes and returns [`glam::DVec2`]; glam is re-exported
//! (`labcore::glam`) so users need no separate, version-matched dependency.
//!
//! ## The seam
//! Every experiment implements [`Experiment`]; [`registry`] lists them with
//! their content file and quiz generators.

pub mod bresenham;
pub mod catalogue;
pub mod clock;
pub mod content;
pub mod control;
pub mod estimation;
pub mod experiment;
pub mod experiments;
pub mod json;
pub mod kinematics;
pub mod layout;
pub mod linalg;
pub mod live_math;
pub mod lms;
pub mod marks;
pub mod math;
pub mod memo;
pub mod mobile;
pub mod planning;
pub mod plot;
pub mod quiz;
pub mod rng;
pub mod route;
pub mod run_input;
pub mod scene;
#[cfg(feature = "reading")]
pub mod step_numbers;
pub mod table;
// Tests only: native builds, and the wasm test builds, which have the whole
// content (`reading`, a default feature). The shipped wasm modules are built
// without default features and never carry it (unused, it still shifted the
// optimiser's choices by about 300 bytes a module).
#[cfg(any(test, feature = "reading", not(target_arch = "wasm32")))]
pub mod testkit;
pub mod timeline;
pub mod units;

pub use clock::Clock;
pub use content::Content;
pub use experiment::{
    ActionSpec, Experiment, Handle, Input, Lab, Modifiers, Notice, Notices, ParamError, ParamKind,
    ParamSpec, Phase, Presentation, Preset, Readout, Sanitized, Status, Tone,
};
pub use experiments::{find, registry, Entry};
pub use glam;
pub use plot::{Plot, Series, SeriesRole};
pub use rng::Lcg64;
pub use scene::{BackdropKey, Item, RasterColour, Role, Scene, ViewBox};
pub use table::Table;
