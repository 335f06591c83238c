// The server recipes of docs/hosting.md, run on the real servers (issue 24 §1, issue
// 51 §5): Debian 12's nginx (with libnginx-mod-http-brotli-static), Apache
// 2.4 with Debian's default modules (once with docs/hosting.md's virtual host and
// once with its .htaccess alone in a shared-hosting folder), Caddy 2.6 and
// lighttpd 1.4. Each recipe is taken out of docs/hosting.md itself (the fenced
// block after its `<!-- recipe: … -->` marker), put into a configuration
// built from the package's own stock one where it has one (nginx.conf,
// apache2.conf, lighttpd.conf: only the listening port, the site, the pid
// and log files are ours; Caddy's stock Caddyfile is one site and nothing
// else), and serves a copy of dist/ under /labs/robotics/ on 127.0.0.1 and
// a free port. Then, behind each server:
//   - every file of dist/ has its type, and a br client, a gzip-only client
//     and an identity client each get a body that decodes to the file;
//   - compressible files carry `Vary: Accept-Encoding`, and the cache headers
//     are those `cargo xtask serve` sends;
//   - /labs/robotics (no slash) redirects to the folder, as docs/hosting.md says;
//   - every experiment's Simulation tab draws with no console error;
//   - the lab works offline after one visit.
// The servers are stopped afterwards; the system's own sites and services are
// not touched. The headers seen and the console errors per experiment are
// printed as a table and written to target/hosts/report.md.
//
// Run: `cargo xtask test` (its step "docs/hosting.md's server recipes"), or
// `node --test tests/hosts/` after `cargo xtask dist`, with the Debian
// packages nginx, libnginx-mod-http-brotli-static, apache2, caddy and
// lighttpd installed (the suite installs them with apt-get when it runs as
// root). Neither Caddy nor lighttpd needs systemd: each runs in the
// foreground on its own configuration and is stopped by its PID.

import { after, before, describe, test } from "node:test";
import assert from "node:assert/strict";
import { spawn, spawnSync } from "node:child_process";
import {
  chmodSync,
  cpSync,
  existsSync,
  mkdirSync,
  mkdtempSync,
  readFileSync,
  readdirSync,
  rmSync,
  writeFileSync,
} from "node:fs";
import { request } from "node:http";
import { tmpdir } from "node:os";
import { dirname, extname, join, relative, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { brotliDecompressSync, gunzipSync } from "node:zlib";
import {
  DIST,
  builtExperimentIds,
  freePort,
  isContentHashed,
  launchBrowser,
  open,
  waitReady,
  withPage,
  workerReady,
} from "../e2e/helpers.mjs";

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), "..", "..");
const HOSTING = join(ROOT, "docs", "hosting.md");
/** The sub-path and the folder docs/hosting.md's recipes name. */
const SUB_PATH = "/labs/robotics/";
const RECIPE_FOLDER = "/srv/robotics";
const PACKAGES = ["nginx", "libnginx-mod-http-brotli-static", "apache2", "caddy", "lighttpd"];
const NGINX = "/usr/sbin/nginx";
const APACHE = "/usr/sbin/apache2";
const CADDY = "/usr/bin/caddy";
const LIGHTTPD = "/usr/sbin/lighttpd";
const BROTLI_MODULE = "/usr/share/nginx/modules/ngx_http_brotli_static_module.so";

/** The three clients: what each sends, and the coding it should get for a file with siblings. */
const CLIENTS = [
  { name: "br", acceptEncoding: "br, gzip, deflate", coding: "br" },
  { name: "gzip", acceptEncoding: "gzip, deflate", coding: "gzip" },
  { name: "identity", acceptEncoding: "identity", coding: null },
];

/**
 * The media type each file of dist/ must go out with (what `cargo xtask
 * serve` sends, see `mime` in crates/xtask/src/serve.rs); for JavaScript,
 * either name a browser accepts for a module script (nginx's mime.types says
 * application/javascript, Debian's /etc/mime.types text/javascript).
 */
const MEDIA_TYPES = {
  ".html": ["text/html"],
  ".js": ["text/javascript", "application/javascript"],
  ".mjs": ["text/javascript", "application/javascript"],
  ".css": ["text/css"],
  ".json": ["application/json"],
  ".wasm": ["application/wasm"],
  ".svg": ["image/svg+xml"],
  ".webmanifest": ["application/manifest+json"],
  ".png": ["image/png"],
  ".ico": ["image/x-icon", "image/vnd.microsoft.icon"],
  ".txt": ["text/plain"],
};

