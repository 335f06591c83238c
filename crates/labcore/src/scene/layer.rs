//! Persistent layers: the parts of a display list the page may keep between
//! frames instead of drawing them again.
//!
//! A scene is rebuilt from state every frame, which is right for a robot, a
//! path or a label, and wasteful for a tree of 100,000 edges that gains a
//! hundred edges a frame. A [`SegmentLayer`] is such a batch kept by the
//! experiment across frames: a list of *slots*, each holding one segment,
//! that grows by [`SegmentLayer::push`], changes a slot by
//! [`SegmentLayer::set`] (an RRT* rewire) and starts over by
//! [`SegmentLayer::clear`] (a new run). Every change is written to a journal,
//! so a painter that remembers where it stopped (a [`LayerMark`]) can ask
//! [`SegmentLayer::plan`] for exactly the work that brings its picture up to
//! date: erase the old version of each rewritten slot it had drawn, draw the
//! new version, draw the appended slots. A painter that counts, for every
//! pixel, how many drawn segments cover it (pixel lit while the count is
//! positive) ends with the same counts, hence the same picture, as a painter
//! that draws the whole list from scratch; the property tests below replay
//! random grow/rewire/clear sequences against that full list.
//!
//! Identity: every layer has an `id`, and cloning the layer's data gives the
//! clone a fresh id. The list is shared copy-on-write ([`Arc`]), so putting a
//! layer in a [`super::Scene`] costs a pointer copy, and a model that changes
//! a layer a scene still holds gets its own copy with a new identity (the
//! painter then redraws it in full; never a wrong picture). The `epoch` counts
//! [`SegmentLayer::clear`]s. Two layers compare equal when their segments are
//! equal: a scene's equality is about the picture, not the cache.
//!
//! For rasters (grids of cells) the equivalent is simpler: a
//! [`super::Item::VersionedRaster`] carries a `version` that changes exactly
//! when its cells change; [`raster_version`] computes one from the cells.

use glam::DVec2;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// One segment of a layer, world coordinates.
pub type Segment = (DVec2, DVec2);

/// A journal keeps at least this many of its latest rewrites, or half the
/// layer's length if more (a painter further behind than half the layer
/// redraws in full anyway, see [`SegmentLayer::plan`]); it drops its oldest
/// entries when it holds twice that.
const JOURNAL_MIN_KEPT: usize = 4096;

static NEXT_LAYER_ID: AtomicU64 = AtomicU64::new(1);

fn fresh_id() -> u64 {
    NEXT_LAYER_ID.fetch_add(1, Ordering::Relaxed)
}

/// One slot rewritten after it was added: `slot` held `old`, now `new`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rewrite {
    pub slot: u32,
    pub old: Segment,
    pub new: Segment,
}

#[derive(Debug)]
struct LayerData {
    id: u64,
    epoch: u64,
    segments: Vec<Segment>,
    /// Rewrites in order; `journal[k]` is rewrite number `journal_start + k`.
    journal: Vec<Rewrite>,
    journal_start: u64,
}

impl Clone for LayerData {
    /// A copy is a different layer: it gets its own identity, so a painter
    /// that drew the original never mistakes the copy's changes for its own.
    /// Its journal starts empty where the original's ends: a painter meets
    /// the copy with a full redraw, so no plan reads the rewrites before it.
    fn clone(&self) -> Self {
        Self {
            id: fresh_id(),
            epoch: self.epoch,
            segments: self.segments.clone(),
            journal: Vec::new(),
            journal_start: self.journal_start + self.journal.len() as u64,
        }
    }
}

/// A batch of segments kept across frames (a growing tree); see the module
/// documentation.
#[derive(Clone)]
pub struct SegmentLayer {
    data: Arc<LayerData>,
}

impl std::fmt::Debug for SegmentLayer {
    /// The segments only: identity, epoch and journal are for the painter,
    /// and a state's description must not depend on them.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SegmentLayer")
            .field("segments", &self.data.segments)
            .finish()
    }
}

