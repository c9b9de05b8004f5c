// The update queue: what to recompute when, and which views to redraw after. Every
// change of the state goes through here; the engines are asked through js/compute.js and
// the views are drawn through js/render.js, with the store (js/store.js) between them.
//
// A control changes -> the candidate state is computed by the main-thread engine (which
// also validates it) -> on success it becomes the state and the views that depend on it
// are redrawn; on failure the message goes next to the field and the last good state
// stays. Design changes (Ks, Cs) coalesce: a burst of slider input becomes one update
// with the latest value. Scenario changes (car, road, objectives, box, surrogate)
// recompute the surrogate, its feasible set and the front at once, and the maps a frame
// later, outside the queue. HiFi and long jobs come back from the workers; an answer for
// an earlier state is dropped.

import { latestOnly } from './engine.js';
import { DEFAULT_VIEW, MODEL_NAMES, datumStateOf, stateTag } from './store.js';
import { fromLink } from './restore.js';
import { FIELD_INPUT, explain, plainWords } from './controls.js';
import { HIFI_GRID, VALIDATION_LEVELS } from './compute.js';
import { fmt } from './format.js';
import { designText } from './chartspecs.js';
import { MAX_SAVED, evaluateKept, pendingEntry } from './compare.js';

/** How long a design rests before its HiFi readout is checked by the full report, ms. */
const CHECK_AFTER_MS = 120;

/** A promise that resolves after the next frame has been painted. */
function afterPaint() {
  return new Promise((r) => requestAnimationFrame(() => setTimeout(r, 0)));
}

const nextTask = () => new Promise((r) => setTimeout(r, 0));

export class Controller {
  /** `store`, `compute` (js/compute.js), `render` (js/render.js), `controls` (js/controls.js). */
  constructor(store, compute, render, controls) {
    this.store = store;
    this.compute = compute;
    this.render = render;
    this.controls = controls;
    /** Updates and jobs in flight (queued or waiting for a worker). */
    this.pending = 0;
    this.queued = 0;
    this.chain = Promise.resolve();
    /** The latest design request (bursts coalesce into it) and the SWS slider's. */
    this.pendingDesign = null;
    /** The design request being computed (between the queue and the state). */
    this.movingTo = null;
    this.pendingSwsMm = null;
    this.mapsJob = null;
    this.spectraTimer = null;
    /**
     * ms from an input to: the LoFi views (`design`), every view with the HiFi column
     * current (`full`), the next frame (`frame`, from the input event's time stamp);
     * scenario updates and their phases; the maps after a scenario edit; the HiFi maps
     * in the worker (`modelMaps`).
     */
    this.metrics = { design: [], full: [], frame: [], scenario: [], scenarioPhases: [], maps: [], modelMaps: [] };
    /**
     * Counters of what was done: fronts drawn, NSGA-II runs and the stale answers dropped,
     * and `nsgaLog` (per accepted NSGA-II answer: the scenario it was for and the one shown).
     */
    /**
     * Called when the first screen is painted: the first map drawn, or the maps failed, or
     * with HiFi or error maps the plane and readout (the page starts its workers then).
     */
    this.onFirstMap = () => {};
    /** True once the page's first maps are drawn (`counters.firstMapAt`: when they were on the screen). */
    this.firstMapsDrawn = false;
    /** True once `load` showed a scenario; `planeDeferred`: the plane waits for the maps. */
    this.scenarioShown = false;
    this.planeDeferred = false;
    this.counters = { frontDraws: 0, frontDrawnAt: 0, nsgaRuns: 0, nsgaDropped: 0, nsgaLog: [], firstMapAt: null, adaptiveDropped: 0 };
    /** True while the adaptive loop runs (its buttons are disabled). */
    this.adaptiveBusy = false;
    /** Called after the views show something new (a design, the HiFi column, the fit, the maps): the lesson panel re-reads its numbers. */
    this.onViewsChanged = () => {};
    /**
     * Called when the kept designs changed under the user (a link or session file, a new
     * scenario): `(note, bad)`, app.js redraws them and shows the note (`bad`: some dropped).
     */
    this.onSavedChanged = () => {};
    /** The timer that asks for the full HiFi report once a slider move has rested. */
    this.checkTimer = null;

    this.hifiRun = latestOnly(async (req) => {
      if (this.store.hifi.datumKey !== req.datumKey) {
        this.store.hifi.datum = await this.compute.hifiReport(req.datumState);
        this.store.hifi.datumKey = req.datumKey;
      }
      const { lofi, hifi: design } = await this.compute.designReports(req.s);
      return { ...req, design, lofi };
    });
    // Each worker job is asked with the state and its tags (`{s, tags}`, js/store.js
    // `tags`) and answers with them, so its answer is shown only while they are current.
    this.modelMapsRun = latestOnly(async ({ s, tags, model, datumState }) => {
      const t0 = performance.now();
      const r = await this.compute.modelMaps(s, tags.fit, model, datumState);
      return { tags, model, ...r, ms: performance.now() - t0 };
    });
    this.fitRun = latestOnly(({ s, tags }) => this.compute.fit(s, tags.fit).then((r) => ({ tags, r })));
    this.hifiFrontRun = latestOnly(({ s, tags }) => this.compute.hifiFront(s, tags.fit).then((r) => ({ tags, r })));
    this.nsgaRun = latestOnly(({ s, tags }) => {
      this.counters.nsgaRuns++;
      return this.compute.nsga(s, tags.fit).then((r) => ({ tags, r }));
    });
    this.spectraRun = latestOnly(({ s, tags }) => this.compute.spectra(s).then((r) => ({ tags, r })));
  }

