//! One module per experiment, and the registry that lists them.

use crate::content::{Content, ContentError};
use crate::experiment::Lab;
use crate::quiz::GeneratorLookup;
use std::sync::OnceLock;

/// The content file's text, for the build tool and the tests, which check
/// edited and broken texts against the compiled-in one (the `reading`
/// feature: native builds). The content itself is compiled in as data
/// (`build.rs`, [`Entry::content`]); the shipped wasm modules carry no text
/// of it to parse.
#[cfg(feature = "reading")]
macro_rules! content_file {
    ($id:literal) => {
        include_str!(concat!("../../../../assets/", $id, ".json"))
    };
}
// Unused in a build with no experiment (the lab report's module,
// `LAB_EXPERIMENTS=`), whose registry is empty.
#[cfg(not(feature = "reading"))]
#[allow(unused_macros)]
macro_rules! content_file {
    ($id:literal) => {
        ""
    };
}

/// One experiment of the lab: how to build it, its content and its quiz generators.
pub struct Entry {
    /// Same as [`crate::experiment::Experiment::id`] and the content file's `id`.
    pub id: &'static str,
    /// The content file's text (`assets/<id>.json`) with the `reading`
    /// feature; empty without it (see `content_file!`).
    pub content_json: &'static str,
    /// A fresh experiment at default parameters.
    pub make: fn() -> Box<dyn Lab>,
    /// The experiment's parameterised quiz questions.
    pub generators: GeneratorLookup,
    /// The parsed content, filled on first use.
    parsed: OnceLock<Result<Content, ContentError>>,
}

impl Entry {
    /// The content file, as `build.rs` compiled it in, checked on first use
    /// and kept.
    pub fn content(&self) -> Result<&Content, ContentError> {
        self.parsed
            .get_or_init(|| self.parse_content())
            .as_ref()
            .map_err(Clone::clone)
    }

    /// The compiled-in content file (read at build time: nothing is parsed
    /// here), checked: it belongs to this experiment and every generator it
    /// names exists; with the `reading` feature also complete
    /// ([`Content::validate`]).
    pub fn parse_content(&self) -> Result<Content, ContentError> {
        let content = crate::content::compiled(self.id).unwrap_or_else(|| {
            Err(ContentError::Parse(format!(
                "no content file assets/{}.json was compiled in",
                self.id
            )))
        })?;
        #[cfg(feature = "reading")]
        content.validate()?;
        self.check(content)
    }

    /// [`Entry::parse_content`] for another text in place of the compiled-in
    /// file (the build tool checks edited files with it; tests feed it broken ones).
    #[cfg(feature = "reading")]
    pub fn parse_content_text(&self, json: &str) -> Result<Content, ContentError> {
        self.check(Content::parse(json)?)
    }

    /// The content belongs to this experiment, and its quiz can be prepared.
    fn check(&self, content: Content) -> Result<Content, ContentError> {
        if content.id != self.id {
            return Err(ContentError::WrongId {
                expected: self.id.into(),
                found: content.id,
            });
        }
        crate::quiz::prepare(&content, self.generators, 0)?;
        #[cfg(feature = "reading")]
        {
            // The names the content gives the live math, against the
            // experiment itself (its equation keys are the same in every
            // variant of its equation set).
            let lab = (self.make)();
            let equations: Vec<&str> = lab.equations().iter().map(|e| e.key).collect();
            let quantities: Vec<&str> = lab.quantities().iter().map(|q| q.key).collect();
            content.check_live_names(&equations, &quantities)?;
        }
        Ok(content)
    }
}

/// Writes, from the one list of experiments below: the experiment modules,
/// the [`crate::catalogue::CATALOGUE`] (numbered in the list's order), the
/// wasm module each ships in ([`crate::catalogue::wasm_module`]), and the
/// registry of this build (one [`Entry`] for each experiment the build holds:
/// `cfg(lab_experiment = "<id>")`, which `build.rs` sets). A line reads
/// `"<id>" => <module>::<Type>, <Group>, "<short title>"` and, for an
/// experiment that shares its wasm module with others, `, in "<module key>"`.
macro_rules! experiments {
    ($($id:literal => $module:ident :: $ty:ident, $group:ident, $title:literal $(, in $wasm:literal)?;)*) => {
        $(pub mod $module;)*

        // The module is named after the id (the procedure-test check and the
        // content file find an experiment's files by its id).
        const _: () = {
            $(assert!(
                same_text(stringify!($module), $id),
                concat!("the module of experiment \"", $id, "\" must be named ", $id)
            );)*
        };

        /// How many experiments the lab lists.
        pub(crate) const LISTED: usize = [$($id),*].len();

        /// The catalogue, numbered 1, 2, … in the list's order.
        pub(crate) const CATALOGUE: [Planned; LISTED] = numbered([$(Planned {
            number: 0,
            id: $id,
            title: $title,
            group: Group::$group,
        }),*]);

        /// Each experiment's wasm module: a shared one, or its own (its id).
        pub(crate) const WASM_MODULES: [(&str, &str); LISTED] =
            [$(($id, wasm_module!($id $(, $wasm)?))),*];

        /// How many experiments this build holds.
        const BUILT: usize = 0 $(+ cfg!(lab_experiment = $id) as usize)*;

        /// The experiments this build holds: every one by default; a wasm module
        /// is built with only its own (`LAB_EXPERIMENTS`, see `build.rs`; `cargo
        /// xtask dist` sets it), so the other experiments' code and content are
        /// not in it.
        static REGISTRY: [Entry; BUILT] = [$(
            #[cfg(lab_experiment = $id)]
            Entry {
                id: $id,
                content_json: content_file!($id),
                make: || Box::new(<$module::$ty>::default()),
                generators: $module::quiz_generator,
                parsed: OnceLock::new(),
            },
        )*];
    };
}

