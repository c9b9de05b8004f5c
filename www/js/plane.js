// The objective plane: DTL against BAcc on the surrogate (with ISO 2631-1 Wk comfort, the
// Wk-weighted BAcc on the LoFi), with its feasible designs (the page's dots), the Pareto
// fronts, the pick (min-max, knee or weighted) and its HiFi re-check, the datum
// (plotters, js/chartspecs.js), and the current design on an overlay canvas (it moves
// with the sliders). A design beyond the axes stays in view: pinned to the edge with an
// arrow towards it. A click selects the nearest front point (and says its pseudo-weights);
// the tooltip names the pick's rule. After an adaptive HiFi run the loop's front and pick
// move to their new place (`move`). The axes are fitted to the fronts and the feasible
// designs (js/planezoom.js), the datum too pinned to the edge when outside; the wheel,
// a drag and the keys (+, -, arrows, 0) zoom and pan, the reset button goes back to the
// fitted axes, and each change is told to the page (a `planezoom` event on the overlay,
// `detail` the zoom, for the link's `pz=`). Handed plain data.

import { Plot } from './plot.js';
import { CLOUD_OPACITY, cloudPoints, objectiveSpec, planeXY } from './chartspecs.js';
import { fmt, fmtPct } from './format.js';
import { fitAxes, panBy, zoomAbout, zoomedAxes, zoomForKey } from './planezoom.js';
import { paintClass } from './classmarks.js';

/** The live layer's colours (the charts' own are in js/chartspecs.js). */
const CLOUD_FILL = `rgba(120, 160, 210, ${CLOUD_OPACITY})`;

/** How long the adaptive loop's front and pick take to move to their new place, ms. */
const MOVE_MS = 400;

/** True when the reader asked for less motion (the plane then jumps). */
function reducedMotion() {
  return typeof matchMedia === 'function' && matchMedia('(prefers-reduced-motion: reduce)').matches;
}

/**
 * `front` (points `{bacc, dtl}`, in order along the front) resampled at `m` equal steps
 * of its length, the length measured in units of `scale` = `[BAcc, DTL]` so both axes
 * count alike: `[[bacc, dtl]]`, first and last points kept.
 */
function resampleFront(front, m, scale) {
  const pts = front.map((p) => [p.bacc, p.dtl]);
  const s = [0];
  for (let i = 1; i < pts.length; i++) {
    s.push(s[i - 1] + Math.hypot((pts[i][0] - pts[i - 1][0]) / scale[0], (pts[i][1] - pts[i - 1][1]) / scale[1]));
  }
  const len = s[s.length - 1];
  const out = [];
  let j = 0;
  for (let k = 0; k < m; k++) {
    const u = m > 1 ? (len * k) / (m - 1) : 0;
    while (j < pts.length - 2 && s[j + 1] < u) j++;
    const a = pts[j];
    const b = pts[Math.min(j + 1, pts.length - 1)];
    const f = s[j + 1] > s[j] ? Math.min(1, (u - s[j]) / (s[j + 1] - s[j])) : 0;
    out.push([a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]);
  }
  return out;
}

/** `[BAcc, DTL]` spans of the points of both fronts (1 where there is none). */
function spans(...fronts) {
  const span = (k) => {
    const v = fronts.flat().map((p) => p[k]);
    return Math.max(...v) - Math.min(...v) || 1;
  };
  return [span('bacc'), span('dtl')];
}

export class ObjectivePlane {
  /**
   * `els`: `{base, overlay, wrap, msg}` elements; `onSelect(point, selected)` gets the
   * front point (`{ks, cs, bacc, dtl, sws}`) nearest a click and `this.selected`.
   */
  constructor({ base, overlay, wrap, msg }, onSelect) {
    this.base = new Plot(base, { fill: true });
    /** The zoom (`[x0, x1, y0, y1]` fractions of the fitted axes, js/planezoom.js) or null; the fitted axes and the datum when outside them. */
    this.zoom = null;
    this.fit = null;
    this.datumOut = null;
    this.reset = wrap.parentElement.querySelector('.op-reset');
    this.reset?.addEventListener('click', () => this.setZoom(null));
    this.bindZoom(overlay);
    this.over = overlay;
    this.wrap = wrap;
    this.msg = msg;
    this.data = null;
    /** The class front's designs (`[{rank, plane: {bacc, dtl}}]` or null, js/classmarks.js). */
    this.klass = null;
    this.design = null;
    this.designAt = null;
    this.designClamped = false;
    this.thick = 1;
    /** True while the adaptive front moves (`move`); `moved`: the last move's `{frames, ms}`. */
    this.animating = false;
    this.moved = null;
    this.raf = null;
    this.moveTimer = null;
    /** The front point last clicked: `{index, point, weights}` (pseudo-weights `[comfort, road holding]`), or null. */
    this.selected = null;
    this.title = overlay.title;
    overlay.addEventListener('click', (ev) => {
      // The end of a drag is no click.
      if (this.dragged) return;
      const hit = this.nearest(ev);
      if (!hit) return;
      this.selected = { index: hit.index, point: hit.point, weights: this.data.front.pseudoWeights[hit.index] };
      onSelect(hit.point, this.selected);
    });
    // The tooltip: the pick's rule and pseudo-weights over the pick, a front point's
    // pseudo-weights over it, else how to use the plane.
    overlay.addEventListener('mousemove', (ev) => {
      const hit = this.nearest(ev);
      const fr = this.data && this.data.front;
      overlay.title = hit && hit.dist < 10 ? (hit.index === fr.study.pick.index ? pickText(fr) : frontPointText(fr, hit.index)) : this.title;
    });
  }

