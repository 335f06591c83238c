//! The cart-pole (inverted pendulum on a cart) of Barto, Sutton & Anderson (1983).
//!
//! **Equations** (Barto, Sutton & Anderson, "Neuronlike adaptive elements that can solve
//! difficult learning control problems", *IEEE Trans. SMC* 13(5), 1983, p. 841, with its
//! friction terms; with both set to zero this is the CartPole benchmark's (Gym's) form,
//! as in the lab description): a cart of mass `M` on a level track,
//! a uniform pole of mass `m` and half-length `l` hinged on it, horizontal force `F`,
//! cart friction `μc` (N) and pivot friction `μp` (N·m·s):
//!
//! ```text
//! temp = (F + m l θ̇² sin θ − μc sgn ẋ) / (M + m)
//! θ̈    = (g sin θ − cos θ · temp − μp θ̇ / (m l)) / (l (4/3 − m cos²θ / (M + m)))
//! ẍ    = temp − m l θ̈ cos θ / (M + m)
//! ```
//!
//! Florian ("Correct equations for the dynamics of the cart-pole system", 2007, eqs.
//! 21–23) derives the exact cart-friction term `μc N_c sgn(N_c ẋ)` with the normal force
//! `N_c`; it reduces to the form above when friction is zero — the default — and the
//! frictionless equations are exact (Florian 2007, eq. 23 with `μc = μp = 0`).
//!
//! **Sign convention.** `x` is the cart position (m, positive to the right); `θ` is the
//! pole angle from upright (rad): `θ = 0` is upright and `θ > 0` leans toward `+x`, so
//! the pole's centre is at `(x + l sin θ, l cos θ)` above the pivot. A positive force
//! pushes the cart toward `+x`, which swings the pole back toward `−x` (`∂θ̈/∂F < 0`).
//!
//! **Integration** with the force held over a step (zero-order hold), optionally split
//! into sub-steps:
//! - [`Integrator::Euler`] — the explicit Euler step of the CartPole-v1 benchmark
//!   (Gymnasium `cartpole.py`, `kinematics_integrator = "euler"`): with accelerations
//!   from the old state, `x ← x + τẋ; ẋ ← ẋ + τẍ; θ ← θ + τθ̇; θ̇ ← θ̇ + τθ̈`
//!   (positions use the old velocities). First order. One such step of 0.02 s with
//!   an endless track (`track_limit_m = ∞`) is the benchmark's step; sub-steps or end
//!   stops make it a different (if close) simulation.
//! - [`Integrator::Rk4`] — classical fourth-order Runge–Kutta.
//!
//! **Energy** `E = ½(M + m)ẋ² + m l ẋ θ̇ cos θ + ⅔ m l² θ̇² + m g l cos θ` (the pole's
//! moment of inertia about its centre is `m l²/3`), conserved when `F = 0` and there is
//! no friction.
//!
//! **Linearisation** about the upright equilibrium, state `s = [x, ẋ, θ, θ̇]`, with
//! `μ = M + m` and `D = l (4/3 − m/μ)` (Coulomb cart friction left out):
//!
//! ```text
//! A = [[0, 1, 0,            0          ],
//!      [0, 0, −m l g/(μ D), μp/(μ D)   ],
//!      [0, 0, 0,            1          ],
//!      [0, 0, g/D,          −μp/(m l D)]]
//! B = [0, 1/μ + m l/(μ² D), 0, −1/(μ D)]ᵀ
//! ```
//!
//! **Control.** The lab's linear state feedback `F = kx·x + kv·ẋ + kθ·θ + kω·θ̇`
//! ([`StateFeedback`]); LQR's `u = −K s` corresponds to `k = −K` ([`lqr_feedback`]).

use super::lqr::{care, LqrError};
use super::poly::{eigenvalues, Complex, RootError};
use crate::linalg::Matrix;

/// Physical parameters. Defaults are the CartPole benchmark's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CartPoleParams {
    /// `g` (m/s²), default 9.8.
    pub gravity_m_s2: f64,
    /// Cart mass `M` (kg), default 1.0.
    pub cart_mass_kg: f64,
    /// Pole mass `m` (kg), default 0.1.
    pub pole_mass_kg: f64,
    /// Pole half-length `l` (m), default 0.5.
    pub half_length_m: f64,
    /// Coulomb friction force of the cart `μc` (N), default 0.
    pub cart_friction_n: f64,
    /// Viscous pivot friction `μp` (N·m·s), default 0.
    pub pole_friction_n_m_s: f64,
    /// Actuator limit, `|F| ≤` this (N); `f64::INFINITY` for none. Default 30 N.
    pub force_limit_n: f64,
    /// End stops at `x = ±` this (m); `f64::INFINITY` for an endless track. Default 2.4 m.
    pub track_limit_m: f64,
}

impl Default for CartPoleParams {
    fn default() -> Self {
        Self {
            gravity_m_s2: 9.8,
            cart_mass_kg: 1.0,
            pole_mass_kg: 0.1,
            half_length_m: 0.5,
            cart_friction_n: 0.0,
            pole_friction_n_m_s: 0.0,
            force_limit_n: 30.0,
            track_limit_m: 2.4,
        }
    }
}

/// Cart-pole state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CartPoleState {
    /// Cart position (m).
    pub x_m: f64,
    /// Cart velocity (m/s).
    pub v_m_s: f64,
    /// Pole angle from upright, `θ > 0` leaning toward `+x` (rad).
    pub theta_rad: f64,
    /// Pole angular velocity (rad/s).
    pub omega_rad_s: f64,
}

