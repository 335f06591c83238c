//! Experiment 6 — A* and Dijkstra on an editable occupancy grid.
//!
//! The student paints walls, places the start (Shift-click, or a drag of its
//! dot on a touch screen) and the goal (Ctrl-click), picks a heuristic, the
//! connectivity and a weight, and presses
//! *Plan & drive*: [`Search::step`] expands a fixed number of cells per fixed
//! time step, so the open list (frontier) and the closed set grow on screen,
//! then the robot drives the path found. A* orders its open list by
//!
//! ```text
//! f(n) = g(n) + w · h(n)        (w = 1: plain A*; h = 0: Dijkstra)
//! ```
//!
//! (Hart, Nilsson & Raphael, *IEEE Trans. SSC* 4(2), 1968; Dijkstra,
//! *Numer. Math.* 1, 1959; Pohl, *Artificial Intelligence* 1(3), 1970 for the
//! weight). *Compare* runs A*, Dijkstra, greedy best-first and weighted A* on
//! the same grid and tabulates expansions, path cost and the ratio to the
//! optimum (Dijkstra's cost).
//!
//! **World coordinates.** A cell is 1 m wide; cell `(x, y)` (row `y` counted
//! downwards, as in [`OccupancyGrid`] and `.map` files) covers
//! `[x, x + 1] × [H − y − 1, H − y]` of the world (y up).
//!
//! **The link** holds every parameter, then the grid: a maze or the arena
//! map as its generator and seed (`maze=W×H.seed`, `map=arena`) plus the
//! cells edited since (`edits=`, the runs of a wall code), or the walls as a
//! wall code ([`encode_walls`], `walls=`), whichever is shorter, up to
//! [`LINK_WALLS_MAX`] characters. When neither fits, `nowalls=W×H` keeps the
//! size and the page that opens it says to load the `.map` file
//! ([`Experiment::export_text`], a Moving AI map). Then both ends as one value,
//! `ends=sx.sy.gx.gy`, applied after the grid as whole points (issue 14).
//!
//! **On a phone** ([`Presentation::viewport_px`] at most [`PHONE_WIDTH_PX`]
//! wide) the view is a window of cells at least [`MIN_CELL_PX`] across around
//! the start and goal; its outer ring of cells is a pan band (drag it, or tap
//! it to move half a window). This is view state, never in the link.

use crate::experiment::{
    check_param, ActionSpec, Experiment, Input, Modifiers, Notices, ParamError, ParamSpec,
    Sanitized, Tone,
};
use crate::planning::astar::{Search, SearchConfig, StepOutcome, Strategy};
use crate::planning::drive_path::DrivePath;
use crate::planning::grid::{Cell, Connectivity, OccupancyGrid};
use crate::planning::heuristic::Heuristic;
use crate::planning::maze::recursive_backtracker;
use crate::planning::movingai::{parse_map, write_map, ARENA_MAP};
use crate::planning::wall_code::{decode_walls, encode_walls, encoded_len};
use crate::plot::{Plot, Series, SeriesRole};
use crate::quiz::{Draw, Generator};
use crate::rng::Lcg64;
use crate::units::format_number;
use glam::DVec2;
use std::cell::RefCell;

const HEURISTICS: &[&str] = &["Manhattan", "Octile", "Euclidean", "None (Dijkstra)"];
const CONNECTIVITY: &[&str] = &["4-connected", "8-connected"];
/// The grid sizes of the `size` choice (columns × rows); the last choice,
/// "other", is any other size (a loaded map).
pub const SIZES: [(usize, usize); 6] = [
    (20, 15),
    (32, 24),
    (64, 48),
    (128, 96),
    (256, 192),
    (512, 512),
];
const SIZE_LABELS: &[&str] = &[
    "20 × 15",
    "32 × 24",
    "64 × 48",
    "128 × 96",
    "256 × 192",
    "512 × 512",
    "other (loaded map)",
];
const OTHER_SIZE: usize = SIZES.len();
/// The largest grid side the experiment accepts (a loaded map or a link).
pub const MAX_SIDE: usize = 1024;
/// The longest wall code kept in the link, characters; above it the link
/// leaves the walls out (about 2 kB keeps every link well inside what
/// browsers and chat programs pass on).
pub const LINK_WALLS_MAX: usize = 2000;
/// At Speed 1 a grid of up to this many cells expands one cell every
/// [`STEPS_PER_EXPANSION`] fixed steps; larger grids expand proportionally
/// more, so every search takes a similar time.
const CELLS_PER_EXPANSION: usize = 768;
/// Fixed steps (1/60 s each) per expanded cell at Speed 1 on a small grid:
/// 10 cells a second, so at the default Speed 3 the default search (about
/// 150 expansions) takes some five seconds and the frontier can be watched
/// as it grows (issue 23 §1).
const STEPS_PER_EXPANSION: usize = 6;
/// The robot drives a path in at most this many seconds (and at least
/// [`MIN_DRIVE_SPEED`] m/s), so a 512 × 512 path does not take minutes.
const DRIVE_TIME_S: f64 = 6.0;
const MIN_DRIVE_SPEED: f64 = 4.0; // m/s (cells per second)
/// The smallest cell a finger can hit, CSS px (issue 13 §6).
pub const MIN_CELL_PX: f64 = 24.0;
/// Canvases at most this wide (a phone held upright: the widest are 430 CSS
/// px) zoom to [`MIN_CELL_PX`] cells by themselves; wider ones only when the
/// student presses *Zoom*. A laptop's canvas beside the plots and the
/// controls is about 500 px wide (issue 23 §1) and shows the whole grid.
pub const PHONE_WIDTH_PX: f64 = 460.0;

const PARAMS: &[ParamSpec] = &[
    ParamSpec::choice("h", "Heuristic", HEURISTICS, 1),
    ParamSpec::choice("conn", "Moves", CONNECTIVITY, 1),
    ParamSpec::slider("w", "Weight w", "", 1.0, 5.0, 0.1, 1.0),
    ParamSpec::slider("rate", "Speed", "×", 1.0, 50.0, 1.0, 3.0).whole_numbers(),
    ParamSpec::choice("size", "Grid size", SIZE_LABELS, 1),
    ParamSpec::number("seed", "Maze seed", 0.0, 999_999.0, 1.0),
    ParamSpec::number("sx", "Start column", 0.0, (MAX_SIDE - 1) as f64, 3.0),
    ParamSpec::number("sy", "Start row", 0.0, (MAX_SIDE - 1) as f64, 12.0),
    ParamSpec::number("gx", "Goal column", 0.0, (MAX_SIDE - 1) as f64, 28.0),
    ParamSpec::number("gy", "Goal row", 0.0, (MAX_SIDE - 1) as f64, 11.0),
];

