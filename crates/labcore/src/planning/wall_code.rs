//! A compact, URL-safe text code for an occupancy grid's walls, so a page can
//! keep the grid in its URL state.
//!
//! ```text
//! <width>x<height>.<run>.<run>.<run>…
//! ```
//!
//! The cells are read row by row (index `y · width + x`) as alternating runs
//! of free and blocked cells, **starting with free** (so a grid whose first
//! cell is a wall starts with a run of 0). Each run length is written in base
//! 36 (`0-9a-z`); runs are separated by `.`; the runs add up to
//! `width · height` (a final free run may be left out). Every character is
//! unreserved in a URL (RFC 3986 §2.3), so the code needs no escaping. An empty
//! 20 × 15 grid is `20x15`; a maze of 41 × 31 takes about 1.5 kB.
//!
//! Random fills have many short runs; above the page's URL budget
//! ([`encoded_len`] tells the size without building the string) the page
//! offers a `.map` file instead ([`super::movingai`]).

use std::fmt;

use super::grid::{GridError, OccupancyGrid};

/// Why a wall code could not be read. Positions are 0-based character offsets.
#[derive(Clone, Debug, PartialEq)]
pub enum WallCodeError {
    /// The `<width>x<height>` head is missing or not two positive numbers.
    BadSize { found: String },
    /// The size is not a valid grid (zero, or over the cell limit).
    Grid(GridError),
    /// A run is not a base-36 number.
    BadRun { position: usize, found: String },
    /// The runs add up to more cells than the grid has.
    TooManyCells { expected: usize },
}

impl fmt::Display for WallCodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BadSize { found } => {
                write!(
                    f,
                    "the grid code must start with <width>x<height>, found `{found}`"
                )
            }
            Self::Grid(e) => write!(f, "{e}"),
            Self::BadRun { position, found } => {
                write!(f, "character {position}: `{found}` is not a run length")
            }
            Self::TooManyCells { expected } => {
                write!(f, "the runs describe more than the grid's {expected} cells")
            }
        }
    }
}

impl std::error::Error for WallCodeError {}

/// Runs of equal cells, alternating free / blocked, starting with free.
fn runs(grid: &OccupancyGrid) -> impl Iterator<Item = usize> + '_ {
    let cells = grid.cells();
    let mut i = 0;
    let mut want_blocked = false;
    std::iter::from_fn(move || {
        if i >= cells.len() {
            return None;
        }
        let start = i;
        while i < cells.len() && cells[i] == want_blocked {
            i += 1;
        }
        want_blocked = !want_blocked;
        Some(i - start)
    })
}

fn base36_len(mut n: usize) -> usize {
    let mut len = 1;
    while n >= 36 {
        n /= 36;
        len += 1;
    }
    len
}

fn push_base36(out: &mut String, mut n: usize) {
    const DIGITS: &[u8; 36] = b"0123456789abcdefghijklmnopqrstuvwxyz";
    let mut buf = [0u8; 16];
    let mut k = buf.len();
    loop {
        k -= 1;
        buf[k] = DIGITS[n % 36];
        n /= 36;
        if n == 0 {
            break;
        }
    }
    out.extend(buf[k..].iter().map(|&b| b as char));
}

/// Trailing free cells need no run.
fn significant_runs(grid: &OccupancyGrid) -> Vec<usize> {
    let mut r: Vec<usize> = runs(grid).collect();
    if r.len() % 2 == 1 {
        r.pop(); // a last free run
    }
    r
}

/// The code of `grid` (module docs).
///
/// # Example
/// ```
/// use labcore::planning::grid::OccupancyGrid;
/// use labcore::planning::wall_code::{decode_walls, encode_walls};
/// // ('@' for walls: a doc line starting with '#' would be hidden by rustdoc)
/// let g = OccupancyGrid::from_ascii("
///     @@..
///     ....
///     ..@.
/// ").unwrap();
/// assert_eq!(encode_walls(&g), "4x3.0.2.8.1");
/// assert_eq!(decode_walls("4x3.0.2.8.1").unwrap(), g);
/// assert_eq!(encode_walls(&OccupancyGrid::new(20, 15).unwrap()), "20x15");
/// ```
#[must_use]
pub fn encode_walls(grid: &OccupancyGrid) -> String {
    let mut s = format!("{}x{}", grid.width(), grid.height());
    for r in significant_runs(grid) {
        s.push('.');
        push_base36(&mut s, r);
    }
    s
}