impl CartPoleState {
    /// `[x, ẋ, θ, θ̇]`.
    #[must_use]
    pub fn to_array(&self) -> [f64; 4] {
        [self.x_m, self.v_m_s, self.theta_rad, self.omega_rad_s]
    }

    /// From `[x, ẋ, θ, θ̇]`.
    #[must_use]
    pub fn from_array(s: [f64; 4]) -> Self {
        Self {
            x_m: s[0],
            v_m_s: s[1],
            theta_rad: s[2],
            omega_rad_s: s[3],
        }
    }

    /// `true` when every component is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.to_array().iter().all(|v| v.is_finite())
    }
}

/// `(ẍ, θ̈)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Accelerations {
    pub x_m_s2: f64,
    pub theta_rad_s2: f64,
}

/// `sgn` with `sgn 0 = 0` (`f64::signum` gives ±1 at ±0).
fn sgn(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

impl CartPoleParams {
    /// `true` when `g ≥ 0`, masses and half-length positive, frictions `≥ 0`, limits
    /// positive (infinity allowed), everything not NaN.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        let fin_pos = |v: f64| v.is_finite() && v > 0.0;
        let fin_nonneg = |v: f64| v.is_finite() && v >= 0.0;
        fin_nonneg(self.gravity_m_s2)
            && fin_pos(self.cart_mass_kg)
            && fin_pos(self.pole_mass_kg)
            && fin_pos(self.half_length_m)
            && fin_nonneg(self.cart_friction_n)
            && fin_nonneg(self.pole_friction_n_m_s)
            && !self.force_limit_n.is_nan()
            && self.force_limit_n > 0.0
            && !self.track_limit_m.is_nan()
            && self.track_limit_m > 0.0
    }

    /// `(ẍ, θ̈)` from the Barto–Sutton–Anderson equations (module docs) under force
    /// `force_n` (not clipped here).
    ///
    /// # Example
    /// ```
    /// use labcore::control::cartpole::{CartPoleParams, CartPoleState};
    /// let p = CartPoleParams::default();
    /// // Upright and still, pushed with 1.1 N: ẍ > 0 and the pole swings back (θ̈ < 0).
    /// let acc = p.accelerations(&CartPoleState::default(), 1.1);
    /// assert!(acc.x_m_s2 > 0.0 && acc.theta_rad_s2 < 0.0);
    /// ```
    #[must_use]
    pub fn accelerations(&self, s: &CartPoleState, force_n: f64) -> Accelerations {
        let (m, l, g) = (self.pole_mass_kg, self.half_length_m, self.gravity_m_s2);
        let total = self.cart_mass_kg + m;
        let (sin, cos) = crate::math::sin_cos(s.theta_rad);
        let temp = (force_n + m * l * s.omega_rad_s * s.omega_rad_s * sin
            - self.cart_friction_n * sgn(s.v_m_s))
            / total;
        let theta_acc = (g * sin - cos * temp - self.pole_friction_n_m_s * s.omega_rad_s / (m * l))
            / (l * (4.0 / 3.0 - m * cos * cos / total));
        let x_acc = temp - m * l * theta_acc * cos / total;
        Accelerations {
            x_m_s2: x_acc,
            theta_rad_s2: theta_acc,
        }
    }

    /// Total mechanical energy (J), potential zero at the pivot height.
    #[must_use]
    pub fn energy_j(&self, s: &CartPoleState) -> f64 {
        let (m, l) = (self.pole_mass_kg, self.half_length_m);
        let total = self.cart_mass_kg + m;
        let cos = crate::math::cos(s.theta_rad);
        0.5 * total * s.v_m_s * s.v_m_s
            + m * l * s.v_m_s * s.omega_rad_s * cos
            + 2.0 / 3.0 * m * l * l * s.omega_rad_s * s.omega_rad_s
            + m * self.gravity_m_s2 * l * cos
    }

    /// `(A, B)` of the linearisation about upright (module docs), state `[x, ẋ, θ, θ̇]`.
    #[must_use]
    pub fn linearize(&self) -> (Matrix, Matrix) {
        let (m, l, g) = (self.pole_mass_kg, self.half_length_m, self.gravity_m_s2);
        let mu = self.cart_mass_kg + m;
        let d = l * (4.0 / 3.0 - m / mu);
        let bp = self.pole_friction_n_m_s;
        let mut a = Matrix::zeros(4, 4);
        a[(0, 1)] = 1.0;
        a[(1, 2)] = -m * l * g / (mu * d);
        a[(1, 3)] = bp / (mu * d);
        a[(2, 3)] = 1.0;
        a[(3, 2)] = g / d;
        a[(3, 3)] = -bp / (m * l * d);
        let b = Matrix::column(&[0.0, 1.0 / mu + m * l / (mu * mu * d), 0.0, -1.0 / (mu * d)]);
        (a, b)
    }

    fn derivative(&self, s: [f64; 4], force_n: f64) -> [f64; 4] {
        let acc = self.accelerations(&CartPoleState::from_array(s), force_n);
        [s[1], acc.x_m_s2, s[3], acc.theta_rad_s2]
    }

    /// Inelastic end stop: if the cart is past `±track_limit_m` and moving outward, put
    /// it on the stop and apply the horizontal impulse `J` that zeroes `ẋ`. The pole
    /// receives the matching change of `θ̇` from the same equations with `F` replaced by
    /// `J` (finite terms drop out of an impulse):
    /// `Δθ̇ = −cos θ (J/μ) / (l (4/3 − m cos²θ/μ))`, `Δẋ = J/μ − m l Δθ̇ cos θ/μ`.
    fn apply_end_stop(&self, s: &mut CartPoleState) {
        let lim = self.track_limit_m;
        if s.x_m.abs() <= lim {
            return;
        }
        s.x_m = s.x_m.clamp(-lim, lim);
        if s.v_m_s * s.x_m <= 0.0 {
            return;
        }
        let (m, l) = (self.pole_mass_kg, self.half_length_m);
        let mu = self.cart_mass_kg + m;
        let cos = crate::math::cos(s.theta_rad);
        let dprime = 4.0 / 3.0 - m * cos * cos / mu;
        let kappa = 1.0 / mu + m * cos * cos / (mu * mu * dprime);
        let impulse = -s.v_m_s / kappa;
        s.omega_rad_s += -cos * (impulse / mu) / (l * dprime);
        s.v_m_s = 0.0;
    }
}

