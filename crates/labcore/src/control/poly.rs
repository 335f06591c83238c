//! Complex numbers, polynomial roots and eigenvalues of small matrices.
//!
//! **Roots.** Degrees 1 and 2 are solved in closed form (the quadratic with the
//! cancellation-free form `q = −(b + sgn(b)√Δ)/2`, roots `q/a` and `c/q`; Press et al.,
//! *Numerical Recipes*, 3rd ed., §5.6). Higher degrees use the Weierstrass /
//! Durand–Kerner simultaneous iteration on the monic polynomial
//!
//! ```text
//! zᵢ ← zᵢ − p(zᵢ) / Πⱼ≠ᵢ (zᵢ − zⱼ)
//! ```
//!
//! (Kerner, *Numer. Math.* 8, 1966), started on the circle of Cauchy's root bound
//! `1 + max |aₖ/aₙ|` at angles that avoid symmetry, followed by two Newton polishing
//! steps per root. Convergence is quadratic for simple roots and linear for repeated
//! ones, so a double root is found to about `√ε` relative accuracy — the conditioning
//! limit of any method working from coefficients. Exact zero trailing coefficients are
//! deflated first (roots exactly 0). Complex roots of a real polynomial come back as
//! exact conjugate pairs; roots whose imaginary part is below `1e-9 · max(1, |z|)` are
//! returned as real.
//!
//! **Eigenvalues.** The characteristic polynomial `det(sI − A)` of an `n × n` matrix
//! comes from the Faddeev–LeVerrier recursion
//!
//! ```text
//! M₀ = 0, c_n = 1;   M_k = A M_{k−1} + c_{n−k+1} I,   c_{n−k} = −tr(A M_k) / k
//! ```
//!
//! (Gantmacher, *The Theory of Matrices*, Vol. 1, 1959, Ch. IV §4), whose roots are
//! then found as above. It is exact in exact arithmetic and accurate for the small
//! (n ≤ 6), well-scaled matrices of this lab; it is not a general-purpose eigensolver.

use crate::linalg::{LinalgError, Matrix};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A complex number `re + i·im`.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Complex {
    pub re: f64,
    pub im: f64,
}

impl Complex {
    /// `re + i·im`.
    #[must_use]
    pub const fn new(re: f64, im: f64) -> Self {
        Self { re, im }
    }

    /// A real number.
    #[must_use]
    pub const fn real(re: f64) -> Self {
        Self { re, im: 0.0 }
    }

    /// `|z|`, without overflow.
    #[must_use]
    pub fn abs(self) -> f64 {
        crate::math::hypot(self.re, self.im)
    }

    /// The conjugate `re − i·im`.
    #[must_use]
    pub fn conj(self) -> Self {
        Self::new(self.re, -self.im)
    }

    /// `true` when both parts are finite.
    #[must_use]
    pub fn is_finite(self) -> bool {
        self.re.is_finite() && self.im.is_finite()
    }
}

impl Add for Complex {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.re + o.re, self.im + o.im)
    }
}

impl Sub for Complex {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.re - o.re, self.im - o.im)
    }
}

impl Mul for Complex {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}

impl Mul<f64> for Complex {
    type Output = Self;
    fn mul(self, k: f64) -> Self {
        Self::new(self.re * k, self.im * k)
    }
}

impl Neg for Complex {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.re, -self.im)
    }
}

impl Div for Complex {
    type Output = Self;
    /// Smith's algorithm (Smith, *CACM* 5(8), 1962), which avoids overflow in `|o|²`.
    fn div(self, o: Self) -> Self {
        if o.re.abs() >= o.im.abs() {
            let r = o.im / o.re;
            let d = o.re + o.im * r;
            Self::new((self.re + self.im * r) / d, (self.im - self.re * r) / d)
        } else {
            let r = o.re / o.im;
            let d = o.re * r + o.im;
            Self::new((self.re * r + self.im) / d, (self.im * r - self.re) / d)
        }
    }
}

/// Why roots or eigenvalues could not be computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RootError {
    /// No coefficients, a zero leading coefficient, or a NaN/infinite coefficient.
    InvalidPolynomial,
    /// The iteration did not settle within its iteration budget.
    NotConverged { iterations: usize, residual: f64 },
    /// The matrix was not square or had a non-finite entry.
    Matrix(LinalgError),
}

/// `p(z)` for real coefficients, highest power first (Horner).
#[must_use]
pub fn eval(coeffs: &[f64], z: Complex) -> Complex {
    coeffs
        .iter()
        .fold(Complex::default(), |acc, &c| acc * z + Complex::real(c))
}