  /** The design the page is moving to (`{ks, cs}`): the latest request, else the state's. */
  targetDesign() {
    const p = this.pendingDesign || this.movingTo;
    return p ? { ks: p.ks, cs: p.cs } : { ks: this.store.state.ks, cs: this.store.state.cs };
  }

  /** True when every view shows the current state (the plane's animation ended, the HiFi front came) and nothing is queued. */
  isSettled() {
    const hf = this.store.hifiFront;
    return this.pending === 0 && this.pendingDesign === null && this.store.hifiChecked() && !this.render.ui.plane.animating &&
      hf !== null && hf.key === this.store.tags?.scenario;
  }

  /** Runs `fn` after every earlier update; each reads the state when it starts. */
  enqueue(fn) {
    this.pending++;
    this.queued++;
    const p = this.chain.then(fn).finally(() => {
      this.pending--;
      this.queued--;
    });
    this.chain = p.catch((e) => this.controls.banner(`Internal error: ${e && e.message ? e.message : e}`, 'error'));
    return p;
  }

  /** Counts a job in flight until `p` settles. */
  track(p) {
    this.pending++;
    return p.finally(() => this.pending--);
  }

  // ------------------------------------------------------------ scenario and design

  /**
   * A change of car, road, objective, box or surrogate (`patch` of the state, or a
   * function read when the update runs) made in field `source`; `note` is said beside
   * the car menu when it applies; `onFail(failure)` shows a refusal instead of the field
   * the core names (a car file's message stays beside the file). Resolves true when applied.
   */
  changeScenario(patchOrFn, source, { note = '', onFail = null } = {}) {
    const tIn = performance.now();
    return this.enqueue(async () => {
      const t0 = performance.now();
      const st = this.store;
      const patch = typeof patchOrFn === 'function' ? patchOrFn() : patchOrFn;
      // A class chosen (the road menu, a lesson step, a class code) leaves the measured road.
      const s = { ...st.state, ...patch };
      if ('class' in patch && !('roadProfile' in patch)) delete s.roadProfile;
      if (s.roadProfile === null) delete s.roadProfile;
      let r;
      try {
        r = await this.compute.scenario(s);
      } catch (e) {
        if (onFail) onFail(e);
        else this.controls.fail(e, source);
        this.render.controls(); // menus go back to the state
        return false;
      }
      if (source) this.controls.setMsg(source, '');
      for (const f of Object.keys(patch)) if (FIELD_INPUT[f]) this.controls.setMsg(f, '');
      this.controls.note(note);
      this.adopt(s, r);
      const t1 = performance.now();
      this.scenarioChanged();
      this.metrics.scenario.push(performance.now() - t0);
      this.metrics.scenarioPhases.push({ wait: t0 - tIn, compute: t1 - t0, render: performance.now() - t1 });
      if (!st.hifiCurrent()) this.requestHifi(t0);
      return true;
    });
  }

