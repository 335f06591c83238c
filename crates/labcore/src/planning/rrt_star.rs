//! RRT, RRT* and Informed RRT* in a 2-D [`World`], one iteration at a time.
//!
//! **RRT** (LaValle, "Rapidly-exploring random trees: a new tool for path
//! planning", TR 98-11, Iowa State University, 1998; LaValle, *Planning
//! Algorithms*, 2006, §5.5). Each iteration draws `x_rand` (the goal itself
//! with probability `goal_bias`), finds the nearest tree node `x_near`, and
//! steers a step of at most `η` towards it:
//!
//! ```text
//! x_new = x_near + min(η, |x_rand − x_near|) · (x_rand − x_near) / |x_rand − x_near|
//! ```
//!
//! `x_new` is added with parent `x_near` unless it or the segment
//! `x_near–x_new` is in collision ([`World::segment_free`], checked every
//! `check_resolution` units).
//!
//! **RRT\*** (Karaman & Frazzoli, "Sampling-based algorithms for optimal
//! motion planning", *IJRR* 30(7), 2011, pp. 846–894, Alg. 6) adds two steps
//! over the near set `X_near` = the nodes within
//!
//! ```text
//! r = min(γ · (ln n / n)^(1/d), η),   d = 2,   n = number of nodes
//! ```
//!
//! of `x_new` (*ibid.* §3.3.3 and Theorem 38: asymptotically optimal for
//! `γ > (2 (1 + 1/d))^(1/d) (μ(X_free) / ζ_d)^(1/d)`, `ζ_2 = π`, which is
//! `√3 √(μ / π)` in the plane and the form OMPL's RRT* uses; the PRM*/RRG
//! constant `2 (1 + 1/d)^(1/d) (μ / ζ_d)^(1/d)` is larger. The default here is
//! `1.1 · 2 √(3/2) √(μ(X) / π)` with the bounds' area `μ(X) ≥ μ(X_free)`, so
//! it satisfies both. Solovey, Janson, Schmerling, Frazzoli & Pavone,
//! "Revisiting the asymptotic optimality of RRT*", *ICRA* 2020, show that the
//! original proof needs a larger radius, `∝ (ln n / n)^(1/(d+1))`; this
//! planner keeps the classic one, as OMPL's RRT* does):
//!
//! - *choose parent*: `x_new`'s parent is the node `x` of `X_near ∪ {x_near}`
//!   minimising `cost(x) + |x − x_new|` whose edge to `x_new` is free
//!   (candidates are tried cheapest first, so usually one edge is checked);
//! - *rewire*: every `x ∈ X_near` with `cost(x_new) + |x_new − x| < cost(x)`
//!   and a free edge gets `x_new` as its parent.
//!
//! `cost(x)` is the path length from the start along the tree. A rewired node
//! passes its new cost down to all its descendants (each node keeps its
//! children in an intrusive list), so `cost(x) = cost(parent) + |x − parent|`
//! holds for every node after every iteration, with the same floating-point
//! expression each time.
//!
//! **Informed RRT\*** (Gammell, Srinivasa & Barfoot, "Informed RRT*: Optimal
//! sampling-based path planning focused via direct sampling of an admissible
//! ellipsoidal heuristic", *IROS* 2014, Alg. 2): once a path of cost `c_best`
//! exists, only states that could shorten it are sampled — those with
//! `|x − x_start| + |x − x_goal| ≤ c_best + r_goal` (the goal is a disc of radius
//! `r_goal`), an ellipse with foci start and goal, transverse diameter
//! `c_best + r_goal` and conjugate diameter `√((c_best + r_goal)² − c_min²)`,
//! `c_min = |x_goal − x_start|`. Points are drawn uniformly in the unit disc
//! (by rejection), stretched and rotated onto the ellipse, and redrawn when
//! outside the bounds; when the ellipse is larger than the bounds, the bounds
//! are sampled and points outside the ellipse redrawn (at most
//! [`MAX_SAMPLE_TRIES`] tries, then a uniform sample).
//!
//! **The best path** is the cheapest node inside the goal disc and its path
//! to the start; its cost only ever decreases, and every decrease is recorded
//! in [`RrtStar::cost_history`] as `(iteration, cost)`.
//!
//! **Random draws**, all from one [`Lcg64`] seeded with `seed`, per iteration:
//! `u` for the goal bias; then, unless the goal was drawn, `x` then `y`
//! uniform in the bounds (Informed: two numbers in `[-1, 1)` per disc try, or
//! `x`, `y` per bounds try). The same seed gives the same tree on every
//! platform (no transcendental calls besides `ln` from `libm`).

use glam::DVec2;
use std::fmt;

use super::spatial_grid::SpatialGrid;
use super::world::World;
use crate::rng::Lcg64;

/// The parent of the root in [`RrtStar::parents`].
pub const NO_PARENT: u32 = u32::MAX;
/// Informed sampling gives up after this many rejected draws and samples the bounds.
pub const MAX_SAMPLE_TRIES: usize = 64;
/// The most nodes a tree may hold (indices are `u32`).
pub const MAX_NODES_LIMIT: usize = 1 << 26;

