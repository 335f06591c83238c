// "Check a report" (check.html): reads a lab report, takes its
// machine-readable record (<script type="application/json"
// id="lab-report-data">, data that no browser runs) and the score printed in
// it, grades the record's answers again with the wasm module that holds the
// report's experiment (the one the lab loads for it; the list is in this
// page's <meta name=lab-module> tags), and says whether the printed score
// matches. Nothing is sent anywhere; every text from the file is shown as
// text.

// did-not-start.js, which runs after this file, looks for it (see there).
window.labStarted = true;
const result = document.getElementById("check-result");
const input = document.getElementById("check-file");
const drop = document.querySelector(".check-drop");
const MODULES = [...document.querySelectorAll("meta[name=lab-module]")].map((m) => ({
  ids: m.dataset.experiments.split(" "),
  js: m.dataset.js,
  wasm: m.dataset.wasm,
}));
const glues = new Map(); // glue path -> Promise of the started module

/** The started wasm module that holds experiment `id`. */
function glueFor(id) {
  const mod = MODULES.find((m) => m.ids.includes(id));
  if (!mod) return Promise.reject(new Error(`this lab has no experiment called “${id}”`));
  if (!glues.has(mod.js)) {
    const start = (async () => {
      const glue = await import(new URL(mod.js, import.meta.url).href);
      await glue.default({ module_or_path: new URL(mod.wasm, import.meta.url) });
      return glue;
    })();
    start.catch(() => glues.delete(mod.js));
    glues.set(mod.js, start);
  }
  return glues.get(mod.js);
}

/** Replaces the result with `lines` ([tag, text] pairs), `tone` good | bad | neutral. */
function show(tone, lines) {
  result.replaceChildren();
  result.dataset.verdict = tone;
  for (const [tag, text] of lines) {
    const el = document.createElement(tag);
    el.textContent = text;
    result.append(el);
  }
}

const scoreText = (s) => `${s[0]} / ${s[1]}`;
const same = (a, b) => Array.isArray(a) && Array.isArray(b) && a.length === 2 && a[0] === b[0] && a[1] === b[1];

/** Checks the text of one report file; returns the verdict shown. */
async function check(text, fileName) {
  // The report's style sheet is left out: this page's policy would refuse
  // it (a console error) and the check needs no styles.
  const doc = new DOMParser().parseFromString(text.replace(/<style[\s\S]*?<\/style>/gi, ""), "text/html");
  const title = doc.querySelector("h1")?.textContent.trim() || "(no title)";
  const who = ["name", "group"]
    .map((f) => doc.querySelector(`[data-field=${f}]`)?.textContent.trim())
    .filter(Boolean)
    .join(", ");
  const date = doc.querySelector(".date")?.textContent.trim() ?? "";
  const about = ["p", `${fileName}: ${title}${who ? ` · ${who}` : ""}${date ? ` · ${date}` : ""}`];
  const node = doc.getElementById("lab-report-data");
  if (!node) {
    return show("bad", [["strong", "No record to check."], about,
      ["p", "This file has no machine-readable record: it is not a lab report made by this lab, or it was made before reports carried one, or the record was removed."]]);
  }
  let record;
  try {
    record = JSON.parse(node.textContent);
  } catch {
    return show("bad", [["strong", "The record is damaged."], about, ["p", "The report's record is not valid JSON: the file was edited."]]);
  }
  const printedMatch = /Score:\s*(\d+)\s*\/\s*(\d+)/.exec(doc.querySelector(".quiz .score")?.textContent ?? "");
  const printed = printedMatch ? [Number(printedMatch[1]), Number(printedMatch[2])] : null;
  const quiz = record?.quiz;
  if (!quiz) {
    if (printed) {
      return show("bad", [["strong", `✗ The report prints a score (${scoreText(printed)}) but its record holds no submitted attempt.`], about,
        ["p", "The file was edited."]]);
    }
    return show("neutral", [["strong", "Nothing to check: the self-assessment had not been submitted when this report was made."], about]);
  }
  if (typeof record.id !== "string" || typeof quiz.seed !== "string" || !Array.isArray(quiz.answers)) {
    return show("bad", [["strong", "The record is incomplete."], about, ["p", "The record lacks the experiment, the seed or the answers: the file was edited."]]);
  }
  let glue;
  try {
    glue = await glueFor(record.id);
  } catch (error) {
    return show("bad", [["strong", "Cannot grade this report."], about, ["p", `The question generators could not be loaded (${error.message ?? error}).`]]);
  }
  const answers = quiz.answers.map((a) => (typeof a === "number" || typeof a === "string" ? a : null));
  const graded = [...glue.report_quiz_score(record.id, quiz.seed, answers)];
  if (graded.length !== 2) {
    return show("bad", [["strong", "✗ The record does not fit this experiment's questions."], about,
      ["p", `Attempt seed ${quiz.seed} draws a different number of questions than the ${answers.length} answers kept: the file was edited, or made by another version of the lab.`]]);
  }
  const seed = ["p", `Experiment ${record.id}, attempt seed ${quiz.seed}: the ${graded[1]} answers kept in the file score ${scoreText(graded)}.`];
  if (!printed) {
    return show("bad", [["strong", "✗ The report prints no score."], about, seed, ["p", "The score line was removed from the file."]]);
  }
  if (same(printed, graded) && same(quiz.score, graded)) {
    return show("good", [["strong", `✓ The printed score, ${scoreText(printed)}, matches the answers in the file.`], about, seed,
      ["p", "This shows the score was not edited on its own. It does not show who made the report (a classmate's report with the name changed passes) nor that the answers are the student's own (answers and score edited together pass); the LMS score is the authority."]]);
  }
  return show("bad", [["strong", `✗ The printed score, ${scoreText(printed)}, does not match: the answers in the file score ${scoreText(graded)}.`], about, seed,
    ["p", "The score was edited after the report was made."]]);
}

async function checkFile(file) {
  if (!file) return;
  show("neutral", [["p", `Checking ${file.name}…`]]);
  try {
    await check(await file.text(), file.name);
  } catch (error) {
    show("bad", [["strong", "Cannot read this file."], ["p", String(error.message ?? error)]]);
  }
}

input.addEventListener("change", () => checkFile(input.files[0]));
for (const kind of ["dragenter", "dragover"]) {
  drop.addEventListener(kind, (e) => {
    e.preventDefault();
    drop.classList.add("over");
  });
}
drop.addEventListener("dragleave", () => drop.classList.remove("over"));
drop.addEventListener("drop", (e) => {
  e.preventDefault();
  drop.classList.remove("over");
  checkFile(e.dataTransfer?.files?.[0]);
});