  /** Takes a computed scenario `r` (js/compute.js `scenario`) for state `s`. */
  adopt(s, r) {
    const st = this.store;
    st.state = s;
    st.tags = r.desc.tags;
    st.desc = r.desc;
    st.lofi = { ...r.lofi, checkedKey: st.tags.design };
    st.mapDesign = r.mapDesign;
    st.surrogate = r.surrogate;
    st.cloud = r.cloud;
    st.front = r.front;
    st.plane = r.plane;
    const key = st.tags.scenario;
    if (st.nsga && st.nsga.key !== key) st.nsga = null;
    if (st.hifiFront && st.hifiFront.key !== key) st.hifiFront = null;
    if (st.adaptive && st.adaptive.key !== key) {
      st.adaptive = null;
      this.counters.adaptiveDropped++;
    }
  }

  /**
   * Redraws what a new scenario changes and starts what it needs from the workers.
   * `planeLater`: the objective plane is drawn once the maps are on the screen
   * (`drawDeferredPlane`; the page's first scenario, see `load`).
   */
  scenarioChanged({ planeLater = false } = {}) {
    this.planeDeferred = planeLater;
    this.render.scenario({ plane: !planeLater });
    this.render.adaptive(this.adaptiveBusy);
    this.counters.frontDrawnAt = performance.now();
    this.counters.frontDraws++;
    this.showMaps();
    if (this.store.view.nsga) this.requestNsga();
    this.requestHifiFront();
    this.requestFit();
    this.refreshKept();
    this.designChanged();
  }

  /**
   * The objective plane, when the first scenario left it for after its maps: its
   * feasible set and front computed first if the scenario came without them.
   */
  drawDeferredPlane() {
    if (!this.planeDeferred) return;
    this.planeDeferred = false;
    this.enqueue(async () => {
      const st = this.store;
      if (!st.front) {
        const { state: s, tags } = st;
        const parts = await this.compute.planeParts(s);
        if (st.tags.scenario !== tags.scenario) return; // a newer scenario brought its own
        st.cloud = parts.cloud;
        st.front = parts.front;
      }
      this.render.scenario();
      this.render.markers();
      this.onViewsChanged();
    });
  }

  /** Redraws what a new design changes. */
  designChanged() {
    this.render.design();
    this.render.hifi();
    this.requestSpectra();
    this.store.scheduleUrl();
    this.onViewsChanged();
  }

  /**
   * The SWS limit slider: the front and pick follow while it is dragged. Input events
   * coalesce: while an update for the slider waits in the queue, a new position only
   * replaces its value, so the front is never more than one update behind the pointer.
   */
  dragSwsLimit(mm) {
    const waiting = this.pendingSwsMm !== null;
    this.pendingSwsMm = mm;
    this.render.swsDragged(mm);
    if (waiting) return;
    this.changeScenario(() => {
      const v = this.pendingSwsMm;
      this.pendingSwsMm = null;
      return { swsLimit: v / 1000 };
    }, 'swsLimit');
  }

