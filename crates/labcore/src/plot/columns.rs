//! A dense series drawn as pixel columns: for each column of the plot, the
//! vertical extent of the polyline through the series' points.
//!
//! A stroked line through a noisy series of a few points per pixel column
//! (the [`decimate_min_max`](super::decimate_min_max) output of a 60-second
//! EKF error at 60 Hz: first, minimum, maximum and last in each column) is a
//! zigzag, and a canvas rasterises a thick stroke of a zigzag slowly: measured
//! in Chromium's software canvas (no GPU, as in the lab's phone stand-in),
//! three such series of 680 points over 340 columns, 2 CSS px wide at DPR 2,
//! took 4–13 ms to rasterise (no CPU throttle) against 0.8–1.6 ms for one
//! filled rectangle per column covering the same pixels. Over one column the polyline covers the interval
//! `[min, max]` of its points inside the column and of its values where it
//! crosses the column's edges (linear interpolation), so a column's rectangle,
//! widened by the line's width, covers what the stroke covers, and adjacent
//! columns join where the line crosses their shared edge.

/// The y interval `(low, high)` the polyline through `points` covers in each
/// of `columns` equal columns of `[left, left + width]` (coordinates in
/// pixels: columns are pixel columns); `low > high` (∞, −∞) in a column the
/// line does not reach.
///
/// Points are joined in order, as a canvas path joins them; a point with a
/// non-finite coordinate is skipped (a canvas ignores it too) and the line
/// goes on from the last finite point. The line is clipped to the columns.
/// Returns `None` (no column picture) when the x of the finite points ever
/// decreases: such a line (a phase portrait) may cross a column twice.
pub fn column_spans(
    points: impl IntoIterator<Item = (f64, f64)>,
    left: f64,
    width: f64,
    columns: usize,
) -> Option<Vec<(f64, f64)>> {
    let mut spans = vec![(f64::INFINITY, f64::NEG_INFINITY); columns];
    let column_width = width / columns as f64;
    let column_of =
        |x: f64| (((x - left) / column_width).floor().max(0.0) as usize).min(columns - 1);
    let mut previous: Option<(f64, f64)> = None;
    for (x, y) in points {
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        // The segment from the previous point (a lone first point: from
        // itself); its start was covered with the segment before it.
        let (xa, ya) = previous.replace((x, y)).unwrap_or((x, y));
        if x < xa {
            return None;
        }
        let (from, to) = (xa.max(left), x.min(left + width));
        if from > to || columns == 0 {
            continue;
        }
        let (first, last) = (column_of(from), column_of(to));
        for (c, span) in spans.iter_mut().enumerate().take(last + 1).skip(first) {
            let edge = left + c as f64 * column_width;
            for at in [from.max(edge), to.min(edge + column_width)] {
                // The line's y at `at`: the points' own y at their own x.
                let v = if at >= x {
                    y
                } else if at <= xa {
                    ya
                } else {
                    ya + (y - ya) * (at - xa) / (x - xa)
                };
                *span = (span.0.min(v), span.1.max(v));
            }
        }
    }
    Some(spans)
}

