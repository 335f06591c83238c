//! A* on an occupancy grid, step by step: A*, Dijkstra, weighted A* and greedy
//! best-first search with one engine.
//!
//! **A\*** (Hart, Nilsson & Raphael, "A Formal Basis for the Heuristic
//! Determination of Minimum Cost Paths", *IEEE Trans. Systems Science and
//! Cybernetics* 4(2), 1968, pp. 100–107) repeatedly removes from the open list
//! the cell with the smallest
//!
//! ```text
//! f(n) = g(n) + h(n)
//! ```
//!
//! where `g(n)` is the cheapest cost from the start found so far and `h(n)` a
//! [`Heuristic`] estimate of the cost to the goal, closes it, and relaxes its
//! neighbours (`g(m) ← g(n) + c(n, m)` when that is lower). It stops when the
//! goal is removed. With a consistent heuristic (every admissible one of
//! [`Heuristic`]) the path is optimal and no closed cell is ever improved
//! (*ibid.*, Theorems 1 and 3). Moves follow the grid's rule
//! ([`OccupancyGrid::neighbours`]): orthogonal cost 1, diagonal `√2`, no corner
//! cutting.
//!
//! The [`Strategy`] changes only the priority:
//!
//! | strategy | priority `f` | guarantee |
//! |---|---|---|
//! | [`Strategy::AStar`] | `g + h` | optimal with an admissible `h` |
//! | A* with [`Heuristic::Zero`] | `g` | Dijkstra's algorithm (Dijkstra, *Numer. Math.* 1, 1959, pp. 269–271) |
//! | [`Strategy::Weighted`] | `g + w · h`, `w ≥ 1` | cost `≤ w ·` optimum (Pohl, "Heuristic search viewed as path finding in a graph", *Artificial Intelligence* 1(3), 1970, pp. 193–204) |
//! | [`Strategy::Greedy`] | `h` | finds a path if one exists; no bound on its cost |
//!
//! A cell is closed once and never reopened (for weighted A* with a consistent
//! `h` the bound `w ·` optimum still holds without reopening: Likhachev, Gordon
//! & Thrun, "ARA*", *NIPS* 2003, Theorem 1).
//!
//! **Ties** break the same way every time: the smallest `f` first; among equal
//! `f` the larger `g` (the cell nearer the goal, so straight corridors are not
//! explored sideways; `g` is compared in single precision, which is plenty
//! for a tie-break); among equal `f` and `g` the smaller cell index
//! `y · width + x`.
//!
//! **Step by step.** [`Search::step`] removes and expands exactly one cell and
//! says which ([`StepOutcome::Expanded`]), or that the search ended
//! ([`StepOutcome::Found`], [`StepOutcome::NoPath`]); it is cheap to call a
//! few hundred times per animation frame. [`Search::run`] goes to the end.
//! Between steps the page can read each cell's [`CellState`] as one raster
//! ([`Search::write_cell_states`]), the head of the open list with `g`, `h`
//! and `f` ([`Search::open_top`]), and the counters.
//!
//! **Speed.** The grid is copied once into a flat byte array with a one-cell
//! blocked border (no bounds tests while expanding); each cell's `g`, parent
//! and state sit together in one 16-byte record; the open list is a binary heap
//! of single `u128` keys packing `f`, `g` and the cell index (IEEE bit patterns
//! order like the numbers for values `≥ 0`), one integer comparison per heap
//! step, with lazy deletion of outdated entries. Cell states are stamped with
//! a search generation, so [`Search::reset`] (new grid) and
//! [`Search::restart`] (same grid, e.g. the page's comparison of strategies)
//! start a new search on a reused `Search` without clearing a million
//! records. On the benchmark of `shared/BENCHMARKS.md` this expands about
//! twice as many cells per second as the `pathfinding` crate's `astar`.

use std::collections::BinaryHeap;
use std::fmt;

use super::grid::{Cell, Connectivity, OccupancyGrid, DIAGONAL_COST};
use super::heuristic::Heuristic;

/// How the priority of an open cell is formed (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Strategy {
    /// `f = g + h` (with [`Heuristic::Zero`]: Dijkstra).
    #[default]
    AStar,
    /// `f = g + w · h` with a finite `w ≥ 1` (Pohl 1970): cost within `w ×` optimum.
    Weighted { weight: f64 },
    /// `f = h`: greedy best-first search.
    Greedy,
}

/// Everything that selects a search variant.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SearchConfig {
    /// 4- or 8-connected moves.
    pub connectivity: Connectivity,
    /// The estimate `h`.
    pub heuristic: Heuristic,
    /// How `g` and `h` form the priority.
    pub strategy: Strategy,
}

impl SearchConfig {
    /// A* with `heuristic`.
    #[must_use]
    pub fn astar(connectivity: Connectivity, heuristic: Heuristic) -> Self {
        Self {
            connectivity,
            heuristic,
            strategy: Strategy::AStar,
        }
    }

    /// Dijkstra's algorithm: A* with [`Heuristic::Zero`].
    #[must_use]
    pub fn dijkstra(connectivity: Connectivity) -> Self {
        Self::astar(connectivity, Heuristic::Zero)
    }

    /// Weighted A*, `f = g + weight · h`.
    #[must_use]
    pub fn weighted(connectivity: Connectivity, heuristic: Heuristic, weight: f64) -> Self {
        Self {
            connectivity,
            heuristic,
            strategy: Strategy::Weighted { weight },
        }
    }

    /// Greedy best-first search, `f = h`.
    #[must_use]
    pub fn greedy(connectivity: Connectivity, heuristic: Heuristic) -> Self {
        Self {
            connectivity,
            heuristic,
            strategy: Strategy::Greedy,
        }
    }