/// Which planner grows the tree.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Planner {
    /// Plain RRT: parent = nearest node, no rewiring.
    Rrt,
    /// RRT*: choose parent and rewire within the shrinking radius.
    #[default]
    RrtStar,
    /// RRT* sampling the informed ellipse once a path exists.
    InformedRrtStar,
}

impl Planner {
    /// Short name for tables and plots.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Planner::Rrt => "RRT",
            Planner::RrtStar => "RRT*",
            Planner::InformedRrtStar => "Informed RRT*",
        }
    }
}

/// Tuning of the planner; every field is public.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RrtConfig {
    pub planner: Planner,
    /// Steer step `η`, world units (finite, > 0); also caps the rewiring radius.
    pub step_eta: f64,
    /// Probability of sampling the goal itself, in `[0, 1]`.
    pub goal_bias: f64,
    /// Spacing of the edge collision checks, world units (finite, > 0).
    pub check_resolution: f64,
    /// Radius of the goal disc, world units (finite, ≥ 0).
    pub goal_radius: f64,
    /// `γ` of the rewiring radius (finite, > 0); `None` = the default of the module docs.
    pub gamma: Option<f64>,
    /// Stop adding nodes at this many (1 … [`MAX_NODES_LIMIT`]).
    pub max_nodes: usize,
    /// Seed of the planner's [`Lcg64`].
    pub seed: u64,
}

impl Default for RrtConfig {
    /// RRT*, `η = 5`, goal bias 5 %, checks every 0.5, goal radius 1, default
    /// `γ`, at most 1,000,000 nodes, seed 1 — the RRT* world of
    /// `shared/BENCHMARKS.md` is 100 × 100.
    fn default() -> Self {
        Self {
            planner: Planner::RrtStar,
            step_eta: 5.0,
            goal_bias: 0.05,
            check_resolution: 0.5,
            goal_radius: 1.0,
            gamma: None,
            max_nodes: 1_000_000,
            seed: 1,
        }
    }
}

/// Why a planner could not be made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RrtError {
    /// An [`RrtConfig`] field outside its documented range; names the field.
    InvalidConfig { field: &'static str },
    /// The start is outside the bounds, NaN, or inside an obstacle.
    StartNotFree,
    /// The goal centre is outside the bounds, NaN, or inside an obstacle.
    GoalNotFree,
}

impl fmt::Display for RrtError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidConfig { field } => write!(f, "the setting `{field}` is out of range"),
            Self::StartNotFree => write!(
                f,
                "the start must be inside the field and not in an obstacle"
            ),
            Self::GoalNotFree => write!(
                f,
                "the goal must be inside the field and not in an obstacle"
            ),
        }
    }
}

impl std::error::Error for RrtError {}

/// A point of the best-cost history.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CostSample {
    /// Iterations done when the cost was reached (1-based).
    pub iteration: usize,
    /// Best path length from then on.
    pub cost: f64,
}

/// What one iteration did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IterationOutcome {
    /// A node was added; `rewired` nodes got it as their new parent.
    Added { node: usize, rewired: usize },
    /// `x_new` or its edge from `x_near` was in collision.
    Collided,
    /// The sample coincided with its nearest node.
    Duplicate,
    /// The tree holds `max_nodes` nodes; nothing was drawn.
    Full,
}

/// Choose-parent candidate: total cost through it, edge length, node, edge state.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    total: f64,
    dist: f64,
    node: u32,
    /// 0 unknown, 1 free, 2 blocked.
    edge: u8,
}

/// A growing RRT / RRT* / Informed RRT* tree (module docs).
#[derive(Clone, Debug)]
pub struct RrtStar {
    world: World,
    start: DVec2,
    goal: DVec2,
    config: RrtConfig,
    gamma: f64,
    rng: Lcg64,
    index: SpatialGrid,
    parent: Vec<u32>,
    cost: Vec<f64>,
    first_child: Vec<u32>,
    next_sibling: Vec<u32>,
    iterations: usize,
    rewires: usize,
    last_rewired: Vec<u32>,
    batch_rewired: Vec<u32>,
    newest: Option<usize>,
    last_radius: f64,
    goal_nodes: Vec<u32>,
    best: Option<u32>,
    history: Vec<CostSample>,
    // Scratch, kept to avoid allocating per iteration.
    near: Vec<u32>,
    candidates: Vec<Candidate>,
    stack: Vec<u32>,
}

/// The one edge-length expression used everywhere (so cost sums are reproducible).
#[inline]
fn edge_len(child: DVec2, parent: DVec2) -> f64 {
    (child - parent).length()
}

