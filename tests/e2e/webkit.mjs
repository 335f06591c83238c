// WebKitGTK (Safari's engine) for the end-to-end tests: Debian's
// `WebKitWebDriver` driving its MiniBrowser on an Xvfb display, through plain
// W3C WebDriver calls (HTTP + JSON, node's own fetch; no client package).
//
// WebDriver classic has no console log, so a page served for WebKit carries
// a probe script (tests/e2e/error-probe.js, put first in <head> by
// startServer's `probe` option) that records console errors, uncaught
// exceptions and unhandled rejections in `window.__labProblems`.

import { spawn } from "node:child_process";
import { existsSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { SHOTS, freePort } from "./helpers.mjs";
import { crop, decodePng, encodePng } from "./png.mjs";

export const WEBKIT_DRIVER = process.env.WEBKIT_DRIVER || "/usr/bin/WebKitWebDriver";
export const XVFB = process.env.XVFB || "/usr/bin/Xvfb";
/** The W3C WebDriver key for an element reference. */
const ELEMENT = "element-6066-11e4-a52e-4f735466cecf";

/** True when Debian's webkit2gtk-driver and xvfb are installed. */
export const webkitAvailable = () => existsSync(WEBKIT_DRIVER) && existsSync(XVFB);

/** Starts Xvfb on a free display (it reports the number on fd 3). */
function startXvfb() {
  return new Promise((ok, fail) => {
    const proc = spawn(XVFB, ["-displayfd", "3", "-screen", "0", "2000x1400x24", "-nolisten", "tcp"], {
      stdio: ["ignore", "ignore", "pipe", "pipe"],
    });
    let err = "";
    let out = "";
    proc.stderr.on("data", (d) => (err += d));
    proc.stdio[3].on("data", (d) => {
      out += d;
      if (out.includes("\n")) ok({ proc, display: `:${out.trim()}` });
    });
    proc.on("exit", (code) => fail(new Error(`Xvfb exited (${code}): ${err}`)));
    proc.on("error", fail);
  });
}

async function waitForDriver(url, driver) {
  for (let i = 0; i < 200; i++) {
    if (driver.exitCode !== null) throw new Error(`WebKitWebDriver exited (${driver.exitCode})`);
    try {
      const res = await fetch(`${url}/status`);
      if (res.ok && (await res.json()).value?.ready) return;
    } catch {
      // not listening yet
    }
    await new Promise((ok) => setTimeout(ok, 50));
  }
  throw new Error("WebKitWebDriver did not become ready");
}

/**
 * Starts Xvfb, WebKitWebDriver and one MiniBrowser session. Returns a
 * `WebKitSession`; `close()` ends the session and both processes.
 */
export async function launchWebKit() {
  const xvfb = await startXvfb();
  const port = await freePort();
  const home = mkdtempSync(join(tmpdir(), "lab-webkit-"));
  const env = {
    ...process.env,
    DISPLAY: xvfb.display,
    // A fresh profile: no cache or service worker from an earlier run.
    HOME: home,
    XDG_CACHE_HOME: join(home, "cache"),
    XDG_DATA_HOME: join(home, "data"),
    XDG_CONFIG_HOME: join(home, "config"),
    // No accessibility bus or dconf on a test machine.
    NO_AT_BRIDGE: "1",
    GSETTINGS_BACKEND: "memory",
    MESA_SHADER_CACHE_DISABLE: "true",
  };
  const driver = spawn(WEBKIT_DRIVER, [`--port=${port}`], { env, stdio: ["ignore", "ignore", "pipe"] });
  let driverLog = "";
  driver.stderr.on("data", (d) => (driverLog = (driverLog + d).slice(-4000)));
  const url = `http://127.0.0.1:${port}`;
  const exited = (proc) => (proc.exitCode !== null || proc.signalCode !== null ? Promise.resolve() : new Promise((ok) => proc.once("exit", ok)));
  const stop = async () => {
    driver.kill();
    await exited(driver);
    xvfb.proc.kill();
    await exited(xvfb.proc);
    // A web process may still be writing as it exits: leftovers are harmless.
    try {
      rmSync(home, { recursive: true, force: true, maxRetries: 5 });
    } catch {}
  };
  try {
    await waitForDriver(url, driver);
    const created = await call(url, "POST", "/session", {
      capabilities: { alwaysMatch: { "webkitgtk:browserOptions": { args: ["--automation"] } } },
    });
    return new WebKitSession(url, created.sessionId, created.capabilities, stop, () => driverLog);
  } catch (e) {
    await stop();
    throw new Error(`${e.message}\n${driverLog}`);
  }
}

async function call(base, method, path, body) {
  const res = await fetch(base + path, {
    method,
    headers: body === undefined ? {} : { "Content-Type": "application/json; charset=utf-8" },
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  const json = await res.json().catch(() => ({}));
  if (!res.ok) {
    const v = json.value ?? {};
    throw new Error(`WebDriver ${method} ${path}: ${v.error ?? res.status}: ${v.message ?? ""}`);
  }
  return json.value;
}

/** One WebDriver session: the few commands the tests use. */
export class WebKitSession {
  constructor(url, id, capabilities, stop, log) {
    this.base = `${url}/session/${id}`;
    this.capabilities = capabilities;
    this.stop = stop;
    this.log = log;
  }

  cmd(method, path, body) {
    return call(this.base, method, path, body);
  }

  /** The browser's name and version, e.g. "MiniBrowser 2.50.6". */
  get version() {
    return `${this.capabilities.browserName} ${this.capabilities.browserVersion}`;
  }

  setWindowSize(width, height) {
    return this.cmd("POST", "/window/rect", { width, height });
  }

  /** Loads a URL (a full load: WebDriver waits for the load event). */
  goto(url) {
    return this.cmd("POST", "/url", { url });
  }

  /** Runs `fn(...args)` in the page; `fn` may return a promise. */
  evaluate(fn, ...args) {
    return this.cmd("POST", "/execute/async", {
      script: `const done = arguments[arguments.length - 1];
        Promise.resolve((${fn}).apply(null, Array.from(arguments).slice(0, -1)))
          .then((v) => done({ ok: v === undefined ? null : v }), (e) => done({ error: String(e && e.stack || e) }));`,
      args,
    }).then((r) => {
      if (r && "error" in r) throw new Error(`in the page: ${r.error}`);
      return r?.ok;
    });
  }

  /** Polls `fn(...args)` in the page until it returns something truthy. */
  async waitFor(fn, { timeout = 15_000, what = String(fn) } = {}, ...args) {
    const end = Date.now() + timeout;
    for (;;) {
      const v = await this.evaluate(fn, ...args);
      if (v) return v;
      if (Date.now() > end) throw new Error(`timed out waiting for ${what}`);
      await new Promise((ok) => setTimeout(ok, 100));
    }
  }

  async find(selector) {
    const found = await this.cmd("POST", "/element", { using: "css selector", value: selector });
    return found[ELEMENT];
  }

  /** Clicks the element (real pointer input through the driver). */
  async click(selector) {
    await this.cmd("POST", `/element/${await this.find(selector)}/click`, {});
  }

  /**
   * Types `text` over a field's whole value, key by key. (Element Clear
   * would fire a change with an empty value, which the lab refuses and
   * undoes; selecting the text and typing over it is what a person does.)
   */
  async type(selector, text) {
    const el = await this.find(selector);
    await this.evaluate((sel) => {
      const input = document.querySelector(sel);
      input.focus();
      input.select();
    }, selector);
    await this.cmd("POST", `/element/${el}/value`, { text });
  }

  /**
   * A PNG of the viewport, or of one element (scrolled into view, cut out
   * of the viewport: WebKitGTK's own element screenshots come out black where
   * the element is not on screen), as a Buffer.
   */
  async screenshot(selector) {
    if (!selector) return Buffer.from(await this.cmd("GET", "/screenshot"), "base64");
    const rect = await this.evaluate((sel) => {
      const el = document.querySelector(sel);
      el.scrollIntoView({ block: "start", inline: "start" });
      return new Promise((ok) =>
        requestAnimationFrame(() =>
          requestAnimationFrame(() => {
            const r = el.getBoundingClientRect();
            const k = devicePixelRatio;
            ok({ x: r.x * k, y: r.y * k, width: r.width * k, height: r.height * k });
          }),
        ),
      );
    }, selector);
    const page = decodePng(Buffer.from(await this.cmd("GET", "/screenshot"), "base64"));
    return encodePng(crop(page, rect));
  }

  /** Saves a screenshot into target/e2e-shots/<name>.png. */
  async saveScreenshot(name, selector) {
    mkdirSync(SHOTS, { recursive: true });
    writeFileSync(join(SHOTS, `${name}.png`), await this.screenshot(selector));
  }

  async close() {
    try {
      await call(this.base, "DELETE", "");
    } finally {
      await this.stop();
    }
  }
}
