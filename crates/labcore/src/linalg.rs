//! Small dense linear algebra: a row-major `f64` [`Matrix`] shared by the lab's solvers
//! (LQR's Riccati solver, EKF localisation and EKF-SLAM).
//!
//! Sizes here are tiny (4×4 for the cart-pole, a few hundred for SLAM), so the
//! textbook algorithms are used as written, without blocking:
//!
//! - LU factorisation with partial (row) pivoting, `P A = L U` — Golub & Van Loan,
//!   *Matrix Computations*, 4th ed., 2013, §3.4.3 (Algorithm 3.4.1), solves by
//!   forward and back substitution (§3.1, Algorithms 3.1.1–3.1.2).
//! - Cholesky `A = L Lᵀ` of a symmetric positive-definite matrix — Golub & Van Loan
//!   §4.2.5 (Algorithm 4.2.1, the *gaxpy* Cholesky).
//!
//! Bad input is a value, not a panic: shape mismatches, singular or indefinite matrices
//! and non-finite entries come back as a [`LinalgError`]. Only indexing out of range
//! panics, exactly as slice indexing does. No fused multiply-add and no reordering of
//! sums: results are bit-identical natively and in wasm.

use std::fmt;
use std::ops::{Index, IndexMut};

/// Why a matrix operation could not be carried out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LinalgError {
    /// The operands' shapes do not fit the operation.
    DimensionMismatch {
        /// `(rows, cols)` of the left operand.
        left: (usize, usize),
        /// `(rows, cols)` of the right operand (or the requested shape).
        right: (usize, usize),
    },
    /// The operation needs a square matrix.
    NotSquare { rows: usize, cols: usize },
    /// A pivot was (numerically) zero: the matrix is singular to working precision.
    Singular {
        /// The elimination step (column) whose pivot vanished.
        column: usize,
    },
    /// Cholesky met a non-positive diagonal: the matrix is not symmetric positive-definite.
    NotPositiveDefinite {
        /// The column whose diagonal `a_jj − Σ l_jk²` was `≤ 0`.
        column: usize,
    },
    /// Cholesky was given a matrix that is not symmetric to the tolerance.
    NotSymmetric,
    /// An entry was NaN or infinite.
    NonFinite,
}

impl fmt::Display for LinalgError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LinalgError::DimensionMismatch { left, right } => write!(
                f,
                "shape mismatch: {}×{} against {}×{}",
                left.0, left.1, right.0, right.1
            ),
            LinalgError::NotSquare { rows, cols } => {
                write!(f, "a square matrix is needed, got {rows}×{cols}")
            }
            LinalgError::Singular { column } => {
                write!(f, "matrix is singular (zero pivot in column {column})")
            }
            LinalgError::NotPositiveDefinite { column } => {
                write!(f, "matrix is not positive-definite (column {column})")
            }
            LinalgError::NotSymmetric => write!(f, "matrix is not symmetric"),
            LinalgError::NonFinite => write!(f, "matrix has a NaN or infinite entry"),
        }
    }
}

impl std::error::Error for LinalgError {}

/// Dense row-major matrix of `f64`: entry `(i, j)` is `data[i * cols + j]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Matrix {
    rows: usize,
    cols: usize,
    data: Vec<f64>,
}

impl Matrix {
    /// The `rows × cols` zero matrix.
    #[must_use]
    pub fn zeros(rows: usize, cols: usize) -> Self {
        Self {
            rows,
            cols,
            data: vec![0.0; rows * cols],
        }
    }

    /// The `n × n` identity.
    #[must_use]
    pub fn identity(n: usize) -> Self {
        let mut m = Self::zeros(n, n);
        for i in 0..n {
            m[(i, i)] = 1.0;
        }
        m
    }

    /// Square matrix with `diag` on the diagonal and zeros elsewhere.
    #[must_use]
    pub fn from_diag(diag: &[f64]) -> Self {
        let mut m = Self::zeros(diag.len(), diag.len());
        for (i, &d) in diag.iter().enumerate() {
            m[(i, i)] = d;
        }
        m
    }

