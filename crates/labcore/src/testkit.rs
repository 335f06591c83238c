//! The experiments' test kit: what every experiment's tests do to a lab, in
//! one place: step it at the page's fixed step, run it until a status
//! matches, read a readout (as text and as a number), apply a link, press an
//! action, click, and replay a run's steps.
//!
//! For tests only (the unit tests of `experiments/*` and the integration
//! tests in `tests/`), so it is compiled natively only: no wasm module
//! carries it, not even as a shift of the optimiser's choices. Its functions
//! panic with a message that names the key or the link when the lab lacks
//! what a test asks for: a test kit's failure is a failed test.

use crate::clock::Clock;
use crate::experiment::{Experiment, Input, Lab, Modifiers, Phase, Presentation, Status};
use crate::route::{self, Page, Tab};
use crate::scene::Scene;
use glam::DVec2;

/// The page's fixed step, in seconds (60 steps a simulated second).
pub const DT_S: f64 = Clock::DT_S;

/// Shift held: with a click, moves a start marker (A*, RRT*).
pub const SHIFT: Modifiers = Modifiers {
    shift: true,
    ctrl: false,
};

/// Ctrl (or Cmd) held: with a click, moves a goal marker (A*, RRT*).
pub const CTRL: Modifiers = Modifiers {
    shift: false,
    ctrl: true,
};

/// Replays `n` fixed steps of [`DT_S`].
pub fn steps<E: Presentation + ?Sized>(e: &mut E, n: usize) {
    for _ in 0..n {
        e.step(DT_S);
    }
}

/// Steps for `seconds` of simulated time, rounded to whole steps of [`DT_S`].
pub fn run_for<E: Presentation + ?Sized>(e: &mut E, seconds: f64) {
    steps(e, (seconds / DT_S).round() as usize);
}

/// Steps while the lab animates, at most `max_s` simulated seconds; returns
/// the simulated seconds stepped (`max_s` or a little over when it never
/// came to rest: check `animating()` where that matters).
pub fn run_while_animating<E: Presentation + ?Sized>(e: &mut E, max_s: f64) -> f64 {
    let mut t_s = 0.0;
    while e.animating() && t_s < max_s {
        e.step(DT_S);
        t_s += DT_S;
    }
    t_s
}

/// The most steps [`settle`] takes before it calls the lab stuck (about 28
/// simulated minutes).
pub const SETTLE_MAX_STEPS: usize = 100_000;

/// Steps until nothing moves (the page would idle); returns the steps taken.
///
/// # Panics
/// When the lab still animates after [`SETTLE_MAX_STEPS`] steps.
pub fn settle<E: Presentation + ?Sized>(e: &mut E) -> usize {
    let mut n = 0;
    while e.animating() {
        assert!(n < SETTLE_MAX_STEPS, "never settles");
        e.step(DT_S);
        n += 1;
    }
    n
}

/// Steps until `done` holds for the status (checked before each step), at
/// most `max_steps` steps; the steps taken, or `None` when it never held.
pub fn run_until_status<E: Presentation + ?Sized>(
    e: &mut E,
    max_steps: usize,
    mut done: impl FnMut(&Status) -> bool,
) -> Option<usize> {
    for n in 0..=max_steps {
        if done(&e.status()) {
            return Some(n);
        }
        if n < max_steps {
            e.step(DT_S);
        }
    }
    None
}

/// [`run_until_status`] for a phase of the run (e.g. [`Phase::Ended`]).
pub fn run_until_phase<E: Presentation + ?Sized>(
    e: &mut E,
    phase: Phase,
    max_steps: usize,
) -> Option<usize> {
    run_until_status(e, max_steps, |s| s.phase == phase)
}

/// The text of readout `key`, as the page shows it.
///
/// # Panics
/// When the lab shows no such readout now.
pub fn readout<E: Presentation + ?Sized>(e: &E, key: &str) -> String {
    e.readouts()
        .into_iter()
        .find(|r| r.key == key)
        .map(|r| r.value)
        .unwrap_or_else(|| panic!("no readout {key}"))
}

/// The leading number of readout `key` (`61.0%` → 61, `-0.250 m` → -0.25,
/// `1.2 × 10⁵` → 1.2: the mantissa only).
///
/// # Panics
/// When there is no such readout or it does not start with a number.
pub fn readout_number<E: Presentation + ?Sized>(e: &E, key: &str) -> f64 {
    let text = readout(e, key);
    leading_number(&text).unwrap_or_else(|| panic!("{key}: “{text}” has no leading number"))
}

/// The number a text starts with (`0.250 m` → 0.25, `−3°` → -3).
#[must_use]
pub fn leading_number(text: &str) -> Option<f64> {
    let text = text.trim_start().replace('\u{2212}', "-");
    let end = text
        .char_indices()
        .find(|&(i, c)| !(c.is_ascii_digit() || c == '.' || (c == '-' && i == 0)))
        .map_or(text.len(), |(i, _)| i);
    text[..end].parse().ok()
}

/// A press and release at `p` (world coordinates, metres): a click or a tap.
pub fn click<E: Presentation + ?Sized>(e: &mut E, p: DVec2) {
    e.input(Input::PointerDown(p));
    e.input(Input::PointerUp(p));
}