const ACTIONS: &[ActionSpec] = &[
    ActionSpec {
        key: "plan",
        label: "Plan & drive",
    },
    ActionSpec {
        key: "compare",
        label: "Compare",
    },
    ActionSpec {
        key: "clear",
        label: "Clear",
    },
    ActionSpec {
        key: "maze",
        label: "Random maze",
    },
    ActionSpec {
        key: "arena",
        label: "Arena map",
    },
    ActionSpec {
        key: "zoom",
        label: "Zoom in / out",
    },
];

/// The default grid (32 × 24): two walls between the start and the goal.
fn default_grid() -> OccupancyGrid {
    let (w, h) = SIZES[1];
    let mut g = OccupancyGrid::new(w, h).unwrap_or_else(|_| unreachable_grid());
    for y in 4..20 {
        g.set_blocked(Cell::new(11, y), true);
    }
    for y in 0..16 {
        g.set_blocked(Cell::new(20, y), true);
    }
    for x in 11..17 {
        g.set_blocked(Cell::new(x, 4), true);
    }
    g
}

/// A 1 × 1 grid; `OccupancyGrid::new` only fails for 0 or huge sizes, so
/// this is never used with the constant sizes above. (Not `expect`: it
/// would print the error with `Debug`: 893 B of the module, gzip.)
fn unreachable_grid() -> OccupancyGrid {
    OccupancyGrid::from_cells(1, 1, vec![false])
        .unwrap_or_else(|_| unreachable!("a 1 × 1 grid is valid"))
}

/// What a pointer drag does.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Drag {
    None,
    /// Painting walls (`true`) or erasing them (`false`), decided by the first cell.
    Paint(bool),
    Start,
    Goal,
    /// Panning the zoomed view: the world point grabbed, and whether the
    /// finger has moved (a tap without a move pans by half a window).
    Pan {
        grab: DVec2,
        moved: bool,
    },
}

/// What the walls were made from (see [`AStarGrid::extra_state`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Base {
    /// Painted, loaded or linked walls: the link holds them as a wall code.
    Plain,
    /// `recursive_backtracker(width, height, seed)`: the link holds
    /// `maze=<W>x<H>.<seed>` and the cells edited since.
    Maze { seed: u64 },
    /// The bundled Moving AI arena map: `map=arena` and the edits.
    Arena,
}

/// Expansions a step of the comparison may make (about a millisecond in the
/// browser), so even a 512 × 512 comparison spreads over frames.
const COMPARE_EXPANSIONS_PER_STEP: usize = 20_000;

/// Where the run stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    /// Nothing planned since the last edit.
    Idle,
    /// The comparison runs, a bounded number of expansions per step.
    Comparing,
    /// The search animates.
    Searching,
    /// The robot follows the path.
    Driving,
    /// The robot reached the goal.
    Arrived,
    /// The open list emptied without reaching the goal.
    NoPath,
    /// `Plan` was pressed with the start or goal in a wall.
    Refused,
    /// The comparison of planners is shown.
    Compared,
}

/// One planner of the comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareRow {
    /// Name shown in the table (with the heuristic or the weight).
    pub name: String,
    pub config: SearchConfig,
    /// Cells expanded until the search ended.
    pub expanded: usize,
    /// Path cost, `None` when there is no path.
    pub cost: Option<f64>,
    /// The path as world points (cell centres).
    pub path: Vec<DVec2>,
}

/// State of the A* experiment.
#[derive(Clone, Debug)]
pub struct AStarGrid {
    grid: OccupancyGrid,
    start: Cell,
    goal: Cell,
    heuristic: Heuristic,
    connectivity: Connectivity,
    weight: f64,
    rate: usize,
    /// The `size` choice: for Clear and Random maze; shows the grid's size.
    size_choice: usize,
    seed: u64,
    /// Cell states in display order (row 0 at the bottom, world `y = 0`):
    /// 0 free, then [`crate::planning::astar::CellState`] values. Read it
    /// through [`Self::raster`]: a search step only marks it stale.
    raster: RefCell<Vec<u8>>,
    /// The search's cell states in grid order (rows y down), refreshed
    /// with the raster.
    scratch: RefCell<Vec<u8>>,
    /// The search changed since the raster was filled: the next read fills
    /// it from the search. A timeline replay of hundreds of steps fills it
    /// once, not at every step (on a 512 × 512 maze that was 98 % of a
    /// jump's time).
    raster_stale: std::cell::Cell<bool>,
    search: Option<Search>,
    phase: Phase,
    /// Fixed steps the search has run.
    search_steps: usize,
    /// The path as world points, with its arc length (metres).
    path: DrivePath,
    path_cells: usize,
    path_cost: f64,
    /// Distance driven along `path`, metres.
    driven_m: f64,
    compare: Vec<CompareRow>,
    /// Planners of a comparison still to run (the one running first).
    compare_queue: Vec<(String, SearchConfig)>,
    /// Whether the first planner in the queue has been started.
    compare_started: bool,
    drag: Drag,
    last_cell: Option<Cell>,
    /// The handle arrow keys move (the one placed or dragged last).
    nudge_goal: bool,
    /// Length of the wall code, characters (kept current on every edit).
    code_len: usize,
    /// What the walls were generated from (a maze and its seed, the arena
    /// map), so the link names the generator and only the cells edited since.
    base: Base,
    /// The generated grid of `base` (`None` for [`Base::Plain`]).
    base_grid: Option<OccupancyGrid>,
    /// The grid's part of the link, kept current on every edit; `None` when
    /// even the shortest form is over [`LINK_WALLS_MAX`].
    grid_link: Option<Vec<(&'static str, String)>>,
    /// The grid came from a link that could not carry its walls
    /// (`nowalls=W×H`); cleared by the first edit or a new grid.
    walls_missing: bool,
    /// Transient messages (a loaded file, a link that lost its walls).
    notices: Notices,
    /// The canvas size the page told (CSS px): view state, never in the link.
    viewport_px: Option<DVec2>,
    /// `Some(on)` once the student pressed *Zoom*; `None`: zoomed when the
    /// canvas is narrow and whole-grid cells would be under [`MIN_CELL_PX`].
    zoom_choice: Option<bool>,
    /// Lower-left corner of the zoomed window, world metres (whole cells).
    pan: DVec2,
    /// Expanded cells and frontier size against fixed steps.
    plots: [Plot; 1],
}

fn new_plots() -> [Plot; 1] {
    [Plot::new(
        "expanded",
        "Search progress",
        ("Step", ""),
        ("Cells", ""),
        vec![
            Series::new("expanded", "", SeriesRole::Primary),
            Series::new("frontier", "", SeriesRole::Secondary),
        ],
    )]
}

impl Default for AStarGrid {
    fn default() -> Self {
        let grid = default_grid();
        let mut s = Self {
            start: Cell::new(PARAMS[6].default as usize, PARAMS[7].default as usize),
            goal: Cell::new(PARAMS[8].default as usize, PARAMS[9].default as usize),
            heuristic: Heuristic::Octile,
            connectivity: Connectivity::Eight,
            weight: 1.0,
            rate: PARAMS[3].default as usize,
            size_choice: 1,
            seed: PARAMS[5].default as u64,
            raster: RefCell::new(Vec::new()),
            scratch: RefCell::new(Vec::new()),
            raster_stale: std::cell::Cell::new(false),
            search: None,
            phase: Phase::Idle,
            search_steps: 0,
            path: DrivePath::default(),
            path_cells: 0,
            path_cost: 0.0,
            driven_m: 0.0,
            compare: Vec::new(),
            compare_queue: Vec::new(),
            compare_started: false,
            drag: Drag::None,
            last_cell: None,
            nudge_goal: false,
            code_len: 0,
            base: Base::Plain,
            base_grid: None,
            grid_link: None,
            walls_missing: false,
            notices: Notices::default(),
            viewport_px: None,
            zoom_choice: None,
            pan: DVec2::ZERO,
            plots: new_plots(),
            grid,
        };
        s.grid_changed();
        s
    }
}

/// The heuristic of choice index `i`.
fn heuristic_of(i: usize) -> Heuristic {
    Heuristic::ALL.get(i).copied().unwrap_or_default()
}

fn heuristic_index(h: Heuristic) -> usize {
    Heuristic::ALL.iter().position(|x| *x == h).unwrap_or(1)
}

/// A name for tables: `octile`, `Manhattan`.
fn heuristic_label(h: Heuristic) -> &'static str {
    HEURISTICS[heuristic_index(h)]
}

