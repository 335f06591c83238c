//! EKF-SLAM with range-bearing observations and known data association.
//!
//! The state stacks the pose and every landmark seen so far,
//! `x = (x, y, θ, m₁x, m₁y, …, m_Nx, m_Ny)`, `n = 3 + 2N`, with one dense
//! `n × n` covariance ([`crate::linalg::Matrix`]). (Thrun, Burgard & Fox,
//! *Probabilistic Robotics*, 2005, §10.2, Tables 10.1–10.2; Durrant-Whyte &
//! Bailey, "Simultaneous localization and mapping: Part I", *IEEE RAM* 13(2),
//! 2006; Bailey & Durrant-Whyte, "… Part II", *IEEE RAM* 13(3), 2006.)
//!
//! **Predict** moves only the pose: with `F`, `Q` of [`super::models`],
//! `P_rr ← F P_rr Fᵀ + Q` and `P_rm ← F P_rm` (the landmarks do not move), so
//! prediction costs `O(n)` (Table 10.1 lines 3–5 exploit the same sparsity).
//!
//! **Initialisation on first sight.** A new landmark seen at range `r`,
//! bearing `φ` is placed at
//!
//! ```text
//! m = (x + r cos(θ + φ),  y + r sin(θ + φ))
//! ```
//!
//! and the state is augmented with its full cross-covariances, with
//! `G_r = ∂m/∂(x, y, θ) = [1 0 −r sin(θ+φ); 0 1 r cos(θ+φ)]` and
//! `G_z = ∂m/∂(r, φ) = [cos(θ+φ) −r sin(θ+φ); sin(θ+φ) r cos(θ+φ)]`:
//!
//! ```text
//! P_mm = G_r P_rr G_rᵀ + G_z R G_zᵀ          P_m,x = G_r P_r,x   (every existing state x)
//! ```
//!
//! (Bailey & Durrant-Whyte 2006 Part II, §"Augmentation"; Thrun et al.
//! Table 10.1 line 11 initialises the mean the same way but keeps the prior
//! covariance — this augmentation is the exact linearised equivalent.)
//!
//! **Update** with an observation of landmark `j` already in the state:
//! `H` has only five non-zero columns (pose and landmark `j`,
//! Table 10.1 lines 15–16):
//!
//! ```text
//! H_r = [ −dx/√q  −dy/√q  0 ;  dy/q  −dx/q  −1 ]      H_j = [ dx/√q  dy/√q ;  −dy/q  dx/q ]
//! ```
//!
//! so `W = P Hᵀ` (n×2) costs `O(n)`, `S = H W + R`, `K = W S⁻¹`, and the
//! Joseph-form covariance (Bucy & Joseph 1968), expanded with `W` and `S`,
//! needs no `n × n × n` product:
//!
//! ```text
//! (I − K H) P (I − K H)ᵀ + K R Kᵀ = P − K Wᵀ − W Kᵀ + K S Kᵀ = P + K Vᵀ + V Kᵀ,
//! V = ½ K S − W                                                  O(n²), one pass
//! ```
//!
//! The identity holds for any gain, so, like the factored Joseph form, the
//! result is insensitive to first order to rounding errors in `K` (for the
//! optimal gain `S Kᵀ = Wᵀ` and it reduces to `P − K S Kᵀ`). Each entry is
//! evaluated from products that are the same for `(i, c)` and `(c, i)`, so
//! `P` stays exactly symmetric.
//!
//! One update is therefore `O(n²) = O(N²)`; landmarks are
//! found by id in `O(N)`.

use glam::{DMat2, DMat3, DVec2, DVec3};

use super::models::{
    check_dt, check_motion, jacob_f, motion_model, process_noise, Control, MotionNoise, Observation,
};
use super::{check_cov2, check_cov3, wrap_angle, EstimationError};
use crate::linalg::Matrix;

/// Default cap on the number of landmarks (keeps the covariance below
/// 1003² entries ≈ 8 MB).
pub const DEFAULT_MAX_LANDMARKS: usize = 500;

/// What an observation did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SlamObservation {
    /// A new landmark was added to the state.
    Initialised { id: usize },
    /// An existing landmark's observation was folded in.
    Updated {
        id: usize,
        /// Innovation, bearing in `[−π, π)`.
        innovation: DVec2,
        /// `νᵀ S⁻¹ ν`.
        nis: f64,
    },
}

/// An EKF-SLAM filter.
#[derive(Clone, Debug, PartialEq)]
pub struct EkfSlam {
    mean: Vec<f64>,
    cov: Matrix,
    /// Landmark ids in state order: landmark `ids[k]` sits at `3 + 2k`.
    ids: Vec<usize>,
    /// Largest number of landmarks the state may hold.
    pub max_landmarks: usize,
    // Scratch columns reused by `update`: the gain K and V = ½ K S − W, as
    // four length-n columns (separate vectors so the O(n²) pass vectorises).
    scratch: [Vec<f64>; 4],
}

