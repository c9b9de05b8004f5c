// The workbench's frame: the tabs that open the drawer of further panels (beside the
// maps and the front on a wide screen, over the right half on a smaller one, in the
// page's flow on a phone), the keyboard shortcuts and their list behind "?". An opened
// panel is scrolled into view (on a phone it is far down the page); opened from the
// keyboard it takes the focus (its first control), and Escape anywhere in the drawer,
// a text field included, closes it and gives the focus back to its tab.

const $ = (id) => document.getElementById(id);

/** What takes the focus in a panel: its controls, in document order. */
const CONTROLS = 'input:not([type="hidden"]), select, textarea, button, a[href], summary, [tabindex]:not([tabindex="-1"])';

/** The first enabled, visible control inside `el`, or null. */
function firstControl(el) {
  return [...el.querySelectorAll(CONTROLS)].find((c) => !c.disabled && !c.closest('[hidden], [inert]') && c.getClientRects().length > 0) ?? null;
}

export class Workbench {
  /**
   * `bench`: the grid; `tabs`: the tab buttons (each `aria-controls` its panel);
   * `onResize()`: called after the drawer opened or closed (the charts redraw).
   */
  constructor({ bench, drawer, tabs, close, onResize }) {
    this.bench = bench;
    this.drawer = drawer;
    this.tabs = tabs;
    this.onResize = onResize;
    this.current = null;
    for (const t of tabs) {
      // A click with `detail` 0 came from the keyboard (Enter or Space on the tab): the focus goes into the panel.
      t.addEventListener('click', (ev) => {
        const id = t.getAttribute('aria-controls');
        if (this.current === id) this.close();
        else this.open(id, { focus: ev.detail === 0 });
      });
      t.addEventListener('keydown', (ev) => {
        // Arrow keys move between the tabs (the ARIA tabs pattern).
        const i = tabs.indexOf(t);
        const j = ev.key === 'ArrowRight' ? i + 1 : ev.key === 'ArrowLeft' ? i - 1 : null;
        if (j === null) return;
        ev.preventDefault();
        tabs[(j + tabs.length) % tabs.length].focus();
      });
    }
    close.addEventListener('click', () => this.close());
    // Escape from anywhere in the drawer, a text field too (a number field first puts back
    // its value, js/app.js), closes it.
    drawer.addEventListener('keydown', (ev) => {
      if (ev.key !== 'Escape' || ev.defaultPrevented) return;
      ev.preventDefault();
      this.close(true);
    });
  }

  /**
   * Opens the drawer on panel `id` (a tab's `aria-controls`) and scrolls it into view;
   * `focus`: its first control takes the focus (opened from the keyboard).
   */
  open(id, { focus = false } = {}) {
    this.current = id;
    for (const t of this.tabs) {
      const on = t.getAttribute('aria-controls') === id;
      t.setAttribute('aria-selected', String(on));
      $(t.getAttribute('aria-controls')).hidden = !on;
    }
    this.drawer.hidden = false;
    this.bench.classList.add('drawer-open');
    this.onResize();
    const panel = $(id);
    // On a phone the drawer is in the page's flow, below the readout: go there.
    this.drawer.scrollIntoView({ block: 'start', behavior: 'instant' });
    if (focus) (firstControl(panel) ?? this.drawer).focus({ preventScroll: true });
  }

  /**
   * Closes the drawer; the focus goes back to the tab that opened it when it was in the
   * drawer (or `refocus`), and on a phone the tab is scrolled back into view.
   */
  close(refocus = false) {
    if (this.current === null) return;
    const tab = this.tabs.find((t) => t.getAttribute('aria-controls') === this.current);
    const inside = refocus || this.drawer.contains(document.activeElement);
    this.current = null;
    for (const t of this.tabs) t.setAttribute('aria-selected', 'false');
    this.drawer.hidden = true;
    this.bench.classList.remove('drawer-open');
    this.onResize();
    if (inside && tab) {
      tab.focus({ preventScroll: true });
      tab.scrollIntoView({ block: 'nearest', behavior: 'instant' });
    }
  }
}

/**
 * The page's keyboard shortcuts (`actions`: name -> function), outside text fields:
 * `?` the list, `1`..`9` the tabs, `d` the datum design, `k` the pick, `s` keeps the design, `m` the first
 * map, `p` projector mode, `l` the lesson panel, `Escape` closes the drawer.
 */
export function bindShortcuts(actions) {
  document.addEventListener('keydown', (ev) => {
    if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
    const t = ev.target;
    if (t.closest && t.closest('input[type="text"], input[type="file"], select, textarea, dialog')) return;
    const k = ev.key;
    let done = true;
    if (k === '?') actions.help();
    else if (/^[1-9]$/.test(k)) actions.tab(Number(k) - 1);
    else if (k === 'd' || k === 'D') actions.datum();
    else if (k === 'k' || k === 'K') actions.pick();
    else if (k === 's' || k === 'S') actions.keep();
    else if (k === 'm' || k === 'M') actions.map();
    else if (k === 'p' || k === 'P') actions.projector();
    else if (k === 'l' || k === 'L') actions.lesson();
    else if (k === 'Escape') actions.escape();
    else done = false;
    if (done) ev.preventDefault();
  });
}
