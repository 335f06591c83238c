//! Experiment 10 — RRT* among circle and rectangle obstacles.
//!
//! *Grow tree* runs [`RrtStar::iterate`] for a fixed number of iterations per
//! fixed time step (the *Iterations per frame* setting; no clock inside), up
//! to an iteration budget. Each iteration samples `x_rand` (the goal with
//! probability *goal bias*), steers from the nearest node by at most `η`,
//!
//! ```text
//! x_new = x_near + min(η, |x_rand − x_near|) · (x_rand − x_near) / |x_rand − x_near|
//! ```
//!
//! and, for RRT*, chooses the cheapest parent and rewires within
//!
//! ```text
//! r = min(γ · (log n / n)^(1/d), η),   d = 2
//! ```
//!
//! (LaValle, TR 98-11, 1998; Karaman & Frazzoli, *IJRR* 30(7), 2011; Gammell,
//! Srinivasa & Barfoot, *IROS* 2014 for the informed variant). The scene draws
//! the whole tree as one batch of segments, the edges rewired during the last
//! frame as a second, flashing batch, the rewiring radius around the newest
//! node and the best path in amber. *Compare* grows RRT, RRT* and Informed
//! RRT* from the same seed side by side and overlays their best-cost curves.
//!
//! **The link** holds every parameter, the start and goal (snapped to 1 cm)
//! and the obstacles as text (key `obs`, see [`encode_obstacles`]).

use crate::experiment::{
    check_param, ActionSpec, Experiment, Input, Modifiers, Notices, ParamError, ParamSpec,
    Sanitized, Tone,
};
use crate::planning::drive_path::DrivePath;
use crate::planning::rrt_star::{Planner, RrtConfig, RrtError, RrtStar};
use crate::planning::world::{Obstacle, World};
use crate::plot::{Plot, Series, SeriesRole};
use crate::quiz::{Draw, Generator};
use crate::rng::Lcg64;
use crate::scene::{Role, SegmentLayer};
use crate::units::format_number;
use glam::DVec2;

/// The field, metres.
pub const FIELD_M: DVec2 = DVec2::new(10.0, 6.0);
/// Radius of the goal disc, metres.
pub const GOAL_RADIUS_M: f64 = 0.25;
/// Spacing of edge collision checks, metres.
pub const CHECK_RESOLUTION_M: f64 = 0.02;
/// Radius of an obstacle added by a click, metres.
pub const NEW_OBSTACLE_RADIUS_M: f64 = 0.4;
/// The most obstacles the field holds.
pub const MAX_OBSTACLES: usize = 40;
/// The robot's speed along the path, m/s.
const DRIVE_SPEED: f64 = 1.2;
/// Pick-up distance of the start and goal markers, metres.
const HANDLE_M: f64 = 0.25;
/// Obstacle coordinates in a link are read within ±this many centimetres.
const LINK_CM_LIMIT: i64 = 100_000;
/// The notice posted when a change of the field or of a setting drops the tree.
pub const CLEARED_NOTICE: &str = "field or settings changed: the tree was cleared, grow it again";

const PLANNERS: &[&str] = &["RRT", "RRT*", "Informed RRT*"];
const PLANNER_KINDS: [Planner; 3] = [Planner::Rrt, Planner::RrtStar, Planner::InformedRrtStar];

const PARAMS: &[ParamSpec] = &[
    ParamSpec::choice("planner", "Planner", PLANNERS, 1),
    ParamSpec::slider("eta", "Step η", "m", 0.1, 2.0, 0.05, 0.5),
    ParamSpec::slider("bias", "Goal bias", "%", 0.0, 50.0, 1.0, 8.0),
    ParamSpec::number("seed", "Seed", 0.0, 999_999.0, 1.0),
    ParamSpec::slider("batch", "Iterations per frame", "/f", 1.0, 400.0, 1.0, 24.0).whole_numbers(),
    ParamSpec::slider(
        "iters",
        "Iteration budget",
        "",
        500.0,
        20000.0,
        500.0,
        4000.0,
    )
    .whole_numbers(),
    ParamSpec::optional_number("sx", "Start x", "m", 0.0, FIELD_M.x),
    ParamSpec::optional_number("sy", "Start y", "m", 0.0, FIELD_M.y),
    ParamSpec::optional_number("gx", "Goal x", "m", 0.0, FIELD_M.x),
    ParamSpec::optional_number("gy", "Goal y", "m", 0.0, FIELD_M.y),
];

