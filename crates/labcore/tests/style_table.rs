//! `web/style.css` declares the theme's custom properties that the canvas
//! reads; the style table (`labcore::scene::style`) is where their values are
//! written first. These tests hold the stylesheet to the table, value for
//! value, so the canvas, the report's SVG and the thumbnails draw each role
//! in one colour.

use labcore::scene::style::{ThemeColour, CANVAS, PLOT_BAND};
use labcore::{Role, SeriesRole};
use std::collections::BTreeMap;

fn stylesheet() -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../web/style.css");
    std::fs::read_to_string(path).expect("web/style.css")
}

/// The body of the first block that follows `opening` (braces balanced).
fn block<'a>(css: &'a str, opening: &str) -> &'a str {
    let start = css
        .find(opening)
        .unwrap_or_else(|| panic!("no `{opening}`"))
        + opening.len();
    let mut depth = 1;
    for (i, c) in css[start..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return &css[start..start + i];
                }
            }
            _ => {}
        }
    }
    panic!("`{opening}` is not closed")
}

/// The `--c-…` and `--p-…` declarations of a block: property → value.
fn theme_vars(block: &str) -> BTreeMap<String, String> {
    block
        .split(';')
        .filter_map(|decl| decl.split_once(':'))
        .map(|(k, v)| (k.trim().to_owned(), v.trim().to_owned()))
        .filter(|(k, _)| k.starts_with("--c-") || k.starts_with("--p-"))
        .collect()
}

/// Every colour of the table: the roles', the canvas, the series' and the band.
fn table() -> Vec<ThemeColour> {
    let mut all: Vec<ThemeColour> = Role::ALL.iter().map(|r| r.style().colour).collect();
    all.push(CANVAS);
    all.extend(SeriesRole::ALL.iter().map(|r| r.style().colour));
    all.push(PLOT_BAND);
    all
}

#[test]
fn style_css_light_and_dark_colours_are_the_style_table_s() {
    let css = stylesheet();
    let light = theme_vars(block(&css, ":root {"));
    let dark_media = block(&css, "@media (prefers-color-scheme: dark) {");
    let dark = theme_vars(block(dark_media, ":root {"));
    let expected = |pick: fn(&ThemeColour) -> &'static str| -> BTreeMap<String, String> {
        table()
            .iter()
            .map(|c| (c.var.to_owned(), pick(c).to_owned()))
            .collect()
    };
    assert_eq!(light, expected(|c| c.light), "web/style.css :root");
    assert_eq!(dark, expected(|c| c.dark), "web/style.css dark theme");
}

#[test]
fn style_css_gives_every_role_its_class_and_its_forced_colour() {
    let css = stylesheet();
    for role in Role::ALL {
        let style = role.style();
        let rule = format!(".{} {{ color: var({}); }}", style.class(), style.var());
        assert!(css.contains(&rule), "web/style.css lacks `{rule}`");
    }
    // Forced colours (Windows High Contrast) repaint every role and series:
    // a role left out would keep a colour the user did not choose.
    let forced = theme_vars(block(
        block(&css, "@media (forced-colors: active) {"),
        ":root {",
    ));
    for colour in table() {
        assert!(
            forced.contains_key(colour.var),
            "forced-colors lacks {}",
            colour.var
        );
    }
}

/// The page's colours and tones (`--bg` … `--bad`), light and dark, are
/// `labcore::layout::page_colours`', value for value: the report prints the
/// light ones, so a change to either side that the other does not follow
/// fails here.
#[test]
fn style_css_page_colours_and_tones_are_the_page_colour_table_s() {
    use labcore::layout::page_colours::PAGE;
    let css = stylesheet();
    let page_vars = |block: &str| -> BTreeMap<String, String> {
        block
            .split(';')
            .filter_map(|decl| decl.split_once(':'))
            .map(|(k, v)| (k.trim().to_owned(), v.trim().to_owned()))
            .filter(|(k, _)| PAGE.iter().any(|c| c.var == k))
            .collect()
    };
    let light = page_vars(block(&css, ":root {"));
    let dark_media = block(&css, "@media (prefers-color-scheme: dark) {");
    let dark = page_vars(block(dark_media, ":root {"));
    let expected = |pick: fn(&ThemeColour) -> &'static str| -> BTreeMap<String, String> {
        PAGE.iter()
            .map(|c| (c.var.to_owned(), pick(c).to_owned()))
            .collect()
    };
    assert_eq!(light, expected(|c| c.light), "web/style.css :root");
    assert_eq!(dark, expected(|c| c.dark), "web/style.css dark theme");
}
