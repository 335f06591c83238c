//! What experiment 6 shows: the grid scene, readouts, status, tables and hint,
//! and what the page needs to show them: the camera (zoom and pan on a
//! phone) and the raster cache of cell states. It reads the model and
//! writes only this view state.

use super::{AStarGrid, Base, Phase, BLOCKED, MIN_CELL_PX, PHONE_WIDTH_PX};
use crate::experiment::{Notice, Presentation, Readout, Status, Tone};
use crate::live_math::{Equation, Expr, Quantity};
use crate::planning::astar::Search;
use crate::planning::astar::{OpenEntry, Strategy};
use crate::planning::grid::Cell;
use crate::planning::heuristic::Heuristic;
use crate::scene::{Item, RasterColour, Role, Scene, ViewBox};
use crate::table::Table;
use crate::units::{format_fixed, format_number};
use glam::DVec2;

/// Rows of the open-list panel (the expanded cell and the next open cells).
const OPEN_ROWS: usize = 8;
/// How the comparison draws each planner's path (A*, Dijkstra, greedy,
/// weighted A*); the table's caption names the lines.
const COMPARE_ROLES: [Role; 4] = [Role::Path, Role::Robot, Role::Warning, Role::Target];

const DX: Expr = Expr::Var("dx");
const DY: Expr = Expr::Var("dy");
const H_CAPTION: &str = "The heuristic of the last cell expanded: |Δx| and |Δy| count the cells between it and the goal across and up, a metre each.";
/// Before a search there is no cell expanded to work the numbers of.
const NO_SEARCH: &str =
    "No search yet: press Plan, and the numbers are those of the last cell it expands.";
const fn heuristic(expr: Expr) -> Equation {
    Equation {
        key: "h",
        symbol: "h",
        expr,
        readout: "last_h",
        caption: H_CAPTION,
        absent: NO_SEARCH,
    }
}
/// The heuristics in [`Heuristic::ALL`]'s order (Hart, Nilsson & Raphael
/// 1968; the octile distance: a diagonal step costs √2).
const HEURISTICS_H: [Equation; 4] = [
    heuristic(Expr::Add(&DX, &DY)),
    heuristic(Expr::Add(
        &Expr::Max(&DX, &DY),
        &Expr::Mul(
            &Expr::Sub(&Expr::Sqrt(&Expr::Num(2.0, "2")), &Expr::Num(1.0, "1")),
            &Expr::Min(&DX, &DY),
        ),
    )),
    heuristic(Expr::Sqrt(&Expr::Add(&Expr::Sq(&DX), &Expr::Sq(&DY)))),
    heuristic(Expr::Num(0.0, "0")),
];
const fn priority(expr: Expr, caption: &'static str) -> Equation {
    Equation {
        key: "f",
        symbol: "f",
        expr,
        readout: "last_f",
        caption,
        absent: NO_SEARCH,
    }
}
/// A*, weighted A* (Pohl 1970) and greedy best-first.
const PRIORITIES: [Equation; 3] = [
    priority(
        Expr::Add(&Expr::Var("g"), &Expr::Var("h")),
        "Its priority: the cost so far g plus the estimate h still to go.",
    ),
    priority(
        Expr::Add(
            &Expr::Var("g"),
            &Expr::Mul(&Expr::Var("w"), &Expr::Var("h")),
        ),
        "Its priority in weighted A*: the estimate counts w times.",
    ),
    priority(
        Expr::Var("h"),
        "Its priority in greedy best-first search: the estimate alone.",
    ),
];
const fn pair(h: usize, f: usize) -> [Equation; 2] {
    [HEURISTICS_H[h], PRIORITIES[f]]
}
/// `[heuristic][strategy]`.
const EQUATIONS: [[&[Equation]; 3]; 4] = [
    [&pair(0, 0), &pair(0, 1), &pair(0, 2)],
    [&pair(1, 0), &pair(1, 1), &pair(1, 2)],
    [&pair(2, 0), &pair(2, 1), &pair(2, 2)],
    [&pair(3, 0), &pair(3, 1), &pair(3, 2)],
];

