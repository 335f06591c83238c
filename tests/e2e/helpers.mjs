// Shared plumbing for the end-to-end tests: the lab's own server
// (`cargo xtask serve`) for dist/ under a sub-path, Debian's headless Chromium through playwright-core, and pages that
// fail their test on console errors, uncaught exceptions, failed requests and
// any request that leaves the test server's origin.

import { after, before } from "node:test";
import assert from "node:assert/strict";
import { spawn, spawnSync } from "node:child_process";
import { createServer as createTcpServer } from "node:net";
import { cpSync, existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join, resolve } from "node:path";
import { createInterface } from "node:readline";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), "..", "..");
export const DIST = join(ROOT, "dist");
export const SHOTS = join(ROOT, "target", "e2e-shots");
/** The lab is served below this prefix, as on a host that puts it in a sub-folder. */
export const BASE_PATH = "/some/sub/path/";
/** Where `startServer({ probe: true })` serves tests/e2e/error-probe.js. */
export const PROBE_PATH = `${BASE_PATH}__test__/error-probe.js`;
export const TABS = ["aim", "theory", "procedure", "simulation", "quiz", "references"];
export const DESKTOP = { width: 1280, height: 800 };
export const PHONE = { width: 360, height: 740 };
const CHROMIUM = process.env.CHROMIUM || "/usr/bin/chromium";

/** A content-hashed file name (`control.0a1b2c3d.wasm`): it never changes. */
export const isContentHashed = (path) => /[^/]\.[0-9a-f]{8}\.[a-z]+$/.test(path);

/**
 * The `cargo xtask` binary: the one running `cargo xtask test` (it says so in
 * LAB_XTASK), else the one `cargo xtask` builds (profile `tool`), built here
 * once if it is missing.
 */
function xtaskBinary() {
  if (process.env.LAB_XTASK) return process.env.LAB_XTASK;
  const target = process.env.CARGO_TARGET_DIR ? resolve(ROOT, process.env.CARGO_TARGET_DIR) : join(ROOT, "target");
  const bin = join(target, "tool", process.platform === "win32" ? "xtask.exe" : "xtask");
  if (!existsSync(bin)) {
    const built = spawnSync("cargo", ["build", "--quiet", "--profile", "tool", "-p", "xtask", "--bin", "xtask"], {
      cwd: ROOT,
      stdio: "inherit",
    });
    if (built.status !== 0 || !existsSync(bin)) throw new Error(`could not build ${bin}`);
  }
  return bin;
}

/** Servers still running when the test process ends are stopped with it. */
const running = new Set();
process.on("exit", () => {
  for (const child of running) child.kill();
});

/**
 * Serves dist/ under BASE_PATH on 127.0.0.1 and a free port with the lab's
 * own server, `cargo xtask serve --dir dist` (crates/xtask/src/serve.rs): its
 * media types, cache headers (hashed names for a year, the rest
 * revalidated), Content-Security-Policy header and compression (dist/'s
 * `.br`/`.gz` siblings, as nginx `brotli_static`/`gzip_static` would) are
 * what the tests see. `compress: false` serves every file as it is
 * (`--no-compression`), as a host that does not compress. `server.hits`
 * lists the paths requested (from the server's log, written before each
 * answer). `probe: true` serves a copy of dist/ whose `index.html` loads
 * tests/e2e/error-probe.js (at PROBE_PATH) first in its <head>, for a
 * browser whose driver reports no console errors. `copy: true` serves a
 * copy of dist/ that the test may change (`server.dir`), as a host's
 * folder that a redeploy changes under an open page. `server.notModified`
 * lists the paths answered 304 (the browser's copy was current: no body),
 * as `hits` does, in order.
 */
