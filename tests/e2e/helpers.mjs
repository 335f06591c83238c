// Shared plumbing for the end-to-end tests: a static server for dist/ under a
// sub-path, Debian's headless Chromium through playwright-core, and pages that
// fail their test on console errors, uncaught exceptions, failed requests and
// any request that leaves the test server's origin.

import { after, before } from "node:test";
import assert from "node:assert/strict";
import { createServer } from "node:http";
import { existsSync, mkdirSync } from "node:fs";
import { readFile, stat } from "node:fs/promises";
import { dirname, extname, join, resolve, sep } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), "..", "..");
export const DIST = join(ROOT, "dist");
export const SHOTS = join(ROOT, "target", "e2e-shots");
/** The lab is served below this prefix, as on a host that puts it in a sub-folder. */
export const BASE_PATH = "/some/sub/path/";
export const TABS = ["aim", "theory", "procedure", "simulation", "quiz", "references"];
export const DESKTOP = { width: 1280, height: 800 };
export const PHONE = { width: 360, height: 740 };
const CHROMIUM = process.env.CHROMIUM || "/usr/bin/chromium";

const MIME = {
  ".html": "text/html; charset=utf-8",
  ".js": "text/javascript; charset=utf-8",
  ".mjs": "text/javascript; charset=utf-8",
  ".css": "text/css; charset=utf-8",
  ".json": "application/json; charset=utf-8",
  ".wasm": "application/wasm",
  ".svg": "image/svg+xml; charset=utf-8",
  ".webmanifest": "application/manifest+json; charset=utf-8",
  ".png": "image/png",
  ".ico": "image/x-icon",
  ".txt": "text/plain; charset=utf-8",
};

/** A content-hashed file name (`control.0a1b2c3d.wasm`): it never changes. */
export const isContentHashed = (path) => /[^/]\.[0-9a-f]{8}\.[a-z]+$/.test(path);

/**
 * Serves dist/ under BASE_PATH on 127.0.0.1 and a free port, with the cache
 * headers `cargo xtask serve` sends (hashed names for a year, the rest
 * revalidated). `compress: true` serves the `.br`/`.gz` siblings that
 * `cargo xtask dist` writes, as nginx `brotli_static`/`gzip_static` would.
 * `server.hits` lists the paths requested.
 */
export async function startServer({ compress = false } = {}) {
  const hits = [];
  if (!existsSync(join(DIST, "index.html"))) {
    throw new Error("dist/index.html is missing: run `cargo xtask dist` first");
  }
  const server = createServer(async (req, res) => {
    const send = (code, body, type = "text/plain; charset=utf-8", headers = {}) => {
      res.writeHead(code, { "Content-Type": type, "Cache-Control": "no-cache", ...headers });
      res.end(req.method === "HEAD" ? undefined : body);
    };
    try {
      if (req.method !== "GET" && req.method !== "HEAD") return send(405, "GET or HEAD only\n");
      const path = decodeURIComponent(new URL(req.url, "http://x").pathname);
      hits.push(path);
      if (path === BASE_PATH.slice(0, -1)) return send(301, "", undefined, { Location: BASE_PATH });
      if (!path.startsWith(BASE_PATH) || path.includes("\0")) return send(404, "not found\n");
      let file = resolve(DIST, "." + sep + path.slice(BASE_PATH.length));
      if (file !== DIST && !file.startsWith(DIST + sep)) return send(403, "forbidden\n");
      if ((await stat(file).catch(() => null))?.isDirectory()) file = join(file, "index.html");
      const body = await readFile(file).catch(() => null);
      if (!body) return send(404, "not found\n");
      const headers = isContentHashed(file) ? { "Cache-Control": "public, max-age=31536000, immutable" } : {};
      if (compress) {
        const accepted = String(req.headers["accept-encoding"] ?? "");
        for (const [coding, ext] of [["br", ".br"], ["gzip", ".gz"]]) {
          if (!accepted.includes(coding)) continue;
          const packed = await readFile(file + ext).catch(() => null);
          if (packed) {
            return send(200, packed, MIME[extname(file)] || "application/octet-stream", {
              ...headers,
              "Content-Encoding": coding,
              Vary: "Accept-Encoding",
            });
          }
        }
      }
      send(200, body, MIME[extname(file)] || "application/octet-stream", headers);
    } catch {
      send(400, "bad request\n");
    }
  });
  await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
  const origin = `http://127.0.0.1:${server.address().port}`;
  return {
    origin,
    hits,
    base: origin + BASE_PATH,
    close: () => new Promise((ok) => server.close(ok)),
  };
}

export function launchBrowser() {
  return chromium.launch({
    executablePath: CHROMIUM,
    args: [
      "--no-sandbox",
      "--disable-gpu",
      "--disable-quic",
      "--no-first-run",
      "--disable-background-networking",
      "--disable-component-update",
      "--disable-sync",
    ],
  });
}

/**
 * Registers before/after hooks for one test file: a server and a browser.
 * Returns a getter object: `lab.server`, `lab.browser`.
 */
export function useLab() {
  const lab = { server: null, browser: null };
  before(async () => {
    lab.server = await startServer();
    lab.browser = await launchBrowser();
  });
  after(async () => {
    await lab.browser?.close();
    await lab.server?.close();
  });
  return lab;
}