    /// Builds a matrix from its rows; every row must have the same length.
    ///
    /// # Example
    /// ```
    /// use labcore::linalg::Matrix;
    /// let a = Matrix::from_rows(&[&[1.0, 2.0], &[3.0, 4.0]]).unwrap();
    /// assert_eq!(a[(1, 0)], 3.0);
    /// assert!(Matrix::from_rows(&[&[1.0, 2.0], &[3.0]]).is_err());
    /// ```
    pub fn from_rows(rows: &[&[f64]]) -> Result<Self, LinalgError> {
        let cols = rows.first().map_or(0, |r| r.len());
        let mut data = Vec::with_capacity(rows.len() * cols);
        for r in rows {
            if r.len() != cols {
                return Err(LinalgError::DimensionMismatch {
                    left: (rows.len(), cols),
                    right: (1, r.len()),
                });
            }
            data.extend_from_slice(r);
        }
        Ok(Self {
            rows: rows.len(),
            cols,
            data,
        })
    }

    /// Wraps a row-major buffer; `data.len()` must equal `rows * cols`.
    pub fn from_vec(rows: usize, cols: usize, data: Vec<f64>) -> Result<Self, LinalgError> {
        if data.len() != rows * cols {
            return Err(LinalgError::DimensionMismatch {
                left: (rows, cols),
                right: (1, data.len()),
            });
        }
        Ok(Self { rows, cols, data })
    }

    /// A column vector (`n × 1`).
    #[must_use]
    pub fn column(values: &[f64]) -> Self {
        Self {
            rows: values.len(),
            cols: 1,
            data: values.to_vec(),
        }
    }

    /// Number of rows.
    #[must_use]
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of columns.
    #[must_use]
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// `(rows, cols)`.
    #[must_use]
    pub fn shape(&self) -> (usize, usize) {
        (self.rows, self.cols)
    }

    /// `true` when `rows == cols`.
    #[must_use]
    pub fn is_square(&self) -> bool {
        self.rows == self.cols
    }

    /// The row-major entries.
    #[must_use]
    pub fn as_slice(&self) -> &[f64] {
        &self.data
    }

