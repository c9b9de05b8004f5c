// The tour: a card beside one real control per step (the control outlined), shown on a
// first visit and from the "Tour" button. Focus moves to the card; Escape closes it;
// it never covers the control it talks about.

const STEPS = [
  ['ks-range', 'Drag the spring rate Ks slider (or use the arrow keys): the readout, the white design dot on the maps and the black dot on the objective plane move at once.'],
  ['map-grid', 'The maps: colour is the criterion over Ks and Cs (hover to read a value); hatched areas break a design objective. Click, drag or touch a map to set the design; arrow keys move it on a focused map.'],
  ['sws-range', 'Drag the SWS limit down (or type 6 mm): more of the box is hatched, and the Pareto front and the pick move as you drag.'],
  ['map-model', 'Switch the maps to the HiFi full car or to the surrogate\'s error: the surrogate is the LoFi tuned to a few HiFi runs (× marks).'],
  ['op-wrap', 'The objective plane: no design beats the front in both comfort (BAcc) and road holding (DTL). The yellow diamond is the min-max pick, re-checked on the full car; click the front to try a point.'],
  ['tab-spectra', 'More in the tabs: the car and road, the objectives, the surrogate, modes, spectra and a time response (body bounce near 1 Hz, wheel hop near 10 Hz). Press ? for the keyboard shortcuts.'],
];

const KEY = 'ridelab.tourDone';

export class Guide {
  /** `card`: the tour's dialog element. */
  constructor(card) {
    this.card = card;
    this.text = card.querySelector('#tour-text');
    this.count = card.querySelector('#tour-count');
    this.next = card.querySelector('#tour-next');
    this.back = card.querySelector('#tour-back');
    this.step = 0;
    this.lit = null;
    this.next.addEventListener('click', () => this.go(this.step + 1));
    this.back.addEventListener('click', () => this.go(this.step - 1));
    card.querySelector('#tour-close').addEventListener('click', () => this.close());
    card.addEventListener('keydown', (ev) => {
      if (ev.key === 'Escape') {
        ev.stopPropagation();
        this.close();
      }
    });
    this.reposition = () => this.place();
  }

  /** The number of steps. */
  get length() {
    return STEPS.length;
  }

  /** Shows the tour on a first visit (nothing stored yet). */
  showIfNew() {
    let done = false;
    try {
      done = localStorage.getItem(KEY) === '1';
    } catch {
      // Storage may be off; show the tour then.
    }
    if (!done) this.open();
  }

  open() {
    this.returnFocus = document.activeElement;
    this.card.hidden = false;
    window.addEventListener('resize', this.reposition);
    this.go(0);
  }

  get isOpen() {
    return !this.card.hidden;
  }

  go(k) {
    if (k >= STEPS.length) {
      this.close();
      return;
    }
    this.step = Math.max(0, k);
    const [id, text] = STEPS[this.step];
    this.text.textContent = text;
    this.count.textContent = `${this.step + 1} of ${STEPS.length}`;
    this.next.textContent = this.step === STEPS.length - 1 ? 'Finish' : 'Next';
    this.back.disabled = this.step === 0;
    this.lit?.classList.remove('spotlight');
    this.lit = document.getElementById(id);
    this.lit?.classList.add('spotlight');
    this.lit?.scrollIntoView({ block: 'nearest' });
    this.place();
    this.card.focus();
  }

  /**
   * Puts the card beside the control: right of it if there is room, else left, else
   * below or above; always inside the viewport.
   */
  place() {
    const el = this.lit;
    if (!el || this.card.hidden) return;
    const r = el.getBoundingClientRect();
    const c = this.card.getBoundingClientRect();
    const vw = document.documentElement.clientWidth;
    const vh = window.innerHeight;
    const gap = 12;
    let x;
    let y;
    let side;
    if (r.right + gap + c.width <= vw) {
      [x, y, side] = [r.right + gap, r.top + r.height / 2 - c.height / 2, 'right'];
    } else if (r.left - gap - c.width >= 0) {
      [x, y, side] = [r.left - gap - c.width, r.top + r.height / 2 - c.height / 2, 'left'];
    } else if (r.bottom + gap + c.height <= vh) {
      [x, y, side] = [r.left + r.width / 2 - c.width / 2, r.bottom + gap, 'below'];
    } else {
      [x, y, side] = [r.left + r.width / 2 - c.width / 2, r.top - gap - c.height, 'above'];
    }
    x = Math.min(vw - c.width - 4, Math.max(4, x));
    y = Math.min(vh - c.height - 4, Math.max(4, y));
    this.card.style.left = `${x + window.scrollX}px`;
    this.card.style.top = `${y + window.scrollY}px`;
    this.card.dataset.side = side;
  }

  close() {
    this.lit?.classList.remove('spotlight');
    this.lit = null;
    this.card.hidden = true;
    window.removeEventListener('resize', this.reposition);
    try {
      localStorage.setItem(KEY, '1');
    } catch {
      // Nothing to remember with; the tour shows again next time.
    }
    if (this.returnFocus && document.contains(this.returnFocus)) this.returnFocus.focus({ preventScroll: true });
  }
}