/// Integration scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Integrator {
    /// Explicit Euler as in CartPole-v1 (positions from the old velocities).
    #[default]
    Euler,
    /// Classical fourth-order Runge–Kutta.
    Rk4,
}

/// Advances `state` by `dt_s` under a constant force (clipped to `±force_limit_n`), in
/// `substeps` equal sub-steps of `integrator`, applying the end stops after each
/// sub-step. Returns `false` and leaves `state` unchanged for a bad `dt_s`, force,
/// parameter set, zero sub-steps, or a non-finite result.
///
/// # Example
/// ```
/// use labcore::control::cartpole::{integrate, CartPoleParams, CartPoleState, Integrator};
/// let p = CartPoleParams::default();
/// let mut s = CartPoleState { theta_rad: 0.01, ..Default::default() };
/// assert!(integrate(&p, &mut s, 0.0, 0.02, Integrator::Euler, 1));
/// // Euler: θ uses the old θ̇ = 0, only θ̇ changes in the first step.
/// assert_eq!(s.theta_rad, 0.01);
/// assert!(s.omega_rad_s > 0.0);
/// assert!(!integrate(&p, &mut s, 0.0, -0.02, Integrator::Euler, 1));
/// ```
pub fn integrate(
    params: &CartPoleParams,
    state: &mut CartPoleState,
    force_n: f64,
    dt_s: f64,
    integrator: Integrator,
    substeps: u32,
) -> bool {
    if !(params.is_valid()
        && dt_s.is_finite()
        && dt_s > 0.0
        && force_n.is_finite()
        && substeps > 0
        && state.is_finite())
    {
        return false;
    }
    let f = force_n.clamp(-params.force_limit_n, params.force_limit_n);
    let h = dt_s / f64::from(substeps);
    let mut s = *state;
    for _ in 0..substeps {
        let y = s.to_array();
        let next = match integrator {
            Integrator::Euler => {
                let d = params.derivative(y, f);
                [
                    y[0] + h * d[0],
                    y[1] + h * d[1],
                    y[2] + h * d[2],
                    y[3] + h * d[3],
                ]
            }
            Integrator::Rk4 => {
                let add = |a: [f64; 4], b: [f64; 4], k: f64| {
                    [
                        a[0] + k * b[0],
                        a[1] + k * b[1],
                        a[2] + k * b[2],
                        a[3] + k * b[3],
                    ]
                };
                let k1 = params.derivative(y, f);
                let k2 = params.derivative(add(y, k1, 0.5 * h), f);
                let k3 = params.derivative(add(y, k2, 0.5 * h), f);
                let k4 = params.derivative(add(y, k3, h), f);
                let mut out = y;
                for i in 0..4 {
                    out[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
                }
                out
            }
        };
        s = CartPoleState::from_array(next);
        params.apply_end_stop(&mut s);
    }
    if !s.is_finite() {
        return false;
    }
    *state = s;
    true
}

/// The upright linearisation `ṡ = A s + B F` as plain arrays, for simulating
/// the linear model beside the nonlinear one (e.g. to see where they part).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearModel {
    /// `A`, row by row, state `[x, ẋ, θ, θ̇]`.
    pub a: [[f64; 4]; 4],
    /// `B`.
    pub b: [f64; 4],
}

impl LinearModel {
    /// `(A, B)` of [`CartPoleParams::linearize`].
    #[must_use]
    pub fn of(params: &CartPoleParams) -> Self {
        let (a, b) = params.linearize();
        let mut out = Self {
            a: [[0.0; 4]; 4],
            b: [0.0; 4],
        };
        for i in 0..4 {
            for j in 0..4 {
                out.a[i][j] = a.get(i, j).unwrap_or(0.0);
            }
            out.b[i] = b.get(i, 0).unwrap_or(0.0);
        }
        out
    }

    /// `A s + B F`.
    #[must_use]
    pub fn derivative(&self, s: [f64; 4], force_n: f64) -> [f64; 4] {
        let mut d = [0.0; 4];
        for (i, row) in self.a.iter().enumerate() {
            d[i] = row.iter().zip(&s).map(|(a, s)| a * s).sum::<f64>() + self.b[i] * force_n;
        }
        d
    }

