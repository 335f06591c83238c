//! The one seam between solvers and the page: [`Experiment`] (the model)
//! and [`Presentation`] (what is shown of it), together a [`Lab`].
//!
//! labweb turns DOM events into [`Input`] values already in world coordinates,
//! calls [`Experiment::step`] with a fixed `dt`, asks for a [`Scene`] and the
//! [`Readout`]s, and paints them. Nothing here knows about the DOM.

use crate::plot::Plot;
use crate::scene::{Scene, ViewBox};
use crate::table::Table;
use crate::units::{format_degrees, format_metres, format_point};
use glam::DVec2;
use std::fmt;

/// How a parameter is shown on the page.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamKind {
    /// A range slider with a number box.
    Slider,
    /// A two-state switch; the value is 0 (`off` label) or 1 (`on` label).
    Toggle { off: &'static str, on: &'static str },
    /// One of several labelled choices; the value is the index.
    Choice(&'static [&'static str]),
    /// A number typed into a field (no slider), e.g. a random seed.
    Number,
    /// A number field that may be empty ([`Experiment::param`] gives `None`),
    /// e.g. a target coordinate before any target is set.
    OptionalNumber,
}

/// One tunable parameter, in the units the page shows (degrees for angles).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamSpec {
    /// Stable key, used in the URL hash (`t1`, `l2`, …).
    pub key: &'static str,
    /// Label shown beside the control, e.g. `θ₁`.
    pub label: &'static str,
    /// Unit shown after the value (`°`, `m`, or empty).
    pub unit: &'static str,
    pub min: f64,
    pub max: f64,
    pub step: f64,
    pub default: f64,
    pub kind: ParamKind,
    /// The value is a whole number (a count, an index): [`ParamSpec::sanitize`]
    /// rounds it, so what `set_param` returns is what the experiment stores.
    /// Always true for toggles, choices and [`ParamKind::Number`].
    pub integer: bool,
    /// A heading the page groups this control under, collapsed by default
    /// (e.g. twelve waypoint coordinates under "Waypoints"); `None`: among
    /// the main controls. Set with [`ParamSpec::in_group`].
    pub group: Option<&'static str>,
}

impl ParamSpec {
    /// A slider parameter.
    #[must_use]
    pub const fn slider(
        key: &'static str,
        label: &'static str,
        unit: &'static str,
        min: f64,
        max: f64,
        step: f64,
        default: f64,
    ) -> Self {
        Self {
            key,
            label,
            unit,
            min,
            max,
            step,
            default,
            kind: ParamKind::Slider,
            integer: false,
            group: None,
        }
    }

    /// A number field without a slider (value rounded to `step` multiples when `step` ≥ 1).
    #[must_use]
    pub const fn number(
        key: &'static str,
        label: &'static str,
        min: f64,
        max: f64,
        default: f64,
    ) -> Self {
        Self {
            key,
            label,
            unit: "",
            min,
            max,
            step: 1.0,
            default,
            kind: ParamKind::Number,
            integer: true,
            group: None,
        }
    }

    /// A number field that may be unset (see [`ParamKind::OptionalNumber`]).
    #[must_use]
    pub const fn optional_number(
        key: &'static str,
        label: &'static str,
        unit: &'static str,
        min: f64,
        max: f64,
    ) -> Self {
        Self {
            key,
            label,
            unit,
            min,
            max,
            step: 0.01,
            default: 0.0,
            kind: ParamKind::OptionalNumber,
            integer: false,
            group: None,
        }
    }

    /// A two-state toggle parameter (value 0 or 1).
    #[must_use]
    pub const fn toggle(
        key: &'static str,
        label: &'static str,
        off: &'static str,
        on: &'static str,
        default_on: bool,
    ) -> Self {
        Self {
            key,
            label,
            unit: "",
            min: 0.0,
            max: 1.0,
            step: 1.0,
            default: if default_on { 1.0 } else { 0.0 },
            kind: ParamKind::Toggle { off, on },
            integer: true,
            group: None,
        }
    }