/**
 * Opens a fresh browser context + page and runs `fn(page, ctx)`. Afterwards
 * the test fails on anything that went wrong in the page.
 *
 * options: viewport, hasTouch, isMobile, colorScheme, allowConsoleErrors, initScript,
 * serviceWorkers ("block" by default: a test that routes or counts requests
 * must see them all; the offline tests pass "allow"), bypassCSP (to inject a
 * test's own script, e.g. axe-core, with addScriptTag).
 */
export async function withPage(lab, options, fn) {
  const {
    viewport = DESKTOP,
    hasTouch = false,
    isMobile = false,
    colorScheme = "light",
    serviceWorkers = "block",
    bypassCSP = false,
  } = options;
  const context = await lab.browser.newContext({ viewport, hasTouch, isMobile, colorScheme, serviceWorkers, bypassCSP });
  context.setDefaultTimeout(10_000);
  const problems = [];
  const origin = lab.server.origin;
  if (options.initScript) await context.addInitScript(options.initScript);
  // Nothing may leave the test server: record it and refuse it.
  await context.route(
    (url) => !["data:", "blob:"].includes(url.protocol) && url.origin !== origin,
    (route) => {
      problems.push(`request to another origin: ${route.request().url()}`);
      return route.abort();
    },
  );
  // Every page of the context (including ones a test opens later) is watched.
  context.on("page", (page) => {
    page.on("console", (msg) => {
      if (msg.type() === "error" && !options.allowConsoleErrors) {
        problems.push(`console error: ${msg.text()}`);
      }
    });
    page.on("pageerror", (err) => problems.push(`uncaught exception: ${err.message}`));
    page.on("requestfailed", (req) =>
      problems.push(`request failed: ${req.url()} (${req.failure()?.errorText})`),
    );
    page.on("response", (res) => {
      if (res.status() >= 400) problems.push(`HTTP ${res.status()} for ${res.url()}`);
    });
  });
  const page = await context.newPage();
  try {
    await fn(page, context);
    assert.deepEqual(problems, [], "the page reported problems");
  } finally {
    await context.close();
  }
}

/**
 * Loads `<base>index.html<hash>`. An experiment page waits until the wasm app
 * has mounted; the home page never loads the wasm, so it waits only for the
 * pre-rendered page.
 */
export async function open(lab, page, hash = "#/") {
  await page.goto(`${lab.server.base}index.html${hash}`);
  const id = hash.match(/^#\/([^/?]+)/)?.[1];
  if (id) {
    await waitReady(page);
    // A link to an experiment of another module (the same page, a new hash)
    // starts that module: wait until its simulation is mounted (on any tab),
    // unless the link names no experiment at all.
    const known = await page.evaluate(
      (x) => Boolean(document.querySelector(`meta[name=lab-page][content="${CSS.escape(x)}"]`)) && x !== "home",
      id,
    );
    if (known) {
      const art = `article.exp[data-experiment="${id}"]:not([hidden])`;
      await page.waitForSelector(`${art} canvas.sim-canvas, ${art} .sim-error`, { state: "attached" });
    }
  } else {
    await page.waitForSelector("[data-page=home]:not([hidden])");
  }
}

/** A readout's number: "0.123 m" → 0.123, "1.1 × 10⁻⁷ m" → 1.1e-7, "∞ (singular)" → Infinity. */
export function readNumber(text) {
  const sup = { "⁰": "0", "¹": "1", "²": "2", "³": "3", "⁴": "4", "⁵": "5", "⁶": "6", "⁷": "7", "⁸": "8", "⁹": "9", "⁻": "-" };
  const t = text.trim();
  if (t.startsWith("∞")) return Infinity;
  const m = t.match(/^(-?[\d.]+)\s*×\s*10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)/);
  if (m) return Number(m[1]) * 10 ** Number([...m[2]].map((c) => sup[c]).join(""));
  return Number.parseFloat(t);
}

export async function waitReady(page) {
  await page.waitForFunction(() => document.body && document.body.dataset.ready === "1");
}

/** Experiment ids, read from the home page's cards (not hard-coded). */
export async function experimentIds(lab) {
  let ids = [];
  await withPage(lab, {}, async (page) => {
    await open(lab, page, "#/");
    ids = await page.$$eval("a.card[data-experiment]", (cards) =>
      cards.map((c) => c.dataset.experiment),
    );
  });
  assert.ok(ids.length > 0, "the home page lists at least one experiment card");
  return ids;
}

/** Text of every `[data-readout]`, keyed by its name. */
export function readouts(page) {
  return page.$$eval("[data-readout]", (els) =>
    Object.fromEntries(els.map((e) => [e.dataset.readout, e.textContent.trim()])),
  );
}

/** Screenshot into target/e2e-shots/ (gitignored). */
export async function screenshot(page, name) {
  mkdirSync(SHOTS, { recursive: true });
  await page.screenshot({ path: join(SHOTS, `${name}.png`) });
}

/** Waits for two animation frames so layout and canvas drawing have settled. */
export function settle(page) {
  return page.evaluate(
    () => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok))),
  );
}
