//! Symbols that point at what they name (issue 27 §3): a scene tags its parts
//! with the keys of the live quantities that name them, and the page draws
//! the tagged part as a halo while a symbol marked with that key is hovered
//! or focused.

use labcore::testkit::steps;
use labcore::{registry, Lab, Lcg64, Scene};

/// Checks every tag of `e`'s scene names one of its quantities and has a
/// finite point or path; returns the tagged keys.
fn tagged_keys(e: &dyn Lab, context: &str) -> Vec<&'static str> {
    let mut scene = Scene::default();
    e.scene(&mut scene);
    let quantities = e.quantities();
    let mut keys = Vec::new();
    for tag in &scene.tags {
        assert!(
            quantities.iter().any(|q| q.key == tag.key),
            "{} {context}: the scene tags {:?}, which is none of its quantities",
            e.id(),
            tag.key
        );
        assert!(
            !tag.points.is_empty() && tag.points.iter().all(|p| p.is_finite()),
            "{} {context}: tag {} has no finite shape: {:?}",
            e.id(),
            tag.key,
            tag.points
        );
        if !keys.contains(&tag.key) {
            keys.push(tag.key);
        }
    }
    keys
}

#[test]
fn live_every_tagged_scene_item_names_a_quantity() {
    for entry in registry() {
        let mut e = (entry.make)();
        tagged_keys(e.as_ref(), "at defaults");
        let mut rng = Lcg64::new(3);
        for trial in 0..40 {
            for spec in e.params() {
                let _ = e.set_param(spec.key, spec.min + (spec.max - spec.min) * rng.next_f64());
            }
            if e.animated() {
                steps(e.as_mut(), 1 + trial * 5);
            }
            tagged_keys(e.as_ref(), &format!("trial {trial}"));
        }
    }
}

/// The arms tag their links and joint angles, fk and ik the tip's or the
/// goal's coordinates, pid the error.
#[test]
fn live_the_scene_tags_links_angles_goal_and_error() {
    let expected: [(&str, &[&str]); 4] = [
        ("fk", &["l1", "t1", "l2", "t2", "x", "y"]),
        ("ik", &["l1", "l2", "px", "py"]),
        ("workspace", &["l1", "t1", "l2", "t2", "l3", "t3"]),
        ("pid", &["e"]),
    ];
    for (id, keys) in expected {
        let Some(entry) = labcore::find(id) else {
            continue;
        };
        let mut e = (entry.make)();
        if id == "ik" {
            // A goal to reach for.
            e.set_param("tx", 0.9).unwrap();
            e.set_param("ty", 0.8).unwrap();
        }
        assert_eq!(tagged_keys(e.as_ref(), "at defaults"), keys, "{id}");
    }
    // θ1's arc runs from the x axis to the first link, at 0.45 of its length.
    let mut fk = (labcore::find("fk").unwrap().make)();
    fk.set_param("t1", 90.0).unwrap();
    let mut scene = Scene::default();
    fk.scene(&mut scene);
    let arc = &scene.tags.iter().find(|t| t.key == "t1").unwrap().points;
    let l1 = fk
        .quantities()
        .iter()
        .find(|q| q.key == "l1")
        .unwrap()
        .value;
    assert!((arc[0] - labcore::glam::DVec2::new(0.45 * l1, 0.0)).length() < 1e-12);
    assert!((*arc.last().unwrap() - labcore::glam::DVec2::new(0.0, 0.45 * l1)).length() < 1e-12);
}
