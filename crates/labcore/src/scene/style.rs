//! The style table: how each [`Role`] of a display list and each
//! [`SeriesRole`] of a plot looks, written once.
//!
//! Every picture of the lab takes its colours, dashes and strokes from here:
//! - the canvas (labweb `draw.rs`, `plot_view.rs`) reads the CSS custom
//!   property [`RoleStyle::var`] of each role, so it follows the page's theme
//!   (light, dark, more contrast, forced colours);
//! - the report's SVG (`report/scene_svg.rs` and the plots in `report.rs`)
//!   writes the light value [`RoleStyle::light`];
//! - the home page's thumbnails (xtask `thumbs.rs`) give each shape the class
//!   [`RoleStyle::class`], whose rule in `web/style.css` is
//!   `color: var(--c-…)`;
//! - `web/style.css` declares the custom properties: `tests/style_table.rs`
//!   checks its light (`:root`) and dark (`prefers-color-scheme: dark`)
//!   values against this table, value for value, and that the more-contrast
//!   and forced-colours blocks know every role.
//!
//! A new role is one line in [`Role`] and one row in [`Role::style`] (the
//! compiler asks for it), then its values in `web/style.css` (the test asks
//! for them). The colours are the Okabe–Ito palette (safe for the common
//! colour-vision deficiencies) and its lighter dark-theme kin; shapes and
//! dashes carry meaning too, never colour alone.
//!
//! Dashes and widths travel with each item of the display list (`dashed`,
//! `width_px`); the patterns and strokes they stand for are the constants
//! below, shared by the canvas and the SVG.

use crate::plot::SeriesRole;

macro_rules! roles {
    ($(#[$meta:meta])* pub enum Role { $($(#[$vmeta:meta])* $variant:ident,)* }) => {
        $(#[$meta])*
        pub enum Role { $($(#[$vmeta])* $variant,)* }

        impl Role {
            /// Every role, in declaration order (`Role::ALL[r as usize] == r`).
            pub const ALL: &'static [Role] = &[$(Role::$variant),*];
        }
    };
}

roles! {
    /// What a shape means; the page picks its colour and weight from the
    /// style table ([`Role::style`]).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
    pub enum Role {
        /// Axes and grid lines.
        Grid,
        /// Reach circles and other theoretical bounds.
        Bound,
        /// The arm's links.
        Link,
        /// Joint markers.
        Joint,
        /// The fixed base.
        Base,
        /// The end-effector.
        Tip,
        /// A user target.
        Target,
        /// A ghost (the other IK branch, a previous pose).
        Ghost,
        /// Sampled points (workspace cloud).
        Sample,
        /// Manipulability ellipse, highlighted quantities.
        Accent,
        /// Something wrong: unreachable target, collision.
        Warning,
        /// Plain text labels.
        Text,
        /// The mobile robot's body.
        Robot,
        /// Obstacles and walls.
        Obstacle,
        /// A planned or best path.
        Path,
        /// An estimate (EKF mean and ellipse), a search frontier.
        Estimate,
        /// Visited or closed cells, tree edges.
        Visited,
    }
}

/// One colour of the theme: its CSS custom property and its values in the
/// light and the dark theme (`#rrggbb`, as `web/style.css` spells them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThemeColour {
    /// The CSS custom property (`--c-link`).
    pub var: &'static str,
    /// The light theme's value (`:root`); the report prints it.
    pub light: &'static str,
    /// The dark theme's value (`prefers-color-scheme: dark`).
    pub dark: &'static str,
}

/// How shapes of one [`Role`] look: one row of the style table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoleStyle {
    /// The colour, in both themes.
    pub colour: ThemeColour,
    /// Opacity of this role's lines, `[0, 1]`: a ghost is see-through.
    pub line_opacity: f64,
}

impl RoleStyle {
    /// The CSS custom property of the role's colour (`--c-link`).
    #[must_use]
    pub const fn var(&self) -> &'static str {
        self.colour.var
    }

    /// The light theme's colour (`#0072B2`).
    #[must_use]
    pub const fn light(&self) -> &'static str {
        self.colour.light
    }

    /// The class a thumbnail gives the role's shapes (`c-link`): the custom
    /// property's name without its dashes.
    #[must_use]
    pub fn class(&self) -> &'static str {
        self.colour.var.trim_start_matches('-')
    }
}

/// A row of the table: a colour and full opacity.
const fn row(var: &'static str, light: &'static str, dark: &'static str) -> RoleStyle {
    RoleStyle {
        colour: ThemeColour { var, light, dark },
        line_opacity: 1.0,
    }
}