impl AStarGrid {
    /// The last cell the search expanded, its `g`, `h` and `f`, and the goal.
    fn last_entry(&self) -> Option<(OpenEntry, Cell)> {
        let search = self.search.as_ref()?;
        let cell = search.last_expanded()?;
        Some((search.entry_of(cell)?, search.goal()))
    }
}

impl Presentation for AStarGrid {
    /// The whole grid, or when [`AStarGrid::zoomed`] a window of
    /// finger-sized cells at the pan (the page fits it to the canvas).
    fn view(&self) -> ViewBox {
        match self.window_cells() {
            Some((c, r)) if self.zoomed() => ViewBox {
                min: self.pan,
                max: self.pan + DVec2::new(c as f64, r as f64),
            },
            _ => ViewBox {
                min: DVec2::ZERO,
                max: DVec2::new(self.grid.width() as f64, self.grid.height() as f64),
            },
        }
    }

    fn viewport_px(&mut self, width_px: f64, height_px: f64) {
        let size = DVec2::new(width_px, height_px);
        if size.is_finite() && size.min_element() > 0.0 {
            self.viewport_px = Some(size);
            self.frame_ends();
        }
    }

    fn scene(&self, out: &mut Scene) {
        let (w, h) = (self.grid.width(), self.grid.height());
        let size = DVec2::new(w as f64, h as f64);
        let raster = self.raster();
        // Kept by the page between frames: uploaded again only when a cell
        // changes (the version is a fingerprint of the cells).
        out.push(Item::VersionedRaster {
            id: RASTER_ID,
            version: crate::scene::raster_version(&raster),
            min: DVec2::ZERO,
            cell_m: 1.0,
            cols: w,
            rows: h,
            cells: raster.clone(),
            palette: vec![
                // CellState 1..4: open, closed, path, wall.
                RasterColour {
                    role: Role::Estimate,
                    alpha: 0.55,
                },
                RasterColour {
                    role: Role::Visited,
                    alpha: 0.45,
                },
                RasterColour {
                    role: Role::Path,
                    alpha: 0.35,
                },
                RasterColour {
                    role: Role::Obstacle,
                    alpha: 1.0,
                },
            ],
        });
        // Cell lines on small grids only (one batch).
        if w <= 64 && h <= 64 {
            let mut lines = Vec::with_capacity(w + h + 2);
            for x in 0..=w {
                lines.push((DVec2::new(x as f64, 0.0), DVec2::new(x as f64, size.y)));
            }
            for y in 0..=h {
                lines.push((DVec2::new(0.0, y as f64), DVec2::new(size.x, y as f64)));
            }
            out.push(Item::Segments {
                segments: lines,
                width_px: 0.5,
                role: Role::Grid,
            });
        }
        out.push(Item::Rect {
            min: DVec2::ZERO,
            max: size,
            role: Role::Bound,
            fill: false,
        });
        // Each planner's path in its own colour and dash; the Compare table
        // names them.
        for (r, role) in self.compare.iter().zip(COMPARE_ROLES) {
            if r.path.len() >= 2 {
                out.push(Item::Polyline {
                    points: r.path.clone(),
                    width_px: 2.5,
                    role,
                    dashed: role != Role::Path,
                    closed: false,
                });
            }
        }
        if self.compare.is_empty() && self.path.len() >= 2 {
            out.push(Item::Polyline {
                points: self.path.points().to_vec(),
                width_px: 3.0,
                role: Role::Path,
                dashed: false,
                closed: false,
            });
        }
        if self.phase == Phase::Searching {
            if let Some(c) = self.search.as_ref().and_then(Search::last_expanded) {
                let p = self.cell_center(c);
                out.push(Item::Rect {
                    min: p - 0.5,
                    max: p + 0.5,
                    role: Role::Accent,
                    fill: false,
                });
            }
        }
        let start = self.cell_center(self.start);
        let goal = self.cell_center(self.goal);
        let marker = if self.zoomed() {
            9.0
        } else {
            (900.0 / w.max(h) as f64).clamp(3.0, 9.0)
        };
        out.push(Item::Dot {
            center: start,
            radius_px: marker,
            role: Role::Sample,
        });
        out.push(Item::Dot {
            center: goal,
            radius_px: marker,
            role: Role::Tip,
        });
        // A marker out of the zoomed view is named by its edge mark (see
        // `pan_band`) alone: its own label, kept on the canvas, would sit on
        // the mark's.
        let view = self.view();
        let zoomed = self.zoomed();
        for (pos, text) in [(start, "start"), (goal, "goal")] {
            if !zoomed || (pos.cmpge(view.min).all() && pos.cmple(view.max).all()) {
                out.push(Item::Label {
                    pos,
                    text: text.into(),
                    role: Role::Text,
                    offset_px: DVec2::new(8.0, -10.0),
                });
            }
        }
        if let Some(p) = self.robot() {
            out.push(Item::Circle {
                center: p,
                radius_m: 0.4,
                role: Role::Robot,
                fill: true,
                dashed: false,
            });
        }
        if self.zoomed() {
            pan_band(self, out);
        }
        // What f = g + h names (issue 27 §3): the path so far to the last
        // cell expanded, whose cost is g, and the estimate h from it to the
        // goal, Δx cells across and Δy up.
        if let (Some((e, goal)), Some(search)) = (self.last_entry(), &self.search) {
            let (c, g) = (self.cell_center(e.cell), self.cell_center(goal));
            let corner = DVec2::new(g.x, c.y);
            out.tag_lines(&[("h", c, g), ("dx", c, corner), ("dy", corner, g)]);
            if let Some(path) = search.path_to(e.cell) {
                // A loop, not an iterator's collect: fewer bytes in the module.
                let mut points = Vec::with_capacity(path.len());
                for cell in path {
                    points.push(self.cell_center(cell));
                }
                out.tag("g", points);
            }
        }
    }