impl EkfSlam {
    /// A filter with no landmarks, pose `pose` with covariance `pose_cov`.
    #[must_use]
    pub fn new(pose: DVec3, pose_cov: DMat3) -> Self {
        let mut cov = Matrix::zeros(3, 3);
        for i in 0..3 {
            for j in 0..3 {
                cov[(i, j)] = pose_cov.col(j)[i];
            }
        }
        Self {
            mean: vec![pose.x, pose.y, wrap_angle(pose.z)],
            cov,
            ids: Vec::new(),
            max_landmarks: DEFAULT_MAX_LANDMARKS,
            scratch: Default::default(),
        }
    }

    /// State dimension `n = 3 + 2N`.
    #[must_use]
    pub fn state_len(&self) -> usize {
        self.mean.len()
    }

    /// Number of landmarks `N` in the state.
    #[must_use]
    pub fn landmark_count(&self) -> usize {
        self.ids.len()
    }

    /// The full mean vector.
    #[must_use]
    pub fn mean(&self) -> &[f64] {
        &self.mean
    }

    /// The full covariance.
    #[must_use]
    pub fn cov(&self) -> &Matrix {
        &self.cov
    }

    /// Landmark ids in state order.
    #[must_use]
    pub fn landmark_ids(&self) -> &[usize] {
        &self.ids
    }

    /// The pose estimate.
    #[must_use]
    pub fn pose(&self) -> DVec3 {
        DVec3::new(self.mean[0], self.mean[1], self.mean[2])
    }

    /// The pose covariance block.
    #[must_use]
    pub fn pose_cov(&self) -> DMat3 {
        let c = &self.cov;
        DMat3::from_cols(
            DVec3::new(c[(0, 0)], c[(1, 0)], c[(2, 0)]),
            DVec3::new(c[(0, 1)], c[(1, 1)], c[(2, 1)]),
            DVec3::new(c[(0, 2)], c[(1, 2)], c[(2, 2)]),
        )
    }

    fn slot(&self, id: usize) -> Option<usize> {
        self.ids.iter().position(|&i| i == id).map(|k| 3 + 2 * k)
    }

    /// Estimate and 2×2 covariance of landmark `id`, if it is in the state.
    #[must_use]
    pub fn landmark(&self, id: usize) -> Option<(DVec2, DMat2)> {
        let j = self.slot(id)?;
        let c = &self.cov;
        Some((
            DVec2::new(self.mean[j], self.mean[j + 1]),
            DMat2::from_cols(
                DVec2::new(c[(j, j)], c[(j + 1, j)]),
                DVec2::new(c[(j, j + 1)], c[(j + 1, j + 1)]),
            ),
        ))
    }

