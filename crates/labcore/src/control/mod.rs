//! Control solvers: PID on a mass with drag, the nonlinear cart-pole, LQR.
//!
//! Plain types and functions, usable without any experiment page:
//!
//! - [`pid`]: a PID controller (integral clamp, derivative on measurement, derivative
//!   filter, actuator saturation), the mass-drag plant `m·a = u − c·v`, the closed loop
//!   with seeded sensor noise, and its closed-loop poles
//!   (Åström & Murray, *Feedback Systems*, 2nd ed., 2021, Ch. 11; Åström & Hägglund,
//!   *Advanced PID Control*, ISA, 2006, Ch. 3).
//! - [`step_info`]: rise time, settling time, overshoot and peak of a sampled step
//!   response, with python-control's `step_info` definitions.
//! - [`cartpole`]: the cart-pole of Barto, Sutton & Anderson (1983), explicit Euler as in
//!   the CartPole-v1 benchmark or RK4, energy, linearisation, state feedback.
//! - [`lqr`]: the continuous algebraic Riccati equation and LQR gains
//!   (Laub 1979; Kleinman 1968; Anderson & Moore, *Optimal Control*, 1990).
//! - [`poly`]: complex numbers, polynomial roots and eigenvalues of small matrices.
//!
//! Every stepping function refuses a NaN, infinite, zero or negative `dt` and leaves the
//! state untouched (it returns `false` or `None`); none of them panics on bad numbers.

pub mod cartpole;
pub mod lqr;
pub mod pid;
pub mod poly;
pub mod step_info;

pub use poly::Complex;

/// Where the poles of a linear system lie.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stability {
    /// Every pole has a negative real part: responses decay.
    Stable,
    /// No pole in the open right half-plane but at least one on the imaginary axis
    /// (within tolerance): responses neither decay nor grow (or grow polynomially).
    MarginallyStable,
    /// A pole in the right half-plane: responses grow exponentially.
    Unstable,
}

impl Stability {
    /// The verdict for a set of poles: a real part within `1e-9 · max(1, |p|max)` of
    /// zero counts as on the axis.
    #[must_use]
    pub fn of(poles: &[Complex]) -> Self {
        let scale = poles.iter().fold(1.0_f64, |m, p| m.max(p.abs()));
        let tol = 1e-9 * scale;
        let max_re = poly::spectral_abscissa(poles);
        if max_re > tol {
            Stability::Unstable
        } else if max_re >= -tol {
            Stability::MarginallyStable
        } else {
            Stability::Stable
        }
    }
}

/// Number of poles with real part above `1e-9 · max(1, |p|max)` (right half-plane).
#[must_use]
pub fn count_right_half_plane(poles: &[Complex]) -> usize {
    let scale = poles.iter().fold(1.0_f64, |m, p| m.max(p.abs()));
    poles.iter().filter(|p| p.re > 1e-9 * scale).count()
}