impl AStarGrid {
    /// The occupancy grid being edited.
    #[must_use]
    pub fn grid(&self) -> &OccupancyGrid {
        &self.grid
    }

    #[must_use]
    pub fn start(&self) -> Cell {
        self.start
    }

    #[must_use]
    pub fn goal(&self) -> Cell {
        self.goal
    }

    /// The comparison's rows (empty before *Compare*).
    #[must_use]
    pub fn comparison(&self) -> &[CompareRow] {
        &self.compare
    }

    /// The search configuration of *Plan & drive*: A* with the chosen
    /// heuristic, weighted when `w > 1`.
    #[must_use]
    pub fn config(&self) -> SearchConfig {
        if self.weight > 1.0 {
            SearchConfig::weighted(self.connectivity, self.heuristic, self.weight)
        } else {
            SearchConfig::astar(self.connectivity, self.heuristic)
        }
    }

    /// The centre of `cell` in world coordinates.
    #[must_use]
    pub fn cell_center(&self, cell: Cell) -> DVec2 {
        DVec2::new(
            cell.x as f64 + 0.5,
            self.grid.height() as f64 - cell.y as f64 - 0.5,
        )
    }

    /// The cell under world point `p`, `None` outside the grid or for NaN.
    #[must_use]
    pub fn cell_at(&self, p: DVec2) -> Option<Cell> {
        if !p.is_finite() {
            return None;
        }
        let x = p.x.floor() as i64;
        let y = (self.grid.height() as f64 - p.y).floor() as i64;
        self.grid.cell_at(x, y)
    }

    /// The cell nearest world point `p` (on the grid's edge for a point
    /// outside), `None` for NaN.
    fn clamped_cell(&self, p: DVec2) -> Option<Cell> {
        if !p.is_finite() {
            return None;
        }
        let (w, h) = (self.grid.width() as f64, self.grid.height() as f64);
        let x = p.x.floor().clamp(0.0, w - 1.0) as usize;
        let y = (h - p.y).floor().clamp(0.0, h - 1.0) as usize;
        Some(Cell::new(x, y))
    }

    /// The wall code length and the raster after the grid changed; the run
    /// and the comparison are dropped.
    fn grid_changed(&mut self) {
        self.measure_link();
        self.invalidate();
    }

    /// The wall code's length and the grid's part of the link: the
    /// generator and the cells edited since when `base` is set and that is
    /// shorter, else the wall code, else nothing (over [`LINK_WALLS_MAX`]).
    fn measure_link(&mut self) {
        self.code_len = encoded_len(&self.grid);
        let (w, h) = (self.grid.width(), self.grid.height());
        let generated = match (self.base, &self.base_grid) {
            (Base::Maze { seed }, Some(b)) => Some((("maze", format!("{w}x{h}.{seed}")), b)),
            (Base::Arena, Some(b)) => Some((("map", "arena".to_owned()), b)),
            _ => None,
        };
        if let Some(((key, value), base)) = generated {
            if let Some(edits) = edit_runs(base, &self.grid) {
                if edits.len() <= LINK_WALLS_MAX && edits.len() < self.code_len {
                    let mut link = vec![(key, value)];
                    if !edits.is_empty() {
                        link.push(("edits", edits));
                    }
                    self.grid_link = Some(link);
                    return;
                }
            }
        }
        self.grid_link = if self.walls_missing {
            Some(vec![("nowalls", format!("{w}x{h}"))])
        } else if self.code_len <= LINK_WALLS_MAX {
            Some(vec![("walls", encode_walls(&self.grid))])
        } else {
            None
        };
    }

    /// Drops the search, the path and the comparison (the grid, an end or a
    /// search setting changed) and repaints the raster from the walls.
    fn invalidate(&mut self) {
        self.search = None;
        self.phase = Phase::Idle;
        self.search_steps = 0;
        self.path.clear();
        self.path_cells = 0;
        self.path_cost = 0.0;
        self.driven_m = 0.0;
        self.compare.clear();
        self.compare_queue.clear();
        self.compare_started = false;
        self.plots[0].clear();
        self.walls_raster();
    }

    /// Sets one cell's wall, keeping the start and goal free of paint, and
    /// updates the raster and code length lazily (see [`Self::end_edit`]).
    fn paint(&mut self, cell: Cell, blocked: bool) -> bool {
        if cell == self.start || cell == self.goal {
            return false;
        }
        if !self.grid.set_blocked(cell, blocked) {
            return false;
        }
        if self.phase == Phase::Idle {
            let (w, h) = (self.grid.width(), self.grid.height());
            let i = (h - 1 - cell.y) * w + cell.x;
            if let Some(v) = self.raster.get_mut().get_mut(i) {
                *v = if blocked { BLOCKED } else { 0 };
            }
        }
        true
    }

