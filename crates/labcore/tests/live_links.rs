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

/// The `\live{key}{…}` keys of experiment `id`'s content file, each once.
fn marked_keys(id: &str) -> Vec<String> {
    let path = format!("{}/../../assets/{id}.json", env!("CARGO_MANIFEST_DIR"));
    let json = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut keys: Vec<String> = Vec::new();
    // In the JSON text a LaTeX backslash is written twice.
    for part in json.split("\\\\live{").skip(1) {
        let key = part.split('}').next().unwrap_or_default().to_owned();
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys
}

/// The keys `e`'s scene tags along a run driven at random: parameters
/// moved, the lab's actions pressed, points of its view clicked and time
/// stepped, from `seed`. Checks every tag on the way (see [`tagged_keys`]).
fn keys_tagged_along_random_runs(e: &mut dyn Lab, seed: u64) -> Vec<&'static str> {
    let mut rng = Lcg64::new(seed);
    let mut seen = tagged_keys(e, "at defaults");
    for trial in 0..60 {
        let view = e.view();
        match rng.next_f64() {
            r if r < 0.2 => {
                let params = e.params();
                if !params.is_empty() {
                    let spec =
                        params[(rng.next_f64() * params.len() as f64) as usize % params.len()];
                    let _ =
                        e.set_param(spec.key, spec.min + (spec.max - spec.min) * rng.next_f64());
                }
            }
            r if r < 0.5 => {
                let actions = e.actions();
                if !actions.is_empty() {
                    let a =
                        actions[(rng.next_f64() * actions.len() as f64) as usize % actions.len()];
                    let _ = e.action(a.key);
                }
            }
            r if r < 0.7 => {
                let p = view.min
                    + (view.max - view.min)
                        * labcore::glam::DVec2::new(rng.next_f64(), rng.next_f64());
                labcore::testkit::click(e, p);
            }
            _ => {}
        }
        steps(e, 1 + (rng.next_f64() * 90.0) as usize);
        for key in tagged_keys(e, &format!("seed {seed} trial {trial}")) {
            if !seen.contains(&key) {
                seen.push(key);
            }
        }
    }
    seen
}

/// Marked symbols that name a number, not a place in the scene: a gain, a
/// limit, a weight. The Theory tab shows their values; the scene has
/// nothing to highlight for them.
const VALUES_ONLY: [(&str, &[&str]); 6] = [
    ("workspace", &["lmax"]),
    ("pid", &["kp", "ki", "kd", "ie", "de", "dy"]),
    ("diffdrive", &["kw", "kv", "vmax", "wmax"]),
    ("astar", &["w"]),
    ("cartpole", &["kth", "kom", "kx", "kv", "omk", "vk", "flim"]),
    ("rrtstar", &["gamma"]),
];

/// Issue 27 §3 for every experiment: along random runs (parameters,
/// actions, clicks, time) every tag names one of its quantities, and every
/// symbol its content marks with `\live` has a tag at some state reached,
/// unless it names a number only ([`VALUES_ONLY`]); every experiment marks
/// symbols and tags its scene.
#[test]
fn live_every_marked_symbol_has_a_tag_along_random_runs_and_every_tag_is_a_quantity() {
    for entry in registry() {
        let id = entry.id;
        let marked = marked_keys(id);
        assert!(
            !marked.is_empty(),
            "{id}: its content marks no \\live symbol"
        );
        let mut tagged: Vec<&str> = Vec::new();
        for seed in 1..=4 {
            let mut e = (entry.make)();
            for key in keys_tagged_along_random_runs(e.as_mut(), seed) {
                if !tagged.contains(&key) {
                    tagged.push(key);
                }
            }
        }
        let values_only = VALUES_ONLY
            .iter()
            .find(|(x, _)| *x == id)
            .map_or(&[][..], |(_, k)| k);
        let untagged: Vec<&String> = marked
            .iter()
            .filter(|k| !tagged.contains(&k.as_str()) && !values_only.contains(&k.as_str()))
            .collect();
        assert!(
            untagged.is_empty(),
            "{id}: marked {untagged:?} but its scene never tagged them (tagged: {tagged:?})"
        );
        for k in values_only {
            assert!(
                !tagged.contains(k),
                "{id}: {k} is tagged: take it off VALUES_ONLY"
            );
        }
    }
}