  /** The wheel (about the pointer), a drag (pan) and the keys on the focused plane zoom and pan. */
  bindZoom(overlay) {
    const frac = (ev) => {
      const r = overlay.getBoundingClientRect();
      const { plot } = this.base.layout();
      return [(ev.clientX - r.left - plot.x) / plot.w, 1 - (ev.clientY - r.top - plot.y) / plot.h];
    };
    overlay.addEventListener('wheel', (ev) => {
      if (!this.fit) return;
      ev.preventDefault();
      const [u, v] = frac(ev);
      const step = ev.deltaMode === 1 ? ev.deltaY * 33 : ev.deltaY;
      this.setZoom(zoomAbout(this.zoom, Math.exp(Math.max(-300, Math.min(300, step)) * 0.0015), Math.min(1, Math.max(0, u)), Math.min(1, Math.max(0, v))));
    }, { passive: false });
    let drag = null;
    overlay.addEventListener('pointerdown', (ev) => {
      if (ev.button !== 0 || ev.pointerType === 'touch' || !this.fit) return;
      drag = { at: frac(ev), zoom: this.zoom, moved: false };
      this.dragged = false;
    });
    overlay.addEventListener('pointermove', (ev) => {
      if (!drag) return;
      const [u, v] = frac(ev);
      const [du, dv] = [drag.at[0] - u, drag.at[1] - v];
      if (!drag.moved && Math.hypot(du * this.base.layout().plot.w, dv * this.base.layout().plot.h) < 4) return;
      if (!drag.moved) overlay.setPointerCapture(ev.pointerId);
      drag.moved = true;
      this.dragged = true;
      this.setZoom(panBy(drag.zoom, du, dv), false);
    });
    const end = () => {
      if (drag && drag.moved) this.setZoom(this.zoom);
      drag = null;
      // The click that ends a drag comes after pointerup: it is skipped, the next one not.
      setTimeout(() => (this.dragged = false), 0);
    };
    overlay.addEventListener('pointerup', end);
    overlay.addEventListener('pointercancel', end);
    overlay.addEventListener('keydown', (ev) => {
      if (ev.ctrlKey || ev.metaKey || ev.altKey || !this.fit) return;
      const z = zoomForKey(this.zoom, ev.key);
      if (z === undefined) return;
      ev.preventDefault();
      ev.stopPropagation();
      this.setZoom(z);
    });
  }

  /** Shows zoom `z` (null: the fitted axes); `tell`: says so to the page (a `planezoom` event). */
  setZoom(z, tell = true) {
    this.zoom = z;
    if (this.reset) this.reset.disabled = z === null;
    if (this.data) this.draw({ ...this.data, zoom: z });
    if (tell) this.over.dispatchEvent(new CustomEvent('planezoom', { bubbles: true, detail: z }));
  }

  /** Line widths times `thick` (projector mode). */
  setStyle({ thick }) {
    this.thick = thick;
  }

