//! Issue 26 §4, memory: the timeline of a 10-minute run at 60 steps a
//! second takes at most 32 MB for every experiment that evolves, measured
//! by counting the heap's live bytes (this test binary's allocator), not
//! estimated. RRT* grows to 20,000 iterations and A* searches a 512 × 512
//! maze. Run with `--nocapture` for the numbers.

mod evolving;
use evolving::EVOLVING;

use labcore::clock::Clock;
use labcore::glam::DVec2;
use labcore::timeline::Timeline;
use labcore::{Lab, Lcg64};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, counting the bytes live now.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to `System`, only counting.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LIVE.fetch_add(layout.size(), Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        System.dealloc(ptr, layout);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        LIVE.fetch_add(new_size, Ordering::Relaxed);
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// 10 minutes at 60 steps a second.
const TEN_MINUTES_STEPS: u64 = 10 * 60 * 60;
const LIMIT_BYTES: usize = 32 * 1024 * 1024;

/// Each experiment set going as a student would.
fn started(id: &str) -> Box<dyn Lab> {
    let mut exp = labcore::testkit::open(id);
    match id {
        "astar" => {
            let size = exp.params().iter().find(|s| s.key == "size").unwrap();
            let labcore::ParamKind::Choice(labels) = size.kind else {
                panic!("A*'s size is a choice")
            };
            let i = labels.iter().position(|l| l.starts_with("512")).unwrap();
            exp.set_param("size", i as f64).unwrap();
            exp.action("maze").unwrap();
            exp.action("plan").unwrap();
        }
        "rrtstar" => {
            exp.set_param("iters", 20_000.0).unwrap();
            exp.action("grow").unwrap();
        }
        "workspace" => exp.action("sweep").unwrap(),
        "dls" => {
            exp.move_handle("target", DVec2::new(1.0, 1.5));
        }
        _ => {}
    }
    exp
}

#[test]
fn memory_a_ten_minute_run_keeps_the_timeline_within_32_mb() {
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for id in EVOLVING {
        let mut exp = started(id);
        let before = LIVE.load(Ordering::Relaxed);
        let mut timeline = Timeline::new(exp.as_ref(), 0);
        let mut peak = 0usize;
        for _ in 0..TEN_MINUTES_STEPS {
            exp.step(Clock::DT_S);
            timeline.stepped(exp.as_ref());
            peak = peak.max(timeline.bytes());
        }
        let with = LIVE.load(Ordering::Relaxed);
        let estimated = timeline.bytes();
        // Scrub to random steps: the worst replay.
        let mut rng = Lcg64::new(5);
        let mut step_once = |e: &mut dyn Lab| e.step(Clock::DT_S);
        for _ in 0..64 {
            let k = rng.int(0, TEN_MINUTES_STEPS as i64) as u64;
            timeline.state_at(k, &mut step_once);
        }
        timeline.state_at(timeline.interval() - 1, &mut step_once);
        let (interval, snapshots, worst) = (
            timeline.interval(),
            timeline.snapshots(),
            timeline.worst_replay(),
        );
        drop(timeline);
        let without = LIVE.load(Ordering::Relaxed);
        let measured = with.saturating_sub(without);
        let ended = exp.status().phase == labcore::Phase::Ended;
        report.push(format!(
            "{id:>9}: interval k {interval:>5} steps, worst replay {worst:>5} steps, \
             {snapshots:>3} snapshots, timeline {:>6.2} MB measured ({:>6.2} MB estimated, \
             peak estimate {:>6.2} MB), model alone {:>6.2} MB{}",
            measured as f64 / 1e6,
            estimated as f64 / 1e6,
            peak as f64 / 1e6,
            before as f64 / 1e6,
            if ended { ", run ended" } else { "" },
        ));
        if measured > LIMIT_BYTES {
            failures.push(format!(
                "{id}: the timeline of a 10-minute run holds {measured} B"
            ));
        }
        if worst >= interval {
            failures.push(format!("{id}: replayed {worst} of interval {interval}"));
        }
    }
    println!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{failures:#?}");
}