    /// A choice among labelled options (value = index).
    #[must_use]
    pub const fn choice(
        key: &'static str,
        label: &'static str,
        options: &'static [&'static str],
        default: usize,
    ) -> Self {
        Self {
            key,
            label,
            unit: "",
            min: 0.0,
            max: (options.len() - 1) as f64,
            step: 1.0,
            default: default as f64,
            kind: ParamKind::Choice(options),
            integer: true,
            group: None,
        }
    }

    /// The same parameter holding whole numbers only (e.g. a link or sample
    /// count on a slider): see [`ParamSpec::whole_numbers`].
    #[must_use]
    pub const fn whole_numbers(self) -> Self {
        Self {
            integer: true,
            ..self
        }
    }

    /// The same parameter shown under a collapsed group heading (see
    /// [`ParamSpec::group`]).
    #[must_use]
    pub const fn in_group(self, group: &'static str) -> Self {
        Self {
            group: Some(group),
            ..self
        }
    }

    /// The group of the controls that sit with the experiment's action
    /// buttons rather than among the others ([`ParamSpec::with_actions`]).
    pub const WITH_ACTIONS: &'static str = "with the actions";

    /// The same parameter shown beside the action buttons: a control that a
    /// Procedure step uses together with an action (cartpole's Control,
    /// switched on within a third of a second of Nudge pole) sits with it,
    /// at every width.
    #[must_use]
    pub const fn with_actions(self) -> Self {
        self.in_group(Self::WITH_ACTIONS)
    }

    /// Checks a proposed value: NaN and infinities are rejected; integer
    /// parameters (toggles, choices, numbers and [`ParamSpec::whole_numbers`]
    /// sliders) are rounded to the nearest whole number; values outside
    /// `[min, max]` are clamped and reported as [`Sanitized::Clamped`]. The
    /// returned value is exactly what the experiment stores.
    pub fn sanitize(&self, value: f64) -> Result<Sanitized, ParamError> {
        if !value.is_finite() {
            return Err(ParamError::NotFinite { key: self.key });
        }
        let discrete = self.integer
            || matches!(
                self.kind,
                ParamKind::Toggle { .. } | ParamKind::Choice(_) | ParamKind::Number
            );
        let v = if discrete { value.round() } else { value };
        let clamped = v.clamp(self.min, self.max);
        if clamped != v {
            Ok(Sanitized::Clamped(clamped))
        } else {
            Ok(Sanitized::InRange(clamped))
        }
    }
}

/// Result of [`ParamSpec::sanitize`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sanitized {
    InRange(f64),
    Clamped(f64),
}

impl Sanitized {
    /// The value to apply.
    #[must_use]
    pub fn value(self) -> f64 {
        match self {
            Sanitized::InRange(v) | Sanitized::Clamped(v) => v,
        }
    }
}

/// A button on the Simulation tab (e.g. "Sweep workspace").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ActionSpec {
    pub key: &'static str,
    pub label: &'static str,
}

/// A named starting state that tells a story ("overshoot vs damping"): the
/// Simulation tab lists an experiment's presets and opens one as a link
/// (`#/<id>/simulation?<query>`), so it is shareable like any other state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Preset {
    /// Short name shown in the menu.
    pub name: &'static str,
    /// One sentence: what the student will see.
    pub description: &'static str,
    /// The link's query, without `?` (`kp=40&ki=0&kd=1`); it may also carry
    /// the shell's keys (`lock=`, `note=`…, see [`crate::route::Instructor`]).
    pub query: &'static str,
}

/// Why a parameter or action was refused. The experiment's state is unchanged.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamError {
    UnknownKey {
        key: String,
    },
    NotFinite {
        key: &'static str,
    },
    UnknownAction {
        key: String,
    },
    /// A text value of [`Experiment::set_extra_state`] that could not be read
    /// (e.g. a malformed wall code); `reason` says what was wrong.
    BadText {
        key: String,
        reason: String,
    },
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParamError::UnknownKey { key } => write!(f, "unknown parameter “{key}”"),
            ParamError::NotFinite { .. } => write!(f, "needs a finite number"),
            ParamError::UnknownAction { key } => write!(f, "unknown action “{key}”"),
            ParamError::BadText { reason, .. } => write!(f, "{reason}"),
        }
    }
}

impl std::error::Error for ParamError {}

/// A pointer or keyboard input, already in world coordinates (metres).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Input {
    /// Primary button / touch / pen pressed at a world point.
    PointerDown(DVec2),
    /// Pointer moved; `pressed` is true while dragging.
    PointerMove { pos: DVec2, pressed: bool },
    /// Pointer released (or cancelled) at a world point.
    PointerUp(DVec2),
    /// Keyboard nudge of the draggable point by a world displacement (arrow keys on the canvas).
    Nudge(DVec2),
}

impl Input {
    /// Where a draggable point (a tip or a target) should go: the pointer
    /// while it is pressed, or `current` moved by a keyboard nudge. `None`
    /// for hover and release. Shared by every experiment with a point to drag.
    #[must_use]
    pub fn drag_point(self, current: impl FnOnce() -> DVec2) -> Option<DVec2> {
        match self {
            Input::PointerDown(p)
            | Input::PointerMove {
                pos: p,
                pressed: true,
            } => Some(p),
            Input::Nudge(delta) => Some(current() + delta),
            Input::PointerMove { pressed: false, .. } | Input::PointerUp(_) => None,
        }
    }
}

