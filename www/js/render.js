// From the store to the views: each function takes what one view shows out of the store
// and hands it over as plain data. The controller (js/controller.js) calls these after it
// has changed the store; the views (js/mapview.js, js/plane.js, js/readout.js, ...) never
// see the store.

import { MapView } from './mapview.js';
import { renderPick, ruleLabel, weightsText } from './plane.js';
import { renderCriteria, feasibilityText, routeNote, renderProps, renderModes, comfortNote } from './readout.js';
import { renderMetrics, tuningText, renderAdaptive, proposalText } from './surrogatepanel.js';
import { adaptivePlane, adaptiveSpec } from './chartspecs.js';
import { MODEL_NAMES } from './store.js';
import { GRID } from './compute.js';
import { fmt, fmtInput, fmtPct, inPageUnits, roadWords } from './format.js';
import { pathText } from './gpupath.js';
import { currentHifiFront, hifiFrontLine, hifiFrontTitle, renderHifiFront } from './hififront.js';
import { renderCasePicks, robustMapLabel, robustPlaneLabel } from './robustcases.js';
import { classMarks } from './classmarks.js';

const $ = (id) => document.getElementById(id);

/** ", on the GPU (name)" or ", on the CPU (why)" for a HiFi or error map with a `compute` path. */
function pathNote(maps) {
  if (!maps.compute) return '';
  return maps.compute === 'gpu' ? `, on the ${pathText('gpu', maps.gpu)}` : `, on the ${pathText('cpu', maps.gpu)}`;
}

/**
 * "x % break the SWS limit, y % break the body-bounce frequency band" from a map mask;
 * `objectives`: the core's design objectives by mask bit (`objectives()`).
 */
function brokenText(maps, objectives) {
  const n = maps.nx * maps.ny;
  const parts = [];
  for (const { bit, label: name } of objectives) {
    let c = 0;
    for (let k = 0; k < n; k++) if (maps.broken[k] & bit) c++;
    if (c) parts.push(`${fmt((100 * c) / n, 3)} % break the ${name}`);
  }
  return parts.join(', ');
}

export class Render {
  /**
   * `store`; `ui`: `{maps: MapView[], plane, spectra, time, damper, carEditor, controls, tables}`
   * (`tables`: the colour tables by name).
   */
  constructor(store, ui) {
    this.store = store;
    this.ui = ui;
  }

  /** The label of the custom car in the car menu (its name and where it came from), or null when there is none. */
  customLabel() {
    const c = this.store.custom;
    if (!c) return null;
    const from = { file: ' (file)', editor: '', link: ' (from the link)', session: ' (from the session)' }[c.origin];
    return `${c.name}${from}`;
  }

  /** Every control from the state. */
  controls() {
    const st = this.store;
    this.ui.controls.sync(st.state, st.desc, st.view, { customLabel: this.customLabel(), swsDragging: false });
  }

  /** The SWS limit's text field while its slider is dragged. */
  swsDragged(mm) {
    $('sws-limit').value = fmtInput(mm, 4);
  }

  /**
   * What a new scenario changes besides the maps: the car editor, the plane (unless
   * `plane` is false: the controller draws it later), the pick.
   */
  scenario({ plane = true } = {}) {
    const st = this.store;
    // The car editor follows the datum car (only a scenario change can change it), but
    // edits in progress survive changes of road, box or objectives.
    const ed = this.ui.carEditor;
    if (ed && JSON.stringify(ed.car) !== JSON.stringify(st.desc.car)) ed.show(st.desc.car);
    this.criteriaLabels();
    if (plane) this.plane();
    renderPick($('op-pick'), st.front);
    renderHifiFront($('op-hifi'), currentHifiFront(st), st.front);
    if (this.ui.robust) this.ui.robust.show({ cases: st.state.cases, mapCase: st.state.case, desc: st.desc });
    renderCasePicks($('op-cases'), st.front);
    this.pickSummary();
    this.controls();
  }

