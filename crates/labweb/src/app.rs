//! Routing and pages: the home page and the six-tab experiment page.

use crate::content_view;
use crate::dom::{self, escape, query, query_all, Listener};
use crate::quiz_view::{self, Attempt};
use crate::sim::{self, SimView};
use labcore::content::Content;
use labcore::route::{self, Page, Tab};
use labcore::{registry, Entry};
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::JsCast;
use web_sys::{Element, Event, HtmlCanvasElement, HtmlElement, KeyboardEvent};

/// The whole application: one mounted page and the hash listener.
pub struct App {
    root: Element,
    page: Option<Mounted>,
    _listeners: Vec<Listener>,
}

enum Mounted {
    Home,
    Experiment(ExperimentPage),
}

impl App {
    /// Builds the navigation and routes to the current hash. Returns `None`
    /// when the page has no `#app` element.
    pub fn boot(on_hash_change: impl FnMut(Event) + 'static) -> Option<Self> {
        let root = dom::by_id("app")?;
        // The nav needs every experiment's title (parsing all content files):
        // a task of its own keeps the first page's task short.
        dom::defer(render_nav);
        let listeners = vec![Listener::new(
            dom::window().as_ref(),
            "hashchange",
            on_hash_change,
        )];
        let mut app = Self {
            root,
            page: None,
            _listeners: listeners,
        };
        app.route();
        if let Some(body) = dom::document().body() {
            let _ = body.set_attribute("data-ready", "1");
        }
        Some(app)
    }

    /// Shows the page the location hash names.
    pub fn route(&mut self) {
        let hash = dom::window().location().hash().unwrap_or_default();
        let ids: Vec<&str> = registry().iter().map(|e| e.id).collect();
        let parsed = route::parse(&hash, &ids);
        let mut notices = parsed.notices;
        match parsed.page {
            Page::Home => {
                if !matches!(self.page, Some(Mounted::Home)) {
                    self.page = None;
                    render_home(&self.root);
                    self.page = Some(Mounted::Home);
                }
                mark_nav(None);
                dom::document().set_title("Robotics virtual lab");
                if !notices.is_empty() {
                    replace_hash("#/");
                }
            }
            Page::Experiment { id, tab, params } => {
                let same = matches!(&self.page, Some(Mounted::Experiment(p)) if p.id == id);
                if !same {
                    self.page = None;
                    let Some(entry) = labcore::find(&id) else {
                        return;
                    };
                    self.page = Some(Mounted::Experiment(ExperimentPage::mount(
                        &self.root, entry,
                    )));
                }
                if let Some(Mounted::Experiment(page)) = &mut self.page {
                    if !params.is_empty() {
                        notices.extend(page.apply_params(&params));
                    }
                    page.select(tab, !same);
                    // Keep the link complete: after a clamp, and when a nav link
                    // (no parameters) lands on the experiment already open.
                    if !notices.is_empty() || (same && params.is_empty()) {
                        page.write_hash();
                    }
                }
                mark_nav(Some(&id));
            }
        }
        if notices.is_empty() {
            dom::clear_notice();
        } else {
            dom::notice(&notices);
        }
    }

    /// Paints the mounted simulation now (tests).
    pub fn paint_now(&self) {
        if let Some(Mounted::Experiment(page)) = &self.page {
            if let Some(sim) = &page.inner.borrow().sim {
                sim.paint_now();
            }
        }
    }
}

fn replace_hash(hash: &str) {
    if let Ok(history) = dom::window().history() {
        let _ = history.replace_state_with_url(&wasm_bindgen::JsValue::NULL, "", Some(hash));
    }
}

fn render_nav() {
    let Some(nav) = dom::by_id("lab-nav") else {
        return;
    };
    let mut html = String::from("<ul>");
    for entry in registry() {
        let (number, title) = match entry.content() {
            Ok(c) => (c.number.to_string(), c.title.clone()),
            Err(_) => ("?".into(), entry.id.to_owned()),
        };
        html.push_str(&format!(
            "<li><a href=\"#/{id}/aim\" data-experiment=\"{id}\"><span class=\"num\">{number}</span> {}</a></li>",
            escape(&title),
            id = entry.id
        ));
    }
    html.push_str("</ul>");
    nav.set_inner_html(&html);
    let ids: Vec<&str> = registry().iter().map(|e| e.id).collect();
    let hash = dom::window().location().hash().unwrap_or_default();
    if let Page::Experiment { id, .. } = route::parse(&hash, &ids).page {
        mark_nav(Some(&id));
    }
}