    /// Advances `state` by `dt_s` under the constant force `force_n` (not
    /// clipped here; there are no end stops in the linear model) in `substeps`
    /// steps of `integrator` — the same schemes as [`integrate`]. Returns
    /// `false` and leaves `state` unchanged for a bad `dt_s`, force, zero
    /// sub-steps or a non-finite result.
    ///
    /// # Example
    /// ```
    /// use labcore::control::cartpole::{CartPoleParams, CartPoleState, Integrator, LinearModel};
    /// let lin = LinearModel::of(&CartPoleParams::default());
    /// let mut s = CartPoleState { theta_rad: 0.01, ..Default::default() };
    /// assert!(lin.integrate(&mut s, 0.0, 0.02, Integrator::Rk4, 4));
    /// assert!(s.theta_rad > 0.01, "the upright pole falls");
    /// ```
    pub fn integrate(
        &self,
        state: &mut CartPoleState,
        force_n: f64,
        dt_s: f64,
        integrator: Integrator,
        substeps: u32,
    ) -> bool {
        if !(dt_s.is_finite() && dt_s > 0.0 && force_n.is_finite() && substeps > 0) {
            return false;
        }
        let h = dt_s / f64::from(substeps);
        let add = |a: [f64; 4], b: [f64; 4], k: f64| {
            [
                a[0] + k * b[0],
                a[1] + k * b[1],
                a[2] + k * b[2],
                a[3] + k * b[3],
            ]
        };
        let mut y = state.to_array();
        for _ in 0..substeps {
            y = match integrator {
                Integrator::Euler => add(y, self.derivative(y, force_n), h),
                Integrator::Rk4 => {
                    let k1 = self.derivative(y, force_n);
                    let k2 = self.derivative(add(y, k1, 0.5 * h), force_n);
                    let k3 = self.derivative(add(y, k2, 0.5 * h), force_n);
                    let k4 = self.derivative(add(y, k3, h), force_n);
                    let mut out = y;
                    for i in 0..4 {
                        out[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
                    }
                    out
                }
            };
        }
        let next = CartPoleState::from_array(y);
        if !next.is_finite() {
            return false;
        }
        *state = next;
        true
    }
}

/// Linear state feedback `F = kx·x + kv·ẋ + kθ·θ + kω·θ̇` (N).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StateFeedback {
    /// N/m.
    pub k_x: f64,
    /// N·s/m.
    pub k_v: f64,
    /// N/rad.
    pub k_theta: f64,
    /// N·s/rad.
    pub k_omega: f64,
}

impl Default for StateFeedback {
    /// The lab description's gains: `kθ = 120`, `kω = 18`, `kx = 3`, `kv = 6`.
    fn default() -> Self {
        Self {
            k_x: 3.0,
            k_v: 6.0,
            k_theta: 120.0,
            k_omega: 18.0,
        }
    }
}

impl StateFeedback {
    /// The force the law asks for (before the actuator limit).
    #[must_use]
    pub fn force_n(&self, s: &CartPoleState) -> f64 {
        self.k_x * s.x_m
            + self.k_v * s.v_m_s
            + self.k_theta * s.theta_rad
            + self.k_omega * s.omega_rad_s
    }

    /// `[kx, kv, kθ, kω]`, the row `k` of `F = k s`.
    #[must_use]
    pub fn to_array(&self) -> [f64; 4] {
        [self.k_x, self.k_v, self.k_theta, self.k_omega]
    }

    /// `true` when every gain is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.to_array().iter().all(|k| k.is_finite())
    }
}

/// Diagonal LQR weights on `[x, ẋ, θ, θ̇]` and on the force.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LqrWeights {
    /// `diag Q`, each `≥ 0`.
    pub q: [f64; 4],
    /// `R > 0` (1/N²).
    pub r: f64,
}

impl Default for LqrWeights {
    /// `Q = diag(1, 1, 10, 1)`, `R = 0.1`: angle weighted most.
    fn default() -> Self {
        Self {
            q: [1.0, 1.0, 10.0, 1.0],
            r: 0.1,
        }
    }
}

/// LQR gains for the upright linearisation, converted to the lab's `F = k·s` sign
/// (`k = −K`), with the Riccati solution for inspection.
///
/// A stabilising solution needs `(A, Q^½)` detectable: every mode that must be
/// stabilised is weighted. With `q[0] = 0` (cart position unweighted) the
/// eigenvalue 0 of the cart's position is unobservable in the cost and this
/// returns an error; any `q[0] > 0` with `r > 0` gives a stable closed loop.
///
/// # Example
/// ```
/// use labcore::control::cartpole::{lqr_feedback, CartPoleParams, LqrWeights};
/// let (k, sol) = lqr_feedback(&CartPoleParams::default(), &LqrWeights::default()).unwrap();
/// assert!(k.k_theta > 0.0 && sol.residual < 1e-9);
/// ```
pub fn lqr_feedback(
    params: &CartPoleParams,
    weights: &LqrWeights,
) -> Result<(StateFeedback, super::lqr::Lqr), LqrError> {
    let weights_ok = weights.q.iter().all(|q| q.is_finite() && *q >= 0.0)
        && weights.r.is_finite()
        && weights.r > 0.0;
    if !(params.is_valid() && weights_ok) {
        return Err(LqrError::InvalidWeights);
    }
    let (a, b) = params.linearize();
    let sol = care(
        &a,
        &b,
        &Matrix::from_diag(&weights.q),
        &Matrix::from_diag(&[weights.r]),
    )?;
    let k = StateFeedback {
        k_x: -sol.k[(0, 0)],
        k_v: -sol.k[(0, 1)],
        k_theta: -sol.k[(0, 2)],
        k_omega: -sol.k[(0, 3)],
    };
    Ok((k, sol))
}

/// Eigenvalues of the upright linearisation `A` (open loop): for the frictionless
/// cart-pole `0, 0, ±√(g/D)` — one in the right half-plane.
pub fn open_loop_eigenvalues(params: &CartPoleParams) -> Result<Vec<Complex>, RootError> {
    eigenvalues(&params.linearize().0)
}