impl Default for SegmentLayer {
    fn default() -> Self {
        Self::new()
    }
}

impl PartialEq for SegmentLayer {
    /// Equal when they hold the same segments (identity and journal aside).
    fn eq(&self, other: &Self) -> bool {
        self.data.segments == other.data.segments
    }
}

/// Where a painter stopped: the layer it drew, its epoch, how many slots and
/// how many rewrites of the journal it had applied.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LayerMark {
    pub id: u64,
    pub epoch: u64,
    pub len: usize,
    pub journal_end: u64,
}

/// One drawing operation of a [`LayerPlan`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LayerOp {
    /// Add this segment's pixels (increment their coverage).
    Draw(Segment),
    /// Remove this segment's pixels (decrement their coverage).
    Erase(Segment),
}

/// The work that brings a painter's picture of a layer up to date.
#[derive(Clone, Debug, PartialEq)]
pub enum LayerPlan<'a> {
    /// Clear the picture and draw every segment.
    Full(&'a [Segment]),
    /// Keep the picture; for each rewrite of a slot below `drawn` erase its
    /// old segment and draw its new one, in order, then draw `appended`.
    Incremental {
        drawn: usize,
        rewrites: &'a [Rewrite],
        appended: &'a [Segment],
    },
}

impl LayerPlan<'_> {
    /// True for a redraw from scratch.
    #[must_use]
    pub fn is_full(&self) -> bool {
        matches!(self, LayerPlan::Full(_))
    }

    /// The operations in order (a full plan is draws only, after a clear).
    pub fn ops(&self) -> impl Iterator<Item = LayerOp> + '_ {
        let (full, drawn, rewrites, appended): (&[Segment], usize, &[Rewrite], &[Segment]) =
            match *self {
                LayerPlan::Full(all) => (all, 0, &[], &[]),
                LayerPlan::Incremental {
                    drawn,
                    rewrites,
                    appended,
                } => (&[], drawn, rewrites, appended),
            };
        full.iter()
            .map(|s| LayerOp::Draw(*s))
            .chain(
                rewrites
                    .iter()
                    .filter(move |r| (r.slot as usize) < drawn)
                    .flat_map(|r| [LayerOp::Erase(r.old), LayerOp::Draw(r.new)]),
            )
            .chain(appended.iter().map(|s| LayerOp::Draw(*s)))
    }

    /// True when the plan erases a segment: it rewrites a slot the painter
    /// had drawn. Only an erase needs the painter's coverage counts.
    #[must_use]
    pub fn erases(&self) -> bool {
        match *self {
            LayerPlan::Full(_) => false,
            LayerPlan::Incremental {
                drawn, rewrites, ..
            } => rewrites.iter().any(|r| (r.slot as usize) < drawn),
        }
    }

    /// How many segments the plan draws (strokes), erasures not counted.
    #[must_use]
    pub fn draws(&self) -> usize {
        self.ops()
            .filter(|op| matches!(op, LayerOp::Draw(_)))
            .count()
    }
}

