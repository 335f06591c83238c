//! The Moving AI benchmark formats: `.map` grids and `.scen` scenario lists
//! (Sturtevant, "Benchmarks for Grid-Based Pathfinding", *IEEE Trans. Comput.
//! Intell. AI Games* 4(2), 2012, pp. 144–148; the format is described at the
//! Moving AI Lab's benchmark page).
//!
//! A `.map` file is a four-line header, then `height` rows of `width`
//! characters:
//!
//! ```text
//! type octile
//! height 3
//! width 4
//! map
//! ..@.
//! .T..
//! ....
//! ```
//!
//! `.` and `G` are free; `@`, `O`, `T` (tree), `S` (swamp) and `W` (water) are
//! blocked — the lab's rule, which treats swamp and water as obstacles. Row `y`
//! of the file is grid row `y`. [`parse_map`] also accepts `height` and
//! `width` in either order, `\r\n` line ends and trailing blank lines.
//!
//! A `.scen` file starts with `version 1` (or `version 1.0`), then one
//! scenario per line, nine fields separated by tabs or spaces: bucket, map
//! file, map width, map height, start x, start y, goal x, goal y, optimal
//! length. The optimal lengths assume octile costs (1, `√2`) and no corner
//! cutting, the lab's [`super::grid`] rule.
//!
//! Every parse error names the 1-based line (and, for a bad character, the
//! 1-based column) and what was expected, so the page can show it as is.

use std::fmt;

use super::grid::{Cell, GridError, OccupancyGrid, MAX_CELLS};

/// The arena map of the Moving AI "Dragon Age: Origins" set (49 × 49), bundled for the page.
pub const ARENA_MAP: &str = include_str!("../../../../assets/maps/arena.map");
/// The 130 scenarios of [`ARENA_MAP`] with their optimal lengths.
pub const ARENA_SCEN: &str = include_str!("../../../../assets/maps/arena.map.scen");

/// What was wrong on a line.
#[derive(Clone, Debug, PartialEq)]
pub enum FormatErrorKind {
    /// The file ended before something that was expected.
    UnexpectedEnd { expected: String },
    /// A header or version line other than the expected one.
    BadHeader {
        expected: &'static str,
        found: String,
    },
    /// A map type other than `octile`.
    UnsupportedType { found: String },
    /// A field that should be a number (or a non-negative finite one).
    BadNumber { field: &'static str, found: String },
    /// `height` or `width` given twice.
    DuplicateHeader { field: &'static str },
    /// A 0 or too-large map size.
    BadSize { width: usize, height: usize },
    /// A map row of the wrong length.
    RowLength { expected: usize, found: usize },
    /// A map character that is not one of `. G @ O T S W`.
    BadTerrain { column: usize, found: char },
    /// A non-blank line after the last map row.
    TrailingText,
    /// A scenario line without exactly nine fields.
    FieldCount { found: usize },
    /// A scenario's start or goal outside its map size.
    OutOfMap {
        which: &'static str,
        x: usize,
        y: usize,
    },
}

/// A malformed `.map` or `.scen` file: the 1-based line and what was wrong there.
#[derive(Clone, Debug, PartialEq)]
pub struct FormatError {
    /// 1-based line number (for [`FormatErrorKind::UnexpectedEnd`], one past the last line).
    pub line: usize,
    pub kind: FormatErrorKind,
}

impl fmt::Display for FormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: ", self.line)?;
        match &self.kind {
            FormatErrorKind::UnexpectedEnd { expected } => {
                write!(f, "the file ends where {expected} was expected")
            }
            FormatErrorKind::BadHeader { expected, found } => {
                write!(f, "expected `{expected}`, found `{found}`")
            }
            FormatErrorKind::UnsupportedType { found } => {
                write!(f, "map type `{found}` is not supported (only `octile`)")
            }
            FormatErrorKind::BadNumber { field, found } => {
                write!(f, "{field} must be a number, found `{found}`")
            }
            FormatErrorKind::DuplicateHeader { field } => write!(f, "`{field}` is given twice"),
            FormatErrorKind::BadSize { width, height } => write!(
                f,
                "a {width} × {height} map is not allowed (1 to {MAX_CELLS} cells)"
            ),
            FormatErrorKind::RowLength { expected, found } => {
                write!(f, "the row has {found} cells, expected {expected}")
            }
            FormatErrorKind::BadTerrain { column, found } => write!(
                f,
                "column {column}: unknown terrain {found:?} (expected one of . G @ O T S W)"
            ),
            FormatErrorKind::TrailingText => write!(f, "unexpected text after the last map row"),
            FormatErrorKind::FieldCount { found } => {
                write!(f, "a scenario has 9 fields, found {found}")
            }
            FormatErrorKind::OutOfMap { which, x, y } => {
                write!(f, "the {which} ({x}, {y}) lies outside the map")
            }
        }
    }
}