const ACTIONS: &[ActionSpec] = &[
    ActionSpec {
        key: "grow",
        label: "Grow tree",
    },
    ActionSpec {
        key: "compare",
        label: "Compare",
    },
    ActionSpec {
        key: "drive",
        label: "Drive path",
    },
    ActionSpec {
        key: "clear",
        label: "Clear obstacles",
    },
    ActionSpec {
        key: "field",
        label: "Default field",
    },
];

const DEFAULT_START: DVec2 = DVec2::new(0.8, 3.0);
const DEFAULT_GOAL: DVec2 = DVec2::new(9.2, 3.0);

/// The default obstacle field: a wall with a gap, discs and a block.
#[must_use]
pub fn default_obstacles() -> Vec<Obstacle> {
    let c = |x, y, r| Obstacle::Circle {
        center: DVec2::new(x, y),
        radius: r,
    };
    let r = |x0, y0, x1, y1| Obstacle::rect(DVec2::new(x0, y0), DVec2::new(x1, y1));
    vec![
        c(2.8, 3.6, 0.9),
        r(1.8, 0.6, 2.6, 1.8),
        r(4.6, 0.0, 5.3, 2.6),
        r(4.6, 3.6, 5.3, 6.0),
        c(7.2, 1.9, 0.8),
        c(7.3, 4.5, 0.7),
    ]
}

/// Rounds to whole centimetres, so a state always equals its link.
fn cm(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

fn cm_vec(p: DVec2) -> DVec2 {
    DVec2::new(cm(p.x), cm(p.y))
}

/// The obstacles as link text: `c<x>_<y>_<r>` and `r<x0>_<y0>_<x1>_<y1>` in
/// whole centimetres, joined by `~` (all URL-unreserved); `none` for none.
///
/// # Example
/// ```
/// use labcore::glam::DVec2;
/// use labcore::experiments::rrtstar::{decode_obstacles, encode_obstacles};
/// use labcore::planning::world::Obstacle;
/// let obs = vec![
///     Obstacle::Circle { center: DVec2::new(2.5, 3.0), radius: 0.6 },
///     Obstacle::rect(DVec2::new(4.0, 1.0), DVec2::new(4.8, 3.5)),
/// ];
/// assert_eq!(encode_obstacles(&obs), "c250_300_60~r400_100_480_350");
/// assert_eq!(decode_obstacles("c250_300_60~r400_100_480_350").unwrap(), obs);
/// assert!(decode_obstacles("c1_2").is_err());
/// ```
#[must_use]
pub fn encode_obstacles(obstacles: &[Obstacle]) -> String {
    if obstacles.is_empty() {
        return "none".into();
    }
    let n = |v: f64| format!("{}", (v * 100.0).round() as i64);
    obstacles
        .iter()
        .map(|o| match *o {
            Obstacle::Circle { center, radius } => {
                format!("c{}_{}_{}", n(center.x), n(center.y), n(radius))
            }
            Obstacle::Rect { min, max } => {
                format!("r{}_{}_{}_{}", n(min.x), n(min.y), n(max.x), n(max.y))
            }
        })
        .collect::<Vec<_>>()
        .join("~")
}

/// Reads [`encode_obstacles`]' text.
///
/// # Errors
/// A message naming the first obstacle that could not be read.
pub fn decode_obstacles(text: &str) -> Result<Vec<Obstacle>, String> {
    if text == "none" {
        return Ok(Vec::new());
    }
    let mut out = Vec::new();
    for (i, item) in text.split('~').enumerate() {
        let bad = || {
            format!(
                "obstacle {} (“{}”) is not c<x>_<y>_<r> or r<x0>_<y0>_<x1>_<y1> in cm",
                i + 1,
                item.chars().take(30).collect::<String>()
            )
        };
        let mut chars = item.chars();
        let kind = chars.next().ok_or_else(bad)?;
        let numbers: Vec<i64> = chars
            .as_str()
            .split('_')
            .map(|s| {
                // A range test, not `abs()`: |i64::MIN| overflows.
                s.parse::<i64>()
                    .ok()
                    .filter(|v| (-LINK_CM_LIMIT..=LINK_CM_LIMIT).contains(v))
            })
            .collect::<Option<Vec<_>>>()
            .ok_or_else(bad)?;
        let m = |v: i64| v as f64 / 100.0;
        let o = match (kind, numbers.as_slice()) {
            ('c', &[x, y, r]) if r > 0 => Obstacle::Circle {
                center: DVec2::new(m(x), m(y)),
                radius: m(r),
            },
            ('r', &[x0, y0, x1, y1]) if x0 <= x1 && y0 <= y1 => Obstacle::Rect {
                min: DVec2::new(m(x0), m(y0)),
                max: DVec2::new(m(x1), m(y1)),
            },
            _ => return Err(bad()),
        };
        out.push(o);
        if out.len() > MAX_OBSTACLES {
            return Err(format!("at most {MAX_OBSTACLES} obstacles"));
        }
    }
    Ok(out)
}

/// What a pointer drag moves.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Drag {
    None,
    Start,
    Goal,
    /// Obstacle `index`, grabbed at `grab` (world) when its reference point
    /// (centre or min corner) was at `origin`.
    Obstacle {
        index: usize,
        grab: DVec2,
        origin: DVec2,
    },
}