/// A point the student can drag (a waypoint, an obstacle, a start or goal,
/// an arm's target), listed so the keyboard and typed coordinates can move it
/// too: every drag has a non-drag alternative (WCAG 2.2 success criterion
/// 2.5.7, "Dragging Movements").
#[derive(Clone, Debug, PartialEq)]
pub struct Handle {
    /// Stable key within the experiment while the handle exists (`w2`,
    /// `start`, `o1`, `target`).
    pub id: String,
    /// What the page and a screen reader call it ("Waypoint 2").
    pub label: String,
    /// Where it is now (world, metres).
    pub at: DVec2,
    /// The keyboard's step for it when it moves on a lattice (a grid cell,
    /// metres); `None`: the page's step, a fraction of the view.
    pub step_m: Option<f64>,
    /// It moves along x only (a setpoint on a track): the Move form offers
    /// x alone and the up and down keys leave it where it is.
    pub x_only: bool,
    /// A cell of a grid of this many rows (1 m cells from the world's
    /// origin), numbered as its experiment's controls number cells: column
    /// from the left, row 0 at the top. The Move form then shows and takes
    /// the column and row, not metres: one system for one point. `None`:
    /// metres.
    pub grid_rows: Option<usize>,
}

impl Handle {
    /// A handle moved by the page's default keyboard step.
    #[must_use]
    pub fn new(id: impl Into<String>, label: impl Into<String>, at: DVec2) -> Self {
        Self {
            id: id.into(),
            label: label.into(),
            at,
            step_m: None,
            x_only: false,
            grid_rows: None,
        }
    }

    /// A handle that moves along x only, at height `at.y`.
    #[must_use]
    pub fn along_x(id: impl Into<String>, label: impl Into<String>, at: DVec2) -> Self {
        Self {
            x_only: true,
            ..Self::new(id, label, at)
        }
    }

    /// The names of the two numbers the Move form shows for this handle and
    /// their values now: `x`, `y` in metres, or a grid cell's `column` and
    /// `row` (see [`Handle::grid_rows`]).
    #[must_use]
    pub fn typed(&self) -> ([&'static str; 2], DVec2) {
        match self.grid_rows {
            Some(rows) => (
                ["column", "row"],
                DVec2::new(self.at.x.floor(), rows as f64 - 1.0 - self.at.y.floor()),
            ),
            None => (["x", "y"], self.at),
        }
    }

    /// The world point for two typed numbers (the inverse of
    /// [`Handle::typed`]): a cell's centre, or the point itself.
    #[must_use]
    pub fn from_typed(&self, v: DVec2) -> DVec2 {
        match self.grid_rows {
            Some(rows) => DVec2::new(v.x.floor() + 0.5, rows as f64 - v.y.floor() - 0.5),
            None => v,
        }
    }

    /// Typed numbers in words: `(2.10, 3.40) m` or `column 3, row 12`.
    #[must_use]
    pub fn typed_text(&self, v: DVec2) -> String {
        match self.grid_rows {
            // Whole numbers (an f64's `{}` would pull in the shortest-float printer).
            Some(_) => format!("column {}, row {}", v.x.floor() as i64, v.y.floor() as i64),
            None => format_point(v),
        }
    }

    /// The target handle of an arm experiment: at `target` once set, else
    /// on the arm's `tip`, where a press would set it (IK and DLS).
    #[must_use]
    pub fn arm_target(target: Option<DVec2>, tip: DVec2) -> Self {
        Self::new("target", "Target", target.unwrap_or(tip))
    }
}

/// A status or notice in a finger's words, shown while the student uses
/// touch: "click" becomes "tap" (statuses and notices start in lower case;
/// hints have [`Presentation::touch_hint`]).
#[must_use]
pub fn for_touch(text: &str) -> String {
    text.replace("click", "tap")
}

/// What a group heading counts ([`ParamSpec::group`]): its points, an
/// `…x`/`…y` pair of keys counting once, and of optional fields only those
/// set (`value` gives a key's value, as [`Experiment::param`]): "Waypoints
/// (2)" for two waypoints, not for four coordinate fields.
#[must_use]
pub fn group_count(specs: &[ParamSpec], group: &str, value: &dyn Fn(&str) -> Option<f64>) -> usize {
    let members = || specs.iter().filter(|s| s.group == Some(group));
    members()
        .filter(|s| {
            // `w1y` counts with its `w1x`.
            let stem = |k: &'static str, end: u8| {
                (k.as_bytes().last() == Some(&end)).then(|| &k[..k.len() - 1])
            };
            stem(s.key, b'y').is_none_or(|y| !members().any(|o| stem(o.key, b'x') == Some(y)))
        })
        .filter(|s| s.kind != ParamKind::OptionalNumber || value(s.key).is_some())
        .count()
}

