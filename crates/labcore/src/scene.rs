//! A display list: what to draw this frame, in world coordinates (metres, y up).
//!
//! Colours are semantic [`Role`]s; the style table ([`style`]) maps each
//! role to a theme colour (light/dark, colour-blind safe) that every
//! renderer shares, so an experiment never names a colour.

use core::f64::consts::TAU;
use glam::DVec2;

mod layer;
pub mod style;
pub mod wheeled;
pub use layer::{raster_version, LayerMark, LayerOp, LayerPlan, Rewrite, Segment, SegmentLayer};
pub use style::Role;

/// The world rectangle shown on the canvas (y points up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewBox {
    pub min: DVec2,
    pub max: DVec2,
}

impl ViewBox {
    /// A square view centred on the origin that frames an arm of reach
    /// `reach_m`: the reach fills the canvas with a 15 % margin for targets
    /// just outside it.
    #[must_use]
    pub fn framing(reach_m: f64) -> Self {
        let reach = if reach_m.is_finite() { reach_m } else { 1.0 };
        Self::centered((reach * 1.15).max(0.5))
    }

    /// A square view centred on the origin with half-width `half_m`.
    #[must_use]
    pub fn centered(half_m: f64) -> Self {
        Self {
            min: DVec2::splat(-half_m),
            max: DVec2::splat(half_m),
        }
    }
}

/// One item of the display list.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// A straight segment; `width_px` is in CSS pixels.
    Line {
        from: DVec2,
        to: DVec2,
        width_px: f64,
        role: Role,
        dashed: bool,
    },
    /// A circle of world radius; filled or stroked.
    Circle {
        center: DVec2,
        radius_m: f64,
        role: Role,
        fill: bool,
        dashed: bool,
    },
    /// A dot of fixed screen size (joints, tips, targets).
    Dot {
        center: DVec2,
        radius_px: f64,
        role: Role,
    },
    /// Many small dots of one role (a sample cloud).
    Points {
        points: Vec<DVec2>,
        radius_px: f64,
        role: Role,
    },
    /// A grid of densities in `[0, 1]` drawn as translucent cells.
    Heatmap {
        min: DVec2,
        cell_m: f64,
        cols: usize,
        rows: usize,
        values: Vec<f32>,
        role: Role,
    },
    /// An ellipse with centre and two semi-axis vectors (world units).
    Ellipse {
        center: DVec2,
        semi_axis_a: DVec2,
        semi_axis_b: DVec2,
        role: Role,
    },
    /// A text label anchored at a world point, offset in CSS pixels.
    Label {
        pos: DVec2,
        text: String,
        role: Role,
        offset_px: DVec2,
    },
    /// An open or closed line through points (a trajectory, a trail).
    Polyline {
        points: Vec<DVec2>,
        width_px: f64,
        role: Role,
        dashed: bool,
        closed: bool,
    },
    /// A filled polygon with an outline (an obstacle, a cart body).
    Polygon { points: Vec<DVec2>, role: Role },
    /// An axis-aligned rectangle, filled with an outline or only stroked.
    Rect {
        min: DVec2,
        max: DVec2,
        role: Role,
        fill: bool,
    },
    /// An arrow from `from` to `to` (a force, a velocity); the head is sized
    /// in CSS pixels so short arrows stay readable.
    Arrow {
        from: DVec2,
        to: DVec2,
        width_px: f64,
        role: Role,
    },
    /// Many arrows of one role drawn as one path (a vector field).
    Arrows {
        arrows: Vec<(DVec2, DVec2)>,
        width_px: f64,
        role: Role,
    },
    /// Many segments of one role drawn as one path (a tree of 100,000 edges).
    Segments {
        segments: Vec<(DVec2, DVec2)>,
        width_px: f64,
        role: Role,
    },
    /// A metre scale bar the page draws in a lower corner of the canvas,
    /// with a round length that fits the current zoom (for scenes whose grid
    /// carries no numbers).
    ScaleBar,
    /// The page marks the canvas edge in the direction of `at` while `at` is
    /// outside the view (a robot or cart that drove off), with `label`.
    OffView {
        at: DVec2,
        label: String,
        role: Role,
    },
    /// The keyboard's chosen handle (see [`crate::experiment::Handle`]): a
    /// ring of `radius_px` CSS pixels around it in the page's focus colour,
    /// with a halo that keeps it visible on any background. The page adds it
    /// after the experiment's scene.
    FocusRing { center: DVec2, radius_px: f64 },
    /// A grid of cells painted as one image: cell `(col, row)` has state
    /// `cells[row * cols + col]`, row 0 at `min.y`; state `s > 0` takes the
    /// colour of `palette[s - 1]` and 0 is transparent (an occupancy grid with
    /// per-cell search states).
    Raster {
        min: DVec2,
        cell_m: f64,
        cols: usize,
        rows: usize,
        cells: Vec<u8>,
        palette: Vec<RasterColour>,
    },
    /// A batch of segments the experiment keeps across frames (a growing
    /// tree): drawn like [`Item::Segments`], but the page keeps the picture
    /// and draws only what changed since its last frame (see [`SegmentLayer`]).
    SegmentLayer {
        layer: SegmentLayer,
        width_px: f64,
        role: Role,
    },
    /// An [`Item::Raster`] the page keeps between frames: `id` names it among
    /// the page's kept rasters (an experiment uses a constant) and `version`
    /// changes whenever `cells` change (for example [`raster_version`] of the
    /// cells); the page rebuilds and uploads the image only when the version,
    /// the size or the colours change.
    VersionedRaster {
        id: u64,
        version: u64,
        min: DVec2,
        cell_m: f64,
        cols: usize,
        rows: usize,
        cells: Vec<u8>,
        palette: Vec<RasterColour>,
    },
}