  /** What says which comfort measure is in use: the plane's heading, the readout's Wk row. */
  criteriaLabels() {
    const wk = this.store.state.comfort === 'wk';
    $('h-objective').querySelector('.th-sub').textContent = robustPlaneLabel(this.store.state, this.store.desc) || (wk ? '(LoFi, Wk comfort)' : '(surrogate)');
    $('criteria').querySelector('tr[data-crit="wk"]').hidden = !wk;
    $('comfort-note').hidden = !wk;
  }

  /** The objective plane from the store (`animate`: the adaptive loop's front and pick move to where they are now). */
  plane(animate = false) {
    const st = this.store;
    // The adaptive loop's surrogate front is unweighted: not drawn on a Wk plane.
    const adaptive = st.plane.model === 'surrogate' ? adaptivePlane(st.adaptive) : null;
    const data = { front: st.front, nsga: st.nsga, cloud: st.cloud, ratio: st.view.ratio, zoom: st.view.planeZoom ?? null, adaptive, hifi: currentHifiFront(st) };
    this.ui.plane.klass = classMarks(st);
    if (animate) this.ui.plane.move(data);
    else this.ui.plane.draw(data);
    $('op-key-adaptive').hidden = !adaptive;
    $('op-key-hifi').hidden = !data.hifi;
    $('op-key-class').hidden = !this.ui.plane.klass;
    this.ui.plane.drawDesign(st.plane.design);
  }

  /** The readout's line on the pick (the Pick tab has the table). */
  pickSummary() {
    const fr = this.store.front;
    const el = $('pick-summary');
    if (!fr || fr.error) {
      el.textContent = fr ? `No ${ruleLabel(this.store.state.pick).toLowerCase()}: no design meets the objectives.` : '';
      return;
    }
    const p = fr.study.pick;
    const worst = Math.max(...fr.recheck.error_percent.map(Math.abs));
    el.textContent = `${ruleLabel(p.rule)}: Ks ${fmt(p.ks / 1000, 4)} kN/m, Cs ${fmt(p.cs / 1000, 4)} kNs/m; ` +
      `${fr.comfort === 'wk' ? 'BAcc (Wk)' : 'BAcc'} ${fmtPct(p.change_percent[0] / 100)}, DTL ${fmtPct(p.change_percent[1] / 100)} vs datum; the HiFi agrees within ${fmt(worst, 2)} %.`;
    el.title = weightsText(p.pseudo_weights);
    // How far to trust the pick: a box bound it sits on, a re-check beyond the tolerance.
    // The short note on the line, the whole message on hover.
    const BOUND = { ks_min: 'lowest Ks', ks_max: 'highest Ks', cs_min: 'lowest Cs', cs_max: 'highest Cs' };
    for (const w of fr.warnings || []) {
      const note = document.createElement('strong');
      note.className = 'pick-warning';
      note.dataset.kind = w.kind;
      note.dataset.field = w.field;
      note.textContent = w.kind === 'box_edge'
        ? ` ⚠ At the box's ${BOUND[w.field] || w.field}: the box stopped it.`
        : ` ⚠ The HiFi re-check misses its ${w.field.toUpperCase()}.`;
      note.title = inPageUnits(w.message);
      el.append(note);
    }
  }

  /** What a new design changes: LoFi and surrogate readout, ride properties, markers, plane marker, controls. */
  design() {
    const st = this.store;
    const { desc, lofi } = st;
    renderCriteria($('criteria'), 'lofi', lofi.design, lofi.datum, desc.swsLimit);
    renderCriteria($('criteria'), 'sur', st.surrogate.design, st.surrogate.datum, desc.swsLimit);
    renderProps($('ride-props'), lofi.design);
    renderModes($('modes-lofi'), lofi.design.modes);
    if (st.state.comfort === 'wk') comfortNote($('comfort-note'), lofi.design, st.hifiCurrent() ? st.hifi.design : null);
    this.markers();
    this.ui.plane.drawDesign(st.plane.design);
    // The linear damper's force-velocity line follows Cs while the time panel is open.
    if (this.ui.damper?.linear && this.ui.damper.visible()) this.ui.damper.refresh();
    this.timeStale();
    this.ui.controls.syncDesign(st.state, st.desc);
  }