    /// Every landmark estimate as `(id, position)`, in state order.
    pub fn landmarks(&self) -> impl Iterator<Item = (usize, DVec2)> + '_ {
        self.ids
            .iter()
            .enumerate()
            .map(|(k, &id)| (id, DVec2::new(self.mean[3 + 2 * k], self.mean[4 + 2 * k])))
    }

    /// Prediction over `dt_s`: `O(n)`. Refuses invalid `dt` and non-finite
    /// input, leaving the filter unchanged.
    pub fn predict(
        &mut self,
        u: Control,
        dt_s: f64,
        noise: &MotionNoise,
    ) -> Result<(), EstimationError> {
        check_dt(dt_s)?;
        check_motion(u, noise)?;
        let q = process_noise(self.pose(), dt_s, noise);
        self.predict_core(u, dt_s, q)
    }

    /// Prediction with a process noise `q` of the pose given directly in
    /// state space (as filterpy and most texts write it): `P_rr ← F P_rr Fᵀ + Q`,
    /// `P_rm ← F P_rm`; [`EkfSlam::predict`] is this with `Q = V M Vᵀ`.
    /// Refuses invalid `dt`, non-finite input and a `q` that is not symmetric
    /// positive semi-definite, leaving the filter unchanged.
    ///
    /// # Example
    /// ```
    /// use labcore::estimation::models::Control;
    /// use labcore::estimation::slam::EkfSlam;
    /// use glam::{DMat3, DVec3};
    /// let mut slam = EkfSlam::new(DVec3::ZERO, DMat3::ZERO);
    /// let q = DMat3::from_diagonal(DVec3::new(1e-4, 1e-4, 1e-5));
    /// slam.predict_with_q(Control::new(1.0, 0.0), 0.5, q).unwrap();
    /// assert_eq!(slam.pose(), DVec3::new(0.5, 0.0, 0.0));
    /// assert_eq!(slam.pose_cov(), q);
    /// ```
    pub fn predict_with_q(
        &mut self,
        u: Control,
        dt_s: f64,
        q: DMat3,
    ) -> Result<(), EstimationError> {
        check_dt(dt_s)?;
        if !u.is_finite() {
            return Err(EstimationError::NonFinite);
        }
        check_cov3(q)?;
        self.predict_core(u, dt_s, q)
    }

    /// The prediction with checked inputs; unchanged on error.
    fn predict_core(&mut self, u: Control, dt_s: f64, q: DMat3) -> Result<(), EstimationError> {
        let x = self.pose();
        let f = jacob_f(x, u, dt_s);
        let new_x = motion_model(x, u, dt_s);
        let prr = symmetric3(f * self.pose_cov() * f.transpose() + q);
        if !(new_x.is_finite() && prr.is_finite()) {
            return Err(EstimationError::NonFinite);
        }
        // F = I + a e₀ e₂ᵀ + b e₁ e₂ᵀ: F P_rm changes rows 0 and 1 only.
        let (a, b) = (f.z_axis.x, f.z_axis.y);
        let n = self.state_len();
        for col in 3..n {
            let p2 = self.cov[(2, col)];
            let p0 = self.cov[(0, col)] + a * p2;
            let p1 = self.cov[(1, col)] + b * p2;
            self.cov[(0, col)] = p0;
            self.cov[(1, col)] = p1;
            self.cov[(col, 0)] = p0;
            self.cov[(col, 1)] = p1;
        }
        for i in 0..3 {
            for j in 0..3 {
                self.cov[(i, j)] = prr.col(j)[i];
            }
        }
        self.mean[..3].copy_from_slice(&new_x.to_array());
        Ok(())
    }

    /// A filter that starts from a prepared map: pose `pose` with covariance
    /// `pose_cov`, and each landmark `(id, mean, covariance)` inserted in
    /// order with [`EkfSlam::insert_landmark`] (independent of the pose and of
    /// each other). Observations of these landmarks are then updates, never
    /// first sightings.
    ///
    /// # Errors
    /// As [`EkfSlam::insert_landmark`], for the first landmark refused.
    ///
    /// # Example
    /// ```
    /// use labcore::estimation::slam::EkfSlam;
    /// use glam::{DMat2, DMat3, DVec2, DVec3};
    /// let map = [(7, DVec2::new(2.0, 1.0), DMat2::from_diagonal(DVec2::splat(0.01)))];
    /// let slam = EkfSlam::with_map(DVec3::ZERO, DMat3::IDENTITY * 1e-3, &map).unwrap();
    /// assert_eq!(slam.state_len(), 5);
    /// assert_eq!(slam.landmark(7), Some((map[0].1, map[0].2)));
    /// ```
    pub fn with_map(
        pose: DVec3,
        pose_cov: DMat3,
        landmarks: &[(usize, DVec2, DMat2)],
    ) -> Result<Self, EstimationError> {
        let mut slam = Self::new(pose, pose_cov);
        for &(id, mean, cov) in landmarks {
            slam.insert_landmark(id, mean, cov)?;
        }
        Ok(slam)
    }

    /// Adds landmark `id` at `mean` with covariance `cov` (metres, m²),
    /// uncorrelated with everything already in the state: a prior from a
    /// prepared map. A zero `cov` makes it a known landmark, as in
    /// localisation.
    ///
    /// # Errors
    /// [`EstimationError::DuplicateLandmark`] if `id` is already in the state,
    /// [`EstimationError::NonFinite`] / [`EstimationError::NotCovariance`] for
    /// a bad mean or covariance, [`EstimationError::TooManyLandmarks`] when
    /// the map is full. The filter is then unchanged.
    pub fn insert_landmark(
        &mut self,
        id: usize,
        mean: DVec2,
        cov: DMat2,
    ) -> Result<(), EstimationError> {
        if self.slot(id).is_some() {
            return Err(EstimationError::DuplicateLandmark { id });
        }
        if !mean.is_finite() {
            return Err(EstimationError::NonFinite);
        }
        check_cov2(cov)?;
        if self.ids.len() >= self.max_landmarks {
            return Err(EstimationError::TooManyLandmarks {
                max: self.max_landmarks,
            });
        }
        let n = self.state_len();
        let mut grown = Matrix::zeros(n + 2, n + 2);
        {
            let src = self.cov.as_slice();
            let dst = grown.as_mut_slice();
            for i in 0..n {
                dst[i * (n + 2)..i * (n + 2) + n].copy_from_slice(&src[i * n..(i + 1) * n]);
            }
        }
        grown[(n, n)] = cov.x_axis.x;
        grown[(n, n + 1)] = cov.y_axis.x;
        grown[(n + 1, n)] = cov.x_axis.y;
        grown[(n + 1, n + 1)] = cov.y_axis.y;
        self.cov = grown;
        self.mean.extend_from_slice(&[mean.x, mean.y]);
        self.ids.push(id);
        Ok(())
    }

    /// Folds in one observation: initialises landmark `z.id` on first sight,
    /// otherwise an `O(n²)` update. `r` is the measurement noise covariance.
    /// On error the filter is unchanged.
    pub fn observe(
        &mut self,
        z: &Observation,
        r: DMat2,
    ) -> Result<SlamObservation, EstimationError> {
        if !(z.z().is_finite() && r.is_finite()) {
            return Err(EstimationError::NonFinite);
        }
        match self.slot(z.id) {
            None => self.initialise(z, r),
            Some(j) => self.update(z, j, r),
        }
    }

    /// Folds in several observations in order; returns `(applied, rejected)`.
    pub fn observe_all(&mut self, observations: &[Observation], r: DMat2) -> (usize, usize) {
        let mut applied = 0;
        for z in observations {
            if self.observe(z, r).is_ok() {
                applied += 1;
            }
        }
        (applied, observations.len() - applied)
    }

    fn initialise(
        &mut self,
        z: &Observation,
        r: DMat2,
    ) -> Result<SlamObservation, EstimationError> {
        if self.ids.len() >= self.max_landmarks {
            return Err(EstimationError::TooManyLandmarks {
                max: self.max_landmarks,
            });
        }
        let x = self.pose();
        let (s, c) = crate::math::sin_cos(x.z + z.bearing_rad);
        let rng = z.range_m;
        let m = DVec2::new(x.x + rng * c, x.y + rng * s);
        // G_r rows and G_z.
        let gr = [[1.0, 0.0, -rng * s], [0.0, 1.0, rng * c]];
        let gz = DMat2::from_cols(DVec2::new(c, s), DVec2::new(-rng * s, rng * c));
        let n = self.state_len();
        // Cross-covariance rows G_r P_r,x for every existing column x.
        let mut cross = [vec![0.0; n], vec![0.0; n]];
        for (row, g) in cross.iter_mut().zip(&gr) {
            for (col, out) in row.iter_mut().enumerate() {
                *out = g[0] * self.cov[(0, col)]
                    + g[1] * self.cov[(1, col)]
                    + g[2] * self.cov[(2, col)];
            }
        }
        // P_mm = G_r P_rr G_rᵀ + G_z R G_zᵀ (G_r P_rr G_rᵀ = cross[:, 0..3] G_rᵀ).
        let mut pmm = [[0.0; 2]; 2];
        for (a, row) in cross.iter().enumerate() {
            for (b, g) in gr.iter().enumerate() {
                pmm[a][b] = row[0] * g[0] + row[1] * g[1] + row[2] * g[2];
            }
        }
        let gzr = gz * r * gz.transpose();
        let pmm = [
            [
                pmm[0][0] + gzr.x_axis.x,
                0.5 * (pmm[0][1] + pmm[1][0] + gzr.y_axis.x + gzr.x_axis.y),
            ],
            [0.0, pmm[1][1] + gzr.y_axis.y],
        ];
        if !(m.is_finite()
            && cross.iter().flatten().all(|v| v.is_finite())
            && pmm[0][0].is_finite()
            && pmm[0][1].is_finite()
            && pmm[1][1].is_finite())
        {
            return Err(EstimationError::NonFinite);
        }
        let mut grown = Matrix::zeros(n + 2, n + 2);
        {
            let src = self.cov.as_slice();
            let dst = grown.as_mut_slice();
            for i in 0..n {
                dst[i * (n + 2)..i * (n + 2) + n].copy_from_slice(&src[i * n..(i + 1) * n]);
            }
        }
        for (a, row) in cross.iter().enumerate() {
            for (col, &v) in row.iter().enumerate() {
                grown[(n + a, col)] = v;
                grown[(col, n + a)] = v;
            }
        }
        grown[(n, n)] = pmm[0][0];
        grown[(n, n + 1)] = pmm[0][1];
        grown[(n + 1, n)] = pmm[0][1];
        grown[(n + 1, n + 1)] = pmm[1][1];
        self.cov = grown;
        self.mean.extend_from_slice(&[m.x, m.y]);
        self.ids.push(z.id);
        Ok(SlamObservation::Initialised { id: z.id })
    }

    fn update(
        &mut self,
        z: &Observation,
        j: usize,
        r: DMat2,
    ) -> Result<SlamObservation, EstimationError> {
        let n = self.state_len();
        let x = self.pose();
        let m = DVec2::new(self.mean[j], self.mean[j + 1]);
        let d = m - x.truncate();
        let q = d.length_squared();
        let sq = q.sqrt();
        if sq.is_nan() || sq <= 1e-9 || !q.is_finite() {
            return Err(EstimationError::LandmarkTooClose { range_m: sq });
        }
        // The five non-zero columns of H and their entries (rows: range, bearing).
        let cols = [0, 1, 2, j, j + 1];
        let h = [
            [-d.x / sq, -d.y / sq, 0.0, d.x / sq, d.y / sq],
            [d.y / q, -d.x / q, -1.0, -d.y / q, d.x / q],
        ];
        let p = self.cov.as_slice();
        let [k0, k1, v0, v1] = &mut self.scratch;
        for col in [&mut *k0, &mut *k1, &mut *v0, &mut *v1] {
            col.clear();
            col.resize(n, 0.0);
        }
        // W = P Hᵀ (n × 2), held in (v0, v1) for now.
        for (i, (w0, w1)) in v0.iter_mut().zip(v1.iter_mut()).enumerate() {
            let row = &p[i * n..(i + 1) * n];
            for (c, &col) in cols.iter().enumerate() {
                *w0 += row[col] * h[0][c];
                *w1 += row[col] * h[1][c];
            }
        }
        // S = H W + R.
        let mut s = [[0.0; 2]; 2];
        for (c, &col) in cols.iter().enumerate() {
            for (s_row, h_row) in s.iter_mut().zip(&h) {
                s_row[0] += h_row[c] * v0[col];
                s_row[1] += h_row[c] * v1[col];
            }
        }
        let s00 = s[0][0] + r.x_axis.x;
        let s11 = s[1][1] + r.y_axis.y;
        let s01 = 0.5 * (s[0][1] + s[1][0] + r.y_axis.x + r.x_axis.y);
        let det = s00 * s11 - s01 * s01;
        if !(s00 > 0.0 && det > 0.0 && det.is_finite()) {
            return Err(EstimationError::SingularInnovation);
        }
        let (i00, i01, i11) = (s11 / det, -s01 / det, s00 / det);
        // K = W S⁻¹, then V = ½ K S − W in place of W.
        for i in 0..n {
            let (w0, w1) = (v0[i], v1[i]);
            let (g0, g1) = (w0 * i00 + w1 * i01, w0 * i01 + w1 * i11);
            k0[i] = g0;
            k1[i] = g1;
            v0[i] = 0.5 * (g0 * s00 + g1 * s01) - w0;
            v1[i] = 0.5 * (g0 * s01 + g1 * s11) - w1;
        }
        let zhat = DVec2::new(sq, wrap_angle(crate::math::atan2(d.y, d.x) - x.z));
        let nu = DVec2::new(z.range_m - zhat.x, wrap_angle(z.bearing_rad - zhat.y));
        let finite = |v: &Vec<f64>| v.iter().all(|x| x.is_finite());
        if !(finite(k0) && finite(k1) && finite(v0) && finite(v1)) {
            return Err(EstimationError::NonFinite);
        }
        // From here on the update cannot fail.
        for ((mi, g0), g1) in self.mean.iter_mut().zip(k0.iter()).zip(k1.iter()) {
            *mi += g0 * nu.x + g1 * nu.y;
        }
        self.mean[2] = wrap_angle(self.mean[2]);
        // Expanded Joseph form P − K Wᵀ − W Kᵀ + K S Kᵀ = P + K Vᵀ + V Kᵀ
        // (splitting K S Kᵀ = ½ K S Kᵀ + ½ K (K S)ᵀ), in one row-wise pass.
        // Entry (i, c) adds K_i·V_c + V_i·K_c and entry (c, i) the same two
        // products in swapped order, so P stays exactly symmetric.
        let p = self.cov.as_mut_slice();
        let (k0, k1, v0, v1) = (&k0[..n], &k1[..n], &v0[..n], &v1[..n]);
        for (i, row) in p.chunks_exact_mut(n).enumerate() {
            let (ki0, ki1, vi0, vi1) = (k0[i], k1[i], v0[i], v1[i]);
            let cols = v0.iter().zip(v1).zip(k0.iter().zip(k1));
            for (pic, ((vc0, vc1), (kc0, kc1))) in row.iter_mut().zip(cols) {
                *pic += (ki0 * vc0 + ki1 * vc1) + (vi0 * kc0 + vi1 * kc1);
            }
        }
        let nis = nu.x * (i00 * nu.x + i01 * nu.y) + nu.y * (i01 * nu.x + i11 * nu.y);
        Ok(SlamObservation::Updated {
            id: z.id,
            innovation: nu,
            nis,
        })
    }
}