  /**
   * A new design (N/m, N s/m) from field `source`; `t0` is when its input happened
   * (performance.now time base). Bursts coalesce into the latest request.
   */
  changeDesign(ks, cs, source, t0 = performance.now()) {
    const waiting = this.pendingDesign !== null;
    this.pendingDesign = { ks, cs, source, t0 };
    if (waiting) return this.chain;
    return this.enqueue(async () => {
      const st = this.store;
      const { ks: k, cs: c, source: src, t0: start } = this.pendingDesign;
      this.movingTo = this.pendingDesign;
      this.pendingDesign = null;
      const s = { ...st.state, ks: k, cs: c };
      // The HiFi readout of the design (about 3 ms) in the same update once the datum's
      // is there, so every view follows the slider in one frame; the datum's (once per
      // scenario) and any failure go to the HiFi worker.
      const withHifi = st.hifiDatumCurrent();
      let r;
      try {
        r = await this.compute.design(s, st.desc, withHifi);
      } catch (e) {
        this.controls.fail(e, src);
        this.render.controls();
        return false;
      } finally {
        this.movingTo = null;
      }
      this.controls.setMsg('ks', '');
      this.controls.setMsg('cs', '');
      st.state = s;
      st.tags = r.tags;
      // The step's readouts, unless the full report of this very design is shown (a
      // checked report stays checked only while it is the one shown).
      if (st.lofi.checkedKey !== r.tags.design) st.lofi = { ...st.lofi, design: r.lofi, checkedKey: null };
      st.mapDesign = r.mapDesign;
      st.surrogate = { ...st.surrogate, design: r.surrogate };
      st.plane = { ...st.plane, design: r.plane };
      if (r.hifi && st.hifi.checkedKey !== r.tags.design) {
        st.hifi.design = r.hifi;
        st.hifi.key = r.tags.design;
        st.hifi.checkedKey = null;
      }
      this.designChanged();
      this.metrics.design.push(performance.now() - start);
      requestAnimationFrame(() => this.metrics.frame.push(performance.now() - start));
      // With a readout, the full report (the same numbers and their frequency-route
      // check) from the HiFi worker once the design has rested for CHECK_AFTER_MS, so a
      // drag is not interrupted by its answers; without one, the HiFi column itself.
      clearTimeout(this.checkTimer);
      if (r.hifi) {
        this.metrics.full.push(performance.now() - start);
        this.checkTimer = setTimeout(() => this.requestHifi(start, { counted: false }), CHECK_AFTER_MS);
      } else this.requestHifi(start);
      return true;
    });
  }

  /**
   * The HiFi reports of the current design and datum from the HiFi worker, with the
   * design's full LoFi report (the latest request waits); `counted`: its arrival is when
   * the HiFi column became current (metrics).
   */
  requestHifi(t0, { counted = true } = {}) {
    const st = this.store;
    const { state: s, tags } = st;
    this.track(
      this.hifiRun({ s, key: tags.design, datumKey: tags.datum, datumState: datumStateOf(s, st.desc), t0 })
        .then((r) => {
          if (!r || r.key !== st.tags.design) return; // superseded
          st.hifi.design = r.design;
          // The LoFi's full report: the step's readout with its frequency-route check.
          st.lofi = { ...st.lofi, design: r.lofi, checkedKey: r.key };
          st.hifi.key = r.key;
          st.hifi.checkedKey = r.key;
          this.render.hifi();
          this.onViewsChanged();
          if (counted) this.metrics.full.push(performance.now() - r.t0);
        })
        .catch((e) => this.controls.banner(`The HiFi model failed: ${e.message || e}`, 'error')),
    );
  }

  // ------------------------------------------------------------ view settings

  /** A change of view settings (`patch` of the view): redraws what shows them. */
  setView(patch) {
    const st = this.store;
    const before = st.view;
    st.view = { ...st.view, ...patch };
    if ('projector' in patch && patch.projector !== before.projector) this.render.projector();
    if ('model' in patch || 'scale' in patch || 'palette' in patch) this.showMaps();
    else if ('plan' in patch) this.render.markers();
    if ('ratio' in patch) this.render.plane();
    this.render.controls();
    st.scheduleUrl();
  }

  // ------------------------------------------------------------ maps

  /** Draws the maps of the view's model, or computes them first. */
  showMaps() {
    const st = this.store;
    const shown = st.shownMaps();
    if (shown) {
      this.render.maps(shown);
      this.onViewsChanged();
      return;
    }
    const model = st.view.model;
    if (model === 'hifi' || model === 'error') {
      this.render.mapStatus(`Computing the ${MODEL_NAMES[model]} maps (${HIFI_GRID.nx} × ${HIFI_GRID.ny}) in the worker…`);
      this.requestModelMaps();
    } else {
      this.render.mapStatus(`Computing the ${MODEL_NAMES[model]} maps…`);
      this.refreshMaps();
    }
  }