/// The colour of one raster state: a role and an opacity in `[0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterColour {
    pub role: Role,
    pub alpha: f32,
}

/// The display list of one frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    pub items: Vec<Item>,
    /// How many of the first items are the scene's backdrop: what a run
    /// does not move (a field, its obstacles, a quiver of forces). The page
    /// keeps their picture while [`Scene::backdrop_key`] stays the same and
    /// paints only the items after them; 0 keeps nothing. Set by
    /// [`Scene::end_backdrop`].
    pub backdrop: usize,
    /// A fingerprint of what the backdrop's items are made from
    /// ([`BackdropKey`]): equal keys mean equal items, which each experiment
    /// that marks a backdrop asserts in a test.
    pub backdrop_key: u64,
    /// The parts of the scene that live quantities name, drawn as a halo
    /// only while a symbol marked with that key is hovered or focused
    /// (issue 27 §3).
    pub tags: Vec<Tag>,
}

/// What a live quantity names in the scene: a link, an angle's arc, the
/// goal. The page draws it as a halo (a wide translucent band under a dashed
/// line, or a dashed ring around a point) while a symbol marked
/// `\\live{key}{…}` is hovered or focused.
#[derive(Clone, Debug, PartialEq)]
pub struct Tag {
    /// The quantity's key ([`crate::live_math::Quantity::key`]).
    pub key: &'static str,
    /// One point (a ring around it) or a path through the points (world, m).
    pub points: Vec<DVec2>,
}

/// Builds a [`Scene::backdrop_key`]: a 64-bit FNV-1a fingerprint of the bits
/// of the numbers a backdrop is drawn from. Comparing a key costs nothing
/// and needs no copy of the items (which would add their comparison and
/// cloning code to every page's module).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BackdropKey(u64);

impl Default for BackdropKey {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl BackdropKey {
    /// Mixes in one number (its exact bits: 0.0 and -0.0 differ).
    #[must_use]
    pub fn num(self, v: f64) -> Self {
        const PRIME: u64 = 0x0000_0100_0000_01b3;
        let mut h = self.0;
        for b in v.to_bits().to_le_bytes() {
            h = (h ^ u64::from(b)).wrapping_mul(PRIME);
        }
        Self(h)
    }

    /// Mixes in a point's coordinates.
    #[must_use]
    pub fn point(self, p: DVec2) -> Self {
        self.num(p.x).num(p.y)
    }