/// One planner's tree in the current run. A copy (a timeline snapshot)
/// takes its own edge layer ([`SegmentLayer::detached`]), so the run it was
/// taken from keeps its layer's identity and the page keeps drawing only new
/// and rewired edges.
#[derive(Debug)]
struct Run {
    planner: Planner,
    tree: RrtStar,
    /// The tree's edges as the page draws them: slot `i` holds node `i + 1`'s
    /// edge from its parent. Kept in step with `tree` by [`Run::grow`], so the
    /// page strokes only new and rewired edges each frame.
    edges: SegmentLayer,
}

impl Clone for Run {
    fn clone(&self) -> Self {
        Self {
            planner: self.planner,
            tree: self.tree.clone(),
            edges: self.edges.detached(),
        }
    }
}

impl Run {
    fn new(planner: Planner, tree: RrtStar) -> Self {
        let mut run = Self {
            planner,
            tree,
            edges: SegmentLayer::new(),
        };
        run.sync_edges();
        run
    }

    /// Node `node`'s edge from its parent (a point at the root).
    fn edge(&self, node: usize) -> (DVec2, DVec2) {
        let nodes = self.tree.nodes();
        let parent = self.tree.parent(node).unwrap_or(node);
        (nodes[parent], nodes[node])
    }

    /// Runs `n` iterations and brings the edge layer up to date.
    fn grow(&mut self, n: usize) {
        self.tree.iterate(n);
        self.sync_edges();
    }

    /// Rewrites the drawn slots of the nodes rewired by the last batch (a
    /// node keeps its slot, only its parent moved), then appends the edges of
    /// the nodes added since. The layer's journal carries the rewrites to the
    /// page, which erases the old edges and draws the new ones, so a rewire
    /// never forces a redraw of the whole tree. Cost: the batch's new and
    /// rewired nodes, independent of the tree's size.
    fn sync_edges(&mut self) {
        let drawn = self.edges.len();
        let rewired: Vec<usize> = self
            .tree
            .rewired_in_last_batch()
            .iter()
            .map(|&i| i as usize)
            .filter(|&i| i >= 1 && i - 1 < drawn)
            .collect();
        for i in rewired {
            let e = self.edge(i);
            self.edges.set(i - 1, e);
        }
        for i in drawn + 1..self.tree.len() {
            let e = self.edge(i);
            self.edges.push(e);
        }
    }