    /// Paints the cells on the line from `a` to `b` (Bresenham), so a fast
    /// drag leaves no gaps.
    fn paint_line(&mut self, a: Cell, b: Cell, blocked: bool) -> bool {
        let mut changed = false;
        let ends = ((a.x as i64, a.y as i64), (b.x as i64, b.y as i64));
        crate::bresenham::line(ends.0, ends.1, |x, y| {
            if let Some(c) = self.grid.cell_at(x, y) {
                changed |= self.paint(c, blocked);
            }
        });
        changed
    }

    /// After walls changed: the code length, and the run is dropped.
    fn end_edit(&mut self) {
        self.walls_missing = false;
        self.measure_link();
        if self.phase != Phase::Idle || !self.compare.is_empty() {
            self.invalidate();
        }
    }

    fn set_start(&mut self, cell: Cell) {
        if cell != self.start && cell != self.goal {
            self.start = cell;
            self.invalidate();
        }
    }

    fn set_goal(&mut self, cell: Cell) {
        if cell != self.goal && cell != self.start {
            self.goal = cell;
            self.invalidate();
        }
    }

    /// Replaces the grid, keeping the start and goal where they fit (clamped
    /// onto the grid otherwise).
    fn replace_grid(&mut self, grid: OccupancyGrid) {
        self.replace_grid_from(grid, Base::Plain, None);
    }

    /// [`Self::replace_grid`] with what the grid was generated from.
    fn replace_grid_from(
        &mut self,
        grid: OccupancyGrid,
        base: Base,
        base_grid: Option<OccupancyGrid>,
    ) {
        let clamp = |c: Cell| Cell::new(c.x.min(grid.width() - 1), c.y.min(grid.height() - 1));
        self.start = clamp(self.start);
        self.goal = clamp(self.goal);
        self.grid = grid;
        self.keep_ends_apart();
        self.base = base;
        self.base_grid = base_grid;
        self.walls_missing = false;
        self.size_choice = size_index(&self.grid).unwrap_or(self.size_choice);
        self.grid_changed();
        self.frame_ends();
    }

    /// When the start and goal landed on one cell (a smaller grid clamped
    /// both onto its corner), moves the goal to the nearest other cell, a
    /// free one if there is any (issue 14: they never share a cell).
    fn keep_ends_apart(&mut self) {
        if self.start != self.goal {
            return;
        }
        let (goal, start) = (self.goal, self.start);
        let grid = &self.grid;
        let best = (0..grid.width() * grid.height())
            .filter_map(|i| grid.cell_of(i))
            .filter(|&c| c != start)
            .min_by_key(|&c| {
                (
                    grid.is_blocked(c),
                    c.x.abs_diff(goal.x) + c.y.abs_diff(goal.y),
                )
            });
        if let Some(cell) = best {
            self.goal = cell;
        }
    }

    /// A new grid with free start and goal cells: the free cells nearest the
    /// top-left and bottom-right corners (reading order from each end).
    fn replace_grid_with_free_ends(&mut self, grid: OccupancyGrid) {
        let cells = grid.cells();
        let first = cells.iter().position(|b| !b);
        let last = cells.iter().rposition(|b| !b);
        let start = first.and_then(|i| grid.cell_of(i));
        let goal = last.and_then(|i| grid.cell_of(i));
        self.replace_grid(grid);
        if let (Some(s), Some(g)) = (start, goal) {
            if s != g {
                self.set_ends(s, g);
            }
        }
    }

    /// Why the ends cannot be planned between, if they cannot.
    fn ends_problem(&self) -> Option<String> {
        if self.grid.is_blocked(self.start) {
            Some(format!(
                "the start {} is in a wall: move it or erase the wall",
                self.start
            ))
        } else if self.grid.is_blocked(self.goal) {
            Some(format!(
                "the goal {} is in a wall: move it or erase the wall",
                self.goal
            ))
        } else {
            None
        }
    }

    /// Starts the animated search (*Plan & drive*).
    fn plan(&mut self) {
        self.invalidate();
        if self.ends_problem().is_some() {
            self.phase = Phase::Refused;
            return;
        }
        match Search::new(&self.grid, self.start, self.goal, self.config()) {
            Ok(search) => {
                self.search = Some(search);
                self.phase = Phase::Searching;
                self.search_raster();
            }
            // The status says why (from `ends_problem`, or that no plan can
            // be made between these cells); a notice would say it twice.
            Err(_) => self.phase = Phase::Refused,
        }
    }

    /// Expansions due after `steps` fixed steps of search:
    /// `⌈steps · rate · max(1, cells / 768) / 6⌉`, so the first step
    /// already expands a cell and the pace holds whatever the rate.
    fn expansions_due(&self, steps: usize) -> usize {
        let cells = self.grid.width() * self.grid.height();
        (steps * self.rate * (cells / CELLS_PER_EXPANSION).max(1)).div_ceil(STEPS_PER_EXPANSION)
    }

    /// The path of a finished search as world points.
    fn world_path(&self, cells: &[Cell]) -> Vec<DVec2> {
        cells.iter().map(|c| self.cell_center(*c)).collect()
    }

    /// Takes the finished search's result: the path to drive, or no path.
    fn search_finished(&mut self) {
        let Some(search) = &self.search else {
            return;
        };
        match search.result() {
            Some(r) => {
                self.path = DrivePath::new(self.world_path(&r.path));
                self.path_cells = r.path.len();
                self.path_cost = r.cost;
                self.driven_m = 0.0;
                self.phase = Phase::Driving;
            }
            None => self.phase = Phase::NoPath,
        }
    }

    /// Starts the comparison of four planners on the current grid. It runs
    /// over the following steps, [`COMPARE_EXPANSIONS_PER_STEP`] expansions a
    /// step (a 512 × 512 grid must not block the page), and ends with the main
    /// search finished (its closed set is shown).
    fn run_compare(&mut self) {
        self.plan();
        if self.phase != Phase::Searching {
            return;
        }
        let conn = self.connectivity;
        // Greedy and weighted A* need a heuristic; with "none" they use the
        // admissible one of the connectivity.
        let h = match (self.heuristic, conn) {
            (Heuristic::Zero, Connectivity::Four) => Heuristic::Manhattan,
            (Heuristic::Zero, Connectivity::Eight) => Heuristic::Octile,
            (h, _) => h,
        };
        let w = if self.weight > 1.0 { self.weight } else { 2.0 };
        self.compare_queue = vec![
            (
                format!("A* ({})", heuristic_label(self.heuristic)),
                SearchConfig::astar(conn, self.heuristic),
            ),
            ("Dijkstra".to_owned(), SearchConfig::dijkstra(conn)),
            (
                format!("Greedy ({})", heuristic_label(h)),
                SearchConfig::greedy(conn, h),
            ),
            (
                format!("Weighted A* (w = {})", format_number(w, 1)),
                SearchConfig::weighted(conn, h, w),
            ),
        ];
        self.compare_started = false;
        self.compare.clear();
        self.phase = Phase::Comparing;
    }