/** Files worth a `Vary: Accept-Encoding` (they have `.br`/`.gz` siblings). */
const hasSiblings = (file) => existsSync(join(DIST, file + ".gz")) || existsSync(join(DIST, file + ".br"));

const IMMUTABLE = "public, max-age=31536000, immutable";

// ---------------------------------------------------------------- docs/hosting.md

/**
 * The fenced block that follows `<!-- recipe: NAME -->` in docs/hosting.md. Fails
 * when the marker is missing or not followed by a fenced block of `lang`.
 */
function recipe(text, name, lang) {
  const marker = `<!-- recipe: ${name} -->`;
  const at = text.indexOf(marker);
  assert.ok(at >= 0, `docs/hosting.md has the marker ${marker}`);
  assert.equal(text.indexOf(marker, at + 1), -1, `docs/hosting.md has ${marker} once`);
  const m = text.slice(at + marker.length).match(/^\s*```(\w+)\n([\s\S]*?)\n```/);
  assert.ok(m, `${marker} is followed by a fenced block`);
  assert.equal(m[1], lang, `${marker}: the block is \`\`\`${lang}`);
  return m[2];
}

// ---------------------------------------------------------------- setup

/** Installs the packages with apt-get when missing and we are root; otherwise says what to run. */
function ensurePackages() {
  const missing = [NGINX, APACHE, BROTLI_MODULE, CADDY, LIGHTTPD].filter((p) => !existsSync(p));
  if (missing.length === 0) return;
  const command = `apt-get update && apt-get install -y ${PACKAGES.join(" ")}`;
  assert.equal(process.getuid(), 0, `missing ${missing.join(", ")}: run (as root) ${command}`);
  const env = { ...process.env, DEBIAN_FRONTEND: "noninteractive" };
  for (const args of [["update"], ["install", "-y", ...PACKAGES]]) {
    const r = spawnSync("apt-get", ["-o", "DPkg::Lock::Timeout=600", ...args], { stdio: "inherit", env });
    assert.equal(r.status, 0, `apt-get ${args.join(" ")} failed`);
  }
}

/** GET (no redirects followed): status, headers and the raw body bytes. */
function get(url, headers = {}) {
  return new Promise((ok, fail) => {
    const req = request(url, { headers }, (res) => {
      const chunks = [];
      res.on("data", (c) => chunks.push(c));
      res.on("end", () => ok({ status: res.statusCode, headers: res.headers, body: Buffer.concat(chunks) }));
      res.on("error", fail);
    });
    req.on("error", fail);
    req.end();
  });
}

/** The servers this suite started: stopped when it ends, however it ends. */
const children = new Set();
process.on("exit", () => {
  for (const child of children) child.kill("SIGTERM");
});

/** Starts `command args`, and waits until `url` answers 200 (or the process dies). */
async function startProcess(name, command, args, env, url, logs) {
  const child = spawn(command, args, { env, stdio: ["ignore", "pipe", "pipe"] });
  let output = "";
  child.stdout.on("data", (d) => (output += d));
  child.stderr.on("data", (d) => (output += d));
  const exited = new Promise((ok) => child.on("exit", (code, signal) => ok({ code, signal })));
  let died = null;
  exited.then((e) => (died = e));
  children.add(child);
  exited.then(() => children.delete(child));
  const problem = () => {
    const log = logs.filter(existsSync).map((f) => readFileSync(f, "utf8")).join("\n");
    return `${name} did not start (${JSON.stringify(died)}):\n${output}\n${log}`;
  };
  // Poll by attempts, not by time: a busy machine only makes it slower.
  for (let attempt = 0; ; attempt++) {
    if (died) throw new Error(problem());
    const res = await get(url).catch(() => null);
    if (res?.status === 200) break;
    if (attempt > 600) {
      child.kill("SIGTERM");
      await exited;
      throw new Error(problem());
    }
    await new Promise((ok) => setTimeout(ok, 50));
  }
  return {
    stop: async () => {
      if (!died) child.kill("SIGTERM");
      await exited;
    },
    output: () => output,
  };
}

/**
 * nginx: Debian's own /etc/nginx/nginx.conf (modules-enabled, mime.types,
 * `gzip on`, …) with our pid, logs, temp paths and, instead of
 * sites-enabled, one server block on `port` holding docs/hosting.md's recipe.
 */