impl RrtStar {
    /// The heap the tree holds, bytes: its nodes' parents, costs and
    /// children, their index, the world, the history and the scratch
    /// (capacities: what a copy of it costs).
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of;
        let u32s = self.parent.capacity()
            + self.first_child.capacity()
            + self.next_sibling.capacity()
            + self.last_rewired.capacity()
            + self.batch_rewired.capacity()
            + self.goal_nodes.capacity()
            + self.near.capacity()
            + self.stack.capacity();
        u32s * size_of::<u32>()
            + self.cost.capacity() * size_of::<f64>()
            + self.history.capacity() * size_of::<CostSample>()
            + self.candidates.capacity() * size_of::<Candidate>()
            + self.index.heap_bytes()
            + self.world.heap_bytes()
    }

    /// A tree holding only the start.
    ///
    /// # Errors
    /// [`RrtError`] for a setting out of range or a start / goal centre that is not free.
    ///
    /// # Example
    /// ```
    /// use glam::DVec2;
    /// use labcore::planning::rrt_star::{RrtConfig, RrtStar};
    /// use labcore::planning::world::{Obstacle, World};
    /// let world = World::new(DVec2::ZERO, DVec2::splat(100.0), vec![
    ///     Obstacle::Circle { center: DVec2::splat(50.0), radius: 20.0 },
    /// ]).unwrap();
    /// let mut tree = RrtStar::new(world, DVec2::splat(5.0), DVec2::splat(95.0), RrtConfig::default()).unwrap();
    /// tree.iterate(3000);
    /// let cost = tree.best_cost().expect("a path around the disc");
    /// assert!(cost > 90.0 * 2f64.sqrt() - 1.0); // not through the disc
    /// assert_eq!(tree.best_path().unwrap().first(), Some(&DVec2::splat(5.0)));
    /// ```
    pub fn new(
        world: World,
        start: DVec2,
        goal: DVec2,
        config: RrtConfig,
    ) -> Result<Self, RrtError> {
        let bad = |field| Err(RrtError::InvalidConfig { field });
        if !(config.step_eta.is_finite() && config.step_eta > 0.0) {
            return bad("step_eta");
        }
        if !(0.0..=1.0).contains(&config.goal_bias) {
            return bad("goal_bias");
        }
        if !(config.check_resolution.is_finite() && config.check_resolution > 0.0) {
            return bad("check_resolution");
        }
        if !(config.goal_radius.is_finite() && config.goal_radius >= 0.0) {
            return bad("goal_radius");
        }
        if !(1..=MAX_NODES_LIMIT).contains(&config.max_nodes) {
            return bad("max_nodes");
        }
        let gamma = match config.gamma {
            Some(g) if g.is_finite() && g > 0.0 => g,
            Some(_) => return bad("gamma"),
            None => default_gamma(world.area()),
        };
        if !world.point_free(start) {
            return Err(RrtError::StartNotFree);
        }
        if !world.point_free(goal) {
            return Err(RrtError::GoalNotFree);
        }
        let mut index = SpatialGrid::new(world.min(), world.max());
        index.insert(start);
        let mut tree = Self {
            world,
            start,
            goal,
            config,
            gamma,
            rng: Lcg64::new(config.seed),
            index,
            parent: vec![NO_PARENT],
            cost: vec![0.0],
            first_child: vec![NO_PARENT],
            next_sibling: vec![NO_PARENT],
            iterations: 0,
            rewires: 0,
            last_rewired: Vec::new(),
            batch_rewired: Vec::new(),
            newest: None,
            last_radius: 0.0,
            goal_nodes: Vec::new(),
            best: None,
            history: Vec::new(),
            near: Vec::new(),
            candidates: Vec::new(),
            stack: Vec::new(),
        };
        if (start - goal).length() <= config.goal_radius {
            tree.goal_nodes.push(0);
            tree.best = Some(0);
            tree.history.push(CostSample {
                iteration: 0,
                cost: 0.0,
            });
        }
        Ok(tree)
    }

    /// Runs `n` iterations (fewer once the tree is full); returns the nodes
    /// added. [`RrtStar::rewired_in_last_batch`] then lists every node rewired
    /// during this call. No clock inside: the page picks `n` to fit its frame
    /// budget.
    pub fn iterate(&mut self, n: usize) -> usize {
        self.batch_rewired.clear();
        let mut added = 0;
        for _ in 0..n {
            match self.step() {
                IterationOutcome::Added { .. } => added += 1,
                IterationOutcome::Full => break,
                _ => {}
            }
            self.batch_rewired.extend_from_slice(&self.last_rewired);
        }
        added
    }

    /// One iteration (module docs).
    pub fn step(&mut self) -> IterationOutcome {
        self.last_rewired.clear();
        if self.parent.len() >= self.config.max_nodes {
            return IterationOutcome::Full;
        }
        self.iterations += 1;
        let x_rand = self.sample();
        let Some(nearest) = self.index.nearest(x_rand) else {
            return IterationOutcome::Duplicate; // unreachable: the root is always there
        };
        let x_near = self.index.points()[nearest];
        let d = (x_rand - x_near).length();
        if d.is_nan() || d <= 0.0 {
            return IterationOutcome::Duplicate;
        }
        let eta = self.config.step_eta;
        let x_new = if d <= eta {
            x_rand
        } else {
            x_near + (x_rand - x_near) * (eta / d)
        };
        let res = self.config.check_resolution;
        if !self.world.point_free(x_new) || !self.world.segment_free(x_near, x_new, res) {
            return IterationOutcome::Collided;
        }

        let n = self.parent.len();
        let (parent, cost_new) = if self.config.planner == Planner::Rrt {
            (nearest as u32, self.cost[nearest] + edge_len(x_new, x_near))
        } else {
            self.last_radius = self.radius(n);
            self.index.within(x_new, self.last_radius, &mut self.near);
            self.choose_parent(x_new, nearest as u32)
        };

        // Add the node.
        let node = self.index.insert(x_new) as u32;
        self.parent.push(parent);
        self.cost.push(cost_new);
        self.first_child.push(NO_PARENT);
        self.next_sibling.push(self.first_child[parent as usize]);
        self.first_child[parent as usize] = node;
        self.newest = Some(node as usize);

        if self.config.planner != Planner::Rrt {
            self.rewire(node, parent);
        }
        if (x_new - self.goal).length() <= self.config.goal_radius {
            self.goal_nodes.push(node);
        }
        self.update_best();
        IterationOutcome::Added {
            node: node as usize,
            rewired: self.last_rewired.len(),
        }
    }

    /// `r = min(γ √(ln n / n), η)` for `n` nodes.
    #[must_use]
    pub fn radius(&self, n: usize) -> f64 {
        if n < 2 {
            return 0.0;
        }
        let n = n as f64;
        (self.gamma * (crate::math::ln(n) / n).sqrt()).min(self.config.step_eta)
    }

    fn sample(&mut self) -> DVec2 {
        if self.rng.next_f64() < self.config.goal_bias {
            return self.goal;
        }
        let (lo, hi) = (self.world.min(), self.world.max());
        if self.config.planner == Planner::InformedRrtStar {
            if let Some(best) = self.best_cost() {
                if let Some(p) = self.sample_informed(best + self.config.goal_radius) {
                    return p;
                }
            }
        }
        DVec2::new(self.rng.range(lo.x, hi.x), self.rng.range(lo.y, hi.y))
    }

    /// A uniform point of `{x : |x − s| + |x − g| ≤ c} ∩ bounds`, or `None`
    /// after [`MAX_SAMPLE_TRIES`] misses.
    fn sample_informed(&mut self, c: f64) -> Option<DVec2> {
        let (s, g) = (self.start, self.goal);
        let c_min = (g - s).length();
        if c_min.is_nan() || c_min <= 0.0 || c.is_nan() || c <= c_min {
            return None;
        }
        let a = 0.5 * c; // semi-major
        let b = 0.5 * (c * c - c_min * c_min).sqrt(); // semi-minor
        let centre = 0.5 * (s + g);
        let e1 = (g - s) / c_min; // major axis
        let e2 = DVec2::new(-e1.y, e1.x);
        let (lo, hi) = (self.world.min(), self.world.max());
        let inside_ellipse = |p: DVec2| (p - s).length() + (p - g).length() <= c;
        let box_area = self.world.area();
        if std::f64::consts::PI * a * b < box_area {
            for _ in 0..MAX_SAMPLE_TRIES {
                let u = DVec2::new(self.rng.range(-1.0, 1.0), self.rng.range(-1.0, 1.0));
                if u.length_squared() > 1.0 {
                    continue;
                }
                let p = centre + e1 * (a * u.x) + e2 * (b * u.y);
                if self.world.in_bounds(p) {
                    return Some(p);
                }
            }
        } else {
            for _ in 0..MAX_SAMPLE_TRIES {
                let p = DVec2::new(self.rng.range(lo.x, hi.x), self.rng.range(lo.y, hi.y));
                if inside_ellipse(p) {
                    return Some(p);
                }
            }
        }
        None
    }

    /// Cheapest collision-free parent among the near set and `nearest` (whose
    /// edge is known to be free); returns it and `x_new`'s cost.
    fn choose_parent(&mut self, x_new: DVec2, nearest: u32) -> (u32, f64) {
        let pts = self.index.points();
        self.candidates.clear();
        let mut has_nearest = false;
        for &i in &self.near {
            let dist = edge_len(x_new, pts[i as usize]);
            let total = self.cost[i as usize] + dist;
            let edge = if i == nearest {
                has_nearest = true;
                1
            } else {
                0
            };
            self.candidates.push(Candidate {
                total,
                dist,
                node: i,
                edge,
            });
        }
        if !has_nearest {
            let dist = edge_len(x_new, pts[nearest as usize]);
            self.candidates.push(Candidate {
                total: self.cost[nearest as usize] + dist,
                dist,
                node: nearest,
                edge: 1,
            });
        }
        let res = self.config.check_resolution;
        loop {
            // Cheapest candidate not known to be blocked (ties: lower index).
            let mut best: Option<usize> = None;
            for (k, c) in self.candidates.iter().enumerate() {
                if c.edge == 2 {
                    continue;
                }
                let better = match best {
                    None => true,
                    Some(b) => {
                        let cb = &self.candidates[b];
                        c.total < cb.total || (c.total == cb.total && c.node < cb.node)
                    }
                };
                if better {
                    best = Some(k);
                }
            }
            // `nearest` is never blocked, so `best` is always found.
            let Some(k) = best else {
                return (
                    nearest,
                    self.cost[nearest as usize] + edge_len(x_new, pts[nearest as usize]),
                );
            };
            let c = self.candidates[k];
            if c.edge == 0 {
                let free = self.world.segment_free(pts[c.node as usize], x_new, res);
                self.candidates[k].edge = if free { 1 } else { 2 };
                if !free {
                    continue;
                }
            }
            return (c.node, c.total);
        }
    }

    /// Rewires the near set through `node` (just added with parent `parent`).
    /// The first `near.len()` candidates of [`Self::choose_parent`] are the
    /// near set in order (`x_near` may follow when it lies outside the radius;
    /// it is not rewired): their edge lengths and any collision verdicts are
    /// reused.
    fn rewire(&mut self, node: u32, parent: u32) {
        let x_new = self.index.points()[node as usize];
        let cost_new = self.cost[node as usize];
        let res = self.config.check_resolution;
        for k in 0..self.near.len() {
            let c = self.candidates[k];
            if c.node == parent {
                continue;
            }
            // Costs are finite sums of finite lengths (no NaN). Read the cost
            // now: an earlier rewire in this loop may have lowered it.
            if cost_new + c.dist >= self.cost[c.node as usize] {
                continue;
            }
            let free = match c.edge {
                1 => true,
                2 => false,
                _ => {
                    let px = self.index.points()[c.node as usize];
                    self.world.segment_free(x_new, px, res)
                }
            };
            if !free {
                continue;
            }
            self.reparent(c.node, node);
            self.rewires += 1;
            self.last_rewired.push(c.node);
        }
    }

    /// Moves `x` under `new_parent` and refreshes the costs of its subtree.
    fn reparent(&mut self, x: u32, new_parent: u32) {
        let old = self.parent[x as usize];
        if old != NO_PARENT {
            // Unlink x from the old parent's child list.
            let mut cur = self.first_child[old as usize];
            if cur == x {
                self.first_child[old as usize] = self.next_sibling[x as usize];
            } else {
                while cur != NO_PARENT {
                    let next = self.next_sibling[cur as usize];
                    if next == x {
                        self.next_sibling[cur as usize] = self.next_sibling[x as usize];
                        break;
                    }
                    cur = next;
                }
            }
        }
        self.parent[x as usize] = new_parent;
        self.next_sibling[x as usize] = self.first_child[new_parent as usize];
        self.first_child[new_parent as usize] = x;
        // Costs of x and all its descendants, parents before children.
        let pts = self.index.points();
        self.stack.clear();
        self.stack.push(x);
        while let Some(v) = self.stack.pop() {
            let p = self.parent[v as usize] as usize;
            self.cost[v as usize] = self.cost[p] + edge_len(pts[v as usize], pts[p]);
            let mut c = self.first_child[v as usize];
            while c != NO_PARENT {
                self.stack.push(c);
                c = self.next_sibling[c as usize];
            }
        }
    }

    fn update_best(&mut self) {
        let mut best = self.best;
        for &g in &self.goal_nodes {
            let better = match best {
                None => true,
                Some(b) => {
                    let (cg, cb) = (self.cost[g as usize], self.cost[b as usize]);
                    cg < cb || (cg == cb && g < b)
                }
            };
            if better {
                best = Some(g);
            }
        }
        let Some(b) = best else { return };
        let cost = self.cost[b as usize];
        self.best = Some(b);
        if !matches!(self.history.last(), Some(h) if cost >= h.cost) {
            self.history.push(CostSample {
                iteration: self.iterations,
                cost,
            });
        }
    }

    /// Node positions, by index (the root, the start, is 0).
    #[must_use]
    pub fn nodes(&self) -> &[DVec2] {
        self.index.points()
    }

    /// Each node's parent index ([`NO_PARENT`] for the root): the tree's edges
    /// as one batch of segments `nodes[i]–nodes[parents[i]]`.
    #[must_use]
    pub fn parents(&self) -> &[u32] {
        &self.parent
    }

    /// Parent of node `i`; `None` for the root or past the end.
    #[must_use]
    pub fn parent(&self, i: usize) -> Option<usize> {
        match self.parent.get(i) {
            Some(&p) if p != NO_PARENT => Some(p as usize),
            _ => None,
        }
    }

    /// Cost from the start along the tree, by node.
    #[must_use]
    pub fn costs(&self) -> &[f64] {
        &self.cost
    }

    /// Number of nodes (the root included).
    #[must_use]
    pub fn len(&self) -> usize {
        self.parent.len()
    }

    /// Never true: the tree always holds the start.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.parent.is_empty()
    }

    /// Iterations run (samples drawn).
    #[must_use]
    pub fn iterations(&self) -> usize {
        self.iterations
    }

    /// The node added last, `None` before the first.
    #[must_use]
    pub fn newest(&self) -> Option<usize> {
        self.newest
    }

    /// The rewiring radius used by the last RRT* iteration that added a node
    /// (to draw around [`RrtStar::newest`]); 0 before, and for plain RRT.
    #[must_use]
    pub fn last_radius(&self) -> f64 {
        self.last_radius
    }

    /// Nodes that got a new parent in the last iteration.
    #[must_use]
    pub fn last_rewired(&self) -> &[u32] {
        &self.last_rewired
    }

    /// Nodes that got a new parent during the last [`RrtStar::iterate`] call
    /// (repeats possible), for the page's flashing edges.
    #[must_use]
    pub fn rewired_in_last_batch(&self) -> &[u32] {
        &self.batch_rewired
    }

    /// Total re-parentings so far.
    #[must_use]
    pub fn rewire_count(&self) -> usize {
        self.rewires
    }

    /// Cost of the best path to the goal disc, once one exists.
    #[must_use]
    pub fn best_cost(&self) -> Option<f64> {
        self.best.map(|b| self.cost[b as usize])
    }

    /// The node ending the best path.
    #[must_use]
    pub fn best_node(&self) -> Option<usize> {
        self.best.map(|b| b as usize)
    }

    /// The best path from the start to the goal disc, as node positions.
    #[must_use]
    pub fn best_path(&self) -> Option<Vec<DVec2>> {
        let mut i = self.best?;
        let pts = self.index.points();
        let mut path = vec![pts[i as usize]];
        // A tree: at most len() steps to the root.
        for _ in 0..self.parent.len() {
            let p = self.parent[i as usize];
            if p == NO_PARENT {
                break;
            }
            path.push(pts[p as usize]);
            i = p;
        }
        path.reverse();
        Some(path)
    }

    /// `(iteration, best cost)` at every improvement, oldest first.
    #[must_use]
    pub fn cost_history(&self) -> &[CostSample] {
        &self.history
    }

    /// `γ` in use.
    #[must_use]
    pub fn gamma(&self) -> f64 {
        self.gamma
    }

    #[must_use]
    pub fn world(&self) -> &World {
        &self.world
    }

    #[must_use]
    pub fn start(&self) -> DVec2 {
        self.start
    }

    #[must_use]
    pub fn goal(&self) -> DVec2 {
        self.goal
    }

    #[must_use]
    pub fn config(&self) -> RrtConfig {
        self.config
    }
}

