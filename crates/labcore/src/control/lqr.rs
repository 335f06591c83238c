//! Continuous-time LQR: the algebraic Riccati equation and the optimal gain.
//!
//! For `ẋ = A x + B u` and the cost `∫ (xᵀQx + uᵀRu) dt` (`Q = Qᵀ ⪰ 0`, `R = Rᵀ ≻ 0`),
//! the optimal law is `u = −K x` with
//!
//! ```text
//! AᵀP + PA − P B R⁻¹ Bᵀ P + Q = 0,        K = R⁻¹ Bᵀ P
//! ```
//!
//! where `P` is the stabilising solution (Anderson & Moore, *Optimal Control: Linear
//! Quadratic Methods*, 1990, §3.3; Åström & Murray, *Feedback Systems*, 2nd ed., §7.5).
//! Note the sign: the lab's state feedback is written `F = k·x`, so `k = −K`.
//!
//! **Solver.** Two stages, both on the `2n × 2n` Hamiltonian
//! `H = [[A, −G], [−Q, −Aᵀ]]`, `G = B R⁻¹ Bᵀ`:
//!
//! 1. *Matrix sign function* (Roberts 1971/1980; Byers, *Linear Algebra Appl.* 85, 1987;
//!    an alternative to Laub's Schur method, Laub, *IEEE TAC* 24(6), 1979): the Newton
//!    iteration `Z ← ½(cZ + (cZ)⁻¹)` with determinant scaling `c = |det Z|^(−1/2n)`
//!    converges to `W = sign(H)`. The stable invariant subspace `[I; P]` of `H` satisfies
//!    `(W + I)[I; P] = 0`, i.e. `[W₁₂; W₂₂ + I] P = −[W₁₁ + I; W₂₁]`, solved in the
//!    least-squares sense.
//! 2. *Newton–Kleinman refinement* (Kleinman, *IEEE TAC* 13(1), 1968): with
//!    `K = R⁻¹BᵀP`, solve the Lyapunov equation
//!    `(A − BK)ᵀ P' + P' (A − BK) + Q + KᵀRK = 0` (by its Kronecker form, fine for the
//!    small `n` here) and repeat while the residual falls. Each step converges
//!    quadratically from a stabilising start, which stage 1 provides.
//!
//! The returned residual is the Frobenius norm of the left-hand side of the Riccati
//! equation at the returned `P`.

use crate::linalg::{LinalgError, Matrix};

/// Why no LQR solution was produced.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LqrError {
    /// `A` not square, or `B`, `Q`, `R` of the wrong shape.
    Shape,
    /// `Q` not symmetric, or `R` not symmetric positive-definite, or a non-finite entry.
    InvalidWeights,
    /// A linear solve failed (typically `(A, B)` not stabilisable or `(A, Q)` not
    /// detectable: the Hamiltonian has eigenvalues on the imaginary axis).
    Linalg(LinalgError),
    /// The iterations did not reach a small residual.
    NotConverged { iterations: usize, residual: f64 },
}

impl From<LinalgError> for LqrError {
    fn from(e: LinalgError) -> Self {
        LqrError::Linalg(e)
    }
}

/// The Riccati solution and the optimal gain.
#[derive(Clone, Debug, PartialEq)]
pub struct Lqr {
    /// Stabilising solution `P` (`n × n`, symmetric positive semi-definite).
    pub p: Matrix,
    /// `K = R⁻¹ Bᵀ P` (`m × n`); the optimal law is `u = −K x`.
    pub k: Matrix,
    /// `‖AᵀP + PA − PBR⁻¹BᵀP + Q‖_F` at `P`.
    pub residual: f64,
    /// Sign-function iterations used.
    pub sign_iterations: usize,
    /// Newton–Kleinman refinement steps used.
    pub newton_iterations: usize,
}

/// Iteration budget of the sign-function stage.
pub const MAX_SIGN_ITERATIONS: usize = 100;
/// Iteration budget of the Newton–Kleinman stage.
pub const MAX_NEWTON_ITERATIONS: usize = 20;

/// `‖AᵀP + PA − PBR⁻¹BᵀP + Q‖_F`.
pub fn riccati_residual(
    a: &Matrix,
    b: &Matrix,
    q: &Matrix,
    r: &Matrix,
    p: &Matrix,
) -> Result<f64, LqrError> {
    let g = b.mul(&r.solve(&b.transpose())?)?;
    let lhs = a
        .transpose()
        .mul(p)?
        .add(&p.mul(a)?)?
        .sub(&p.mul(&g)?.mul(p)?)?
        .add(q)?;
    Ok(lhs.frobenius_norm())
}

