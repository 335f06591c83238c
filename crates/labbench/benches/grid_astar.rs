//! "A* on a grid" of `shared/BENCHMARKS.md`: the lab's incremental `Search`
//! against `pathfinding::prelude::astar` on the same 1000 × 1000 grid and the
//! same 20 queries, in the same run.
//!
//! Each query is timed on its own, ours then the peer's, so both see the same
//! machine load. Ours reuses one `Search` made once on the grid
//! (`Search::restart`: no grid copy, no clearing; the one-off copy is timed
//! separately). One warm-up pass, then
//! [`REPS`] passes; the median per query is reported. Costs are compared
//! exactly before timing: our path's move counts give the peer's integer cost,
//! and the peer's path gives our floating-point cost.

use labbench::grid_astar::{
    move_counts, octile_length, our_config, run_ours, run_peer, run_peer_counted, PeerGrid,
    Scenario,
};
use labcore::planning::astar::Search;
use labcore::planning::grid::Cell;
use std::hint::black_box;
use std::time::Instant;

const REPS: usize = 7;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn time(mut f: impl FnMut()) -> f64 {
    f();
    median(
        (0..REPS)
            .map(|_| {
                let t0 = Instant::now();
                f();
                t0.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

fn main() {
    let t0 = Instant::now();
    let scenario = Scenario::new();
    let grid = &scenario.grid;
    let peer = PeerGrid::new(grid);
    println!(
        "A* on a grid (shared/BENCHMARKS.md): 1000 × 1000, {:.2} % walls (LCG 42), 8-connected octile, no corner cutting; built in {:.0} ms",
        100.0 * grid.blocked_count() as f64 / 1e6,
        t0.elapsed().as_secs_f64() * 1e3
    );
    let mut search = Search::new(grid, Cell::new(0, 0), Cell::new(0, 0), our_config())
        .expect("the corner is forced free");

    let reset_s = time(|| {
        search
            .reset(grid, Cell::new(0, 0), Cell::new(0, 0), our_config())
            .expect("free corner");
    });
    println!(
        "  Search::reset (copies the 1M-cell grid, once per grid): {:.3} ms",
        reset_s * 1e3
    );

    println!(
        "\n  {:>3} {:>21} {:>12} {:>9} {:>9} | {:>9} {:>9} {:>9} | {:>9} {:>9} {:>6}",
        "#",
        "query",
        "cost",
        "ours exp",
        "peer exp",
        "ours ms",
        "peer ms",
        "ratio",
        "ours M/s",
        "peer M/s",
        "same"
    );
    let (mut ours_total, mut peer_total) = (0.0, 0.0);
    let (mut ours_exp_total, mut peer_exp_total) = (0usize, 0usize);
    for (k, &(s, g)) in scenario.queries.iter().enumerate() {
        let ours = run_ours(&mut search, s, g);
        let theirs = run_peer(&peer, s, g);
        let counted = run_peer_counted(&peer, s, g);
        let (cost, same, ours_exp, peer_exp) = match (&ours, &theirs, counted) {
            (Some((cost, exp, path)), Some((icost, ppath)), Some((_, pexp))) => {
                let (a, b) = move_counts(path);
                let pcells: Vec<Cell> = ppath
                    .iter()
                    .map(|&i| grid.cell_of(i as usize).expect("in grid"))
                    .collect();
                let (pa, pb) = move_counts(&pcells);
                let same = a * 1000 + b * 1414 == u64::from(*icost)
                    && (octile_length(pa, pb) - cost).abs() < 1e-6;
                assert!(
                    same,
                    "query {k}: ours {cost} ({a}, {b}) vs peer {icost} ({pa}, {pb})"
                );
                (*cost, same, *exp, pexp)
            }
            (None, None, None) => (f64::NAN, true, search.expanded(), 0),
            _ => panic!("query {k}: ours and the peer disagree on reachability"),
        };
        let ours_s = time(|| {
            black_box(run_ours(&mut search, black_box(s), black_box(g)));
        });
        let peer_s = time(|| {
            black_box(run_peer(&peer, black_box(s), black_box(g)));
        });
        ours_total += ours_s;
        peer_total += peer_s;
        ours_exp_total += ours_exp;
        peer_exp_total += peer_exp;
        println!(
            "  {:>3} {:>21} {:>12.4} {:>9} {:>9} | {:>9.3} {:>9.3} {:>8.2}x | {:>9.2} {:>9.2} {:>6}",
            k,
            format!("{s}→{g}"),
            cost,
            ours_exp,
            peer_exp,
            ours_s * 1e3,
            peer_s * 1e3,
            peer_s / ours_s,
            ours_exp as f64 / ours_s / 1e6,
            peer_exp as f64 / peer_s / 1e6,
            if same { "yes" } else { "NO" }
        );
    }
    println!(
        "\n  all 20 queries: ours {:.1} ms ({} expansions, {:.2} M/s), pathfinding {:.1} ms ({} expansions, {:.2} M/s)",
        ours_total * 1e3,
        ours_exp_total,
        ours_exp_total as f64 / ours_total / 1e6,
        peer_total * 1e3,
        peer_exp_total,
        peer_exp_total as f64 / peer_total / 1e6
    );
    println!(
        "  throughput ratio (expansions/s ours ÷ pathfinding): {:.2}x; time ratio pathfinding ÷ ours: {:.2}x (target ≥ 1.5x)",
        (ours_exp_total as f64 / ours_total) / (peer_exp_total as f64 / peer_total),
        peer_total / ours_total
    );
}