async function startNginx(dir, labFolder, hosting) {
  const port = await freePort();
  const site = recipe(hosting, "nginx", "nginx").replaceAll(RECIPE_FOLDER, labFolder);
  const conf = join(dir, "nginx");
  mkdirSync(conf, { recursive: true });
  writeFileSync(join(conf, "lab-site.conf"), site);
  let text = readFileSync("/etc/nginx/nginx.conf", "utf8");
  const replace = (pattern, by) => {
    assert.match(text, pattern, `/etc/nginx/nginx.conf has ${pattern}`);
    text = text.replace(pattern, by);
  };
  replace(/^user\s[^;]*;/m, "");
  replace(/^worker_processes\s[^;]*;/m, "worker_processes 1;");
  replace(/^pid\s[^;]*;/m, `pid ${conf}/nginx.pid;`);
  replace(/^error_log\s[^;]*;/m, `error_log ${conf}/error.log;`);
  replace(/^(\s*)access_log\s[^;]*;/m, `$1access_log ${conf}/access.log;`);
  replace(
    /^(\s*)include \/etc\/nginx\/sites-enabled\/\*;/m,
    [
      ...["client_body", "proxy", "fastcgi", "uwsgi", "scgi"].map((t) => `$1${t}_temp_path ${conf}/${t};`),
      `$1server {`,
      `$1    listen 127.0.0.1:${port};`,
      `$1    include ${conf}/lab-site.conf;`,
      `$1}`,
    ].join("\n"),
  );
  writeFileSync(join(conf, "nginx.conf"), text);
  const origin = `http://127.0.0.1:${port}`;
  const server = await startProcess(
    "nginx",
    NGINX,
    ["-e", join(conf, "error.log"), "-c", join(conf, "nginx.conf"), "-g", "daemon off;"],
    process.env,
    origin + SUB_PATH,
    [join(conf, "error.log")],
  );
  return { name: "nginx", origin, base: origin + SUB_PATH, ...server, log: join(conf, "error.log") };
}

/**
 * Apache: Debian's own /etc/apache2/apache2.conf (mods-enabled, conf-enabled,
 * the `<Directory />` defaults) run with `-d /etc/apache2 -f ours`, our own
 * pid, lock and log directories and, instead of ports.conf and
 * sites-enabled, one port and one virtual host; mod_rewrite and mod_headers
 * loaded as `a2enmod rewrite headers` would (without enabling them on the
 * system); docs/hosting.md's .htaccess in the lab's folder.
 *
 * The virtual host holds docs/hosting.md's server recipe (an Alias of
 * /labs/robotics to `labFolder`), or, with `sharedRoot`, nothing of the
 * lab's: a shared host's web space, `sharedRoot` as the DocumentRoot with
 * `AllowOverride All`, and the lab copied to `labs/robotics/` in it
 * (`labFolder` must be that folder), where the .htaccess alone serves it.
 */
async function startApache(dir, labFolder, hosting, { sharedRoot = null } = {}) {
  const port = await freePort();
  writeFileSync(join(labFolder, ".htaccess"), recipe(hosting, "apache .htaccess", "apache"));
  const conf = join(dir, sharedRoot ? "apache-shared" : "apache");
  const docroot = sharedRoot ?? join(dir, "apache-docroot");
  if (sharedRoot) assert.equal(labFolder, join(sharedRoot, SUB_PATH), "the lab is in the web space's labs/robotics/");
  mkdirSync(conf, { recursive: true });
  mkdirSync(docroot, { recursive: true });
  const site = sharedRoot
    ? [`<Directory ${docroot}>`, `    AllowOverride All`, `    Require all granted`, `</Directory>`].join("\n")
    : recipe(hosting, "apache", "apache").replaceAll(RECIPE_FOLDER, labFolder);
  let text = readFileSync("/etc/apache2/apache2.conf", "utf8");
  const replace = (pattern, by) => {
    assert.match(text, pattern, `/etc/apache2/apache2.conf has ${pattern}`);
    text = text.replace(pattern, by);
  };
  replace(
    /^Include ports\.conf$/m,
    [
      `Listen 127.0.0.1:${port}`,
      ...["rewrite", "headers"].map(
        (m) => `<IfModule !${m}_module>\n    Include mods-available/${m}.load\n</IfModule>`,
      ),
    ].join("\n"),
  );
  replace(
    /^IncludeOptional sites-enabled\/\*\.conf$/m,
    [
      `ServerName 127.0.0.1`,
      `<VirtualHost 127.0.0.1:${port}>`,
      `    DocumentRoot ${docroot}`,
      `    Include ${conf}/lab-site.conf`,
      `</VirtualHost>`,
    ].join("\n"),
  );
  writeFileSync(join(conf, "lab-site.conf"), site);
  writeFileSync(join(conf, "apache2.conf"), text);
  // As root, Debian's www-data; otherwise Apache keeps the user it runs as.
  const root = process.getuid() === 0;
  const env = {
    ...process.env,
    APACHE_RUN_USER: root ? "www-data" : `#${process.getuid()}`,
    APACHE_RUN_GROUP: root ? "www-data" : `#${process.getgid()}`,
    APACHE_PID_FILE: join(conf, "apache2.pid"),
    APACHE_RUN_DIR: conf,
    APACHE_LOCK_DIR: conf,
    APACHE_LOG_DIR: conf,
    LANG: "C",
  };
  const origin = `http://127.0.0.1:${port}`;
  const server = await startProcess(
    "apache2",
    APACHE,
    ["-d", "/etc/apache2", "-f", join(conf, "apache2.conf"), "-DFOREGROUND"],
    env,
    origin + SUB_PATH,
    [join(conf, "error.log")],
  );
  const name = sharedRoot ? "Apache .htaccess alone" : "Apache";
  return { name, origin, base: origin + SUB_PATH, ...server, log: join(conf, "error.log") };
}