/// Keys held while a pointer input happened (Shift-click, Ctrl-click).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Modifiers {
    pub shift: bool,
    /// Ctrl, or ⌘ on a Mac.
    pub ctrl: bool,
}

/// Tone of the status badge above the canvas.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tone {
    Neutral,
    Good,
    Warning,
    Bad,
}

/// Where the run stands, as the model's evidence says.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Phase {
    /// The run can go on (running, waiting for input, balancing…).
    #[default]
    Live,
    /// The run is over (a goal reached, a pole fallen, a loop unstable, a
    /// search done): stepping changes nothing worth watching, so the time bar
    /// offers Replay instead of Pause.
    Ended,
}

/// The run's state shown in the status badge (e.g. "in reach", "reached the
/// goal"). It is derived from the model every frame, never from a message:
/// transient messages are [`Notice`]s.
#[derive(Clone, Debug, PartialEq)]
pub struct Status {
    pub text: String,
    pub tone: Tone,
    pub phase: Phase,
}

impl Status {
    /// A status of a run that can go on.
    #[must_use]
    pub fn new(text: impl Into<String>, tone: Tone) -> Self {
        Self {
            text: text.into(),
            tone,
            phase: Phase::Live,
        }
    }

    /// A status of a run that has ended ([`Phase::Ended`]).
    #[must_use]
    pub fn ended(text: impl Into<String>, tone: Tone) -> Self {
        Self {
            text: text.into(),
            tone,
            phase: Phase::Ended,
        }
    }
}

/// A transient message beside the status ("all 6 waypoints are queued",
/// "settings changed: run the check again"). The page shows it under the
/// badge, never in its place, and hides it after a few seconds or at the
/// student's next input, action or parameter change, unless that posted a
/// new one (a new [`Notice::serial`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Notice {
    /// Grows with every post, so the page can tell a new notice from an old one.
    pub serial: u64,
    pub text: String,
    pub tone: Tone,
}

/// The notice an experiment last posted: keep one as a field and return
/// [`Notices::current`] from [`Presentation::notice`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Notices {
    serial: u64,
    current: Option<Notice>,
}

impl Notices {
    /// Posts a notice (it replaces the previous one).
    pub fn post(&mut self, text: impl Into<String>, tone: Tone) {
        self.serial += 1;
        self.current = Some(Notice {
            serial: self.serial,
            text: text.into(),
            tone,
        });
    }

    /// Withdraws the current notice (e.g. when what it warned about is over).
    pub fn clear(&mut self) {
        self.current = None;
    }

    /// The notice to show, if any.
    #[must_use]
    pub fn current(&self) -> Option<Notice> {
        self.current.clone()
    }
}

/// One live number beside the canvas, already formatted.
#[derive(Clone, Debug, PartialEq)]
pub struct Readout {
    /// Stable key (tests and the page find the readout by it).
    pub key: &'static str,
    pub label: &'static str,
    /// Formatted value including its unit, e.g. `1.234 m` or `--` when undefined.
    pub value: String,
}

impl Readout {
    #[must_use]
    pub fn new(key: &'static str, label: &'static str, value: impl Into<String>) -> Self {
        Self {
            key,
            label,
            value: value.into(),
        }
    }

    /// A length in metres with exactly [`Readout::METRE_DECIMALS`] decimals,
    /// e.g. `1.500 m` (`--` when not finite).
    #[must_use]
    pub fn metres(key: &'static str, label: &'static str, value_m: f64) -> Self {
        Self::new(key, label, format_metres(value_m))
    }

    /// An angle in degrees with exactly [`Readout::DEGREE_DECIMALS`] decimal,
    /// e.g. `-35.0°` (`--` when not finite).
    #[must_use]
    pub fn degrees(key: &'static str, label: &'static str, value_deg: f64) -> Self {
        Self::new(key, label, format_degrees(value_deg))
    }

    /// Decimals of every length readout, in every experiment (1 mm).
    pub const METRE_DECIMALS: usize = crate::units::METRE_DECIMALS;
    /// Decimals of every angle readout, in every experiment (0.1°).
    pub const DEGREE_DECIMALS: usize = crate::units::DEGREE_DECIMALS;
}