impl std::error::Error for FormatError {}

fn err(line: usize, kind: FormatErrorKind) -> FormatError {
    FormatError { line, kind }
}

/// Whether a `.map` terrain character is blocked (`Some(true)`), free
/// (`Some(false)`) or unknown (`None`).
#[must_use]
pub fn terrain_blocked(c: char) -> Option<bool> {
    match c {
        '.' | 'G' => Some(false),
        '@' | 'O' | 'T' | 'S' | 'W' => Some(true),
        _ => None,
    }
}

/// Numbered lines (1-based) without their line ends.
fn numbered(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines()
        .map(|l| l.strip_suffix('\r').unwrap_or(l))
        .enumerate()
        .map(|(i, l)| (i + 1, l))
}

/// Reads a `.map` file (module docs).
///
/// # Errors
/// A [`FormatError`] naming the first bad line.
///
/// # Example
/// ```
/// use labcore::planning::grid::Cell;
/// use labcore::planning::movingai::{parse_map, write_map};
/// let text = "type octile\nheight 2\nwidth 3\nmap\n.@.\nT.G\n";
/// let grid = parse_map(text).unwrap();
/// assert_eq!((grid.width(), grid.height()), (3, 2));
/// assert!(grid.is_blocked(Cell::new(1, 0)) && grid.is_free(Cell::new(2, 1)));
/// assert_eq!(write_map(&grid), "type octile\nheight 2\nwidth 3\nmap\n.@.\n@..\n");
///
/// let bad = "type octile\nheight 2\nwidth 3\nmap\n.@.\n.x.\n";
/// assert_eq!(
///     parse_map(bad).unwrap_err().to_string(),
///     "line 6: column 2: unknown terrain 'x' (expected one of . G @ O T S W)"
/// );
/// ```
pub fn parse_map(text: &str) -> Result<OccupancyGrid, FormatError> {
    let mut lines = numbered(text);
    let mut last_line = 0;
    let mut next = |expected: &str| -> Result<(usize, &str), FormatError> {
        match lines.next() {
            Some((n, l)) => {
                last_line = n;
                Ok((n, l))
            }
            None => Err(err(
                last_line + 1,
                FormatErrorKind::UnexpectedEnd {
                    expected: expected.to_string(),
                },
            )),
        }
    };

    let (n, line) = next("`type octile`")?;
    let mut words = line.split_whitespace();
    match (words.next(), words.next(), words.next()) {
        (Some("type"), Some("octile"), None) => {}
        (Some("type"), Some(other), None) => {
            return Err(err(
                n,
                FormatErrorKind::UnsupportedType {
                    found: other.to_string(),
                },
            ))
        }
        _ => {
            return Err(err(
                n,
                FormatErrorKind::BadHeader {
                    expected: "type octile",
                    found: line.to_string(),
                },
            ))
        }
    }

    let (mut width, mut height) = (None, None);
    for _ in 0..2 {
        let (n, line) = next("`height H` or `width W`")?;
        let mut words = line.split_whitespace();
        let (key, value, extra) = (words.next(), words.next(), words.next());
        let (field, slot) = match key {
            Some("height") => ("height", &mut height),
            Some("width") => ("width", &mut width),
            _ => {
                return Err(err(
                    n,
                    FormatErrorKind::BadHeader {
                        expected: "height H` or `width W",
                        found: line.to_string(),
                    },
                ))
            }
        };
        if slot.is_some() {
            return Err(err(n, FormatErrorKind::DuplicateHeader { field }));
        }
        let parsed = match (value, extra) {
            (Some(v), None) => v.parse::<usize>().ok(),
            _ => None,
        };
        let Some(v) = parsed else {
            return Err(err(
                n,
                FormatErrorKind::BadNumber {
                    field,
                    found: value.unwrap_or("").to_string(),
                },
            ));
        };
        *slot = Some(v);
    }
    let (width, height) = (width.unwrap_or(0), height.unwrap_or(0));

    let (n, line) = next("`map`")?;
    if line.trim() != "map" {
        return Err(err(
            n,
            FormatErrorKind::BadHeader {
                expected: "map",
                found: line.to_string(),
            },
        ));
    }
    let cells_n = match OccupancyGrid::new(width, height) {
        Ok(_) => width * height,
        Err(_) => return Err(err(n, FormatErrorKind::BadSize { width, height })),
    };

    let mut cells = Vec::with_capacity(cells_n);
    for row in 0..height {
        let (n, line) = next(&format!("map row {} of {height}", row + 1))?;
        let found = line.chars().count();
        if found != width {
            return Err(err(
                n,
                FormatErrorKind::RowLength {
                    expected: width,
                    found,
                },
            ));
        }
        for (column, c) in line.chars().enumerate() {
            match terrain_blocked(c) {
                Some(b) => cells.push(b),
                None => {
                    return Err(err(
                        n,
                        FormatErrorKind::BadTerrain {
                            column: column + 1,
                            found: c,
                        },
                    ))
                }
            }
        }
    }
    for (n, line) in lines {
        if !line.trim().is_empty() {
            return Err(err(n, FormatErrorKind::TrailingText));
        }
    }
    OccupancyGrid::from_cells(width, height, cells).map_err(|e| match e {
        GridError::Empty { .. } | GridError::TooLarge { .. } => {
            err(4, FormatErrorKind::BadSize { width, height })
        }
        _ => err(
            4,
            FormatErrorKind::RowLength {
                expected: width,
                found: 0,
            },
        ),
    })
}