  /**
   * The LoFi (or surrogate) maps of the current scenario, computed and drawn after the
   * next paint and outside the update queue, one map per task: an edit shows its front
   * and readout first, its maps a frame later, and a newer edit never waits for a map.
   * The refresh steps aside while updates are queued and starts again if the state
   * changes under it; it reads the state when it runs. At most one is scheduled.
   * The page's first maps are the exception: nothing of the user's can wait behind them
   * yet, so they are computed and drawn at once, in the task that loaded the first state,
   * and the first screen (plane, readout and maps) paints in one frame (issue #29).
   */
  refreshMaps() {
    if (this.mapsJob) return;
    const st = this.store;
    const eager = !this.firstMapsDrawn;
    this.mapsJob = this.track(
      (async () => {
        for (let pass = 0; ; pass++) {
          const atOnce = eager && pass === 0;
          if (!atOnce) {
            await afterPaint();
            if (this.queued > 0) continue;
          }
          const s = st.state;
          const key = st.tags.scenario;
          const t0 = performance.now();
          if (!st.maps || st.maps.key !== key) st.maps = { ...(await this.compute.lofiMaps(s)), key };
          if (st.view.model === 'surrogate' && (!st.surMaps || st.surMaps.key !== key)) {
            st.surMaps = { ...(await this.compute.surrogateMaps(s)), key };
          }
          if (st.state !== s) continue;
          const shown = st.shownMaps();
          // HiFi and error maps come from the worker; their arrival draws them.
          if (!shown) {
            if (st.view.model === 'hifi' || st.view.model === 'error') {
              this.drawDeferredPlane();
              return;
            }
            continue;
          }
          let current = true;
          for (let k = 0; k < 3; k++) {
            if (st.state !== s || st.shownMaps()?.maps !== shown.maps) {
              current = false;
              break;
            }
            // Two short tasks per map (data, then drawing), so an edit waits at most one.
            this.render.mapData(k, shown);
            if (!atOnce) await nextTask();
            this.render.mapDraw(k);
            if (!atOnce) await nextTask();
          }
          if (!current || st.state !== s) continue;
          this.render.mapsDone(shown);
          this.onViewsChanged();
          if (!this.firstMapsDrawn) {
            this.firstMapsDrawn = true;
            // The first map counts once it is on the screen: after the frame that paints it.
            afterPaint().then(() => {
              this.counters.firstMapAt = performance.now();
              this.drawDeferredPlane();
              this.onFirstMap();
            });
          }
          this.metrics.maps.push(performance.now() - t0);
          return;
        }
      })()
        .catch((e) => {
          this.controls.banner(`The maps failed: ${e.message || e}`, 'error');
          this.drawDeferredPlane();
          this.onFirstMap();
        })
        .finally(() => {
          this.mapsJob = null;
        }),
    );
  }

  /** The HiFi or surrogate-error maps of the current scenario, from the heavy worker. */
  requestModelMaps() {
    const st = this.store;
    const { state: s, tags } = st;
    const model = st.view.model;
    this.track(
      this.modelMapsRun({ s, tags, model, datumState: datumStateOf(s, st.desc) })
        .then((r) => {
          if (!r) return;
          this.metrics.modelMaps.push(r.ms);
          st.modelMaps = { model: r.model, key: r.tags.scenario, maps: r.maps, datum: r.datum, ms: r.ms };
          if (r.maps.compute) this.render.computePath(r.maps.compute, r.maps.gpu);
          if (r.model === st.view.model && r.tags.scenario === st.tags.scenario) this.showMaps();
        })
        .catch((e) => this.render.mapStatus(`The ${MODEL_NAMES[model]} maps failed: ${e.message || e}`, 'bad')),
    );
  }

  // ------------------------------------------------------------ worker jobs