  /** The HiFi column and modes, greyed while they belong to an earlier state. */
  hifi() {
    const st = this.store;
    const { desc, lofi, hifi } = st;
    const current = st.hifiCurrent();
    const datumOk = st.hifiDatumCurrent();
    renderCriteria($('criteria'), 'hifi', hifi.design, datumOk ? hifi.datum : null, desc.swsLimit, !current);
    if (hifi.design) renderModes($('modes-hifi'), hifi.design.modes, !current);
    if (st.state.comfort === 'wk') comfortNote($('comfort-note'), lofi.design, current ? hifi.design : null);
    const f = feasibilityText(lofi.design, current ? hifi.design : null, desc.swsLimit);
    const fe = $('feasibility');
    fe.textContent = f.text;
    fe.className = f.ok ? 'status good' : 'status bad';
    $('route-note').textContent = routeNote(lofi.design, current ? hifi.design : null);
  }

  /** The data of map `k` (not drawn). */
  mapData(k, shown, draw = false) {
    const st = this.store;
    const { desc } = st;
    // The LoFi's and HiFi's BAcc map is Wk-weighted with Wk comfort; the surrogate's is not.
    this.ui.maps[k].setComfort(st.state.comfort === 'wk' && (st.view.model === 'lofi' || st.view.model === 'hifi'));
    this.ui.maps[k].setData({
      maps: shown.maps, box: desc.designBox, swsLimit: desc.swsLimit, scale: st.view.scale, datum: shown.datum,
      kind: shown.kind, palette: st.view.palette, tables: this.ui.tables,
    }, draw);
  }

  mapDraw(k) {
    this.ui.maps[k].drawAtSize();
  }

  /** Every map from `shown` (`store.shownMaps()`), its status line and markers. */
  maps(shown) {
    for (let k = 0; k < this.ui.maps.length; k++) this.mapData(k, shown, true);
    this.mapsDone(shown);
  }

  /** After the maps are drawn: the status line and the markers. */
  mapsDone(shown) {
    this.mapsHead();
    this.mapStatusOf(shown);
    this.markers();
  }

  /** The maps' heading names the model shown. */
  mapsHead() {
    const st = this.store;
    const robust = robustMapLabel(st.state, st.desc, st.view.model);
    $('maps-model').textContent = MODEL_NAMES[st.view.model] + (robust ? `, ${robust}` : '');
  }

  /** A status line under the maps (`kind`: 'good', 'bad' or plain). */
  mapStatus(text, kind = '') {
    this.mapsHead();
    const el = $('map-status');
    el.textContent = text;
    el.title = text;
    el.classList.toggle('good', kind === 'good');
    el.classList.toggle('bad', kind === 'bad');
  }

  /** The footer's line: which path drew the HiFi maps (`compute`: "gpu" or "cpu"; `gpu`: the GPU path's status). */
  computePath(compute, gpu) {
    $('compute-path').textContent = `HiFi maps: ${pathText(compute, gpu)}.`;
  }

  /** The line under the maps: how much of the box is feasible, what breaks where. */
  mapStatusOf(shown) {
    const st = this.store;
    const { state } = st;
    const model = st.view.model;
    const rl = robustMapLabel(state, st.desc, model);
    const road = rl ? (rl.startsWith('case ') ? rl : `every case, ${rl}`) : roadWords(state);
    const maps = shown.maps;
    const n = maps.nx * maps.ny;
    const who = `(${MODEL_NAMES[model === 'error' ? 'hifi' : model]}${maps.nx !== GRID.nx ? `, ${maps.nx} × ${maps.ny} grid` : ''})`;
    const timing = st.modelMaps && shown.maps === st.modelMaps.maps ? ` Computed in ${fmt(st.modelMaps.ms, 3)} ms in the worker${pathNote(maps)}.` : '';
    const errorNote = model === 'error' ? ' Error maps are in % of the HiFi whatever the colour setting.' : '';
    if (maps.feasibleCount === n) {
      this.mapStatus(`Every design in the box meets the design objectives on ${road} ${who}.${timing}${errorNote}`, 'good');
    } else if (maps.feasibleCount === 0) {
      this.mapStatus(
        `No design in the box meets the design objectives on ${road} ${who}: the whole map is hatched (${brokenText(maps, this.store.objectives)}). ` +
          'Try a smoother road, a lower speed or a looser objective.',
        'bad',
      );
    } else {
      this.mapStatus(`${fmt((100 * maps.feasibleCount) / n, 3)} % of the design box meets the design objectives on ${road} ${who}; ${brokenText(maps, this.store.objectives)}.${timing}${errorNote}`, 'good');
    }
  }