    /// One step of the comparison: up to [`COMPARE_EXPANSIONS_PER_STEP`]
    /// expansions of the planner at the front of the queue; a finished
    /// planner becomes a table row; after the last, the main search runs to
    /// its end the same way and the comparison is shown.
    fn compare_step(&mut self) {
        let Some(mut search) = self.search.take() else {
            self.phase = Phase::Idle;
            return;
        };
        let mut budget = COMPARE_EXPANSIONS_PER_STEP;
        while budget > 0 {
            let config = match self.compare_queue.first() {
                Some((_, config)) => *config,
                None => self.config(),
            };
            if !self.compare_started {
                if search.restart(self.start, self.goal, config).is_err() {
                    if self.compare_queue.is_empty() {
                        break;
                    }
                    self.compare_queue.remove(0);
                    continue;
                }
                self.compare_started = true;
            }
            let before = search.expanded();
            let outcome = if self.compare_queue.is_empty() {
                // The main search, in the steps Plan & drive takes: the
                // Search progress plot shows it as Plan & drive draws it
                // (issue 53 §5: it read "No data yet" beside the table).
                let n = self.expansions_due(self.search_steps + 1)
                    - self.expansions_due(self.search_steps);
                let outcome = search.step_n(n);
                self.search_steps += 1;
                let plot = &mut self.plots[0];
                plot.series[0].push(self.search_steps as f64, search.expanded() as f64);
                plot.series[1].push(self.search_steps as f64, search.frontier_len() as f64);
                plot.touch();
                outcome
            } else {
                search.step_n(budget)
            };
            budget = budget.saturating_sub((search.expanded() - before).max(1));
            if !matches!(outcome, Some(StepOutcome::Found | StepOutcome::NoPath)) {
                continue;
            }
            self.compare_started = false;
            if self.compare_queue.is_empty() {
                // The main search is finished: show it and the table.
                self.search = Some(search);
                self.search_raster();
                if let Some(r) = self.search.as_ref().and_then(Search::result) {
                    self.path = DrivePath::new(self.world_path(&r.path));
                    self.path_cells = r.path.len();
                    self.path_cost = r.cost;
                }
                self.phase = Phase::Compared;
                return;
            }
            let (name, config) = self.compare_queue.remove(0);
            let result = search.result();
            self.compare.push(CompareRow {
                name,
                config,
                expanded: search.expanded(),
                cost: result.map(|r| r.cost),
                path: result.map_or_else(Vec::new, |r| self.world_path(&r.path)),
            });
        }
        // The cells show the planner being compared now: what is drawn is a
        // function of the state, not of when it was last drawn (issue 53 §8).
        self.search = Some(search);
        self.search_raster();
    }

    /// The optimum of the comparison: Dijkstra's cost.
    fn optimum(&self) -> Option<f64> {
        self.compare
            .iter()
            .find(|r| r.config.heuristic == Heuristic::Zero && r.config.strategy == Strategy::AStar)
            .and_then(|r| r.cost)
    }

    fn new_grid_of_choice(&self) -> Option<OccupancyGrid> {
        let (w, h) = match SIZES.get(self.size_choice) {
            Some(&s) => s,
            None => (self.grid.width(), self.grid.height()),
        };
        OccupancyGrid::new(w, h).ok()
    }

    fn maze(&mut self) {
        let (w, h) = match SIZES.get(self.size_choice) {
            Some(&s) => s,
            None => (self.grid.width(), self.grid.height()),
        };
        self.maze_of(w, h, self.seed);
    }

    /// A `w × h` maze from `seed`, the start in the first room and the goal
    /// in the last (what *Random maze* and a `maze=` link make).
    fn maze_of(&mut self, w: usize, h: usize, seed: u64) {
        let Ok(maze) = recursive_backtracker(w, h, seed) else {
            return;
        };
        self.replace_grid_from(maze.clone(), Base::Maze { seed }, Some(maze));
        // Rooms have odd coordinates up to n − 2: the first and the last room.
        let last = |n: usize| {
            let m = n - 2;
            if m % 2 == 1 {
                m
            } else {
                m - 1
            }
        };
        if w >= 4 && h >= 4 && (last(w), last(h)) != (1, 1) {
            self.set_ends(Cell::new(1, 1), Cell::new(last(w), last(h)));
        }
    }

    fn arena(&mut self) {
        let Ok(grid) = parse_map(ARENA_MAP) else {
            return;
        };
        self.replace_grid_from(grid.clone(), Base::Arena, Some(grid));
        if let Some(s) = arena_scenario() {
            if self.grid.in_bounds(s.start) && self.grid.in_bounds(s.goal) && s.start != s.goal {
                self.set_ends(s.start, s.goal);
            }
        }
    }

    /// The benchmark's optimal length when the grid is the unedited arena
    /// map with the ends of its scenario (shown in the status).
    fn arena_optimum(&self) -> Option<f64> {
        if self.base != Base::Arena || self.base_grid.as_ref() != Some(&self.grid) {
            return None;
        }
        arena_scenario()
            .filter(|s| s.start == self.start && s.goal == self.goal)
            .map(|s| s.optimal_length)
    }

    /// Moves both ends at once (they must differ), keeping the view on them.
    fn set_ends(&mut self, start: Cell, goal: Cell) {
        if start == goal || !self.grid.in_bounds(start) || !self.grid.in_bounds(goal) {
            return;
        }
        self.start = start;
        self.goal = goal;
        self.invalidate();
        self.frame_ends();
    }

    /// Whether the walls fit in the link (as a generator and its edits, or
    /// as a wall code).
    #[must_use]
    pub fn walls_in_link(&self) -> bool {
        self.grid_link.is_some()
    }

    fn robot(&self) -> Option<DVec2> {
        if !matches!(self.phase, Phase::Driving | Phase::Arrived) {
            return None;
        }
        self.path.at(self.driven_m)
    }

    fn path_length_m(&self) -> f64 {
        self.path.length_m()
    }

    fn moving_handle(&mut self, cell: Cell) {
        match self.drag {
            Drag::Start => self.set_start(cell),
            Drag::Goal => self.set_goal(cell),
            _ => return,
        }
        self.follow(self.cell_center(cell));
    }
}

/// The raster value of a wall ([`crate::planning::astar::CellState::Blocked`]).
const BLOCKED: u8 = crate::planning::astar::CellState::Blocked as u8;

