// The workbench's frame: the tabs that open the drawer of further panels (beside the
// maps and the front on a wide screen, over the right half on a smaller one, in the
// page's flow on a phone), the keyboard shortcuts and their list behind "?".

const $ = (id) => document.getElementById(id);

/** Is the drawer a column of the grid (the first set keeps its room) rather than over it? */
export const WIDE = '(min-width: 1600px) and (min-height: 1000px)';

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
      t.addEventListener('click', () => (this.current === t.getAttribute('aria-controls') ? this.close() : this.open(t.getAttribute('aria-controls'))));
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
    drawer.addEventListener('keydown', (ev) => {
      if (ev.key === 'Escape' && !ev.target.closest('input[type="text"]')) this.close();
    });
  }

  /** Opens the drawer on panel `id` (a tab's `aria-controls`). */
  open(id) {
    this.current = id;
    for (const t of this.tabs) {
      const on = t.getAttribute('aria-controls') === id;
      t.setAttribute('aria-selected', String(on));
      $(t.getAttribute('aria-controls')).hidden = !on;
    }
    this.drawer.hidden = false;
    this.bench.classList.add('drawer-open');
    this.onResize();
  }

  close() {
    if (this.current === null) return;
    const tab = this.tabs.find((t) => t.getAttribute('aria-controls') === this.current);
    this.current = null;
    for (const t of this.tabs) t.setAttribute('aria-selected', 'false');
    this.drawer.hidden = true;
    this.bench.classList.remove('drawer-open');
    this.onResize();
    if (this.drawer.contains(document.activeElement)) tab?.focus();
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