/// One experiment's model: parameters, state, a fixed-step simulation,
/// input, actions, plots as data, handles, link state, files and presets.
/// What is shown of it is its [`Presentation`].
///
/// Contract: every method leaves the state finite whatever it is given; a
/// refused input leaves the state exactly as it was.
pub trait Experiment {
    /// Stable key: URL hash, content file name, tests.
    fn id(&self) -> &'static str;
    /// The tunable parameters, in display order.
    fn params(&self) -> &'static [ParamSpec];
    /// Current value of a parameter in display units; `None` for an unknown
    /// key or an unset [`ParamKind::OptionalNumber`].
    fn param(&self, key: &str) -> Option<f64>;
    /// Sets a parameter (display units). Returns what was applied (it may be clamped).
    fn set_param(&mut self, key: &str, value: f64) -> Result<Sanitized, ParamError>;
    /// The buttons of the Simulation tab.
    fn actions(&self) -> &'static [ActionSpec] {
        &[]
    }
    /// Runs a button's action.
    fn action(&mut self, key: &str) -> Result<(), ParamError> {
        Err(ParamError::UnknownAction { key: key.into() })
    }
    /// Whether the button of action `key` is shown now: one that has
    /// nothing to act on is hidden (potential's "Hide basin map" while no
    /// basin map is shown). Default: every button is shown.
    fn action_shown(&self, _key: &str) -> bool {
        true
    }
    /// A pointer or keyboard input in world coordinates.
    fn input(&mut self, input: Input);
    /// An input with the modifier keys held at the time (the page always
    /// calls this). Default: the modifiers do not matter.
    fn input_with(&mut self, input: Input, _modifiers: Modifiers) {
        self.input(input);
    }
    /// Advances the simulation by one fixed step of `dt_s` seconds
    /// (deterministic). Accepts `0 < dt_s ≤` [`crate::clock::MAX_DT_S`] (the
    /// shell uses [`crate::clock::Clock::DT_S`]); a NaN, infinite, negative,
    /// zero or too long step is refused and leaves the state exactly as it
    /// was (check with [`crate::clock::valid_dt`]).
    fn step(&mut self, dt_s: f64);
    /// Whether the experiment evolves in time, so the page shows the time
    /// controls (play/pause, step, speed, reset). Default: no.
    fn animated(&self) -> bool {
        false
    }
    /// The model's own step, seconds: what one press of the time bar's Step
    /// takes (and what the time bar says a step is). An experiment with a
    /// natural step (a filter cycle) returns it; the shell takes the nearest
    /// whole number of [`crate::clock::Clock::DT_S`] steps
    /// ([`crate::clock::Clock::fixed_steps_in`]), so running and stepping
    /// still take the same fixed steps. Default: one fixed step.
    fn natural_step_s(&self) -> f64 {
        crate::clock::Clock::DT_S
    }
    /// Back to the start of the run (time controls' Reset): the motion, the
    /// trail, the plots restart; the parameters are kept.
    fn reset(&mut self) {}
    /// The live plots, in display order. The page redraws a plot when its
    /// [`Plot::revision`] changes.
    fn plots(&self) -> &[Plot] {
        &[]
    }
    /// Whether a pointer pressed at `p` (world) grabs a draggable handle (a
    /// tip, a target, an obstacle) within `tolerance_m`. On touch screens a
    /// swipe that starts elsewhere scrolls the page; a tap still acts.
    fn handle_at(&self, _p: DVec2, _tolerance_m: f64) -> bool {
        false
    }
    /// Every draggable handle now, in a stable order (the keyboard cycles
    /// through them with `[` and `]`). An experiment whose
    /// [`Experiment::handle_at`] is true somewhere lists at least one.
    /// Default: none.
    fn handles(&self) -> Vec<Handle> {
        Vec::new()
    }
    /// Moves the handle `id` to `to` (world) exactly as a pointer drag would:
    /// a press on the handle, a move to `to`, a release there. Returns
    /// whether there was such a handle (a refused point, NaN or infinite,
    /// changes nothing). Override it where a press on the handle could grab
    /// another one or a short drag counts as a tap.
    fn move_handle(&mut self, id: &str, to: DVec2) -> bool {
        let Some(h) = self.handles().into_iter().find(|h| h.id == id) else {
            return false;
        };
        if !to.is_finite() {
            return false;
        }
        self.input(Input::PointerDown(h.at));
        finish_drag(self, to)
    }
    /// File name extensions the experiment can load (e.g. `[".map"]`); the
    /// page offers a file picker and dropping a file on the canvas.
    fn file_types(&self) -> &'static [&'static str] {
        &[]
    }
    /// Loads a file the student chose. On error the state is unchanged and
    /// the message (naming the line where it can) is shown on the page.
    fn load_file(&mut self, _name: &str, _text: &str) -> Result<(), String> {
        Err("this experiment does not load files".into())
    }
    /// A text file the student can save (file name, contents), e.g. the grid
    /// as a map when it is too large for a link. `None`: no such button.
    fn export_text(&self) -> Option<(String, String)> {
        None
    }
    /// Text-valued state that belongs in the link beside the numeric
    /// parameters (e.g. a grid's walls as a wall code, obstacles), as
    /// `(key, value)` pairs; [`crate::route::format`] appends them after the
    /// parameters (percent-encoding anything outside the URL's unreserved
    /// characters). A key may be left out, e.g. when the value would make the
    /// link too long; the experiment then says so in its status or readouts.
    /// Keys must differ from the [`Experiment::params`] keys. Default: none.
    fn extra_state(&self) -> Vec<(&'static str, String)> {
        Vec::new()
    }
    /// Applies one text value from a link ([`crate::route::apply_params`]
    /// applies these before the numeric parameters, so e.g. a start cell is
    /// checked against the grid the link describes). On error the state is
    /// unchanged: [`ParamError::UnknownKey`] for a key the experiment does not
    /// keep, [`ParamError::BadText`] for a value it cannot read.
    fn set_extra_state(&mut self, key: &str, _value: &str) -> Result<(), ParamError> {
        Err(ParamError::UnknownKey { key: key.into() })
    }
    /// Named starting states that tell a story, shown in a Presets menu on
    /// the Simulation tab. Default: none.
    fn presets(&self) -> &'static [Preset] {
        &[]
    }
    /// Whether the simulation is still moving (the page may idle when false).
    fn animating(&self) -> bool {
        true
    }
    /// An estimate of the heap the model's state holds, bytes: what one
    /// snapshot of it costs the timeline, which keeps its snapshots within
    /// a budget ([`crate::timeline::Timeline::BUDGET_BYTES`]). Default: the
    /// plots' samples; an experiment holding more (a grid, a tree) adds it.
    fn state_bytes(&self) -> usize {
        crate::plot::plots_bytes(self.plots())
    }
    /// How many units of work one step is, as the timeline replays it: an
    /// experiment whose step runs a batch (RRT*'s iterations per frame)
    /// says how big, and the timeline snapshots it that many times more
    /// often ([`crate::timeline::Timeline::first_interval`]), so a scrub
    /// replays about as much work in every experiment. Default: 1.
    fn step_weight(&self) -> u64 {
        1
    }
    /// Which kind of work a step does now, where kinds cost very
    /// differently (A*: 1 while a search expands cells, 0 while the robot
    /// drives or nothing moves): the timeline keeps a snapshot wherever it
    /// changes ([`crate::timeline::Timeline::stepped`]), so a jump past a
    /// finished search never replays it, however far apart its periodic
    /// snapshots of a big state are. Default: 0, one kind.
    fn work_phase(&self) -> u8 {
        0
    }
    /// The timeline is about to replay steps of this copy and read it only
    /// after [`Experiment::end_replay`] ([`crate::timeline::Timeline::state_at`]):
    /// a step may put off what it derives from the state alone (pid's step
    /// metrics scan the whole response, every step) until then. Default:
    /// nothing.
    fn begin_replay(&mut self) {}
    /// The replay is over: derive what its steps put off, so the state is
    /// bit for bit the one the live run had at that step. Default: nothing.
    fn end_replay(&mut self) {}
    /// Takes the runs that `end` (another state of the same experiment:
    /// the run's last, [`Lab::as_any`]) keeps only to compare with (PID's
    /// pinned runs) in place of its own. The page shows a past moment of a
    /// run with the comparisons its end has, as it draws the end's plots
    /// (issue 53 §2: pinned runs stay while the timeline goes back). A
    /// comparison never changes how the run steps. Default: none kept.
    fn take_comparisons(&mut self, _end: &dyn std::any::Any) {}
}

