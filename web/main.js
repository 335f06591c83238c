// Bootstrap. index.html is the shell; the home page and each experiment's
// reading tabs are small pages of their own (rendered at build time,
// `pages/<id>.<hash>.html`) that these lines fetch and show before any wasm
// arrives. Then they start the
// wasm module that holds the experiment (`pkg/<key>.<hash>.js|wasm`, with
// progress), which owns routing among its experiments; a link to an
// experiment of another module starts that module. Everything else lives in
// Rust.

// did-not-start.js, which runs after this file, looks for it: the page
// says so when a browser did not run this module (a server that sends `.js`
// with another type than JavaScript).
window.labStarted = true;
const app = document.getElementById("app");
const nav = document.getElementById("lab-nav");
const PAGES = new Map([...document.querySelectorAll("meta[name=lab-page]")].map((m) => [m.content, m.dataset.href]));
const MODULES = [...document.querySelectorAll("meta[name=lab-module]")].map((m) => ({
  key: m.content,
  ids: m.dataset.experiments.split(" "),
  js: m.dataset.js,
  wasm: m.dataset.wasm,
  bytes: Number(m.dataset.bytes) || 0,
}));
const moduleOf = (id) => MODULES.find((m) => m.ids.includes(id));
const glues = new Map(); // module key -> Promise of its started glue module
const running = new Set(); // keys of the modules that have started (their glue resolved)
const articles = new Map(); // experiment id -> Promise of its article element
let active = null; // the key of the module that has the app mounted
// Inside an LMS (a frame, or a window opened by the LMS) the SCORM bridge
// must be there before a module starts; elsewhere it is never downloaded.
const framed = (() => {
  try {
    return window.top !== window || Boolean(window.opener);
  } catch {
    return true;
  }
})();
const lms = framed
  ? import(`./scorm.js${new URL(import.meta.url).search}`).catch(() => null)
  : Promise.resolve(null);
let switching = Promise.resolve();
// The site's version this page was loaded with (the `?v=` stamp of main.js).
const siteVersion = new URL(import.meta.url).searchParams.get("v");

const fatal = (message) => {
  const box = document.getElementById("fatal");
  box.querySelector(".fatal-text").textContent = message;
  box.hidden = false;
  for (const wait of document.querySelectorAll(".wasm-wait p")) {
    wait.textContent = "The simulation engine could not start; the reading tabs still work.";
  }
  for (const bar of document.querySelectorAll(".wasm-progress")) bar.remove();
};

// Whether the server holds another version of the lab than this page's: a
// redeploy since the page loaded, whose new files replaced the content-hashed
// ones this page names. Then a missing file is no fault of the lab's: the
// page says the lab was updated and offers a reload.
const redeployed = async () => {
  if (!siteVersion) return false;
  try {
    const r = await fetch(new URL("index.html", import.meta.url), { cache: "no-store" });
    return r.ok && !(await r.text()).includes(`main.js?v=${siteVersion}`);
  } catch {
    return false;
  }
};
const updated = () => {
  const box = document.getElementById("stale");
  box.hidden = false;
  box.querySelector("button").onclick = () => location.reload();
  for (const bar of document.querySelectorAll(".wasm-progress")) bar.remove();
  for (const wait of document.querySelectorAll(".wasm-wait p")) wait.textContent = "The lab was updated: reload the page to start this simulation.";
};

const progress = (fraction) => {
  for (const bar of document.querySelectorAll(".wasm-progress")) {
    bar.value = Math.round(100 * fraction);
    bar.textContent = `${Math.round(100 * fraction)} %`;
  }
};

const hashRoute = () => {
  const match = location.hash.match(/^#\/([^/?]+)(?:\/([^/?]*))?/);
  return match ? { id: decodeURIComponent(match[1]), tab: match[2] } : null;
};

// Downloads a module's wasm with a progress bar, then starts it (its start
// function mounts the app on the current hash).
async function startModule(mod) {
  if (typeof WebAssembly !== "object") {
    throw new Error("this browser does not support WebAssembly; please use a current version of Firefox, Chrome, Edge or Safari");
  }
  const response = await fetch(new URL(mod.wasm, import.meta.url));
  if (!response.ok) throw new Error(`HTTP ${response.status} for the wasm module`);
  let bytes;
  if (response.body && mod.bytes > 0) {
    const reader = response.body.getReader();
    const chunks = [];
    let received = 0;
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      chunks.push(value);
      received += value.length;
      progress(Math.min(1, received / mod.bytes));
    }
    bytes = new Uint8Array(received);
    let at = 0;
    for (const c of chunks) { bytes.set(c, at); at += c.length; }
  } else {
    bytes = new Uint8Array(await response.arrayBuffer());
  }
  progress(1);
  await lms;
  const glue = await import(new URL(mod.js, import.meta.url).href);
  await glue.default({ module_or_path: bytes });
  return glue;
}