    /// Every edge computed from the tree (tests compare the layer with it).
    #[cfg(test)]
    fn all_edges(&self) -> Vec<(DVec2, DVec2)> {
        (1..self.tree.len()).map(|i| self.edge(i)).collect()
    }
}

/// State of the RRT* experiment.
#[derive(Clone, Debug)]
pub struct RrtStarField {
    planner: Planner,
    eta_m: f64,
    bias_percent: f64,
    seed: u64,
    batch: usize,
    budget: usize,
    start: DVec2,
    goal: DVec2,
    obstacles: Vec<Obstacle>,
    /// The trees of the current run: one (*Grow tree*) or three (*Compare*).
    runs: Vec<Run>,
    growing: bool,
    /// Why the last run could not start.
    error: Option<RrtError>,
    /// Distance driven along the frozen path, metres.
    driven_m: Option<f64>,
    /// The path frozen for driving, with its arc length.
    drive_path: DrivePath,
    drag: Drag,
    /// Which handle arrow keys move (the one grabbed last).
    nudge: Drag,
    /// Transient messages (the tree was cleared, nothing to drive yet),
    /// shown under the status, never in its place.
    notices: Notices,
    plots: [Plot; 1],
}

fn series_role(p: Planner) -> SeriesRole {
    match p {
        Planner::Rrt => SeriesRole::Secondary,
        Planner::RrtStar => SeriesRole::Primary,
        Planner::InformedRrtStar => SeriesRole::Tertiary,
    }
}

fn path_role(p: Planner) -> Role {
    match p {
        Planner::Rrt => Role::Warning,
        Planner::RrtStar => Role::Path,
        Planner::InformedRrtStar => Role::Robot,
    }
}

fn cost_plot(planners: &[Planner]) -> Plot {
    Plot::new(
        "cost",
        "Best path length",
        ("Iteration", ""),
        ("Best length", "m"),
        planners
            .iter()
            .map(|p| Series::new(p.name(), "m", series_role(*p)))
            .collect(),
    )
}

impl Default for RrtStarField {
    fn default() -> Self {
        Self {
            planner: Planner::RrtStar,
            eta_m: PARAMS[1].default,
            bias_percent: PARAMS[2].default,
            seed: PARAMS[3].default as u64,
            batch: PARAMS[4].default as usize,
            budget: PARAMS[5].default as usize,
            start: DEFAULT_START,
            goal: DEFAULT_GOAL,
            obstacles: default_obstacles(),
            runs: Vec::new(),
            growing: false,
            error: None,
            driven_m: None,
            drive_path: DrivePath::default(),
            drag: Drag::None,
            nudge: Drag::Start,
            notices: Notices::default(),
            plots: [cost_plot(&[Planner::RrtStar])],
        }
    }
}

impl RrtStarField {
    /// The planner settings of a run.
    #[must_use]
    pub fn config(&self, planner: Planner) -> RrtConfig {
        RrtConfig {
            planner,
            step_eta: self.eta_m,
            goal_bias: self.bias_percent / 100.0,
            check_resolution: CHECK_RESOLUTION_M,
            goal_radius: GOAL_RADIUS_M,
            gamma: None,
            max_nodes: self.budget + 1,
            seed: self.seed,
        }
    }

    /// The field with the current obstacles.
    ///
    /// # Errors
    /// When an obstacle is invalid (never for obstacles made by the page).
    pub fn world(&self) -> Result<World, String> {
        World::new(DVec2::ZERO, FIELD_M, self.obstacles.clone()).map_err(|e| e.to_string())
    }

