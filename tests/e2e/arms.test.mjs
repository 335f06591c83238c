// Experiments 2, 3 and 9 driven like a student would: click targets, toggle
// the elbow, sweep the workspace, watch the DLS iterations converge.

import { test } from "node:test";
import assert from "node:assert/strict";
import { open, readNumber, readouts, runFor, runUntil, screenshot, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

/** Page coordinates of world point (x, y) on the simulation canvas (uniform fit, y up). */
async function worldToPage(page, x, y) {
  const box = await page.locator("canvas.sim-canvas").boundingBox();
  const [minX, minY, maxX, maxY] = (await page.locator("canvas.sim-canvas").getAttribute("data-view"))
    .split(",")
    .map(Number);
  const scale = Math.min(box.width / (maxX - minX), box.height / (maxY - minY));
  return {
    x: box.x + box.width / 2 + (x - (minX + maxX) / 2) * scale,
    y: box.y + box.height / 2 - (y - (minY + maxY) / 2) * scale,
  };
}

async function clickWorld(page, x, y) {
  const p = await worldToPage(page, x, y);
  await page.mouse.click(p.x, p.y);
}

const metres = (text) => Number.parseFloat(text);
const degrees = (text) => Number.parseFloat(text);

/** Waits until the status badge matches `pattern`. */
async function waitStatus(page, pattern) {
  await runUntil(
      page,
    (source) => new RegExp(source).test(document.querySelector(".sim-status").textContent),
    pattern.source,
  );
  return page.locator(".sim-status").textContent();
}

test("ik: a clicked target is solved, the arm animates there, and the elbow toggle flips the bend", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/ik/simulation");
    await clickWorld(page, 0.9, 0.8);
    await waitStatus(page, /^in reach$/);
    // The move takes 0.8 s; wait until the readouts match the target.
    await runUntil(page, () => {
      const x = Number.parseFloat(document.querySelector("[data-readout=x]").textContent);
      const y = Number.parseFloat(document.querySelector("[data-readout=y]").textContent);
      return Math.hypot(x - 0.9, y - 0.8) < 0.02;
    });
    let r = await readouts(page);
    const up = { t1: degrees(r.theta1), t2: degrees(r.theta2) };
    assert.ok(up.t2 <= 0, `elbow up has θ2 ≤ 0, got ${r.theta2}`);
    // FK of the solved angles (L1 = 1, L2 = 0.7) is where the pointer clicked (within a pixel).
    const rad = Math.PI / 180;
    const x = Math.cos(up.t1 * rad) + 0.7 * Math.cos((up.t1 + up.t2) * rad);
    const y = Math.sin(up.t1 * rad) + 0.7 * Math.sin((up.t1 + up.t2) * rad);
    assert.ok(Math.hypot(x - 0.9, y - 0.8) < 0.02, `FK(IK) = (${x}, ${y})`);
    // Screen readers hear the settled result, not the pose the arm started
    // from: the readouts, then (the run has ended) the scene's description.
    await runUntil(
      page,
      (t1) => /θ₁ (solved: )?/.test(document.querySelector(".sim-live").textContent)
        && document.querySelector(".sim-live").textContent.includes(t1),
      r.theta1,
    );
    assert.match(await page.locator(".sim-live").textContent(), /in reach/);

    await page.locator("input[data-param=elbow][value='0']").check({ force: true });
    await runUntil(page, () => Number.parseFloat(document.querySelector("[data-readout=theta2]").textContent) > 0);
    await runFor(page, 1000);
    r = await readouts(page);
    assert.ok(degrees(r.theta2) > 0, "elbow down has θ2 > 0");
    assert.ok(Math.abs(degrees(r.theta2) + up.t2) < 0.15, "the branches mirror θ2");
    assert.ok(Math.hypot(metres(r.x) - 0.9, metres(r.y) - 0.8) < 0.02, "same tip, other bend");
    assert.match(await page.evaluate(() => location.hash), /elbow=0/);
    await screenshot(page, "ik-elbow-down");
  }));

test("ik: a target outside the annulus shows 'out of reach', says why, and the arm stretches toward it", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/ik/simulation");
    await clickWorld(page, 2.2, 0.0);
    const status = await waitStatus(page, /out of reach/);
    assert.match(status, /target 2\.\d\d m away > L₁ \+ L₂ = 1\.70 m/);
    // The arm reaches out along the line to the target (|tip| = L1 + L2, on the x axis).
    await runUntil(page, () => {
      const x = Number.parseFloat(document.querySelector("[data-readout=x]").textContent);
      const y = Number.parseFloat(document.querySelector("[data-readout=y]").textContent);
      return Math.abs(x - 1.7) < 0.02 && Math.abs(y) < 0.02;
    });
    // Inside the inner hole (|p| < |L1 − L2| = 0.3) is out of reach too.
    await clickWorld(page, 0.1, 0.05);
    await waitStatus(page, /out of reach/);
  }));

test("workspace: Sweep fills the cloud over many frames and the radii match theory", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/workspace/simulation?l1=1&l2=0.5&l3=0.2&n=20000");
    await page.locator("button[data-action=sweep]").click();
    await runUntil(page, () => /sweeping/.test(document.querySelector(".sim-status").textContent));
    await waitStatus(page, /^swept 20000 samples$/);
    const r = await readouts(page);
    assert.equal(r.samples, "20000 / 20000");
    assert.equal(r.outer_theory, "1.700 m");
    assert.equal(r.inner_theory, "0.300 m");
    assert.ok(Math.abs(metres(r.outer) - 1.7) < 0.02, `outer measured ${r.outer}`);
    assert.ok(Math.abs(metres(r.inner) - 0.3) < 0.03, `inner measured ${r.inner}`);
    await screenshot(page, "workspace-swept");
    // Changing a length clears the cloud: the status is the state (ready to
    // sweep); "settings changed: sweep again" is a notice beside it.
    await page.locator("input[type=text][data-param=l3]").fill("0.6");
    await page.locator("input[type=text][data-param=l3]").press("Enter");
    await waitStatus(page, /^ready to sweep$/);
    const cleared = await readouts(page);
    assert.equal(cleared.samples, "0");
    assert.equal(cleared.outer, "--");
  }));

test("dls: a reachable click converges below 1e-6 m; an unreachable one settles on the boundary", () =>
  withPage(lab, { clock: true }, async (page) => {
    await open(lab, page, "#/dls/simulation?n=7&rate=60");
    assert.equal(await page.locator("input[type=range][data-param=n]").inputValue(), "7");
    await clickWorld(page, 1.2, 0.9);
    const status = await waitStatus(page, /converged|closest|stopped/);
    assert.match(status, /^converged in \d+ iterations$/);
    const r = await readouts(page);
    assert.ok(Number(r.iterations) > 0);
    assert.ok(readNumber(r.error) < 1e-6, `error ${r.error}`);
    assert.ok(Number.parseFloat(r.w) > 0);
    await clickWorld(page, 0, 2.6);
    await waitStatus(page, /closest reachable pose/);
    const far = await readouts(page);
    assert.ok(Math.abs(readNumber(far.error) - 0.2) < 0.01, `error to (0, 2.6) is 2.6 − 2.4: ${far.error}`);
    await screenshot(page, "dls-boundary");
  }));