  /**
   * The plane of `data` = `{front, nsga, cloud, ratio}` in three layers on the base
   * canvas: plotters' axes, the cloud of feasible designs (thousands of dots in one
   * path), then plotters' fronts and markers. With no front the core's message (naming
   * the binding objective) replaces the plot. Ends a move in progress (`frame`: the
   * move's own frames).
   */
  draw(data, frame = false) {
    if (!frame) this.stopMove();
    this.data = data;
    const fr = data.front;
    if (!fr || fr.error) {
      this.msg.textContent = fr ? `No front to draw: ${fr.error.replace(/^sws_limit: /, 'SWS limit: ')}` : '';
      this.msg.hidden = !fr;
      this.wrap.hidden = true;
      return;
    }
    this.msg.hidden = true;
    this.wrap.hidden = false;
    if ('zoom' in data) this.zoom = data.zoom;
    if (this.reset) this.reset.disabled = this.zoom === null;
    const spec = objectiveSpec(data, { ratio: data.ratio, live: true });
    if (this.thick !== 1) for (const s of spec.series) s.size = (s.size || 2) * this.thick;
    // Every cell of a cloud up to 120 wide, every other one of a larger one.
    const cloud = data.cloud ? cloudPoints(data.cloud, fr, data.ratio, data.cloud.nx > 120 ? 2 : 1) : [];
    // The class front's designs (js/classfront.js) are in the fit: every student in view.
    const xy = planeXY(fr, data.ratio);
    const klass = (this.klass || []).map((row) => xy(row.plane.bacc, row.plane.dtl));
    this.fit = fitAxes([...spec.series.filter((s) => s.name !== 'datum' && !s.name.startsWith('feasible')).flatMap((s) => s.points), ...klass], cloud);
    const axes = zoomedAxes(this.fit, this.zoom);
    spec.xRange = axes.x;
    spec.yRange = axes.y;
    // The datum beyond the axes: out of the chart, pinned to its edge on the overlay.
    const datum = spec.series.find((s) => s.name === 'datum').points[0];
    const inside = datum[0] >= axes.x[0] && datum[0] <= axes.x[1] && datum[1] >= axes.y[0] && datum[1] <= axes.y[1];
    this.datumOut = inside ? null : datum;
    if (!inside) spec.series = spec.series.filter((s) => s.name !== 'datum');
    if (this.base.draw(spec, 'axes')) {
      this.base.dots(cloud, CLOUD_FILL, 1.4 * this.thick);
      this.base.draw(spec, 'series');
    }
    this.drawDesign(this.design);
  }

  /**
   * Draws `data`, the adaptive loop's front and pick moving there over MOVE_MS ms from
   * `data.adaptive.was` (one frame per animation frame: both fronts resampled at the same
   * fractions of their length and blended, the pick on a straight line, eased). With
   * prefers-reduced-motion, or nothing to move from, it jumps. The last frame is
   * `draw(data)` itself, so what stays drawn is exactly the computed front and pick.
   */
  move(data) {
    this.stopMove();
    const a = data.adaptive;
    if (!a || !a.was || !a.was.front.length || !a.front.length || reducedMotion()) {
      this.draw(data);
      if (a && a.was) this.moved = { frames: 0, ms: 0 };
      return;
    }
    const m = Math.max(a.was.front.length, a.front.length, 2);
    const scale = spans(a.was.front, a.front);
    const p0 = resampleFront(a.was.front, m, scale);
    const p1 = resampleFront(a.front, m, scale);
    const c0 = a.was.pick.criteria;
    const c1 = a.pick.criteria;
    const t0 = performance.now();
    let frames = 0;
    this.animating = true;
    const finish = (now) => {
      this.stopMove();
      this.moved = { frames, ms: now - t0 };
      this.draw(data, true);
    };
    // A hidden page gets no animation frames: the move ends on a timer then.
    this.moveTimer = setTimeout(() => finish(performance.now()), 3 * MOVE_MS);
    const step = (now) => {
      // A frame's timestamp is when the frame began, which can be before `t0`: clamped,
      // so the first frame is not ahead of the next (the move stays one way).
      const t = Math.min(1, Math.max(0, (now - t0) / MOVE_MS));
      if (t >= 1) {
        finish(now);
        return;
      }
      const e = t * t * (3 - 2 * t);
      const mix = (x, y) => x + e * (y - x);
      const front = p0.map((p, i) => ({ bacc: mix(p[0], p1[i][0]), dtl: mix(p[1], p1[i][1]) }));
      const pick = { ...a.pick, criteria: { ...c1, bacc: mix(c0.bacc, c1.bacc), dtl: mix(c0.dtl, c1.dtl) } };
      frames++;
      this.draw({ ...data, adaptive: { ...a, front, pick } }, true);
      this.raf = requestAnimationFrame(step);
    };
    this.raf = requestAnimationFrame(step);
  }

  /** Stops a move in progress where it is (the caller draws what comes next). */
  stopMove() {
    if (this.raf !== null) cancelAnimationFrame(this.raf);
    clearTimeout(this.moveTimer);
    this.raf = null;
    this.animating = false;
  }