    #[must_use]
    pub fn finish(self) -> u64 {
        self.0
    }
}

impl Scene {
    /// Empties the list, keeping its allocation.
    pub fn clear(&mut self) {
        self.items.clear();
        self.backdrop = 0;
        self.backdrop_key = 0;
        self.tags.clear();
    }

    /// Tags what quantity `key` names: one point, or a path (see [`Tag`]).
    pub fn tag(&mut self, key: &'static str, points: Vec<DVec2>) {
        self.tags.push(Tag { key, points });
    }

    /// Tags a planar arm's parts with the quantities that name them: link
    /// `i` with `l<i>`, joint angle `i` with `t<i>`, an arc from the previous
    /// link's direction (the x axis for the first) to its own, at 0.45 of
    /// the link's length (three links at most).
    pub fn tag_arm(&mut self, joints: &[DVec2], angles_rad: &[f64]) {
        const LINKS: [&str; 3] = ["l1", "l2", "l3"];
        const ANGLES: [&str; 3] = ["t1", "t2", "t3"];
        let mut heading = 0.0;
        for (i, (w, a)) in joints.windows(2).zip(angles_rad).enumerate().take(3) {
            self.tag(LINKS[i], w.to_vec());
            let radius = 0.45 * (w[1] - w[0]).length();
            self.tag_arc(ANGLES[i], w[0], radius, heading, heading + a);
            heading += a;
        }
    }

    /// Tags an angle: an arc of `radius_m` around `center` from direction
    /// `from_rad` to `to_rad` (radians from +x, counter-clockwise).
    pub fn tag_arc(
        &mut self,
        key: &'static str,
        center: DVec2,
        radius_m: f64,
        from_rad: f64,
        to_rad: f64,
    ) {
        self.tag_curve(
            key,
            center,
            DVec2::new(radius_m, 0.0),
            DVec2::new(0.0, radius_m),
            from_rad,
            to_rad,
        );
    }

    /// Tags a whole ellipse around `center` with semi-axis vectors
    /// `semi_axis_a` and `semi_axis_b` (m; a circle of radius r has
    /// `(r, 0)` and `(0, r)`), as a closed path of 33 points.
    pub fn tag_ellipse(
        &mut self,
        key: &'static str,
        center: DVec2,
        semi_axis_a: DVec2,
        semi_axis_b: DVec2,
    ) {
        self.tag_curve(key, center, semi_axis_a, semi_axis_b, 0.0, TAU);
    }

    /// Tags a circle of `radius_m` around `center` (a radius, a reach).
    pub fn tag_circle(&mut self, key: &'static str, center: DVec2, radius_m: f64) {
        self.tag_arc(key, center, radius_m, 0.0, TAU);
    }

    /// `center + a cos t + b sin t` for `t` from `from_rad` to `to_rad`:
    /// an arc of an ellipse, 33 points (an arc of 16 segments was as fine
    /// for a joint angle; a whole ellipse wants more).
    fn tag_curve(
        &mut self,
        key: &'static str,
        center: DVec2,
        a: DVec2,
        b: DVec2,
        from_rad: f64,
        to_rad: f64,
    ) {
        // A plain loop: an iterator's collect costs every page's module
        // several hundred bytes of adapters.
        let mut points = Vec::with_capacity(33);
        for i in 0..33u32 {
            let t = from_rad + (to_rad - from_rad) * f64::from(i) / 32.0;
            points.push(center + a * libm::cos(t) + b * libm::sin(t));
        }
        self.tag(key, points);
    }