    fn readouts(&self) -> Vec<Readout> {
        let (expanded, frontier) = self
            .search
            .as_ref()
            .map_or((0, 0), |s| (s.expanded(), s.frontier_len()));
        let found = self.path_cells > 0;
        vec![
            Readout::new("expanded", "Expanded", expanded.to_string()),
            Readout::new("frontier", "Frontier", frontier.to_string()),
            Readout::new(
                "path_cells",
                "Path cells",
                if found {
                    self.path_cells.to_string()
                } else {
                    "--".into()
                },
            ),
            Readout::metres(
                "path_cost",
                "Path cost",
                if found { self.path_cost } else { f64::NAN },
            ),
            Readout::metres(
                "last_h",
                "Last expanded: h",
                self.last_entry().map_or(f64::NAN, |(e, _)| e.h),
            ),
            Readout::metres(
                "last_f",
                "Last expanded: f",
                self.last_entry().map_or(f64::NAN, |(e, _)| e.f),
            ),
            Readout::new(
                "grid",
                "Grid",
                format!(
                    "{} × {}, {} walls",
                    self.grid.width(),
                    self.grid.height(),
                    self.grid.blocked_count()
                ),
            ),
            Readout::new(
                "link",
                "Link",
                if self.walls_missing {
                    "the walls were left out: load the .map file".to_owned()
                } else if self.walls_in_link() {
                    "holds the walls".to_owned()
                } else {
                    "too large for the walls: use Save file (.map)".to_owned()
                },
            ),
        ]
    }

    /// The last cell expanded: its distance to the goal in cells (a metre
    /// each), `g`, `h` and the weight.
    fn quantities(&self) -> Vec<Quantity> {
        let last = self.last_entry();
        let (dx, dy) = last.map_or((f64::NAN, f64::NAN), |(e, goal)| {
            (
                e.cell.x.abs_diff(goal.x) as f64,
                e.cell.y.abs_diff(goal.y) as f64,
            )
        });
        let weight = match self.search.as_ref().map(|s| s.config().strategy) {
            Some(Strategy::Weighted { weight }) => weight,
            _ => 1.0,
        };
        vec![
            Quantity::new("dx", "|Δx|", dx, 0, "m"),
            Quantity::new("dy", "|Δy|", dy, 0, "m"),
            Quantity::new("g", "g", last.map_or(f64::NAN, |(e, _)| e.g), 3, "m"),
            Quantity::new("h", "h", last.map_or(f64::NAN, |(e, _)| e.h), 3, "m"),
            Quantity::new("w", "w", weight, 1, ""),
        ]
    }