  /** The surrogate's fit report (samples, tuning, metrics on the HiFi grid), from the heavy worker. */
  requestFit() {
    const st = this.store;
    const { state: s, tags } = st;
    if (tags.fit === st.fitKey) return;
    this.render.fitStatus('Fitting and validating on the HiFi…');
    const t0 = performance.now();
    this.track(
      this.fitRun({ s, tags })
        .then((out) => {
          if (!out || out.tags.fit !== st.tags.fit) return;
          st.fit = out.r;
          st.fitKey = out.tags.fit;
          this.render.fit(performance.now() - t0);
          this.onViewsChanged();
        })
        .catch((e) => this.render.fitStatus(`The surrogate fit failed: ${e.message || e}`)),
    );
  }

  /**
   * The HiFi's own front of the current scenario beside the plane's (heavy worker, about
   * 5000 HiFi runs, its starting grid on the GPU when there is one); asked on every
   * scenario change, an answer for an earlier scenario dropped. Until it comes the plane
   * shows the last one only if it is for this scenario.
   */
  requestHifiFront() {
    const st = this.store;
    const { state: s, tags } = st;
    if (st.hifiFront && st.hifiFront.key === tags.scenario) return;
    this.render.hifiFrontStatus('HiFi front: computing…');
    this.track(
      this.hifiFrontRun({ s, tags }).then((out) => {
        if (!out || out.tags.scenario !== st.tags.scenario) return;
        st.hifiFront = { ...out.r, key: out.tags.scenario };
        this.render.hifiFront();
      }),
    );
  }

  /**
   * The NSGA-II front of the current scenario, from the heavy worker; asked again on
   * every later scenario change. An answer for an earlier scenario is dropped.
   */
  requestNsga() {
    const st = this.store;
    st.view.nsga = true;
    this.render.nsgaStatus('NSGA-II running…');
    this.track(
      this.nsgaRun({ s: st.state, tags: st.tags }).then((out) => {
        if (!out) return; // superseded by a newer request
        const key = out.tags.scenario;
        const now = st.tags.scenario;
        if (key !== now) {
          this.counters.nsgaDropped++;
          return;
        }
        this.counters.nsgaLog.push({ key, shown: now });
        st.nsga = { ...out.r, key };
        this.render.nsga();
      }),
    );
  }

  /**
   * `n` more HiFi runs of the adaptive loop (heavy worker), started on the current
   * scenario first when there is none for it: before each run the proposal is shown, after
   * it the panel, the markers and the plane. A scenario change drops the loop (js/store.js
   * `adaptive`); a step answered after it is dropped too.
   */
  async runAdaptive(n) {
    const st = this.store;
    if (this.adaptiveBusy) return;
    this.adaptiveBusy = true;
    this.pending++;
    this.render.adaptive(true);
    try {
      const s = st.state;
      const key = st.tags.scenario;
      if (!st.adaptive || st.adaptive.key !== key) {
        this.render.adaptiveStatus(`Running the ${s.plan} plan on the HiFi and fitting ${s.surrogate}…`);
        const r = await this.compute.adaptiveStart(s);
        if (st.tags.scenario !== key) return;
        this.render.adaptiveStatus(`Checking the uncertainty estimate against the HiFi on its ${VALIDATION_LEVELS} × ${VALIDATION_LEVELS} grid…`);
        const uncertainty = await this.compute.adaptiveUncertainty(s);
        if (st.tags.scenario !== key) return;
        st.adaptive = { key, state: s, report: r.report, proposal: r.proposal, front: r.front, errors: [r.recheck.error], was: null, ms: [], uncertainty };
        this.adaptiveShown();
      }
      for (let k = 0; k < n; k++) {
        const a = st.adaptive;
        if (!a || a.proposal.error) break;
        // Converged (the core's stop rule): only an explicit single "Run anyway" goes on.
        if (a.proposal.converged && (n > 1 || k > 0)) break;
        this.render.adaptiveStatus(`Running the HiFi at ${designText(a.proposal.candidate)} (${k + 1} of ${n})…`);
        const r = await this.compute.adaptiveStep(a.state);
        const report = st.adaptive === a ? await this.compute.adaptiveReport(a.state) : null;
        const uncertainty = st.adaptive === a ? await this.compute.adaptiveUncertainty(a.state) : null;
        if (st.adaptive !== a) return;
        const was = { front: a.front, pick: a.report.history[a.report.history.length - 1].pick };
        st.adaptive = { ...a, report, proposal: r.proposal, front: r.front, errors: [...a.errors, r.recheck.error], was, ms: [...a.ms, r.ms], uncertainty };
        this.adaptiveShown(true);
      }
    } catch (e) {
      this.render.adaptiveStatus(`The adaptive run failed: ${plainWords(e.message || String(e))}`);
    } finally {
      this.adaptiveBusy = false;
      this.pending--;
      this.render.adaptive(false);
    }
  }