/// Whether the dash pattern `dash` (on and off lengths, repeated; empty is
/// solid) is on at distance `at` from its start. A line drawn in columns
/// takes its dashes along x.
#[must_use]
pub fn dash_is_on(dash: &[f64], at: f64) -> bool {
    let period: f64 = dash.iter().sum();
    if dash.is_empty() || period.is_nan() || period <= 0.0 {
        return true;
    }
    // `at` modulo the period (not `rem_euclid`: its `fmod` would add a
    // kilobyte to every wasm module).
    let mut into = at - (at / period).floor() * period;
    for (i, length) in dash.iter().enumerate() {
        if into < *length {
            return i % 2 == 0;
        }
        into -= length;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spans over `columns` 1-px columns from 0, `None` where empty.
    fn spans(points: &[(f64, f64)], columns: usize) -> Vec<Option<(f64, f64)>> {
        column_spans(points.iter().copied(), 0.0, columns as f64, columns)
            .expect("x never decreases")
            .into_iter()
            .map(|(lo, hi)| (lo <= hi).then_some((lo, hi)))
            .collect()
    }

    #[test]
    fn a_rising_line_covers_one_unit_per_unit_column() {
        // y = x from (0, 0) to (4, 4) over four 1-px columns: column c spans
        // [c, c + 1], and neighbours meet where the line crosses their edge.
        let s = spans(&[(0.0, 0.0), (4.0, 4.0)], 4);
        assert_eq!(
            s,
            vec![
                Some((0.0, 1.0)),
                Some((1.0, 2.0)),
                Some((2.0, 3.0)),
                Some((3.0, 4.0))
            ]
        );
    }

    #[test]
    fn a_column_takes_its_points_extremes_and_its_edge_crossings() {
        // Points at x = 0.5 (y 3), 1.2 (y −2), 1.8 (y 5), 2.5 (y 1), 3 columns.
        // Column 0: the point 3 and, at its edge x = 1, 3 − 5·(0.5/0.7) =
        // −0.571. Column 1: −0.571 at x = 1, the points −2 and 5, and
        // 5 − 4·(0.2/0.7) = 3.857 at x = 2: [−2, 5]. Column 2: 3.857 and 1.
        let s = spans(&[(0.5, 3.0), (1.2, -2.0), (1.8, 5.0), (2.5, 1.0)], 3);
        let (lo0, hi0) = s[0].unwrap();
        assert!(
            (lo0 - (3.0 - 5.0 * 0.5 / 0.7)).abs() < 1e-12 && hi0 == 3.0,
            "{:?}",
            s[0]
        );
        assert_eq!(s[1], Some((-2.0, 5.0)));
        let (lo2, hi2) = s[2].unwrap();
        assert!(
            lo2 == 1.0 && (hi2 - (5.0 - 4.0 * 0.2 / 0.7)).abs() < 1e-12,
            "{:?}",
            s[2]
        );
    }

    #[test]
    fn columns_the_line_does_not_reach_are_none_and_outside_points_are_clipped() {
        // From x = 1.5 to 2.5 in 5 columns of [0, 5]; a point at x = 9 beyond
        // the right edge continues the line to the edge at x = 5.
        let s = spans(&[(1.5, 0.0), (2.5, 1.0), (9.0, 1.0)], 5);
        assert_eq!(s[0], None);
        assert_eq!(s[1], Some((0.0, 0.5)));
        assert_eq!(s[2], Some((0.5, 1.0)));
        assert_eq!(s[3], Some((1.0, 1.0)));
        assert_eq!(s[4], Some((1.0, 1.0)));
    }

    #[test]
    fn non_finite_points_are_skipped_and_a_decreasing_x_has_no_columns() {
        let s = spans(
            &[
                (0.5, 1.0),
                (f64::NAN, 7.0),
                (1.5, f64::INFINITY),
                (1.5, 2.0),
            ],
            2,
        );
        assert_eq!(s, vec![Some((1.0, 1.5)), Some((1.5, 2.0))]);
        assert_eq!(column_spans([(1.0, 0.0), (0.5, 0.0)], 0.0, 2.0, 2), None);
    }

    #[test]
    fn degenerate_plots_give_empty_or_single_columns_without_panicking() {
        let line = [(0.0, 1.0), (1.0, 2.0)];
        assert_eq!(column_spans(line, 0.0, 1.0, 0), Some(vec![]));
        for width in [0.0, f64::NAN, -1.0] {
            let s = column_spans(line, 0.0, width, 3).unwrap();
            assert_eq!(s.len(), 3);
        }
    }

    #[test]
    fn a_vertical_step_covers_both_of_its_ends() {
        let s = spans(&[(0.5, 0.0), (0.5, 3.0), (1.5, 3.0)], 2);
        assert_eq!(s, vec![Some((0.0, 3.0)), Some((3.0, 3.0))]);
    }

    /// A seeded property: every column span is the extent of the polyline
    /// sampled finely over that column, for random noisy series.
    #[test]
    fn spans_equal_the_extent_of_the_finely_sampled_polyline() {
        let mut rng = crate::rng::Lcg64::new(26);
        for _ in 0..200 {
            let columns = 1 + (rng.next_f64() * 40.0) as usize;
            let n = 2 + (rng.next_f64() * 120.0) as usize;
            let mut x = -2.0;
            let points: Vec<(f64, f64)> = (0..n)
                .map(|_| {
                    x += rng.next_f64() * 2.0 * (columns as f64 + 4.0) / n as f64;
                    (x, rng.next_f64() * 10.0 - 5.0)
                })
                .collect();
            let s = spans(&points, columns);
            for (c, span) in s.iter().enumerate() {
                let (a, b) = (c as f64, c as f64 + 1.0);
                let mut seen: Option<(f64, f64)> = None;
                for w in points.windows(2) {
                    let ((xa, ya), (xb, yb)) = (w[0], w[1]);
                    for k in 0..=2000 {
                        let t = f64::from(k) / 2000.0;
                        let (px, py) = (xa + (xb - xa) * t, ya + (yb - ya) * t);
                        if px >= a && px <= b && px >= 0.0 && px <= columns as f64 {
                            let e = seen.get_or_insert((py, py));
                            e.0 = e.0.min(py);
                            e.1 = e.1.max(py);
                        }
                    }
                }
                match (span, seen) {
                    (None, None) => {}
                    (Some((lo, hi)), Some((slo, shi))) => {
                        // The fine sampling finds the extent from inside.
                        assert!(
                            *lo <= slo + 1e-9 && *hi >= shi - 1e-9,
                            "column {c}: {span:?} vs {seen:?}"
                        );
                        let step = 10.0 * 20.0 / 2000.0;
                        assert!(
                            slo - lo <= step && hi - shi <= step,
                            "column {c}: {span:?} vs {seen:?}"
                        );
                    }
                    other => panic!("column {c}: {other:?}"),
                }
            }
        }
    }

    #[test]
    fn dashes_follow_their_pattern_and_repeat() {
        let dash = [9.0, 3.0, 2.0, 3.0];
        let on: Vec<bool> = (0..17)
            .map(|i| dash_is_on(&dash, f64::from(i) + 0.5))
            .collect();
        let expect = [true; 9]
            .into_iter()
            .chain([false; 3])
            .chain([true; 2])
            .chain([false; 3])
            .collect::<Vec<_>>();
        assert_eq!(on, expect);
        assert!(dash_is_on(&dash, 17.5), "the pattern repeats every 17 px");
        assert!(
            dash_is_on(&[], 3.0) && dash_is_on(&[0.0, 0.0], 3.0),
            "solid"
        );
    }
}