fn eval_with_derivative(coeffs: &[f64], z: Complex) -> (Complex, Complex) {
    let mut p = Complex::default();
    let mut dp = Complex::default();
    for &c in coeffs {
        dp = dp * z + p;
        p = p * z + Complex::real(c);
    }
    (p, dp)
}

/// Iteration budget of the Durand–Kerner loop.
pub const MAX_ROOT_ITERATIONS: usize = 2000;

/// All complex roots of the real polynomial `c₀ sⁿ + c₁ sⁿ⁻¹ + … + cₙ` (coefficients
/// highest power first, `c₀ ≠ 0`), sorted by real part then imaginary part.
///
/// # Example
/// ```
/// use labcore::control::poly::roots;
/// // s³ + 6s² + 11s + 6 = (s + 1)(s + 2)(s + 3)
/// let r = roots(&[1.0, 6.0, 11.0, 6.0]).unwrap();
/// for (z, want) in r.iter().zip([-3.0, -2.0, -1.0]) {
///     assert!((z.re - want).abs() < 1e-12 && z.im == 0.0);
/// }
/// ```
pub fn roots(coeffs: &[f64]) -> Result<Vec<Complex>, RootError> {
    if coeffs.is_empty() || coeffs[0] == 0.0 || coeffs.iter().any(|c| !c.is_finite()) {
        return Err(RootError::InvalidPolynomial);
    }
    let mut coeffs = coeffs.to_vec();
    let mut out = Vec::with_capacity(coeffs.len() - 1);
    // Deflate exact zero roots.
    while coeffs.len() > 1 && coeffs[coeffs.len() - 1] == 0.0 {
        coeffs.pop();
        out.push(Complex::real(0.0));
    }
    let lead = coeffs[0];
    let monic: Vec<f64> = coeffs.iter().map(|c| c / lead).collect();
    let n = monic.len() - 1;
    match n {
        0 => {}
        1 => out.push(Complex::real(-monic[1])),
        2 => out.extend(quadratic(monic[1], monic[2])),
        _ => out.extend(durand_kerner(&monic)?),
    }
    tidy(&mut out);
    Ok(out)
}

/// Roots of `s² + b s + c` without cancellation.
fn quadratic(b: f64, c: f64) -> [Complex; 2] {
    let disc = b * b - 4.0 * c;
    if disc >= 0.0 {
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        if q == 0.0 {
            // b = 0 and c = 0: a double root at 0.
            return [Complex::real(0.0), Complex::real(0.0)];
        }
        [Complex::real(q), Complex::real(c / q)]
    } else {
        let re = -0.5 * b;
        let im = 0.5 * (-disc).sqrt();
        [Complex::new(re, im), Complex::new(re, -im)]
    }
}

fn durand_kerner(monic: &[f64]) -> Result<Vec<Complex>, RootError> {
    let n = monic.len() - 1;
    let bound = 1.0 + monic[1..].iter().fold(0.0_f64, |m, c| m.max(c.abs()));
    // Start on a circle inside the Cauchy bound at angles 2πk/n + 0.4 (breaks symmetry
    // with real-coefficient polynomials).
    let radius = 0.5 * bound;
    let mut z: Vec<Complex> = (0..n)
        .map(|k| {
            let angle = 2.0 * std::f64::consts::PI * k as f64 / n as f64 + 0.4;
            let (s, c) = crate::math::sin_cos(angle);
            Complex::new(radius * c, radius * s)
        })
        .collect();
    for _ in 0..MAX_ROOT_ITERATIONS {
        let mut change: f64 = 0.0;
        for i in 0..n {
            let mut denom = Complex::real(1.0);
            for j in 0..n {
                if j != i {
                    denom = denom * (z[i] - z[j]);
                }
            }
            if denom.abs() == 0.0 {
                // Coincident iterates: nudge apart deterministically.
                z[i] = z[i] + Complex::new(1e-8 * bound, 1e-8 * bound);
                change = f64::INFINITY;
                continue;
            }
            let delta = eval(monic, z[i]) / denom;
            z[i] = z[i] - delta;
            change = change.max(delta.abs() / z[i].abs().max(1.0));
        }
        if change <= 4.0 * f64::EPSILON {
            break;
        }
    }
    if z.iter().any(|r| !r.is_finite()) {
        return Err(RootError::NotConverged {
            iterations: MAX_ROOT_ITERATIONS,
            residual: f64::INFINITY,
        });
    }
    // Newton polishing (keeps a step only when it lowers |p|).
    for r in &mut z {
        for _ in 0..2 {
            let (p, dp) = eval_with_derivative(monic, *r);
            if dp.abs() == 0.0 {
                break;
            }
            let candidate = *r - p / dp;
            if candidate.is_finite() && eval(monic, candidate).abs() <= p.abs() {
                *r = candidate;
            }
        }
    }
    // Residual check relative to the polynomial's scale at |z|.
    let mut worst: f64 = 0.0;
    for r in &z {
        let scale = monic
            .iter()
            .rev()
            .enumerate()
            .map(|(k, c)| c.abs() * r.abs().powi(k as i32))
            .sum::<f64>()
            .max(f64::MIN_POSITIVE);
        worst = worst.max(eval(monic, *r).abs() / scale);
    }
    if worst > 1e-6 {
        return Err(RootError::NotConverged {
            iterations: MAX_ROOT_ITERATIONS,
            residual: worst,
        });
    }
    Ok(z)
}

