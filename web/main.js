// Bootstrap. The reading tabs are already in the page (rendered at build
// time); these few lines show the page the link names before the wasm
// arrives, fetch the wasm only when an experiment is opened (with progress),
// and hand routing over to it once it runs. Everything else lives in Rust.

const app = document.getElementById("app");
const nav = document.getElementById("lab-nav");
const TABS = ["aim", "theory", "procedure", "simulation", "quiz", "references"];
let wasmReady = false;
let loading = null;

const fatal = (message) => {
  const box = document.getElementById("fatal");
  box.querySelector(".fatal-text").textContent = message;
  box.hidden = false;
  for (const wait of document.querySelectorAll(".wasm-wait p")) {
    wait.textContent = "The simulation engine could not start; the reading tabs still work.";
  }
  for (const bar of document.querySelectorAll(".wasm-progress")) bar.remove();
};

const progress = (fraction) => {
  for (const bar of document.querySelectorAll(".wasm-progress")) {
    bar.value = Math.round(100 * fraction);
    bar.textContent = `${Math.round(100 * fraction)} %`;
  }
};

// Downloads the wasm with a progress bar, then starts it (which mounts the app).
async function loadWasm() {
  if (typeof WebAssembly !== "object") {
    fatal("This browser does not support WebAssembly; please use a current version of Firefox, Chrome, Edge or Safari.");
    return;
  }
  const version = new URL(import.meta.url).search;
  const url = new URL("./pkg/labweb_bg.wasm" + version, import.meta.url);
  const total = Number(document.querySelector("meta[name=lab-wasm-bytes]")?.content) || 0;
  const response = await fetch(url);
  if (!response.ok) throw new Error(`HTTP ${response.status} for the wasm module`);
  let bytes;
  if (response.body && total > 0) {
    const reader = response.body.getReader();
    const chunks = [];
    let received = 0;
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      chunks.push(value);
      received += value.length;
      progress(Math.min(1, received / total));
    }
    bytes = new Uint8Array(received);
    let at = 0;
    for (const c of chunks) { bytes.set(c, at); at += c.length; }
  } else {
    bytes = new Uint8Array(await response.arrayBuffer());
  }
  progress(1);
  const glue = await import("./pkg/labweb.js");
  await glue.default({ module_or_path: bytes });
  wasmReady = true;
  window.labweb = glue;
}

function ensureWasm() {
  if (!loading) {
    loading = loadWasm().catch((error) => {
      fatal(`The simulation engine failed to load (${error}). If you opened the file directly, serve the folder over HTTP instead.`);
    });
  }
}

// Shows the page the hash names until the wasm takes over routing.
function showPage() {
  if (wasmReady) return;
  nav?.querySelector("details")?.removeAttribute("open");
  const match = location.hash.match(/^#\/([^/?]+)(?:\/([^/?]*))?/);
  const article = match && [...app.querySelectorAll("article.exp")].find((a) => a.dataset.experiment === match[1]);
  const home = app.querySelector("[data-page=home]");
  if (home) home.hidden = Boolean(article);
  for (const a of app.querySelectorAll("article.exp")) a.hidden = a !== article;
  for (const a of nav?.querySelectorAll("a[data-experiment]") ?? []) {
    if (article && a.dataset.experiment === article.dataset.experiment) a.setAttribute("aria-current", "page");
    else a.removeAttribute("aria-current");
  }
  if (!article) {
    // A link that names no page is malformed: the wasm explains what was wrong.
    if (!/^#?\/?$/.test(location.hash)) ensureWasm();
    return;
  }
  const tab = TABS.includes(match[2]) ? match[2] : "aim";
  article.dataset.tab = tab;
  for (const t of article.querySelectorAll("[role=tab]")) {
    const on = t.dataset.tab === tab;
    t.setAttribute("aria-selected", String(on));
    t.tabIndex = on ? 0 : -1;
  }
  for (const p of article.querySelectorAll("[role=tabpanel]")) p.hidden = p.dataset.panel !== tab;
  document.title = `${article.querySelector("h1")?.textContent ?? ""} — Robotics virtual lab`;
  ensureWasm();
}

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