/// Eigenvalues of `A + B k` under the feedback `F = k·s` (ignoring the force limit).
pub fn closed_loop_eigenvalues(
    params: &CartPoleParams,
    gains: &StateFeedback,
) -> Result<Vec<Complex>, RootError> {
    let (a, b) = params.linearize();
    let k = Matrix::from_rows(&[&gains.to_array()]).map_err(RootError::Matrix)?;
    let bk = b.mul(&k).map_err(RootError::Matrix)?;
    eigenvalues(&a.add(&bk).map_err(RootError::Matrix)?)
}

/// When the pole counts as fallen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FallCriterion {
    /// Fallen when `|θ| >` this (rad).
    pub angle_limit_rad: f64,
    /// Out of bounds when `|x| >` this (m).
    pub x_limit_m: f64,
}

impl FallCriterion {
    /// The lab's criterion: fallen past horizontal (90°), no position bound.
    #[must_use]
    pub fn horizontal() -> Self {
        Self {
            angle_limit_rad: std::f64::consts::FRAC_PI_2,
            x_limit_m: f64::INFINITY,
        }
    }

    /// CartPole-v1's termination: `|θ| > 12°` or `|x| > 2.4 m`.
    #[must_use]
    pub fn benchmark() -> Self {
        Self {
            angle_limit_rad: 12.0_f64.to_radians(),
            x_limit_m: 2.4,
        }
    }

    /// The status of a state under this criterion.
    #[must_use]
    pub fn status(&self, s: &CartPoleState) -> PoleStatus {
        if !s.is_finite() || s.theta_rad.abs() > self.angle_limit_rad {
            PoleStatus::Fallen
        } else if s.x_m.abs() > self.x_limit_m {
            PoleStatus::OutOfBounds
        } else {
            PoleStatus::Up
        }
    }
}

impl Default for FallCriterion {
    fn default() -> Self {
        Self::horizontal()
    }
}

/// Up, fallen or off the allowed track.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PoleStatus {
    Up,
    Fallen,
    OutOfBounds,
}

/// Default pole nudge, an added angular velocity (rad/s).
pub const NUDGE_RAD_S: f64 = 0.5;

/// What the last step's force was computed from: the state at the start of
/// the step, the gains, the limit and whether control was on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceInputs {
    pub state: CartPoleState,
    pub gains: StateFeedback,
    /// `|F| ≤` this (N).
    pub force_limit_n: f64,
    pub control_enabled: bool,
}

/// A controlled cart-pole: physics, feedback, integrator choice, status and time.
#[derive(Clone, Debug, PartialEq)]
pub struct CartPole {
    pub params: CartPoleParams,
    pub state: CartPoleState,
    pub gains: StateFeedback,
    /// When `false`, `F = 0` (open loop: the pole falls).
    pub control_enabled: bool,
    pub integrator: Integrator,
    /// Sub-steps per [`CartPole::step`], at least 1.
    pub substeps: u32,
    pub criterion: FallCriterion,
    /// Simulated time (s).
    pub time_s: f64,
    last_force_n: f64,
    last_saturated: bool,
    last_inputs: Option<ForceInputs>,
}

impl CartPole {
    /// Default physics and gains, Euler with 4 sub-steps, starting at `initial`.
    #[must_use]
    pub fn new(initial: CartPoleState) -> Self {
        Self {
            params: CartPoleParams::default(),
            state: initial,
            gains: StateFeedback::default(),
            control_enabled: true,
            integrator: Integrator::Euler,
            substeps: 4,
            criterion: FallCriterion::default(),
            time_s: 0.0,
            last_force_n: 0.0,
            last_saturated: false,
            last_inputs: None,
        }
    }

    /// The force applied in the last step, after the limit (N).
    #[must_use]
    pub fn last_force_n(&self) -> f64 {
        self.last_force_n
    }

    /// What the last step's force was computed from; `None` before the first step.
    #[must_use]
    pub fn last_inputs(&self) -> Option<ForceInputs> {
        self.last_inputs
    }

    /// `true` when the last step's force was cut by the actuator limit.
    #[must_use]
    pub fn last_saturated(&self) -> bool {
        self.last_saturated
    }

    /// Current status under [`CartPole::criterion`].
    #[must_use]
    pub fn status(&self) -> PoleStatus {
        self.criterion.status(&self.state)
    }

    /// Total energy of the current state (J).
    #[must_use]
    pub fn energy_j(&self) -> f64 {
        self.params.energy_j(&self.state)
    }

    /// Adds `delta_omega_rad_s` to the pole's angular velocity (a tap on the pole).
    /// Non-finite values are ignored.
    pub fn nudge(&mut self, delta_omega_rad_s: f64) {
        if delta_omega_rad_s.is_finite() {
            self.state.omega_rad_s += delta_omega_rad_s;
        }
    }

    /// Back to `initial` at time 0.
    pub fn reset(&mut self, initial: CartPoleState) {
        self.state = initial;
        self.time_s = 0.0;
        self.last_force_n = 0.0;
        self.last_saturated = false;
        self.last_inputs = None;
    }

