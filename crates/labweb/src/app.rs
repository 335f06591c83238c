//! Routing and pages: the home page and the six-tab experiment page.
//!
//! `cargo xtask dist` puts the navigation and the home page into
//! `index.html` and each experiment's article (reading tabs filled in) into a
//! reading page of its own; `main.js` fetches and shows the one the link
//! names, then starts the wasm module of that experiment's group. Once a
//! module runs, this module owns routing within it: it shows the page the
//! hash names, mounts the simulation and the quiz into their panels, and
//! keeps the link complete; a link to an experiment of another group is left
//! to `main.js`, which starts that group's module. Articles missing from the
//! document (test pages, a link followed before its reading page arrived) are
//! rendered from the same [`labpage::content_html`] functions.

use crate::dom::{self, escape, query, query_all, Listener};
use crate::quiz_view::{self, Attempt};
use crate::sim::{self, SimView};
use labcore::content::Content;
use labcore::route::{self, Page, Tab};
use labcore::Entry;
use labpage::content_html;
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::JsCast;
use web_sys::{Element, Event, HtmlCanvasElement, HtmlElement, KeyboardEvent};

/// The whole application: one mounted page and the history listeners.
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
    /// Fills in the navigation if the page has none and routes to the current
    /// hash. Returns `None` when the page has no `#app` element.
    pub fn boot(on_hash_change: impl FnMut(Event) + 'static + Clone) -> Option<Self> {
        let root = dom::by_id("app")?;
        // The site's pages are built with their menu; a test page (every
        // experiment's reading content built in) gets it here. A shipped
        // module carries no menu, as it carries no reading content.
        #[cfg(feature = "reading")]
        if let Some(nav) = dom::by_id("lab-nav") {
            if query(&nav, "details").is_none() {
                nav.set_inner_html(&content_html::nav());
            }
        }
        if let Some(loading) = query(&root, ":scope > .loading") {
            loading.remove();
        }
        // `hashchange` for links and typed hashes; `popstate` for Back and
        // Forward (routing twice to the same hash changes nothing).
        let listeners = vec![
            Listener::new(dom::window().as_ref(), "hashchange", on_hash_change.clone()),
            Listener::new(dom::window().as_ref(), "popstate", on_hash_change),
        ];
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
        // Every experiment of the lab is a page, also those whose code is in
        // another module: `main.js` hands those over to their module.
        let ids: Vec<&str> = labcore::catalogue::CATALOGUE.iter().map(|p| p.id).collect();
        let mut parsed = route::parse(&hash, &ids);
        // Bare: no parameters and no seed (the menu's `#/pid/aim`, a tab).
        let bare = matches!(&parsed.page, Page::Experiment { params, .. } if params.is_empty())
            && parsed.quiz_seed.is_none();
        let mut class_seed = parsed.quiz_seed;
        // An instructor's link holds for the visit: kept for its experiment
        // until another one or "Leave the instructor's settings", and given
        // to the links that set none (see `route::Route::keep_instructor`).
        if let Page::Experiment { id, .. } = &parsed.page {
            let fresh = !matches!(&self.page, Some(Mounted::Experiment(p)) if p.id == *id);
            let key = instructor_key(id);
            if parsed.carries_instructor() {
                if let Some(s) = session() {
                    let _ = s.set_item(&key, &hash);
                }
            } else if let Some(kept) = session().and_then(|s| s.get_item(&key).ok().flatten()) {
                class_seed = parsed.keep_instructor(&kept, fresh).unwrap_or(class_seed);
            }
        }
        let quiz_seed = parsed.quiz_seed;
        let instructor = parsed.instructor;
        // A hidden value typed plainly (`m=2.5&hide=m`) leaves the address bar.
        let hides = !instructor.hidden.is_empty();
        let quiz_rules = instructor.quiz;
        let mut notices = parsed.notices;
        close_nav_menu();
        match parsed.page {
            Page::Home => {
                if !matches!(self.page, Some(Mounted::Home)) {
                    self.page = None;
                    show_home(&self.root);
                    self.page = Some(Mounted::Home);
                }
                mark_nav(None);
                if !notices.is_empty() {
                    replace_hash("#/");
                }
            }
            Page::Experiment { id, tab, params } => {
                let same = matches!(&self.page, Some(Mounted::Experiment(p)) if p.id == id);
                if !same {
                    self.page = None;
                    // Not in this module: `main.js` shows its reading page and
                    // starts its module, which routes from here.
                    let Some(entry) = labcore::find(&id) else {
                        mark_nav(Some(&id));
                        return;
                    };
                    // The built site brings each article as a reading page of
                    // its own: until `main.js` has added it (and calls
                    // `reroute`), there is nothing to mount into.
                    if hosts_reading_pages() && !has_article(&self.root, &id) {
                        mark_nav(Some(&id));
                        return;
                    }
                    self.page = Some(Mounted::Experiment(ExperimentPage::mount(
                        &self.root, entry,
                    )));
                }
                if let Some(Mounted::Experiment(page)) = &mut self.page {
                    // A link with parameters describes a whole state: in a tab
                    // that already shows this experiment, start again from the
                    // constructor so nothing the link leaves out is kept. The
                    // link of exactly the state shown (Back to it, or the link
                    // the page itself just wrote: a tab link is routed twice,
                    // on `popstate` and on `hashchange`, and the first writes
                    // the whole link) changes nothing: applying it again would
                    // restart a run under a running clock (a parameter set
                    // restarts PID's step response).
                    let shown = same && page.shows(&hash);
                    let new_state = !params.is_empty() && !shown;
                    if same && new_state {
                        page.rebuild_sim();
                    }
                    if new_state {
                        notices.extend(page.apply_params(&params));
                    }
                    // An instructor's locks, hidden controls and note come
                    // with a whole state (or alone); a bare link (a tab
                    // switch) keeps those already set. A quiz seed alone on
                    // another tab than the Self-assessment (whose own link
                    // carries the student's seed) is an instructor's class
                    // seed: it keeps them too, and reaches the Simulation
                    // tab's link and the lab report's answer-key default.
                    // The Self-assessment tab's own link carries the grading
                    // rules and the student's seed, nothing else: routed again
                    // (Back, or a tab link's second routing) it keeps the
                    // instructor's locks, note and report choice.
                    let quiz_tab_link = params.is_empty()
                        && tab == Tab::Quiz
                        && !instructor.is_empty()
                        && instructor.holds_only_quiz_rules();
                    if quiz_tab_link {
                        page.set_quiz_rules(quiz_rules);
                    } else if new_state || (params.is_empty() && !instructor.is_empty()) {
                        notices.extend(page.set_instructor(instructor, class_seed));
                        page.set_quiz_rules(quiz_rules);
                    } else if params.is_empty() && class_seed.is_some() && tab != Tab::Quiz {
                        page.set_quiz_seed(class_seed);
                    }
                    // An instructor's link fixes the attempt (`?quiz=123`): the
                    // whole class gets the same numbers. Not inside a SCO: the
                    // attempt the LMS keeps is never replaced by a link's.
                    if let Some(seed) = quiz_seed.filter(|_| !crate::lms::in_sco()) {
                        let mut p = page.inner.borrow_mut();
                        if p.attempt.as_ref().map(|a| a.seed) != Some(seed) {
                            p.new_attempt(seed);
                        }
                    }
                    let tab_changed = page.inner.borrow().tab != tab;
                    page.select(tab, !same || tab_changed);
                    // Keep the link complete: after a clamp, and when a link
                    // without parameters lands on the simulation; veiled.
                    if hides
                        || !notices.is_empty()
                        || (bare && matches!(tab, Tab::Simulation | Tab::Quiz))
                    {
                        page.write_hash();
                    }
                }
                mark_nav(Some(&id));
            }
        }
        if notices.is_empty() {
            dom::clear_notice();
        } else {
            dom::notice(&route::summarize_notices(&notices, route::NOTICE_LIMIT));
        }
    }

    /// Calls `f` with the mounted simulation (tests compare its model with
    /// a run of their own); `None` when no simulation is mounted.
    #[doc(hidden)]
    pub fn with_sim<R>(&self, f: impl FnOnce(&SimView) -> R) -> Option<R> {
        match &self.page {
            Some(Mounted::Experiment(page)) => page.inner.borrow().sim.as_ref().map(f),
            _ => None,
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

/// The tab's session storage: an instructor's link is kept there for the
/// visit (the tab's life, reloads included; not another tab or browser).
fn session() -> Option<web_sys::Storage> {
    dom::window().session_storage().ok().flatten()
}

/// Where the instructor's link of experiment `id` is kept.
fn instructor_key(id: &str) -> String {
    format!("labinstructor:{id}")
}

fn replace_hash(hash: &str) {
    if let Ok(history) = dom::window().history() {
        let _ = history.replace_state_with_url(&wasm_bindgen::JsValue::NULL, "", Some(hash));
    }
}

/// A new history entry (a page or tab change), so Back returns to it.
fn push_hash(hash: &str) {
    if let Ok(history) = dom::window().history() {
        let _ = history.push_state_with_url(&wasm_bindgen::JsValue::NULL, "", Some(hash));
    }
}

fn close_nav_menu() {
    if let Some(menu) = dom::by_id("lab-nav").and_then(|n| query(&n, "details[open]")) {
        let _ = menu.remove_attribute("open");
    }
}

fn mark_nav(current: Option<&str>) {
    let Some(nav) = dom::by_id("lab-nav") else {
        return;
    };
    let mut label = String::new();
    for a in query_all(&nav, "a[data-experiment]") {
        if current.is_some() && a.get_attribute("data-experiment").as_deref() == current {
            let _ = a.set_attribute("aria-current", "page");
            if let Some(num) = query(&a, ".num") {
                label = format!("Experiment {}", num.text_content().unwrap_or_default());
            }
        } else {
            let _ = a.remove_attribute("aria-current");
        }
    }
    if let Some(span) = query(&nav, ".nav-current") {
        span.set_text_content(Some(&if label.is_empty() {
            String::new()
        } else {
            format!(" · {label}")
        }));
    }
}

/// Shows the home page (once `main.js` has added it) and hides every
/// experiment article.
fn show_home(root: &Element) {
    dom::show_article(None, "");
    // The home page is a reading page of its own: `main.js` fetches it and
    // adds it (a module holds only its group's content, too little for it).
    let Some(home) = query(root, "[data-page=home]") else {
        return;
    };
    // Cards without a picture get one painted from the experiment's preview
    // state, one task per picture (each preview computes a little).
    for pic in query_all(&home, ".card-pic:empty") {
        let Some(id) = pic
            .closest("[data-experiment]")
            .ok()
            .flatten()
            .and_then(|c| c.get_attribute("data-experiment"))
        else {
            continue;
        };
        let Some(entry) = labcore::find(&id) else {
            continue;
        };
        let Ok(canvas) = dom::document()
            .create_element("canvas")
            .and_then(|c| c.dyn_into::<HtmlCanvasElement>().map_err(Into::into))
        else {
            continue;
        };
        let _ = pic.append_child(&canvas);
        dom::defer(move || {
            if canvas.is_connected() {
                let mut exp = (entry.make)();
                exp.preview();
                sim::paint_thumbnail(&canvas, exp.as_ref());
            }
        });
    }
    dom::next_frame(|| dom::window().scroll_to_with_x_and_y(0.0, 0.0));
}

/// Builds the experiment fresh from its registry constructor and mounts its
/// Simulation tab into the article (its failure must not take the reading
/// tabs down).
fn mount_sim(root: &Element, entry: &'static Entry) -> Option<SimView> {
    let panel = query(root, "[data-panel=simulation]")?;
    let exp = (entry.make)();
    let caption = escape(exp.hint());
    let title = query(&panel, ".panel-title").map_or(String::new(), |h| h.outer_html());
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
    /// The instructor's attempts limit and score rule, and what is graded.
    grading: quiz_view::Grading,
}

struct ExperimentPage {
    id: &'static str,
    inner: Rc<RefCell<PageInner>>,
    _listeners: Vec<Listener>,
}

fn random_seed() -> u64 {
    (js_sys::Math::random() * 1e9).floor() as u64
}

/// Whether `main.js` brings the reading pages (`<meta name="lab-page">` in
/// the built site); test pages have none and get articles rendered here.
fn hosts_reading_pages() -> bool {
    dom::document()
        .query_selector("meta[name=lab-page]")
        .ok()
        .flatten()
        .is_some()
}

fn has_article(root: &Element, id: &str) -> bool {
    query(root, &format!("article.exp[data-experiment=\"{id}\"]")).is_some()
}

/// The experiment's article: the one `main.js` added, or (test pages, built
/// with every experiment's full content) one rendered here. A shipped module
/// carries no reading content and never renders one: it waits for `main.js`.
fn find_or_render_article(app_root: &Element, entry: &'static Entry) -> Element {
    let selector = format!("article.exp[data-experiment=\"{}\"]", entry.id);
    if let Some(article) = query(app_root, &selector) {
        return article;
    }
    #[cfg(feature = "reading")]
    {
        let html = content_html::article(entry.id, entry.content().map_err(|e| e.to_string()));
        let _ = app_root.insert_adjacent_html("beforeend", &html);
    }
    query(app_root, &selector).unwrap_or_else(|| app_root.clone())
}

impl ExperimentPage {
    fn mount(app_root: &Element, entry: &'static Entry) -> Self {
        let content = entry.content();
        let root = find_or_render_article(app_root, entry);
        // Shown on the tab it shows already (main.js showed the link's tab
        // before the module ran); `select` then shows the routed one.
        let shown_tab = root.get_attribute("data-tab").unwrap_or_default();
        dom::show_article(Some(&root), &shown_tab);

        let sim = mount_sim(&root, entry);

        let inner = Rc::new(RefCell::new(PageInner {
            id: entry.id,
            entry,
            root: root.clone(),
            tab: Tab::Aim,
            sim,
            content: content.ok(),
            attempt: None,
            grading: quiz_view::Grading::load(entry.id, route::QuizRules::default()),
        }));
        // The attempt in progress before a reload, else a fresh one.
        let seed = quiz_view::load_saved(entry.id).map_or_else(random_seed, |saved| saved.seed);
        inner.borrow_mut().new_attempt(seed);

        let mut listeners = Vec::new();
        if let Some(tablist) = query(&root, "[role=tablist]") {
            // Tabs are links (they work before the wasm); arrow keys move
            // between them as in any tab list.
            let page = inner.clone();
            listeners.push(Listener::new(
                tablist.as_ref(),
                "keydown",
                move |e: Event| {
                    let Some(e) = e.dyn_ref::<KeyboardEvent>() else {
                        return;
                    };
                    let p = page.borrow();
                    let i = Tab::ALL.iter().position(|t| *t == p.tab).unwrap_or(0);
                    let n = Tab::ALL.len();
                    let next = match e.key().as_str() {
                        "ArrowRight" => (i + 1) % n,
                        "ArrowLeft" => (i + n - 1) % n,
                        "Home" => 0,
                        "End" => n - 1,
                        " " => i,
                        _ => return,
                    };
                    e.prevent_default();
                    let hash = format!("#/{}/{}", p.id, Tab::ALL[next].slug());
                    let tab_el = query(
                        &p.root,
                        &format!("[role=tab][data-tab={}]", Tab::ALL[next].slug()),
                    );
                    p.flush_link();
                    drop(p);
                    push_hash(&hash);
                    crate::reroute();
                    if let Some(h) = tab_el.as_ref().and_then(|t| t.dyn_ref::<HtmlElement>()) {
                        let _ = h.focus();
                    }
                },
            ));
        }
        // Leaving the Simulation tab by a link (a tab, a preset): the link
        // of the state shown is written first (it is paced while a run
        // goes), so Back returns to this state, not one up to 250 ms old.
        let page = inner.clone();
        listeners.push(Listener::new(root.as_ref(), "click", move |e: Event| {
            let Some(el) = e.target().and_then(|t| t.dyn_into::<Element>().ok()) else {
                return;
            };
            if el.closest("a[href^=\"#\"]").ok().flatten().is_some() {
                page.borrow().flush_link();
            }
            // "Leave the instructor's settings": forgotten for the visit,
            // and the experiment opens at its defaults (a link of its own,
            // so Back returns to the instructor's).
            if el
                .closest("[data-instructor-leave]")
                .ok()
                .flatten()
                .is_some()
            {
                let p = page.borrow();
                if let Some(s) = session() {
                    let _ = s.remove_item(&instructor_key(p.id));
                }
                // The focus goes to the Simulation tab (the button is hidden).
                if let Some(tab) = query(&p.root, "[role=tab][data-tab=simulation]") {
                    let _ = tab.unchecked_ref::<HtmlElement>().focus();
                }
                let hash = route::format((p.entry.make)().as_ref(), Tab::Simulation);
                // Routed at once (the page is not borrowed meanwhile).
                drop(p);
                let _ = dom::window().location().set_hash(&hash);
            }
        }));
        if let Some(quiz_panel) = query(&root, "[data-panel=quiz]") {
            let page = inner.clone();
            listeners.push(Listener::new(
                quiz_panel.as_ref(),
                "submit",
                move |e: Event| {
                    e.prevent_default();
                    let p = &mut *page.borrow_mut();
                    p.grading.hide_key = p.key_hidden();
                    if let (Some(form), Some(attempt)) = (query(&p.root, "form.quiz"), &p.attempt) {
                        // Asks for confirmation first when questions are unanswered.
                        let quiz = p.content.map_or(&[][..], |c| &c.quiz);
                        quiz_view::submit(&form, attempt, &mut p.grading, quiz);
                    }
                },
            ));
            // Keep the attempt's seed and answers across a reload.
            let page = inner.clone();
            listeners.push(Listener::new(quiz_panel.as_ref(), "input", move |_| {
                let p = page.borrow();
                if let (Some(form), Some(attempt)) = (query(&p.root, "form.quiz"), &p.attempt) {
                    quiz_view::store(p.id, &form, attempt, p.grading.tally);
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
                        p.write_hash();
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

    fn set_instructor(
        &mut self,
        instructor: route::Instructor,
        quiz_seed: Option<u64>,
    ) -> Vec<String> {
        match &self.inner.borrow().sim {
            Some(sim) => sim.set_instructor(instructor, quiz_seed),
            None => Vec::new(),
        }
    }

    /// The link's attempts limit and score rule for the quiz (a SCORM
    /// launch's rules stay); other rules start their own count outside an
    /// LMS.
    fn set_quiz_rules(&mut self, rules: route::QuizRules) {
        let mut p = self.inner.borrow_mut();
        if p.grading.rules != rules {
            p.grading = quiz_view::Grading::load(p.id, rules);
        }
    }

    fn set_quiz_seed(&mut self, quiz_seed: Option<u64>) {
        if let Some(sim) = &self.inner.borrow().sim {
            sim.set_quiz_seed(quiz_seed);
        }
    }

    /// Whether `hash` is the link of the state the simulation shows now.
    fn shows(&self, hash: &str) -> bool {
        let p = self.inner.borrow();
        p.sim.as_ref().is_some_and(|sim| {
            let now = sim.hash(Tab::Simulation);
            now == hash
                || now.split_once('?').map(|(_, q)| q) == hash.split_once('?').map(|(_, q)| q)
        })
    }

    /// Drops the simulation and builds it again from the experiment's
    /// constructor (fresh clock and speed too); the link is applied after.
    fn rebuild_sim(&mut self) {
        let mut p = self.inner.borrow_mut();
        p.sim = None;
        let sim = mount_sim(&p.root, p.entry);
        p.sim = sim;
        // `select` starts the frame loop again for the shown tab.
        let tab = p.tab;
        p.select(tab, false);
    }

    fn select(&mut self, tab: Tab, scroll_top: bool) {
        let mut p = self.inner.borrow_mut();
        p.select(tab, scroll_top);
    }

    fn write_hash(&self) {
        self.inner.borrow().write_hash();
    }
}

impl Drop for ExperimentPage {
    /// Leaving an experiment stops its simulation (listeners, frame loop,
    /// observers) and puts the placeholders back, so no dead canvas or stale
    /// quiz stays in the hidden article.
    fn drop(&mut self) {
        let mut p = self.inner.borrow_mut();
        p.sim = None;
        p.attempt = None;
        if let Some(panel) = query(&p.root, "[data-panel=simulation]") {
            let title = query(&panel, ".panel-title").map_or(String::new(), |h| h.outer_html());
            panel.set_inner_html(&format!("{title}{}", content_html::LOADING));
        }
        if let Some(form) = query(&p.root, "form.quiz") {
            form.set_inner_html(content_html::LOADING);
        }
    }
}

impl PageInner {
    fn select(&mut self, tab: Tab, scroll_top: bool) {
        self.tab = tab;
        dom::show_article(Some(&self.root), tab.slug());
        if let Some(sim) = &mut self.sim {
            sim.set_active(tab == Tab::Simulation);
        }
        if scroll_top {
            dom::next_frame(|| dom::window().scroll_to_with_x_and_y(0.0, 0.0));
        }
    }

    fn write_hash(&self) {
        let hash = match (&self.sim, self.tab) {
            // The Self-assessment link names its attempt, so it can be
            // shared, after the instructor's grading rules (kept on reload).
            (_, Tab::Quiz) => {
                let rules = route::Instructor {
                    quiz: self.grading.rules,
                    ..route::Instructor::default()
                };
                let mut pairs = rules.query();
                pairs.extend(
                    self.attempt
                        .as_ref()
                        .map(|a| format!("{}={}", route::QUIZ_KEY, a.seed)),
                );
                route::with_query(format!("#/{}/quiz", self.id), &pairs)
            }
            (Some(sim), tab) => sim.hash(tab),
            (None, tab) => format!("#/{}/{}", self.id, tab.slug()),
        };
        replace_hash(&hash);
    }

    /// On the Simulation tab, writes its link now if it is behind the state.
    fn flush_link(&self) {
        if let (Tab::Simulation, Some(sim)) = (self.tab, &self.sim) {
            sim.flush_link();
        }
    }

    /// Whether the answer key in force for this page is `never` (one rule
    /// for the Self-assessment tab and the lab report).
    fn key_hidden(&self) -> bool {
        let hash = self.sim.as_ref().map(|s| s.hash(Tab::Simulation));
        crate::lms::answer_key(&hash.unwrap_or_default()) == route::AnswerKey::Never
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
                // A new attempt is not graded yet (a kept one is marked
                // again by `restore`), so the LMS does not keep it as graded.
                let _ = form.remove_attribute(crate::lms::SUBMITTED_ATTR);
                // Answers typed before a reload come back (same seed only).
                self.grading.hide_key = self.key_hidden();
                if let Some(saved) = quiz_view::load_saved(self.id) {
                    quiz_view::restore(&form, &attempt, &saved, &mut self.grading);
                }
                // An LMS's review launch shows the kept attempt read-only.
                if crate::lms::review() {
                    for control in query_all(&form, "input, button") {
                        let _ = control.set_attribute("disabled", "");
                    }
                }
                quiz_view::store(self.id, &form, &attempt, self.grading.tally);
                self.attempt = Some(attempt);
            }
            Err(e) => form.set_inner_html(&content_html::content_error(&e.to_string())),
        }
    }
}