/// Snap near-real roots to the real axis, make complex roots exact conjugate pairs,
/// and sort by (re, im).
fn tidy(z: &mut Vec<Complex>) {
    for r in z.iter_mut() {
        if r.im.abs() <= 1e-9 * r.abs().max(1.0) {
            r.im = 0.0;
        }
    }
    let upper: Vec<Complex> = z.iter().copied().filter(|r| r.im > 0.0).collect();
    let lower: Vec<Complex> = z.iter().copied().filter(|r| r.im < 0.0).collect();
    if upper.len() == lower.len() {
        let mut used = vec![false; lower.len()];
        let mut paired = Vec::with_capacity(z.len());
        for u in &upper {
            let best = lower
                .iter()
                .enumerate()
                .filter(|(k, _)| !used[*k])
                .min_by(|a, b| (a.1.conj() - *u).abs().total_cmp(&(b.1.conj() - *u).abs()))
                .map(|(k, _)| k);
            if let Some(k) = best {
                used[k] = true;
                let l = lower[k];
                let re = 0.5 * (u.re + l.re);
                let im = 0.5 * (u.im - l.im);
                paired.push(Complex::new(re, im));
                paired.push(Complex::new(re, -im));
            }
        }
        paired.extend(z.iter().copied().filter(|r| r.im == 0.0));
        *z = paired;
    }
    z.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
}

/// Coefficients of `det(sI − A)`, highest power first (`[1, c_{n−1}, …, c_0]`), by the
/// Faddeev–LeVerrier recursion.
///
/// # Example
/// ```
/// use labcore::{control::poly::characteristic_polynomial, linalg::Matrix};
/// let a = Matrix::from_rows(&[&[0.0, 1.0], &[-2.0, -3.0]]).unwrap();
/// assert_eq!(characteristic_polynomial(&a).unwrap(), vec![1.0, 3.0, 2.0]);
/// ```
pub fn characteristic_polynomial(a: &Matrix) -> Result<Vec<f64>, RootError> {
    if !a.is_square() {
        return Err(RootError::Matrix(LinalgError::NotSquare {
            rows: a.rows(),
            cols: a.cols(),
        }));
    }
    if !a.is_finite() {
        return Err(RootError::Matrix(LinalgError::NonFinite));
    }
    let n = a.rows();
    let mut coeffs = vec![1.0];
    let mut m = Matrix::zeros(n, n);
    let mut am = Matrix::zeros(n, n);
    let mut c_prev = 1.0;
    for k in 1..=n {
        // M_k = A M_{k−1} + c_{n−k+1} I
        Matrix::mul_into(a, &m, &mut am).map_err(RootError::Matrix)?;
        m = am.clone();
        for i in 0..n {
            m[(i, i)] += c_prev;
        }
        Matrix::mul_into(a, &m, &mut am).map_err(RootError::Matrix)?;
        let trace: f64 = (0..n).map(|i| am[(i, i)]).sum();
        let c = -trace / k as f64;
        coeffs.push(c);
        c_prev = c;
    }
    Ok(coeffs)
}

/// Eigenvalues of a small real square matrix (roots of its characteristic polynomial),
/// sorted by real part.
///
/// # Example
/// ```
/// use labcore::{control::poly::eigenvalues, linalg::Matrix};
/// // A rotation generator: eigenvalues ±i.
/// let a = Matrix::from_rows(&[&[0.0, -1.0], &[1.0, 0.0]]).unwrap();
/// let ev = eigenvalues(&a).unwrap();
/// assert_eq!(ev[0].re, 0.0);
/// assert!((ev[0].im.abs() - 1.0).abs() < 1e-15);
/// ```
pub fn eigenvalues(a: &Matrix) -> Result<Vec<Complex>, RootError> {
    roots(&characteristic_polynomial(a)?)
}