/**
 * Caddy: Debian's package ships one site and no global options, so the
 * configuration is ours: no admin endpoint, no automatic HTTPS, and one
 * site on `port` holding docs/hosting.md's recipe. Caddy's data and config
 * folders go to `dir`, not the user's home.
 */
async function startCaddy(dir, labFolder, hosting) {
  const port = await freePort();
  const conf = join(dir, "caddy");
  mkdirSync(conf, { recursive: true });
  const site = recipe(hosting, "caddy", "caddy").replaceAll(RECIPE_FOLDER, labFolder);
  const indented = site.split("\n").map((l) => (l ? `\t${l}` : l)).join("\n");
  writeFileSync(
    join(conf, "Caddyfile"),
    `{\n\tadmin off\n\tauto_https off\n}\nhttp://127.0.0.1:${port} {\n${indented}\n}\n`,
  );
  const env = { ...process.env, HOME: conf, XDG_DATA_HOME: conf, XDG_CONFIG_HOME: conf };
  const origin = `http://127.0.0.1:${port}`;
  const server = await startProcess(
    "caddy",
    CADDY,
    ["run", "--config", join(conf, "Caddyfile"), "--adapter", "caddyfile"],
    env,
    origin + SUB_PATH,
    [],
  );
  return { name: "Caddy", origin, base: origin + SUB_PATH, ...server };
}

/**
 * The type map of lighttpd's own tutorial (TutorialConfiguration), put where
 * Debian's lighttpd.conf builds its map from /etc/mime.types: the map an
 * admin who followed the tutorial has, under which `.js` and `.css` go out
 * as application/octet-stream unless the recipe says otherwise.
 */
const LIGHTTPD_TUTORIAL_TYPES = `mimetype.assign = (
  ".html" => "text/html",
  ".txt" => "text/plain",
  ".jpg" => "image/jpeg",
  ".png" => "image/png"
)`;

/**
 * lighttpd: Debian's own /etc/lighttpd/lighttpd.conf (its modules,
 * index-file names, conf-enabled/) with our port, pid, log and upload
 * folder, the tutorial's type map in place of Debian's, Debian's
 * 20-deflate.conf enabled (its cache in `dir`), and docs/hosting.md's recipe at
 * the end, run in the foreground (`-D`).
 */