/// Solves the Lyapunov equation `Aᵀ X + X A + W = 0` for `X` through its Kronecker form
/// `(I ⊗ Aᵀ + Aᵀ ⊗ I) vec X = −vec W` (Golub & Van Loan 2013, §7.6.3 discusses better
/// methods for large `n`; here `n ≤ 8`). Unique when no two eigenvalues of `A` sum to 0.
pub fn solve_lyapunov(a: &Matrix, w: &Matrix) -> Result<Matrix, LqrError> {
    let n = a.rows();
    if !a.is_square() || w.shape() != (n, n) {
        return Err(LqrError::Shape);
    }
    let mut big = Matrix::zeros(n * n, n * n);
    let mut rhs = Matrix::zeros(n * n, 1);
    for i in 0..n {
        for j in 0..n {
            let row = i * n + j;
            // Σ_k A_ki X_kj + Σ_k X_ik A_kj = −W_ij
            for k in 0..n {
                big[(row, k * n + j)] += a[(k, i)];
                big[(row, i * n + k)] += a[(k, j)];
            }
            rhs[(row, 0)] = -w[(i, j)];
        }
    }
    let x = big.solve(&rhs)?;
    let mut x = Matrix::from_vec(n, n, x.as_slice().to_vec())?;
    x.symmetrize();
    Ok(x)
}