// Makes `mod` the module that runs the app: the previous one unmounts, this
// one starts (first time) or mounts again. Calls run one after the other.
function switchTo(mod) {
  switching = switching.then(async () => {
    const wanted = moduleOf(hashRoute()?.id ?? "") ?? mod;
    if (wanted !== mod || active === mod.key) return;
    if (active) (await glues.get(active).catch(() => null))?.unmount();
    active = mod.key;
    const first = !glues.has(mod.key);
    if (first) glues.set(mod.key, startModule(mod));
    let glue;
    try {
      glue = await glues.get(mod.key);
    } catch (error) {
      active = null;
      glues.delete(mod.key);
      if (await redeployed()) return updated();
      fatal(`The simulation engine failed to load (${error.message ?? error}). If you opened the file directly, serve the folder over HTTP instead.`);
      return;
    }
    if (!first) glue.boot();
    running.add(mod.key);
    window.labweb = glue;
  });
  return switching;
}

// The reading page `id` ("home" or an experiment): in the document already,
// or fetched from its file and added (hidden).
const pageSelector = (id) =>
  id === "home" ? "[data-page=home]" : `article.exp[data-experiment="${CSS.escape(id)}"]`;
function ensurePage(id) {
  const present = app.querySelector(pageSelector(id));
  if (present) return Promise.resolve(present);
  if (!PAGES.has(id)) return Promise.reject(new Error(`no page named ${id}`));
  if (!articles.has(id)) {
    const load = fetch(new URL(PAGES.get(id), import.meta.url))
      .then((r) => {
        if (!r.ok) throw new Error(`HTTP ${r.status} for the reading page`);
        return r.text();
      })
      .then((html) => {
        const again = app.querySelector(pageSelector(id));
        if (again) return again;
        const template = document.createElement("template");
        template.innerHTML = html;
        const page = template.content.firstElementChild;
        page.hidden = true;
        if (id === "home") app.prepend(page);
        else app.append(page);
        app.querySelector(":scope > .loading")?.remove();
        return page;
      });
    load.catch(() => articles.delete(id));
    articles.set(id, load);
  }
  return articles.get(id);
}

// labShowArticle: begin
// Shows the home page (`article` null), or `article` on `tab`: the one place
// a page or a tab is shown. Used here before a module runs (and while another
// module hands over), and by the wasm once it runs (labweb's
// `dom::show_article`), so the two cannot drift. Self-contained: the wasm's
// test pages run this very text (between the begin and end lines).
window.labShowArticle = function showArticle(article, tab) {
  const app = document.getElementById("app");
  const home = app.querySelector("[data-page=home]");
  if (home) home.hidden = Boolean(article);
  for (const a of app.querySelectorAll("article.exp")) a.hidden = a !== article;
  for (const a of document.querySelectorAll("#lab-nav a[data-experiment]")) {
    if (article && a.dataset.experiment === article.dataset.experiment) a.setAttribute("aria-current", "page");
    else a.removeAttribute("aria-current");
  }
  if (!article) {
    document.title = "Robotics virtual lab";
    return;
  }
  const tabs = ["aim", "theory", "procedure", "simulation", "quiz", "references"];
  tab = tabs.includes(tab) ? tab : "aim";
  article.dataset.tab = tab;
  for (const t of article.querySelectorAll("[role=tab]")) {
    const on = t.dataset.tab === tab;
    t.setAttribute("aria-selected", String(on));
    t.tabIndex = on ? 0 : -1;
  }
  for (const p of article.querySelectorAll("[role=tabpanel]")) p.hidden = p.dataset.panel !== tab;
  document.title = `${article.querySelector("h1")?.textContent ?? ""} — Robotics virtual lab`;
};
// labShowArticle: end