use labcore::glam::DVec2;
use labcore::testkit::{click, press};

/// The points of `e`'s first tag named `key`.
fn tag(e: &dyn Lab, key: &str) -> Vec<DVec2> {
    let mut scene = Scene::default();
    e.scene(&mut scene);
    let found = scene.tags.iter().find(|t| t.key == key);
    found
        .unwrap_or_else(|| panic!("{}: no tag {key}", e.id()))
        .points
        .clone()
}

/// Quantity `key`'s value (unrounded).
fn value(e: &dyn Lab, key: &str) -> f64 {
    e.quantities().iter().find(|q| q.key == key).unwrap().value
}

fn near(a: DVec2, b: DVec2) -> bool {
    (a - b).length() < 1e-9
}

fn make(id: &str) -> Box<dyn Lab> {
    (labcore::find(id).unwrap().make)()
}

/// rrtstar: r(n) is the circle of radius min(γ √(ln n / n), η) around the
/// newest node (the n-th), and η the circle that caps it.
#[test]
fn live_rrtstar_r_of_n_is_the_circle_of_that_radius_around_the_newest_node() {
    let mut e = make("rrtstar");
    press(e.as_mut(), "grow");
    steps(e.as_mut(), 40);
    let n = value(e.as_ref(), "n");
    let (gamma, eta) = (value(e.as_ref(), "gamma"), value(e.as_ref(), "eta"));
    let r = (gamma * (n.ln() / n).sqrt()).min(eta);
    assert!(
        n > 20.0 && (value(e.as_ref(), "radius") - r).abs() < 1e-12,
        "n {n}, r {r}"
    );
    let newest = tag(e.as_ref(), "n");
    assert_eq!(newest.len(), 1, "the newest node is a ring");
    let circle = tag(e.as_ref(), "radius");
    assert!(
        circle.len() > 16 && near(circle[0], *circle.last().unwrap()),
        "a closed circle"
    );
    for p in &circle {
        assert!(
            ((*p - newest[0]).length() - r).abs() < 1e-9,
            "{p} is not {r} m from {}",
            newest[0]
        );
    }
    for p in tag(e.as_ref(), "eta") {
        assert!(((p - newest[0]).length() - eta).abs() < 1e-9);
    }
}

/// ekf: P's tag (σ² = P_xx + P_yy) is the 3σ ellipse the scene draws, and
/// e_x, e_y run from the estimate to the truth.
#[test]
fn live_ekf_p_is_the_3_sigma_ellipse_and_e_runs_from_the_estimate_to_the_truth() {
    let mut e = make("ekf");
    steps(e.as_mut(), 300);
    let mut scene = Scene::default();
    e.scene(&mut scene);
    let ellipses: Vec<(DVec2, DVec2, DVec2)> = scene
        .items
        .iter()
        .filter_map(|i| match *i {
            labcore::Item::Ellipse {
                center,
                semi_axis_a,
                semi_axis_b,
                ..
            } => Some((center, semi_axis_a, semi_axis_b)),
            _ => None,
        })
        .collect();
    let (c, a, b) = *ellipses.last().expect("the estimate's ellipse");
    // 3σ: the squared semi-axes add up to 9 times the variances' sum.
    let trace = value(e.as_ref(), "pxx") + value(e.as_ref(), "pyy");
    assert!((a.length_squared() + b.length_squared() - 9.0 * trace).abs() < 1e-9 * trace.max(1.0));
    for key in ["pxx", "pyy"] {
        let points = tag(e.as_ref(), key);
        assert!(points.len() > 16 && near(points[0], *points.last().unwrap()));
        for p in points {
            let d = p - c;
            let on =
                (d.dot(a) / a.length_squared()).powi(2) + (d.dot(b) / b.length_squared()).powi(2);
            assert!(
                (on - 1.0).abs() < 1e-9,
                "{key}: {p} is off the drawn ellipse ({on})"
            );
        }
    }
    let (ex, ey) = (tag(e.as_ref(), "ex"), tag(e.as_ref(), "ey"));
    assert!(near(ex[0], c), "e starts at the estimate");
    assert!(((ex[1] - ex[0]).x - value(e.as_ref(), "ex")).abs() < 1e-9 && (ex[1] - ex[0]).y == 0.0);
    assert!(near(ex[1], ey[0]) && ((ey[1] - ey[0]).y - value(e.as_ref(), "ey")).abs() < 1e-9);
    // The landmark sighted: z from the truth (e's end) and ẑ from the estimate meet at it.
    let (z, zh) = (tag(e.as_ref(), "zr"), tag(e.as_ref(), "zhr"));
    assert!(near(z[0], ey[1]) && near(zh[0], c) && near(z[1], zh[1]));
}

