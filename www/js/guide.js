// The guided first view: a short tour that points at one part of the page per step
// (outline and scroll), shown on a first visit and from the "Tour" button. It sits in the
// page flow (not over it), so it never blocks a control.

const STEPS = [
  ['ks-range', 'Drag the spring rate Ks slider: the readout, the design marker (white dot) on the maps and the black dot on the objective plane move at once.'],
  ['map-grid', 'Read the maps: colour is the criterion over Ks and Cs, hatched areas break a design objective. Click or drag on a map to set the design.'],
  ['sws-range', 'Drag the SWS limit slider down (or type 6 mm): more of the box is hatched, and the Pareto front and the pick move as you drag.'],
  ['map-model', 'Switch the maps to HiFi or to the surrogate error: the surrogate is the LoFi tuned to a few HiFi runs (× marks).'],
  ['op-wrap', 'The objective plane: no design beats the front in both comfort (BAcc) and road holding (DTL). The yellow diamond is the min-max pick, re-checked on the full car.'],
  ['sp-frf-bacc', 'Frequency responses and a time response show why: body bounce near 1 Hz, wheel hop near 10 Hz.'],
];

const KEY = 'ridelab.tourDone';

export class Guide {
  constructor(root) {
    this.root = root;
    this.list = root.querySelector('ol');
    this.step = 0;
    this.lit = null;
    for (const [, text] of STEPS) {
      const li = document.createElement('li');
      li.textContent = text;
      this.list.append(li);
    }
    root.querySelector('#guide-next').addEventListener('click', () => this.go(this.step + 1));
    root.querySelector('#guide-close').addEventListener('click', () => this.close());
  }

  /** Shows the tour on a first visit (nothing stored yet). */
  showIfNew() {
    let done = false;
    try {
      done = localStorage.getItem(KEY) === '1';
    } catch {
      // Storage may be off; show the tour then.
    }
    if (!done) this.open(false);
  }

  open(focus = true) {
    this.root.hidden = false;
    this.go(0, focus);
  }

  go(k, focus = true) {
    if (k >= STEPS.length) {
      this.close();
      return;
    }
    this.step = k;
    [...this.list.children].forEach((li, i) => li.classList.toggle('current', i === k));
    this.root.querySelector('#guide-next').textContent = k === STEPS.length - 1 ? 'Finish' : `Next (${k + 2} of ${STEPS.length})`;
    this.lit?.classList.remove('spotlight');
    const el = document.getElementById(STEPS[k][0]);
    this.lit = el;
    if (el && focus) {
      el.classList.add('spotlight');
      el.scrollIntoView({ block: 'center', behavior: 'smooth' });
    }
  }

  close() {
    this.lit?.classList.remove('spotlight');
    this.root.hidden = true;
    try {
      localStorage.setItem(KEY, '1');
    } catch {
      // Nothing to remember with; the tour shows again next time.
    }
  }
}