fn mark_nav(current: Option<&str>) {
    let Some(nav) = dom::by_id("lab-nav") else {
        return;
    };
    for a in query_all(&nav, "a[data-experiment]") {
        if current.is_some() && a.get_attribute("data-experiment").as_deref() == current {
            let _ = a.set_attribute("aria-current", "page");
            // The nav scrolls sideways on narrow screens: keep the current one
            // visible (at the next frame, when layout is done anyway).
            dom::next_frame(move || {
                if a.is_connected() {
                    let options = web_sys::ScrollIntoViewOptions::new();
                    options.set_block(web_sys::ScrollLogicalPosition::Nearest);
                    options.set_inline(web_sys::ScrollLogicalPosition::Nearest);
                    a.scroll_into_view_with_scroll_into_view_options(&options);
                }
            });
        } else {
            let _ = a.remove_attribute("aria-current");
        }
    }
}

fn render_home(root: &Element) {
    let mut cards = String::new();
    for entry in registry() {
        let (number, title, summary) = match entry.content() {
            Ok(c) => (c.number, c.title.clone(), c.summary.clone()),
            Err(e) => (0, entry.id.to_owned(), e.to_string()),
        };
        cards.push_str(&format!(
            "<li><a class=\"card\" href=\"#/{id}/aim\" data-experiment=\"{id}\">\
             <canvas class=\"card-pic\" aria-hidden=\"true\"></canvas>\
             <span class=\"card-num\">Experiment {number}</span>\
             <span class=\"card-title\">{title}</span>\
             <span class=\"card-summary\">{summary}</span></a></li>",
            id = entry.id,
            title = escape(&title),
            summary = escape(&summary),
        ));
    }
    root.set_inner_html(&format!(
        "<section class=\"home\"><h1>Robot kinematics, planning and control</h1>\
         <p class=\"lede\">Each experiment pairs the theory with a live simulation you can touch: \
         drag the arm, change a parameter, watch the numbers respond. Every experiment has an aim, \
         the theory with its formulas, a step-by-step procedure, a graded self-assessment and references.</p>\
         <ul class=\"cards\">{cards}</ul></section>"
    ));
    // One task per picture: each preview computes a little (a workspace
    // sweep, an IK solve), and together they would make one long task.
    for (canvas, entry) in query_all(root, "canvas.card-pic")
        .into_iter()
        .zip(registry())
    {
        if let Ok(canvas) = canvas.dyn_into::<HtmlCanvasElement>() {
            dom::defer(move || {
                if canvas.is_connected() {
                    let mut exp = (entry.make)();
                    exp.preview();
                    sim::paint_thumbnail(&canvas, exp.as_ref());
                }
            });
        }
    }
    dom::next_frame(|| dom::window().scroll_to_with_x_and_y(0.0, 0.0));
}

/// State of a mounted experiment page shared with its listeners.
struct PageInner {
    id: &'static str,
    entry: &'static Entry,
    root: Element,
    tab: Tab,
    sim: Option<SimView>,
    content: Option<&'static Content>,
    attempt: Option<Attempt>,
}

struct ExperimentPage {
    id: &'static str,
    inner: Rc<RefCell<PageInner>>,
    _listeners: Vec<Listener>,
}

fn random_seed() -> u64 {
    (js_sys::Math::random() * 1e9).floor() as u64
}