    /// The row-major entries, mutable.
    pub fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.data
    }

    /// Row `i` as a slice. Panics if `i >= rows`, like slice indexing.
    #[must_use]
    pub fn row(&self, i: usize) -> &[f64] {
        &self.data[i * self.cols..(i + 1) * self.cols]
    }

    /// Entry `(i, j)`, or `None` when out of range.
    #[must_use]
    pub fn get(&self, i: usize, j: usize) -> Option<f64> {
        (i < self.rows && j < self.cols).then(|| self.data[i * self.cols + j])
    }

    /// `true` when every entry is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.data.iter().all(|v| v.is_finite())
    }

    /// The transpose `Aᵀ`.
    #[must_use]
    pub fn transpose(&self) -> Self {
        let mut t = Self::zeros(self.cols, self.rows);
        for i in 0..self.rows {
            for j in 0..self.cols {
                t[(j, i)] = self[(i, j)];
            }
        }
        t
    }

    fn same_shape(&self, other: &Self) -> Result<(), LinalgError> {
        if self.shape() == other.shape() {
            Ok(())
        } else {
            Err(LinalgError::DimensionMismatch {
                left: self.shape(),
                right: other.shape(),
            })
        }
    }

    /// `A + B` (same shape).
    pub fn add(&self, other: &Self) -> Result<Self, LinalgError> {
        self.same_shape(other)?;
        let data = self.data.iter().zip(&other.data).map(|(a, b)| a + b);
        Ok(Self {
            rows: self.rows,
            cols: self.cols,
            data: data.collect(),
        })
    }

    /// `A − B` (same shape).
    pub fn sub(&self, other: &Self) -> Result<Self, LinalgError> {
        self.same_shape(other)?;
        let data = self.data.iter().zip(&other.data).map(|(a, b)| a - b);
        Ok(Self {
            rows: self.rows,
            cols: self.cols,
            data: data.collect(),
        })
    }

    /// `k · A`.
    #[must_use]
    pub fn scale(&self, k: f64) -> Self {
        Self {
            rows: self.rows,
            cols: self.cols,
            data: self.data.iter().map(|a| k * a).collect(),
        }
    }

    /// The product `A B` (`A` is `m × k`, `B` is `k × n`).
    ///
    /// # Example
    /// ```
    /// use labcore::linalg::Matrix;
    /// let a = Matrix::from_rows(&[&[1.0, 2.0], &[3.0, 4.0]]).unwrap();
    /// let b = Matrix::from_rows(&[&[5.0], &[6.0]]).unwrap();
    /// assert_eq!(a.mul(&b).unwrap().as_slice(), &[17.0, 39.0]);
    /// ```
    pub fn mul(&self, other: &Self) -> Result<Self, LinalgError> {
        let mut out = Self::zeros(self.rows, other.cols);
        Self::mul_into(self, other, &mut out)?;
        Ok(out)
    }

    /// `out ← A B` without allocating; `out` must already be `A.rows × B.cols` and must
    /// not alias `A` or `B` (the borrow checker guarantees that). On a shape error `out`
    /// is left as it was.
    pub fn mul_into(a: &Self, b: &Self, out: &mut Self) -> Result<(), LinalgError> {
        if a.cols != b.rows {
            return Err(LinalgError::DimensionMismatch {
                left: a.shape(),
                right: b.shape(),
            });
        }
        if out.shape() != (a.rows, b.cols) {
            return Err(LinalgError::DimensionMismatch {
                left: (a.rows, b.cols),
                right: out.shape(),
            });
        }
        for i in 0..a.rows {
            for j in 0..b.cols {
                let mut s = 0.0;
                for k in 0..a.cols {
                    s += a.data[i * a.cols + k] * b.data[k * b.cols + j];
                }
                out.data[i * out.cols + j] = s;
            }
        }
        Ok(())
    }

    /// `A x` for a vector `x` of length `cols`.
    pub fn mul_vec(&self, x: &[f64]) -> Result<Vec<f64>, LinalgError> {
        if x.len() != self.cols {
            return Err(LinalgError::DimensionMismatch {
                left: self.shape(),
                right: (x.len(), 1),
            });
        }
        Ok((0..self.rows)
            .map(|i| self.row(i).iter().zip(x).map(|(a, b)| a * b).sum())
            .collect())
    }

    /// Largest absolute entry, `max |a_ij|` (0 for an empty matrix).
    #[must_use]
    pub fn max_abs(&self) -> f64 {
        self.data.iter().fold(0.0, |m, v| m.max(v.abs()))
    }

    /// Frobenius norm `√(Σ a_ij²)`.
    #[must_use]
    pub fn frobenius_norm(&self) -> f64 {
        self.data.iter().map(|v| v * v).sum::<f64>().sqrt()
    }

    /// `true` when square and `|a_ij − a_ji| ≤ tol · max(1, max|a|)` for all `i, j`
    /// (a relative tolerance, so the test does not depend on the matrix's scale).
    #[must_use]
    pub fn is_symmetric(&self, tol: f64) -> bool {
        if !self.is_square() {
            return false;
        }
        let bound = tol * self.max_abs().max(1.0);
        (0..self.rows).all(|i| (0..i).all(|j| (self[(i, j)] - self[(j, i)]).abs() <= bound))
    }

    /// Replaces a square `A` by `(A + Aᵀ) / 2` in place, removing the asymmetry rounding
    /// leaves in a covariance or Riccati update. A non-square matrix is left unchanged.
    pub fn symmetrize(&mut self) {
        if !self.is_square() {
            return;
        }
        for i in 0..self.rows {
            for j in 0..i {
                let m = 0.5 * (self[(i, j)] + self[(j, i)]);
                self[(i, j)] = m;
                self[(j, i)] = m;
            }
        }
    }

    /// LU factorisation with partial pivoting, `P A = L U` (Golub & Van Loan 2013,
    /// Algorithm 3.4.1). A pivot with `|u_kk| ≤ n · ε · max|a|` counts as zero and gives
    /// [`LinalgError::Singular`].
    pub fn lu(&self) -> Result<Lu, LinalgError> {
        if !self.is_square() {
            return Err(LinalgError::NotSquare {
                rows: self.rows,
                cols: self.cols,
            });
        }
        if !self.is_finite() {
            return Err(LinalgError::NonFinite);
        }
        let n = self.rows;
        let mut lu = self.clone();
        let mut perm: Vec<usize> = (0..n).collect();
        let mut sign = 1.0;
        let tiny = n as f64 * f64::EPSILON * self.max_abs();
        for k in 0..n {
            // Pivot: largest |a_ik| for i ≥ k.
            let mut p = k;
            for i in k + 1..n {
                if lu[(i, k)].abs() > lu[(p, k)].abs() {
                    p = i;
                }
            }
            if lu[(p, k)].abs() <= tiny || lu[(p, k)] == 0.0 {
                return Err(LinalgError::Singular { column: k });
            }
            if p != k {
                for j in 0..n {
                    lu.data.swap(k * n + j, p * n + j);
                }
                perm.swap(k, p);
                sign = -sign;
            }
            let pivot = lu[(k, k)];
            for i in k + 1..n {
                let l = lu[(i, k)] / pivot;
                lu[(i, k)] = l;
                for j in k + 1..n {
                    let u = lu[(k, j)];
                    lu[(i, j)] -= l * u;
                }
            }
        }
        Ok(Lu { lu, perm, sign })
    }

    /// Solves `A X = B` for `X` by LU with partial pivoting.
    ///
    /// # Example
    /// ```
    /// use labcore::linalg::Matrix;
    /// let a = Matrix::from_rows(&[&[2.0, 1.0], &[1.0, 3.0]]).unwrap();
    /// let x = a.solve(&Matrix::column(&[3.0, 5.0])).unwrap();
    /// assert!((x[(0, 0)] - 0.8).abs() < 1e-15 && (x[(1, 0)] - 1.4).abs() < 1e-15);
    /// ```
    pub fn solve(&self, b: &Self) -> Result<Self, LinalgError> {
        self.lu()?.solve(b)
    }

    /// The inverse `A⁻¹`, or an error when `A` is singular or not square.
    pub fn inverse(&self) -> Result<Self, LinalgError> {
        self.lu()?.solve(&Self::identity(self.rows))
    }

    /// `det A` via LU (0 when singular to working precision).
    pub fn determinant(&self) -> Result<f64, LinalgError> {
        match self.lu() {
            Ok(lu) => Ok(lu.determinant()),
            Err(LinalgError::Singular { .. }) => Ok(0.0),
            Err(e) => Err(e),
        }
    }

    /// Cholesky factor `L` (lower triangular, positive diagonal) with `A = L Lᵀ`
    /// (Golub & Van Loan 2013, Algorithm 4.2.1). `A` must be symmetric to `sym_tol`
    /// (see [`Matrix::is_symmetric`]) and positive-definite; only its lower triangle is read.
    ///
    /// # Example
    /// ```
    /// use labcore::linalg::Matrix;
    /// let a = Matrix::from_rows(&[&[4.0, 2.0], &[2.0, 5.0]]).unwrap();
    /// let l = a.cholesky(1e-12).unwrap();
    /// assert_eq!(l.as_slice(), &[2.0, 0.0, 1.0, 2.0]);
    /// ```
    pub fn cholesky(&self, sym_tol: f64) -> Result<Self, LinalgError> {
        if !self.is_square() {
            return Err(LinalgError::NotSquare {
                rows: self.rows,
                cols: self.cols,
            });
        }
        if !self.is_finite() {
            return Err(LinalgError::NonFinite);
        }
        if !self.is_symmetric(sym_tol) {
            return Err(LinalgError::NotSymmetric);
        }
        let n = self.rows;
        let mut l = Self::zeros(n, n);
        for j in 0..n {
            let mut d = self[(j, j)];
            for k in 0..j {
                d -= l[(j, k)] * l[(j, k)];
            }
            if d.is_nan() || d <= 0.0 {
                return Err(LinalgError::NotPositiveDefinite { column: j });
            }
            let ljj = d.sqrt();
            l[(j, j)] = ljj;
            for i in j + 1..n {
                let mut s = self[(i, j)];
                for k in 0..j {
                    s -= l[(i, k)] * l[(j, k)];
                }
                l[(i, j)] = s / ljj;
            }
        }
        Ok(l)
    }
}