    fn equations(&self) -> &'static [Equation] {
        let config = self
            .search
            .as_ref()
            .map_or_else(|| self.config(), |s| s.config());
        let h = Heuristic::ALL
            .iter()
            .position(|x| *x == config.heuristic)
            .unwrap_or(1);
        let strategy = match config.strategy {
            Strategy::AStar => 0,
            Strategy::Weighted { .. } => 1,
            Strategy::Greedy => 2,
        };
        EQUATIONS[h][strategy]
    }

    fn status(&self) -> Status {
        let inadmissible = !self.heuristic.is_admissible(self.connectivity) || self.weight > 1.0;
        let caveat = if self.weight > 1.0 {
            format!(" (weighted: ≤ {}× optimum)", format_number(self.weight, 1))
        } else if inadmissible {
            " (Manhattan overestimates diagonals)".to_owned()
        } else {
            String::new()
        };
        let benchmark = self.arena_optimum().map_or(String::new(), |o| {
            format!("; benchmark optimum {}", format_fixed(o, 3))
        });
        let good = if inadmissible {
            Tone::Warning
        } else {
            Tone::Good
        };
        match self.phase {
            Phase::Refused => Status::new(
                self.ends_problem()
                    .unwrap_or_else(|| "cannot plan between these cells".into()),
                Tone::Bad,
            ),
            _ if self.ends_problem().is_some() => {
                Status::new(self.ends_problem().unwrap_or_default(), Tone::Bad)
            }
            Phase::Idle if self.walls_missing => Status::new(
                format!(
                    "walls not in the link: load this {} × {} grid's .map file",
                    self.grid.width(),
                    self.grid.height()
                ),
                Tone::Warning,
            ),
            Phase::Idle if !self.walls_in_link() => Status::new(
                "ready; too large for the link: use Save file",
                Tone::Warning,
            ),
            Phase::Idle => Status::new(
                match self.base {
                    Base::Maze { seed } => format!("ready: maze from seed {seed}"),
                    Base::Arena => format!("ready: arena map (Moving AI){benchmark}"),
                    Base::Plain => "ready: press Plan & drive".to_owned(),
                },
                Tone::Neutral,
            ),
            Phase::Comparing => Status::new(
                format!("comparing… {} of 4 planners done", self.compare.len()),
                Tone::Neutral,
            ),
            Phase::Searching => Status::new(
                format!(
                    "searching… {} expanded",
                    self.search.as_ref().map_or(0, Search::expanded)
                ),
                Tone::Neutral,
            ),
            Phase::Driving => Status::new(
                format!(
                    "path found, cost {}: driving{caveat}",
                    format_fixed(self.path_cost, 3)
                ),
                good,
            ),
            Phase::Arrived => Status::ended(
                format!(
                    "arrived: path cost {}{caveat}{benchmark}",
                    format_fixed(self.path_cost, 3)
                ),
                good,
            ),
            Phase::NoPath => Status::ended(
                "no path: the goal cannot be reached from the start",
                Tone::Bad,
            ),
            Phase::Compared => Status::ended(
                format!("compared {} planners on this grid", self.compare.len()),
                Tone::Good,
            ),
        }
    }

    fn notice(&self) -> Option<Notice> {
        self.notices.current()
    }

    /// "Start at cell (2, 20), goal at cell (29, 3) on a 32 × 24 grid with 37
    /// walls; arrived: path cost 32.627." Cells as (column, row), row 0 at the top.
    fn describe(&self) -> String {
        let robot = match (self.phase, self.robot()) {
            (Phase::Driving | Phase::Arrived, Some(p)) => {
                format!(" Robot at {}.", crate::units::format_point(p))
            }
            _ => String::new(),
        };
        format!(
            "Start at cell ({}, {}), goal at cell ({}, {}) on a {} × {} grid with {} walls; {}.{robot}",
            self.start.x,
            self.start.y,
            self.goal.x,
            self.goal.y,
            self.grid.width(),
            self.grid.height(),
            self.grid.blocked_count(),
            self.status().text
        )
    }

    fn hint(&self) -> &'static str {
        match (self.walls_in_link(), self.zoomed()) {
            (true, false) => "Drag to paint or erase walls; Shift-click sets the start, Ctrl-click the goal (or drag them). Then press Plan & drive.",
            (true, true) => "Drag to paint or erase walls; Shift-click sets the start, Ctrl-click the goal (or drag them). The dashed edge band pans: drag or click it. Zoom in / out shows the whole grid.",
            (false, _) => "This grid is too large to keep in the link: use Save file to keep it as a .map file. Drag to paint walls; Shift-click sets the start, Ctrl-click the goal.",
        }
    }

    /// The hint on a touch screen: no Shift- or Ctrl-click there, so the start
    /// and goal are placed by dragging their dots.
    fn touch_hint(&self) -> &'static str {
        match (self.walls_in_link(), self.zoomed()) {
            (true, false) => "Swipe to paint or erase walls. To place the start (green) or the goal (red), touch its dot and drag it to the cell you want. Then press Plan & drive.",
            (true, true) => "Swipe to paint or erase walls. To place the start (green) or the goal (red), touch its dot and drag it to the cell you want. Drag or tap the dashed edge band to pan; Zoom in / out shows the whole grid.",
            (false, _) => "This grid is too large to keep in the link: use Save file to keep it as a .map file. Swipe to paint walls; touch the start or goal dot and drag it to move it.",
        }
    }

    fn tables(&self) -> Vec<Table> {
        let mut tables = Vec::new();
        if let Some(search) = &self.search {
            let mut open = Table::new(
                "open",
                "Open list: the cell being expanded, then the next cells by f",
                &["", "cell", "g", "h", "f"],
            );
            let config = search.config();
            let f_of = |g: f64, h: f64| match config.strategy {
                Strategy::AStar => g + h,
                Strategy::Weighted { weight } => g + weight * h,
                Strategy::Greedy => h,
            };
            if let Some(cell) = search.last_expanded() {
                let g = search.g_of(cell).unwrap_or(0.0);
                let h = config.heuristic.between(cell, search.goal());
                open.push_row(vec![
                    "expanding".into(),
                    cell.to_string(),
                    format_number(g, 3),
                    format_number(h, 3),
                    format_number(f_of(g, h), 3),
                ]);
                open.highlight = Some(0);
            }
            for (i, e) in search.open_top(OPEN_ROWS).into_iter().enumerate() {
                open.push_row(vec![
                    format!("{}", i + 1),
                    e.cell.to_string(),
                    format_number(e.g, 3),
                    format_number(e.h, 3),
                    format_number(e.f, 3),
                ]);
            }
            tables.push(open);
        }
        if !self.compare.is_empty() {
            let mut t = Table::new(
                "compare",
                "Compare on this grid. Ratio: cost ÷ optimum; time: expansions relative to Dijkstra (a deterministic estimate). Paths: A* solid amber; Dijkstra blue, greedy orange, weighted A* pink dashes.",
                &[
                    "planner",
                    "expanded",
                    "cost",
                    "ratio",
                    "time",
                ],
            );
            let optimum = self.optimum();
            let dijkstra_expanded = self
                .compare
                .iter()
                .find(|r| r.name == "Dijkstra")
                .map_or(0, |r| r.expanded);
            for r in &self.compare {
                let (cost, ratio) = match (r.cost, optimum) {
                    (Some(c), Some(o)) if o > 0.0 => (format_fixed(c, 3), format_fixed(c / o, 2)),
                    (Some(c), _) => (format_fixed(c, 3), "1.00".into()),
                    (None, _) => ("no path".into(), "--".into()),
                };
                let time = if dijkstra_expanded > 0 {
                    format_fixed(r.expanded as f64 / dijkstra_expanded as f64, 2)
                } else {
                    "--".into()
                };
                t.push_row(vec![
                    r.name.clone(),
                    r.expanded.to_string(),
                    cost,
                    ratio,
                    time,
                ]);
            }
            // The comparison the student asked for comes first, above the
            // finished search's open list (issue 53 §5).
            tables.insert(0, t);
        }
        tables
    }

    fn captures_touch(&self) -> bool {
        true
    }

    fn preview(&mut self) {
        self.plan();
        if let Some(search) = self.search.as_mut() {
            search.run();
        }
        self.search_raster();
        self.search_finished();
        self.driven_m = self.path_length_m() * 0.6;
    }
}

