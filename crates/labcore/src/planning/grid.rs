//! Occupancy grid: a `width × height` raster of free and blocked cells, and the
//! lab's neighbour rule.
//!
//! Cell `(x, y)` lives at index `y · width + x` (row by row, `x` fastest), the
//! order of `shared/BENCHMARKS.md` and of the Moving AI `.map` rows
//! ([`super::movingai`]). `y` grows downwards, as on the page and in the files.
//!
//! **Neighbour rule** ([`OccupancyGrid::neighbours`]). With
//! [`Connectivity::Four`] a cell reaches its four orthogonal neighbours, each
//! at cost 1. With [`Connectivity::Eight`] it also reaches the four diagonal
//! ones at cost `√2`, but only when *both* orthogonal cells beside the diagonal are
//! free: a diagonal never cuts the corner of a wall. This is the rule of the
//! Moving AI benchmarks (Sturtevant, "Benchmarks for Grid-Based Pathfinding",
//! *IEEE Trans. Comput. Intell. AI Games* 4(2), 2012, §III), so their optimal
//! lengths are the lab's optimal lengths.

use std::fmt;

/// The largest number of cells a grid may have (`2²⁴`, e.g. 4096 × 4096).
/// Keeps every index (with a one-cell border) in a `u32` and a malformed file
/// from asking for gigabytes.
pub const MAX_CELLS: usize = 1 << 24;

/// `√2`, the cost of a diagonal move.
pub const DIAGONAL_COST: f64 = std::f64::consts::SQRT_2;

/// A grid cell, column `x` and row `y` (0-based, `y` downwards).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Cell {
    pub x: usize,
    pub y: usize,
}

impl Cell {
    /// The cell `(x, y)`.
    #[must_use]
    pub const fn new(x: usize, y: usize) -> Self {
        Self { x, y }
    }
}

impl fmt::Display for Cell {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "({}, {})", self.x, self.y)
    }
}

/// Which moves a search may take.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Connectivity {
    /// Up, down, left, right; each costs 1.
    Four,
    /// The four orthogonal moves (cost 1) and the four diagonals (cost `√2`,
    /// only when both side cells are free).
    #[default]
    Eight,
}

/// Why a grid could not be made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum GridError {
    /// Width or height is 0.
    Empty { width: usize, height: usize },
    /// More than [`MAX_CELLS`] cells (or `width × height` overflows).
    TooLarge { width: usize, height: usize },
    /// `cells.len()` is not `width × height`.
    WrongCellCount { expected: usize, found: usize },
    /// An ASCII grid whose row `row` (0-based) has a different length from row 0.
    RaggedRow {
        row: usize,
        expected: usize,
        found: usize,
    },
    /// An ASCII grid with a character other than `.`, `#` or `@`.
    BadCharacter {
        row: usize,
        column: usize,
        found: char,
    },
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty { width, height } => {
                write!(f, "a grid needs at least one cell (got {width} × {height})")
            }
            Self::TooLarge { width, height } => write!(
                f,
                "a {width} × {height} grid is larger than the limit of {MAX_CELLS} cells"
            ),
            Self::WrongCellCount { expected, found } => {
                write!(f, "expected {expected} cells, found {found}")
            }
            Self::RaggedRow {
                row,
                expected,
                found,
            } => write!(f, "row {row} has {found} cells, expected {expected}"),
            Self::BadCharacter { row, column, found } => write!(
                f,
                "row {row}, column {column}: unexpected character {found:?} (use '.' or '#')"
            ),
        }
    }
}

impl std::error::Error for GridError {}

/// The eight moves `(dx, dy)` in the order [`OccupancyGrid::neighbours`]
/// yields them: the four orthogonal ones, then the four diagonals.
pub const MOVES: [(i8, i8); 8] = [
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (-1, 1),
    (1, -1),
    (-1, -1),
];

/// A `width × height` grid of free (`false`) and blocked (`true`) cells.
///
/// The fields are private so that `cells.len() == width · height` always holds;
/// every accessor treats a cell outside the grid as blocked and never panics.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct OccupancyGrid {
    width: usize,
    height: usize,
    cells: Vec<bool>,
}