impl Index<(usize, usize)> for Matrix {
    type Output = f64;
    /// Entry `(row, col)`; panics when out of range, like slice indexing.
    fn index(&self, (i, j): (usize, usize)) -> &f64 {
        assert!(
            i < self.rows && j < self.cols,
            "index ({i}, {j}) out of range"
        );
        &self.data[i * self.cols + j]
    }
}

impl IndexMut<(usize, usize)> for Matrix {
    fn index_mut(&mut self, (i, j): (usize, usize)) -> &mut f64 {
        assert!(
            i < self.rows && j < self.cols,
            "index ({i}, {j}) out of range"
        );
        &mut self.data[i * self.cols + j]
    }
}

/// A packed LU factorisation `P A = L U` from [`Matrix::lu`]: `L` (unit diagonal, not
/// stored) below the diagonal, `U` on and above it.
#[derive(Clone, Debug, PartialEq)]
pub struct Lu {
    lu: Matrix,
    /// `perm[i]` is the row of `A` that became row `i` of `P A`.
    perm: Vec<usize>,
    sign: f64,
}

impl Lu {
    /// Solves `A X = B` by forward substitution with `L` then back substitution with `U`
    /// (Golub & Van Loan 2013, Algorithms 3.1.1–3.1.2).
    pub fn solve(&self, b: &Matrix) -> Result<Matrix, LinalgError> {
        let n = self.lu.rows;
        if b.rows != n {
            return Err(LinalgError::DimensionMismatch {
                left: self.lu.shape(),
                right: b.shape(),
            });
        }
        let mut x = Matrix::zeros(n, b.cols);
        for (i, &p) in self.perm.iter().enumerate() {
            for j in 0..b.cols {
                x[(i, j)] = b[(p, j)];
            }
        }
        for c in 0..b.cols {
            for i in 0..n {
                let mut s = x[(i, c)];
                for k in 0..i {
                    s -= self.lu[(i, k)] * x[(k, c)];
                }
                x[(i, c)] = s;
            }
            for i in (0..n).rev() {
                let mut s = x[(i, c)];
                for k in i + 1..n {
                    s -= self.lu[(i, k)] * x[(k, c)];
                }
                x[(i, c)] = s / self.lu[(i, i)];
            }
        }
        Ok(x)
    }