/// The name of A*'s grid among the rasters the page keeps ("astar").
const RASTER_ID: u64 = 0x61_73_74_61_72;

/// The zoomed view's pan band: a dashed line one cell inside each edge with
/// more grid beyond, an arrow on that side, and marks toward the start, the
/// goal and the robot when they are out of view.
fn pan_band(a: &AStarGrid, out: &mut Scene) {
    let view = a.view();
    let (w, h) = (a.grid.width() as f64, a.grid.height() as f64);
    let lo = DVec2::new(
        if view.min.x > 0.0 {
            view.min.x + 1.0
        } else {
            view.min.x
        },
        if view.min.y > 0.0 {
            view.min.y + 1.0
        } else {
            view.min.y
        },
    );
    let hi = DVec2::new(
        if view.max.x < w {
            view.max.x - 1.0
        } else {
            view.max.x
        },
        if view.max.y < h {
            view.max.y - 1.0
        } else {
            view.max.y
        },
    );
    out.push(Item::Polyline {
        points: vec![lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)],
        width_px: 1.5,
        role: Role::Accent,
        dashed: true,
        closed: true,
    });
    let mid = (view.min + view.max) * 0.5;
    let arrows = [
        (view.min.x > 0.0, DVec2::new(view.min.x + 0.5, mid.y), "◀"),
        (view.max.x < w, DVec2::new(view.max.x - 0.5, mid.y), "▶"),
        (view.min.y > 0.0, DVec2::new(mid.x, view.min.y + 0.5), "▼"),
        (view.max.y < h, DVec2::new(mid.x, view.max.y - 0.5), "▲"),
    ];
    for (shown, pos, text) in arrows {
        if shown {
            out.push(Item::Label {
                pos,
                text: text.into(),
                role: Role::Accent,
                offset_px: DVec2::new(-5.0, 5.0),
            });
        }
    }
    let inside = |p: DVec2| p.cmpge(view.min).all() && p.cmple(view.max).all();
    let marks = [
        (Some(a.cell_center(a.start)), "start", Role::Sample),
        (Some(a.cell_center(a.goal)), "goal", Role::Tip),
        (a.robot(), "robot", Role::Robot),
    ];
    for (at, label, role) in marks {
        if let Some(at) = at.filter(|p| !inside(*p)) {
            out.push(Item::OffView {
                at,
                label: label.into(),
                role,
            });
        }
    }
}