export async function startServer({ compress = true, probe = false, copy = false } = {}) {
  if (!existsSync(join(DIST, "index.html"))) {
    throw new Error("dist/index.html is missing: run `cargo xtask dist` first");
  }
  let dir = DIST;
  if (probe || copy) {
    dir = mkdtempSync(join(tmpdir(), "lab-copy-"));
    cpSync(DIST, dir, { recursive: true });
  }
  if (probe) {
    const index = join(dir, "index.html");
    const probed = readFileSync(index, "utf8").replace("<head>", `<head>\n<script src="${PROBE_PATH}"></script>`);
    writeFileSync(index, probed);
    // The precompressed copies would be sent instead of the probed page.
    for (const ext of [".br", ".gz"]) rmSync(index + ext, { force: true });
    const probeFile = join(dir, PROBE_PATH.slice(BASE_PATH.length));
    mkdirSync(dirname(probeFile), { recursive: true });
    cpSync(join(ROOT, "tests", "e2e", "error-probe.js"), probeFile);
  }
  const args = ["serve", "--dir", dir, "--port", "0", "--host", "127.0.0.1", "--base", BASE_PATH];
  if (!compress) args.push("--no-compression");
  const child = spawn(xtaskBinary(), args, { cwd: ROOT, stdio: ["ignore", "pipe", "pipe"] });
  running.add(child);
  const hits = [];
  const notModified = [];
  const said = [];
  // Every request is logged as `GET /path?query`: the log must be read (a
  // full pipe would stop the server), and it says what was requested.
  const pathOf = (target) => {
    try {
      return decodeURIComponent(new URL(target, "http://x").pathname);
    } catch {
      return target;
    }
  };
  createInterface({ input: child.stderr }).on("line", (line) => {
    const unchanged = line.match(/^not modified (\S+)$/);
    if (unchanged) return notModified.push(pathOf(unchanged[1]));
    const m = line.match(/^[A-Z]+ (\S+)$/);
    if (!m) return said.push(line);
    hits.push(pathOf(m[1]));
  });
  const origin = await new Promise((ok, fail) => {
    const lines = createInterface({ input: child.stdout });
    lines.on("line", (line) => {
      const m = line.match(/ at (http:\/\/[^/\s]+)\//);
      if (m) ok(m[1]);
    });
    child.on("exit", (code) =>
      // An old binary without --dir says so here: `cargo xtask dist` builds it anew.
      setImmediate(() => fail(new Error(`xtask serve exited (${code}) before it served: ${said.join(" ")}`))),
    );
    child.on("error", fail);
  });
  return {
    origin,
    hits,
    notModified,
    dir,
    base: origin + BASE_PATH,
    close: async () => {
      running.delete(child);
      if (child.exitCode === null && child.signalCode === null) {
        const exited = new Promise((ok) => child.once("exit", ok));
        child.kill();
        await exited;
      }
      if (dir !== DIST) rmSync(dir, { recursive: true, force: true });
    },
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
 * clock (Playwright's clock, stopped from the start: see `runFor` and `runUntil`),
 * serviceWorkers ("block" by default: a test that routes or counts requests
 * must see them all; the offline tests pass "allow"), bypassCSP (to inject a
 * test's own script, e.g. axe-core, with addScriptTag), expectHttpError
 * (`(url) => boolean`: an HTTP error the test expects for that URL, e.g. a
 * file a redeploy removed, fails nothing, nor the console's line about it;
 * the test asserts that it happened).
 */
/** Contexts whose pages run on a stopped clock (`withPage`'s `clock`). */
const stoppedClocks = new WeakSet();

/**
 * Whether a failed request is the browser giving up its own fetch of the
 * tab's icon (Chromium's net::ERR_ABORTED, Firefox's NS_BINDING_ABORTED,
 * WebKit's cancellation) — which happens when a page navigates away before
 * the icon arrived, and says nothing about the lab.
 */
export function browserCancelledIcon(url, errorText) {
  const icon = new URL(url).pathname.endsWith("/favicon.svg");
  return icon && /ABORTED|cancel/i.test(errorText);
}

export async function withPage(lab, options, fn) {
  const {
    viewport = DESKTOP,
    hasTouch = false,
    isMobile = false,
    colorScheme = "light",
    serviceWorkers = "block",
    bypassCSP = false,
    clock = false,
  } = options;
  const context = await lab.browser.newContext({ viewport, hasTouch, isMobile, colorScheme, serviceWorkers, bypassCSP });
  context.setDefaultTimeout(10_000);
  // The page's clock is Playwright's, stopped before the page loads: no
  // animation frame or timer fires unless the test advances time (`runFor`,
  // `runUntil`), so a simulation moves by the same fixed steps however busy
  // the machine is. (Loading needs no timer: fetches and the wasm's start
  // are promises.)
  if (clock) {
    await context.clock.install();
    await context.clock.pauseAt(Date.now() + 1000);
    // The clock's frame ids start at 10^12; web-sys reads an id as an i32
    // (browsers count from 1), so a cancelled frame would be cancelled under
    // a truncated id and still fire. Hand the page small ids.
    await context.addInitScript(() => {
      const request = window.requestAnimationFrame.bind(window);
      const cancel = window.cancelAnimationFrame.bind(window);
      const ids = new Map();
      let next = 1;
      window.requestAnimationFrame = (callback) => {
        const id = next++;
        ids.set(id, request((t) => {
          ids.delete(id);
          callback(t);
        }));
        return id;
      };
      window.cancelAnimationFrame = (id) => {
        if (ids.has(id)) cancel(ids.get(id));
        ids.delete(id);
      };
    });
    stoppedClocks.add(context);
  }
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
    const expected = (url) => Boolean(url && options.expectHttpError?.(url));
    page.on("console", (msg) => {
      if (msg.type() === "error" && !options.allowConsoleErrors) {
        if (/^Failed to load resource/.test(msg.text()) && expected(msg.location().url)) return;
        problems.push(`console error: ${msg.text()}`);
      }
    });
    page.on("pageerror", (err) => problems.push(`uncaught exception: ${err.message}`));
    page.on("requestfailed", (req) => {
      const error = req.failure()?.errorText ?? "";
      // The browser fetches the tab's icon on its own schedule and cancels
      // that fetch when the test navigates on; a cancelled icon is not a
      // failure of the page (CI saw net::ERR_ABORTED on favicon.svg).
      if (browserCancelledIcon(req.url(), error)) return;
      problems.push(`request failed: ${req.url()} (${error})`);
    });
    page.on("response", (res) => {
      if (res.status() >= 400 && !expected(res.url())) problems.push(`HTTP ${res.status()} for ${res.url()}`);
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
      await poll(
        page,
        (x) => {
          const art = `article.exp[data-experiment="${CSS.escape(x)}"]:not([hidden])`;
          return Boolean(document.querySelector(`${art} canvas.sim-canvas, ${art} .sim-error`));
        },
        id,
      );
      // On a stopped clock, one frame: the controls and readouts show the
      // link's state as a running page's first frame shows it.
      if (stoppedClocks.has(page.context())) await page.clock.runFor(17);
    }
  } else {
    await poll(page, () => Boolean(document.querySelector("[data-page=home]:not([hidden])")));
  }
}

/**
 * Waits, in real time, until `predicate(arg)` holds in the page, asking from
 * here (Node) every 25 ms: unlike `page.waitForFunction`, whose polling
 * runs on the page's own animation frames and timers, it also works on a
 * page whose clock is stopped (`withPage`'s `clock`). For page-load and DOM
 * events only; a simulated event is reached with `runUntil`.
 */
export async function poll(page, predicate, arg, { timeout = 10_000 } = {}) {
  const end = Date.now() + timeout;
  for (;;) {
    if (await page.evaluate(predicate, arg)) return;
    if (Date.now() > end) throw new Error(`poll: the page did not get there within ${timeout} ms`);
    await new Promise((ok) => setTimeout(ok, 25));
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
  await poll(page, () => Boolean(document.body && document.body.dataset.ready === "1"));
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

/**
 * The experiments of the built site, in the lab's order: the reading pages
 * `cargo xtask dist` lists in dist/index.html (`<meta name="lab-page">`),
 * written from labcore's one list of experiments. Tests take the ids from
 * here (or from the home page's cards), never from a list or a count of
 * their own.
 */
export function builtExperimentIds() {
  const html = readFileSync(join(DIST, "index.html"), "utf8");
  return [...html.matchAll(/<meta name="lab-page" content="([a-z0-9]+)"/g)]
    .map((m) => m[1])
    .filter((id) => id !== "home");
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

/**
 * Waits for two animation frames so layout and canvas drawing have settled.
 * On a stopped clock it runs two frames' worth of page time instead.
 */
export function settle(page) {
  if (stoppedClocks.has(page.context())) return page.clock.runFor(34);
  return page.evaluate(
    () => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok))),
  );
}

/**
 * Waits until `predicate(arg)` holds in the page: on a stopped clock
 * (`withPage`'s `clock`) by running page time (`runUntil`), else as
 * `page.waitForFunction` does. For helpers shared by tests of both kinds.
 */
export function until(page, predicate, arg, options = {}) {
  if (stoppedClocks.has(page.context())) return runUntil(page, predicate, arg, options);
  return page.waitForFunction(predicate, arg, options);
}

/** Advances a frozen clock by `ms` of page time, one 60 Hz frame at a time. */
export async function runFor(page, ms) {
  await page.clock.runFor(ms);
}

/**
 * Advances a frozen clock in slices of `sliceMs` until `predicate(arg)`
 * holds in the page, at most `maxMs` of page time (simulated time, not the
 * machine's): the run either reaches the event within that budget or the
 * lab is wrong. Returns the page time it took, in ms.
 */
export async function runUntil(page, predicate, arg, { sliceMs = 50, maxMs, timeout, what = "the condition" } = {}) {
  // `timeout` (page.waitForFunction's word, a wall-clock bound in the tests
  // this replaced) is page time here, and never under 60 s of it: a bound
  // in simulated time costs a busy machine nothing.
  maxMs = maxMs ?? Math.max(timeout ?? 0, 60_000);
  for (let t = 0; ; t += sliceMs) {
    if (await page.evaluate(predicate, arg)) return t;
    if (t >= maxMs) throw new Error(`${what} did not hold within ${maxMs} ms of page time`);
    await page.clock.runFor(sliceMs);
  }
}

/**
 * `runUntil` for a readout: `[data-readout=key]`'s number (its magnitude with
 * `abs`) is `op` (">" or "<") `bound`. Returns the readout's text.
 */
export async function runUntilReadout(page, key, op, bound, { abs = false, maxMs = 60_000 } = {}) {
  await runUntil(
    page,
    ([k, o, b, a]) => {
      const el = document.querySelector(`article.exp:not([hidden]) [data-readout="${k}"]`);
      if (!el) return false;
      const raw = Number.parseFloat(el.textContent);
      const v = a ? Math.abs(raw) : raw;
      return o === ">" ? v > b : v < b;
    },
    [key, op, bound, abs],
    { maxMs, what: `readout ${key} ${op} ${bound}` },
  );
  return (await readouts(page))[key];
}

/**
 * Page coordinates of world point (x, y) on the visible experiment's
 * simulation canvas, as the page maps them (labweb's viewport: the view in
 * `data-view` fitted uniformly and centred, y up). Scrolls the canvas into
 * view first, as a student would before pointing at it.
 */
export async function worldToPage(page, x, y) {
  const canvas = page.locator("article.exp:not([hidden]) canvas.sim-canvas");
  await canvas.scrollIntoViewIfNeeded();
  const box = await canvas.boundingBox();
  const [minX, minY, maxX, maxY] = (await canvas.getAttribute("data-view")).split(",").map(Number);
  const scale = Math.min(box.width / (maxX - minX), box.height / (maxY - minY));
  return {
    x: box.x + box.width / 2 + (x - (minX + maxX) / 2) * scale,
    y: box.y + box.height / 2 - (y - (minY + maxY) / 2) * scale,
    scale,
  };
}

/** A free TCP port on 127.0.0.1. */
export function freePort() {
  return new Promise((ok, fail) => {
    const s = createTcpServer();
    s.on("error", fail);
    s.listen(0, "127.0.0.1", () => {
      const { port } = s.address();
      s.close(() => ok(port));
    });
  });
}

/**
 * Waits until the service worker controls the page and holds its cache;
 * returns its scope and how many files the cache holds (the worker fills
 * its cache while it installs: once it controls the page, the cache is whole).
 */
export function workerReady(page) {
  return page.evaluate(async () => {
    const reg = await navigator.serviceWorker.ready;
    if (!navigator.serviceWorker.controller) {
      await new Promise((ok) => navigator.serviceWorker.addEventListener("controllerchange", ok, { once: true }));
    }
    const names = await caches.keys();
    const cache = await caches.open(names.find((n) => n.startsWith("lab-")));
    return { scope: reg.scope, cached: (await cache.keys()).length };
  });
}