    /// The factors `(a, b)` of the priority `f = a · g + b · h`, or the error
    /// for a weight that is below 1, NaN or infinite.
    fn priority_factors(&self) -> Result<(f64, f64), SearchError> {
        match self.strategy {
            Strategy::AStar => Ok((1.0, 1.0)),
            Strategy::Weighted { weight } if weight.is_finite() && weight >= 1.0 => {
                Ok((1.0, weight))
            }
            Strategy::Weighted { weight } => Err(SearchError::InvalidWeight { weight }),
            Strategy::Greedy => Ok((0.0, 1.0)),
        }
    }
}

/// Why a search could not start. The search (when reset) is left as it was.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SearchError {
    /// The start cell lies outside the grid.
    StartOutOfBounds { cell: Cell },
    /// The goal cell lies outside the grid.
    GoalOutOfBounds { cell: Cell },
    /// The start cell is a wall.
    StartBlocked { cell: Cell },
    /// The goal cell is a wall.
    GoalBlocked { cell: Cell },
    /// A weighted-A* weight below 1, NaN or infinite.
    InvalidWeight { weight: f64 },
}

impl fmt::Display for SearchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::StartOutOfBounds { cell } => write!(f, "the start {cell} is outside the grid"),
            Self::GoalOutOfBounds { cell } => write!(f, "the goal {cell} is outside the grid"),
            Self::StartBlocked { cell } => write!(f, "the start {cell} is inside a wall"),
            Self::GoalBlocked { cell } => write!(f, "the goal {cell} is inside a wall"),
            Self::InvalidWeight { weight } => {
                write!(f, "the weight must be a finite number ≥ 1 (got {weight})")
            }
        }
    }
}

impl std::error::Error for SearchError {}

/// What one [`Search::step`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepOutcome {
    /// `cell` was removed from the open list, closed, and its neighbours relaxed.
    Expanded { cell: Cell },
    /// The goal was removed from the open list: [`Search::result`] holds the path.
    Found,
    /// The open list is empty: the goal cannot be reached.
    NoPath,
}

/// Where a search stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SearchStatus {
    /// Cells are still open.
    Searching,
    /// The goal was reached; the result is available.
    Found,
    /// Every reachable cell was closed without reaching the goal.
    NoPath,
}

/// A cell as the page paints it; `as u8` gives the raster value of
/// [`Search::write_cell_states`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum CellState {
    /// Free, never reached.
    Unseen = 0,
    /// On the open list (the frontier).
    Open = 1,
    /// Expanded (the closed set).
    Closed = 2,
    /// On the found path (start and goal included).
    Path = 3,
    /// A wall.
    Blocked = 4,
}

/// A finished search's answer.
#[derive(Clone, Debug, PartialEq)]
pub struct PathResult {
    /// From start to goal, both included.
    pub path: Vec<Cell>,
    /// Sum of the move costs along `path` (1 per orthogonal move, `√2` per diagonal).
    pub cost: f64,
    /// Cells expanded (closed), the goal included.
    pub expanded: usize,
}

/// One entry of the open list as [`Search::open_top`] reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenEntry {
    pub cell: Cell,
    /// Cost from the start along the best path found so far.
    pub g: f64,
    /// The heuristic estimate to the goal, unweighted.
    pub h: f64,
    /// The priority the open list is ordered by (`g + h`, `g + w·h` or `h`).
    pub f: f64,
}

/// Per-cell record: cost so far, parent (padded index, `NONE` for the start)
/// and the stamp that says whether the cell is unseen, open or closed in the
/// current search.
#[derive(Clone, Copy, Debug)]
struct Node {
    g: f64,
    parent: u32,
    stamp: u32,
}

const NONE: u32 = u32::MAX;

/// Open-list key packed into one `u128`; `BinaryHeap` pops the largest, so
/// each part is stored such that "larger" means "first":
///
/// ```text
/// bits 127..64: !f.to_bits()      smaller f first (for x ≥ 0, x.to_bits() orders like x)
/// bits  63..32: (g as f32).to_bits()  larger g first
/// bits  31..0 : !index            smaller cell index first
/// ```
///
/// `f` is kept exactly; `g` only breaks ties, so single precision is enough
/// (two equal-`f` cells whose `g` agree to 24 bits fall back on the index).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct HeapEntry(u128);

impl HeapEntry {
    #[inline]
    fn new(f: f64, g: f64, index: u32) -> Self {
        Self(
            (u128::from(!f.to_bits()) << 64)
                | (u128::from((g as f32).to_bits()) << 32)
                | u128::from(!index),
        )
    }
    #[inline]
    fn index(self) -> usize {
        !(self.0 as u32) as usize
    }
    #[inline]
    fn f(self) -> f64 {
        f64::from_bits(!((self.0 >> 64) as u64))
    }
}

/// An incremental grid search (see the module docs). Owns a copy of the grid
/// taken at [`Search::new`] / [`Search::reset`]: editing the grid afterwards
/// does not affect a running search.
#[derive(Clone, Debug)]
pub struct Search {
    width: usize,
    height: usize,
    /// `width + 2`: rows of the padded arrays.
    pitch: usize,
    /// Padded walls, 1 = blocked, with a blocked one-cell border.
    blocked: Vec<u8>,
    nodes: Vec<Node>,
    /// Current generation: a cell is open when its stamp is `2·gen`, closed at `2·gen + 1`.
    generation: u32,
    heap: BinaryHeap<HeapEntry>,
    config: SearchConfig,
    g_factor: f64,
    h_factor: f64,
    start: Cell,
    goal: Cell,
    start_index: usize,
    goal_index: usize,
    expanded: usize,
    open_count: usize,
    last_expanded: Option<Cell>,
    status: SearchStatus,
    result: Option<PathResult>,
}

