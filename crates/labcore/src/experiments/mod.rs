//! One module per experiment, and the registry that lists them.

use crate::content::{Content, ContentError};
use crate::experiment::Lab;
use crate::quiz::GeneratorLookup;
use std::sync::OnceLock;

pub mod astar;
pub mod cartpole;
pub mod diffdrive;
pub mod dls;
pub mod ekf;
pub mod fk;
pub mod ik;
pub mod pid;
pub mod potential;
pub mod rrtstar;
pub mod workspace;

/// The content file compiled into this build: the whole of
/// `assets/<id>.json` with the `reading` feature (native builds, tests, the
/// build tool); without it (the shipped wasm modules, whose reading tabs are
/// pages of their own) only the part the quiz and the page title need, which
/// `build.rs` writes.
#[cfg(feature = "reading")]
macro_rules! content_file {
    ($id:literal) => {
        include_str!(concat!("../../../../assets/", $id, ".json"))
    };
}
#[cfg(not(feature = "reading"))]
macro_rules! content_file {
    ($id:literal) => {
        include_str!(concat!(env!("OUT_DIR"), "/", $id, ".quiz.json"))
    };
}

/// One experiment of the lab: how to build it, its content and its quiz generators.
pub struct Entry {
    /// Same as [`crate::experiment::Experiment::id`] and the content file's `id`.
    pub id: &'static str,
    /// The content file (`assets/<id>.json`), compiled in (without the
    /// `reading` feature, its quiz part only: see `content_file!`).
    pub content_json: &'static str,
    /// A fresh experiment at default parameters.
    pub make: fn() -> Box<dyn Lab>,
    /// The experiment's parameterised quiz questions.
    pub generators: GeneratorLookup,
    /// The parsed content, filled on first use.
    parsed: OnceLock<Result<Content, ContentError>>,
}

impl Entry {
    /// The content file, parsed and validated on first use and kept.
    pub fn content(&self) -> Result<&Content, ContentError> {
        self.parsed
            .get_or_init(|| self.parse_content())
            .as_ref()
            .map_err(Clone::clone)
    }

    /// Parses and validates the content file, checking that it belongs to this
    /// experiment and that every generator it names exists.
    pub fn parse_content(&self) -> Result<Content, ContentError> {
        self.parse_content_text(self.content_json)
    }

    /// [`Entry::parse_content`] for another text in place of the compiled-in
    /// file (the build tool checks edited files with it; tests feed it broken ones).
    pub fn parse_content_text(&self, json: &str) -> Result<Content, ContentError> {
        #[cfg(feature = "reading")]
        let content = Content::parse(json)?;
        // The quiz part of a file the build tool validated whole.
        #[cfg(not(feature = "reading"))]
        let content = crate::json::Json::parse(json)
            .and_then(|v| Content::from_json(&v))
            .map_err(ContentError::Parse)?;
        if content.id != self.id {
            return Err(ContentError::WrongId {
                expected: self.id.into(),
                found: content.id,
            });
        }
        crate::quiz::prepare(&content, self.generators, 0)?;
        Ok(content)
    }
}

/// How many experiments this build holds.
const BUILT: usize = cfg!(feature = "fk") as usize
    + cfg!(feature = "ik") as usize
    + cfg!(feature = "workspace") as usize
    + cfg!(feature = "diffdrive") as usize
    + cfg!(feature = "potential") as usize
    + cfg!(feature = "astar") as usize
    + cfg!(feature = "pid") as usize
    + cfg!(feature = "cartpole") as usize
    + cfg!(feature = "dls") as usize
    + cfg!(feature = "rrtstar") as usize
    + cfg!(feature = "ekf") as usize;

/// The experiments this build holds: every one by default; a wasm module
/// of one group is built with only its group's features (`cargo xtask dist`),
/// so the other experiments' code and content are not in it.
static REGISTRY: [Entry; BUILT] = [
    #[cfg(feature = "fk")]
    Entry {
        id: "fk",
        content_json: content_file!("fk"),
        make: || Box::new(fk::ForwardKinematics::default()),
        generators: fk::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "ik")]
    Entry {
        id: "ik",
        content_json: content_file!("ik"),
        make: || Box::new(ik::InverseKinematics::default()),
        generators: ik::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "workspace")]
    Entry {
        id: "workspace",
        content_json: content_file!("workspace"),
        make: || Box::new(workspace::Workspace::default()),
        generators: workspace::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "diffdrive")]
    Entry {
        id: "diffdrive",
        content_json: content_file!("diffdrive"),
        make: || Box::new(diffdrive::DiffDrive::default()),
        generators: diffdrive::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "potential")]
    Entry {
        id: "potential",
        content_json: content_file!("potential"),
        make: || Box::new(potential::PotentialFieldLab::default()),
        generators: potential::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "astar")]
    Entry {
        id: "astar",
        content_json: content_file!("astar"),
        make: || Box::new(astar::AStarGrid::default()),
        generators: astar::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "pid")]
    Entry {
        id: "pid",
        content_json: content_file!("pid"),
        make: || Box::new(pid::PidControl::default()),
        generators: pid::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "cartpole")]
    Entry {
        id: "cartpole",
        content_json: content_file!("cartpole"),
        make: || Box::new(cartpole::CartPoleBalance::default()),
        generators: cartpole::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "dls")]
    Entry {
        id: "dls",
        content_json: content_file!("dls"),
        make: || Box::new(dls::DampedLeastSquares::default()),
        generators: dls::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "rrtstar")]
    Entry {
        id: "rrtstar",
        content_json: content_file!("rrtstar"),
        make: || Box::new(rrtstar::RrtStarField::default()),
        generators: rrtstar::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "ekf")]
    Entry {
        id: "ekf",
        content_json: content_file!("ekf"),
        make: || Box::new(ekf::EkfExperiment::default()),
        generators: ekf::quiz_generator,
        parsed: OnceLock::new(),
    },
];

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