  /** Design, datum, pick and sample markers on every map, with the design's value in each caption. */
  markers() {
    const st = this.store;
    const { state, desc, lofi } = st;
    const shown = st.shownMaps();
    const datum = { ks: desc.datumKs, cs: desc.datumCs };
    const samples = st.view.plan && st.fit && st.fitKey === st.tags?.fit ? st.fit.samples : null;
    const pick = st.front && !st.front.error ? st.front.study.pick : null;
    const a = st.adaptive;
    const adaptive = a ? { added: a.report.added.map((x) => x.sample), next: a.proposal.error ? null : a.proposal.candidate } : null;
    const sur = st.view.model === 'surrogate';
    // The LoFi maps' BAcc is the Wk-weighted one with Wk comfort (the reports' `bacc_wk`).
    const wk = (r) => (st.state.comfort === 'wk' ? { ...r, bacc: r.bacc_wk } : r);
    // With robust cases the LoFi maps are robust (or one case's): their value at the design.
    const cased = !sur && st.state.cases && st.mapDesign && shown;
    const value = sur ? st.surrogate.design : cased ? st.mapDesign : wk(lofi.design);
    const ref = sur ? st.surrogate.datum : cased ? shown.datum : wk(lofi.datum);
    const klass = classMarks(st);
    $('maps-key-class').hidden = !klass;
    for (const v of this.ui.maps) {
      const k = v.crit.key;
      const caption = shown && (st.view.model === 'lofi' || sur) ? MapView.caption(v.crit, value[k], ref[k], st.view.scale) : '';
      v.setMarkers({ design: { ks: state.ks, cs: state.cs }, datum, samples, pick, adaptive, klass }, caption);
    }
    this.ui.uncertainty.moveDesign({ ks: state.ks, cs: state.cs });
  }

  /** The surrogate panel's report and the markers of its samples. */
  fit(ms) {
    const r = this.store.fit;
    renderMetrics($('sur-metrics'), r);
    $('sur-tuning').textContent = tuningText(r);
    this.fitStatus(`${r.surrogate} on ${r.plan}: fitted and validated in ${fmt(ms, 3)} ms (worker).`);
    this.markers();
  }

  fitStatus(text) {
    $('sur-status').textContent = text;
  }

  /**
   * The Surrogate tab's adaptive loop: buttons (disabled while `busy`), the proposal's
   * line, the samples added and the history chart; the map and plane keys of the loop.
   */
  adaptive(busy) {
    const a = this.store.adaptive;
    // A converged loop (the core's stop rule) offers one more run anyway, not five.
    const converged = Boolean(a && a.proposal.converged);
    $('ad-next').disabled = busy;
    $('ad-next').textContent = converged ? 'Run anyway' : 'Next HiFi run';
    $('ad-more').disabled = busy || converged;
    $('maps-key-adaptive').hidden = !a;
    if (!busy) this.adaptiveStatus(a ? proposalText(a.proposal) : 'No adaptive run yet: "Next HiFi run" runs the plan on the HiFi, fits the surrogate and adds one HiFi run where it helps the front most.');
    renderAdaptive($('ad-samples'), a);
    $('ad-chart-box').hidden = !a;
    if (a) this.ui.adaptiveChart.draw(adaptiveSpec(a));
    this.uncertainty();
  }

  /** The adaptive loop's uncertainty map and its caption (hidden without a loop). */
  uncertainty() {
    const st = this.store;
    this.ui.uncertainty.show(st.adaptive, {
      box: st.desc.designBox, design: { ks: st.state.ks, cs: st.state.cs }, datum: { ks: st.desc.datumKs, cs: st.desc.datumCs },
      palette: st.view.palette, tables: this.ui.tables,
    });
  }