impl Search {
    /// The heap the search holds, bytes: its padded grid, its nodes, the
    /// open list and the path found (capacities: what a copy of it costs).
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of;
        self.blocked.capacity()
            + self.nodes.capacity() * size_of::<Node>()
            + self.heap.capacity() * size_of::<HeapEntry>()
            + self
                .result
                .as_ref()
                .map_or(0, |r| r.path.capacity() * size_of::<Cell>())
    }

    /// A search from `start` to `goal` on `grid`, with the start on the open list
    /// and nothing expanded yet.
    ///
    /// # Errors
    /// [`SearchError`] when an end is outside the grid or in a wall, or the weight is invalid.
    ///
    /// # Example
    /// ```
    /// use labcore::planning::astar::{Search, SearchConfig, StepOutcome};
    /// use labcore::planning::grid::{Cell, Connectivity, OccupancyGrid};
    /// use labcore::planning::heuristic::Heuristic;
    /// let grid = OccupancyGrid::from_ascii("
    ///     ....
    ///     .##.
    ///     ....
    /// ").unwrap();
    /// let config = SearchConfig::astar(Connectivity::Eight, Heuristic::Octile);
    /// let mut s = Search::new(&grid, Cell::new(0, 1), Cell::new(3, 1), config).unwrap();
    /// assert_eq!(s.step(), StepOutcome::Expanded { cell: Cell::new(0, 1) });
    /// assert_eq!(s.frontier_len(), 2); // (0, 0) and (0, 2); diagonals would cut the wall
    /// assert_eq!(s.run(), StepOutcome::Found);
    /// let r = s.result().unwrap();
    /// // Over the top: up, three right, down — no diagonal may clip the wall's corners.
    /// assert_eq!(r.cost, 5.0);
    /// assert_eq!(r.path.len(), 6);
    /// ```
    pub fn new(
        grid: &OccupancyGrid,
        start: Cell,
        goal: Cell,
        config: SearchConfig,
    ) -> Result<Self, SearchError> {
        let mut s = Self {
            width: 0,
            height: 0,
            pitch: 0,
            blocked: Vec::new(),
            nodes: Vec::new(),
            generation: 0,
            heap: BinaryHeap::new(),
            config,
            g_factor: 1.0,
            h_factor: 1.0,
            start,
            goal,
            start_index: 0,
            goal_index: 0,
            expanded: 0,
            open_count: 0,
            last_expanded: None,
            status: SearchStatus::NoPath,
            result: None,
        };
        s.reset(grid, start, goal, config)?;
        Ok(s)
    }

    /// Starts a new search, reusing this one's memory: the per-cell records
    /// are not cleared (their generation stamps go stale), only the grid is
    /// copied. On error nothing changes.
    ///
    /// # Errors
    /// As [`Search::new`].
    pub fn reset(
        &mut self,
        grid: &OccupancyGrid,
        start: Cell,
        goal: Cell,
        config: SearchConfig,
    ) -> Result<(), SearchError> {
        if !grid.in_bounds(start) {
            return Err(SearchError::StartOutOfBounds { cell: start });
        }
        if !grid.in_bounds(goal) {
            return Err(SearchError::GoalOutOfBounds { cell: goal });
        }
        if grid.is_blocked(start) {
            return Err(SearchError::StartBlocked { cell: start });
        }
        if grid.is_blocked(goal) {
            return Err(SearchError::GoalBlocked { cell: goal });
        }
        config.priority_factors()?;

        let (w, h) = (grid.width(), grid.height());
        let pitch = w + 2;
        let padded = pitch * (h + 2);
        self.blocked.clear();
        self.blocked.resize(padded, 1);
        for (y, row) in grid.cells().chunks(w).enumerate() {
            let at = (y + 1) * pitch + 1;
            for (dst, &b) in self.blocked[at..at + w].iter_mut().zip(row) {
                *dst = u8::from(b);
            }
        }
        if self.nodes.len() != padded {
            self.nodes.clear();
            self.nodes.resize(
                padded,
                Node {
                    g: 0.0,
                    parent: NONE,
                    stamp: 0,
                },
            );
            self.generation = 0;
        }
        self.width = w;
        self.height = h;
        self.pitch = pitch;
        // Checked above, so this cannot fail.
        self.restart(start, goal, config)
    }

    /// A new search on the grid copy this search already holds (e.g. another
    /// strategy or other ends on the same grid, as the page's comparison does):
    /// like [`Search::reset`] without copying the grid. On error nothing changes.
    ///
    /// # Errors
    /// As [`Search::new`], against the held grid.
    pub fn restart(
        &mut self,
        start: Cell,
        goal: Cell,
        config: SearchConfig,
    ) -> Result<(), SearchError> {
        let (w, h) = (self.width, self.height);
        let inside = |c: Cell| c.x < w && c.y < h;
        if !inside(start) {
            return Err(SearchError::StartOutOfBounds { cell: start });
        }
        if !inside(goal) {
            return Err(SearchError::GoalOutOfBounds { cell: goal });
        }
        let pitch = self.pitch;
        let start_index = (start.y + 1) * pitch + start.x + 1;
        let goal_index = (goal.y + 1) * pitch + goal.x + 1;
        if self.blocked[start_index] != 0 {
            return Err(SearchError::StartBlocked { cell: start });
        }
        if self.blocked[goal_index] != 0 {
            return Err(SearchError::GoalBlocked { cell: goal });
        }
        let (g_factor, h_factor) = config.priority_factors()?;
        // Stamps 2·gen and 2·gen + 1 must stay clear of every earlier stamp.
        if self.generation >= u32::MAX / 2 - 1 {
            for n in &mut self.nodes {
                n.stamp = 0;
            }
            self.generation = 0;
        }
        self.generation += 1;
        self.config = config;
        self.g_factor = g_factor;
        self.h_factor = h_factor;
        self.start = start;
        self.goal = goal;
        self.start_index = start_index;
        self.goal_index = goal_index;
        self.expanded = 0;
        self.open_count = 1;
        self.last_expanded = None;
        self.status = SearchStatus::Searching;
        self.result = None;
        self.heap.clear();
        let open = self.open_stamp();
        self.nodes[start_index] = Node {
            g: 0.0,
            parent: NONE,
            stamp: open,
        };
        let f0 = self.h_factor * self.heuristic(start.x + 1, start.y + 1);
        self.heap.push(HeapEntry::new(f0, 0.0, start_index as u32));
        Ok(())
    }

    #[inline]
    fn open_stamp(&self) -> u32 {
        2 * self.generation
    }

    /// `h` of the padded cell `(px, py)`.
    #[inline]
    fn heuristic(&self, px: usize, py: usize) -> f64 {
        let dx = px.abs_diff(self.goal.x + 1) as f64;
        let dy = py.abs_diff(self.goal.y + 1) as f64;
        self.config.heuristic.of_offsets(dx, dy)
    }

    #[inline]
    fn cell_of_padded(&self, i: usize) -> Cell {
        // Padded indices fit in u32 (MAX_CELLS): 32-bit division is faster.
        let (i, p) = (i as u32, self.pitch as u32);
        Cell::new((i % p) as usize - 1, (i / p) as usize - 1)
    }

    #[inline]
    fn padded_of(&self, cell: Cell) -> Option<usize> {
        (cell.x < self.width && cell.y < self.height)
            .then(|| (cell.y + 1) * self.pitch + cell.x + 1)
    }

    /// Removes the best open cell and expands it (module docs); once the search
    /// has ended, returns the same final outcome again.
    pub fn step(&mut self) -> StepOutcome {
        match self.status {
            SearchStatus::Found => return StepOutcome::Found,
            SearchStatus::NoPath => return StepOutcome::NoPath,
            SearchStatus::Searching => {}
        }
        let open = self.open_stamp();
        let closed = open + 1;
        while let Some(entry) = self.heap.pop() {
            let i = entry.index();
            let node = &mut self.nodes[i];
            if node.stamp != open {
                continue; // an outdated duplicate of a closed cell
            }
            node.stamp = closed;
            let g = node.g;
            self.open_count -= 1;
            self.expanded += 1;
            let cell = self.cell_of_padded(i);
            self.last_expanded = Some(cell);
            if i == self.goal_index {
                self.finish(g);
                return StepOutcome::Found;
            }
            self.expand(i, g, cell.x + 1, cell.y + 1);
            return StepOutcome::Expanded { cell };
        }
        self.status = SearchStatus::NoPath;
        self.last_expanded = None;
        StepOutcome::NoPath
    }

    /// Steps until the search ends; returns [`StepOutcome::Found`] or [`StepOutcome::NoPath`].
    pub fn run(&mut self) -> StepOutcome {
        loop {
            match self.step() {
                StepOutcome::Expanded { .. } => {}
                done => return done,
            }
        }
    }

    /// At most `max_steps` steps (for an animation frame), stopping early when
    /// the search ends; returns the last outcome (`None` when `max_steps` is 0).
    pub fn step_n(&mut self, max_steps: usize) -> Option<StepOutcome> {
        let mut last = None;
        for _ in 0..max_steps {
            let out = self.step();
            last = Some(out);
            if !matches!(out, StepOutcome::Expanded { .. }) {
                break;
            }
        }
        last
    }

    /// Relaxes the neighbours of padded cell `i` = `(px, py)` with cost-so-far `g`.
    #[inline(always)]
    fn expand(&mut self, i: usize, g: f64, px: usize, py: usize) {
        let p = self.pitch;
        let b = &self.blocked;
        let (n, s, w, e) = (i - p, i + p, i - 1, i + 1);
        let (fn_, fs, fw, fe) = (b[n] == 0, b[s] == 0, b[w] == 0, b[e] == 0);
        let diagonal = self.config.connectivity == Connectivity::Eight;
        let (nw, ne, sw, se) = (
            diagonal && fn_ && fw && b[n - 1] == 0,
            diagonal && fn_ && fe && b[n + 1] == 0,
            diagonal && fs && fw && b[s - 1] == 0,
            diagonal && fs && fe && b[s + 1] == 0,
        );
        let parent = i as u32;
        let g1 = g + 1.0;
        if fe {
            self.relax(e, g1, parent, px + 1, py);
        }
        if fw {
            self.relax(w, g1, parent, px - 1, py);
        }
        if fs {
            self.relax(s, g1, parent, px, py + 1);
        }
        if fn_ {
            self.relax(n, g1, parent, px, py - 1);
        }
        let gd = g + DIAGONAL_COST;
        if se {
            self.relax(s + 1, gd, parent, px + 1, py + 1);
        }
        if sw {
            self.relax(s - 1, gd, parent, px - 1, py + 1);
        }
        if ne {
            self.relax(n + 1, gd, parent, px + 1, py - 1);
        }
        if nw {
            self.relax(n - 1, gd, parent, px - 1, py - 1);
        }
    }

    #[inline(always)]
    fn relax(&mut self, j: usize, g: f64, parent: u32, px: usize, py: usize) {
        let open = self.open_stamp();
        let node = &mut self.nodes[j];
        if node.stamp == open {
            if g >= node.g {
                return;
            }
        } else if node.stamp == open + 1 {
            return; // closed: never reopened
        } else {
            self.open_count += 1;
        }
        *node = Node {
            g,
            parent,
            stamp: open,
        };
        let f = self.g_factor * g + self.h_factor * self.heuristic(px, py);
        self.heap.push(HeapEntry::new(f, g, j as u32));
    }

    fn finish(&mut self, cost: f64) {
        let path = self.trace(self.goal_index);
        self.result = Some(PathResult {
            path,
            cost,
            expanded: self.expanded,
        });
        self.status = SearchStatus::Found;
    }

    /// The cells from the start to padded cell `i` along parents.
    fn trace(&self, mut i: usize) -> Vec<Cell> {
        let mut path = Vec::new();
        // Parents form a tree; the bound only guards against a logic error.
        for _ in 0..self.nodes.len() {
            path.push(self.cell_of_padded(i));
            let parent = self.nodes[i].parent;
            if parent == NONE {
                break;
            }
            i = parent as usize;
        }
        path.reverse();
        path
    }

    /// Where the search stands.
    #[must_use]
    pub fn status(&self) -> SearchStatus {
        self.status
    }

    /// Whether the search has ended (found or no path).
    #[must_use]
    pub fn is_done(&self) -> bool {
        self.status != SearchStatus::Searching
    }

    /// The path, its cost and the expansions, once found.
    #[must_use]
    pub fn result(&self) -> Option<&PathResult> {
        self.result.as_ref()
    }

    /// Cells expanded so far (the goal included once found).
    #[must_use]
    pub fn expanded(&self) -> usize {
        self.expanded
    }

    /// Cells on the open list (each counted once, however many heap entries it has).
    #[must_use]
    pub fn frontier_len(&self) -> usize {
        self.open_count
    }

    /// The cell the last [`Search::step`] expanded (the goal after `Found`);
    /// `None` before the first step and after `NoPath`.
    #[must_use]
    pub fn last_expanded(&self) -> Option<Cell> {
        self.last_expanded
    }

    #[must_use]
    pub fn start(&self) -> Cell {
        self.start
    }

    #[must_use]
    pub fn goal(&self) -> Cell {
        self.goal
    }

    #[must_use]
    pub fn config(&self) -> SearchConfig {
        self.config
    }

    /// Grid width of the copy being searched.
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Grid height of the copy being searched.
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    fn raw_state(&self, i: usize) -> CellState {
        let open = self.open_stamp();
        if self.blocked[i] != 0 {
            CellState::Blocked
        } else if self.nodes[i].stamp == open {
            CellState::Open
        } else if self.nodes[i].stamp == open + 1 {
            CellState::Closed
        } else {
            CellState::Unseen
        }
    }

    /// The state of one cell (`Blocked` outside the grid). Path cells are
    /// reported as [`CellState::Path`] once found.
    #[must_use]
    pub fn cell_state(&self, cell: Cell) -> CellState {
        let Some(i) = self.padded_of(cell) else {
            return CellState::Blocked;
        };
        if let Some(r) = &self.result {
            if r.path.contains(&cell) {
                return CellState::Path;
            }
        }
        self.raw_state(i)
    }

    /// Every cell's [`CellState`] as `u8`, row by row (`y · width + x`), into
    /// `out` (cleared first): one raster for the page.
    pub fn write_cell_states(&self, out: &mut Vec<u8>) {
        out.clear();
        out.reserve(self.width * self.height);
        for y in 0..self.height {
            let row = (y + 1) * self.pitch + 1;
            out.extend((row..row + self.width).map(|i| self.raw_state(i) as u8));
        }
        if let Some(r) = &self.result {
            for c in &r.path {
                out[c.y * self.width + c.x] = CellState::Path as u8;
            }
        }
    }

    /// The best known cost from the start to `cell`, if it has been reached.
    #[must_use]
    pub fn g_of(&self, cell: Cell) -> Option<f64> {
        let i = self.padded_of(cell)?;
        matches!(self.raw_state(i), CellState::Open | CellState::Closed).then(|| self.nodes[i].g)
    }

    /// The best known path from the start to `cell` (open or closed), e.g. to
    /// draw the route to the cell being expanded.
    #[must_use]
    pub fn path_to(&self, cell: Cell) -> Option<Vec<Cell>> {
        self.g_of(cell)?;
        self.padded_of(cell).map(|i| self.trace(i))
    }

    /// `g`, `h` and the priority `f` of a cell the search has reached (open
    /// or closed), as the open list ranks it: `g + h`, `g + w·h` or `h`.
    #[must_use]
    pub fn entry_of(&self, cell: Cell) -> Option<OpenEntry> {
        let g = self.g_of(cell)?;
        let h = self.heuristic(cell.x + 1, cell.y + 1);
        Some(OpenEntry {
            cell,
            g,
            h,
            f: self.g_factor * g + self.h_factor * h,
        })
    }

    /// The first `k` cells the open list would expand next, in that order, with
    /// their `g`, `h` and `f`. Costs `O(frontier · k)` per call, `k` being a
    /// panel's few rows: meant for a panel redrawn once per frame. One pass
    /// that keeps the `k` largest entries in order, rather than a sort and a
    /// selection: each generic sort the wasm module holds costs about 1 KB
    /// of its gzip bytes.
    #[must_use]
    pub fn open_top(&self, k: usize) -> Vec<OpenEntry> {
        if k == 0 {
            return Vec::new();
        }
        let open = self.open_stamp();
        // The `k` largest entries, largest first. A cell may sit in the heap
        // more than once (each time its g dropped); the entry popped first is
        // the one with the largest key, so a cell keeps its largest entry. A
        // smaller entry of a cell whose larger one has been pushed out of the
        // list is smaller than every entry kept, so it cannot come back in.
        let mut live: Vec<HeapEntry> = Vec::with_capacity(k + 1);
        for &e in self.heap.iter() {
            if self.nodes[e.index()].stamp != open {
                continue;
            }
            if let Some(i) = live.iter().position(|kept| kept.index() == e.index()) {
                if e <= live[i] {
                    continue;
                }
                live.remove(i);
            }
            if live.len() == k && live.last().is_some_and(|last| e <= *last) {
                continue;
            }
            let at = live.iter().position(|kept| e > *kept).unwrap_or(live.len());
            live.insert(at, e);
            live.truncate(k);
        }
        live.into_iter()
            .map(|e| {
                let cell = self.cell_of_padded(e.index());
                OpenEntry {
                    cell,
                    g: self.nodes[e.index()].g,
                    h: self.heuristic(cell.x + 1, cell.y + 1),
                    f: e.f(),
                }
            })
            .collect()
    }
}