/// The `size` choice of a grid's dimensions.
fn size_index(grid: &OccupancyGrid) -> Option<usize> {
    SIZES
        .iter()
        .position(|&(w, h)| w == grid.width() && h == grid.height())
}

/// The benchmark scenario of the arena map: the last of its list, in its
/// hardest bucket (the last line of `assets/maps/arena.map.scen`,
/// `12 arena.map 49 49 4 32 47 19 48.38477631`). Only this one is compiled
/// into the page, written out rather than parsed, so the module carries no
/// `.scen` reader (`the_arena_scenario_is_the_files_last` checks it against
/// the file).
fn arena_scenario() -> Option<crate::planning::movingai::Scenario> {
    Some(crate::planning::movingai::Scenario {
        bucket: 12,
        map: "arena.map".into(),
        map_width: 49,
        map_height: 49,
        start: Cell::new(4, 32),
        goal: Cell::new(47, 19),
        optimal_length: 48.384_776_31,
    })
}

/// The cells of `grid` that differ from `base`, as the runs of a wall code
/// (alternating unchanged / toggled, base 36, `.`-separated; empty when
/// nothing changed). `None` when the sizes differ.
fn edit_runs(base: &OccupancyGrid, grid: &OccupancyGrid) -> Option<String> {
    if (base.width(), base.height()) != (grid.width(), grid.height()) {
        return None;
    }
    let toggled: Vec<bool> = base
        .cells()
        .iter()
        .zip(grid.cells())
        .map(|(a, b)| a != b)
        .collect();
    let diff = OccupancyGrid::from_cells(grid.width(), grid.height(), toggled).ok()?;
    let code = encode_walls(&diff);
    Some(
        code.split_once('.')
            .map_or(String::new(), |(_, runs)| runs.to_owned()),
    )
}

/// `base` with the cells named by [`edit_runs`]'s `runs` toggled.
fn apply_edits(base: &OccupancyGrid, runs: &str) -> Result<OccupancyGrid, String> {
    let (w, h) = (base.width(), base.height());
    let diff = decode_walls(&format!("{w}x{h}.{runs}")).map_err(|e| e.to_string())?;
    let cells = base
        .cells()
        .iter()
        .zip(diff.cells())
        .map(|(a, t)| a != t)
        .collect();
    OccupancyGrid::from_cells(w, h, cells).map_err(|e| e.to_string())
}

/// Reads `<W>x<H>` (a grid size within [`MAX_SIDE`]).
fn parse_size(text: &str) -> Result<(usize, usize), String> {
    let grid = decode_walls(text).map_err(|e| e.to_string())?;
    check_side(&grid)?;
    if text.contains('.') {
        return Err(format!("`{text}` is not a grid size <width>x<height>"));
    }
    Ok((grid.width(), grid.height()))
}

/// Checks a loaded or linked grid's size.
fn check_side(grid: &OccupancyGrid) -> Result<(), String> {
    if grid.width() > MAX_SIDE || grid.height() > MAX_SIDE {
        Err(format!(
            "the grid is {} × {}; this page takes grids up to {MAX_SIDE} × {MAX_SIDE}",
            grid.width(),
            grid.height()
        ))
    } else if grid.width() * grid.height() < 2 {
        Err("the grid needs at least two cells".into())
    } else {
        Ok(())
    }
}

/// Presets: named starting states that tell a story (see [`crate::experiment::Preset`]).
const PRESETS: &[crate::experiment::Preset] = &[
    crate::experiment::Preset {
        name: "The trap maze",
        description: "The start sits in a cup that opens away from the goal: A* (and even weighted, greedy A*) floods the cup before it finds the way round.",
        query: "walls=32x24.3s.d.v.1.v.1.v.1.v.1.v.1.v.1.v.1.v.1.v.1.v.1.v.1.v.1.v.1.v.1.j.d&sx=14&sy=12&gx=28&gy=12",
    },
    crate::experiment::Preset {
        name: "Dijkstra floods the grid",
        description: "No heuristic: the search expands in every direction, several times the cells A* needs, for the same cost.",
        query: "h=3",
    },
    crate::experiment::Preset {
        name: "Manhattan with diagonals",
        description: "An inadmissible heuristic: Manhattan distance overestimates on an 8-connected grid and the status warns.",
        query: "h=0&conn=1",
    },
];

