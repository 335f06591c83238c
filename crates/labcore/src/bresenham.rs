//! Bresenham's line: the cells (or pixels) of a straight line between two
//! integer points, one per step along the longer axis.
//!
//! One algorithm, two users: the A* grid paints walls along a fast drag
//! with it (no gaps between the cells the pointer reported), and the canvas
//! draws big batches of segments pixel by pixel with it (labweb `draw.rs`
//! and its kept layers).
//!
//! Reference: J. E. Bresenham, "Algorithm for computer control of a digital
//! plotter", IBM Systems Journal 4(1), 1965, pp. 25–30 (here in its
//! all-octant integer-error form).

/// Calls `visit(x, y)` for each cell of the line from `from` to `to`, both
/// ends included, in order from `from`: every cell touches the previous one
/// by an edge or a corner, and there is one cell per column of an x-major
/// line (per row of a y-major one), so `max(|dx|, |dy|) + 1` cells.
///
/// The caller clips the ends first when only a window of the plane matters:
/// the walk is linear in the line's length.
///
/// # Example
/// ```
/// let mut cells = Vec::new();
/// labcore::bresenham::line((0, 0), (6, 2), |x, y| cells.push((x, y)));
/// // y = x/3 rounded: 0, 0.33, 0.67, 1, 1.33, 1.67, 2.
/// assert_eq!(cells, [(0, 0), (1, 0), (2, 1), (3, 1), (4, 1), (5, 2), (6, 2)]);
/// ```
#[inline]
pub fn line(from: (i64, i64), to: (i64, i64), mut visit: impl FnMut(i64, i64)) {
    let (mut x, mut y) = from;
    let (x1, y1) = to;
    let (dx, dy) = ((x1 - x).abs(), -(y1 - y).abs());
    let (sx, sy) = (if x < x1 { 1 } else { -1 }, if y < y1 { 1 } else { -1 });
    let mut err = dx + dy;
    // At most |dx| + |dy| + 1 cells: a bound, so no input loops for ever.
    for _ in 0..=(dx - dy) {
        visit(x, y);
        if x == x1 && y == y1 {
            break;
        }
        let e2 = 2 * err;
        if e2 >= dy {
            err += dy;
            x += sx;
        }
        if e2 <= dx {
            err += dx;
            y += sy;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::line;

    fn cells(from: (i64, i64), to: (i64, i64)) -> Vec<(i64, i64)> {
        let mut out = Vec::new();
        line(from, to, |x, y| out.push((x, y)));
        out
    }

    #[test]
    fn a_line_visits_one_cell_per_step_of_its_longer_axis_from_end_to_end() {
        for (from, to) in [
            ((0, 0), (5, 2)),
            ((3, 7), (2, 0)),
            ((-4, 3), (6, -1)),
            ((2, 2), (-3, -3)),
            ((0, 0), (0, -6)),
            ((1, 1), (1, 1)),
        ] {
            let c = cells(from, to);
            let long = (to.0 - from.0).abs().max((to.1 - from.1).abs());
            assert_eq!(c.len() as i64, long + 1, "{from:?} → {to:?}");
            assert_eq!(c.first(), Some(&from));
            assert_eq!(c.last(), Some(&to));
            assert!(
                c.windows(2).all(|w| {
                    let (ax, ay, bx, by) = (w[0].0, w[0].1, w[1].0, w[1].1);
                    (ax - bx).abs() <= 1 && (ay - by).abs() <= 1 && w[0] != w[1]
                }),
                "{from:?} → {to:?}: {c:?}"
            );
        }
    }

    #[test]
    fn a_line_stays_within_half_a_cell_of_the_true_line() {
        let (from, to) = ((0i64, 0i64), (13i64, 5i64));
        for (x, y) in cells(from, to) {
            let exact = y as f64 - x as f64 * 5.0 / 13.0;
            assert!(exact.abs() <= 0.5 + 1e-12, "({x}, {y})");
        }
    }

    #[test]
    fn the_line_back_covers_the_same_cells_for_a_diagonal_and_an_axis() {
        for (from, to) in [((0, 0), (4, 4)), ((0, 0), (7, 0)), ((2, -3), (2, 5))] {
            let mut back = cells(to, from);
            back.reverse();
            assert_eq!(cells(from, to), back);
        }
    }
}
