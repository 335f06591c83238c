//! The lab's table of contents: all eleven experiments in the lab's
//! numbering, grouped by topic, whether built yet or not.

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
    /// The lab's number (1–11).
    pub number: u32,
    /// The registry id once the experiment is built (see [`crate::registry`]).
    pub id: &'static str,
    /// Short title, used until the content file exists.
    pub title: &'static str,
    pub group: Group,
}

/// All eleven experiments, in the lab's numbering.
pub const CATALOGUE: [Planned; 11] = [
    Planned {
        number: 1,
        id: "fk",
        title: "2-link arm forward kinematics",
        group: Group::Kinematics,
    },
    Planned {
        number: 2,
        id: "ik",
        title: "2-link inverse kinematics",
        group: Group::Kinematics,
    },
    Planned {
        number: 3,
        id: "workspace",
        title: "3-link arm and its workspace",
        group: Group::Kinematics,
    },
    Planned {
        number: 4,
        id: "diffdrive",
        title: "Differential-drive robot to waypoints",
        group: Group::MobileRobots,
    },
    Planned {
        number: 5,
        id: "potential",
        title: "Potential-field obstacle avoidance",
        group: Group::MobileRobots,
    },
    Planned {
        number: 6,
        id: "astar",
        title: "A* and Dijkstra grid planning",
        group: Group::Planning,
    },
    Planned {
        number: 7,
        id: "pid",
        title: "PID control of a mass with drag",
        group: Group::Control,
    },
    Planned {
        number: 8,
        id: "cartpole",
        title: "Cart-pole balancing",
        group: Group::Control,
    },
    Planned {
        number: 9,
        id: "dls",
        title: "n-link Jacobian IK (damped least squares)",
        group: Group::Kinematics,
    },
    Planned {
        number: 10,
        id: "rrtstar",
        title: "RRT* sampling-based planning",
        group: Group::Planning,
    },
    Planned {
        number: 11,
        id: "ekf",
        title: "EKF localization and EKF-SLAM",
        group: Group::Estimation,
    },
];

/// The catalogue entry of an experiment id.
#[must_use]
pub fn planned(id: &str) -> Option<&'static Planned> {
    CATALOGUE.iter().find(|p| p.id == id)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_one_to_eleven_and_ids_unique() {
        for (i, p) in CATALOGUE.iter().enumerate() {
            assert_eq!(p.number as usize, i + 1);
            assert_eq!(CATALOGUE.iter().filter(|q| q.id == p.id).count(), 1);
        }
    }

    #[test]
    fn every_built_experiment_is_catalogued_with_its_content_number() {
        for entry in crate::registry() {
            let p = planned(entry.id).expect("catalogued");
            let content = entry.content().expect("content parses");
            assert_eq!(content.number, p.number, "{}", entry.id);
        }
    }
}