impl Role {
    /// The role's row of the style table.
    ///
    /// Inlined, so a program that reads one column (the canvas reads only
    /// [`RoleStyle::var`]) carries only that column's strings.
    #[inline(always)]
    #[must_use]
    pub const fn style(self) -> RoleStyle {
        match self {
            //                     CSS property    light      dark
            Role::Grid => row("--c-grid", "#e3e7ec", "#242b33"),
            Role::Bound => row("--c-bound", "#7a8590", "#8c97a3"),
            Role::Link => row("--c-link", "#0072B2", "#56B4E9"),
            Role::Joint => row("--c-joint", "#1b1f24", "#e7eaee"),
            Role::Base => row("--c-base", "#1b1f24", "#e7eaee"),
            Role::Tip => row("--c-tip", "#D55E00", "#f08a4b"),
            Role::Target => row("--c-target", "#CC79A7", "#e59cc9"),
            Role::Ghost => RoleStyle {
                line_opacity: GHOST_LINE_OPACITY,
                ..row("--c-ghost", "#5f6a75", "#8c97a3")
            },
            Role::Sample => row("--c-sample", "#009E73", "#2fc495"),
            Role::Accent => row("--c-accent", "#B36B00", "#F0E442"),
            Role::Warning => row("--c-warning", "#D55E00", "#f08a4b"),
            Role::Text => row("--c-text", "#1b1f24", "#e7eaee"),
            Role::Robot => row("--c-robot", "#0072B2", "#56B4E9"),
            Role::Obstacle => row("--c-obstacle", "#5f6a75", "#8c97a3"),
            Role::Path => row("--c-path", "#E69F00", "#F0E442"),
            Role::Estimate => row("--c-estimate", "#CC79A7", "#e59cc9"),
            Role::Visited => row("--c-visited", "#56B4E9", "#2b5d7a"),
        }
    }
}

/// A ghost's lines are drawn at this opacity (and dashed), so the pose it
/// shadows reads first.
const GHOST_LINE_OPACITY: f64 = 0.7;

/// The canvas behind every scene.
pub const CANVAS: ThemeColour = ThemeColour {
    var: "--c-canvas",
    light: "#ffffff",
    dark: "#12161b",
};

/// A plot's shaded bands (a tolerance, a settling band).
pub const PLOT_BAND: ThemeColour = ThemeColour {
    var: "--p-band",
    light: "#E69F00",
    dark: "#E69F00",
};

/// How one series of a plot looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeriesStyle {
    /// The colour, in both themes.
    pub colour: ThemeColour,
    /// The dash pattern, CSS pixels on and off (empty: solid). Every pair
    /// of series roles differs in dash as well as colour, so a plot reads in
    /// grey print too.
    pub dash_px: &'static [f64],
}

const fn series(
    var: &'static str,
    light: &'static str,
    dark: &'static str,
    dash_px: &'static [f64],
) -> SeriesStyle {
    SeriesStyle {
        colour: ThemeColour { var, light, dark },
        dash_px,
    }
}

impl SeriesRole {
    /// The series role's row of the style table (inlined, as
    /// [`Role::style`]).
    #[inline(always)]
    #[must_use]
    pub const fn style(self) -> SeriesStyle {
        match self {
            //                                     CSS property light      dark       dash
            SeriesRole::Primary => series("--p-1", "#0072B2", "#56B4E9", &[]),
            SeriesRole::Secondary => series("--p-2", "#D55E00", "#f08a4b", &[9.0, 4.0]),
            SeriesRole::Tertiary => series("--p-3", "#009E73", "#2fc495", &[2.0, 3.0]),
            SeriesRole::Quaternary => series("--p-4", "#CC79A7", "#e59cc9", &[9.0, 3.0, 2.0, 3.0]),
            SeriesRole::Reference => series("--p-5", "#5f6a75", "#a3adb8", &[5.0, 5.0]),
            SeriesRole::Bound => series("--p-6", "#B36B00", "#F0E442", &[2.0, 2.0]),
        }
    }
}

/// A plot's reference lines: their dash, CSS pixels on and off (their
/// colour is [`SeriesRole::Reference`]'s).
pub const REF_LINE_DASH_PX: [f64; 2] = [6.0, 4.0];
/// Opacity of a plot's shaded bands ([`PLOT_BAND`]).
pub const BAND_OPACITY: f64 = 0.22;

/// The dash of a dashed item (`dashed: true`), CSS pixels on and off.
pub const DASH_PX: [f64; 2] = [6.0, 5.0];
/// Stroke of outlines (circles, ellipses, polygons, rectangles) and of the
/// ring around dots, CSS pixels.
pub const OUTLINE_PX: f64 = 2.0;
/// Opacity of a filled circle's or an ellipse's area.
pub const FILL_OPACITY_LIGHT: f64 = 0.18;
/// Opacity of a filled polygon's or rectangle's area.
pub const FILL_OPACITY: f64 = 0.35;
/// Opacity of the dots of a small sample cloud.
pub const POINTS_OPACITY: f64 = 0.55;
/// Width of the background halo behind a label's letters, CSS pixels.
pub const LABEL_HALO_PX: f64 = 4.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_role_list_is_in_declaration_order_and_every_role_has_its_own_property() {
        for (i, role) in Role::ALL.iter().enumerate() {
            assert_eq!(*role as usize, i);
            let style = role.style();
            assert!(style.var().starts_with("--c-"), "{role:?}");
            assert_eq!(style.class(), &style.var()[2..]);
            for value in [style.colour.light, style.colour.dark] {
                assert!(
                    value.len() == 7
                        && value.starts_with('#')
                        && value[1..].chars().all(|c| c.is_ascii_hexdigit()),
                    "{role:?}: {value}"
                );
            }
            for other in &Role::ALL[i + 1..] {
                assert_ne!(style.var(), other.style().var(), "{role:?} {other:?}");
            }
        }
    }

    #[test]
    fn every_series_role_differs_from_every_other_in_dash_and_property() {
        for (i, a) in SeriesRole::ALL.iter().enumerate() {
            for b in &SeriesRole::ALL[i + 1..] {
                assert_ne!(a.style().dash_px, b.style().dash_px, "{a:?} {b:?}");
                assert_ne!(a.style().colour.var, b.style().colour.var);
            }
        }
    }
}