/// diffdrive: θ is the arc from the x axis to the heading, e_θ the arc from
/// the heading on by the error, d the line from the robot to its goal.
#[test]
fn live_diffdrive_theta_and_e_are_arcs_at_the_robot_and_d_runs_to_the_goal() {
    let mut e = make("diffdrive");
    let view = e.view();
    click(
        e.as_mut(),
        view.min + (view.max - view.min) * DVec2::new(0.8, 0.75),
    );
    steps(e.as_mut(), 20);
    let (theta, err) = (
        value(e.as_ref(), "theta").to_radians(),
        value(e.as_ref(), "e"),
    );
    let d = tag(e.as_ref(), "d");
    let robot = d[0];
    let dir = |a: f64| DVec2::new(a.cos(), a.sin());
    let arc = tag(e.as_ref(), "theta");
    assert!(
        near(arc[0], robot + 0.45 * dir(0.0))
            && near(*arc.last().unwrap(), robot + 0.45 * dir(theta))
    );
    let arc = tag(e.as_ref(), "e");
    assert!(
        near(arc[0], robot + 0.7 * dir(theta))
            && near(*arc.last().unwrap(), robot + 0.7 * dir(theta + err))
    );
    // The goal lies along heading + error, d away (d as of the last command).
    let to_goal = d[1] - robot;
    assert!(
        (to_goal.length() - value(e.as_ref(), "d")).abs() < 0.05,
        "{to_goal}"
    );
    assert!(to_goal.normalize().dot(dir(theta + err)) > 0.999);
}

/// astar: Δx and Δy are the legs from the last cell expanded to the goal,
/// h the line between, g the path so far ending at that cell.
#[test]
fn live_astar_dx_dy_run_from_the_last_cell_to_the_goal_and_g_ends_there() {
    let mut e = make("astar");
    press(e.as_mut(), "plan");
    // On to a cell off the goal's row and column.
    for _ in 0..300 {
        steps(e.as_mut(), 1);
        if value(e.as_ref(), "g") > 0.0
            && value(e.as_ref(), "dx") > 0.0
            && value(e.as_ref(), "dy") > 0.0
        {
            break;
        }
    }
    let (dx, dy, h, g) = (
        tag(e.as_ref(), "dx"),
        tag(e.as_ref(), "dy"),
        tag(e.as_ref(), "h"),
        tag(e.as_ref(), "g"),
    );
    // A leg of no length is a ring at its point.
    let span = |p: &[DVec2]| (*p.last().unwrap() - p[0]).length();
    assert!(value(e.as_ref(), "dx") > 0.0 && value(e.as_ref(), "dy") > 0.0);
    assert!((span(&dx) - value(e.as_ref(), "dx")).abs() < 1e-9);
    assert!((span(&dy) - value(e.as_ref(), "dy")).abs() < 1e-9);
    assert!(near(dx[0], h[0]) && near(dx[1], dy[0]) && near(dy[1], h[1]));
    assert!(g.len() > 1 && near(*g.last().unwrap(), h[0]), "{g:?}");
    // Its length is g when every move is straight or diagonal (1 or √2 per cell).
    let length: f64 = g.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    assert!((length - value(e.as_ref(), "g")).abs() < 1e-9);
}

