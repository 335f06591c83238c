// The test LMS: scorm-again's Scorm12API as `window.API`, every call it gets
// recorded in `window.lmsLog`, then the SCO named by `?sco=<id>` (default:
// the manifest's first item) launched in the iframe from the package's
// imsmanifest.xml, as an LMS does. `window.SAVED_CMI` (set by the test
// before the page loads) is the cmi an LMS kept from an earlier session.
// Like some real LMSs, it drops the launch URL's `#` fragment (issue 24);
// `?launch-query=<pairs>` appends to the launch's query, as a package built
// with `cargo xtask dist --scorm --attempts 2 --score last` writes it;
// `?lms-query=<pairs>` appends the LMS's own query after a second `?` (as
// some LMSs do) and `?bare=1` launches `index.html` with no query at all.
// `?student=`, `?mode=` and `?credit=` set cmi.core.student_id (default
// s-001), lesson_mode and credit. Every API call the SCO makes is also
// recorded with its result in `window.lmsCalls` ([name, ...args, result]),
// and the runtime posts each commit to the test server (`/lms/commit`).
(async () => {
  const status = document.getElementById("lms-status");
  const log = (window.lmsLog = []);
  // Commits go to the test server as a real LMS's do (the runtime posts
  // the cmi: a synchronous request for LMSCommit, a beacon for LMSFinish).
  const api = new Scorm12API({ autocommit: false, logLevel: 5, lmsCommitUrl: "commit" });
  for (const name of ["LMSInitialize", "LMSCommit", "LMSFinish"]) {
    api.on(name, () => log.push([name]));
  }
  const calls = (window.lmsCalls = []);
  for (const name of ["LMSInitialize", "LMSGetValue", "LMSSetValue", "LMSCommit", "LMSFinish", "LMSGetLastError", "LMSGetErrorString"]) {
    const call = api[name].bind(api);
    api[name] = (...args) => {
      const result = call(...args);
      calls.push([name, ...args, result]);
      return result;
    };
  }
  api.on("LMSSetValue.cmi.*", (element, value) => log.push(["LMSSetValue", element, value]));

  const pkg = "content/1/";
  const manifest = new DOMParser().parseFromString(
    await (await fetch(pkg + "imsmanifest.xml")).text(),
    "application/xml",
  );
  const items = [...manifest.getElementsByTagName("item")];
  const wanted = new URLSearchParams(location.search).get("sco");
  const item = wanted ? items.find((i) => i.getAttribute("identifier") === `item-${wanted}`) : items[0];
  const resource = [...manifest.getElementsByTagName("resource")].find(
    (r) => r.getAttribute("identifier") === item.getAttribute("identifierref"),
  );
  const mastery = item.getElementsByTagNameNS("*", "masteryscore")[0]?.textContent ?? "";

  if (window.SAVED_CMI) {
    api.loadFromJSON(window.SAVED_CMI);
    api.cmi.core.entry = "resume";
  } else {
    api.cmi.core.entry = "ab-initio";
  }
  api.cmi.student_data.mastery_score = mastery;
  const asked = new URLSearchParams(location.search);
  api.cmi.core.student_id = asked.get("student") ?? "s-001";
  if (asked.get("mode")) api.cmi.core.lesson_mode = asked.get("mode");
  if (asked.get("credit")) api.cmi.core.credit = asked.get("credit");
  api.cmi.core.student_name = "Student, Test";
  window.API = api;
  window.lmsLaunch = resource.getAttribute("href");
  const extra = new URLSearchParams(location.search).get("launch-query");
  let launched = window.lmsLaunch.split("#")[0];
  if (extra) launched += (launched.includes("?") ? "&" : "?") + extra;
  const lmsQuery = asked.get("lms-query");
  if (lmsQuery) launched += "?" + lmsQuery;
  if (asked.get("bare")) launched = "index.html";
  window.lmsLaunched = launched;
  // `?origin=` puts the SCO on another origin (where it must not reach the API).
  const origin = new URLSearchParams(location.search).get("origin");
  const here = location.pathname.replace(/[^/]*$/, "");
  document.getElementById("sco").src = (origin ? origin + here : "") + pkg + launched;
  status.textContent = `launched ${window.lmsLaunch}`;
})().catch((e) => {
  document.getElementById("lms-status").textContent = `LMS error: ${e}`;
  throw e;
});