/// Solves the continuous algebraic Riccati equation and returns `P` and `K`.
///
/// `A` is `n × n`, `B` is `n × m`, `Q` is `n × n` symmetric, `R` is `m × m` symmetric
/// positive-definite. Fails with a value, never a panic.
///
/// # Example
/// ```
/// use labcore::{control::lqr::care, linalg::Matrix};
/// // Scalar ẋ = u, Q = 1, R = 1: P² = 1 → P = 1, K = 1.
/// let one = Matrix::identity(1);
/// let sol = care(&Matrix::zeros(1, 1), &one, &one, &one).unwrap();
/// assert!((sol.p[(0, 0)] - 1.0).abs() < 1e-12 && (sol.k[(0, 0)] - 1.0).abs() < 1e-12);
/// ```
pub fn care(a: &Matrix, b: &Matrix, q: &Matrix, r: &Matrix) -> Result<Lqr, LqrError> {
    let n = a.rows();
    let m = b.cols();
    if !a.is_square() || b.rows() != n || q.shape() != (n, n) || r.shape() != (m, m) || n == 0 {
        return Err(LqrError::Shape);
    }
    let finite = a.is_finite() && b.is_finite() && q.is_finite() && r.is_finite();
    if !(finite && q.is_symmetric(1e-12)) || r.cholesky(1e-12).is_err() {
        return Err(LqrError::InvalidWeights);
    }
    let r_inv_bt = r.solve(&b.transpose())?;
    let g = b.mul(&r_inv_bt)?;

    // Stage 1: sign function of the Hamiltonian.
    let nn = 2 * n;
    let mut z = Matrix::zeros(nn, nn);
    for i in 0..n {
        for j in 0..n {
            z[(i, j)] = a[(i, j)];
            z[(i, n + j)] = -g[(i, j)];
            z[(n + i, j)] = -q[(i, j)];
            z[(n + i, n + j)] = -a[(j, i)];
        }
    }
    let mut sign_iterations = 0;
    let mut converged = false;
    let mut scaling = true;
    while sign_iterations < MAX_SIGN_ITERATIONS {
        sign_iterations += 1;
        let lu = z.lu()?;
        let c = if scaling {
            let det = lu.determinant().abs();
            crate::math::exp(-crate::math::ln(det) / nn as f64)
        } else {
            1.0
        };
        let c = if c.is_finite() && c > 0.0 { c } else { 1.0 };
        let inv = lu.solve(&Matrix::identity(nn))?;
        let next = z.scale(0.5 * c).add(&inv.scale(0.5 / c))?;
        let change = next.sub(&z)?.frobenius_norm();
        z = next;
        if !z.is_finite() {
            return Err(LqrError::NotConverged {
                iterations: sign_iterations,
                residual: f64::INFINITY,
            });
        }
        if change <= 1e-2 * z.frobenius_norm() {
            // Near convergence scaling only slows the final quadratic phase.
            scaling = false;
        }
        if change <= 1e-12 * z.frobenius_norm() {
            converged = true;
            break;
        }
    }
    if !converged {
        return Err(LqrError::NotConverged {
            iterations: sign_iterations,
            residual: f64::NAN,
        });
    }
    // [W12; W22 + I] P = −[W11 + I; W21], least squares via the normal equations.
    let mut lhs = Matrix::zeros(nn, n);
    let mut rhs = Matrix::zeros(nn, n);
    for i in 0..nn {
        for j in 0..n {
            lhs[(i, j)] = z[(i, n + j)] + if i == n + j { 1.0 } else { 0.0 };
            rhs[(i, j)] = -(z[(i, j)] + if i == j { 1.0 } else { 0.0 });
        }
    }
    let lt = lhs.transpose();
    let mut p = lt.mul(&lhs)?.solve(&lt.mul(&rhs)?)?;
    p.symmetrize();

    // Stage 2: Newton–Kleinman refinement.
    let mut residual = riccati_residual(a, b, q, r, &p)?;
    let mut newton_iterations = 0;
    while newton_iterations < MAX_NEWTON_ITERATIONS && residual > 0.0 {
        let k = r_inv_bt.mul(&p)?;
        let ac = a.sub(&b.mul(&k)?)?;
        let w = q.add(&k.transpose().mul(&r.mul(&k)?)?)?;
        let Ok(candidate) = solve_lyapunov(&ac, &w) else {
            break;
        };
        let cand_residual = riccati_residual(a, b, q, r, &candidate)?;
        // Keep only improvements (a NaN residual is not one).
        if cand_residual.is_nan() || cand_residual >= residual {
            break;
        }
        newton_iterations += 1;
        let improvement = residual / cand_residual;
        p = candidate;
        residual = cand_residual;
        if improvement < 2.0 {
            break;
        }
    }
    let scale = 1.0 + q.frobenius_norm() + p.frobenius_norm() * (1.0 + a.frobenius_norm());
    if !residual.is_finite() || residual > 1e-8 * scale {
        return Err(LqrError::NotConverged {
            iterations: sign_iterations + newton_iterations,
            residual,
        });
    }
    let k = r_inv_bt.mul(&p)?;
    Ok(Lqr {
        p,
        k,
        residual,
        sign_iterations,
        newton_iterations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::poly::eigenvalues;

    #[test]
    fn double_integrator_matches_closed_form() {
        // ẍ = u, Q = I, R = 1: P = [[√3, 1], [1, √3]], K = [1, √3].
        let a = Matrix::from_rows(&[&[0.0, 1.0], &[0.0, 0.0]]).unwrap();
        let b = Matrix::column(&[0.0, 1.0]);
        let sol = care(&a, &b, &Matrix::identity(2), &Matrix::identity(1)).unwrap();
        let s3 = 3f64.sqrt();
        let want = [s3, 1.0, 1.0, s3];
        for (got, want) in sol.p.as_slice().iter().zip(want) {
            assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        }
        assert!((sol.k[(0, 0)] - 1.0).abs() < 1e-12 && (sol.k[(0, 1)] - s3).abs() < 1e-12);
        assert!(sol.residual < 1e-12);
        // Closed loop A − BK is stable.
        let ac = a.sub(&b.mul(&sol.k).unwrap()).unwrap();
        assert!(eigenvalues(&ac).unwrap().iter().all(|z| z.re < 0.0));
    }

    #[test]
    fn unstable_scalar_plant() {
        // ẋ = a x + u, Q = q, R = 1: P = a + √(a² + q).
        let (a, q) = (2.0, 3.0);
        let sol = care(
            &Matrix::from_diag(&[a]),
            &Matrix::identity(1),
            &Matrix::from_diag(&[q]),
            &Matrix::identity(1),
        )
        .unwrap();
        assert!((sol.p[(0, 0)] - (a + (a * a + q).sqrt())).abs() < 1e-12);
    }

    #[test]
    fn lyapunov_by_hand() {
        // A = −I: −2X + W = 0 → X = W/2.
        let w = Matrix::from_rows(&[&[2.0, 1.0], &[1.0, 4.0]]).unwrap();
        let x = solve_lyapunov(&Matrix::identity(2).scale(-1.0), &w).unwrap();
        assert_eq!(x, w.scale(0.5));
    }

    #[test]
    fn bad_problems_are_errors() {
        let a = Matrix::from_rows(&[&[0.0, 1.0], &[0.0, 0.0]]).unwrap();
        let b = Matrix::column(&[0.0, 1.0]);
        let q = Matrix::identity(2);
        assert_eq!(
            care(&a, &b, &q, &Matrix::from_diag(&[-1.0])),
            Err(LqrError::InvalidWeights)
        );
        assert_eq!(
            care(&a, &b, &Matrix::identity(3), &Matrix::identity(1)),
            Err(LqrError::Shape)
        );
        // Not stabilisable: an unstable mode the input cannot reach.
        let a = Matrix::from_diag(&[1.0, -1.0]);
        let b = Matrix::column(&[0.0, 1.0]);
        assert!(care(&a, &b, &q, &Matrix::identity(1)).is_err());
    }
}