impl ExperimentPage {
    fn mount(app_root: &Element, entry: &'static Entry) -> Self {
        let content = entry.content();
        let (number, title, summary) = match &content {
            Ok(c) => (c.number.to_string(), c.title.clone(), c.summary.clone()),
            Err(_) => (String::new(), entry.id.to_owned(), String::new()),
        };
        let mut tabs = String::new();
        let mut panels = String::new();
        for tab in Tab::ALL {
            let slug = tab.slug();
            tabs.push_str(&format!(
                "<button type=\"button\" role=\"tab\" id=\"tab-{slug}\" data-tab=\"{slug}\" \
                 aria-controls=\"panel-{slug}\" aria-selected=\"false\" tabindex=\"-1\">{}</button>",
                tab.title()
            ));
            let body = match (&content, tab) {
                (Ok(c), Tab::Aim) => content_view::aim(c),
                (Ok(c), Tab::Theory) => content_view::theory(c),
                (Ok(c), Tab::Procedure) => content_view::procedure(c),
                (Ok(c), Tab::References) => content_view::references(c),
                (Ok(_), Tab::Quiz) => "<form class=\"quiz\" novalidate></form>".to_owned(),
                (_, Tab::Simulation) => String::new(),
                (Err(e), _) => content_view::content_error(&e.to_string()),
            };
            panels.push_str(&format!(
                "<section role=\"tabpanel\" id=\"panel-{slug}\" data-panel=\"{slug}\" \
                 aria-labelledby=\"tab-{slug}\" tabindex=\"0\" hidden><h2 class=\"panel-title\">{}</h2>{body}</section>",
                tab.title()
            ));
        }
        app_root.set_inner_html(&format!(
            "<article class=\"exp\" data-experiment=\"{id}\">\
             <header class=\"exp-head\"><p class=\"exp-num\">Experiment {number}</p>\
             <h1 tabindex=\"-1\">{title}</h1><p class=\"exp-summary\">{summary}</p></header>\
             <div role=\"tablist\" class=\"tabs\" aria-label=\"Sections of this experiment\">{tabs}</div>\
             {panels}</article>",
            id = entry.id,
            title = escape(&title),
            summary = escape(&summary),
        ));
        dom::document().set_title(&format!("{title} — Robotics virtual lab"));
        let root = query(app_root, "article.exp").unwrap_or_else(|| app_root.clone());

        // The simulation: its failure must not take the reading tabs down.
        let sim = query(&root, "[data-panel=simulation]").and_then(|panel| {
            let exp = (entry.make)();
            let caption = escape(exp.hint());
            let title = panel.inner_html();
            panel.set_inner_html(&format!("{title}{}", sim::render(exp.as_ref(), &caption)));
            match SimView::mount(&panel, exp) {
                Ok(view) => Some(view),
                Err(e) => {
                    panel.set_inner_html(&format!(
                        "{title}<p class=\"sim-error\" role=\"alert\">The simulation cannot start: {}. \
                         The other tabs still work.</p>",
                        escape(&e.0)
                    ));
                    None
                }
            }
        });

        let inner = Rc::new(RefCell::new(PageInner {
            id: entry.id,
            entry,
            root: root.clone(),
            tab: Tab::Aim,
            sim,
            content: content.ok(),
            attempt: None,
        }));
        // The attempt in progress before a reload, else a fresh one.
        let seed = quiz_view::load_saved(entry.id).map_or_else(random_seed, |saved| saved.seed);
        inner.borrow_mut().new_attempt(seed);

        let mut listeners = Vec::new();
        if let Some(tablist) = query(&root, "[role=tablist]") {
            let page = inner.clone();
            listeners.push(Listener::new(tablist.as_ref(), "click", move |e: Event| {
                let Some(tab) = e
                    .target()
                    .and_then(|t| t.dyn_into::<Element>().ok())
                    .and_then(|el| el.closest("[role=tab]").ok().flatten())
                    .and_then(|el| el.get_attribute("data-tab"))
                    .and_then(|slug| Tab::from_slug(&slug))
                else {
                    return;
                };
                let mut p = page.borrow_mut();
                p.select(tab, false);
                p.write_hash();
            }));
            let page = inner.clone();
            listeners.push(Listener::new(
                tablist.as_ref(),
                "keydown",
                move |e: Event| {
                    let Some(e) = e.dyn_ref::<KeyboardEvent>() else {
                        return;
                    };
                    let mut p = page.borrow_mut();
                    let i = Tab::ALL.iter().position(|t| *t == p.tab).unwrap_or(0);
                    let n = Tab::ALL.len();
                    let next = match e.key().as_str() {
                        "ArrowRight" => (i + 1) % n,
                        "ArrowLeft" => (i + n - 1) % n,
                        "Home" => 0,
                        "End" => n - 1,
                        _ => return,
                    };
                    e.prevent_default();
                    p.select(Tab::ALL[next], false);
                    p.write_hash();
                    if let Some(btn) = query(&p.root, &format!("#tab-{}", Tab::ALL[next].slug())) {
                        if let Some(h) = btn.dyn_ref::<HtmlElement>() {
                            let _ = h.focus();
                        }
                    }
                },
            ));
        }
        if let Some(quiz_panel) = query(&root, "[data-panel=quiz]") {
            let page = inner.clone();
            listeners.push(Listener::new(
                quiz_panel.as_ref(),
                "submit",
                move |e: Event| {
                    e.prevent_default();
                    let p = page.borrow();
                    if let (Some(form), Some(attempt)) = (query(&p.root, "form.quiz"), &p.attempt) {
                        // Asks for confirmation first when questions are unanswered.
                        quiz_view::submit(&form, attempt);
                    }
                },
            ));
            // Keep the attempt's seed and answers across a reload.
            let page = inner.clone();
            listeners.push(Listener::new(quiz_panel.as_ref(), "input", move |_| {
                let p = page.borrow();
                if let (Some(form), Some(attempt)) = (query(&p.root, "form.quiz"), &p.attempt) {
                    quiz_view::store(p.id, &form, attempt);
                }
            }));
            let page = inner.clone();
            listeners.push(Listener::new(
                quiz_panel.as_ref(),
                "click",
                move |e: Event| {
                    let is_new = e
                        .target()
                        .and_then(|t| t.dyn_into::<Element>().ok())
                        .and_then(|el| el.closest("button.quiz-new").ok().flatten())
                        .is_some();
                    if is_new {
                        let mut p = page.borrow_mut();
                        let seed = p.attempt.as_ref().map_or(1, |a| a.seed);
                        // A new seed different from the last one.
                        let mut next = random_seed();
                        if next == seed {
                            next = seed.wrapping_add(1);
                        }
                        p.new_attempt(next);
                        // The button was replaced: focus the top of the new attempt.
                        if let Some(intro) = query(&p.root, ".quiz-intro") {
                            if let Some(h) = intro.dyn_ref::<HtmlElement>() {
                                let _ = h.focus();
                            }
                        }
                    }
                },
            ));
        }
        Self {
            id: entry.id,
            inner,
            _listeners: listeners,
        }
    }

