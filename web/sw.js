// The lab's service worker: after one visit, every experiment works offline,
// including ones never opened. `cargo xtask dist` fills in VERSION (the site's
// content hash, the same as the `?v=` stamps) and FILES (every file of the
// site, by the URL the pages ask for it).
//
// - Install: caches all of FILES in `lab-<VERSION>`, in one go (a cache is a
//   whole version of the site or nothing).
// - Pages (navigations) go to the network first, so an online visit always
//   gets the newest index.html and with it the newest file names; offline,
//   the cached copy of the page asked for answers (check.html, index.html
//   with its launch query), else index.html (the folder's address).
// - Everything else comes from the caches first: names are versioned
//   (`?v=` or a content hash in the name), so a cached answer is never stale.
// - Activate: keeps this version and the one before it (a page still open on
//   the old version may still ask for its modules), deletes the rest.
//
// `cargo xtask serve` rebuilds change every versioned name, and navigations
// go to the network first, so a stale worker never hides a rebuild.

const VERSION = "__VERSION__";
const FILES = __FILES__;
const PREFIX = "lab-";
const CACHE = PREFIX + VERSION;

self.addEventListener("install", (event) => {
  event.waitUntil(
    caches
      .open(CACHE)
      .then((cache) => cache.addAll(FILES.map((f) => new Request(f, { cache: "reload" }))))
      .then(() => self.skipWaiting()),
  );
});

self.addEventListener("activate", (event) => {
  event.waitUntil(
    (async () => {
      const names = (await caches.keys()).filter((n) => n.startsWith(PREFIX) && n !== CACHE);
      // The newest other version stays for pages still open on it.
      const dates = await Promise.all(names.map(async (n) => [n, Number((await (await caches.open(n)).match("__installed__"))?.headers.get("x-at") ?? 0)]));
      dates.sort((a, b) => b[1] - a[1]);
      await Promise.all(dates.slice(1).map(([n]) => caches.delete(n)));
      const cache = await caches.open(CACHE);
      await cache.put("__installed__", new Response("", { headers: { "x-at": String(Date.now()) } }));
      await self.clients.claim();
    })(),
  );
});

self.addEventListener("fetch", (event) => {
  const request = event.request;
  if (request.method !== "GET" || new URL(request.url).origin !== self.location.origin) return;
  if (request.mode === "navigate") {
    event.respondWith(
      fetch(request).catch(async () => {
        const cache = await caches.open(CACHE);
        return (
          (await cache.match(request, { ignoreSearch: true })) ??
          (await cache.match(new URL("index.html", self.registration.scope).href)) ??
          Response.error()
        );
      }),
    );
    return;
  }
  event.respondWith(
    (async () => {
      const hit = await caches.match(request);
      return hit ?? fetch(request);
    })(),
  );
});
