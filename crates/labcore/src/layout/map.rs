//! World (metres, y up) to pixels (y down): the one map the canvas, the
//! report's figure and the thumbnails draw a scene with.

use crate::scene::ViewBox;
use glam::DVec2;

/// A uniform-scale map from world metres (y up) to pixels (y down): the
/// world point `center_world` lands on the pixel `center_px`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldMap {
    /// Pixels per metre, the same along x and y.
    pub scale_px_per_m: f64,
    /// The world point at the picture's centre, metres.
    pub center_world: DVec2,
    /// The picture's centre, pixels.
    pub center_px: DVec2,
}

impl WorldMap {
    /// Fits `view` into a `width_px` × `height_px` picture at one scale for
    /// both axes, centred (the spare length of the longer side is split
    /// evenly). A degenerate view (zero, negative or not finite) still gives
    /// a finite, positive scale.
    #[must_use]
    pub fn fit(view: ViewBox, width_px: f64, height_px: f64) -> Self {
        let size = (view.max - view.min).max(DVec2::splat(1e-9));
        let scale = (width_px / size.x).min(height_px / size.y).max(1e-9);
        Self {
            scale_px_per_m: scale,
            center_world: (view.min + view.max) * 0.5,
            center_px: DVec2::new(width_px, height_px) * 0.5,
        }
    }

    /// The pixel of world point `p` (metres).
    #[must_use]
    pub fn to_px(&self, p: DVec2) -> DVec2 {
        let d = (p - self.center_world) * self.scale_px_per_m;
        DVec2::new(self.center_px.x + d.x, self.center_px.y - d.y)
    }

    /// The world point (metres) under pixel `px`: the inverse of [`Self::to_px`].
    #[must_use]
    pub fn to_world(&self, px: DVec2) -> DVec2 {
        let d = px - self.center_px;
        self.center_world + DVec2::new(d.x, -d.y) / self.scale_px_per_m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view(min: (f64, f64), max: (f64, f64)) -> ViewBox {
        ViewBox {
            min: DVec2::new(min.0, min.1),
            max: DVec2::new(max.0, max.1),
        }
    }

    #[test]
    fn a_view_fits_at_one_scale_centred_with_y_up() {
        // World (0, 0)–(2, 1) into 400 × 300: x limits (200 px/m), the
        // 200 px tall picture of the world sits 50 px below the top.
        let m = WorldMap::fit(view((0.0, 0.0), (2.0, 1.0)), 400.0, 300.0);
        assert_eq!(m.scale_px_per_m, 200.0);
        assert_eq!(m.to_px(DVec2::new(0.0, 0.0)), DVec2::new(0.0, 250.0));
        assert_eq!(m.to_px(DVec2::new(2.0, 1.0)), DVec2::new(400.0, 50.0));
        assert_eq!(m.to_px(DVec2::new(1.0, 0.5)), DVec2::new(200.0, 150.0));
        // World −1…1 square into 100 × 400: x limits (50 px/m).
        let m = WorldMap::fit(view((-1.0, -1.0), (1.0, 1.0)), 100.0, 400.0);
        assert_eq!(m.to_px(DVec2::new(-1.0, 1.0)), DVec2::new(0.0, 150.0));
    }

    #[test]
    fn to_world_undoes_to_px() {
        let m = WorldMap::fit(view((-3.0, 2.0), (5.0, 7.5)), 640.0, 480.0);
        for p in [(-3.0, 2.0), (0.25, 4.0), (5.0, 7.5), (100.0, -40.0)] {
            let p = DVec2::new(p.0, p.1);
            assert!((m.to_world(m.to_px(p)) - p).length() < 1e-12, "{p}");
        }
    }

    #[test]
    fn a_degenerate_view_has_a_finite_positive_scale() {
        for v in [
            view((1.0, 1.0), (1.0, 1.0)),
            view((2.0, 0.0), (0.0, 1.0)),
            view((0.0, 0.0), (f64::NAN, 1.0)),
        ] {
            let s = WorldMap::fit(v, 300.0, 200.0).scale_px_per_m;
            assert!(s.is_finite() && s > 0.0, "{v:?}: {s}");
        }
    }
}