impl SegmentLayer {
    /// The heap a copy of it holds, bytes: its segments (a copy starts with
    /// an empty journal, [`SegmentLayer::detached`]).
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of::<LayerData>() + self.data.segments.len() * std::mem::size_of::<Segment>()
    }

    /// An empty layer with a fresh identity.
    #[must_use]
    pub fn new() -> Self {
        Self {
            data: Arc::new(LayerData {
                id: fresh_id(),
                epoch: 0,
                segments: Vec::new(),
                journal: Vec::new(),
                journal_start: 0,
            }),
        }
    }

    /// A copy that is a layer of its own, with a fresh identity, sharing
    /// nothing with this one. What a copy of the model that keeps the layer
    /// takes (a timeline snapshot): sharing the list instead would make the
    /// original's next change copy it, under a new identity, and the painter
    /// would redraw the original's picture in full.
    #[must_use]
    pub fn detached(&self) -> Self {
        Self {
            data: Arc::new(LayerData::clone(&self.data)),
        }
    }

    /// An empty layer holding `segments`.
    #[must_use]
    pub fn from_segments(segments: Vec<Segment>) -> Self {
        let mut layer = Self::new();
        Arc::make_mut(&mut layer.data).segments = segments;
        layer
    }

    /// The layer's identity (unique in this process).
    #[must_use]
    pub fn id(&self) -> u64 {
        self.data.id
    }

    /// How many times the layer was cleared.
    #[must_use]
    pub fn epoch(&self) -> u64 {
        self.data.epoch
    }

    /// The segments, slot by slot.
    #[must_use]
    pub fn segments(&self) -> &[Segment] {
        &self.data.segments
    }

    #[must_use]
    pub fn len(&self) -> usize {
        self.data.segments.len()
    }

    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.data.segments.is_empty()
    }

    /// Where a painter that has just drawn this layer stands.
    #[must_use]
    pub fn mark(&self) -> LayerMark {
        LayerMark {
            id: self.data.id,
            epoch: self.data.epoch,
            len: self.data.segments.len(),
            journal_end: self.data.journal_start + self.data.journal.len() as u64,
        }
    }

    /// Appends a segment in a new slot.
    pub fn push(&mut self, segment: Segment) {
        Arc::make_mut(&mut self.data).segments.push(segment);
    }

    /// Replaces slot `slot`'s segment; returns false (and changes nothing)
    /// when there is no such slot. Rewriting a slot with its own segment is
    /// not a change and is not journalled.
    pub fn set(&mut self, slot: usize, segment: Segment) -> bool {
        match self.data.segments.get(slot) {
            None => return false,
            Some(old) if *old == segment => return true,
            Some(_) => {}
        }
        let data = Arc::make_mut(&mut self.data);
        let old = std::mem::replace(&mut data.segments[slot], segment);
        data.journal.push(Rewrite {
            slot: slot as u32,
            old,
            new: segment,
        });
        let keep = JOURNAL_MIN_KEPT.max(data.segments.len() / 2);
        if data.journal.len() > 2 * keep {
            let drop = data.journal.len() - keep;
            data.journal.drain(..drop);
            data.journal_start += drop as u64;
        }
        true
    }

    /// Empties the layer and starts a new epoch (painters redraw from scratch).
    pub fn clear(&mut self) {
        let data = Arc::make_mut(&mut self.data);
        data.epoch += 1;
        data.segments.clear();
        data.journal.clear();
        data.journal_start = 0;
    }

    /// The work that brings a painter that stopped at `since` up to date
    /// (see [`LayerPlan`]); `None` (never painted) or a mark of another layer,
    /// another epoch, or further back than the journal keeps gives a full
    /// plan, and so does a backlog of rewrites that would cost more than
    /// drawing everything again.
    #[must_use]
    pub fn plan(&self, since: Option<&LayerMark>) -> LayerPlan<'_> {
        let d = &*self.data;
        let full = LayerPlan::Full(&d.segments);
        let Some(m) = since else { return full };
        let journal_end = d.journal_start + d.journal.len() as u64;
        if m.id != d.id
            || m.epoch != d.epoch
            || m.len > d.segments.len()
            || m.journal_end < d.journal_start
            || m.journal_end > journal_end
        {
            return full;
        }
        let rewrites = &d.journal[(m.journal_end - d.journal_start) as usize..];
        let appended = &d.segments[m.len..];
        // Each rewrite costs an erase and a draw.
        if 2 * rewrites.len() + appended.len() > d.segments.len() {
            return full;
        }
        LayerPlan::Incremental {
            drawn: m.len,
            rewrites,
            appended,
        }
    }
}