/// The wasm module key of an experiment line: the one it names, or the id.
macro_rules! wasm_module {
    ($id:literal) => {
        $id
    };
    ($id:literal, $wasm:literal) => {
        $wasm
    };
}

// The lab's experiments, in its numbering; the only list of them. Adding an
// experiment is its folder (or file) here, its content file
// `assets/<id>.json` and one line below. The build holds every experiment
// with a content file (`build.rs`); README's table is written from this list
// and the content by `cargo xtask readme`.
//
// Wasm modules: experiments of one catalogue group that share their solvers
// share a module, as long as a first visit stays within its budget (700 KB
// raw, 250 KB gzip in all: `tests/e2e/weight.test.mjs`); the heavier ones
// have a module of their own. Measured as built (opt-level z, wasm-opt -O3,
// gzip -9), one module per catalogue group came to 469–561 KB raw, 210–244
// KB gzip, too close to the budget or over it with the page's HTML, CSS and
// JS (about 23 KB gzip): kinematics 223 KB gzip, planning 244, control 231;
// one experiment alone, 189 (fk) to 217 KB gzip (astar). diffdrive and
// potential shared "mobile" until its first visit outgrew the budget (257.1
// and 257.7 KB gzip with the link's inputs during a run, issue 53): each has
// its own module now, as the rule above asks.
experiments! {
    "fk" => fk::ForwardKinematics, Kinematics, "2-link arm forward kinematics", in "arms";
    "ik" => ik::InverseKinematics, Kinematics, "2-link inverse kinematics", in "arms";
    "workspace" => workspace::Workspace, Kinematics, "3-link arm and its workspace", in "chains";
    "diffdrive" => diffdrive::DiffDrive, MobileRobots, "Differential-drive robot to waypoints";
    "potential" => potential::PotentialFieldLab, MobileRobots, "Potential-field obstacle avoidance";
    "astar" => astar::AStarGrid, Planning, "A* and Dijkstra grid planning";
    "pid" => pid::PidControl, Control, "PID control of a mass with drag";
    "cartpole" => cartpole::CartPoleBalance, Control, "Cart-pole balancing";
    "dls" => dls::DampedLeastSquares, Kinematics, "n-link Jacobian IK (damped least squares)", in "chains";
    "rrtstar" => rrtstar::RrtStarField, Planning, "RRT* sampling-based planning";
    "ekf" => ekf::EkfExperiment, Estimation, "EKF localization and EKF-SLAM";
}

/// A topic of the lab; the navigation and the home page group by it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    Kinematics,
    MobileRobots,
    Planning,
    Control,
    Estimation,
}

impl Group {
    /// Every group, in the order the lab shows them.
    pub const ALL: [Group; 5] = [
        Group::Kinematics,
        Group::MobileRobots,
        Group::Planning,
        Group::Control,
        Group::Estimation,
    ];

    #[must_use]
    pub fn title(self) -> &'static str {
        match self {
            Group::Kinematics => "Kinematics",
            Group::MobileRobots => "Mobile robots",
            Group::Planning => "Planning",
            Group::Control => "Control",
            Group::Estimation => "Estimation",
        }
    }

    /// Stable key (HTML ids).
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Group::Kinematics => "kinematics",
            Group::MobileRobots => "mobile",
            Group::Planning => "planning",
            Group::Control => "control",
            Group::Estimation => "estimation",
        }
    }
}

/// One experiment of the lab's plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Planned {
    /// The lab's number (1, 2, …: its place in the list).
    pub number: u32,
    /// The registry id once the experiment is built (see [`crate::registry`]).
    pub id: &'static str,
    /// Short title, used until the content file exists.
    pub title: &'static str,
    pub group: Group,
}

/// `plan` with `number` set to 1, 2, … in order.
const fn numbered<const N: usize>(mut plan: [Planned; N]) -> [Planned; N] {
    let mut i = 0;
    while i < N {
        plan[i].number = i as u32 + 1;
        i += 1;
    }
    plan
}

/// Whether two texts are the same (`==` on `str` is not `const`).
const fn same_text(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// Every experiment, in lab order.
#[must_use]
pub fn registry() -> &'static [Entry] {
    &REGISTRY
}

/// The entry with this id.
#[must_use]
pub fn find(id: &str) -> Option<&'static Entry> {
    REGISTRY.iter().find(|e| e.id == id)
}