/// potential: d is the clearance from the nearest obstacle's surface to the
/// robot (r from its centre), d₀ the circle where its push starts, k_a the pull.
#[test]
fn live_potential_d_r_and_d0_measure_the_nearest_obstacle() {
    let mut e = make("potential");
    let view = e.view();
    click(
        e.as_mut(),
        view.min + (view.max - view.min) * DVec2::new(0.9, 0.5),
    );
    let c = DVec2::new(value(e.as_ref(), "cx"), value(e.as_ref(), "cy"));
    let (r, d, d0) = (
        value(e.as_ref(), "r"),
        value(e.as_ref(), "d"),
        value(e.as_ref(), "d0"),
    );
    let dt = tag(e.as_ref(), "d");
    assert!(
        ((dt[0] - c).length() - r).abs() < 1e-9,
        "d starts on the surface"
    );
    assert!(((dt[1] - dt[0]).length() - d).abs() < 1e-9 && d > 0.0);
    for p in tag(e.as_ref(), "d0") {
        assert!(((p - c).length() - (r + d0)).abs() < 1e-9);
    }
    // k_a: the pull, from the robot towards the goal.
    let pull = tag(e.as_ref(), "ka");
    let goal = DVec2::new(value(e.as_ref(), "xg"), value(e.as_ref(), "yg"));
    assert!(near(pull[0], dt[1]));
    assert!(
        (pull[1] - pull[0])
            .normalize()
            .dot((goal - pull[0]).normalize())
            > 1.0 - 1e-9
    );
}

/// cartpole: θ is the arc at the pivot from the upright to the pole, l the
/// pole's lower half, x_k the cart's offset along the track.
#[test]
fn live_cartpole_theta_is_the_arc_from_the_upright_to_the_pole() {
    let mut e = make("cartpole");
    steps(e.as_mut(), 30);
    let th = value(e.as_ref(), "th").to_radians();
    let l = tag(e.as_ref(), "l");
    let pivot = l[0];
    assert!(((l[1] - pivot).length() - value(e.as_ref(), "l")).abs() < 1e-9);
    assert!(
        (l[1] - pivot)
            .normalize()
            .dot(DVec2::new(th.sin(), th.cos()))
            > 1.0 - 1e-12
    );
    let arc = tag(e.as_ref(), "th");
    assert!(near(arc[0], pivot + DVec2::new(0.0, 0.4)));
    assert!(near(
        *arc.last().unwrap(),
        pivot + 0.4 * DVec2::new(th.sin(), th.cos())
    ));
    let x = tag(e.as_ref(), "xk");
    assert!(
        near(x[0], DVec2::ZERO) && (x[1].x - value(e.as_ref(), "xk")).abs() < 1e-9 && x[1].y == 0.0
    );
}

/// dls: e is the line from the tip (x, y) to the target, as long as |e|;
/// σmax and σmin the velocity ellipse's semi-axes, in their ratio.
#[test]
fn live_dls_e_runs_from_the_tip_to_the_target() {
    let mut e = make("dls");
    click(e.as_mut(), DVec2::new(0.4, 1.1));
    let err = tag(e.as_ref(), "error");
    let tip = DVec2::new(value(e.as_ref(), "x"), value(e.as_ref(), "y"));
    let target = DVec2::new(value(e.as_ref(), "xt"), value(e.as_ref(), "yt"));
    assert!(near(err[0], tip) && near(err[1], target), "{err:?}");
    assert!(((err[1] - err[0]).length() - value(e.as_ref(), "error")).abs() < 1e-12);
    let (a, b) = (tag(e.as_ref(), "smax"), tag(e.as_ref(), "smin"));
    let ratio = (a[1] - a[0]).length() / (b[1] - b[0]).length();
    assert!((ratio - value(e.as_ref(), "smax") / value(e.as_ref(), "smin")).abs() < 1e-9 * ratio);
    assert!(
        (a[1] - a[0]).dot(b[1] - b[0]).abs() < 1e-12,
        "the semi-axes are perpendicular"
    );
}