    /// The tree shown: the selected planner's, else the first.
    fn shown(&self) -> Option<&RrtStar> {
        self.shown_run().map(|r| &r.tree)
    }

    /// The run shown: the selected planner's, else the first.
    fn shown_run(&self) -> Option<&Run> {
        self.runs
            .iter()
            .find(|r| r.planner == self.planner)
            .or_else(|| self.runs.first())
    }

    /// The best path of the tree shown.
    #[must_use]
    pub fn best_path(&self) -> Option<Vec<DVec2>> {
        self.shown().and_then(RrtStar::best_path)
    }

    /// Starts a run of `planners` from the same seed.
    fn start_run(&mut self, planners: &[Planner]) {
        self.runs.clear();
        self.growing = false;
        self.driven_m = None;
        self.drive_path.clear();
        self.error = None;
        self.notices.clear();
        self.plots = [cost_plot(planners)];
        let world = match self.world() {
            Ok(w) => w,
            Err(e) => {
                self.notices.post(e, Tone::Bad);
                return;
            }
        };
        for &planner in planners {
            match RrtStar::new(world.clone(), self.start, self.goal, self.config(planner)) {
                Ok(tree) => self.runs.push(Run::new(planner, tree)),
                Err(e) => {
                    self.runs.clear();
                    self.error = Some(e);
                    return;
                }
            }
        }
        self.growing = true;
    }

    /// The planners of the current run (to replay it).
    fn run_planners(&self) -> Vec<Planner> {
        self.runs.iter().map(|r| r.planner).collect()
    }

    /// Drops the run after a change of the field or of a planner setting.
    fn invalidate(&mut self) {
        if !self.runs.is_empty() {
            self.notices.post(CLEARED_NOTICE, Tone::Warning);
        }
        self.runs.clear();
        self.growing = false;
        self.error = None;
        self.driven_m = None;
        self.drive_path.clear();
        self.plots = [cost_plot(&[self.planner])];
    }

    fn obstacle_at(&self, p: DVec2, tolerance_m: f64) -> Option<usize> {
        // The topmost (last drawn) first.
        self.obstacles.iter().rposition(|o| match *o {
            Obstacle::Circle { center, radius } => (p - center).length() <= radius + tolerance_m,
            Obstacle::Rect { min, max } => {
                p.x >= min.x - tolerance_m
                    && p.x <= max.x + tolerance_m
                    && p.y >= min.y - tolerance_m
                    && p.y <= max.y + tolerance_m
            }
        })
    }

    /// The obstacle's reference point: the centre of a circle, the min corner of a rectangle.
    fn origin_of(o: &Obstacle) -> DVec2 {
        match *o {
            Obstacle::Circle { center, .. } => center,
            Obstacle::Rect { min, .. } => min,
        }
    }

    fn centre_of(o: &Obstacle) -> DVec2 {
        match *o {
            Obstacle::Circle { center, .. } => center,
            Obstacle::Rect { min, max } => (min + max) * 0.5,
        }
    }

    /// Moves obstacle `i` so its reference point is at `to` (centimetres,
    /// within a metre of the field, so a drag can take it off the field).
    fn move_obstacle(&mut self, i: usize, to: DVec2) {
        let to = cm_vec(to.clamp(DVec2::splat(-1.0), FIELD_M + 1.0));
        let Some(o) = self.obstacles.get_mut(i) else {
            return;
        };
        let moved = match *o {
            Obstacle::Circle { radius, .. } => Obstacle::Circle { center: to, radius },
            Obstacle::Rect { min, max } => Obstacle::Rect {
                min: to,
                max: cm_vec(to + (max - min)),
            },
        };
        if moved != *o {
            *o = moved;
            self.invalidate();
        }
    }

    fn in_field(p: DVec2) -> bool {
        p.x >= 0.0 && p.y >= 0.0 && p.x <= FIELD_M.x && p.y <= FIELD_M.y
    }

