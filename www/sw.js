// RideLab's service worker: the page keeps working offline after the first visit. It
// caches the files of one build (the page, the wasm, the workers' modules) under a cache
// named by the build's content hash and answers from that cache first. A new build (a
// new hash, so a new sw.js) installs beside the old one and waits; the page offers to
// switch (the "take-over" message). The older builds' caches stay until a page of this
// build has booted from this worker (the "booted" message): a new build that fails to
// start leaves the last good one's files in place.
// The two placeholders are filled in by www/sw-stamp.mjs, a post-build hook of Trunk
// (Trunk.toml).

const BUILD = '__RIDELAB_BUILD__';
const FILES = ['__RIDELAB_FILES__'];
const CACHE = `ridelab-${BUILD}`;

self.addEventListener('install', (ev) => {
  ev.waitUntil(caches.open(CACHE).then((c) => c.addAll(FILES.map((f) => new Request(f, { cache: 'reload' })))));
});

self.addEventListener('activate', (ev) => {
  ev.waitUntil(self.clients.claim());
});

/**
 * Drops the other builds' caches, once a page of this build has booted; not while a newer
 * build is installing or waiting (its cache is one of them).
 */
async function dropOlderCaches() {
  if (self.registration.installing || self.registration.waiting) return;
  const old = (await caches.keys()).filter((k) => k.startsWith('ridelab-') && k !== CACHE);
  await Promise.all(old.map((k) => caches.delete(k)));
}

// A page tells the waiting build to take over (it reloads when it has), and a page that
// booted from this build says so.
self.addEventListener('message', (ev) => {
  if (ev.data && ev.data.ridelab === 'take-over') self.skipWaiting();
  if (ev.data && ev.data.ridelab === 'booted') ev.waitUntil(dropOlderCaches());
});

self.addEventListener('fetch', (ev) => {
  const req = ev.request;
  if (req.method !== 'GET' || new URL(req.url).origin !== self.location.origin) return;
  ev.respondWith(
    caches.open(CACHE).then(async (c) => {
      // The page with a query (`?engine=main`) is the same page.
      const hit = (await c.match(req, { ignoreSearch: true })) || (req.mode === 'navigate' ? await c.match('./') : undefined);
      return hit || fetch(req);
    }),
  );
});