/// The camera (view state, never in the link: the canvas size, the zoom
/// and the pan) and the raster cache of cell states the scene paints.
impl AStarGrid {
    /// Whether the view shows a finger-sized window instead of the grid.
    #[must_use]
    pub fn zoomed(&self) -> bool {
        let auto = self.viewport_px.is_some_and(|v| v.x <= PHONE_WIDTH_PX);
        self.zoom_choice.unwrap_or(auto) && self.window_cells().is_some()
    }

    /// The zoomed window's size in cells (columns, rows) for the canvas the
    /// page told: as many [`MIN_CELL_PX`] cells as fit, `None` when the whole
    /// grid already shows cells that large (or no canvas size is known yet).
    pub(super) fn window_cells(&self) -> Option<(usize, usize)> {
        let vp = self.viewport_px?;
        let (w, h) = (self.grid.width(), self.grid.height());
        if (vp.x / w as f64).min(vp.y / h as f64) >= MIN_CELL_PX {
            return None;
        }
        let fit = |px: f64, n: usize| ((px / MIN_CELL_PX).floor() as usize).clamp(1, n);
        let (c, r) = (fit(vp.x, w), fit(vp.y, h));
        (c < w || r < h).then_some((c, r))
    }

    /// The pan clamped so the window stays on the grid.
    pub(super) fn clamp_pan(&self, pan: DVec2) -> DVec2 {
        let Some((c, r)) = self.window_cells() else {
            return DVec2::ZERO;
        };
        let max = DVec2::new(
            (self.grid.width() - c) as f64,
            (self.grid.height() - r) as f64,
        );
        let p = if pan.is_finite() { pan } else { DVec2::ZERO };
        p.round().clamp(DVec2::ZERO, max)
    }

