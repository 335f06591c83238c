// Experiments 6 (A*) and 10 (RRT*) driven like a student would: paint walls,
// Shift-click the start, plan and drive, read the open list and the
// comparison, load the arena map and a broken one, reopen a maze from its
// link, grow an RRT* tree and download its cost curve.

import { test } from "node:test";
import assert from "node:assert/strict";
import { readFile } from "node:fs/promises";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { DESKTOP, open, readNumber, readouts, runUntil, screenshot, settle, useLab, withPage, worldToPage } from "./helpers.mjs";

const lab = useLab();
const ART = "article.exp:not([hidden])";
const PHONE_390 = { width: 390, height: 844 };
const ARENA = join(resolve(dirname(fileURLToPath(import.meta.url)), "..", ".."), "assets", "maps", "arena.map");

/** Page point of the centre of grid cell (col, row) of an A* grid `rows` high (row 0 at the top). */
function cellToPage(page, col, row, rows) {
  return worldToPage(page, col + 0.5, rows - row - 0.5);
}

function waitStatus(page, pattern, timeout = 20_000) {
  return runUntil(
      page,
    (source) => new RegExp(source).test(document.querySelector("article.exp:not([hidden]) .sim-status").textContent),
    pattern.source,
    { timeout },
  );
}

const walls = async (page) => Number((await readouts(page)).grid.match(/(\d+) walls/)[1]);

test("astar: drag paints walls, Shift-click moves the start, Plan & drive finds the path; open list and Compare tables render", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation?rate=18");
    assert.equal(await page.locator(`${ART} canvas.sim-canvas`).getAttribute("data-touch"), "all");
    const before = await walls(page);
    // Paint a wall down column 25, rows 16 to 22 (free in the default grid).
    const a = await cellToPage(page, 25, 16, 24);
    const b = await cellToPage(page, 25, 22, 24);
    await page.mouse.move(a.x, a.y);
    await page.mouse.down();
    await page.mouse.move(b.x, b.y, { steps: 8 });
    await page.mouse.up();
    // The readout follows a drag at the text's pace (every 250 ms) and
    // shows its last value when it ends: wait for that one.
    await runUntil(page, (n) => /(\d+) walls/.exec(document.querySelector("[data-readout=grid]").textContent)[1] >= n, before + 7);
    assert.equal(await walls(page), before + 7, "seven cells painted, no gaps");
    // Shift-click sets the start.
    const s = await cellToPage(page, 2, 2, 24);
    await page.keyboard.down("Shift");
    await page.mouse.click(s.x, s.y);
    await page.keyboard.up("Shift");
    await runUntil(page, () => /sx=2&sy=2/.test(location.hash));
    assert.equal(await walls(page), before + 7, "Shift-click paints nothing");
    assert.match(await page.evaluate(() => location.hash), /walls=32x24\./);

    await page.click(`${ART} button[data-action=plan]`);
    // The open list panel: the cell being expanded is highlighted.
    const openList = page.locator(`${ART} [data-table=open]`);
    await runUntil(page, () => Boolean(document.querySelector("article.exp:not([hidden]) tr.current")));
    assert.deepEqual(await openList.locator("thead th").allInnerTexts(), ["", "cell", "g", "h", "f"]);
    assert.equal(await openList.locator("tr.current td").first().innerText(), "expanding");
    await screenshot(page, "astar-searching");
    await waitStatus(page, /^arrived: path cost/);
    const r = await readouts(page);
    assert.ok(readNumber(r.path_cost) > 20, `path cost ${r.path_cost}`);
    assert.ok(Number(r.expanded) > Number(r.path_cells), `${r.expanded} expanded, ${r.path_cells} on the path`);

    await page.click(`${ART} button[data-action=compare]`);
    const compare = page.locator(`${ART} [data-table=compare]`);
    await runUntil(page, () => document.querySelectorAll("article.exp:not([hidden]) [data-table=compare] tbody tr").length >= 4);
    const rows = await compare.locator("tbody tr").evaluateAll((trs) => trs.map((tr) => [...tr.cells].map((c) => c.textContent)));
    assert.equal(rows.length, 4);
    assert.match(rows[0][0], /^A\* \(Octile\)/);
    assert.equal(rows[1][0], "Dijkstra");
    assert.equal(rows[1][3], "1.00", "Dijkstra is the optimum");
    assert.equal(rows[0][2], rows[1][2], "octile A* is optimal too");
    assert.ok(Number(rows[0][1]) <= Number(rows[1][1]), "A* expands no more than Dijkstra");
    assert.match(rows[2][0], /^Greedy/);
    assert.ok(Number(rows[2][3]) >= 1);
    await screenshot(page, "astar-compare");
  }));