  adaptiveStatus(text) {
    $('ad-status').textContent = text;
  }

  /** The NSGA-II front on the plane, and its line. */
  nsga() {
    const st = this.store;
    const r = st.nsga;
    const stm = st.front && !st.front.error ? fmt(st.front.study.hypervolume, 4) : '–';
    this.nsgaStatus(r.error
      ? `NSGA-II: ${r.error}`
      : `NSGA-II (population 60, 60 generations, seed 1): ${r.study.front.length} points, hypervolume ${fmt(r.study.hypervolume, 4)} vs STM ${stm} (each against its own reference point).`);
    this.plane();
  }

  /** The HiFi's own front arrived (or failed): the plane, its line and the Pick tab's table. */
  hifiFront() {
    const h = this.store.hifiFront;
    this.hifiFrontStatus(hifiFrontLine(h, this.store.front));
    $('op-hifi-status').title = h && !h.error ? hifiFrontTitle(h) : '';
    renderHifiFront($('op-hifi'), h, this.store.front);
    this.plane();
  }

  hifiFrontStatus(text) {
    $('op-hifi-status').textContent = text;
  }

  nsgaStatus(text) {
    $('op-status').textContent = text;
  }

  /** The FRF / PSD panel of state `s`'s design. */
  spectra(s) {
    this.ui.spectra?.show(this.store.spectra);
    this.spectraStatus(`Ks ${fmt(s.ks / 1000, 4)} kN/m, Cs ${fmt(s.cs / 1000, 4)} kNs/m`);
  }

  spectraStatus(text) {
    $('sp-status').textContent = text;
  }

  /** The time panel's charts and side view after a run, with its status line. */
  time(text) {
    const st = this.store;
    $('tp-charts').hidden = false;
    this.ui.time?.draw(st.time.result, st.state.speed, st.time.linear);
    this.timeStale();
    $('tp-play').disabled = false;
    this.timeStatus(text);
  }

  timeStatus(text, running = false) {
    $('tp-status').textContent = text;
    $('tp-run').disabled = running;
  }

  /** Says when the time response shown belongs to an earlier design or scenario. */
  timeStale() {
    const st = this.store;
    const el = $('tp-stale');
    if (!st.time) el.textContent = 'Press "Run time response" to simulate the current design.';
    else el.textContent = st.timeCurrent() ? '' : 'The time response shown is for an earlier design or road; run it again for the current one.';
  }

  /** Projector mode on or off: type size (CSS), line widths, and every chart redrawn. */
  projector() {
    const on = this.store.view.projector;
    document.documentElement.classList.toggle('projector', on);
    const thick = on ? 1.8 : 1;
    for (const v of [...this.ui.maps, this.ui.plane, this.ui.uncertainty, ...this.panelViews()]) v.setStyle({ thick });
    requestAnimationFrame(() => this.redrawAll());
  }

  /** The charts of the panels loaded after the first map (js/panels.js), once they are. */
  panelViews() {
    return [this.ui.spectra, this.ui.time, this.ui.damper, this.ui.road].filter(Boolean);
  }

  /** The panels loaded after the first map (js/panels.js): brought up to the store and the view. */
  panels() {
    const st = this.store;
    const thick = st.view.projector ? 1.8 : 1;
    for (const v of this.panelViews()) v.setStyle({ thick });
    if (st.desc) this.ui.carEditor.show(st.desc.car);
  }

  /** Redraws every chart at its current size (after a resize, the type size or the drawer). */
  redrawAll() {
    const st = this.store;
    if (!st.state) return;
    for (const v of this.ui.maps) {
      if (v.resize()) continue;
      v.drawBase();
      v.drawOverlay();
    }
    this.plane();
    if (st.adaptive && !$('ad-chart-box').hidden) this.ui.adaptiveChart.draw(adaptiveSpec(st.adaptive));
    this.ui.uncertainty.redraw();
    if (!this.ui.spectra) return;
    if (st.spectra) this.ui.spectra.show(st.spectra);
    if (st.time) this.ui.time.draw(st.time.result, st.state.speed, st.time.linear);
    if (this.ui.damper.visible()) this.ui.damper.refresh();
  }
}