    /// Tags several quantities at once, each `(key, from, to)`: a ring
    /// around `from` when `to` is the same point, else the line between.
    /// One loop for every experiment's points and lines keeps each page's
    /// module small.
    pub fn tag_lines(&mut self, tags: &[(&'static str, DVec2, DVec2)]) {
        for &(key, from, to) in tags {
            let mut points = Vec::with_capacity(2);
            points.push(from);
            if to != from {
                points.push(to);
            }
            self.tag(key, points);
        }
    }

    /// Marks the items pushed so far as the backdrop, made from what `key`
    /// fingerprints (see [`Scene::backdrop`]). Only a hint for the painter:
    /// the picture is the same either way.
    pub fn end_backdrop(&mut self, key: u64) {
        self.backdrop = self.items.len();
        self.backdrop_key = key;
    }

    pub fn push(&mut self, item: Item) {
        self.items.push(item);
    }

    /// Draws a serial chain: links between consecutive points, joints, base and tip.
    pub fn chain(&mut self, joints: &[DVec2], role: Role) {
        for w in joints.windows(2) {
            self.items.push(Item::Line {
                from: w[0],
                to: w[1],
                width_px: if role == Role::Ghost { 4.0 } else { 7.0 },
                role,
                // The ghost differs by dash, not only by colour.
                dashed: role == Role::Ghost,
            });
        }
        if role == Role::Ghost {
            return;
        }
        if let Some((first, rest)) = joints.split_first() {
            self.items.push(Item::Dot {
                center: *first,
                radius_px: 9.0,
                role: Role::Base,
            });
            if let Some((tip, middle)) = rest.split_last() {
                for j in middle {
                    self.items.push(Item::Dot {
                        center: *j,
                        radius_px: 6.0,
                        role: Role::Joint,
                    });
                }
                self.items.push(Item::Dot {
                    center: *tip,
                    radius_px: 8.0,
                    role: Role::Tip,
                });
            }
        }
    }

    /// A dashed circle centred on the origin (reach bounds); skipped when `radius_m` ≤ 0.
    pub fn bound_circle(&mut self, radius_m: f64) {
        if radius_m > 1e-9 {
            self.items.push(Item::Circle {
                center: DVec2::ZERO,
                radius_m,
                role: Role::Bound,
                fill: false,
                dashed: true,
            });
        }
    }

    /// Axes through the origin across the view.
    pub fn axes(&mut self, view: ViewBox) {
        self.items.push(Item::Line {
            from: DVec2::new(view.min.x, 0.0),
            to: DVec2::new(view.max.x, 0.0),
            width_px: 1.0,
            role: Role::Grid,
            dashed: false,
        });
        self.items.push(Item::Line {
            from: DVec2::new(0.0, view.min.y),
            to: DVec2::new(0.0, view.max.y),
            width_px: 1.0,
            role: Role::Grid,
            dashed: false,
        });
    }

    /// True when every coordinate in the list is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        let ok = |p: &DVec2| p.is_finite();
        self.items.iter().all(|item| match item {
            Item::Line { from, to, .. } => ok(from) && ok(to),
            Item::Circle {
                center, radius_m, ..
            } => ok(center) && radius_m.is_finite(),
            Item::Dot { center, .. } => ok(center),
            Item::Points { points, .. } => points.iter().all(ok),
            Item::Heatmap { min, cell_m, .. } => ok(min) && cell_m.is_finite(),
            Item::Ellipse {
                center,
                semi_axis_a,
                semi_axis_b,
                ..
            } => ok(center) && ok(semi_axis_a) && ok(semi_axis_b),
            Item::Label { pos, .. } => ok(pos),
            Item::ScaleBar => true,
            Item::OffView { at, .. } => ok(at),
            Item::FocusRing { center, radius_px } => ok(center) && radius_px.is_finite(),
            Item::Polyline { points, .. } | Item::Polygon { points, .. } => points.iter().all(ok),
            Item::Rect { min, max, .. } => ok(min) && ok(max),
            Item::Arrow { from, to, .. } => ok(from) && ok(to),
            Item::Arrows { arrows: pairs, .. }
            | Item::Segments {
                segments: pairs, ..
            } => pairs.iter().all(|(a, b)| ok(a) && ok(b)),
            Item::SegmentLayer { layer, .. } => {
                layer.segments().iter().all(|(a, b)| ok(a) && ok(b))
            }
            Item::Raster {
                min,
                cell_m,
                cols,
                rows,
                cells,
                ..
            }
            | Item::VersionedRaster {
                min,
                cell_m,
                cols,
                rows,
                cells,
                ..
            } => ok(min) && cell_m.is_finite() && cells.len() >= cols * rows,
        })
    }
}