/** The view's world box [minX, minY, maxX, maxY] (a zoomed window on a phone). */
async function viewBox(page) {
  return (await page.locator(`${ART} canvas.sim-canvas`).getAttribute("data-view")).split(",").map(Number);
}

test("astar: a finger paints walls too: the canvas takes the touch and the page does not scroll", () =>
  withPage(lab, { viewport: PHONE_390, hasTouch: true, clock: true }, async (page, context) => {
    await open(lab, page, "#/astar/simulation");
    await page.locator(`${ART} canvas.sim-canvas`).scrollIntoViewIfNeeded();
    const before = await walls(page);
    const scrollY = await page.evaluate(() => scrollY);
    // Seven free cells of column 6 inside the view (a phone may show a
    // zoomed window: stay off its one-cell pan band).
    const [, , , maxY] = await viewBox(page);
    const top = Math.ceil(24 - maxY) + 2;
    const a = await cellToPage(page, 6, top, 24);
    const b = await cellToPage(page, 6, top + 6, 24);
    const cdp = await context.newCDPSession(page);
    const touch = (type, p) =>
      cdp.send("Input.dispatchTouchEvent", { type, touchPoints: p ? [{ x: Math.round(p.x), y: Math.round(p.y), id: 1 }] : [] });
    await touch("touchStart", a);
    for (let i = 1; i <= 8; i++) await touch("touchMove", { x: a.x, y: a.y + ((b.y - a.y) * i) / 8 });
    await touch("touchEnd");
    // The readout follows a drag at the text's pace (every 250 ms) and
    // shows its last value when it ends: wait for that one.
    await runUntil(page, (n) => /(\d+) walls/.exec(document.querySelector("[data-readout=grid]").textContent)[1] >= n, before + 7);
    assert.equal(await walls(page), before + 7, "a vertical swipe painted seven cells");
    assert.equal(await page.evaluate(() => scrollY), scrollY, "the page did not scroll");
  }));

test("astar step 1: on a 390 px phone the grid's cells are at least 24 CSS px under a finger", () =>
  withPage(lab, { viewport: PHONE_390, hasTouch: true, clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation?rate=18");
    const canvas = page.locator(`${ART} canvas.sim-canvas`);
    const box = await canvas.boundingBox();
    const [minX, minY, maxX, maxY] = await viewBox(page);
    const cellPx = Math.min(box.width / (maxX - minX), box.height / (maxY - minY));
    assert.ok(cellPx >= 24, `${cellPx.toFixed(1)} px per cell`);
    assert.doesNotMatch(await page.evaluate(() => location.hash), /pan|zoom/, "the view is not in the link");
  }));

test("astar: the arena map loads from the file input, a malformed map is refused with its line, and the link keeps the walls", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation");
    const input = page.locator(`${ART} input.file-input`);
    await input.setInputFiles(ARENA);
    await runUntil(page, () => /^49 × 49/.test(document.querySelector("[data-readout=grid]").textContent));
    const message = page.locator(`${ART} .sim-message`);
    await runUntil(page, () => /Loaded “arena\.map”/.test(document.querySelector("article.exp:not([hidden]) .sim-message").textContent));
    await runUntil(page, () => /walls=49x49\./.test(location.hash));
    const grid = (await readouts(page)).grid;

    await input.setInputFiles({
      name: "broken.map",
      mimeType: "text/plain",
      buffer: Buffer.from("type octile\nheight 2\nwidth 3\nmap\n...\n.x.\n"),
    });
    await runUntil(page, () => /broken\.map/.test(document.querySelector("article.exp:not([hidden]) .sim-message").textContent));
    assert.match(await message.innerText(), /Could not load “broken\.map”: .*line 6/);
    assert.equal((await readouts(page)).grid, grid, "the arena map is kept");

    await page.click(`${ART} button[data-action=plan]`);
    await waitStatus(page, /^arrived/);
    // A reload of the link gives the same grid.
    const hash = await page.evaluate(() => location.hash);
    await page.reload();
    await runUntil(page, () => document.body.dataset.ready === "1");
    assert.equal(await page.evaluate(() => location.hash), hash);
    assert.equal((await readouts(page)).grid, grid);
    // Save file gives the map back.
    const [download] = await Promise.all([page.waitForEvent("download"), page.click(`${ART} [data-export=text]`)]);
    assert.equal(download.suggestedFilename(), "grid.map");
    const text = await readFile(await download.path(), "utf8");
    assert.match(text, /^type octile\nheight 49\nwidth 49\nmap\n/);
  }));