  /**
   * The current design's marker (`design`: its criteria `{bacc, dtl}` by the plane's
   * model) on the overlay, and the datum's when it lies beyond the axes; each pinned to
   * the edge with an arrow towards it when outside.
   */
  drawDesign(design) {
    this.design = design;
    const b = this.base;
    const d = this.data;
    if (!d || !d.front || d.front.error || !b.placed || b.error) return;
    const c = this.over;
    const { w, h, dpr, zoom } = b.size;
    if (c.width !== b.canvas.width || c.height !== b.canvas.height) {
      c.width = b.canvas.width;
      c.height = b.canvas.height;
    }
    if (c.style.height !== b.canvas.style.height) c.style.height = b.canvas.style.height;
    const g = c.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, w, h);
    const r = 4.5 * zoom * Math.sqrt(this.thick);
    if (this.datumOut) {
      // The datum's square, white with a black rim as in the chart.
      this.pinned(g, b.px(...this.datumOut), 0.9 * r, (mx, my, rr) => {
        g.beginPath();
        g.rect(mx - rr, my - rr, 2 * rr, 2 * rr);
        g.fillStyle = '#fff';
        g.fill();
        g.lineWidth = 1.6 * this.thick;
        g.strokeStyle = '#000';
        g.stroke();
      });
    }
    const { plot, fs } = b.layout();
    const xy = planeXY(d.front, d.ratio);
    paintClass(g, this.klass, (row) => {
      const [x, y] = b.px(...xy(row.plane.bacc, row.plane.dtl));
      return x >= plot.x && x <= plot.x + plot.w && y >= plot.y && y <= plot.y + plot.h ? [x, y] : null;
    }, { r: 0.9 * r, lw: this.thick, fs: fs * 1.05 });
    if (!design) return;
    const [px, py] = b.px(...planeXY(d.front, d.ratio)(design.bacc, design.dtl));
    const at = this.pinned(g, [px, py], r, (mx, my, rr) => {
      g.beginPath();
      g.arc(mx, my, rr, 0, 2 * Math.PI);
      g.fillStyle = '#000';
      g.fill();
      g.lineWidth = 2 * this.thick;
      g.strokeStyle = '#fff';
      g.stroke();
    });
    this.designAt = at.at;
    this.designClamped = at.out;
  }

  /**
   * A marker of radius `r` at `[px, py]` (CSS px) painted by `paint(x, y, r)`: inside the
   * plot where it is, else pinned to the edge (one arrow length in) with a black arrow
   * whose tip is at the edge, pointing to where it lies. Returns `{at, out}`.
   */
  pinned(g, [px, py], r, paint) {
    const { plot } = this.base.layout();
    const cx = Math.min(plot.x + plot.w - r - 2, Math.max(plot.x + r + 2, px));
    const cy = Math.min(plot.y + plot.h - r - 2, Math.max(plot.y + r + 2, py));
    const out = cx !== px || cy !== py;
    let at = [cx, cy];
    if (out) {
      const a = Math.atan2(py - cy, px - cx);
      const ux = Math.cos(a);
      const uy = Math.sin(a);
      at = [cx - ux * 3.5 * r, cy - uy * 3.5 * r];
      g.beginPath();
      g.moveTo(at[0] + ux * r, at[1] + uy * r);
      g.lineTo(cx - ux * r * 0.5, cy - uy * r * 0.5);
      g.lineWidth = 2.2 * this.thick;
      g.strokeStyle = '#000';
      g.stroke();
      const tx = cx + ux * r;
      const ty = cy + uy * r;
      g.beginPath();
      g.moveTo(tx, ty);
      g.lineTo(tx - ux * 2 * r - uy * r, ty - uy * 2 * r + ux * r);
      g.lineTo(tx - ux * 2 * r + uy * r, ty - uy * 2 * r - ux * r);
      g.closePath();
      g.fillStyle = '#000';
      g.fill();
    }
    paint(at[0], at[1], r);
    return { at, out };
  }

  /** The front point nearest a click (CSS px on the plot) as `{point, index, dist}` (dist in CSS px), or null away from the plot. */
  nearest(ev) {
    const d = this.data;
    if (!d || !d.front || d.front.error || !this.base.placed) return null;
    const rect = this.over.getBoundingClientRect();
    const x = ev.clientX - rect.left;
    const y = ev.clientY - rect.top;
    const { plot } = this.base.layout();
    if (x < plot.x || x > plot.x + plot.w || y < plot.y || y > plot.y + plot.h) return null;
    const xy = planeXY(d.front, d.ratio);
    let best = null;
    let bestD = Infinity;
    d.front.study.front.forEach((p, index) => {
      const [px, py] = this.base.px(...xy(p.bacc, p.dtl));
      const dist = Math.hypot(px - x, py - y);
      if (dist < bestD) [best, bestD] = [{ point: p, index, dist }, dist];
    });
    return best;
  }
}

