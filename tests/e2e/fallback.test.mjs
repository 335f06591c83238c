// Graceful degradation: no 2D canvas context (old or locked-down browsers,
// some privacy modes). Reading material must still work; the simulation
// says clearly that it cannot draw.

import { test } from "node:test";
import assert from "node:assert/strict";
import { open, useLab, withPage } from "./helpers.mjs";

const lab = useLab();

test("without a 2D canvas context the reading tabs still work and the simulation shows .sim-error", () =>
  withPage(
    lab,
    {
      // Console errors are expected here; uncaught exceptions still fail the test.
      allowConsoleErrors: true,
      initScript: () => {
        HTMLCanvasElement.prototype.getContext = function () {
          return null;
        };
      },
    },
    async (page) => {
      await open(lab, page, "#/fk/aim");
      for (const slug of ["aim", "theory"]) {
        await page.click(`[role=tab][data-tab="${slug}"]`);
        const panel = page.locator(`[role=tabpanel][data-panel="${slug}"]`);
        assert.ok(await panel.isVisible(), `${slug} panel visible`);
        const text = (await panel.innerText()).trim();
        assert.ok(text.length > 40, `${slug} panel shows its text (${text.length} chars)`);
      }
      await page.click('[role=tab][data-tab="simulation"]');
      const error = page.locator('[data-panel="simulation"] .sim-error');
      await error.waitFor({ state: "visible" });
      assert.ok((await error.innerText()).trim().length > 0, "the error says what is wrong");
    },
  ));