/// Writes `grid` as a `.map` file: free cells `.`, blocked `@`, `\n` line ends.
#[must_use]
pub fn write_map(grid: &OccupancyGrid) -> String {
    let mut s = format!(
        "type octile\nheight {}\nwidth {}\nmap\n",
        grid.height(),
        grid.width()
    );
    s.reserve((grid.width() + 1) * grid.height());
    for row in grid.cells().chunks(grid.width()) {
        s.extend(row.iter().map(|&b| if b { '@' } else { '.' }));
        s.push('\n');
    }
    s
}

/// One line of a `.scen` file.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Difficulty bucket (about optimal length / 4).
    pub bucket: u32,
    /// The map file the scenario belongs to.
    pub map: String,
    pub map_width: usize,
    pub map_height: usize,
    pub start: Cell,
    pub goal: Cell,
    /// Optimal octile path length, no corner cutting.
    pub optimal_length: f64,
}

/// Reads a `.scen` file (module docs). Blank lines are skipped.
///
/// # Errors
/// A [`FormatError`] naming the first bad line.
///
/// # Example
/// ```
/// use labcore::planning::grid::Cell;
/// use labcore::planning::movingai::parse_scen;
/// let text = "version 1\n0\tarena.map\t49\t49\t1\t2\t3\t4\t2.82842712\n";
/// let s = parse_scen(text).unwrap();
/// assert_eq!(s[0].start, Cell::new(1, 2));
/// assert_eq!(s[0].goal, Cell::new(3, 4));
/// let e = parse_scen("version 1\n0 arena.map 49 49 1 2 3 4\n").unwrap_err();
/// assert_eq!(e.line, 2);
/// ```
pub fn parse_scen(text: &str) -> Result<Vec<Scenario>, FormatError> {
    let mut lines = numbered(text);
    let Some((n, first)) = lines.next() else {
        return Err(err(
            1,
            FormatErrorKind::UnexpectedEnd {
                expected: "`version 1`".to_string(),
            },
        ));
    };
    let mut words = first.split_whitespace();
    let version_ok = matches!(
        (words.next(), words.next(), words.next()),
        (Some("version"), Some(v), None) if v.parse::<f64>().is_ok()
    );
    if !version_ok {
        return Err(err(
            n,
            FormatErrorKind::BadHeader {
                expected: "version 1",
                found: first.to_string(),
            },
        ));
    }
    let mut out = Vec::new();
    for (n, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.len() != 9 {
            return Err(err(
                n,
                FormatErrorKind::FieldCount {
                    found: fields.len(),
                },
            ));
        }
        const NAMES: [&str; 9] = [
            "bucket",
            "map",
            "map width",
            "map height",
            "start x",
            "start y",
            "goal x",
            "goal y",
            "optimal length",
        ];
        let int = |i: usize| -> Result<usize, FormatError> {
            fields[i].parse::<usize>().map_err(|_| {
                err(
                    n,
                    FormatErrorKind::BadNumber {
                        field: NAMES[i],
                        found: fields[i].to_string(),
                    },
                )
            })
        };
        let bucket = fields[0].parse::<u32>().map_err(|_| {
            err(
                n,
                FormatErrorKind::BadNumber {
                    field: NAMES[0],
                    found: fields[0].to_string(),
                },
            )
        })?;
        let (map_width, map_height) = (int(2)?, int(3)?);
        let start = Cell::new(int(4)?, int(5)?);
        let goal = Cell::new(int(6)?, int(7)?);
        let optimal_length = match fields[8].parse::<f64>() {
            Ok(v) if v.is_finite() && v >= 0.0 => v,
            _ => {
                return Err(err(
                    n,
                    FormatErrorKind::BadNumber {
                        field: NAMES[8],
                        found: fields[8].to_string(),
                    },
                ))
            }
        };
        for (which, c) in [("start", start), ("goal", goal)] {
            if c.x >= map_width || c.y >= map_height {
                return Err(err(
                    n,
                    FormatErrorKind::OutOfMap {
                        which,
                        x: c.x,
                        y: c.y,
                    },
                ));
            }
        }
        out.push(Scenario {
            bucket,
            map: fields[1].to_string(),
            map_width,
            map_height,
            start,
            goal,
            optimal_length,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::astar::{astar_path, Search, SearchConfig};
    use crate::planning::grid::Connectivity;
    use crate::planning::heuristic::Heuristic;

    #[test]
    fn arena_map_reads_and_round_trips() {
        let grid = parse_map(ARENA_MAP).unwrap();
        assert_eq!((grid.width(), grid.height()), (49, 49));
        assert!(grid.is_blocked(Cell::new(0, 0))); // 'T'
        assert!(grid.is_free(Cell::new(3, 1))); // '.'
        let again = parse_map(&write_map(&grid)).unwrap();
        assert_eq!(again, grid);
        // Windows line ends and a trailing blank line are fine.
        let crlf = ARENA_MAP.replace('\n', "\r\n") + "\r\n";
        assert_eq!(parse_map(&crlf).unwrap(), grid);
    }

    /// Every arena scenario: octile A* (and Dijkstra) length equals the file's
    /// optimal length to 1e-6, and the path ends where it should.
    #[test]
    fn all_arena_scenarios_are_optimal() {
        let grid = parse_map(ARENA_MAP).unwrap();
        let scen = parse_scen(ARENA_SCEN).unwrap();
        assert_eq!(scen.len(), 130);
        let mut search =
            Search::new(&grid, scen[0].start, scen[0].goal, SearchConfig::default()).unwrap();
        for (i, s) in scen.iter().enumerate() {
            assert_eq!(
                (s.map.as_str(), s.map_width, s.map_height),
                ("arena.map", 49, 49)
            );
            for config in [
                SearchConfig::astar(Connectivity::Eight, Heuristic::Octile),
                SearchConfig::astar(Connectivity::Eight, Heuristic::Euclidean),
                SearchConfig::dijkstra(Connectivity::Eight),
            ] {
                search.reset(&grid, s.start, s.goal, config).unwrap();
                search.run();
                let r = search
                    .result()
                    .unwrap_or_else(|| panic!("scenario {i}: no path"));
                assert!(
                    (r.cost - s.optimal_length).abs() < 1e-6,
                    "scenario {} ({:?}): {} vs {}",
                    i + 2,
                    config.heuristic,
                    r.cost,
                    s.optimal_length
                );
                assert_eq!((r.path[0], *r.path.last().unwrap()), (s.start, s.goal));
            }
        }
        // The one-shot function agrees.
        let last = scen.last().unwrap();
        let r = astar_path(&grid, last.start, last.goal, SearchConfig::default())
            .unwrap()
            .unwrap();
        assert!((r.cost - last.optimal_length).abs() < 1e-6);
    }

    /// Malformed maps: (text, expected line, a word the message must contain).
    #[test]
    fn malformed_maps_name_the_line() {
        let cases: &[(&str, usize, &str)] = &[
            ("", 1, "ends where `type octile` was expected"),
            ("type grid\nheight 1\nwidth 1\nmap\n.\n", 1, "`grid`"),
            ("typo octile\n", 1, "expected `type octile`"),
            ("type octile\n", 2, "ends where `height H` or `width W`"),
            (
                "type octile\nheight x\nwidth 1\nmap\n.\n",
                2,
                "height must be a number",
            ),
            ("type octile\nheight 1\nheight 1\n", 3, "given twice"),
            (
                "type octile\nheight 1\nlength 1\nmap\n.\n",
                3,
                "expected `height H` or `width W`",
            ),
            (
                "type octile\nheight 1\nwidth 1 2\nmap\n.\n",
                3,
                "width must be a number",
            ),
            (
                "type octile\nheight 1\nwidth 1\nmop\n.\n",
                4,
                "expected `map`",
            ),
            ("type octile\nheight 0\nwidth 5\nmap\n", 4, "0 map"),
            (
                "type octile\nheight 100000\nwidth 100000\nmap\n",
                4,
                "not allowed",
            ),
            (
                "type octile\nheight 2\nwidth 3\nmap\n...\n..\n",
                6,
                "has 2 cells, expected 3",
            ),
            (
                "type octile\nheight 2\nwidth 3\nmap\n...\n",
                6,
                "map row 2 of 2",
            ),
            (
                "type octile\nheight 2\nwidth 3\nmap\n...\n..#\n",
                6,
                "column 3",
            ),
            (
                "type octile\nheight 1\nwidth 3\nmap\n...\n\nxyz\n",
                7,
                "after the last map row",
            ),
        ];
        for (text, line, words) in cases {
            let e = parse_map(text).expect_err(text);
            assert_eq!(e.line, *line, "{text:?}: {e}");
            let msg = e.to_string();
            assert!(msg.contains(words), "{text:?}: `{msg}` lacks `{words}`");
            assert!(msg.starts_with(&format!("line {line}: ")));
        }
        // Every terrain letter of the format is accepted.
        let g = parse_map("type octile\nwidth 7\nheight 1\nmap\n.G@OTSW\n").unwrap();
        assert_eq!(g.cells(), &[false, false, true, true, true, true, true]);
    }

    #[test]
    fn malformed_scenarios_name_the_line() {
        let good = "0\tarena.map\t49\t49\t1\t2\t3\t4\t2.5";
        let cases: Vec<(String, usize, &str)> = vec![
            (String::new(), 1, "ends where `version 1` was expected"),
            ("versio 1\n".into(), 1, "expected `version 1`"),
            (
                format!("version 1\n{good}\n\n0 a 49 49 1 2 3\n"),
                4,
                "9 fields, found 7",
            ),
            (
                format!("version 1.0\n{good}\nx a 4 4 1 1 1 1 1\n"),
                3,
                "bucket must be",
            ),
            (
                "version 1\n0 a 4 4 1 -1 1 1 1\n".into(),
                2,
                "start y must be",
            ),
            (
                "version 1\n0 a 4 4 1 1 1 1 nan\n".into(),
                2,
                "optimal length must be",
            ),
            (
                "version 1\n0 a 4 4 1 1 4 1 1\n".into(),
                2,
                "goal (4, 1) lies outside",
            ),
        ];
        for (text, line, words) in &cases {
            let e = parse_scen(text).expect_err(text);
            assert_eq!(e.line, *line, "{text:?}: {e}");
            assert!(
                e.to_string().contains(words),
                "{text:?}: `{e}` lacks `{words}`"
            );
        }
        assert_eq!(
            parse_scen(&format!("version 1\n{good}\n")).unwrap().len(),
            1
        );
    }
}