    /// One control period: the force `F = k·s` (or 0 with control off) is computed from
    /// the current state, clipped, and held for `dt_s`. Returns `false` and changes
    /// nothing on a bad `dt_s`, parameters or gains.
    pub fn step(&mut self, dt_s: f64) -> bool {
        if !self.gains.is_finite() {
            return false;
        }
        let demand = if self.control_enabled {
            self.gains.force_n(&self.state)
        } else {
            0.0
        };
        if !demand.is_finite() {
            return false;
        }
        let lim = self.params.force_limit_n;
        let applied = demand.clamp(-lim, lim);
        let mut s = self.state;
        if !integrate(
            &self.params,
            &mut s,
            applied,
            dt_s,
            self.integrator,
            self.substeps,
        ) {
            return false;
        }
        self.last_inputs = Some(ForceInputs {
            state: self.state,
            gains: self.gains,
            force_limit_n: lim,
            control_enabled: self.control_enabled,
        });
        self.state = s;
        self.time_s += dt_s;
        self.last_force_n = applied;
        self.last_saturated = applied != demand;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::count_right_half_plane;

    fn free() -> CartPoleParams {
        CartPoleParams {
            force_limit_n: f64::INFINITY,
            track_limit_m: f64::INFINITY,
            ..CartPoleParams::default()
        }
    }

    #[test]
    fn hand_computed_accelerations_and_euler_step() {
        let p = CartPoleParams::default();
        // Upright, at rest, F = 1.1: temp = 1, D = 0.5·(4/3 − 0.1/1.1),
        // θ̈ = −1/D, ẍ = 1 − 0.05·θ̈/1.1.
        let d = 0.5 * (4.0 / 3.0 - 0.1 / 1.1);
        let acc = p.accelerations(&CartPoleState::default(), 1.1);
        assert!((acc.theta_rad_s2 + 1.0 / d).abs() < 1e-14);
        assert!((acc.x_m_s2 - (1.0 + 0.05 / (1.1 * d))).abs() < 1e-14);
        // One CartPole-v1 Euler step from (0, 0.1, 0, 0.2) with F = 1.1:
        let mut s = CartPoleState {
            x_m: 0.0,
            v_m_s: 0.1,
            theta_rad: 0.0,
            omega_rad_s: 0.2,
        };
        let a = p.accelerations(&s, 1.1);
        assert!(integrate(&p, &mut s, 1.1, 0.02, Integrator::Euler, 1));
        assert_eq!(s.x_m, 0.02 * 0.1);
        assert_eq!(s.theta_rad, 0.02 * 0.2);
        assert_eq!(s.v_m_s, 0.1 + 0.02 * a.x_m_s2);
        assert_eq!(s.omega_rad_s, 0.2 + 0.02 * a.theta_rad_s2);
    }

    /// One CartPole-v1 step, worked by hand with Gymnasium's `cartpole.py`
    /// formulas (τ = 0.02 s, force ±10 N, `x ← x + τẋ; ẋ ← ẋ + τẍ; θ ← θ + τθ̇;
    /// θ̇ ← θ̇ + τθ̈`, double precision): one Euler step without end stops is
    /// that step; the lab's setting (four sub-steps, end stops) is not, which
    /// is why the lab's option is called "Euler (4 sub-steps)".
    #[test]
    fn one_euler_step_without_end_stops_is_the_gymnasium_step() {
        let p = free();
        let cases = [
            (
                [0.01, -0.2, 0.03, 0.4],
                10.0,
                [0.006, -0.005316169155413664, 0.038, 0.11692433252290102],
            ),
            (
                [-1.3, 0.7, -0.15, -1.1],
                -10.0,
                [-1.286, 0.5071358809308707, -0.172, -0.857887116586486],
            ),
        ];
        for (start, force, gym) in cases {
            let mut s = CartPoleState::from_array(start);
            assert!(integrate(&p, &mut s, force, 0.02, Integrator::Euler, 1));
            for (ours, theirs) in s.to_array().iter().zip(gym) {
                assert!((ours - theirs).abs() < 1e-15, "{ours} vs {theirs}");
            }
            let mut lab = CartPoleState::from_array(start);
            let lab_params = CartPoleParams {
                force_limit_n: f64::INFINITY,
                ..CartPoleParams::default()
            };
            assert!(integrate(
                &lab_params,
                &mut lab,
                force,
                0.02,
                Integrator::Euler,
                4
            ));
            let apart = lab
                .to_array()
                .iter()
                .zip(gym)
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(apart > 1e-3, "four sub-steps differ: {apart}");
        }
    }

    #[test]
    fn bad_input_leaves_state_unchanged() {
        let p = CartPoleParams::default();
        let s0 = CartPoleState {
            theta_rad: 0.1,
            ..Default::default()
        };
        let mut s = s0;
        for dt in [0.0, -0.01, f64::NAN, f64::INFINITY] {
            assert!(!integrate(&p, &mut s, 0.0, dt, Integrator::Rk4, 1));
        }
        assert!(!integrate(&p, &mut s, f64::NAN, 0.01, Integrator::Rk4, 1));
        assert!(!integrate(&p, &mut s, 0.0, 0.01, Integrator::Rk4, 0));
        let bad = CartPoleParams {
            pole_mass_kg: 0.0,
            ..p
        };
        assert!(!integrate(&bad, &mut s, 0.0, 0.01, Integrator::Rk4, 1));
        assert_eq!(s, s0);
        let mut cp = CartPole::new(s0);
        let before = cp.clone();
        assert!(!cp.step(f64::NAN) && !cp.step(-1.0));
        cp.gains.k_x = f64::NAN;
        assert!(!cp.step(0.02));
        cp.gains = before.gains;
        cp.nudge(f64::NAN);
        assert_eq!(cp, before);
    }

    #[test]
    fn rk4_conserves_energy_without_force_or_friction() {
        let p = free();
        let mut s = CartPoleState {
            theta_rad: 0.3,
            omega_rad_s: 0.5,
            v_m_s: 0.2,
            x_m: 0.0,
        };
        let e0 = p.energy_j(&s);
        let mut worst: f64 = 0.0;
        for _ in 0..500 {
            assert!(integrate(&p, &mut s, 0.0, 0.02, Integrator::Rk4, 4));
            worst = worst.max((p.energy_j(&s) - e0).abs());
        }
        // 10 s of a swinging pole; |E| ≈ 0.5 J.
        assert!(worst < 1e-6 * e0.abs().max(1.0), "drift {worst}");
        // Euler at the same step drifts far more.
        let mut s = CartPoleState {
            theta_rad: 0.3,
            omega_rad_s: 0.5,
            v_m_s: 0.2,
            x_m: 0.0,
        };
        for _ in 0..500 {
            assert!(integrate(&p, &mut s, 0.0, 0.02, Integrator::Euler, 4));
        }
        assert!((p.energy_j(&s) - e0).abs() > 1e3 * worst);
    }

    #[test]
    fn friction_dissipates_energy() {
        let p = CartPoleParams {
            cart_friction_n: 0.05,
            pole_friction_n_m_s: 0.01,
            ..free()
        };
        let mut s = CartPoleState {
            theta_rad: 0.3,
            ..Default::default()
        };
        let e0 = p.energy_j(&s);
        for _ in 0..500 {
            assert!(integrate(&p, &mut s, 0.0, 0.02, Integrator::Rk4, 4));
        }
        assert!(p.energy_j(&s) < e0 - 1e-3);
    }

    #[test]
    fn analytic_linearisation_matches_finite_differences() {
        for p in [
            free(),
            CartPoleParams {
                pole_friction_n_m_s: 0.02,
                ..free()
            },
        ] {
            let (a, b) = p.linearize();
            let h = 1e-6;
            for j in 0..4 {
                let mut plus = [0.0; 4];
                let mut minus = [0.0; 4];
                plus[j] = h;
                minus[j] = -h;
                let fp = p.derivative(plus, 0.0);
                let fm = p.derivative(minus, 0.0);
                for i in 0..4 {
                    let fd = (fp[i] - fm[i]) / (2.0 * h);
                    assert!(
                        (fd - a[(i, j)]).abs() < 1e-7,
                        "A[{i},{j}] {fd} vs {}",
                        a[(i, j)]
                    );
                }
            }
            let fp = p.derivative([0.0; 4], h);
            let fm = p.derivative([0.0; 4], -h);
            for i in 0..4 {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                assert!((fd - b[(i, 0)]).abs() < 1e-7);
            }
        }
    }

    #[test]
    fn open_loop_has_one_unstable_eigenvalue_lqr_and_defaults_none() {
        let p = free();
        let ev = open_loop_eigenvalues(&p).unwrap();
        assert_eq!(count_right_half_plane(&ev), 1, "{ev:?}");
        let d = 0.5 * (4.0 / 3.0 - 0.1 / 1.1);
        let unstable = ev.iter().fold(f64::MIN, |m, z| m.max(z.re));
        assert!((unstable - (9.8_f64 / d).sqrt()).abs() < 1e-9);

        let (k, sol) = lqr_feedback(&p, &LqrWeights::default()).unwrap();
        assert!(sol.residual < 1e-9, "residual {}", sol.residual);
        let cl = closed_loop_eigenvalues(&p, &k).unwrap();
        assert!(cl.iter().all(|z| z.re < 0.0), "{cl:?}");
        let cl = closed_loop_eigenvalues(&p, &StateFeedback::default()).unwrap();
        assert!(cl.iter().all(|z| z.re < 0.0), "default gains: {cl:?}");
        // Without the angle term nothing holds the pole.
        let weak = StateFeedback {
            k_theta: 0.0,
            ..StateFeedback::default()
        };
        assert!(count_right_half_plane(&closed_loop_eigenvalues(&p, &weak).unwrap()) > 0);
    }

    /// Detectability: the cart position must be weighted.
    #[test]
    fn lqr_needs_a_weight_on_the_cart_position() {
        let p = CartPoleParams::default();
        for q in [[0.0, 1.0, 10.0, 1.0], [0.0, 100.0, 100.0, 100.0]] {
            assert!(
                lqr_feedback(&p, &LqrWeights { q, r: 0.1 }).is_err(),
                "{q:?}"
            );
        }
        for q in [[1e-3, 0.0, 0.0, 0.0], [0.1, 0.0, 100.0, 0.0]] {
            let (k, _) = lqr_feedback(&p, &LqrWeights { q, r: 10.0 }).unwrap();
            let cl = closed_loop_eigenvalues(&p, &k).unwrap();
            assert!(cl.iter().all(|z| z.re < 0.0), "{q:?}: {cl:?}");
        }
    }

    #[test]
    fn feedback_recovers_from_a_nudge() {
        let (lqr, _) = lqr_feedback(&CartPoleParams::default(), &LqrWeights::default()).unwrap();
        for gains in [StateFeedback::default(), lqr] {
            for integrator in [Integrator::Euler, Integrator::Rk4] {
                let mut cp = CartPole::new(CartPoleState {
                    theta_rad: 0.05,
                    ..Default::default()
                });
                cp.gains = gains;
                cp.integrator = integrator;
                cp.nudge(NUDGE_RAD_S);
                let mut max_theta: f64 = 0.0;
                for _ in 0..1000 {
                    assert!(cp.step(0.02));
                    assert_eq!(cp.status(), PoleStatus::Up);
                    max_theta = max_theta.max(cp.state.theta_rad.abs());
                }
                assert!(max_theta > 0.05, "the nudge did tilt the pole");
                assert!(cp.state.theta_rad.abs() < 1e-3, "{gains:?} {:?}", cp.state);
                assert!(cp.state.x_m.abs() < 0.05, "{gains:?} {:?}", cp.state);
                assert_eq!(cp.status(), PoleStatus::Up);
            }
        }
        // Open loop, it falls.
        let mut cp = CartPole::new(CartPoleState {
            theta_rad: 0.05,
            ..Default::default()
        });
        cp.control_enabled = false;
        for _ in 0..200 {
            cp.step(0.02);
        }
        assert_eq!(cp.status(), PoleStatus::Fallen);
        assert_eq!(
            FallCriterion::benchmark().status(&CartPoleState {
                theta_rad: 0.3,
                ..Default::default()
            }),
            PoleStatus::Fallen
        );
        assert_eq!(
            FallCriterion::benchmark().status(&CartPoleState {
                x_m: 2.5,
                ..Default::default()
            }),
            PoleStatus::OutOfBounds
        );
    }

    #[test]
    fn halving_dt_shows_each_integrators_order() {
        let p = free();
        // Constant force over 1 s at dt = 1/n, 1/2n, 1/4n; the successive differences
        // shrink by 2^order (Richardson), without needing an exact solution.
        let run_free = |integrator: Integrator, n: u32| {
            let mut s = CartPoleState {
                theta_rad: 0.2,
                omega_rad_s: -0.3,
                v_m_s: 0.1,
                x_m: 0.0,
            };
            for _ in 0..n {
                assert!(integrate(
                    &p,
                    &mut s,
                    0.5,
                    1.0 / f64::from(n),
                    integrator,
                    1
                ));
            }
            s.to_array()
        };
        let diff = |a: [f64; 4], b: [f64; 4]| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - y) * (x - y))
                .sum::<f64>()
                .sqrt()
        };
        for (integrator, lo, hi, base) in [
            (Integrator::Euler, 1.8, 2.2, 200),
            (Integrator::Rk4, 14.0, 18.0, 25),
        ] {
            let a = run_free(integrator, base);
            let b = run_free(integrator, 2 * base);
            let c = run_free(integrator, 4 * base);
            let ratio = diff(a, b) / diff(b, c);
            assert!((lo..hi).contains(&ratio), "{integrator:?}: {ratio}");
        }
    }

    #[test]
    fn linear_and_nonlinear_agree_for_small_angles_only() {
        let p = free();
        let (a, _) = p.linearize();
        let compare = |theta0: f64| {
            let mut s = CartPoleState {
                theta_rad: theta0,
                ..Default::default()
            };
            let mut lin = s.to_array();
            let h = 1e-3;
            for _ in 0..500 {
                assert!(integrate(&p, &mut s, 0.0, h, Integrator::Rk4, 1));
                // RK4 on the linear model ẏ = A y.
                let f = |y: [f64; 4]| {
                    let v = a.mul_vec(&y).unwrap();
                    [v[0], v[1], v[2], v[3]]
                };
                let add = |y: [f64; 4], k: [f64; 4], c: f64| {
                    [
                        y[0] + c * k[0],
                        y[1] + c * k[1],
                        y[2] + c * k[2],
                        y[3] + c * k[3],
                    ]
                };
                let k1 = f(lin);
                let k2 = f(add(lin, k1, 0.5 * h));
                let k3 = f(add(lin, k2, 0.5 * h));
                let k4 = f(add(lin, k3, h));
                for i in 0..4 {
                    lin[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
                }
            }
            // Relative angle error after 0.5 s.
            (s.theta_rad - lin[2]).abs() / lin[2].abs()
        };
        assert!(compare(1e-3) < 1e-5);
        assert!(compare(0.5) > 0.1);
    }

    #[test]
    fn end_stop_halts_the_cart_and_kicks_the_pole_consistently() {
        let p = CartPoleParams {
            track_limit_m: 1.0,
            ..free()
        };
        let mut s = CartPoleState {
            x_m: 0.999,
            v_m_s: 1.0,
            theta_rad: 0.1,
            omega_rad_s: 0.0,
        };
        assert!(integrate(&p, &mut s, 0.0, 0.01, Integrator::Rk4, 1));
        assert_eq!((s.x_m, s.v_m_s), (1.0, 0.0));
        // Stopping the cart throws the pole forward (toward +x).
        assert!(s.omega_rad_s > 1.0);

        // The impulse model is the limit of a large, brief force: stop a cart moving at
        // 1 m/s with θ = 0.1 by F = −J/δ over δ = 1 µs and compare the pole's kick.
        let mut at_stop = CartPoleState {
            x_m: 1.0,
            v_m_s: 1.0,
            theta_rad: 0.1,
            omega_rad_s: 0.0,
        };
        let mut stopped = CartPoleState {
            x_m: 1.5,
            ..at_stop
        };
        p.apply_end_stop(&mut stopped);
        let (m, mu, cos) = (0.1, 1.1, crate::math::cos(0.1));
        let dprime = 4.0 / 3.0 - m * cos * cos / mu;
        let impulse = -1.0 / (1.0 / mu + m * cos * cos / (mu * mu * dprime));
        let delta = 1e-6;
        let open = CartPoleParams {
            track_limit_m: f64::INFINITY,
            ..p
        };
        assert!(integrate(
            &open,
            &mut at_stop,
            impulse / delta,
            delta,
            Integrator::Rk4,
            1
        ));
        assert!(at_stop.v_m_s.abs() < 1e-4, "{at_stop:?}");
        assert!((at_stop.omega_rad_s - stopped.omega_rad_s).abs() < 1e-4);
    }
}