test("astar step 6: a 512 × 512 maze travels in its link as its seed and reopens as the same maze", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation?size=5&rate=50");
    await page.click(`${ART} button[data-action=maze]`);
    await runUntil(page, () => /maze=512x512\.1/.test(location.hash) && !/&walls=/.test(location.hash));
    const grid = (await readouts(page)).grid;
    assert.match(grid, /^512 × 512, \d+ walls/);
    assert.match((await readouts(page)).link, /holds the walls/);
    await page.click(`${ART} button[data-action=plan]`);
    await waitStatus(page, /^(path found|arrived)/, 30_000);
    await screenshot(page, "astar-512-maze");
    await page.reload();
    await runUntil(page, () => document.body.dataset.ready === "1");
    assert.equal((await readouts(page)).grid, grid, "the link rebuilt the maze, not an empty grid");
  }));

test("astar: a link that could not carry its walls says so and asks for the .map file", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/astar/simulation?size=6&nowalls=600x400&ends=1.0.599.399");
    await waitStatus(page, /walls not in the link: load this 600 × 400 grid's \.map file/);
    assert.match((await readouts(page)).link, /load the \.map file/);
    assert.equal(await page.locator(`${ART} input.file-input`).count(), 1, "the page offers to load a .map");
  }));

test("rrtstar: the best length shrinks as the tree grows, Compare overlays three curves, and the cost CSV downloads", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/rrtstar/simulation?batch=8&iters=4000");
    await page.click(`${ART} button[data-action=grow]`);
    await runUntil(page, () => /\d/.test(document.querySelector("[data-readout=best]").textContent), null, { timeout: 20_000 });
    const first = readNumber((await readouts(page)).best);
    await runUntil(
      page,
      (b) => Number.parseFloat(document.querySelector("[data-readout=best]").textContent) < b - 0.05,
      first,
      { timeout: 30_000 },
    );
    await screenshot(page, "rrtstar-growing");
    await waitStatus(page, /^done: best path/, 60_000);
    const r = await readouts(page);
    assert.ok(readNumber(r.best) < first, `${r.best} < ${first}`);
    assert.ok(Number(r.rewires) > 0);
    const [csv] = await Promise.all([page.waitForEvent("download"), page.click(`${ART} [data-plot-csv=cost]`)]);
    assert.equal(csv.suggestedFilename(), "rrtstar-seed1-cost.csv");
    const lines = (await readFile(await csv.path(), "utf8")).trim().split(/\r?\n/);
    assert.equal(lines[0], "Iteration,RRT* (m)");
    const costs = lines.slice(1).map((l) => Number(l.split(",")[1]));
    assert.ok(costs.length > 10);
    assert.ok(costs.every((c, i) => i === 0 || c <= costs[i - 1]), "the best cost never increases");

    await page.click(`${ART} button[data-action=compare]`);
    await waitStatus(page, /^comparing/);
    await waitStatus(page, /^done: best path/, 60_000);
    const table = page.locator(`${ART} [data-table=compare] tbody tr`);
    assert.equal(await table.count(), 3);
    const [both] = await Promise.all([page.waitForEvent("download"), page.click(`${ART} [data-plot-csv=cost]`)]);
    const head = (await readFile(await both.path(), "utf8")).split(/\r?\n/)[0];
    assert.match(head, /RRT \(m\).*RRT\* \(m\).*Informed RRT\* \(m\)/);
    await page.click(`${ART} button[data-action=drive]`);
    await waitStatus(page, /^arrived at the goal/);
  }));

for (const viewport of [DESKTOP, PHONE_390]) {
  test(`screenshots at ${viewport.width}px: both planning Simulation tabs fit without sideways scrolling`, () =>
    withPage(lab, { viewport, clock: true }, async (page) => {
      await open(lab, page, "#/astar/simulation");
      await page.click(`${ART} button[data-action=plan]`);
      await runUntil(page, () => Boolean(document.querySelector("article.exp:not([hidden]) [data-table=open] tr.current")));
      await settle(page);
      assert.ok((await page.evaluate(() => document.documentElement.scrollWidth)) <= viewport.width);
      await screenshot(page, `astar-sim-${viewport.width}`);
      await page.goto(page.url().replace(/#.*/, "#/rrtstar/simulation?iters=1500&batch=60"));
      await runUntil(page, () => document.body.dataset.ready === "1");
      await page.click(`${ART} button[data-action=grow]`);
      await waitStatus(page, /^done/, 30_000);
      await settle(page);
      assert.ok((await page.evaluate(() => document.documentElement.scrollWidth)) <= viewport.width);
      await screenshot(page, `rrtstar-sim-${viewport.width}`);
    }));
}