    /// `det A = ±Π u_ii` (sign of the row permutation).
    #[must_use]
    pub fn determinant(&self) -> f64 {
        (0..self.lu.rows).fold(self.sign, |d, i| d * self.lu[(i, i)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(rows: &[&[f64]]) -> Matrix {
        Matrix::from_rows(rows).unwrap()
    }

    #[test]
    fn constructors_and_shape() {
        let i3 = Matrix::identity(3);
        assert_eq!(i3.shape(), (3, 3));
        assert_eq!(
            i3.as_slice(),
            &[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
        );
        assert_eq!(
            Matrix::from_diag(&[2.0, 3.0]).as_slice(),
            &[2.0, 0.0, 0.0, 3.0]
        );
        assert_eq!(Matrix::zeros(2, 3).as_slice(), &[0.0; 6]);
        assert_eq!(Matrix::column(&[1.0, 2.0]).shape(), (2, 1));
        assert!(Matrix::from_vec(2, 2, vec![1.0; 3]).is_err());
        assert_eq!(m(&[&[1.0, 2.0, 3.0]]).get(0, 2), Some(3.0));
        assert_eq!(m(&[&[1.0, 2.0, 3.0]]).get(1, 0), None);
    }

    #[test]
    fn transpose_add_sub_scale_by_hand() {
        let a = m(&[&[1.0, 2.0, 3.0], &[4.0, 5.0, 6.0]]);
        assert_eq!(a.transpose(), m(&[&[1.0, 4.0], &[2.0, 5.0], &[3.0, 6.0]]));
        let b = m(&[&[1.0, 1.0, 1.0], &[2.0, 2.0, 2.0]]);
        assert_eq!(a.add(&b).unwrap(), m(&[&[2.0, 3.0, 4.0], &[6.0, 7.0, 8.0]]));
        assert_eq!(a.sub(&b).unwrap(), m(&[&[0.0, 1.0, 2.0], &[2.0, 3.0, 4.0]]));
        assert_eq!(
            a.scale(-2.0),
            m(&[&[-2.0, -4.0, -6.0], &[-8.0, -10.0, -12.0]])
        );
        assert_eq!(
            a.add(&a.transpose()),
            Err(LinalgError::DimensionMismatch {
                left: (2, 3),
                right: (3, 2)
            })
        );
    }

    #[test]
    fn product_by_hand_and_into_preallocated() {
        let a = m(&[&[1.0, 2.0, 3.0], &[4.0, 5.0, 6.0]]);
        let b = m(&[&[7.0, 8.0], &[9.0, 10.0], &[11.0, 12.0]]);
        // [1·7+2·9+3·11, 1·8+2·10+3·12; 4·7+5·9+6·11, 4·8+5·10+6·12]
        let expected = m(&[&[58.0, 64.0], &[139.0, 154.0]]);
        assert_eq!(a.mul(&b).unwrap(), expected);
        let mut out = Matrix::zeros(2, 2);
        Matrix::mul_into(&a, &b, &mut out).unwrap();
        assert_eq!(out, expected);
        let mut wrong = Matrix::identity(3);
        assert!(Matrix::mul_into(&a, &b, &mut wrong).is_err());
        assert_eq!(wrong, Matrix::identity(3), "untouched on error");
        assert!(a.mul(&a).is_err());
        assert_eq!(a.mul_vec(&[1.0, 0.0, -1.0]).unwrap(), vec![-2.0, -2.0]);
    }

    #[test]
    fn lu_solve_needs_pivoting_and_matches_hand_solution() {
        // a_11 = 0 forces a row swap. With x = (1, 2, 3):
        //   b = A x = (0 + 4 + 3, 1 + 2 + 3, 2 + 2 + 0) = (7, 6, 4).
        let a = m(&[&[0.0, 2.0, 1.0], &[1.0, 1.0, 1.0], &[2.0, 1.0, 0.0]]);
        let x = a.solve(&Matrix::column(&[7.0, 6.0, 4.0])).unwrap();
        for (got, want) in x.as_slice().iter().zip([1.0, 2.0, 3.0]) {
            assert!((got - want).abs() < 1e-14, "{got} vs {want}");
        }
        // det by cofactor expansion along row 0: −2·(0 − 2) + 1·(1 − 2) = 3.
        assert!((a.determinant().unwrap() - 3.0).abs() < 1e-14);
    }

    #[test]
    fn inverse_by_hand_and_singular_is_an_error() {
        let a = m(&[&[4.0, 7.0], &[2.0, 6.0]]);
        // 1/10 · [6, −7; −2, 4]
        let inv = a.inverse().unwrap();
        let expected = [0.6, -0.7, -0.2, 0.4];
        for (got, want) in inv.as_slice().iter().zip(expected) {
            assert!((got - want).abs() < 1e-15);
        }
        let prod = a.mul(&inv).unwrap();
        assert!(prod.sub(&Matrix::identity(2)).unwrap().max_abs() < 1e-15);

        let singular = m(&[&[1.0, 2.0], &[2.0, 4.0]]);
        assert!(matches!(
            singular.inverse(),
            Err(LinalgError::Singular { .. })
        ));
        assert_eq!(singular.determinant(), Ok(0.0));
        assert!(matches!(
            Matrix::zeros(2, 3).inverse(),
            Err(LinalgError::NotSquare { rows: 2, cols: 3 })
        ));
        let nan = m(&[&[f64::NAN, 0.0], &[0.0, 1.0]]);
        assert_eq!(
            nan.solve(&Matrix::column(&[1.0, 1.0])),
            Err(LinalgError::NonFinite)
        );
    }

    #[test]
    fn cholesky_by_hand_and_rejections() {
        // [4 12 −16; 12 37 −43; −16 −43 98] = L Lᵀ with L = [2 0 0; 6 1 0; −8 5 3].
        let a = m(&[
            &[4.0, 12.0, -16.0],
            &[12.0, 37.0, -43.0],
            &[-16.0, -43.0, 98.0],
        ]);
        let l = a.cholesky(1e-12).unwrap();
        assert_eq!(
            l,
            m(&[&[2.0, 0.0, 0.0], &[6.0, 1.0, 0.0], &[-8.0, 5.0, 3.0]])
        );
        let indefinite = m(&[&[1.0, 2.0], &[2.0, 1.0]]);
        assert_eq!(
            indefinite.cholesky(1e-12),
            Err(LinalgError::NotPositiveDefinite { column: 1 })
        );
        let asym = m(&[&[2.0, 1.0], &[0.0, 2.0]]);
        assert_eq!(asym.cholesky(1e-12), Err(LinalgError::NotSymmetric));
    }

    #[test]
    fn symmetry_check_and_symmetrize() {
        let mut a = m(&[&[1.0, 2.0], &[2.0 + 1e-10, 3.0]]);
        assert!(!a.is_symmetric(1e-12));
        assert!(a.is_symmetric(1e-9));
        a.symmetrize();
        assert!(a.is_symmetric(0.0));
        assert_eq!(a[(0, 1)], 2.0 + 0.5e-10);
        assert!(!Matrix::zeros(2, 3).is_symmetric(1.0));
    }

    #[test]
    fn norms_by_hand() {
        let a = m(&[&[3.0, -4.0]]);
        assert_eq!(a.frobenius_norm(), 5.0);
        assert_eq!(a.max_abs(), 4.0);
    }
}
