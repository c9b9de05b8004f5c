// The offline copy: registers the service worker (sw.js), offers a new build when one is
// waiting, and tells the worker in control that this page has booted.

/**
 * Offline after the first visit: the service worker (sw.js) caches the page, the wasm and
 * the workers. Registered once the page is ready (its install fetches every file of the
 * build once). A new build's worker installs and waits (the browser looks for a new
 * sw.js on every visit): the page says so and switches to it when asked, once
 * `mayLeave(what)` agrees (an unsaved lesson asks first). A page that has booted tells
 * the worker in control ("booted"), which only then drops the older builds' caches.
 */
export function registerServiceWorker(controls, mayLeave) {
  if (!('serviceWorker' in navigator) || location.protocol === 'file:') return;
  const sw = navigator.serviceWorker;
  const offer = (reg) => {
    if (!reg.waiting || !sw.controller) return;
    controls.banner('A new version of RideLab is ready.', 'warn', {
      label: 'Use it now (reload)',
      run: () => {
        if (!mayLeave('Reload the page')) return;
        sw.addEventListener('controllerchange', () => location.reload());
        reg.waiting.postMessage({ ridelab: 'take-over' });
      },
    });
  };
  sw.ready.then(() => sw.controller?.postMessage({ ridelab: 'booted' }));
  sw.register(new URL('../sw.js', import.meta.url), { scope: new URL('../', import.meta.url).pathname })
    .then((reg) => {
      offer(reg);
      reg.addEventListener('updatefound', () => {
        const w = reg.installing;
        w?.addEventListener('statechange', () => w.state === 'installed' && offer(reg));
      });
    })
    .catch((e) => console.warn(`RideLab: no offline copy (${e && e.message ? e.message : e})`));
}