impl Experiment for AStarGrid {
    fn presets(&self) -> &'static [crate::experiment::Preset] {
        PRESETS
    }

    fn id(&self) -> &'static str {
        "astar"
    }

    fn params(&self) -> &'static [ParamSpec] {
        PARAMS
    }

    fn param(&self, key: &str) -> Option<f64> {
        Some(match key {
            "h" => heuristic_index(self.heuristic) as f64,
            "conn" => match self.connectivity {
                Connectivity::Four => 0.0,
                Connectivity::Eight => 1.0,
            },
            "w" => self.weight,
            "rate" => self.rate as f64,
            "size" => size_index(&self.grid).unwrap_or(OTHER_SIZE) as f64,
            "seed" => self.seed as f64,
            "sx" => self.start.x as f64,
            "sy" => self.start.y as f64,
            "gx" => self.goal.x as f64,
            "gy" => self.goal.y as f64,
            _ => return None,
        })
    }

    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError> {
        let applied = check_param(PARAMS, key, value)?;
        let v = applied.value();
        match key {
            "h" => {
                self.heuristic = heuristic_of(v as usize);
                self.invalidate();
            }
            "conn" => {
                self.connectivity = if v == 0.0 {
                    Connectivity::Four
                } else {
                    Connectivity::Eight
                };
                self.invalidate();
            }
            "w" => {
                self.weight = v;
                self.invalidate();
            }
            "rate" => self.rate = v as usize,
            "size" => {
                let i = v as usize;
                if i >= OTHER_SIZE {
                    // "other" names a loaded size; it cannot be chosen.
                    let current = size_index(&self.grid).unwrap_or(OTHER_SIZE);
                    return Ok(if current == OTHER_SIZE {
                        applied
                    } else {
                        Sanitized::Clamped(current as f64)
                    });
                }
                self.size_choice = i;
                if size_index(&self.grid) != Some(i) {
                    if let Some(grid) = self.new_grid_of_choice() {
                        self.replace_grid(grid);
                    }
                }
            }
            "seed" => self.seed = v as u64,
            "sx" | "sy" | "gx" | "gy" => {
                let limit = if key.ends_with('x') {
                    self.grid.width() - 1
                } else {
                    self.grid.height() - 1
                };
                let n = (v as usize).min(limit);
                let mut cell = if key.starts_with('s') {
                    self.start
                } else {
                    self.goal
                };
                if key.ends_with('x') {
                    cell.x = n;
                } else {
                    cell.y = n;
                }
                let other = if key.starts_with('s') {
                    self.goal
                } else {
                    self.start
                };
                if cell == other {
                    // Start and goal never share a cell: keep the old value.
                    let kept = self.param(key).unwrap_or(0.0);
                    return Ok(Sanitized::Clamped(kept));
                }
                if key.starts_with('s') {
                    self.start = cell;
                } else {
                    self.goal = cell;
                }
                self.invalidate();
                if n as f64 != v {
                    return Ok(Sanitized::Clamped(n as f64));
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
            "plan" => self.plan(),
            "compare" => self.run_compare(),
            "clear" => {
                if let Some(grid) = self.new_grid_of_choice() {
                    self.replace_grid(grid);
                }
            }
            "maze" => self.maze(),
            "arena" => self.arena(),
            "zoom" => {
                let zoomed = self.zoomed();
                self.zoom_choice = Some(!zoomed);
                self.frame_ends();
            }
            _ => return Err(ParamError::UnknownAction { key: key.into() }),
        }
        Ok(())
    }

    fn input(&mut self, input: Input) {
        self.input_with(input, Modifiers::default());
    }

    /// Shift-click sets the start, Ctrl-click the goal (and a drag goes on
    /// moving it); a press on the start or goal drags it; elsewhere a drag
    /// paints walls, or erases them when the first cell was a wall. Arrow
    /// keys move the start or goal (the one placed last) one cell.
    fn input_with(&mut self, input: Input, modifiers: Modifiers) {
        match input {
            Input::PointerDown(p) => {
                self.drag = Drag::None;
                self.last_cell = None;
                if modifiers.shift || modifiers.ctrl {
                    let Some(cell) = self.clamped_cell(p) else {
                        return;
                    };
                    self.drag = if modifiers.shift {
                        Drag::Start
                    } else {
                        Drag::Goal
                    };
                    self.nudge_goal = self.drag == Drag::Goal;
                    self.moving_handle(cell);
                    return;
                }
                let Some(cell) = self.cell_at(p) else {
                    return;
                };
                if cell == self.start || cell == self.goal {
                    self.drag = if cell == self.start {
                        Drag::Start
                    } else {
                        Drag::Goal
                    };
                    self.nudge_goal = self.drag == Drag::Goal;
                    return;
                }
                if self.band_side(p).is_some() {
                    // The zoomed view's edge band pans instead of painting.
                    self.drag = Drag::Pan {
                        grab: p,
                        moved: false,
                    };
                    return;
                }
                let paint = !self.grid.is_blocked(cell);
                self.drag = Drag::Paint(paint);
                self.last_cell = Some(cell);
                if self.paint(cell, paint) {
                    self.end_edit();
                }
            }
            Input::PointerMove { pos, pressed: true } => match self.drag {
                Drag::Paint(paint) => {
                    let Some(cell) = self.cell_at(pos) else {
                        self.last_cell = None;
                        return;
                    };
                    let from = self.last_cell.unwrap_or(cell);
                    self.last_cell = Some(cell);
                    if self.paint_line(from, cell, paint) {
                        self.end_edit();
                    }
                }
                Drag::Start | Drag::Goal => {
                    if let Some(cell) = self.clamped_cell(pos) {
                        self.moving_handle(cell);
                    }
                }
                Drag::Pan { grab, moved } => {
                    if !pos.is_finite() {
                        return;
                    }
                    // Keep the grabbed world point under the finger.
                    let moved = moved || (pos - grab).length() > 0.5;
                    if moved {
                        self.pan = self.clamp_pan(self.pan + (grab - pos));
                    }
                    self.drag = Drag::Pan { grab, moved };
                }
                Drag::None => {}
            },
            Input::PointerMove { pressed: false, .. } => {}
            Input::PointerUp(_) => {
                if let Drag::Pan { grab, moved: false } = self.drag {
                    // A tap on the band pans half a window that way.
                    if let (Some(d), Some((c, r))) = (self.band_side(grab), self.window_cells()) {
                        let half = DVec2::new((c / 2).max(1) as f64, (r / 2).max(1) as f64);
                        self.pan = self.clamp_pan(self.pan + d * half);
                    }
                }
                self.drag = Drag::None;
                self.last_cell = None;
            }
            Input::Nudge(d) => {
                if !d.is_finite() || d == DVec2::ZERO {
                    return;
                }
                // One cell along the larger component; world y up = row up.
                let (dx, dy): (i64, i64) = if d.x.abs() >= d.y.abs() {
                    (d.x.signum() as i64, 0)
                } else {
                    (0, -(d.y.signum() as i64))
                };
                let c = if self.nudge_goal {
                    self.goal
                } else {
                    self.start
                };
                if let Some(to) = self.grid.cell_at(c.x as i64 + dx, c.y as i64 + dy) {
                    if self.nudge_goal {
                        self.set_goal(to);
                    } else {
                        self.set_start(to);
                    }
                    self.follow(self.cell_center(to));
                }
            }
        }
    }

    fn step(&mut self, dt_s: f64) {
        if !crate::clock::valid_dt(dt_s) {
            return;
        }
        match self.phase {
            Phase::Comparing => self.compare_step(),
            Phase::Searching => {
                let n = self.expansions_due(self.search_steps + 1)
                    - self.expansions_due(self.search_steps);
                let Some(search) = self.search.as_mut() else {
                    self.phase = Phase::Idle;
                    return;
                };
                let outcome = search.step_n(n);
                let (expanded, frontier) = (search.expanded(), search.frontier_len());
                self.search_steps += 1;
                let plot = &mut self.plots[0];
                plot.series[0].push(self.search_steps as f64, expanded as f64);
                plot.series[1].push(self.search_steps as f64, frontier as f64);
                plot.touch();
                self.search_raster();
                if matches!(outcome, Some(StepOutcome::Found | StepOutcome::NoPath)) {
                    self.search_finished();
                }
            }
            Phase::Driving => {
                let length = self.path_length_m();
                let speed = (length / DRIVE_TIME_S).max(MIN_DRIVE_SPEED);
                self.driven_m = (self.driven_m + speed * dt_s).min(length);
                if self.driven_m >= length {
                    self.phase = Phase::Arrived;
                }
                if let Some(p) = self.robot() {
                    self.follow(p);
                }
            }
            _ => {}
        }
    }

    fn animated(&self) -> bool {
        true
    }

    /// Restarts the search (or the comparison) from the first expansion,
    /// with the same grid, ends and settings.
    fn reset(&mut self) {
        match self.phase {
            Phase::Searching | Phase::Driving | Phase::Arrived | Phase::NoPath => self.plan(),
            Phase::Compared | Phase::Comparing => self.run_compare(),
            Phase::Idle | Phase::Refused => {}
        }
    }

    fn plots(&self) -> &[Plot] {
        &self.plots
    }

    /// The start and the goal; the keyboard moves them one cell at a time,
    /// and the Move form names them by column and row, as the controls do.
    fn handles(&self) -> Vec<crate::experiment::Handle> {
        [("start", "Start", self.start), ("goal", "Goal", self.goal)]
            .into_iter()
            .map(|(id, label, cell)| crate::experiment::Handle {
                step_m: Some(1.0),
                grid_rows: Some(self.grid.height()),
                ..crate::experiment::Handle::new(id, label, self.cell_center(cell))
            })
            .collect()
    }

    fn handle_at(&self, p: DVec2, tolerance_m: f64) -> bool {
        let near = |c: Cell| (self.cell_center(c) - p).length() <= tolerance_m.max(0.5);
        near(self.start) || near(self.goal)
    }

    fn file_types(&self) -> &'static [&'static str] {
        &[".map"]
    }

    /// Loads a Moving AI `.map`; the start and goal move to the first and
    /// last free cells. A malformed file leaves everything as it was.
    ///
    /// Every grid the page can reach can be saved and loaded again: a map
    /// of at least two cells, whatever its walls (issue 14: Save wrote maps
    /// that Load refused).
    fn load_file(&mut self, name: &str, text: &str) -> Result<(), String> {
        let grid = parse_map(text).map_err(|e| format!("{name}: {e}"))?;
        check_side(&grid).map_err(|e| format!("{name}: {e}"))?;
        self.replace_grid_with_free_ends(grid);
        self.notices.post(format!("loaded {name}"), Tone::Neutral);
        Ok(())
    }

    fn export_text(&self) -> Option<(String, String)> {
        Some(("grid.map".into(), write_map(&self.grid)))
    }

    /// The grid (`walls=` a wall code; or `maze=W×H.seed` / `map=arena`
    /// with `edits=` the cells changed since; or `nowalls=W×H` when no form
    /// fits in [`LINK_WALLS_MAX`]), then both ends as one value
    /// `ends=sx.sy.gx.gy`, so a link applies them as whole points after the
    /// grid (issue 14).
    fn extra_state(&self) -> Vec<(&'static str, String)> {
        let (w, h) = (self.grid.width(), self.grid.height());
        let mut out = self
            .grid_link
            .clone()
            .unwrap_or_else(|| vec![("nowalls", format!("{w}x{h}"))]);
        let (s, g) = (self.start, self.goal);
        out.push(("ends", format!("{}.{}.{}.{}", s.x, s.y, g.x, g.y)));
        out
    }

    fn set_extra_state(&mut self, key: &str, value: &str) -> Result<(), ParamError> {
        let bad = |reason: String| ParamError::BadText {
            key: key.into(),
            reason,
        };
        match key {
            "walls" => {
                let grid = decode_walls(value).map_err(|e| bad(e.to_string()))?;
                check_side(&grid).map_err(bad)?;
                self.replace_grid(grid);
            }
            "maze" => {
                let (size, seed) = value
                    .rsplit_once('.')
                    .ok_or_else(|| bad(format!("`{value}` is not <width>x<height>.<seed>")))?;
                let (w, h) = parse_size(size).map_err(bad)?;
                let seed: u64 = seed
                    .parse()
                    .map_err(|_| bad(format!("`{seed}` is not a maze seed")))?;
                self.maze_of(w, h, seed);
            }
            "map" => {
                if value != "arena" {
                    return Err(bad(format!("`{value}` is not a map this page knows")));
                }
                self.arena();
            }
            "edits" => {
                let base = match (&self.base_grid, self.base) {
                    (Some(b), Base::Maze { .. } | Base::Arena) if b == &self.grid => b,
                    _ => return Err(bad("edits need a maze or map before them".into())),
                };
                let grid = apply_edits(base, value).map_err(bad)?;
                self.grid = grid;
                // The ends stay free of walls as a brush leaves them.
                self.end_edit();
                self.invalidate();
            }
            "nowalls" => {
                let (w, h) = parse_size(value).map_err(bad)?;
                let grid = OccupancyGrid::new(w, h).map_err(|e| bad(e.to_string()))?;
                self.replace_grid(grid);
                self.walls_missing = true;
                self.measure_link();
                self.notices.post(
                    format!(
                        "This link could not carry the walls of its {w} × {h} grid: \
                         load the grid's .map file (saved with Save file) to get them."
                    ),
                    Tone::Warning,
                );
            }
            "ends" => {
                let n: Vec<usize> = value
                    .split('.')
                    .map(str::parse)
                    .collect::<Result<_, _>>()
                    .map_err(|_| bad(format!("`{value}` is not sx.sy.gx.gy")))?;
                let [sx, sy, gx, gy] = n[..] else {
                    return Err(bad(format!("`{value}` is not sx.sy.gx.gy")));
                };
                let (start, goal) = (Cell::new(sx, sy), Cell::new(gx, gy));
                if start == goal || !self.grid.in_bounds(start) || !self.grid.in_bounds(goal) {
                    return Err(bad(format!(
                        "the start and goal must be two different cells of the {} × {} grid",
                        self.grid.width(),
                        self.grid.height()
                    )));
                }
                self.set_ends(start, goal);
            }
            _ => return Err(ParamError::UnknownKey { key: key.into() }),
        }
        Ok(())
    }

    /// The grid's per-cell arrays (walls, the generated grid, the raster
    /// and its scratch, the search's nodes and open list), the paths, with
    /// the plot: about 23 bytes a cell while a search is kept.
    fn state_bytes(&self) -> usize {
        use std::mem::size_of;
        let compare: usize = self
            .compare
            .iter()
            .map(|r| r.name.capacity() + r.path.capacity() * size_of::<DVec2>())
            .sum();
        self.grid.heap_bytes()
            + self.base_grid.as_ref().map_or(0, OccupancyGrid::heap_bytes)
            + self.raster.borrow().capacity()
            + self.scratch.borrow().capacity()
            + self.search.as_ref().map_or(0, Search::heap_bytes)
            + self.path.heap_bytes()
            + self.compare.capacity() * size_of::<CompareRow>()
            + compare
            + crate::plot::plots_bytes(&self.plots)
    }

    fn animating(&self) -> bool {
        matches!(
            self.phase,
            Phase::Searching | Phase::Comparing | Phase::Driving
        )
    }

    /// 1 while a search (or a comparison) expands cells: a step of it can
    /// be thousands of expansions, a step of the drive a few additions.
    fn work_phase(&self) -> u8 {
        u8::from(matches!(self.phase, Phase::Searching | Phase::Comparing))
    }
}

mod quiz;
mod view;
pub use quiz::quiz_generator;

#[cfg(test)]
mod tests;