/// What is shown of an experiment (its `view.rs`): the view box, the display
/// list, the readouts, the status badge, notices, hints, the screen
/// reader's description and the tables. Methods take `&self` and only read
/// the model, except [`Presentation::viewport_px`] (view state, never in the
/// link) and [`Presentation::preview`] (the home-page picture's state).
///
/// It extends [`Experiment`] (the view depends on the model, never the
/// other way), so one vtable serves both: a second, independent supertrait
/// would give every experiment a second vtable in each wasm module.
pub trait Presentation: Experiment {
    /// The world rectangle the canvas should show.
    fn view(&self) -> ViewBox;
    /// The canvas's size in CSS pixels, told by the page on mount and on every
    /// resize, so an experiment can choose a view that keeps handles and cells
    /// finger-sized on a phone. It must not change the link state. Default:
    /// ignored.
    fn viewport_px(&mut self, _width_px: f64, _height_px: f64) {}
    /// Fills `out` with this frame's display list (cleared first by the caller).
    fn scene(&self, out: &mut Scene);
    /// The live numbers beside the canvas.
    fn readouts(&self) -> Vec<Readout>;
    /// The status badge: the run's state from the model's evidence.
    fn status(&self) -> Status;
    /// The latest transient notice, if any (see [`Notice`]). Default: none.
    fn notice(&self) -> Option<Notice> {
        None
    }
    /// One or two sentences a screen reader says about the scene ("robot at
    /// (2.10, 3.40) m heading 45°, 2 of 3 waypoints reached"), on request and
    /// when a run ends. Default: the status and the readouts.
    fn describe(&self) -> String {
        let readouts: Vec<String> = self
            .readouts()
            .iter()
            .map(|r| format!("{} {}", r.label, r.value))
            .collect();
        format!("{}. {}.", self.status().text, readouts.join(", "))
    }
    /// One line above the canvas telling the student how to interact.
    fn hint(&self) -> &'static str;
    /// The hint to show while the student uses touch, when it differs
    /// (e.g. no Shift-click on a phone). Default: [`Presentation::hint`].
    fn touch_hint(&self) -> &'static str {
        self.hint()
    }
    /// The live quantities "The math" panel puts into the equations: key,
    /// symbol, value as shown and unit ([`crate::live_math`]).
    fn quantities(&self) -> Vec<crate::live_math::Quantity> {
        Vec::new()
    }
    /// The governing equations "The math" panel shows, each producing one
    /// readout; none by default.
    fn equations(&self) -> &'static [crate::live_math::Equation] {
        &[]
    }
    /// The keys of the plots besides the main one that the Procedure has
    /// the student watch (issue 53 §5): the page puts them first under the
    /// main plot, in view beside the canvas on a laptop and right under the
    /// main plot on a phone. Default: none (the plots in their order).
    fn watched_plots(&self) -> &'static [&'static str] {
        &[]
    }
    /// Live tables shown beside the canvas (an open list, a comparison).
    fn tables(&self) -> Vec<Table> {
        Vec::new()
    }
    /// Whether the canvas must take every touch (e.g. painting walls), so a
    /// swipe over it never scrolls the page. The page says so and offers a
    /// way to scroll. Default: no.
    fn captures_touch(&self) -> bool {
        false
    }
    /// Puts the experiment in a representative state for its home-page
    /// picture (e.g. a swept workspace, a solved target). Default: as built.
    fn preview(&mut self) {}
}