async function startLighttpd(dir, labFolder, hosting) {
  const port = await freePort();
  const conf = join(dir, "lighttpd");
  const docroot = join(dir, "lighttpd-docroot");
  for (const d of [conf, docroot, join(conf, "compress"), join(conf, "uploads")]) mkdirSync(d, { recursive: true });
  let text = readFileSync("/etc/lighttpd/lighttpd.conf", "utf8");
  const replace = (pattern, by) => {
    assert.match(text, pattern, `/etc/lighttpd/lighttpd.conf has ${pattern}`);
    text = text.replace(pattern, by);
  };
  replace(/^server\.document-root\s*=.*$/m, `server.document-root = "${docroot}"`);
  replace(/^server\.upload-dirs\s*=.*$/m, `server.upload-dirs = ( "${conf}/uploads" )`);
  replace(/^server\.errorlog\s*=.*$/m, `server.errorlog = "${conf}/error.log"`);
  replace(/^server\.pid-file\s*=.*$/m, `server.pid-file = "${conf}/lighttpd.pid"`);
  // As root, Debian's www-data; otherwise lighttpd keeps the user it runs as.
  if (process.getuid() !== 0) {
    replace(/^server\.username\s*=.*\n/m, "");
    replace(/^server\.groupname\s*=.*\n/m, "");
  }
  replace(/^server\.port\s*=.*$/m, `server.port = ${port}\nserver.bind = "127.0.0.1"`);
  replace(/^include_shell "\/usr\/share\/lighttpd\/use-ipv6\.pl.*\n/m, "");
  replace(/^include_shell "\/usr\/share\/lighttpd\/create-mime\.conf\.pl"$/m, LIGHTTPD_TUTORIAL_TYPES);
  const deflate = readFileSync("/etc/lighttpd/conf-available/20-deflate.conf", "utf8").replace(
    /^deflate\.cache-dir\s*=.*$/m,
    `deflate.cache-dir = "${conf}/compress/"`,
  );
  assert.match(deflate, /mod_deflate/, "Debian's 20-deflate.conf loads mod_deflate");
  const site = recipe(hosting, "lighttpd", "lighttpd").replaceAll(RECIPE_FOLDER, labFolder);
  writeFileSync(join(conf, "lighttpd.conf"), `${text}\n${deflate}\n${site}\n`);
  // lighttpd opens its log and writes its cache as the user it runs as.
  if (process.getuid() === 0) spawnSync("chown", ["-R", "www-data:www-data", conf]);
  const origin = `http://127.0.0.1:${port}`;
  const server = await startProcess(
    "lighttpd",
    LIGHTTPD,
    ["-D", "-f", join(conf, "lighttpd.conf")],
    process.env,
    origin + SUB_PATH,
    [join(conf, "error.log")],
  );
  return { name: "lighttpd", origin, base: origin + SUB_PATH, ...server, log: join(conf, "error.log") };
}

/** Every file of dist/ except the precompressed siblings, relative, with `/`. */
function distFiles(dir = DIST) {
  return readdirSync(dir, { withFileTypes: true }).flatMap((e) => {
    const full = join(dir, e.name);
    if (e.isDirectory()) return distFiles(full);
    if (/\.(br|gz)$/.test(e.name)) return [];
    return [relative(DIST, full).split("\\").join("/")];
  });
}

/** The row of the report a file belongs to: its extension, and whether its name is content-hashed. */
function fileKind(file) {
  const ext = extname(file) || file;
  return `${ext}${isContentHashed(file) ? " (hashed)" : ""}`;
}

/** Decodes a body by its Content-Encoding. */
function decode(body, coding) {
  if (!coding) return body;
  if (coding === "br") return brotliDecompressSync(body);
  if (coding === "gzip") return gunzipSync(body);
  throw new Error(`unexpected Content-Encoding ${coding}`);
}

/**
 * The Simulation tab of `id` is mounted and its canvas is drawn: a sample of
 * its pixels holds at least three colours (a background alone is one).
 * Returns how many colours the sample holds.
 */
async function simulationDraws(page, id) {
  const canvas = page.locator(`article.exp[data-experiment=${id}]:not([hidden]) canvas.sim-canvas`);
  await canvas.waitFor({ state: "visible" });
  // Two frames, so the first paint is on the canvas.
  await page.evaluate(() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok))));
  const colours = await canvas.evaluate((c) => {
    const data = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    const seen = new Set();
    for (let i = 0; i < data.length; i += 4 * 97) seen.add(data.slice(i, i + 4).join(","));
    return seen.size;
  });
  assert.ok(colours >= 3, `${id}: the canvas is drawn (${colours} colours in the sample)`);
  return colours;
}

// ---------------------------------------------------------------- the suite

const hosting = readFileSync(HOSTING, "utf8");
const files = existsSync(DIST) ? distFiles().sort() : [];
/** Rows of the headers table: server, client, kind, file, and the four headers. */
const headerRows = [];
/** Rows of the console table: server, experiment, console errors, colours in a pixel sample, coding of the wasm. */
const consoleRows = [];
let work = null;
let browser = null;
const servers = {};

