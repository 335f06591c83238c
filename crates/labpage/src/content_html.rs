//! HTML of the pages that need no simulation: the navigation, the home page
//! and each experiment's article with its six tabs (Aim, Theory, Procedure and
//! References filled in; Simulation and Self-assessment as placeholders the
//! wasm front end fills).
//!
//! `cargo xtask dist` writes this HTML into `index.html`, so the reading tabs
//! show as soon as the page arrives; the front end reuses the same functions
//! when a page has no pre-rendered article. Content files are ours and
//! compiled in, so their text (with MathML and a few inline tags) goes into
//! the page as HTML; anything from the URL never does.

use crate::catalogue::{Group, CATALOGUE};
use crate::content::{Block, Content, Reference};
use crate::route::Tab;

/// Escapes text for inclusion in HTML (content and attribute values); the
/// one rule of [`labcore::layout::html::escape`].
pub use labcore::layout::html::escape;

#[must_use]
pub fn aim(content: &Content) -> String {
    content.aim.iter().map(|p| format!("<p>{p}</p>")).collect()
}

#[must_use]
pub fn theory(content: &Content) -> String {
    content
        .theory
        .iter()
        .map(|b| match b {
            Block::Heading(h) => format!("<h3>{h}</h3>"),
            Block::Paragraph(p) => format!("<p>{p}</p>"),
            // Its own scroll box: a wide formula never widens the page.
            Block::Formula(f) => {
                format!("<div class=\"formula\" tabindex=\"0\" role=\"group\" aria-label=\"Formula\">{f}</div>")
            }
            Block::Note(n) => format!("<aside class=\"note\">{n}</aside>"),
        })
        .collect()
}

#[must_use]
pub fn procedure(content: &Content) -> String {
    let steps: String = content
        .procedure
        .iter()
        .map(|s| format!("<li>{s}</li>"))
        .collect();
    format!("<ol class=\"steps\">{steps}</ol>")
}

fn reference(r: &Reference) -> String {
    let mut s = format!(
        "<span class=\"ref-authors\">{}</span> — <cite>{}</cite>. {}",
        r.authors, r.title, r.venue
    );
    if let Some(year) = r.year {
        s.push_str(&format!(", {year}"));
    }
    if let Some(detail) = &r.detail {
        s.push_str(&format!(". {detail}"));
    }
    s.push('.');
    if let Some(link) = r.link() {
        // Validated by `Content::validate` (an http(s) URL or a DOI); escaped all the same.
        let shown = match &r.doi {
            Some(doi) => format!("doi:{doi}"),
            None => link.clone(),
        };
        s.push_str(&format!(
            " <a class=\"ref-link\" href=\"{}\" rel=\"noopener\">{}</a>",
            escape(&link),
            escape(&shown)
        ));
    }
    s
}

#[must_use]
pub fn references(content: &Content) -> String {
    let items: String = content
        .references
        .iter()
        .map(|r| format!("<li>{}</li>", reference(r)))
        .collect();
    format!("<ol class=\"refs\">{items}</ol>")
}

/// Shown in place of a tab whose content file failed to load.
#[must_use]
pub fn content_error(message: &str) -> String {
    format!(
        "<p class=\"sim-error\" role=\"alert\">This experiment's text could not be loaded: {}</p>",
        escape(message)
    )
}

/// The short tab label shown on narrow screens (the full title stays the
/// accessible name).
#[must_use]
pub fn short_title(tab: Tab) -> &'static str {
    match tab {
        Tab::Aim => "Aim",
        Tab::Theory => "Theory",
        Tab::Procedure => "Steps",
        Tab::Simulation => "Sim",
        Tab::Quiz => "Quiz",
        Tab::References => "Refs",
    }
}

/// Placeholder of the Simulation and Self-assessment panels until the wasm
/// front end is ready; `main.js` shows download progress in it.
pub const LOADING: &str = "<div class=\"wasm-wait\"><p>Loading the simulation engine…</p>\
     <progress class=\"wasm-progress\" max=\"100\" aria-label=\"Download progress\"></progress></div>";