/// An experiment and its presentation: what the registry makes and the page
/// runs. Every type with both traits that can be copied is one. A `&dyn Lab`
/// passes where a `&dyn Experiment` (the model alone) is asked for.
pub trait Lab: Presentation {
    /// A copy of the whole experiment as it is now: what the timeline keeps
    /// as a snapshot ([`crate::timeline::Timeline`]). Stepping the copy and
    /// the original alike gives the same states, bit for bit.
    fn snapshot(&self) -> Box<dyn Lab>;
    /// The state as [`std::any::Any`], for
    /// [`Experiment::take_comparisons`].
    fn as_any(&self) -> &dyn std::any::Any;
}

impl<T: Presentation + Clone + 'static> Lab for T {
    fn snapshot(&self) -> Box<dyn Lab> {
        Box::new(self.clone())
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}

/// Ends a drag an experiment has grabbed (a press on a handle, or its own
/// record of one): moves the pressed pointer to `to` and releases it there,
/// as a hand would. [`Experiment::move_handle`] and its overrides end with it.
pub fn finish_drag<E: Experiment + ?Sized>(exp: &mut E, to: DVec2) -> bool {
    exp.input(Input::PointerMove {
        pos: to,
        pressed: true,
    });
    exp.input(Input::PointerUp(to));
    true
}