// labRewriteMarkup: begin
// Writes `html` into `el` as innerHTML would, but keeps the nodes that stay:
// where the new markup has a node of the same name and attributes at the
// same place, the node is kept and its children are compared in turn; a
// text that changed is rewritten in place. "The math" panel writes a running
// simulation's numbers with it (labweb's `dom::rewrite_markup`): only the
// numbers' text is laid out and repainted, not formulas parsed anew.
// Markup with the very tags of the last write, whose texts the parser took
// as they are (checked at that write), needs no parse: its texts go to the
// same text nodes. Self-contained, like labShowArticle (the wasm's test
// pages run this text).
const shapeOf = new WeakMap();
const entities = document.createElement("textarea");
window.labRewriteMarkup = function rewriteMarkup(el, html) {
  // A `\r` or NUL always goes through the parser, which reads `\r` as `\n`
  // and drops NUL; no text written here holds either.
  const parserAlike = !/[\r\0]/.test(html);
  // Plain text into an element that holds one text node (the time bar's
  // time, a readout, the badge: every frame of a scrub): that node's text,
  // without the parse below.
  const only = el.firstChild;
  if (parserAlike && only?.nodeType === Node.TEXT_NODE && !only.nextSibling && !/[<&]/.test(html)) {
    if (only.data !== html) only.data = html;
    return;
  }
  const tags = html.match(/<[^>]*>/g)?.join("") ?? "";
  // The texts between the tags, with their character references decoded.
  const runs = html
    .split(/<[^>]*>/)
    .filter((t) => t)
    .map((t) => (t.includes("&") ? ((entities.innerHTML = t), entities.value) : t));
  const texts = [];
  const textsOf = () => {
    const walk = document.createTreeWalker(el, NodeFilter.SHOW_TEXT);
    while (walk.nextNode()) texts.push(walk.currentNode);
    return texts.length === runs.length;
  };
  if (parserAlike && shapeOf.get(el) === tags && textsOf()) {
    runs.forEach((t, i) => {
      if (texts[i].data !== t) texts[i].data = t;
    });
    return;
  }
  const parsed = document.createElement("template");
  parsed.innerHTML = html;
  const attributes = (node) => [...(node.attributes ?? [])].map((a) => `${a.name}=${a.value}`).join("\n");
  const keep = (old, now) => {
    const was = old.childNodes;
    const fresh = now.childNodes;
    if (was.length !== fresh.length) return old.replaceChildren(...fresh);
    // From the end: a node moved into `old` leaves `fresh`, not its earlier nodes.
    for (let i = fresh.length - 1; i >= 0; i--) {
      const [a, b] = [was[i], fresh[i]];
      if (a.nodeName !== b.nodeName || attributes(a) !== attributes(b)) a.replaceWith(b);
      else if (a.nodeType !== Node.ELEMENT_NODE) {
        if (a.nodeValue !== b.nodeValue) a.nodeValue = b.nodeValue;
      } else keep(a, b);
    }
  };
  keep(el, parsed.content);
  texts.length = 0;
  if (textsOf() && texts.every((n, i) => n.data === runs[i])) shapeOf.set(el, tags);
  else shapeOf.delete(el);
};
// labRewriteMarkup: end
// labWatchBox: begin
// Tells `onChange(width, height, inWindow)` what the browser's observers see
// of `el` each time it changes: its size (CSS px, a ResizeObserver) and
// whether any of it is in the window (an IntersectionObserver; true until
// that has reported). They report after the browser laid the page out, so
// a frame that uses these reads no size and never makes the browser lay the
// page out in the middle of it. Returns the function that stops watching.
// Self-contained, like labRewriteMarkup (the wasm's test pages run this text).
// Once stopped it never calls `onChange` again: an IntersectionObserver may
// still deliver a report it queued before `disconnect`, and the page frees
// `onChange` when it stops watching.
window.labWatchBox = function watchBox(el, onChange) {
  let width = 0;
  let height = 0;
  let inWindow = true;
  let watching = true;
  const sized = new ResizeObserver((entries) => {
    const shown = height === 0;
    ({ width, height } = entries[entries.length - 1].contentRect);
    // Shown again (a tab, a panel): in the window until the other observer
    // says otherwise; its last word was about a box that was not laid out.
    // It speaks again only when its answer changes, and a box that left the
    // window hidden and came back still out of it would stay "in" for good:
    // observed afresh, it reports the box as it is now.
    if (shown && height > 0 && watching) {
      inWindow = true;
      seen.unobserve(el);
      seen.observe(el);
    }
    if (watching) onChange(width, height, inWindow);
  });
  const seen = new IntersectionObserver((entries) => {
    inWindow = entries[entries.length - 1].isIntersecting;
    if (watching) onChange(width, height, inWindow);
  });
  sized.observe(el);
  seen.observe(el);
  return () => {
    watching = false;
    sized.disconnect();
    seen.disconnect();
  };
};
// labWatchBox: end
// labWhenIdle: begin
// Sends `el` the event "lab-idle" once the browser's main thread is idle
// between frames (requestIdleCallback), `timeoutMs` later at the latest on a
// busy page. Returns false where the browser has no idle callbacks (WebKit's
// Safari). Self-contained, like labRewriteMarkup.
window.labWhenIdle = (el, timeoutMs) =>
  !!window.requestIdleCallback?.(() => el.dispatchEvent(new Event("lab-idle")), { timeout: timeoutMs });