/// Largest real part of a set of roots (`−∞` for an empty set): the system is
/// asymptotically stable when it is negative.
#[must_use]
pub fn spectral_abscissa(z: &[Complex]) -> f64 {
    z.iter().fold(f64::NEG_INFINITY, |m, r| m.max(r.re))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Complex, b: Complex, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn complex_arithmetic_by_hand() {
        let a = Complex::new(1.0, 2.0);
        let b = Complex::new(3.0, -1.0);
        assert_eq!(a * b, Complex::new(5.0, 5.0));
        // (1 + 2i)/(3 − i) = (1 + 2i)(3 + i)/10 = (1 + 7i)/10
        assert!(close(a / b, Complex::new(0.1, 0.7), 1e-15));
        assert!(close(
            b / Complex::new(0.0, 2.0),
            Complex::new(-0.5, -1.5),
            1e-15
        ));
        assert_eq!(Complex::new(3.0, 4.0).abs(), 5.0);
    }

    #[test]
    fn low_degree_closed_forms() {
        assert_eq!(roots(&[2.0, -4.0]).unwrap(), vec![Complex::real(2.0)]);
        // s² + 2s + 5: −1 ± 2i
        let r = roots(&[1.0, 2.0, 5.0]).unwrap();
        assert_eq!(r, vec![Complex::new(-1.0, -2.0), Complex::new(-1.0, 2.0)]);
        // Cancellation-prone: s² + 1e8 s + 1 has roots ≈ −1e8 and −1e-8.
        let r = roots(&[1.0, 1e8, 1.0]).unwrap();
        assert!((r[1].re + 1e-8).abs() < 1e-22);
        assert!(roots(&[0.0, 1.0]).is_err());
        assert!(roots(&[1.0, f64::NAN]).is_err());
    }

    #[test]
    fn quartic_with_complex_pairs_and_a_zero_root() {
        // (s² + 2s + 5)(s − 3)s = s⁴ − s³ − s² − 15s
        let r = roots(&[1.0, -1.0, -1.0, -15.0, 0.0]).unwrap();
        let want = [
            Complex::new(-1.0, -2.0),
            Complex::new(-1.0, 2.0),
            Complex::real(0.0),
            Complex::real(3.0),
        ];
        for (got, want) in r.iter().zip(want) {
            assert!(close(*got, want, 1e-12), "{got:?} vs {want:?}");
        }
        // Conjugates are exact.
        assert_eq!(r[0], r[1].conj());
    }

    #[test]
    fn repeated_root_to_sqrt_epsilon() {
        // (s + 2)²(s + 1) = s³ + 5s² + 8s + 4
        let r = roots(&[1.0, 5.0, 8.0, 4.0]).unwrap();
        assert!(close(r[0], Complex::real(-2.0), 1e-7));
        assert!(close(r[1], Complex::real(-2.0), 1e-7));
        assert!(close(r[2], Complex::real(-1.0), 1e-12));
    }

    #[test]
    fn eigenvalues_of_a_companion_and_a_block_matrix() {
        // Companion of s³ + 6s² + 11s + 6.
        let a =
            Matrix::from_rows(&[&[0.0, 1.0, 0.0], &[0.0, 0.0, 1.0], &[-6.0, -11.0, -6.0]]).unwrap();
        assert_eq!(
            characteristic_polynomial(&a).unwrap(),
            vec![1.0, 6.0, 11.0, 6.0]
        );
        let ev = eigenvalues(&a).unwrap();
        for (z, want) in ev.iter().zip([-3.0, -2.0, -1.0]) {
            assert!(close(*z, Complex::real(want), 1e-12));
        }
        // Block-diagonal: [[1, 2], [-2, 1]] ⊕ [-4]: 1 ± 2i and −4.
        let b =
            Matrix::from_rows(&[&[1.0, 2.0, 0.0], &[-2.0, 1.0, 0.0], &[0.0, 0.0, -4.0]]).unwrap();
        let ev = eigenvalues(&b).unwrap();
        assert!(close(ev[0], Complex::real(-4.0), 1e-12));
        assert!(close(ev[2], Complex::new(1.0, 2.0), 1e-12));
        assert_eq!(spectral_abscissa(&ev), ev[2].re);
        assert!(eigenvalues(&Matrix::zeros(2, 3)).is_err());
    }
}