/// A drag with the pointer pressed through `path` (world coordinates): a
/// press at the first point, a move to each next one, a release at the last.
pub fn drag_through<E: Presentation + ?Sized>(e: &mut E, path: &[DVec2]) {
    let (Some(&from), Some(&to)) = (path.first(), path.last()) else {
        return;
    };
    e.input(Input::PointerDown(from));
    for &pos in &path[1..] {
        e.input(Input::PointerMove { pos, pressed: true });
    }
    e.input(Input::PointerUp(to));
}

/// The notice shown beside the status now, or `""` when there is none.
pub fn notice_text<E: Presentation + ?Sized>(e: &E) -> String {
    e.notice().map(|n| n.text).unwrap_or_default()
}

/// Presses the action button `key`.
///
/// # Panics
/// When the lab refuses the action.
pub fn press<E: Presentation + ?Sized>(e: &mut E, key: &str) {
    e.action(key)
        .unwrap_or_else(|err| panic!("action {key}: {err:?}"));
}

/// Sets each `(key, value)` parameter in turn (display units), as the
/// sliders do.
///
/// # Panics
/// When the lab refuses a value.
pub fn set_params<E: Presentation + ?Sized>(e: &mut E, pairs: &[(&str, f64)]) {
    for &(key, value) in pairs {
        e.set_param(key, value)
            .unwrap_or_else(|err| panic!("{key} = {value}: {err:?}"));
    }
}

/// Applies a whole link (`#/<id>/simulation?…`) to `e` as the page does when
/// it opens it, the instructor's rules included; every notice it gave.
///
/// # Panics
/// When the link is not an experiment's page.
pub fn apply_link(e: &mut dyn Experiment, link: &str) -> Vec<String> {
    let parsed = route::parse(link, &[e.id()]);
    let mut notices = parsed.notices;
    let mut instructor = parsed.instructor;
    notices.extend(instructor.resolve(e.params()));
    let Page::Experiment { params, .. } = parsed.page else {
        panic!("not an experiment's link: {link}");
    };
    notices.extend(route::apply_params(e, &params));
    notices
}

/// What opening `e`'s Simulation link on a fresh page gives: the rebuilt
/// lab, the link and the link's notices.
pub fn through_link<E: Presentation + Default>(e: &E) -> (E, String, Vec<String>) {
    let link = route::format(e, Tab::Simulation);
    let (fresh, notices) = route::restore(&link, E::default());
    (fresh, link, notices)
}

/// The lab `e`'s Simulation link rebuilds on a fresh page, checked: the
/// link gives no notice, the rebuilt lab's link is the same, and so is
/// every parameter.
///
/// # Panics
/// When any of that fails.
#[must_use]
pub fn reopen<E: Presentation + Default>(e: &E) -> E {
    let (fresh, link, notices) = through_link(e);
    assert!(notices.is_empty(), "{link}: {notices:?}");
    assert_eq!(route::format(&fresh, Tab::Simulation), link);
    for spec in e.params() {
        assert_eq!(fresh.param(spec.key), e.param(spec.key), "{}", spec.key);
    }
    fresh
}

/// The experiment `id`, fresh from the registry.
///
/// # Panics
/// When no experiment has that id.
#[must_use]
pub fn open(id: &str) -> Box<dyn Lab> {
    (crate::find(id)
        .unwrap_or_else(|| panic!("no experiment {id}"))
        .make)()
}

/// The display list the lab draws now.
pub fn scene_of<E: Presentation + ?Sized>(e: &E) -> Scene {
    let mut scene = Scene::default();
    e.scene(&mut scene);
    scene
}

/// The state after the Procedure's steps `1..=k`, each step's actions (and
/// checks) replayed on the state the previous ones left, from the default.
#[must_use]
pub fn after_step<E: Default>(procedure: &[fn(&mut E)], k: usize) -> E {
    let mut e = E::default();
    for step in &procedure[..k] {
        step(&mut e);
    }
    e
}

/// Issue 15: the correct option of a choice question is the strictly
/// longest in at most a quarter of experiment `id`'s choice questions (of
/// which it has at least six), so length does not give the answer away.
///
/// # Panics
/// When that does not hold.
pub fn assert_the_correct_option_is_seldom_the_longest(id: &str) {
    let tells = crate::find(id)
        .unwrap_or_else(|| panic!("no experiment {id}"))
        .content()
        .unwrap_or_else(|err| panic!("{id} content: {err:?}"))
        .length_tells();
    assert!(tells.choices >= 6, "{id}: {tells:?}");
    assert!(4 * tells.longest <= tells.choices, "{id}: {tells:?}");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leading_numbers_of_readout_texts() {
        assert_eq!(leading_number("61.0%"), Some(61.0));
        assert_eq!(leading_number("-0.250 m"), Some(-0.25));
        assert_eq!(leading_number("−3.0°"), Some(-3.0));
        assert_eq!(leading_number("1.2 × 10⁵"), Some(1.2));
        assert_eq!(leading_number("--"), None);
        assert_eq!(leading_number("12-3"), Some(12.0));
    }

    #[test]
    fn running_until_a_status_counts_the_steps_and_gives_up() {
        let mut e = open("pid");
        assert_eq!(run_until_status(e.as_mut(), 10, |_| true), Some(0));
        assert_eq!(run_until_status(e.as_mut(), 3, |_| false), None);
        let mut looks = 0;
        let taken = run_until_status(e.as_mut(), 10, |_| {
            looks += 1;
            looks > 4
        });
        assert_eq!(taken, Some(4));
    }
}