fn symmetric3(a: DMat3) -> DMat3 {
    (a + a.transpose()) * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimation::models::{sample_motion, RangeBearingSensor, SensorNoise};
    use crate::rng::Lcg64;
    use std::f64::consts::PI;

    /// Dense reference: the textbook Joseph form with full `n × n` products.
    fn dense_update(
        mean: &[f64],
        cov: &Matrix,
        j: usize,
        z: DVec2,
        r: DMat2,
    ) -> (Vec<f64>, Matrix) {
        let n = mean.len();
        let (x, y, th) = (mean[0], mean[1], mean[2]);
        let (dx, dy) = (mean[j] - x, mean[j + 1] - y);
        let q = dx * dx + dy * dy;
        let sq = q.sqrt();
        let mut h = Matrix::zeros(2, n);
        for (c, (a, b)) in [
            (0, (-dx / sq, dy / q)),
            (1, (-dy / sq, -dx / q)),
            (2, (0.0, -1.0)),
            (j, (dx / sq, -dy / q)),
            (j + 1, (dy / sq, dx / q)),
        ] {
            h[(0, c)] = a;
            h[(1, c)] = b;
        }
        let rm =
            Matrix::from_rows(&[&[r.x_axis.x, r.y_axis.x], &[r.x_axis.y, r.y_axis.y]]).unwrap();
        let s = h
            .mul(cov)
            .unwrap()
            .mul(&h.transpose())
            .unwrap()
            .add(&rm)
            .unwrap();
        let k = cov
            .mul(&h.transpose())
            .unwrap()
            .mul(&s.inverse().unwrap())
            .unwrap();
        let nu = [z.x - sq, wrap_angle(z.y - wrap_angle(dy.atan2(dx) - th))];
        let mut new_mean = mean.to_vec();
        for (i, m) in new_mean.iter_mut().enumerate() {
            *m += k[(i, 0)] * nu[0] + k[(i, 1)] * nu[1];
        }
        new_mean[2] = wrap_angle(new_mean[2]);
        let ikh = Matrix::identity(n).sub(&k.mul(&h).unwrap()).unwrap();
        let joseph = ikh
            .mul(cov)
            .unwrap()
            .mul(&ikh.transpose())
            .unwrap()
            .add(&k.mul(&rm).unwrap().mul(&k.transpose()).unwrap())
            .unwrap();
        (new_mean, joseph)
    }

    fn random_filter(rng: &mut Lcg64, landmarks: usize) -> EkfSlam {
        let mut slam = EkfSlam::new(
            DVec3::new(0.1, -0.2, 0.3),
            DMat3::from_diagonal(DVec3::new(0.01, 0.02, 0.003)),
        );
        let r = SensorNoise::default().r();
        for id in 0..landmarks {
            let z = Observation {
                id: 10 + id,
                range_m: rng.range(1.0, 4.0),
                bearing_rad: rng.range(-PI, PI),
            };
            slam.observe(&z, r).unwrap();
            slam.predict(Control::new(0.5, 0.2), 0.1, &MotionNoise::default())
                .unwrap();
        }
        slam
    }

    /// The O(n²) update equals the dense n³ Joseph form to rounding.
    #[test]
    fn sparse_update_matches_the_dense_joseph_form() {
        let mut rng = Lcg64::new(5);
        let r = SensorNoise::default().r();
        for _ in 0..20 {
            let mut slam = random_filter(&mut rng, 6);
            let id = 10 + rng.int(0, 5) as usize;
            let j = slam.slot(id).unwrap();
            let (m, _) = slam.landmark(id).unwrap();
            let zhat = super::super::models::observation_model(slam.pose(), m);
            let z = DVec2::new(
                zhat.x + rng.normal(0.0, 0.1),
                wrap_angle(zhat.y + rng.normal(0.0, 0.03)),
            );
            let (ref_mean, ref_cov) = dense_update(slam.mean(), slam.cov(), j, z, r);
            let obs = Observation {
                id,
                range_m: z.x,
                bearing_rad: z.y,
            };
            assert!(matches!(
                slam.observe(&obs, r),
                Ok(SlamObservation::Updated { .. })
            ));
            for (a, b) in slam.mean().iter().zip(&ref_mean) {
                assert!((a - b).abs() < 1e-12, "{a} vs {b}");
            }
            let diff = slam.cov().sub(&ref_cov).unwrap().max_abs();
            assert!(diff < 1e-13, "{diff}");
            assert!(slam.cov().is_symmetric(0.0));
        }
    }

    /// Initialisation by hand: pose (1, 2, π/2) with P_rr = diag(0.01, 0.02,
    /// 0.03), landmark seen at r = 2, φ = −π/2 → m = (3, 2).
    #[test]
    fn initialisation_matches_hand_computed_augmentation() {
        let mut slam = EkfSlam::new(
            DVec3::new(1.0, 2.0, PI / 2.0),
            DMat3::from_diagonal(DVec3::new(0.01, 0.02, 0.03)),
        );
        let r = DMat2::from_diagonal(DVec2::new(0.04, 0.0025));
        let z = Observation {
            id: 4,
            range_m: 2.0,
            bearing_rad: -PI / 2.0,
        };
        assert_eq!(
            slam.observe(&z, r),
            Ok(SlamObservation::Initialised { id: 4 })
        );
        let (m, pm) = slam.landmark(4).unwrap();
        assert!((m - DVec2::new(3.0, 2.0)).length() < 1e-12);
        // θ + φ = 0: G_r = [1 0 0; 0 1 2], G_z = [1 0; 0 2].
        // P_mm = diag(0.01, 0.02 + 4·0.03) + diag(0.04, 4·0.0025).
        assert!((pm.x_axis.x - 0.05).abs() < 1e-15);
        assert!((pm.y_axis.y - (0.14 + 0.01)).abs() < 1e-15);
        assert!(pm.x_axis.y.abs() < 1e-15);
        // Cross-covariance with the pose: G_r P_rr = [0.01 0 0; 0 0.02 0.06].
        let c = slam.cov();
        assert!((c[(3, 0)] - 0.01).abs() < 1e-15 && (c[(4, 1)] - 0.02).abs() < 1e-15);
        assert!((c[(4, 2)] - 0.06).abs() < 1e-15 && c[(3, 2)].abs() < 1e-15);
        assert!(c.is_symmetric(0.0));
        // A second landmark correlates with the first through the pose.
        let z2 = Observation {
            id: 9,
            range_m: 1.0,
            bearing_rad: 0.0,
        };
        slam.observe(&z2, r).unwrap();
        assert_eq!(slam.state_len(), 7);
        assert!(slam.cov()[(5, 3)].abs() > 0.0 || slam.cov()[(6, 4)].abs() > 0.0);
        assert_eq!(slam.landmark_ids(), &[4, 9]);
    }

    #[test]
    fn refuses_bad_input_and_respects_the_landmark_cap() {
        let mut slam = EkfSlam::new(DVec3::ZERO, DMat3::from_diagonal(DVec3::splat(0.01)));
        slam.max_landmarks = 1;
        let r = SensorNoise::default().r();
        let z = Observation {
            id: 0,
            range_m: 1.0,
            bearing_rad: 0.0,
        };
        slam.observe(&z, r).unwrap();
        assert_eq!(
            slam.observe(&Observation { id: 1, ..z }, r),
            Err(EstimationError::TooManyLandmarks { max: 1 })
        );
        let before = slam.clone();
        assert_eq!(
            slam.observe(
                &Observation {
                    range_m: f64::NAN,
                    ..z
                },
                r
            ),
            Err(EstimationError::NonFinite)
        );
        assert!(matches!(
            slam.predict(Control::new(1.0, 0.0), -0.1, &MotionNoise::default()),
            Err(EstimationError::InvalidDt { .. })
        ));
        assert!(matches!(
            slam.predict(Control::new(f64::NAN, 0.0), 0.1, &MotionNoise::default()),
            Err(EstimationError::NonFinite)
        ));
        assert_eq!(slam, before);
        // Drive onto the landmark: the update is refused, the filter kept.
        slam.predict(Control::new(1.0, 0.0), 1.0, &MotionNoise::default())
            .unwrap();
        let before = slam.clone();
        assert!(matches!(
            slam.observe(&z, r),
            Err(EstimationError::LandmarkTooClose { .. })
        ));
        assert_eq!(slam, before);
        assert_eq!(slam.observe_all(&[z, z], r), (0, 2));
    }

    /// A robot circling among 12 unknown landmarks: every landmark is
    /// initialised, estimates converge (final error well under the first-sight
    /// error, within 3σ), landmark uncertainty shrinks monotonically while
    /// observed, and P stays symmetric positive-definite (Cholesky succeeds).
    #[test]
    fn landmark_estimates_converge() {
        let truth_map: Vec<DVec2> = (0..12)
            .map(|i| {
                let a = i as f64 * PI / 6.0;
                let rad = if i % 2 == 0 { 3.0 } else { 4.5 };
                DVec2::new(rad * a.cos(), rad * a.sin())
            })
            .collect();
        let sensor = RangeBearingSensor {
            max_range_m: 3.5,
            fov_rad: PI,
            noise: SensorNoise::default(),
        };
        let noise = MotionNoise {
            sigma_v_mps: 0.05,
            sigma_omega_radps: 0.02,
        };
        let mut rng = Lcg64::new(99);
        let start = DVec3::new(3.75, 0.0, PI / 2.0);
        let mut truth = start;
        let mut slam = EkfSlam::new(start, DMat3::from_diagonal(DVec3::splat(1e-6)));
        let r = sensor.noise.r();
        let u = Control::new(0.75, 0.2);
        let mut first_error = [f64::NAN; 12];
        let mut last_var = [f64::INFINITY; 12];
        for _ in 0..2000 {
            truth = sample_motion(truth, u, 0.05, &noise, &mut rng).0;
            slam.predict(u, 0.05, &noise).unwrap();
            for z in sensor.observe(truth, &truth_map, &mut rng) {
                slam.observe(&z, r).unwrap();
                let (m, pm) = slam.landmark(z.id).unwrap();
                if first_error[z.id].is_nan() {
                    first_error[z.id] = (m - truth_map[z.id]).length();
                }
                let var = pm.x_axis.x + pm.y_axis.y;
                assert!(
                    var <= last_var[z.id] * (1.0 + 1e-9),
                    "landmark {} variance grew on update",
                    z.id
                );
                last_var[z.id] = var;
            }
        }
        assert_eq!(slam.landmark_count(), 12);
        let mut sum_first = 0.0;
        let mut sum_final = 0.0;
        for (id, truth_m) in truth_map.iter().enumerate() {
            let (m, pm) = slam.landmark(id).unwrap();
            let err = m - *truth_m;
            // Inside its own covariance's 99.9 % region (χ²₂ bound 13.8).
            let d2 = err.dot(pm.inverse() * err);
            assert!(d2 < 13.8, "landmark {id}: {d2}");
            sum_first += first_error[id];
            sum_final += err.length();
        }
        assert!(
            sum_final < 0.5 * sum_first,
            "first {sum_first}, final {sum_final}"
        );
        assert!(
            sum_final / 12.0 < 0.15,
            "mean final error {}",
            sum_final / 12.0
        );
        assert!(slam.cov().cholesky(0.0).is_ok());
    }

    /// Issue 15: a prepared map. A landmark inserted with zero covariance is
    /// a known landmark: an EKF-SLAM update from it equals the localisation
    /// update, and the landmark stays where it was put.
    #[test]
    fn a_known_landmark_from_a_prepared_map_updates_like_localisation() {
        use crate::estimation::ekf::ekf_update;
        let pose = DVec3::new(0.5, -0.2, 0.4);
        let pose_cov = DMat3::from_cols(
            DVec3::new(0.02, 0.004, 0.001),
            DVec3::new(0.004, 0.03, -0.002),
            DVec3::new(0.001, -0.002, 0.01),
        );
        let m = DVec2::new(3.0, 1.5);
        let mut slam = EkfSlam::with_map(pose, pose_cov, &[(4, m, DMat2::ZERO)]).unwrap();
        assert_eq!(slam.landmark_ids(), &[4]);
        assert_eq!(slam.landmark(4), Some((m, DMat2::ZERO)));
        let z = Observation {
            id: 4,
            range_m: 2.9,
            bearing_rad: 0.05,
        };
        let r = SensorNoise::default().r();
        let out = slam.observe(&z, r).unwrap();
        assert!(matches!(out, SlamObservation::Updated { id: 4, .. }));
        let loc = ekf_update(pose, pose_cov, &z, m, r).unwrap().belief;
        assert!((slam.pose() - loc.mean).length() < 1e-12);
        let pc = slam.pose_cov();
        for j in 0..3 {
            for i in 0..3 {
                assert!(
                    (pc.col(j)[i] - loc.cov.col(j)[i]).abs() < 1e-12,
                    "P[{i}][{j}]"
                );
            }
        }
        let (m_after, m_cov) = slam.landmark(4).unwrap();
        assert!((m_after - m).length() < 1e-12);
        assert!(m_cov.x_axis.length() + m_cov.y_axis.length() < 1e-12);

        // An uncertain prior is inserted as given, uncorrelated with the rest.
        let prior = DMat2::from_cols(DVec2::new(0.05, 0.01), DVec2::new(0.01, 0.04));
        slam.insert_landmark(9, DVec2::new(-1.0, 2.0), prior)
            .unwrap();
        assert_eq!(slam.landmark(9), Some((DVec2::new(-1.0, 2.0), prior)));
        let n = slam.state_len();
        assert_eq!(n, 7);
        for col in 0..5 {
            assert_eq!(slam.cov()[(5, col)], 0.0);
            assert_eq!(slam.cov()[(col, 6)], 0.0);
        }
        // Refused inserts change nothing.
        let before = slam.clone();
        let asym = DMat2::from_cols(DVec2::new(0.05, 0.02), DVec2::new(0.0, 0.04));
        let neg = DMat2::from_diagonal(DVec2::new(0.05, -0.01));
        assert_eq!(
            slam.insert_landmark(4, DVec2::ZERO, prior),
            Err(EstimationError::DuplicateLandmark { id: 4 })
        );
        assert_eq!(
            slam.insert_landmark(5, DVec2::NAN, prior),
            Err(EstimationError::NonFinite)
        );
        assert_eq!(
            slam.insert_landmark(5, DVec2::ZERO, asym),
            Err(EstimationError::NotCovariance)
        );
        assert_eq!(
            slam.insert_landmark(5, DVec2::ZERO, neg),
            Err(EstimationError::NotCovariance)
        );
        slam.max_landmarks = 2;
        assert_eq!(
            slam.insert_landmark(5, DVec2::ZERO, prior),
            Err(EstimationError::TooManyLandmarks { max: 2 })
        );
        slam.max_landmarks = before.max_landmarks;
        assert_eq!(slam, before);
        assert!(EkfSlam::with_map(pose, pose_cov, &[(1, m, prior), (1, m, prior)]).is_err());
    }

    /// Issue 15: SLAM prediction with a state-space `Q` moves the pose block
    /// exactly as localisation does and the pose–landmark block as `F P_rm`.
    #[test]
    fn slam_predict_with_a_state_space_q_matches_localisation_and_f_p_rm() {
        use crate::estimation::ekf::ekf_predict_with_q;
        let pose = DVec3::new(0.0, 0.0, 0.7);
        let pose_cov = DMat3::from_diagonal(DVec3::new(0.01, 0.02, 0.003));
        let prior = DMat2::from_diagonal(DVec2::new(0.04, 0.04));
        let mut slam =
            EkfSlam::with_map(pose, pose_cov, &[(0, DVec2::new(2.0, 2.0), prior)]).unwrap();
        // One update correlates the pose with the landmark.
        slam.observe(
            &Observation {
                id: 0,
                range_m: 2.8,
                bearing_rad: 0.1,
            },
            SensorNoise::default().r(),
        )
        .unwrap();
        let (p_rr, p_rm) = (
            slam.pose_cov(),
            [[0, 3], [0, 4], [1, 3], [1, 4], [2, 3], [2, 4]],
        );
        let cross = |s: &EkfSlam, i: usize, j: usize| s.cov()[(i, j)];
        assert!(cross(&slam, 0, 3).abs() > 1e-6);
        let before = slam.clone();
        let (u, dt) = (Control::new(0.6, -0.3), 0.2);
        let q = DMat3::from_cols(
            DVec3::new(1e-4, 2e-5, 0.0),
            DVec3::new(2e-5, 3e-4, 1e-5),
            DVec3::new(0.0, 1e-5, 5e-5),
        );
        slam.predict_with_q(u, dt, q).unwrap();
        let loc = ekf_predict_with_q(before.pose(), p_rr, u, dt, q).unwrap();
        assert!((slam.pose() - loc.mean).length() < 1e-15);
        assert!(slam.pose_cov().abs_diff_eq(loc.cov, 1e-15));
        let th = before.pose().z;
        let (a, b) = (-0.6 * th.sin() * dt, 0.6 * th.cos() * dt);
        for [i, j] in p_rm {
            let hand = match i {
                0 => cross(&before, 0, j) + a * cross(&before, 2, j),
                1 => cross(&before, 1, j) + b * cross(&before, 2, j),
                _ => cross(&before, 2, j),
            };
            assert!((cross(&slam, i, j) - hand).abs() < 1e-15, "P[{i}][{j}]");
            assert_eq!(cross(&slam, i, j), cross(&slam, j, i));
        }
        // The landmark block is untouched; a bad Q changes nothing.
        assert_eq!(slam.landmark(0), before.landmark(0));
        let after = slam.clone();
        let bad = DMat3::from_diagonal(DVec3::new(1e-4, -1e-4, 1e-4));
        assert_eq!(
            slam.predict_with_q(u, dt, bad),
            Err(EstimationError::NotCovariance)
        );
        assert_eq!(slam, after);
    }
}