/// Length in bytes of [`encode_walls`]'s result, without building it.
#[must_use]
pub fn encoded_len(grid: &OccupancyGrid) -> usize {
    let head = format!("{}x{}", grid.width(), grid.height()).len();
    head + significant_runs(grid)
        .iter()
        .map(|&r| 1 + base36_len(r))
        .sum::<usize>()
}

/// Reads a code written by [`encode_walls`].
///
/// # Errors
/// [`WallCodeError`] naming what was wrong and where.
pub fn decode_walls(code: &str) -> Result<OccupancyGrid, WallCodeError> {
    let mut parts = code.split('.');
    let head = parts.next().unwrap_or("");
    let bad_size = || WallCodeError::BadSize {
        found: head.to_string(),
    };
    let (w, h) = head.split_once('x').ok_or_else(bad_size)?;
    let parse = |s: &str| {
        s.parse::<usize>()
            .ok()
            .filter(|_| s.bytes().all(|b| b.is_ascii_digit()))
    };
    let (width, height) = match (parse(w), parse(h)) {
        (Some(w), Some(h)) => (w, h),
        _ => return Err(bad_size()),
    };
    // Size check first, so `width · height` below cannot overflow.
    OccupancyGrid::new(width, height).map_err(WallCodeError::Grid)?;
    let total = width * height;
    let mut cells = Vec::with_capacity(total);
    let mut blocked = false;
    let mut position = head.len() + 1;
    for part in parts {
        let n = if part.is_empty() || part.len() > 12 {
            None
        } else {
            usize::from_str_radix(part, 36).ok().filter(|_| {
                part.bytes()
                    .all(|b| b.is_ascii_digit() || b.is_ascii_lowercase())
            })
        };
        let Some(n) = n else {
            return Err(WallCodeError::BadRun {
                position,
                found: part.to_string(),
            });
        };
        if n > total - cells.len() {
            return Err(WallCodeError::TooManyCells { expected: total });
        }
        cells.resize(cells.len() + n, blocked);
        blocked = !blocked;
        position += part.len() + 1;
    }
    cells.resize(total, false);
    OccupancyGrid::from_cells(width, height, cells).map_err(WallCodeError::Grid)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::maze::{random_fill, recursive_backtracker};
    use crate::rng::Lcg64;

    #[test]
    fn round_trips_and_length_matches() {
        let mut rng = Lcg64::new(4);
        let mut grids = vec![
            OccupancyGrid::new(1, 1).unwrap(),
            OccupancyGrid::from_cells(2, 1, vec![true, true]).unwrap(),
            recursive_backtracker(41, 31, 3).unwrap(),
            recursive_backtracker(512, 512, 3).unwrap(),
        ];
        for _ in 0..50 {
            let (w, h) = (rng.int(1, 40) as usize, rng.int(1, 40) as usize);
            grids.push(random_fill(w, h, rng.range(0.0, 100.0), &mut rng).unwrap());
        }
        for g in &grids {
            let code = encode_walls(g);
            assert_eq!(code.len(), encoded_len(g));
            assert!(code.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'.'));
            assert_eq!(&decode_walls(&code).unwrap(), g);
        }
        let maze = encode_walls(&grids[2]);
        assert!(maze.len() < 2000, "{}", maze.len());
    }

    #[test]
    fn malformed_codes_are_errors() {
        let cases: &[(&str, &str)] = &[
            ("", "must start with"),
            ("20", "must start with"),
            ("20x", "must start with"),
            ("+2x3", "must start with"),
            ("0x3", "at least one cell"),
            ("99999x99999", "larger than the limit"),
            ("4x3.0.2.Z", "character 8"),
            ("4x3..1", "character 4"),
            ("4x3.c.1", "more than the grid's 12 cells"),
        ];
        for (code, words) in cases {
            let e = decode_walls(code).expect_err(code);
            assert!(e.to_string().contains(words), "{code}: `{e}`");
        }
    }
}