/// The default `γ = 1.1 · 2 √(1 + 1/2) · √(area / π)` for a world of `area`:
/// above both Karaman & Frazzoli's RRT* bound `√3 √(μ / π)` (Theorem 38) and
/// their PRM*/RRG constant `2 √(3/2) √(μ / π)`.
#[must_use]
pub fn default_gamma(area: f64) -> f64 {
    1.1 * 2.0 * (1.5f64).sqrt() * (area / std::f64::consts::PI).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::world::Obstacle;

    /// The world of `shared/BENCHMARKS.md`: 30 circles `(10 + 80u, 10 + 80u,
    /// 3 + 5u)`, the LCG's state set to `1 · a + c` before the first draw.
    fn benchmark_world() -> World {
        let mut rng = Lcg64::new(
            1u64.wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407),
        );
        let obstacles = (0..30)
            .map(|_| {
                let x = 10.0 + 80.0 * rng.next_f64();
                let y = 10.0 + 80.0 * rng.next_f64();
                let r = 3.0 + 5.0 * rng.next_f64();
                Obstacle::Circle {
                    center: DVec2::new(x, y),
                    radius: r,
                }
            })
            .collect();
        World::new(DVec2::ZERO, DVec2::splat(100.0), obstacles).unwrap()
    }

    fn mixed_world() -> World {
        World::new(
            DVec2::ZERO,
            DVec2::splat(60.0),
            vec![
                Obstacle::rect(DVec2::new(20.0, 0.0), DVec2::new(25.0, 45.0)),
                Obstacle::rect(DVec2::new(35.0, 15.0), DVec2::new(40.0, 60.0)),
                Obstacle::Circle {
                    center: DVec2::new(10.0, 40.0),
                    radius: 6.0,
                },
                Obstacle::Circle {
                    center: DVec2::new(50.0, 20.0),
                    radius: 5.0,
                },
            ],
        )
        .unwrap()
    }

    fn planner(p: Planner, seed: u64) -> RrtStar {
        RrtStar::new(
            mixed_world(),
            DVec2::new(5.0, 5.0),
            DVec2::new(55.0, 55.0),
            RrtConfig {
                planner: p,
                seed,
                ..RrtConfig::default()
            },
        )
        .unwrap()
    }

    /// Every node's cost is its parent's plus the edge, and the child lists
    /// are exactly the inverse of the parent array.
    fn assert_tree_consistent(t: &RrtStar) {
        let pts = t.nodes();
        let mut children = 0;
        for i in 0..t.len() {
            match t.parent(i) {
                None => {
                    assert_eq!(i, 0);
                    assert_eq!(t.costs()[0], 0.0);
                }
                Some(p) => {
                    let expected = t.costs()[p] + (pts[i] - pts[p]).length();
                    assert!((t.costs()[i] - expected).abs() <= 1e-9, "node {i}");
                    assert_eq!(t.costs()[i], expected, "node {i}: bit-exact");
                    children += 1;
                }
            }
            let mut c = t.first_child[i];
            while c != NO_PARENT {
                assert_eq!(t.parent[c as usize], i as u32);
                c = t.next_sibling[c as usize];
            }
        }
        let listed: usize = (0..t.len())
            .map(|i| {
                let mut n = 0;
                let mut c = t.first_child[i];
                while c != NO_PARENT {
                    n += 1;
                    c = t.next_sibling[c as usize];
                }
                n
            })
            .sum();
        assert_eq!(listed, children);
    }

    #[test]
    fn costs_stay_consistent_through_many_rewires() {
        for p in [Planner::RrtStar, Planner::InformedRrtStar] {
            let mut t = planner(p, 3);
            for _ in 0..20 {
                t.iterate(200);
                assert_tree_consistent(&t);
            }
            assert!(t.rewire_count() > 500, "{p:?}: {}", t.rewire_count());
        }
    }

    #[test]
    fn every_edge_and_the_path_are_collision_free() {
        for p in [Planner::Rrt, Planner::RrtStar, Planner::InformedRrtStar] {
            let mut t = planner(p, 5);
            t.iterate(3000);
            let w = t.world().clone();
            let res = t.config().check_resolution;
            let pts = t.nodes();
            for i in 1..t.len() {
                let q = pts[t.parent(i).unwrap()];
                assert!(w.point_free(pts[i]));
                assert!(w.segment_free(q, pts[i], res), "{p:?} edge {i}");
                // Geometric check: no edge enters an obstacle deeper than the
                // check spacing allows (sagitta of the biggest circle, and δ/2
                // for a rectangle corner).
                for o in w.obstacles() {
                    assert!(penetration(o, q, pts[i]) <= 0.5 * res + 1e-9);
                }
            }
            let path = t.best_path().expect("a path");
            assert!(path.windows(2).all(|s| w.segment_free(s[0], s[1], res)));
            assert_eq!(path[0], t.start());
            assert!((*path.last().unwrap() - t.goal()).length() <= 1.0);
            let len: f64 = path.windows(2).map(|s| (s[1] - s[0]).length()).sum();
            assert!((len - t.best_cost().unwrap()).abs() < 1e-9);
        }
    }

    /// How deep the segment `a–b` reaches into `o` (0 when it stays outside).
    fn penetration(o: &Obstacle, a: DVec2, b: DVec2) -> f64 {
        match *o {
            Obstacle::Circle { center, radius } => {
                let d = b - a;
                let t = if d.length_squared() > 0.0 {
                    ((center - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (radius - (a + d * t - center).length()).max(0.0)
            }
            Obstacle::Rect { min, max } => {
                // Sample finely; depth = distance to the nearest side from inside.
                (0..=1000)
                    .map(|k| a + (b - a) * (k as f64 / 1000.0))
                    .filter(|p| o.contains(*p))
                    .map(|p| {
                        (p.x - min.x)
                            .min(max.x - p.x)
                            .min(p.y - min.y)
                            .min(max.y - p.y)
                    })
                    .fold(0.0, f64::max)
            }
        }
    }

    #[test]
    fn best_cost_never_increases_and_history_records_each_drop() {
        for p in [Planner::Rrt, Planner::RrtStar, Planner::InformedRrtStar] {
            let mut t = planner(p, 8);
            let mut last = f64::INFINITY;
            for _ in 0..4000 {
                t.step();
                if let Some(c) = t.best_cost() {
                    assert!(c <= last, "{p:?}");
                    last = c;
                }
            }
            let h = t.cost_history();
            assert!(!h.is_empty());
            assert!(h
                .windows(2)
                .all(|w| w[1].cost < w[0].cost && w[1].iteration > w[0].iteration));
            assert_eq!(h.last().unwrap().cost, t.best_cost().unwrap());
        }
    }

    #[test]
    fn same_seed_same_tree_and_different_seed_different_tree() {
        let mut a = planner(Planner::InformedRrtStar, 11);
        let mut b = planner(Planner::InformedRrtStar, 11);
        a.iterate(2500);
        for _ in 0..25 {
            b.iterate(100);
        }
        assert_eq!(a.nodes(), b.nodes());
        assert_eq!(a.parents(), b.parents());
        assert_eq!(a.costs(), b.costs());
        assert_eq!(a.cost_history(), b.cost_history());
        let mut c = planner(Planner::InformedRrtStar, 12);
        c.iterate(2500);
        assert_ne!(a.nodes(), c.nodes());
    }

    #[test]
    fn rrt_star_beats_rrt_on_the_benchmark_world() {
        let run = |p: Planner| {
            let mut t = RrtStar::new(
                benchmark_world(),
                DVec2::new(2.0, 2.0),
                DVec2::new(98.0, 98.0),
                RrtConfig {
                    planner: p,
                    ..RrtConfig::default()
                },
            )
            .unwrap();
            t.iterate(20_000);
            t.best_cost().expect("a path")
        };
        let (rrt, star, informed) = (
            run(Planner::Rrt),
            run(Planner::RrtStar),
            run(Planner::InformedRrtStar),
        );
        let straight = 96.0 * std::f64::consts::SQRT_2 - 1.0;
        assert!(star < rrt, "RRT* {star} vs RRT {rrt}");
        assert!(informed < rrt, "Informed {informed} vs RRT {rrt}");
        assert!(star >= straight && informed >= straight);
        // RRT* gets within a few percent of the straight-line bound.
        assert!(star < 1.1 * straight, "{star}");
    }

    #[test]
    fn informed_samples_stay_in_the_ellipse_and_bounds() {
        let mut t = planner(Planner::InformedRrtStar, 2);
        let c = 80.0;
        for _ in 0..2000 {
            if let Some(p) = t.sample_informed(c) {
                assert!(t.world().in_bounds(p));
                assert!((p - t.start).length() + (p - t.goal).length() <= c + 1e-9);
            }
        }
        // A bound below the straight line has no informed set.
        assert_eq!(t.sample_informed(10.0), None);
    }

    #[test]
    fn radius_shrinks_and_is_capped_by_eta() {
        let t = planner(Planner::RrtStar, 1);
        assert_eq!(t.radius(1), 0.0);
        assert_eq!(t.radius(10), t.config().step_eta);
        let (r1, r2) = (t.radius(100_000), t.radius(1_000_000));
        assert!(r2 < r1 && r1 < t.config().step_eta);
        let expected = t.gamma() * (crate::math::ln(1e5) / 1e5).sqrt();
        assert!((r1 - expected).abs() < 1e-12);
    }

    #[test]
    fn bad_settings_and_ends_are_errors() {
        let w = mixed_world();
        let ok = RrtConfig::default();
        let (s, g) = (DVec2::new(5.0, 5.0), DVec2::new(55.0, 55.0));
        let cases = [
            (
                RrtConfig {
                    step_eta: 0.0,
                    ..ok
                },
                "step_eta",
            ),
            (
                RrtConfig {
                    step_eta: f64::NAN,
                    ..ok
                },
                "step_eta",
            ),
            (
                RrtConfig {
                    goal_bias: 1.5,
                    ..ok
                },
                "goal_bias",
            ),
            (
                RrtConfig {
                    check_resolution: -1.0,
                    ..ok
                },
                "check_resolution",
            ),
            (
                RrtConfig {
                    goal_radius: f64::INFINITY,
                    ..ok
                },
                "goal_radius",
            ),
            (
                RrtConfig {
                    gamma: Some(0.0),
                    ..ok
                },
                "gamma",
            ),
            (RrtConfig { max_nodes: 0, ..ok }, "max_nodes"),
        ];
        for (cfg, field) in cases {
            assert_eq!(
                RrtStar::new(w.clone(), s, g, cfg).err(),
                Some(RrtError::InvalidConfig { field })
            );
        }
        assert_eq!(
            RrtStar::new(w.clone(), DVec2::new(22.0, 10.0), g, ok).err(),
            Some(RrtError::StartNotFree)
        );
        assert_eq!(
            RrtStar::new(w.clone(), s, DVec2::new(f64::NAN, 1.0), ok).err(),
            Some(RrtError::GoalNotFree)
        );
        assert_eq!(
            RrtStar::new(w, s, DVec2::new(61.0, 1.0), ok).err(),
            Some(RrtError::GoalNotFree)
        );
    }

    #[test]
    fn max_nodes_stops_growth_and_start_in_goal_is_a_path() {
        let mut t = RrtStar::new(
            mixed_world(),
            DVec2::new(5.0, 5.0),
            DVec2::new(5.5, 5.0),
            RrtConfig {
                max_nodes: 50,
                ..RrtConfig::default()
            },
        )
        .unwrap();
        assert_eq!(t.best_cost(), Some(0.0));
        assert_eq!(t.best_path(), Some(vec![DVec2::new(5.0, 5.0)]));
        t.iterate(10_000);
        assert_eq!(t.len(), 50);
        assert_eq!(t.step(), IterationOutcome::Full);
        assert_eq!(t.best_cost(), Some(0.0));
    }

    #[test]
    fn plain_rrt_never_rewires_and_reports_the_radius_zero() {
        let mut t = planner(Planner::Rrt, 4);
        t.iterate(2000);
        assert_eq!(t.rewire_count(), 0);
        assert_eq!(t.last_radius(), 0.0);
        // Each node hangs from the node that was nearest when it was added:
        // its edge is at most η long.
        let pts = t.nodes();
        for i in 1..t.len() {
            let p = t.parent(i).unwrap();
            assert!((pts[i] - pts[p]).length() <= t.config().step_eta + 1e-12);
        }
    }

    #[test]
    fn batch_rewires_collect_the_iterations() {
        let mut t = planner(Planner::RrtStar, 6);
        t.iterate(500);
        let before = t.rewire_count();
        t.iterate(300);
        assert_eq!(t.rewired_in_last_batch().len(), t.rewire_count() - before);
        assert!(t.last_radius() > 0.0 && t.newest().is_some());
    }
}
