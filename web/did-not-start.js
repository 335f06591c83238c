// A classic script, not a module: it runs where the lab's module scripts
// cannot. A browser runs a module script (main.js, check.js) only when the
// server sends it with a JavaScript type; a host that sends `.js` as
// application/octet-stream would leave the page on "Loading…" with no word.
// The page loads this file after its module script, with `defer`: browsers
// run the two in that order, so by now the module has set
// `window.labStarted`, or it never will. Then the page says so, with the
// type the server sent when that is the cause. (A file of the site, not an
// inline script: the page's Content-Security-Policy allows only those.)
(() => {
  const module = document.querySelector("script[type=module][src]");
  const box = document.getElementById("fatal");
  if (window.labStarted || !module || !box) return;
  const name = module.getAttribute("src").split("?")[0];
  const say = (text) => {
    box.querySelector(".fatal-text").textContent = `The lab could not start: ${text}`;
    box.hidden = false;
    for (const el of document.querySelectorAll(".loading")) el.remove();
  };
  say(`${name} did not run.`);
  fetch(module.src).then((r) => {
    const type = r.headers.get("Content-Type");
    if (r.ok && !/javascript/i.test(type)) say(`the server sent ${name} as “${type}”, not text/javascript (docs/hosting.md, “File types”).`);
  }, () => {});
})();