    fn apply_params(&mut self, params: &[(String, String)]) -> Vec<String> {
        match &self.inner.borrow().sim {
            Some(sim) => sim.apply_params(params),
            None => vec!["The simulation is not running, so its settings were ignored.".into()],
        }
    }

    fn select(&mut self, tab: Tab, fresh: bool) {
        let mut p = self.inner.borrow_mut();
        p.select(tab, fresh);
    }

    fn write_hash(&self) {
        self.inner.borrow().write_hash();
    }
}

impl PageInner {
    fn select(&mut self, tab: Tab, scroll_top: bool) {
        self.tab = tab;
        for t in Tab::ALL {
            let on = t == tab;
            if let Some(btn) = query(&self.root, &format!("#tab-{}", t.slug())) {
                let _ = btn.set_attribute("aria-selected", if on { "true" } else { "false" });
                let _ = btn.set_attribute("tabindex", if on { "0" } else { "-1" });
            }
            if let Some(panel) = query(&self.root, &format!("#panel-{}", t.slug())) {
                dom::set_hidden(&panel, !on);
            }
        }
        if let Some(sim) = &mut self.sim {
            sim.set_active(tab == Tab::Simulation);
        }
        if scroll_top {
            dom::next_frame(|| dom::window().scroll_to_with_x_and_y(0.0, 0.0));
        }
    }

    fn write_hash(&self) {
        let hash = match &self.sim {
            Some(sim) => sim.hash(self.tab),
            None => format!("#/{}/{}", self.id, self.tab.slug()),
        };
        replace_hash(&hash);
    }

    fn new_attempt(&mut self, seed: u64) {
        let Some(form) = query(&self.root, "form.quiz") else {
            return;
        };
        let Some(content) = &self.content else { return };
        match labcore::quiz::prepare(content, self.entry.generators, seed) {
            Ok(questions) => {
                let attempt = Attempt { seed, questions };
                form.set_inner_html(&quiz_view::render(&attempt));
                let _ = form.remove_attribute("data-confirm-unanswered");
                // Answers typed before a reload come back (same seed only).
                if let Some(saved) = quiz_view::load_saved(self.id) {
                    quiz_view::restore(&form, &attempt, &saved);
                }
                quiz_view::store(self.id, &form, &attempt);
                self.attempt = Some(attempt);
            }
            Err(e) => form.set_inner_html(&content_view::content_error(&e.to_string())),
        }
    }
}