/// The whole `<article>` of one experiment: header, the tab row and six
/// panels, all hidden except Aim. `id` is the registry id.
#[must_use]
pub fn article(id: &str, content: Result<&Content, String>) -> String {
    let (number, title, summary) = match &content {
        Ok(c) => (c.number.to_string(), c.title.clone(), c.summary.clone()),
        Err(_) => (String::new(), id.to_owned(), String::new()),
    };
    let mut tabs = String::new();
    let mut panels = String::new();
    for tab in Tab::ALL {
        let slug = tab.slug();
        let selected = tab == Tab::Aim;
        tabs.push_str(&format!(
            "<a role=\"tab\" id=\"tab-{id}-{slug}\" href=\"#/{id}/{slug}\" data-tab=\"{slug}\" \
             aria-controls=\"panel-{id}-{slug}\" aria-selected=\"{selected}\" tabindex=\"{tabindex}\">\
             <span class=\"tab-long\">{long}</span><span class=\"tab-short\" aria-hidden=\"true\">{short}</span></a>",
            long = tab.title(),
            short = short_title(tab),
            tabindex = if selected { 0 } else { -1 },
        ));
        let body = match (&content, tab) {
            (Ok(c), Tab::Aim) => aim(c),
            (Ok(c), Tab::Theory) => theory(c),
            (Ok(c), Tab::Procedure) => procedure(c),
            (Ok(c), Tab::References) => references(c),
            (Ok(_), Tab::Quiz) => format!("<form class=\"quiz\" novalidate>{LOADING}</form>"),
            (_, Tab::Simulation) => LOADING.to_owned(),
            (Err(e), _) => content_error(e),
        };
        panels.push_str(&format!(
            "<section role=\"tabpanel\" id=\"panel-{id}-{slug}\" data-panel=\"{slug}\" \
             aria-labelledby=\"tab-{id}-{slug}\" tabindex=\"0\"{hidden}><h2 class=\"panel-title\">{}</h2>{body}</section>",
            tab.title(),
            hidden = if selected { "" } else { " hidden" },
        ));
    }
    format!(
        "<article class=\"exp\" data-experiment=\"{id}\" data-tab=\"aim\">\
         <header class=\"exp-head\"><p class=\"exp-num\">Experiment {number}</p>\
         <h1 tabindex=\"-1\">{title}</h1><p class=\"exp-summary\">{summary}</p></header>\
         <nav role=\"tablist\" class=\"tabs\" aria-label=\"Sections of this experiment\">{tabs}</nav>\
         {panels}</article>",
        title = escape(&title),
        summary = escape(&summary),
    )
}

/// A built experiment's number, title and summary, or the catalogue's title
/// for one not built yet (`None` summary).
fn describe(id: &str) -> (u32, String, Option<String>) {
    let plan = crate::catalogue::planned(id);
    let number = plan.map_or(0, |p| p.number);
    match crate::find(id).map(|e| e.content()) {
        Some(Ok(c)) => (c.number, c.title.clone(), Some(c.summary.clone())),
        Some(Err(e)) => (number, id.to_owned(), Some(e.to_string())),
        None => (number, plan.map_or(id, |p| p.title).to_owned(), None),
    }
}

/// The grouped experiment menu: a `<details>` disclosure holding one list per
/// group, so any experiment is two clicks away (open, choose) at every width
/// and without JavaScript. Experiments not built yet are listed, not linked.
#[must_use]
pub fn nav() -> String {
    let mut groups = String::new();
    for group in Group::ALL {
        let mut items = String::new();
        for plan in CATALOGUE.iter().filter(|p| p.group == group) {
            let (number, title, built) = describe(plan.id);
            items.push_str(&if built.is_some() {
                format!(
                    "<li><a href=\"#/{id}/aim\" data-experiment=\"{id}\"><span class=\"num\">{number}</span>\
                     <span class=\"nav-title\">{title}</span></a></li>",
                    id = plan.id,
                    title = escape(&title),
                )
            } else {
                format!(
                    "<li><span class=\"soon\" aria-disabled=\"true\"><span class=\"num\">{number}</span>\
                     <span class=\"nav-title\">{title}</span> <span class=\"soon-tag\">coming soon</span></span></li>",
                    title = escape(&title),
                )
            });
        }
        groups.push_str(&format!(
            "<section class=\"nav-group\" aria-labelledby=\"nav-{key}\"><h2 id=\"nav-{key}\">{title}</h2><ul>{items}</ul></section>",
            key = group.key(),
            title = group.title(),
        ));
    }
    format!(
        "<details class=\"nav-menu\"><summary><span class=\"nav-burger\" aria-hidden=\"true\">☰</span> \
         Experiments<span class=\"nav-current\"></span></summary><div class=\"nav-panel\">{groups}</div></details>"
    )
}