before(async () => {
  assert.ok(existsSync(join(DIST, "index.html")), "dist/index.html is missing: run `cargo xtask dist` first");
  ensurePackages();
  // A copy of dist/ that the servers' workers (www-data, nobody) can read,
  // and where Apache's .htaccess can go without touching dist/.
  work = mkdtempSync(join(tmpdir(), "lab-hosts-"));
  chmodSync(work, 0o755);
  const folder = join(work, "robotics");
  cpSync(DIST, folder, { recursive: true });
  spawnSync("chmod", ["-R", "a+rX", folder]);
  // Each server gets its own copy (Apache's .htaccess stays out of the others').
  const copy = (name) => {
    const to = join(work, name);
    cpSync(folder, to, { recursive: true });
    return to;
  };
  const sharedRoot = join(work, "shared-web-space");
  const sharedFolder = join(sharedRoot, SUB_PATH);
  mkdirSync(dirname(sharedFolder), { recursive: true });
  cpSync(folder, sharedFolder, { recursive: true });
  spawnSync("chmod", ["-R", "a+rX", sharedRoot]);
  const [nginxFolder, caddyFolder, lighttpdFolder] = ["nginx", "caddy", "lighttpd"].map((s) => copy(`robotics-${s}`));
  servers.nginx = await startNginx(work, nginxFolder, hosting);
  servers.apache = await startApache(work, folder, hosting);
  servers.apacheShared = await startApache(work, sharedFolder, hosting, { sharedRoot });
  servers.caddy = await startCaddy(work, caddyFolder, hosting);
  servers.lighttpd = await startLighttpd(work, lighttpdFolder, hosting);
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  for (const s of Object.values(servers)) await s.stop();
  if (work) rmSync(work, { recursive: true, force: true });
  if (headerRows.length === 0 && consoleRows.length === 0) return;
  const report = renderReport();
  const out = join(ROOT, "target", "hosts");
  mkdirSync(out, { recursive: true });
  writeFileSync(join(out, "report.md"), report);
  console.log(`\n${report}\n(also in target/hosts/report.md)`);
});

/** The tables the closing note quotes, in Markdown. */
function renderReport() {
  const lines = ["Headers, per server, file type and client (— = no such header)", ""];
  lines.push("| server | file type: files | client | Content-Type | Content-Encoding | Vary | Cache-Control |");
  lines.push("| --- | --- | --- | --- | --- | --- | --- |");
  const groups = new Map();
  for (const r of headerRows) {
    const key = [r.server, r.kind, r.client].join("\u0000");
    if (!groups.has(key)) groups.set(key, { ...r, files: new Set(), values: {} });
    const g = groups.get(key);
    g.files.add(r.file);
    for (const h of ["type", "encoding", "vary", "cache"]) (g.values[h] ??= new Set()).add(r[h] || "—");
  }
  const serverOrder = Object.values(servers).map((s) => s.name);
  const clientOrder = CLIENTS.map((c) => c.name);
  const sorted = [...groups.values()].sort(
    (x, y) =>
      serverOrder.indexOf(x.server) - serverOrder.indexOf(y.server) ||
      x.kind.localeCompare(y.kind) ||
      clientOrder.indexOf(x.client) - clientOrder.indexOf(y.client),
  );
  for (const g of sorted) {
    const cell = (h) => [...g.values[h]].join(" / ");
    const names = [...g.files];
    const which = names.length <= 3 ? names.join(", ") : `${names.length} files, e.g. ${names[0]}`;
    lines.push(
      `| ${g.server} | ${g.kind}: ${which} | ${g.client} | ${cell("type")} | ${cell("encoding")} | ${cell("vary")} | ${cell("cache")} |`,
    );
  }
  lines.push("", "Simulation tab in Chromium, per experiment: console errors (colours in a pixel sample of the canvas)", "");
  lines.push(`| experiment | ${serverOrder.join(" | ")} |`);
  lines.push(`| --- | ${serverOrder.map(() => "---").join(" | ")} |`);
  const ids = [...new Set(consoleRows.map((r) => r.id))];
  for (const id of ids) {
    const cells = serverOrder.map((name) => {
      const r = consoleRows.find((x) => x.id === id && x.server === name);
      return r ? `${r.errors} (${r.colours})` : "not run";
    });
    lines.push(`| ${id} | ${cells.join(" | ")} |`);
  }
  const codings = [...new Set(consoleRows.map((r) => `${r.server}: ${r.wasmEncoding}`))];
  lines.push("", `The wasm reached Chromium with Content-Encoding ${codings.join(", ")}.`);
  return lines.join("\n");
}

test("docs/hosting.md marks its nginx and Apache recipes so that this suite can take them out", () => {
  assert.match(recipe(hosting, "nginx", "nginx"), /brotli_static on;/);
  assert.match(recipe(hosting, "apache", "apache"), /AllowOverride/);
  assert.match(recipe(hosting, "apache .htaccess", "apache"), /RewriteEngine On/);
});

