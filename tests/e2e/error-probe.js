// Put first in <head> by the test server (startServer's `probe` option) for
// browsers whose driver reports no console: records console errors, uncaught
// exceptions and unhandled rejections in window.__labProblems.
(() => {
  const problems = [];
  window.__labProblems = problems;
  const error = console.error.bind(console);
  console.error = (...args) => {
    problems.push(`console error: ${args.map(String).join(" ")}`);
    error(...args);
  };
  window.addEventListener("error", (e) => {
    // A resource that failed to load (script, image) fires a non-bubbling
    // error on the element; capture sees it as well.
    const target = e.target && e.target !== window ? ` (${e.target.src || e.target.href || e.target.tagName})` : "";
    problems.push(`uncaught exception: ${e.message || "load error"}${target}`);
  }, true);
  window.addEventListener("unhandledrejection", (e) => problems.push(`unhandled rejection: ${e.reason}`));
})();