/// The home page: a lede, then one section of cards per group. `thumbnail`
/// gives each built experiment's picture (inline SVG), or an empty string.
#[must_use]
pub fn home(thumbnail: impl Fn(&str) -> String) -> String {
    let mut sections = String::new();
    for group in Group::ALL {
        let mut cards = String::new();
        for plan in CATALOGUE.iter().filter(|p| p.group == group) {
            let (number, title, summary) = describe(plan.id);
            let title = escape(&title);
            cards.push_str(&match summary {
                Some(summary) => format!(
                    "<li><a class=\"card\" href=\"#/{id}/aim\" data-experiment=\"{id}\">\
                     <span class=\"card-pic\" aria-hidden=\"true\">{pic}</span>\
                     <span class=\"card-num\">Experiment {number}</span>\
                     <span class=\"card-title\">{title}</span>\
                     <span class=\"card-summary\">{summary}</span></a></li>",
                    id = plan.id,
                    pic = thumbnail(plan.id),
                    summary = escape(&summary),
                ),
                None => format!(
                    "<li><div class=\"card card-soon\"><span class=\"card-num\">Experiment {number}</span>\
                     <span class=\"card-title\">{title}</span>\
                     <span class=\"card-summary\">Coming soon.</span></div></li>"
                ),
            });
        }
        sections.push_str(&format!(
            "<section class=\"group\" aria-labelledby=\"group-{key}\"><h2 id=\"group-{key}\">{title}</h2>\
             <ul class=\"cards\">{cards}</ul></section>",
            key = group.key(),
            title = group.title(),
        ));
    }
    format!(
        "<section class=\"home\" data-page=\"home\"><h1>Robot kinematics, planning and control</h1>\
         <p class=\"lede\">Each experiment pairs the theory with a live simulation you can touch: \
         drag the arm, change a parameter, watch the numbers respond. Every experiment has an aim, \
         the theory with its formulas, a step-by-step procedure, a graded self-assessment and references.</p>\
         {sections}</section>"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escape_covers_html_specials() {
        assert_eq!(
            escape("<a href=\"x\">&'"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&#39;"
        );
    }

    #[test]
    fn nav_lists_all_eleven_in_groups_and_links_the_built_ones() {
        let html = nav();
        for plan in &CATALOGUE {
            assert!(html.contains(&format!("<span class=\"num\">{}</span>", plan.number)));
        }
        for entry in crate::registry() {
            assert!(
                html.contains(&format!("href=\"#/{}/aim\"", entry.id)),
                "{}",
                entry.id
            );
        }
        assert_eq!(
            html.matches("class=\"nav-group\"").count(),
            Group::ALL.len()
        );
    }

    #[test]
    fn article_has_six_tabs_and_only_aim_visible() {
        let entry = crate::find("fk").expect("fk");
        let html = article("fk", entry.content().map_err(|e| e.to_string()));
        assert_eq!(html.matches("role=\"tab\"").count(), 6);
        assert_eq!(html.matches("role=\"tabpanel\"").count(), 6);
        assert_eq!(html.matches(" hidden>").count(), 5);
        assert!(html.contains("id=\"panel-fk-theory\""));
    }

    #[test]
    fn home_has_a_section_per_group() {
        let html = home(|_| String::new());
        assert_eq!(html.matches("class=\"group\"").count(), Group::ALL.len());
        let cards = html.matches("class=\"card\"").count()
            + html.matches("class=\"card card-soon\"").count();
        assert_eq!(cards, CATALOGUE.len());
    }
}
