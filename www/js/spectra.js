// The FRF and PSD panel: six log-log charts (|H| and the output PSDs of BAcc, DTL, SWS;
// LoFi, HiFi and the surrogate's tuned LoFi), drawn by plotters from the spectra handed in.

import { Plot } from './plot.js';
import { OUTPUTS, spectraSpec } from './chartspecs.js';

export class SpectraPanel {
  /** `canvasOf(which, key)`: the canvas of one chart; `section`: the panel (drawn while it is shown). */
  constructor(canvasOf, section, keyRoute) {
    this.section = section;
    this.keyRoute = keyRoute;
    this.plots = [];
    this.thick = 1;
    for (const which of ['frf', 'psd']) {
      for (const o of OUTPUTS) this.plots.push({ which, key: o.key, plot: new Plot(canvasOf(which, o.key), { aspect: 0.7 }) });
    }
    this.data = null;
    this.dirty = false;
    this.visible = false;
    new IntersectionObserver((entries) => {
      this.visible = entries.some((e) => e.isIntersecting);
      if (this.visible && this.dirty) this.draw(this.data);
    }).observe(section);
  }

  setStyle({ thick }) {
    this.thick = thick;
  }

  /**
   * Draws `sp` now if the panel is on screen, else when it comes into view: six log-log
   * charts are the largest redraw after a design change, and nobody sees them hidden.
   */
  show(sp) {
    this.data = sp;
    this.dirty = !this.visible;
    if (this.visible) this.draw(sp);
  }

  /** The six charts of `sp` through plotters. */
  draw(sp) {
    this.data = sp;
    this.dirty = false;
    if (!sp) {
      // None for this design and road (the status says why): no earlier spectra stay drawn.
      for (const { plot } of this.plots) plot.canvas.getContext('2d').clearRect(0, 0, plot.canvas.width, plot.canvas.height);
      this.keyRoute.textContent = '';
      return;
    }
    this.keyRoute.textContent = sp.surrogateRoute;
    for (const { which, key, plot } of this.plots) {
      const spec = spectraSpec(sp, which, key, { legend: 'none' });
      if (this.thick !== 1) for (const s of spec.series) s.size *= this.thick;
      plot.draw(spec);
    }
  }
}
