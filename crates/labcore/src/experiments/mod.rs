//! One module per experiment, and the registry that lists them.

use crate::content::{Content, ContentError};
use crate::experiment::Experiment;
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

/// One experiment of the lab: how to build it, its content and its quiz generators.
pub struct Entry {
    /// Same as [`Experiment::id`] and the content file's `id`.
    pub id: &'static str,
    /// The content file (`assets/<id>.json`), compiled in.
    pub content_json: &'static str,
    /// A fresh experiment at default parameters.
    pub make: fn() -> Box<dyn Experiment>,
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
        let content = Content::parse(json)?;
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
        content_json: include_str!("../../../../assets/fk.json"),
        make: || Box::new(fk::ForwardKinematics::default()),
        generators: fk::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "ik")]
    Entry {
        id: "ik",
        content_json: include_str!("../../../../assets/ik.json"),
        make: || Box::new(ik::InverseKinematics::default()),
        generators: ik::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "workspace")]
    Entry {
        id: "workspace",
        content_json: include_str!("../../../../assets/workspace.json"),
        make: || Box::new(workspace::Workspace::default()),
        generators: workspace::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "diffdrive")]
    Entry {
        id: "diffdrive",
        content_json: include_str!("../../../../assets/diffdrive.json"),
        make: || Box::new(diffdrive::DiffDrive::default()),
        generators: diffdrive::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "potential")]
    Entry {
        id: "potential",
        content_json: include_str!("../../../../assets/potential.json"),
        make: || Box::new(potential::PotentialFieldLab::default()),
        generators: potential::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "astar")]
    Entry {
        id: "astar",
        content_json: include_str!("../../../../assets/astar.json"),
        make: || Box::new(astar::AStarGrid::default()),
        generators: astar::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "pid")]
    Entry {
        id: "pid",
        content_json: include_str!("../../../../assets/pid.json"),
        make: || Box::new(pid::PidControl::default()),
        generators: pid::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "cartpole")]
    Entry {
        id: "cartpole",
        content_json: include_str!("../../../../assets/cartpole.json"),
        make: || Box::new(cartpole::CartPoleBalance::default()),
        generators: cartpole::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "dls")]
    Entry {
        id: "dls",
        content_json: include_str!("../../../../assets/dls.json"),
        make: || Box::new(dls::DampedLeastSquares::default()),
        generators: dls::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "rrtstar")]
    Entry {
        id: "rrtstar",
        content_json: include_str!("../../../../assets/rrtstar.json"),
        make: || Box::new(rrtstar::RrtStarField::default()),
        generators: rrtstar::quiz_generator,
        parsed: OnceLock::new(),
    },
    #[cfg(feature = "ekf")]
    Entry {
        id: "ekf",
        content_json: include_str!("../../../../assets/ekf.json"),
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