/** The pick rule's name (`minmax`, `knee`, `asf:W`) on the page: "Min-max pick", "Knee pick", "Weighted pick (W = 0.3)". */
export function ruleLabel(rule) {
  if (rule === 'knee') return 'Knee pick';
  const m = /^asf:(.*)$/.exec(rule || '');
  return m ? `Weighted pick (W = ${m[1]})` : 'Min-max pick';
}

/** The comfort axis of a front (`fr.comfort`): its short name. */
function comfortName(fr) {
  return fr.comfort === 'wk' ? 'BAcc (Wk)' : 'BAcc';
}

/** "pseudo-weights comfort 0.62, road holding 0.38" of `[w_comfort, w_dtl]`. */
export function weightsText(w) {
  return `pseudo-weights comfort ${w[0].toFixed(2)}, road holding ${w[1].toFixed(2)}`;
}

/** One front point `k` of `fr` in words: place, design, criteria and pseudo-weights. */
export function frontPointText(fr, k) {
  const p = fr.study.front[k];
  return `Front point ${k + 1} of ${fr.study.front.length}: Ks ${fmt(p.ks / 1000, 4)} kN/m, Cs ${fmt(p.cs / 1000, 4)} kNs/m, ` +
    `${comfortName(fr)} ${fmt(p.bacc, 4)} m/s², DTL ${fmt(p.dtl, 4)} N; ${weightsText(fr.pseudoWeights[k])}.`;
}

/** The pick of `fr` in words: its rule, design and pseudo-weights. */
function pickText(fr) {
  const p = fr.study.pick;
  return `${ruleLabel(p.rule)}: Ks ${fmt(p.ks / 1000, 4)} kN/m, Cs ${fmt(p.cs / 1000, 4)} kNs/m; ${weightsText(p.pseudo_weights)}.`;
}

/** The pick's table: its rule, Ks, Cs, pseudo-weights, the plane model's and HiFi criteria, % vs datum, their difference. */
export function renderPick(table, fr) {
  if (!fr || fr.error) {
    table.replaceChildren();
    return;
  }
  const p = fr.study.pick;
  const r = fr.recheck;
  const row = (name, unit, k, scale, dec) => {
    const i = { bacc: 0, dtl: 1, sws: 2 }[k];
    return `<tr><th scope="row">${name} <span class="unit">${unit}</span></th>
      <td class="num" data-value="${p.criteria[k]}">${fmt(p.criteria[k] * scale, dec)}</td>
      <td class="num delta">${fmtPct(p.change_percent[i] / 100)}</td>
      <td class="num" data-value="${r.rechecked[k]}">${fmt(r.rechecked[k] * scale, dec)}</td>
      <td class="num delta">${fmtPct(r.rechecked_change_percent[i] / 100)}</td>
      <td class="num">${fmtPct(r.error_percent[i] / 100, 2)}</td></tr>`;
  };
  const on = fr.comfort === 'wk' || fr.robust ? 'LoFi' : 'Surrogate';
  const w = p.pseudo_weights;
  table.innerHTML = `
    <caption>${ruleLabel(p.rule)}: Ks = <b data-value="${p.ks}">${fmt(p.ks / 1000, 4)} kN/m</b>,
      Cs = <b data-value="${p.cs}">${fmt(p.cs / 1000, 4)} kNs/m</b>;
      <span class="pick-weights" data-rule="${p.rule}" data-weights="${w.join(',')}">${weightsText(w)}</span>;
      hypervolume ${fmt(fr.study.hypervolume, 4)} (m/s²)·N, ${fr.study.evaluations} runs of ${fr.study.evaluator}</caption>
    <thead><tr><th scope="col">Criterion</th><th scope="col" class="num">${on}</th><th scope="col" class="num">vs datum</th>
      <th scope="col" class="num">HiFi re-check</th><th scope="col" class="num">vs datum</th>
      <th scope="col" class="num">${on} − HiFi</th></tr></thead>
    <tbody>${row(comfortName(fr), 'm/s²', 'bacc', 1, 4)}${row('DTL', 'N', 'dtl', 1, 4)}${row('SWS', 'mm', 'sws', 1000, 4)}</tbody>`;
}