    fn clamp_to_field(p: DVec2) -> DVec2 {
        cm_vec(p.clamp(DVec2::ZERO, FIELD_M))
    }

    fn set_start(&mut self, p: DVec2) {
        let p = Self::clamp_to_field(p);
        if p != self.start {
            self.start = p;
            self.invalidate();
        }
    }

    fn set_goal(&mut self, p: DVec2) {
        let p = Self::clamp_to_field(p);
        if p != self.goal {
            self.goal = p;
            self.invalidate();
        }
    }

    fn drive(&mut self) {
        match self.best_path() {
            Some(path) if path.len() >= 2 => {
                self.growing = false;
                self.drive_path = DrivePath::new(path);
                self.driven_m = Some(0.0);
                self.notices.clear();
            }
            _ => self
                .notices
                .post("no path to drive yet: grow the tree first", Tone::Warning),
        }
    }

    fn robot(&self) -> Option<DVec2> {
        self.drive_path.at(self.driven_m?)
    }

    fn drive_length(&self) -> f64 {
        self.drive_path.length_m()
    }

    fn driving(&self) -> bool {
        self.driven_m.is_some_and(|d| d < self.drive_length())
    }
}

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "RRT keeps its first path",
        description: "Plain RRT never rewires: press Grow and its path stays long and crooked.",
        query: "planner=0",
    },
    crate::experiment::Preset {
        name: "RRT* straightens it",
        description: "The same seed with RRT*: rewiring shortens the best path as the tree grows.",
        query: "planner=1",
    },
];

impl Experiment for RrtStarField {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