  /**
   * Redraws what shows the adaptive loop: its panel, the markers and the plane (after a
   * step, `animate`: the front and pick move there from where they were).
   */
  adaptiveShown(animate = false) {
    this.render.adaptive(true);
    this.render.markers();
    this.render.plane(animate);
  }

  /** FRFs and PSDs of the current design (heavy worker), 60 ms after the last change. */
  requestSpectra() {
    const st = this.store;
    // Spectra depend on the car, road and design, and on the surrogate's fit.
    const keyFor = (tags) => `${tags.design}:${tags.fit}`;
    const key = keyFor(st.tags);
    if (key === st.spectraKey) return;
    st.spectraKey = key;
    clearTimeout(this.spectraTimer);
    if (!this.spectraTimer) this.pending++;
    this.spectraTimer = setTimeout(() => {
      this.spectraTimer = null;
      const s = st.state;
      this.spectraRun({ s, tags: st.tags })
        .then((out) => {
          if (!out || keyFor(out.tags) !== keyFor(st.tags)) return;
          st.spectra = out.r;
          this.render.spectra(s);
        })
        .catch((e) => {
          st.spectraKey = null;
          st.spectra = null;
          this.render.spectra(s);
          this.render.spectraStatus(`Spectra failed: ${e.message || e}`);
        })
        .finally(() => this.pending--);
    }, 60);
  }

  /**
   * Runs the time response of the current design (`opts`: `seed` and the damper; heavy
   * worker); with a nonlinear damper also the linear run on the same road, to overlay.
   */
  async runTime(opts, describeRun) {
    const st = this.store;
    const { state: s, tags } = st;
    this.pending++;
    const t0 = performance.now();
    this.render.timeStatus('Simulating…', true);
    try {
      const [result, linear] = await Promise.all([
        this.compute.time(s, opts),
        opts.damper ? this.compute.time(s, { seed: opts.seed }) : null,
      ]);
      st.time = { result, linear, key: stateTag(tags), opts };
      this.render.time(`Done in ${fmt(performance.now() - t0, 3)} ms (${describeRun}).`);
    } catch (e) {
      this.render.timeStatus(`The time response failed: ${e.message || e}`);
    } finally {
      this.pending--;
    }
  }

  // ------------------------------------------------------------ links and sessions

  /**
   * The state, view and kept designs a hash asks for, as far as they can be used
   * (js/restore.js: each bad key named in `problems`); the defaults when none of it can.
   */
  async fromHash(hash) {
    const st = this.store;
    try {
      return await fromLink(this.compute, st.defaults, hash);
    } catch (e) {
      return { state: { ...st.defaults }, view: {}, kept: null, problems: [`it cannot be used (${explain(e, e.field)}), so the default view is shown`] };
    }
  }