/// The slot (0-based) and axis of a numbered point's link key: with prefix
/// `'w'`, `w3x` → `(2, true)` and `w1y` → `(0, false)`; `None` for another
/// key or a number outside `1..=count`. Used by experiments that keep
/// numbered points (waypoints, obstacles) as `x`/`y` parameter pairs.
#[must_use]
pub fn point_slot(key: &str, prefix: char, count: usize) -> Option<(usize, bool)> {
    let rest = key.strip_prefix(prefix)?;
    let (digits, is_x) = match rest.strip_suffix('x') {
        Some(d) => (d, true),
        None => (rest.strip_suffix('y')?, false),
    };
    // Digits only: `parse` would also take a sign (`w+1x`).
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let n: usize = digits.parse().ok()?;
    n.checked_sub(1).filter(|i| *i < count).map(|i| (i, is_x))
}

/// The formatted value of the readout `key`, or `None` when the experiment
/// shows no such readout now.
#[must_use]
pub fn readout_value(experiment: &dyn Presentation, key: &str) -> Option<String> {
    experiment
        .readouts()
        .into_iter()
        .find(|r| r.key == key)
        .map(|r| r.value)
}

/// A target point after setting one coordinate from a `tx`/`ty` parameter:
/// `key` ending in `x` sets x, otherwise y; with no point yet, the other
/// coordinate comes from `fallback` (usually the current tip).
#[must_use]
pub fn with_coordinate(point: Option<DVec2>, fallback: DVec2, key: &str, value: f64) -> DVec2 {
    let from = point.unwrap_or(fallback);
    if key.ends_with('x') {
        DVec2::new(value, from.y)
    } else {
        DVec2::new(from.x, value)
    }
}

/// A dragged or nudged target point clamped into the ranges of its typed
/// coordinates (`x_key`, `y_key` of `specs`), so every target a pointer or
/// the keyboard can set is one a link (`tx=…&ty=…`) reproduces without a
/// notice. The canvas may show more than the range (a wide screen): a click
/// beyond it sets the target on the range's edge.
#[must_use]
pub fn clamp_to_params(specs: &[ParamSpec], x_key: &str, y_key: &str, p: DVec2) -> DVec2 {
    let clamp = |key: &str, v: f64| match find_spec(specs, key) {
        Some(s) => v.clamp(s.min, s.max),
        None => v,
    };
    DVec2::new(clamp(x_key, p.x), clamp(y_key, p.y))
}

/// Shared helper: look up a spec by key.
#[must_use]
pub fn find_spec<'a>(specs: &'a [ParamSpec], key: &str) -> Option<&'a ParamSpec> {
    specs.iter().find(|s| s.key == key)
}

/// The first half of every `set_param`: finds `key` among `specs` and
/// sanitizes `value` (clamped to range; NaN, infinities and unknown keys refused).
pub fn check_param(specs: &[ParamSpec], key: &str, value: f64) -> Result<Sanitized, ParamError> {
    find_spec(specs, key)
        .ok_or_else(|| ParamError::UnknownKey { key: key.into() })?
        .sanitize(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPEC: ParamSpec = ParamSpec::slider("t1", "θ1", "°", -180.0, 180.0, 1.0, 35.0);

    #[test]
    fn sanitize_clamps_and_rejects_nan() {
        assert_eq!(SPEC.sanitize(10.0), Ok(Sanitized::InRange(10.0)));
        assert_eq!(SPEC.sanitize(500.0), Ok(Sanitized::Clamped(180.0)));
        assert_eq!(SPEC.sanitize(-500.0), Ok(Sanitized::Clamped(-180.0)));
        assert!(SPEC.sanitize(f64::NAN).is_err());
        assert!(SPEC.sanitize(f64::INFINITY).is_err());
    }

    /// Regression: DLS `set_param("n", 2.5)` returned `InRange(2.5)` but stored 3.
    #[test]
    fn integer_sliders_round_in_sanitize() {
        let n = ParamSpec::slider("n", "Links", "", 2.0, 8.0, 1.0, 4.0).whole_numbers();
        assert!(n.integer);
        assert_eq!(n.sanitize(2.5), Ok(Sanitized::InRange(3.0)));
        assert_eq!(n.sanitize(4.49), Ok(Sanitized::InRange(4.0)));
        assert_eq!(n.sanitize(8.6), Ok(Sanitized::Clamped(8.0)));
        assert_eq!(SPEC.sanitize(10.5), Ok(Sanitized::InRange(10.5)));
    }

    #[test]
    fn toggles_round_to_zero_or_one() {
        let t = ParamSpec::toggle("elbow", "Elbow", "down", "up", true);
        assert_eq!(t.sanitize(0.7), Ok(Sanitized::InRange(1.0)));
        assert_eq!(t.sanitize(3.0), Ok(Sanitized::Clamped(1.0)));
    }
}