    fn id(&self) -> &'static str {
        "rrtstar"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        Some(match key {
            "planner" => PLANNER_KINDS
                .iter()
                .position(|p| *p == self.planner)
                .unwrap_or(1) as f64,
            "eta" => self.eta_m,
            "bias" => self.bias_percent,
            "seed" => self.seed as f64,
            "batch" => self.batch as f64,
            "iters" => self.budget as f64,
            "sx" => self.start.x,
            "sy" => self.start.y,
            "gx" => self.goal.x,
            "gy" => self.goal.y,
            _ => return None,
        })
    }

    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let mut applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        match key {
            "planner" => {
                self.planner = PLANNER_KINDS[(v as usize).min(2)];
                self.invalidate();
            }
            "eta" => {
                self.eta_m = v;
                self.invalidate();
            }
            "bias" => {
                self.bias_percent = v;
                self.invalidate();
            }
            "seed" => {
                self.seed = v as u64;
                self.invalidate();
            }
            "batch" => self.batch = v as usize,
            "iters" => {
                self.budget = v as usize;
                self.invalidate();
            }
            "sx" | "sy" | "gx" | "gy" => {
                // Whole centimetres, like a drag.
                let c = cm(v);
                if c != v {
                    applied = Sanitized::Clamped(c);
                }
                let mut p = if key.starts_with('s') {
                    self.start
                } else {
                    self.goal
                };
                if key.ends_with('x') {
                    p.x = c;
                } else {
                    p.y = c;
                }
                if key.starts_with('s') {
                    self.set_start(p);
                } else {
                    self.set_goal(p);
                }
            }
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        Ok(applied)
    }

    fn actions(&self) -> &'static [ActionSpec] {
        ACTIONS
    }

    fn action(&mut self, key: &str) -> Result<(), ParamError> {
        match key {
            "grow" => self.start_run(&[self.planner]),
            "compare" => self.start_run(&PLANNER_KINDS),
            "drive" => self.drive(),
            "clear" => {
                self.obstacles.clear();
                self.invalidate();
            }
            "field" => {
                self.obstacles = default_obstacles();
                self.start = DEFAULT_START;
                self.goal = DEFAULT_GOAL;
                self.invalidate();
            }
            _ => return Err(ParamError::UnknownAction { key: key.into() }),
        }
        Ok(())
    }

    fn input(&mut self, input: Input) {
        self.input_with(input, Modifiers::default());
    }

    /// Shift-click sets the start, Ctrl-click the goal; a press on the
    /// start, the goal or an obstacle drags it; a press on free space adds a
    /// disc there (drag to place it). An obstacle dropped outside the field
    /// is removed. Arrow keys move the handle grabbed last.
    fn input_with(&mut self, input: Input, modifiers: Modifiers) {
        match input {
            Input::PointerDown(p) => {
                self.drag = Drag::None;
                if !p.is_finite() {
                    return;
                }
                if modifiers.shift {
                    self.drag = Drag::Start;
                    self.set_start(p);
                } else if modifiers.ctrl {
                    self.drag = Drag::Goal;
                    self.set_goal(p);
                } else if (p - self.start).length() <= HANDLE_M {
                    self.drag = Drag::Start;
                } else if (p - self.goal).length() <= HANDLE_M {
                    self.drag = Drag::Goal;
                } else if let Some(index) = self.obstacle_at(p, 0.0) {
                    self.drag = Drag::Obstacle {
                        index,
                        grab: p,
                        origin: Self::origin_of(&self.obstacles[index]),
                    };
                } else if Self::in_field(p) {
                    if self.obstacles.len() >= MAX_OBSTACLES {
                        self.notices.post(
                            format!("the field holds at most {MAX_OBSTACLES} obstacles"),
                            Tone::Warning,
                        );
                        return;
                    }
                    let center = cm_vec(p);
                    self.obstacles.push(Obstacle::Circle {
                        center,
                        radius: NEW_OBSTACLE_RADIUS_M,
                    });
                    self.invalidate();
                    self.drag = Drag::Obstacle {
                        index: self.obstacles.len() - 1,
                        grab: center,
                        origin: center,
                    };
                }
                if self.drag != Drag::None {
                    self.nudge = self.drag;
                }
            }
            Input::PointerMove { pos, pressed: true } if pos.is_finite() => match self.drag {
                Drag::Start => self.set_start(pos),
                Drag::Goal => self.set_goal(pos),
                Drag::Obstacle {
                    index,
                    grab,
                    origin,
                } => self.move_obstacle(index, origin + (pos - grab)),
                Drag::None => {}
            },
            Input::PointerMove { .. } => {}
            Input::PointerUp(_) => {
                if let Drag::Obstacle { index, .. } = self.drag {
                    let off = self
                        .obstacles
                        .get(index)
                        .is_some_and(|o| !Self::in_field(Self::centre_of(o)));
                    if off {
                        self.obstacles.remove(index);
                        self.nudge = Drag::Start;
                        self.invalidate();
                    }
                }
                self.drag = Drag::None;
            }
            Input::Nudge(d) => {
                if !d.is_finite() {
                    return;
                }
                match self.nudge {
                    Drag::Goal => self.set_goal(self.goal + d),
                    Drag::Obstacle { index, .. } => {
                        if let Some(o) = self.obstacles.get(index) {
                            let to = Self::origin_of(o) + d;
                            self.move_obstacle(index, to);
                        }
                    }
                    _ => self.set_start(self.start + d),
                }
            }
        }
    }

    fn step(&mut self, dt_s: f64) {
        if !crate::clock::valid_dt(dt_s) {
            return;
        }
        if self.growing {
            let (batch, budget) = (self.batch, self.budget);
            let mut all_done = true;
            for (i, run) in self.runs.iter_mut().enumerate() {
                let left = budget.saturating_sub(run.tree.iterations());
                if left == 0 {
                    continue;
                }
                run.grow(batch.min(left));
                if let Some(c) = run.tree.best_cost() {
                    if let Some(s) = self.plots[0].series.get_mut(i) {
                        s.push(run.tree.iterations() as f64, c);
                    }
                }
                if run.tree.iterations() < budget && run.tree.len() < budget + 1 {
                    all_done = false;
                }
            }
            self.plots[0].touch();
            if all_done {
                self.growing = false;
            }
        } else if let Some(d) = self.driven_m {
            let length = self.drive_length();
            self.driven_m = Some((d + DRIVE_SPEED * dt_s).min(length));
        }
    }

    fn animated(&self) -> bool {
        true
    }

    /// Regrows the current run from its first iteration (same seed, same trees).
    fn reset(&mut self) {
        let planners = self.run_planners();
        if !planners.is_empty() {
            self.start_run(&planners);
        }
    }

    fn plots(&self) -> &[Plot] {
        &self.plots
    }

    /// The start, the goal and the obstacles (`o1`…, by centre).
    fn handles(&self) -> Vec<crate::experiment::Handle> {
        use crate::experiment::Handle as H;
        let mut out = vec![
            H::new("start", "Start", self.start),
            H::new("goal", "Goal", self.goal),
        ];
        for (i, o) in self.obstacles.iter().enumerate() {
            out.push(H::new(
                format!("o{}", i + 1),
                format!("Obstacle {}", i + 1),
                Self::centre_of(o),
            ));
        }
        out
    }

    /// A drag of handle `id`: grabbed by name (where the start or goal
    /// overlaps an obstacle, a press there would take them), moved so its
    /// centre is at `to`, released (an obstacle left off the field goes, as
    /// after a pointer drag).
    fn move_handle(&mut self, id: &str, to: DVec2) -> bool {
        let drag = match id {
            "start" => Drag::Start,
            "goal" => Drag::Goal,
            _ => {
                match crate::experiment::point_slot(&format!("{id}x"), 'o', self.obstacles.len()) {
                    Some((index, _)) => {
                        let o = &self.obstacles[index];
                        Drag::Obstacle {
                            index,
                            grab: Self::centre_of(o),
                            origin: Self::origin_of(o),
                        }
                    }
                    None => return false,
                }
            }
        };
        if !to.is_finite() {
            return false;
        }
        self.drag = drag;
        self.nudge = drag;
        crate::experiment::finish_drag(self, to)
    }

    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        let tol = tolerance_m.max(HANDLE_M);
        (p - self.start).length() <= tol
            || (p - self.goal).length() <= tol
            || self.obstacle_at(p, tolerance_m.max(0.0)).is_some()
    }
    fn extra_state(&self) -> Vec<(&'static str, String)> {
        vec![("obs", encode_obstacles(&self.obstacles))]
    }

    fn set_extra_state(&mut self, key: &str, value: &str) -> Result<(), ParamError> {
        if key != "obs" {
            return Err(ParamError::UnknownKey { key: key.into() });
        }
        let obstacles = decode_obstacles(value).map_err(|reason| ParamError::BadText {
            key: key.into(),
            reason,
        })?;
        if obstacles != self.obstacles {
            self.obstacles = obstacles;
            self.invalidate();
        }
        Ok(())
    }

    /// Each run's tree (nodes, their index, the world) and the edge layer
    /// the page draws, the obstacles, the path driven, with the plot.
    fn state_bytes(&self) -> usize {
        use std::mem::size_of;
        let runs: usize = self
            .runs
            .iter()
            .map(|r| r.tree.heap_bytes() + r.edges.heap_bytes())
            .sum();
        runs + self.runs.capacity() * size_of::<Run>()
            + self.obstacles.capacity() * size_of::<Obstacle>()
            + self.drive_path.heap_bytes()
            + crate::plot::plots_bytes(&self.plots)
    }

    /// A step grows a batch of iterations.
    fn step_weight(&self) -> u64 {
        self.batch as u64
    }

    fn animating(&self) -> bool {
        self.growing || self.driving()
    }
}

mod quiz;
mod view;
pub use quiz::quiz_generator;

#[cfg(test)]
mod tests;