  /**
   * Shows `state`, `view` and the `kept` designs in place of the current ones; the
   * `problems` (what of the link or file was left out, each with its reason) and any kept
   * design that cannot be evaluated are named in the banner. `origin` ('link' or
   * 'session') names where they came from. A state the engine cannot compute is refused
   * with the reason and the current state stays (at start-up, with none yet, the
   * defaults are shown). Resolves true when shown.
   */
  async load({ state, view, kept = null, problems = [] }, origin = 'link') {
    const st = this.store;
    const what = origin === 'session' ? 'This session file' : 'This link';
    // The page's first scenario on LoFi or surrogate maps: the maps are computed and drawn
    // in this task, the plane's feasible set and front once they are on the screen, so
    // the first maps paint sooner (issue #29).
    const first = !this.scenarioShown;
    const planeLater = first && ['lofi', 'surrogate'].includes({ ...DEFAULT_VIEW, ...view }.model);
    let r;
    try {
      r = await this.compute.scenario(state, { plane: !planeLater });
    } catch (e) {
      const why = plainWords(e.message || String(e));
      if (st.state) {
        this.controls.banner(`${what} cannot be computed (${why}); nothing of it was applied, the current view stays.`, 'error');
        return false;
      }
      problems = [...problems, `it cannot be computed (${why}), so the default view is shown`];
      [state, view, kept] = [{ ...st.defaults }, {}, null];
      r = await this.compute.scenario(state, { plane: !planeLater });
    }
    if (state.car === 'custom') st.custom = { json: state.carJson, ks: r.desc.datumKs, cs: r.desc.datumCs, origin, name: r.desc.car.name };
    const projector = st.view.projector;
    st.view = { ...DEFAULT_VIEW, ...view };
    st.nsga = null;
    if (kept) st.saved = [];
    this.adopt(state, r);
    this.controls.clearAll();
    if (st.view.projector !== projector) this.render.projector();
    this.scenarioShown = true;
    this.scenarioChanged({ planeLater });
    // With HiFi or error maps (the workers draw them) the first screen is the plane and
    // readout drawn here: the workers start after this paint, not after maps only they draw.
    if (first && !planeLater) afterPaint().then(() => this.onFirstMap());
    this.requestHifi(performance.now());
    const failed = kept ? await this.restoreKept(kept) : [];
    const said = [...problems, ...failed.map((f) => `kept design ${f}: cannot be evaluated (left out)`)];
    if (said.length) this.controls.banner(`${what}: ${said.join('; ')}. Each of these kept the default or was left out; the rest applies.`);
    // A load is not a drag: its link is in the address bar when the load resolves.
    st.writeUrl();
    return true;
  }

  /**
   * The kept designs of a link or session file (`[[ks N/m, cs N s/m], ...]`), evaluated
   * on the current scenario, in place of the kept list; resolves to the designs that
   * cannot be evaluated, each named with its reason.
   */
  async restoreKept(kept) {
    const st = this.store;
    const { entries, failed } = await evaluateKept(this.compute, st.state, st.desc, kept, st.tags.scenario);
    st.saved = entries;
    this.onSavedChanged(`${entries.length} of ${MAX_SAVED} designs kept, evaluated on this car and road.`);
    st.scheduleUrl();
    return failed;
  }

  /**
   * The kept designs after a scenario change: those evaluated for another scenario are
   * shown pending at once (never with the old car's numbers), then evaluated again on
   * this one in the queue; one that cannot be is dropped, and the note says why.
   */
  refreshKept() {
    const st = this.store;
    const key = st.tags.scenario;
    if (!st.saved.some((e) => e.key !== key)) return;
    st.saved = st.saved.map((e) => (e.key === key ? e : pendingEntry(e)));
    this.onSavedChanged('Evaluating the kept designs on the new car and road…');
    this.enqueue(async () => {
      if (st.tags.scenario !== key || !st.saved.some((e) => e.key !== key)) return;
      const { entries, failed } = await evaluateKept(this.compute, st.state, st.desc, st.saved.map((e) => [e.ks, e.cs]), key);
      if (st.tags.scenario !== key) return;
      st.saved = entries;
      const dropped = failed.length ? ` Dropped, as they cannot be evaluated on it: ${failed.join('; ')}.` : '';
      this.onSavedChanged(`The kept designs were evaluated again on the new car and road.${dropped}`, failed.length > 0);
      st.scheduleUrl();
    });
  }

  /** Loads a hash (a link, or the address bar's after a hash change). */
  loadHash(hash) {
    return this.enqueue(async () => this.load(await this.fromHash(hash)));
  }
}