/// One complete search: `Ok(Some(result))` with a path, `Ok(None)` when the
/// goal cannot be reached.
///
/// # Errors
/// [`SearchError`] when an end is outside the grid or in a wall, or the weight is invalid.
///
/// # Example
/// ```
/// use labcore::planning::astar::{astar_path, SearchConfig};
/// use labcore::planning::grid::{Cell, Connectivity, OccupancyGrid};
/// let grid = OccupancyGrid::from_ascii("
///     ..#..
///     ..#..
///     ..#..
/// ").unwrap();
/// let dijkstra = SearchConfig::dijkstra(Connectivity::Four);
/// assert_eq!(astar_path(&grid, Cell::new(0, 0), Cell::new(4, 0), dijkstra), Ok(None));
/// let r = astar_path(&grid, Cell::new(0, 0), Cell::new(1, 2), dijkstra).unwrap().unwrap();
/// assert_eq!(r.cost, 3.0);
/// ```
pub fn astar_path(
    grid: &OccupancyGrid,
    start: Cell,
    goal: Cell,
    config: SearchConfig,
) -> Result<Option<PathResult>, SearchError> {
    let mut search = Search::new(grid, start, goal, config)?;
    search.run();
    Ok(search.result)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::grid::DIAGONAL_COST as D;

    fn c(x: usize, y: usize) -> Cell {
        Cell::new(x, y)
    }

    /// Finds the one `S` and one `G` in an ASCII grid and returns the grid with them free.
    fn parse(text: &str) -> (OccupancyGrid, Cell, Cell) {
        let rows: Vec<&str> = text
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect();
        let (mut s, mut g) = (c(0, 0), c(0, 0));
        for (y, row) in rows.iter().enumerate() {
            for (x, ch) in row.chars().enumerate() {
                match ch {
                    'S' => s = c(x, y),
                    'G' => g = c(x, y),
                    _ => {}
                }
            }
        }
        let plain = text.replace(['S', 'G'], ".");
        (OccupancyGrid::from_ascii(&plain).unwrap(), s, g)
    }

    /// Hand-computed optimal costs, as (grid, connectivity, expected cost or None).
    #[test]
    fn hand_computed_grids() {
        let cases: &[(&str, Connectivity, Option<f64>)] = &[
            // Open 5×3: 4 right, 2 down → 2 diagonals + 2 straight.
            (
                "S....
                 .....
                 ....G",
                Connectivity::Eight,
                Some(2.0 + 2.0 * D),
            ),
            ("S....\n.....\n....G", Connectivity::Four, Some(6.0)),
            // A wall with a gap at the bottom; diagonals may not clip its corner.
            (
                "S.#..
                 ..#..
                 ....G",
                Connectivity::Eight,
                // (2, 2) is the only gap; entering it diagonally would cut (2, 1), so it is
                // (0,0)→(0,1)→(1,2) [1 + √2], →(2,2)→(3,2)→(4,2) [3].
                Some(4.0 + D),
            ),
            // The only route passes diagonally between two walls touching at a corner: forbidden.
            (
                "S#
                 #G",
                Connectivity::Eight,
                None,
            ),
            ("S#\n#G", Connectivity::Four, None),
            // Start is goal.
            ("S", Connectivity::Eight, Some(0.0)),
            // A U-shaped detour.
            (
                "......
                 .####.
                 .#S.#.
                 .#..#.
                 .#G.#.",
                Connectivity::Four,
                Some(2.0),
            ),
            (
                "......
                 .####.
                 .#S.#.
                 .####.
                 .#.G#.",
                Connectivity::Four,
                None,
            ),
            // Around a bar: S at left of row 2, G at right of row 2, bar in the middle rows 1–3.
            (
                ".......
                 ...#...
                 S..#..G
                 ...#...
                 .......",
                Connectivity::Eight,
                // Around the bar's end (3, 4), which can only be entered and left
                // orthogonally: 2 diagonals down to (2, 4), 2 straight to (4, 4), 2 diagonals up.
                Some(4.0 * D + 2.0),
            ),
        ];
        for (text, conn, expected) in cases {
            let (grid, s, g) = parse(text);
            for h in Heuristic::ALL {
                if !h.is_admissible(*conn) {
                    continue;
                }
                let got = astar_path(&grid, s, g, SearchConfig::astar(*conn, h)).unwrap();
                match (expected, &got) {
                    (None, None) => {}
                    (Some(e), Some(r)) => {
                        assert!((r.cost - e).abs() < 1e-12, "{text}: {h:?} got {}", r.cost);
                        assert_eq!(r.path.first(), Some(&s));
                        assert_eq!(r.path.last(), Some(&g));
                    }
                    _ => panic!("{text}: {h:?} expected {expected:?}, got {got:?}"),
                }
            }
        }
    }

    #[test]
    fn path_moves_are_legal_and_sum_to_the_cost() {
        let (grid, s, g) = parse(
            "S..#......
             .#.#.####.
             .#...#....
             .#####.##.
             ........#G",
        );
        let r = astar_path(&grid, s, g, SearchConfig::default())
            .unwrap()
            .unwrap();
        let mut sum = 0.0;
        for w in r.path.windows(2) {
            let step = grid
                .neighbours(w[0], Connectivity::Eight)
                .find(|(to, _)| *to == w[1])
                .expect("each step is a legal move");
            sum += step.1;
        }
        assert!((sum - r.cost).abs() < 1e-12);
    }

    #[test]
    fn errors_for_bad_ends_and_weights() {
        let grid = OccupancyGrid::from_ascii("..#\n...").unwrap();
        let cfg = SearchConfig::default();
        assert_eq!(
            Search::new(&grid, c(3, 0), c(0, 0), cfg).err(),
            Some(SearchError::StartOutOfBounds { cell: c(3, 0) })
        );
        assert_eq!(
            Search::new(&grid, c(0, 0), c(0, 2), cfg).err(),
            Some(SearchError::GoalOutOfBounds { cell: c(0, 2) })
        );
        assert_eq!(
            Search::new(&grid, c(2, 0), c(0, 0), cfg).err(),
            Some(SearchError::StartBlocked { cell: c(2, 0) })
        );
        assert_eq!(
            Search::new(&grid, c(0, 0), c(2, 0), cfg).err(),
            Some(SearchError::GoalBlocked { cell: c(2, 0) })
        );
        for w in [0.5, f64::NAN, f64::INFINITY, -1.0] {
            let cfg = SearchConfig::weighted(Connectivity::Eight, Heuristic::Octile, w);
            assert!(matches!(
                Search::new(&grid, c(0, 0), c(1, 1), cfg),
                Err(SearchError::InvalidWeight { .. })
            ));
        }
        assert!(SearchError::InvalidWeight { weight: 0.5 }
            .to_string()
            .contains("0.5"));
        // A failed reset leaves the search as it was.
        let mut s = Search::new(&grid, c(0, 0), c(2, 1), cfg).unwrap();
        s.step();
        assert!(s.reset(&grid, c(2, 0), c(0, 0), cfg).is_err());
        assert_eq!((s.start(), s.expanded()), (c(0, 0), 1));
    }

    #[test]
    fn steps_report_each_expansion_and_the_end_repeats() {
        let (grid, s, g) = parse("S...G");
        let mut search = Search::new(&grid, s, g, SearchConfig::default()).unwrap();
        assert_eq!(search.last_expanded(), None);
        for x in 0..4 {
            assert_eq!(search.step(), StepOutcome::Expanded { cell: c(x, 0) });
            assert_eq!(search.last_expanded(), Some(c(x, 0)));
            assert_eq!(search.frontier_len(), 1);
        }
        assert_eq!(search.step(), StepOutcome::Found);
        assert_eq!(search.step(), StepOutcome::Found);
        assert_eq!(search.expanded(), 5);
        assert_eq!(search.result().unwrap().expanded, 5);
        assert!(search.is_done());
        let mut v = Vec::new();
        search.write_cell_states(&mut v);
        assert_eq!(v, vec![3; 5]);
    }

    #[test]
    fn no_path_ends_and_closes_the_reachable_region() {
        let (grid, s, g) = parse(
            "S.#..
             ..#.G
             ###..",
        );
        let mut search = Search::new(&grid, s, g, SearchConfig::default()).unwrap();
        assert_eq!(search.run(), StepOutcome::NoPath);
        assert_eq!(search.expanded(), 4);
        assert_eq!(search.frontier_len(), 0);
        assert_eq!(search.step(), StepOutcome::NoPath);
        assert_eq!(search.result(), None);
        let mut v = Vec::new();
        search.write_cell_states(&mut v);
        #[rustfmt::skip]
        let expected = vec![
            2, 2, 4, 0, 0,
            2, 2, 4, 0, 0,
            4, 4, 4, 0, 0,
        ];
        assert_eq!(v, expected);
        assert_eq!(search.cell_state(c(9, 9)), CellState::Blocked);
    }

    /// The open list's first `k` by sorting every live entry, largest
    /// first, one per cell (its largest): what `open_top` must equal.
    fn open_top_by_sorting(s: &Search, k: usize) -> Vec<(Cell, f64)> {
        let open = s.open_stamp();
        let mut live: Vec<HeapEntry> = s
            .heap
            .iter()
            .filter(|e| s.nodes[e.index()].stamp == open)
            .copied()
            .collect();
        live.sort_unstable_by(|a, b| b.cmp(a));
        let mut seen = std::collections::HashSet::new();
        live.retain(|e| seen.insert(e.index()));
        live.truncate(k);
        live.iter()
            .map(|e| (s.cell_of_padded(e.index()), e.f()))
            .collect()
    }

    #[test]
    fn open_top_equals_a_sort_of_the_open_list_on_random_grids() {
        let mut rng = crate::rng::Lcg64::new(52);
        let mut duplicates_seen = false;
        for round in 0..60 {
            let (w, h) = (6 + (round % 9), 5 + (round % 7));
            let mut grid = OccupancyGrid::new(w, h).unwrap();
            for _ in 0..(w * h / 4) {
                let cell = c(
                    (rng.next_f64() * w as f64) as usize,
                    (rng.next_f64() * h as f64) as usize,
                );
                grid.set_blocked(cell, true);
            }
            let (start, goal) = (c(0, 0), c(w - 1, h - 1));
            grid.set_blocked(start, false);
            grid.set_blocked(goal, false);
            let Ok(mut s) = Search::new(&grid, start, goal, SearchConfig::default()) else {
                continue;
            };
            for _ in 0..(round % 13 + 1) {
                s.step();
                duplicates_seen |= s.heap.len() > s.frontier_len();
                for k in [1, 3, 8, 50] {
                    let got: Vec<(Cell, f64)> =
                        s.open_top(k).iter().map(|e| (e.cell, e.f)).collect();
                    assert_eq!(got, open_top_by_sorting(&s, k), "round {round}, k {k}");
                }
            }
        }
        assert!(
            duplicates_seen,
            "the sample reaches a cell in the heap twice"
        );
    }

    #[test]
    fn open_top_lists_the_next_pops_with_g_h_f() {
        let grid = OccupancyGrid::new(5, 5).unwrap();
        let mut s = Search::new(&grid, c(2, 2), c(4, 2), SearchConfig::default()).unwrap();
        s.step();
        let top = s.open_top(3);
        assert_eq!(top.len(), 3);
        // (3,2): g 1, h 1; then (3,1) and (3,3): g √2, h √2 — equal f and g, index order.
        assert_eq!(top[0].cell, c(3, 2));
        assert_eq!((top[0].g, top[0].h, top[0].f), (1.0, 1.0, 2.0));
        assert_eq!(top[1].cell, c(3, 1));
        assert_eq!(top[2].cell, c(3, 3));
        assert!((top[1].f - 2.0 * D).abs() < 1e-15 && top[1].g == D);
        assert_eq!(s.open_top(100).len(), 8);
        assert_eq!(s.open_top(0), vec![]);
        // The first listed is the next expanded.
        assert_eq!(s.step(), StepOutcome::Expanded { cell: top[0].cell });
    }

    #[test]
    fn ties_prefer_larger_g_then_lower_index() {
        // Open 4-connected grid, Manhattan: every cell on a monotone path has
        // f = 4. Larger g first drives straight to the goal with no side trips.
        let grid = OccupancyGrid::new(3, 3).unwrap();
        let mut s = Search::new(
            &grid,
            c(0, 0),
            c(2, 2),
            SearchConfig::astar(Connectivity::Four, Heuristic::Manhattan),
        )
        .unwrap();
        let mut order = Vec::new();
        while let StepOutcome::Expanded { cell } = s.step() {
            order.push(cell);
        }
        // (0,0) → ties (1,0) idx 1 and (0,1) idx 3: lower index first → (1,0);
        // then its children have g 2 > 1 → (2,0) [idx 2] before (1,1) [idx 4] …
        assert_eq!(order, vec![c(0, 0), c(1, 0), c(2, 0), c(2, 1)]);
        assert_eq!(s.result().unwrap().expanded, 5);
    }

    #[test]
    fn reset_reuses_memory_and_forgets_the_old_search() {
        let (grid, s, g) = parse(
            "S.....
             .####.
             .....G",
        );
        let mut search = Search::new(&grid, s, g, SearchConfig::default()).unwrap();
        search.run();
        let first = search.result().cloned().unwrap();
        for _ in 0..3 {
            search.reset(&grid, s, g, SearchConfig::default()).unwrap();
            assert_eq!(search.expanded(), 0);
            assert_eq!(search.cell_state(c(1, 0)), CellState::Unseen);
            search.run();
            assert_eq!(search.result(), Some(&first));
        }
        // A differently sized grid.
        let small = OccupancyGrid::new(2, 2).unwrap();
        search
            .reset(&small, c(0, 0), c(1, 1), SearchConfig::default())
            .unwrap();
        search.run();
        assert_eq!(search.result().unwrap().cost, D);
    }

    #[test]
    fn path_to_and_g_of_follow_the_tree() {
        let grid = OccupancyGrid::new(4, 1).unwrap();
        let mut s = Search::new(&grid, c(0, 0), c(3, 0), SearchConfig::default()).unwrap();
        s.step_n(2);
        assert_eq!(s.g_of(c(2, 0)), Some(2.0));
        assert_eq!(s.path_to(c(2, 0)), Some(vec![c(0, 0), c(1, 0), c(2, 0)]));
        assert_eq!(s.g_of(c(3, 0)), None);
        assert_eq!(s.step_n(0), None);
        assert_eq!(s.step_n(10), Some(StepOutcome::Found));
    }

    #[test]
    fn greedy_and_weighted_take_the_strategy() {
        let (grid, s, g) = parse(
            "..........
             .########.
             S.......#G
             .########.
             ..........",
        );
        let optimal = astar_path(&grid, s, g, SearchConfig::default())
            .unwrap()
            .unwrap();
        let greedy = astar_path(
            &grid,
            s,
            g,
            SearchConfig::greedy(Connectivity::Eight, Heuristic::Octile),
        )
        .unwrap()
        .unwrap();
        // Greedy runs into the dead-end corridor first.
        assert!(greedy.expanded > 8);
        assert!(greedy.cost >= optimal.cost);
        for w in [1.0, 1.5, 3.0] {
            let r = astar_path(
                &grid,
                s,
                g,
                SearchConfig::weighted(Connectivity::Eight, Heuristic::Octile, w),
            )
            .unwrap()
            .unwrap();
            assert!(r.cost <= w * optimal.cost + 1e-9);
        }
    }
}