// labWhenIdle: end
const showStatic = window.labShowArticle;

const pageFailed = async (error) => {
  if (await redeployed()) return updated();
  fatal(`This page could not be loaded (${error.message ?? error}). Check the connection and reload.`);
};

async function showPage() {
  nav?.querySelector("details")?.removeAttribute("open");
  const route = hashRoute();
  const mod = route && moduleOf(route.id);
  if (!mod) {
    // The home page (also under a running module, which shows it only once
    // it is in the document), or a link that names no experiment: a running
    // module explains it; before any, the first module starts to explain it.
    const home = await ensurePage("home").catch(pageFailed);
    if (hashRoute() && moduleOf(hashRoute().id)) return;
    if (home && (!active || /^#?\/?$/.test(location.hash))) showStatic(null);
    if (!active && !/^#?\/?$/.test(location.hash) && MODULES.length) switchTo(MODULES[0]);
    return;
  }
  // Among the running module's experiments, its own listener routes; it waits
  // for the article of an experiment not shown before, added here.
  if (active === mod.key) {
    let present = app.querySelector(pageSelector(route.id));
    const added = !present;
    if (added) {
      try {
        present = await ensurePage(route.id);
      } catch (error) {
        pageFailed(error);
        return;
      }
    }
    // A module still downloading (or failing to start) routes nothing yet:
    // the tab chosen meanwhile (a tab link, Back) is shown from here.
    if (!running.has(mod.key)) {
      const now = hashRoute();
      if (now?.id === route.id) showStatic(present, now.tab);
      return;
    }
    if (added && active === mod.key && hashRoute()?.id === route.id) (await glues.get(active))?.reroute();
    return;
  }
  let article;
  try {
    article = await ensurePage(route.id);
  } catch (error) {
    pageFailed(error);
    return;
  }
  const now = hashRoute();
  if (now?.id !== route.id) return;
  if (active !== mod.key) showStatic(article, now.tab);
  switchTo(mod);
}

// A SCORM launch names its experiment in the query (`index.html?sco=pid`),
// which LMSs keep where some drop the `#`: without a hash, open it. An LMS
// that appends its own query with a second `?` (`?sco=pid?scorm_launch=1`)
// is read as if it had used `&` (as scorm.js's scoOf reads it).
const scoQuery = new URLSearchParams(location.search.slice(1).replaceAll("?", "&"));
const sco = /^[\w-]*/.exec(scoQuery.get("sco") ?? "")[0];
if (sco && moduleOf(sco) && /^#?\/?$/.test(location.hash)) history.replaceState(null, "", `#/${sco}/aim`);
window.addEventListener("hashchange", showPage);
showPage();

// The experiments menu closes on Escape and on a click elsewhere.
document.addEventListener("keydown", (e) => {
  const open = nav?.querySelector("details[open]");
  if (e.key === "Escape" && open) {
    open.removeAttribute("open");
    open.querySelector("summary")?.focus();
  }
});
document.addEventListener("click", (e) => {
  const open = nav?.querySelector("details[open]");
  if (open && (!open.contains(e.target) || e.target.closest("a"))) open.removeAttribute("open");
});
// The skip link moves focus to the page without touching the hash (which
// names the page shown); a listener here, not an inline handler, which the
// Content-Security-Policy forbids.
document.querySelector("a.skip")?.addEventListener("click", (e) => {
  e.preventDefault();
  app.focus();
});
document.querySelector("#notice .notice-close").addEventListener("click", () => {
  document.getElementById("notice").hidden = true;
});

// The lab report's module (pkg/report.<hash>.js|wasm, crate labreport) is not
// part of any experiment's download: it is fetched the first time a student
// makes a report, or as the pointer or keyboard focus reaches the button so
// that the press finds it ready. The experiment's module calls
// labReport(bytes, done, failed) with the report's data; a failed download
// is tried again at the next press.
const REPORT = document.querySelector("meta[name=lab-report]")?.dataset;
let reportGlue = null;
let reportTries = 0;
const loadReport = () => {
  if (!reportGlue) {
    reportGlue = (async () => {
      if (!REPORT) throw new Error("this copy of the lab has no report module");
      // A browser keeps a module that failed for its address: a retry asks
      // for it under a new one.
      const url = new URL(REPORT.js, import.meta.url);
      if (reportTries++ > 0) url.searchParams.set("try", reportTries);
      const glue = await import(url.href);
      await glue.default({ module_or_path: new URL(REPORT.wasm, import.meta.url) });
      return glue;
    })();
    reportGlue.catch(() => { reportGlue = null; });
  }
  return reportGlue;
};
window.labReport = (bytes, done, failed) => {
  loadReport().then((glue) => glue.render(bytes)).then(done, failed);
};
for (const kind of ["pointerover", "focusin"]) {
  document.addEventListener(kind, (e) => {
    if (e.target.closest?.("[data-export=report]")) loadReport().catch(() => {});
    if (e.target.closest?.(".instructor-panel > summary")) loadInstructor().catch(() => {});
  }, { passive: true });
}

// The Instructor panel's code (instructor.<hash>.js, from web/instructor.js)
// is not part of any experiment's download either: a student never needs it.
// It is fetched the first time a panel is opened, or as the pointer or
// keyboard focus reaches its summary, and builds the panel in the
// placeholder the experiment's module leaves. A failed download says so in
// the panel and is tried again at the next opening.
const INSTRUCTOR = document.querySelector("meta[name=lab-instructor]")?.dataset.js ?? "instructor.js";
let instructorCode = null;
let instructorTries = 0;
const loadInstructor = () => {
  if (!instructorCode) {
    const url = new URL(INSTRUCTOR, import.meta.url);
    if (instructorTries++ > 0) url.searchParams.set("try", instructorTries);
    instructorCode = import(url.href);
    instructorCode.catch(() => { instructorCode = null; });
  }
  return instructorCode;
};
// `toggle` does not bubble: caught on its way down.
document.addEventListener("toggle", (e) => {
  const panel = e.target;
  if (!panel.open || !panel.matches?.(".instructor-panel")) return;
  loadInstructor().then((code) => code.build(panel), () => {
    const wait = panel.querySelector(".instructor-wait");
    if (wait) wait.textContent = "The instructor's tools could not be loaded. Check the connection, then close and open this panel again.";
  });
}, true);

// Offline after one visit: once the page has loaded (never competing with
// its first download), the service worker caches the whole site. A visit
// after a new deployment says so quietly.
try {
  const seen = localStorage.getItem("lab-version");
  if (siteVersion && seen && seen !== siteVersion) {
    const box = document.getElementById("updated");
    box.hidden = false;
    box.querySelector(".notice-close").addEventListener("click", () => { box.hidden = true; });
  }
  if (siteVersion) localStorage.setItem("lab-version", siteVersion);
} catch {
  // Storage may be off (private mode): no notice then.
}
// Not inside a frame: an LMS (SCORM package) serves the lab its own way.
if ("serviceWorker" in navigator && window.isSecureContext && siteVersion && window.top === window) {
  const register = () =>
    navigator.serviceWorker.register(new URL("sw.js", import.meta.url), { scope: "./" }).catch(() => {});
  if (document.readyState === "complete") register();
  else addEventListener("load", register, { once: true });
}