    /// Centres the zoomed window on the start and goal when both fit,
    /// otherwise on the start.
    pub(super) fn frame_ends(&mut self) {
        let Some((c, r)) = self.window_cells() else {
            self.pan = DVec2::ZERO;
            return;
        };
        let (s, g) = (self.cell_center(self.start), self.cell_center(self.goal));
        let inner = DVec2::new(c as f64 - 2.0, r as f64 - 2.0);
        let d = (s - g).abs();
        let centre = if d.x < inner.x && d.y < inner.y {
            (s + g) * 0.5
        } else {
            s
        };
        self.pan = self.clamp_pan(centre - DVec2::new(c as f64, r as f64) * 0.5);
    }

    /// Pans the zoomed window the least that brings `p` (world) inside its
    /// inner part (off the pan band).
    pub(super) fn follow(&mut self, p: DVec2) {
        if !self.zoomed() {
            return;
        }
        let view = self.view();
        let lo = view.min + 1.0;
        let hi = view.max - 1.0;
        let shift = DVec2::new(
            (p.x - lo.x).min(0.0) + (p.x - hi.x).max(0.0),
            (p.y - lo.y).min(0.0) + (p.y - hi.y).max(0.0),
        );
        self.pan = self.clamp_pan(self.pan + shift.signum() * shift.abs().ceil());
    }

    /// The pan direction of a press at `p` on the zoomed view's edge band
    /// (the outer ring of cells on each side with more grid beyond), or
    /// `None` inside.
    pub(super) fn band_side(&self, p: DVec2) -> Option<DVec2> {
        if !self.zoomed() || !p.is_finite() {
            return None;
        }
        let view = self.view();
        let (w, h) = (self.grid.width() as f64, self.grid.height() as f64);
        let side = |v: f64, lo: f64, hi: f64, max: f64| {
            if v < lo + 1.0 && lo > 0.0 {
                -1.0
            } else if v > hi - 1.0 && hi < max {
                1.0
            } else {
                0.0
            }
        };
        let d = DVec2::new(
            side(p.x, view.min.x, view.max.x, w),
            side(p.y, view.min.y, view.max.y, h),
        );
        (d != DVec2::ZERO).then_some(d)
    }

    /// The raster showing only the walls.
    pub(super) fn walls_raster(&mut self) {
        let (w, h) = (self.grid.width(), self.grid.height());
        let raster = self.raster.get_mut();
        raster.clear();
        raster.resize(w * h, 0);
        for (y, row) in self.grid.cells().chunks(w).enumerate() {
            let r = (h - 1 - y) * w;
            for (dst, &b) in raster[r..r + w].iter_mut().zip(row) {
                *dst = if b { BLOCKED } else { 0 };
            }
        }
        self.raster_stale.set(false);
    }

    /// The raster is to show the search's cell states: it is filled from
    /// them when next read ([`Self::raster`]).
    pub(super) fn search_raster(&mut self) {
        if self.search.is_some() {
            self.raster_stale.set(true);
        }
    }

    /// The raster of cell states as shown (row 0 at the bottom), filled
    /// from the search first if a step changed it (rows flipped to y up).
    pub(super) fn raster(&self) -> std::cell::Ref<'_, Vec<u8>> {
        if self.raster_stale.replace(false) {
            if let Some(search) = &self.search {
                let mut scratch = self.scratch.borrow_mut();
                search.write_cell_states(&mut scratch);
                let (w, h) = (self.grid.width(), self.grid.height());
                if scratch.len() == w * h {
                    let mut raster = self.raster.borrow_mut();
                    raster.resize(w * h, 0);
                    for (y, row) in scratch.chunks(w).enumerate() {
                        let r = (h - 1 - y) * w;
                        raster[r..r + w].copy_from_slice(row);
                    }
                }
            }
        }
        self.raster.borrow()
    }
}