test("hosts beyond nginx and Apache: docs/hosting.md has a Caddy and a lighttpd recipe, and says which types a server must send", () => {
  assert.match(recipe(hosting, "caddy", "caddy"), /precompressed br gzip/);
  assert.match(recipe(hosting, "lighttpd", "lighttpd"), /mimetype\.assign/);
  const types = hosting.match(/^## File types\n([^]*?)\n## /m)?.[1];
  assert.ok(types, "docs/hosting.md has a section \"File types\"");
  for (const ext of Object.keys(MEDIA_TYPES).filter((e) => e !== ".mjs")) {
    assert.match(types, new RegExp(`\`\\${ext}\``), `"File types" names ${ext}`);
  }
  for (const ext of [".html", ".js", ".css"]) {
    const row = types.split("\n").find((l) => l.startsWith(`| \`${ext}\``));
    assert.match(row ?? "", /\*\*must\*\*/, `${ext} is a type a server must send`);
  }
  assert.match(types.split("\n").find((l) => l.startsWith("| `.wasm`")) ?? "", /nice to have/, ".wasm is only nice to have");
});

/** The servers of the suite, by key: the names the tests carry. */
const SERVER_TITLES = {
  nginx: "nginx serving dist/ with docs/hosting.md's recipe",
  apache: "Apache serving dist/ with docs/hosting.md's recipe",
  apacheShared: "Apache shared hosting: docs/hosting.md's .htaccess alone in a folder with AllowOverride All",
  caddy: "Caddy 2.6 serving dist/ with docs/hosting.md's recipe",
  lighttpd: "lighttpd 1.4 serving dist/ with docs/hosting.md's recipe (the tutorial's type map)",
};

for (const key of Object.keys(SERVER_TITLES)) {
  describe(SERVER_TITLES[key], () => {
    const lab = {
      get server() {
        return servers[key];
      },
      get browser() {
        return browser;
      },
    };

    /** Every file of dist/ fetched once by each client: the rows the next three tests check. */
    let fetched = null;
    const fetchAll = () =>
      (fetched ??= (async () => {
        const server = servers[key];
        const rows = [];
        for (const file of files) {
          for (const client of CLIENTS) {
            const res = await get(server.base + file, { "Accept-Encoding": client.acceptEncoding });
            const h = res.headers;
            const row = {
              server: server.name,
              client: client.name,
              clientCoding: client.coding,
              kind: fileKind(file),
              file,
              res,
              where: `${server.name}, ${client.name} client, ${file}`,
              type: h["content-type"],
              encoding: h["content-encoding"],
              vary: h.vary,
              cache: h["cache-control"],
            };
            rows.push(row);
            headerRows.push(row);
          }
        }
        return rows;
      })());

    test("every file of dist/ has its Content-Type; br, gzip and identity clients each get a body that decodes to the file", async () => {
      assert.ok(files.length > 20, `dist/ has files (${files.length})`);
      const problems = [];
      for (const row of await fetchAll()) {
        const { file, res, where } = row;
        if (res.status !== 200) {
          problems.push(`${where}: HTTP ${res.status}`);
          continue;
        }
        const types = MEDIA_TYPES[extname(file)];
        const essence = String(row.type).split(";")[0].trim().toLowerCase();
        if (!types) problems.push(`${where}: the suite does not know the type of ${extname(file) || file}: add it to MEDIA_TYPES`);
        else if (!types.includes(essence)) problems.push(`${where}: Content-Type ${row.type}, expected ${types.join(" or ")}`);
        const sibling = row.clientCoding && existsSync(join(DIST, `${file}.${row.clientCoding === "br" ? "br" : "gz"}`));
        const expected = sibling ? row.clientCoding : undefined;
        if (row.encoding !== expected) problems.push(`${where}: Content-Encoding ${row.encoding}, expected ${expected}`);
        let decoded = null;
        try {
          decoded = decode(res.body, row.encoding);
        } catch (e) {
          problems.push(`${where}: the body does not decode as ${row.encoding}: ${e.message}`);
        }
        if (decoded && !decoded.equals(readFileSync(join(DIST, file)))) problems.push(`${where}: the decoded body is not the file`);
        if (res.headers["content-language"] !== undefined) {
          problems.push(`${where}: Content-Language ${res.headers["content-language"]} (".br" is not Breton)`);
        }
      }
      assert.deepEqual(problems, []);
    });

    test("compressible files say Vary: Accept-Encoding to every client", async () => {
      const problems = [];
      const rows = (await fetchAll()).filter((r) => hasSiblings(r.file));
      assert.ok(rows.length > 0, "dist/ has files with .br/.gz siblings");
      for (const { vary, where } of rows) {
        if (!String(vary ?? "").toLowerCase().split(/\s*,\s*/).includes("accept-encoding")) problems.push(`${where}: Vary ${vary}`);
      }
      assert.deepEqual(problems, []);
    });

    test("cache headers: content-hashed names immutable for a year, index.html, sw.js, the manifest and the rest no-cache", async () => {
      for (const name of ["index.html", "sw.js", "manifest.webmanifest"]) {
        assert.ok(files.includes(name) && !isContentHashed(name), `dist/ has ${name}, a name without a hash`);
      }
      assert.ok(files.some((f) => f.startsWith("pkg/") && isContentHashed(f)), "dist/pkg/ has hashed modules");
      const problems = [];
      for (const { file, cache, where } of await fetchAll()) {
        const expected = isContentHashed(file) ? IMMUTABLE : "no-cache";
        if (cache !== expected) problems.push(`${where}: Cache-Control ${cache}, expected ${expected}`);
      }
      assert.deepEqual(problems, []);
      // The folder URL is index.html, revalidated too.
      const server = servers[key];
      const folder = await get(server.base, { "Accept-Encoding": "identity" });
      assert.equal(folder.status, 200);
      assert.ok(folder.body.equals(readFileSync(join(DIST, "index.html"))), "the folder URL serves index.html");
      assert.equal(folder.headers["cache-control"], "no-cache", "the folder URL: Cache-Control");
    });

    test("/labs/robotics without its slash redirects (301) to /labs/robotics/, as docs/hosting.md says", async () => {
      const server = servers[key];
      const bare = server.origin + SUB_PATH.slice(0, -1);
      const res = await get(bare);
      assert.equal(res.status, 301, `${bare}: status`);
      assert.equal(new URL(res.headers.location, bare).href, server.base, "Location is the folder");
      assert.match(hosting, /`\/labs\/robotics` \(no slash\)[^]*?301/, "docs/hosting.md says what a host does with the URL without its slash");
      await withPage(lab, {}, async (page) => {
        await page.goto(bare);
        await page.waitForSelector("[data-page=home]:not([hidden]) a.card");
        assert.equal(page.url(), server.base, "the browser ends on the folder URL");
      });
    });

    test("every experiment's Simulation tab draws, with no console error", async (t) => {
      const server = servers[key];
      let ids = [];
      await withPage(lab, {}, async (page) => {
        await open(lab, page, "#/");
        ids = await page.$$eval("a.card[data-experiment]", (cards) => cards.map((c) => c.dataset.experiment));
      });
      assert.deepEqual([...ids].sort(), builtExperimentIds().sort(), `the home page lists the experiments (${ids.length})`);
      for (const id of ids) {
        await t.test(id, () =>
          withPage(lab, {}, async (page) => {
            let errors = 0;
            let wasmEncoding = null;
            page.on("console", (msg) => msg.type() === "error" && errors++);
            page.on("pageerror", () => errors++);
            page.on("response", async (res) => {
              if (new URL(res.url()).pathname.endsWith(".wasm")) {
                wasmEncoding = (await res.allHeaders())["content-encoding"] ?? "identity";
              }
            });
            await open(lab, page, `#/${id}/simulation`);
            const colours = await simulationDraws(page, id);
            consoleRows.push({ server: server.name, id, errors, colours, wasmEncoding });
            assert.equal(errors, 0, `${server.name}, ${id}: console errors`);
          }),
        );
      }
    });

    test("offline after one visit: every experiment opens and draws with the network off", () =>
      withPage(lab, { serviceWorkers: "allow" }, async (page, context) => {
        const server = servers[key];
        await open(lab, page, "#/");
        const ids = await page.$$eval("a.card[data-experiment]", (cards) => cards.map((c) => c.dataset.experiment));
        await open(lab, page, `#/${ids[0]}/simulation`);
        const { scope, cached } = await workerReady(page);
        assert.equal(scope, server.base, "the worker's scope is the lab's folder");
        assert.ok(cached > 20, `the whole site is cached (${cached} files)`);
        await context.setOffline(true);
        for (const id of ids) {
          await page.goto(`${server.base}index.html#/${id}/simulation`);
          await waitReady(page);
          await simulationDraws(page, id);
        }
        await page.reload();
        await waitReady(page);
        await simulationDraws(page, ids[ids.length - 1]);
        await page.goto(server.base);
        await page.waitForSelector("[data-page=home]:not([hidden]) a.card");
        await context.setOffline(false);
      }));
  });
}