fn check_size(width: usize, height: usize) -> Result<usize, GridError> {
    if width == 0 || height == 0 {
        return Err(GridError::Empty { width, height });
    }
    match width.checked_mul(height) {
        Some(n) if n <= MAX_CELLS => Ok(n),
        _ => Err(GridError::TooLarge { width, height }),
    }
}

impl OccupancyGrid {
    /// The heap it holds, bytes (capacities: what a copy of it costs).
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        self.cells.capacity()
    }

    /// An all-free grid.
    ///
    /// # Example
    /// ```
    /// use labcore::planning::grid::{Cell, OccupancyGrid};
    /// let g = OccupancyGrid::new(20, 15).unwrap();
    /// assert_eq!((g.width(), g.height(), g.blocked_count()), (20, 15, 0));
    /// assert!(g.is_free(Cell::new(19, 14)));
    /// assert!(!g.is_free(Cell::new(20, 0))); // outside counts as blocked
    /// assert!(OccupancyGrid::new(0, 5).is_err());
    /// ```
    pub fn new(width: usize, height: usize) -> Result<Self, GridError> {
        let n = check_size(width, height)?;
        Ok(Self {
            width,
            height,
            cells: vec![false; n],
        })
    }

    /// A grid from its cells, row by row (`true` = blocked).
    pub fn from_cells(width: usize, height: usize, cells: Vec<bool>) -> Result<Self, GridError> {
        let n = check_size(width, height)?;
        if cells.len() != n {
            return Err(GridError::WrongCellCount {
                expected: n,
                found: cells.len(),
            });
        }
        Ok(Self {
            width,
            height,
            cells,
        })
    }

    /// A grid drawn as text: one line per row, `.` free, `#` or `@` blocked.
    /// Leading and trailing whitespace of each line and blank lines are ignored,
    /// so a grid can be written indented inside a raw string.
    ///
    /// # Example
    /// ```
    /// use labcore::planning::grid::{Cell, OccupancyGrid};
    /// let g = OccupancyGrid::from_ascii("
    ///     ..#
    ///     .##
    /// ").unwrap();
    /// assert_eq!((g.width(), g.height()), (3, 2));
    /// assert!(g.is_blocked(Cell::new(2, 0)) && g.is_free(Cell::new(0, 1)));
    /// assert_eq!(g.to_ascii(), "..#\n.##\n");
    /// ```
    pub fn from_ascii(text: &str) -> Result<Self, GridError> {
        let rows: Vec<&str> = text
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect();
        let width = rows.first().map_or(0, |r| r.chars().count());
        let height = rows.len();
        let n = check_size(width, height)?;
        let mut cells = Vec::with_capacity(n);
        for (row, line) in rows.iter().enumerate() {
            let found = line.chars().count();
            if found != width {
                return Err(GridError::RaggedRow {
                    row,
                    expected: width,
                    found,
                });
            }
            for (column, c) in line.chars().enumerate() {
                cells.push(match c {
                    '.' => false,
                    '#' | '@' => true,
                    found => return Err(GridError::BadCharacter { row, column, found }),
                });
            }
        }
        Self::from_cells(width, height, cells)
    }

    /// The grid as text, `.` free and `#` blocked, each row ending in `\n`.
    #[must_use]
    pub fn to_ascii(&self) -> String {
        let mut s = String::with_capacity((self.width + 1) * self.height);
        for row in self.cells.chunks(self.width) {
            s.extend(row.iter().map(|&b| if b { '#' } else { '.' }));
            s.push('\n');
        }
        s
    }

    /// Number of columns.
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Number of rows.
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// All cells row by row, `true` = blocked (length `width · height`).
    #[must_use]
    pub fn cells(&self) -> &[bool] {
        &self.cells
    }

    /// Number of blocked cells.
    #[must_use]
    pub fn blocked_count(&self) -> usize {
        self.cells.iter().filter(|&&b| b).count()
    }

    /// Whether `cell` lies inside the grid.
    #[must_use]
    pub fn in_bounds(&self, cell: Cell) -> bool {
        cell.x < self.width && cell.y < self.height
    }

    /// The cell at signed coordinates (e.g. from a pointer position), or `None`
    /// outside the grid.
    #[must_use]
    pub fn cell_at(&self, x: i64, y: i64) -> Option<Cell> {
        let (x, y) = (usize::try_from(x).ok()?, usize::try_from(y).ok()?);
        let c = Cell::new(x, y);
        self.in_bounds(c).then_some(c)
    }

    /// `y · width + x`, or `None` outside the grid.
    #[must_use]
    pub fn index(&self, cell: Cell) -> Option<usize> {
        self.in_bounds(cell).then(|| cell.y * self.width + cell.x)
    }

    /// The cell at index `i`, or `None` past the end.
    #[must_use]
    pub fn cell_of(&self, i: usize) -> Option<Cell> {
        (i < self.cells.len()).then(|| Cell::new(i % self.width, i / self.width))
    }

    /// Whether `cell` is blocked; a cell outside the grid is blocked.
    #[must_use]
    pub fn is_blocked(&self, cell: Cell) -> bool {
        match self.index(cell) {
            Some(i) => self.cells[i],
            None => true,
        }
    }

    /// Whether `cell` is inside the grid and free.
    #[must_use]
    pub fn is_free(&self, cell: Cell) -> bool {
        !self.is_blocked(cell)
    }

    /// Sets `cell` blocked or free. Returns whether anything changed (`false`
    /// outside the grid).
    pub fn set_blocked(&mut self, cell: Cell, blocked: bool) -> bool {
        match self.index(cell) {
            Some(i) if self.cells[i] != blocked => {
                self.cells[i] = blocked;
                true
            }
            _ => false,
        }
    }

    /// Flips `cell`; returns its new state (`Some(true)` = now blocked), or
    /// `None` outside the grid.
    pub fn toggle(&mut self, cell: Cell) -> Option<bool> {
        let i = self.index(cell)?;
        self.cells[i] = !self.cells[i];
        Some(self.cells[i])
    }

    /// Frees every cell.
    pub fn clear(&mut self) {
        self.cells.fill(false);
    }

    /// The cells reachable from `cell` in one move, with the move's cost
    /// (1 or `√2`), in the order of [`MOVES`]. Diagonals need both side cells
    /// free (no corner cutting). Nothing for a blocked or outside cell.
    ///
    /// # Example
    /// ```
    /// use labcore::planning::grid::{Cell, Connectivity, OccupancyGrid};
    /// let g = OccupancyGrid::from_ascii("
    ///     ...
    ///     .#.
    ///     ...
    /// ").unwrap();
    /// // From the top-left corner: right and down; the diagonal would cut the wall's corner.
    /// let n: Vec<_> = g.neighbours(Cell::new(0, 0), Connectivity::Eight).collect();
    /// assert_eq!(n, vec![(Cell::new(1, 0), 1.0), (Cell::new(0, 1), 1.0)]);
    /// ```
    pub fn neighbours(
        &self,
        cell: Cell,
        connectivity: Connectivity,
    ) -> impl Iterator<Item = (Cell, f64)> + '_ {
        let count = if self.is_blocked(cell) {
            0
        } else {
            match connectivity {
                Connectivity::Four => 4,
                Connectivity::Eight => 8,
            }
        };
        let free = move |dx: i8, dy: i8| -> Option<Cell> {
            let x = cell.x.checked_add_signed(dx as isize)?;
            let y = cell.y.checked_add_signed(dy as isize)?;
            let c = Cell::new(x, y);
            self.is_free(c).then_some(c)
        };
        MOVES[..count].iter().filter_map(move |&(dx, dy)| {
            let to = free(dx, dy)?;
            if dx != 0 && dy != 0 {
                free(dx, 0)?;
                free(0, dy)?;
                Some((to, DIAGONAL_COST))
            } else {
                Some((to, 1.0))
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_is_row_major_and_round_trips() {
        let g = OccupancyGrid::new(7, 5).unwrap();
        assert_eq!(g.index(Cell::new(3, 2)), Some(2 * 7 + 3));
        assert_eq!(g.index(Cell::new(7, 0)), None);
        assert_eq!(g.index(Cell::new(0, 5)), None);
        for i in 0..35 {
            assert_eq!(g.index(g.cell_of(i).unwrap()), Some(i));
        }
        assert_eq!(g.cell_of(35), None);
        assert_eq!(g.cell_at(-1, 0), None);
        assert_eq!(g.cell_at(6, 4), Some(Cell::new(6, 4)));
        assert_eq!(g.cell_at(6, 5), None);
    }

    #[test]
    fn size_limits_are_errors() {
        assert_eq!(
            OccupancyGrid::new(0, 3),
            Err(GridError::Empty {
                width: 0,
                height: 3
            })
        );
        assert!(matches!(
            OccupancyGrid::new(usize::MAX, 2),
            Err(GridError::TooLarge { .. })
        ));
        assert!(matches!(
            OccupancyGrid::new(4097, 4096),
            Err(GridError::TooLarge { .. })
        ));
        assert!(OccupancyGrid::new(4096, 4096).is_ok());
        assert_eq!(
            OccupancyGrid::from_cells(2, 2, vec![false; 3]),
            Err(GridError::WrongCellCount {
                expected: 4,
                found: 3
            })
        );
    }

    #[test]
    fn ascii_errors_name_the_row() {
        assert_eq!(
            OccupancyGrid::from_ascii("...\n..\n"),
            Err(GridError::RaggedRow {
                row: 1,
                expected: 3,
                found: 2
            })
        );
        assert_eq!(
            OccupancyGrid::from_ascii("...\n.x.\n"),
            Err(GridError::BadCharacter {
                row: 1,
                column: 1,
                found: 'x'
            })
        );
        assert!(matches!(
            OccupancyGrid::from_ascii("\n  \n"),
            Err(GridError::Empty { .. })
        ));
    }

    #[test]
    fn set_and_toggle_report_changes_and_ignore_outside() {
        let mut g = OccupancyGrid::new(3, 3).unwrap();
        assert!(g.set_blocked(Cell::new(1, 1), true));
        assert!(!g.set_blocked(Cell::new(1, 1), true));
        assert_eq!(g.toggle(Cell::new(1, 1)), Some(false));
        assert_eq!(g.toggle(Cell::new(0, 2)), Some(true));
        assert_eq!(g.toggle(Cell::new(3, 0)), None);
        assert!(!g.set_blocked(Cell::new(9, 9), true));
        assert_eq!(g.blocked_count(), 1);
        g.clear();
        assert_eq!(g.blocked_count(), 0);
    }

    /// Each case: grid, cell, connectivity, the expected neighbours as (x, y, cost ×1000 rounded).
    #[test]
    fn neighbour_table() {
        let g = OccupancyGrid::from_ascii(
            "
            ....
            .#..
            ....
            ...#
            ",
        )
        .unwrap();
        const D: i64 = 1414;
        type Expected = &'static [(usize, usize, i64)];
        let cases: &[(Cell, Connectivity, Expected)] = &[
            (
                Cell::new(0, 0),
                Connectivity::Eight,
                &[(1, 0, 1000), (0, 1, 1000)],
            ),
            (
                Cell::new(2, 2),
                Connectivity::Eight,
                &[
                    (3, 2, 1000),
                    (1, 2, 1000),
                    (2, 3, 1000),
                    (2, 1, 1000),
                    // (3,3) blocked, (1,3) ok, (3,1) ok, (1,1) blocked
                    (1, 3, D),
                    (3, 1, D),
                ],
            ),
            (
                Cell::new(2, 2),
                Connectivity::Four,
                &[(3, 2, 1000), (1, 2, 1000), (2, 3, 1000), (2, 1, 1000)],
            ),
            // (2,3)->(3,2)? from (2,3): right (3,3) blocked, so the diagonal to (3,2) cuts a corner.
            (
                Cell::new(2, 3),
                Connectivity::Eight,
                &[(1, 3, 1000), (2, 2, 1000), (1, 2, D)],
            ),
            (Cell::new(1, 1), Connectivity::Eight, &[]),
            (Cell::new(4, 0), Connectivity::Eight, &[]),
        ];
        for (cell, conn, expected) in cases {
            let got: Vec<(usize, usize, i64)> = g
                .neighbours(*cell, *conn)
                .map(|(c, cost)| (c.x, c.y, (cost * 1000.0) as i64))
                .collect();
            assert_eq!(&got, expected, "from {cell} with {conn:?}");
        }
    }
}