/// A version for a raster's cells: a 64-bit FNV-1a fingerprint of the bytes,
/// so it changes whenever a cell changes (two different grids share a
/// version with probability about 2⁻⁶⁴) and stays put while they do not.
/// Linear in the cell count, a few tens of microseconds for 512² cells.
#[must_use]
pub fn raster_version(cells: &[u8]) -> u64 {
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    let mut h: u64 = 0xcbf2_9ce4_8422_2325 ^ cells.len() as u64;
    let mut chunks = cells.chunks_exact(8);
    for c in &mut chunks {
        let word = u64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]);
        h = (h ^ word).wrapping_mul(PRIME);
        h ^= h >> 29;
    }
    for &b in chunks.remainder() {
        h = (h ^ u64::from(b)).wrapping_mul(PRIME);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Lcg64;
    use std::collections::HashMap;

    #[test]
    fn a_detached_copy_is_its_own_layer_and_the_original_keeps_drawing_incrementally() {
        let a = (DVec2::ZERO, DVec2::ONE);
        let b = (DVec2::ONE, DVec2::new(2.0, 0.0));
        let mut live = SegmentLayer::from_segments(vec![a]);
        let (id, drawn) = (live.id(), live.mark());
        let copy = live.detached();
        assert_ne!(copy.id(), id);
        assert_eq!(copy, live, "the same segments");
        // The original is not shared, so changing it keeps its identity and
        // a painter that drew it gets only the new slot.
        live.push(b);
        assert_eq!(live.id(), id);
        assert_eq!(
            live.plan(Some(&drawn)).ops().collect::<Vec<_>>(),
            [LayerOp::Draw(b)]
        );
        // A shared one (a plain clone) changes identity on its next change.
        let shared = live.clone();
        live.push(a);
        assert_ne!(live.id(), id);
        assert_eq!(shared.id(), id);
        // A painter that drew the original never takes the copy for it.
        assert!(copy.plan(Some(&drawn)).is_full());
        assert_eq!(copy.plan(Some(&copy.mark())).ops().count(), 0);
    }

    fn seg(rng: &mut Lcg64) -> Segment {
        // Coarse coordinates so repeats (and no-op rewrites) happen.
        let mut c = || (rng.next_f64() * 8.0).floor();
        (DVec2::new(c(), c()), DVec2::new(c(), c()))
    }

    fn key(s: &Segment) -> [u64; 4] {
        [
            s.0.x.to_bits(),
            s.0.y.to_bits(),
            s.1.x.to_bits(),
            s.1.y.to_bits(),
        ]
    }

    /// A painter that keeps a coverage count per segment, the way the page
    /// keeps one per pixel (pixels are a sum over segments, so equal
    /// per-segment counts mean equal pictures).
    #[derive(Default)]
    struct Painter {
        counts: HashMap<[u64; 4], i64>,
        mark: Option<LayerMark>,
        draws: usize,
        fulls: usize,
    }

    impl Painter {
        fn paint(&mut self, layer: &SegmentLayer) {
            let plan = layer.plan(self.mark.as_ref());
            if plan.is_full() {
                self.counts.clear();
                self.fulls += 1;
            }
            for op in plan.ops() {
                match op {
                    LayerOp::Draw(s) => {
                        *self.counts.entry(key(&s)).or_default() += 1;
                        self.draws += 1;
                    }
                    LayerOp::Erase(s) => {
                        let c = self.counts.entry(key(&s)).or_default();
                        *c -= 1;
                        assert!(*c >= 0, "erased a segment that was not drawn");
                    }
                }
            }
            self.counts.retain(|_, c| *c != 0);
            self.mark = Some(layer.mark());
        }
    }

    fn full_counts(layer: &SegmentLayer) -> HashMap<[u64; 4], i64> {
        let mut m = HashMap::new();
        for s in layer.segments() {
            *m.entry(key(s)).or_default() += 1;
        }
        m
    }

    #[test]
    fn a_static_layer_plans_no_work_and_appends_plan_only_the_new_slots() {
        let mut rng = Lcg64::new(1);
        let mut layer = SegmentLayer::new();
        for _ in 0..1000 {
            layer.push(seg(&mut rng));
        }
        assert!(layer.plan(None).is_full());
        assert_eq!(layer.plan(None).draws(), 1000);
        let mark = layer.mark();
        let plan = layer.plan(Some(&mark));
        assert!(!plan.is_full());
        assert_eq!(plan.draws(), 0, "nothing changed, nothing drawn");
        for _ in 0..7 {
            layer.push(seg(&mut rng));
        }
        let plan = layer.plan(Some(&mark));
        assert_eq!(plan.draws(), 7);
        assert_eq!(plan.ops().count(), 7);
    }

    #[test]
    fn a_rewrite_of_a_drawn_slot_erases_the_old_segment_and_draws_the_new() {
        let a = (DVec2::ZERO, DVec2::X);
        let b = (DVec2::ZERO, DVec2::Y);
        let c = (DVec2::ONE, DVec2::Y);
        let mut layer = SegmentLayer::from_segments(vec![a; 20]);
        let mark = layer.mark();
        assert!(layer.set(1, b));
        assert!(layer.set(1, c));
        assert!(layer.set(1, c), "the same segment again is accepted");
        assert!(!layer.set(20, c), "no such slot");
        layer.push(b);
        assert!(layer.set(20, c), "a slot added since the mark");
        let ops: Vec<LayerOp> = layer.plan(Some(&mark)).ops().collect();
        assert_eq!(
            ops,
            vec![
                LayerOp::Erase(a),
                LayerOp::Draw(b),
                LayerOp::Erase(b),
                LayerOp::Draw(c),
                // Slot 20 was never drawn: only its current segment.
                LayerOp::Draw(c),
            ]
        );
        assert!(layer.plan(Some(&mark)).erases());
    }

    #[test]
    fn only_a_rewrite_of_a_drawn_slot_makes_a_plan_erase() {
        let a = (DVec2::ZERO, DVec2::X);
        let b = (DVec2::ZERO, DVec2::Y);
        let mut layer = SegmentLayer::from_segments(vec![a; 4]);
        assert!(!layer.plan(None).erases(), "a full redraw only draws");
        let mark = layer.mark();
        layer.push(a);
        assert!(!layer.plan(Some(&mark)).erases(), "appending only draws");
        assert!(layer.set(4, b));
        assert!(
            !layer.plan(Some(&mark)).erases(),
            "a slot added since the mark was never drawn"
        );
        assert!(layer.set(0, b));
        let plan = layer.plan(Some(&mark));
        assert!(plan.erases());
        assert_eq!(
            plan.erases(),
            plan.ops().any(|op| matches!(op, LayerOp::Erase(_)))
        );
    }

    #[test]
    fn clear_clone_and_foreign_marks_plan_a_full_redraw() {
        let mut layer = SegmentLayer::from_segments(vec![(DVec2::ZERO, DVec2::X); 10]);
        let mark = layer.mark();
        let held = layer.clone();
        // The clone shares the data: same identity until one of them changes.
        assert_eq!(held.id(), layer.id());
        layer.push((DVec2::X, DVec2::Y));
        assert_ne!(held.id(), layer.id(), "the changed copy is a new layer");
        assert!(layer.plan(Some(&mark)).is_full());
        assert_eq!(held.plan(Some(&mark)).draws(), 0);
        let mut other = held.clone();
        other.clear();
        assert_eq!(other.epoch(), 1);
        assert!(other.is_empty());
        assert!(other.plan(Some(&held.mark())).is_full());
        assert!(SegmentLayer::new().plan(Some(&mark)).is_full());
        assert_eq!(held, SegmentLayer::from_segments(held.segments().to_vec()));
    }

    #[test]
    fn random_grow_rewire_clear_sequences_paint_the_full_list() {
        for seed in 0..40 {
            let mut rng = Lcg64::new(seed);
            let mut layer = SegmentLayer::new();
            let mut painter = Painter::default();
            let mut lagging = Painter::default();
            for frame in 0..120 {
                let r = rng.next_f64();
                if r < 0.02 {
                    layer.clear();
                } else if r < 0.05 {
                    // A scene still holds the layer while the model changes it.
                    let held = layer.clone();
                    layer.push(seg(&mut rng));
                    assert_ne!(held.id(), layer.id());
                }
                let grow = (rng.next_f64() * 30.0) as usize;
                for _ in 0..grow {
                    layer.push(seg(&mut rng));
                }
                let rewires = (rng.next_f64() * 12.0) as usize;
                for _ in 0..rewires {
                    if !layer.is_empty() {
                        let slot = (rng.next_f64() * layer.len() as f64) as usize;
                        layer.set(slot, seg(&mut rng));
                    }
                }
                painter.paint(&layer);
                assert_eq!(
                    painter.counts,
                    full_counts(&layer),
                    "seed {seed} frame {frame}"
                );
                // A painter that skips frames catches up just as well.
                if frame % 5 == 0 {
                    lagging.paint(&layer);
                    assert_eq!(lagging.counts, full_counts(&layer));
                }
            }
            assert!(
                painter.fulls < 40,
                "seed {seed}: {} full redraws",
                painter.fulls
            );
        }
    }

    #[test]
    fn growth_costs_the_new_slots_whatever_the_size() {
        for size in [1_000usize, 100_000] {
            let mut rng = Lcg64::new(5);
            let mut layer = SegmentLayer::new();
            for _ in 0..size {
                layer.push(seg(&mut rng));
            }
            let mut painter = Painter::default();
            painter.paint(&layer);
            let before = painter.draws;
            for _ in 0..10 {
                for _ in 0..100 {
                    layer.push(seg(&mut rng));
                }
                painter.paint(&layer);
            }
            assert_eq!(painter.draws - before, 1000, "size {size}");
            assert_eq!(painter.fulls, 1);
        }
    }

    #[test]
    fn a_painter_far_behind_the_journal_redraws_in_full() {
        let mut layer = SegmentLayer::from_segments(vec![(DVec2::ZERO, DVec2::X); 100]);
        let mark = layer.mark();
        for i in 0..(3 * JOURNAL_MIN_KEPT) {
            let x = (i % 7) as f64 + 1.0;
            layer.set(i % 100, (DVec2::ZERO, DVec2::splat(x)));
        }
        assert!(layer.plan(Some(&mark)).is_full());
        // The journal was trimmed, not kept whole.
        assert!(layer.data.journal.len() <= 2 * JOURNAL_MIN_KEPT);
        assert!(layer.data.journal_start > 0);
        assert!(mark.journal_end < layer.data.journal_start);
        let mut painter = Painter::default();
        painter.paint(&layer);
        layer.set(3, (DVec2::ONE, DVec2::ONE));
        let plan = layer.plan(painter.mark.as_ref());
        assert_eq!(plan.ops().count(), 2);
    }

    #[test]
    fn the_raster_version_changes_with_any_cell_and_only_then() {
        let mut cells = vec![0u8; 512 * 512 + 3];
        let v0 = raster_version(&cells);
        assert_eq!(raster_version(&cells.clone()), v0);
        let mut seen = vec![v0];
        for i in [0, 7, 8, 1000, 512 * 512, 512 * 512 + 2] {
            cells[i] = 1;
            let v = raster_version(&cells);
            assert!(!seen.contains(&v), "cell {i}");
            seen.push(v);
            cells[i] = 0;
            assert_eq!(raster_version(&cells), v0);
        }
        assert_ne!(raster_version(&[0; 4]), raster_version(&[0; 5]));
    }
}
