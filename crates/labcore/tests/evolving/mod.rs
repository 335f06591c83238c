//! The experiments issue 26 names as evolving in time or iterations, shared
//! by the timeline's tests (`timeline.rs`, `timeline_memory.rs`).

/// The nine experiments the issue names (any other animated one is tested too).
pub const EVOLVING: [&str; 9] = [
    "diffdrive",
    "potential",
    "pid",
    "cartpole",
    "ekf",
    "rrtstar",
    "astar",
    "dls",
    "workspace",
];
