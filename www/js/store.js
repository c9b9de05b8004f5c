// The page's data: the state (the core's state object, SI units), the view (page-only
// settings), the results computed for them, and the URL that carries state and view.
// Only the controller (js/controller.js) writes here; views never read it (they are
// handed plain data, see js/render.js).

import { encodeHash } from './urlstate.js';

/** The page-only settings of a fresh view. */
export const DEFAULT_VIEW = {
  /** Map colours: 'abs' values or 'rel' % change against the datum. */
  scale: 'abs',
  /** Projector mode: large type, thick lines, high contrast. */
  projector: false,
  /** The maps' model: 'lofi', 'hifi', 'surrogate' or 'error'. */
  model: 'lofi',
  /** The surrogate's sample plan marked on the maps. */
  plan: true,
  /** The objective plane on ratio-to-datum axes. */
  ratio: false,
  /** Colour scale of absolute map values: 'viridis' or 'cividis'. */
  palette: 'viridis',
  /** NSGA-II asked for (recomputed on scenario changes; not in the URL). */
  nsga: false,
};

/** What each map model is called on the page. */
export const MODEL_NAMES = { lofi: 'LoFi', hifi: 'HiFi', surrogate: 'surrogate', error: 'surrogate error' };

/**
 * The content key of a scenario: everything but the design point. Only the class codes
 * (js/classcode.js) use it: a code carries a hash of it, which must match on every
 * student's machine and page version. The page keys its own results by the core's tags
 * (the store's `tags`).
 */
export function scenarioKey(s) {
  return JSON.stringify({ ...s, ks: 0, cs: 0 });
}

/** The tag of a whole state (scenario and design), from the core's `tags`. */
export function stateTag(tags) {
  return `${tags.scenario}:${tags.design}`;
}

/** The state `s` at the datum design of its car (`desc` from `describe`). */
export function datumStateOf(s, desc) {
  return { ...s, ks: desc.datumKs, cs: desc.datumCs };
}

export class Store {
  constructor() {
    /** Defaults and lists from the core (js/compute.js `boot`). */
    this.defaults = null;
    this.presets = [];
    this.classes = [];
    this.surrogateNames = [];
    this.state = null;
    /**
     * The core's tags of the state (`describe`'s and `designStep`'s `tags`: `{design,
     * datum, fit, scenario}`, each a hash of the fields one kind of result depends on).
     * Every result below is kept with the tag it was asked under, and is current while
     * the state's tag is the same: the page builds no keys of its own (issue #28).
     */
    this.tags = null;
    this.view = { ...DEFAULT_VIEW };
    /** `describe` of the state's scenario. */
    this.desc = null;
    /**
     * LoFi reports of the design and the datum, always for the current state: `design` is
     * the full report when `checkedKey` is the state's design tag, else a slider step's
     * readout (the same numbers without the frequency-route check).
     */
    this.lofi = { design: null, datum: null, checkedKey: null };
    /** With robust cases, the design's criteria as the LoFi maps show them (`mapCriteria`), else null. */
    this.mapDesign = null;
    /** The surrogate's criteria of the design and the datum (`{bacc, dtl, sws, dtl_relative}`). */
    this.surrogate = { design: null, datum: null };
    /** HiFi reports and the tags (`design`, `datum`) they belong to (may lag the state). */
    /** `design` may be the quick readout of a slider move (`checkedKey` lags `key` until the full report is in). */
    this.hifi = { design: null, datum: null, key: null, datumKey: null, checkedKey: null };
    /** Designs kept to compare side by side (js/compare.js; their Ks, Cs are in the link). */
    this.saved = [];
    /**
     * The class front (js/classfront.js) when codes were applied: `{key, rows, problems}`,
     * evaluated on the scenario `key`; null when none (or cleared).
     */
    this.classFront = null;
    /** The LoFi and surrogate maps at the page's grid, each with the scenario tag (`key`) it is for. */
    this.maps = null;
    this.surMaps = null;
    /** The map shown when it is the HiFi's or the error's: `{model, key, maps, datum, ms}`. */
    this.modelMaps = null;
    /** The objective plane's feasible set (on the plane's model, js/compute.js `planeModel`). */
    this.cloud = null;
    /** The objective plane's model and the design's criteria by it (`{model, design}`). */
    this.plane = { model: 'surrogate', design: null };
    /** The STM front study of the current scenario (`{error}` when none is feasible). */
    this.front = null;
    /** The NSGA-II study when asked for, with the scenario key it is for. */
    this.nsga = null;
    /**
     * The HiFi's own front and the plane's front judged on it (js/compute.js
     * `hifiFront`: `{front, hifiRuns, compute, plane, ms}` or `{error}`), with the
     * scenario key it is for; null until it comes.
     */
    this.hifiFront = null;
    /** The surrogate's fit report and the fit tag of what it was fitted to. */
    this.fit = null;
    this.fitKey = null;
    /** FRFs and PSDs of the current design, and the tags they are for. */
    this.spectra = null;
    this.spectraKey = null;
    /**
     * The adaptive HiFi loop of the Surrogate tab (issue #15) when started, for the
     * scenario `key`: `{key, state, report, proposal, front, errors, was, ms, uncertainty}`
     * (`report`: the core's; `proposal`: the next run, or `{error}`; `front`: the loop's
     * surrogate's front; `errors[i]`: the pick's HiFi re-check error after
     * `report.history[i]`, %; `was`: the front and pick before the latest step, or null;
     * `ms`: each step's time in the worker; `uncertainty`: the loop's uncertainty map and
     * its check against the HiFi, js/engine.js `Host.adaptiveUncertainty`). Dropped when
     * the scenario changes.
     */
    this.adaptive = null;
    /** The time response when run: `{result, linear, key, opts}` (`linear`: the same road with the linear damper, for a nonlinear run). */
    this.time = null;
    /** The last custom car: `{json, ks, cs, origin}` (`origin`: 'file' or 'editor'). */
    this.custom = null;
    this.lastHash = '';
    this.urlTimer = null;
    /** A hash the address bar keeps instead of the view's (a lesson link while its lesson is open), or null. */
    this.pinnedHash = null;
  }

  /** True when the HiFi reports belong to the current design and datum. */
  hifiCurrent() {
    return this.tags !== null && this.hifi.key === this.tags.design && this.hifiDatumCurrent();
  }

  /** True when the HiFi datum report belongs to the current scenario. */
  /** The HiFi column is current and holds the full report (with its frequency-route check). */
  hifiChecked() {
    return this.hifiCurrent() && this.hifi.checkedKey === this.hifi.key;
  }

  hifiDatumCurrent() {
    return this.tags !== null && this.hifi.datumKey === this.tags.datum;
  }

  /** The map data the maps show for the view's model: `{maps, datum, kind}`, or null while computing. */
  shownMaps() {
    const m = this.view.model;
    if (this.tags === null) return null;
    const key = this.tags.scenario;
    // With Wk comfort the LoFi map's BAcc is Wk-weighted, and so is its datum's.
    const lofiDatum = this.state.comfort === 'wk' ? { ...this.lofi.datum, bacc: this.lofi.datum.bacc_wk } : this.lofi.datum;
    // With robust cases the LoFi and HiFi maps carry their own (robust or case) datum.
    const cased = (maps, d) => (this.state.cases && maps.datum ? maps.datum : d);
    if (m === 'lofi' && this.maps && this.maps.key === key) return { maps: this.maps, datum: cased(this.maps, lofiDatum), kind: 'value' };
    if (m === 'surrogate' && this.surMaps && this.surMaps.key === key) return { maps: this.surMaps, datum: this.surrogate.datum, kind: 'value' };
    const mm = this.modelMaps;
    if (mm && mm.model === m && mm.key === key) return { maps: mm.maps, datum: m === 'hifi' ? cased(mm.maps, mm.datum) : mm.datum, kind: m === 'error' ? 'error' : 'value' };
    return null;
  }

  /** The time response shown, when it was run for the current state. */
  timeCurrent() {
    return this.time !== null && this.tags !== null && this.time.key === stateTag(this.tags);
  }

  /** Writes the URL hash 120 ms after the last change (a drag writes it once). */
  scheduleUrl() {
    clearTimeout(this.urlTimer);
    this.urlTimer = setTimeout(() => this.writeUrl(), 120);
  }

  /** Keeps `hash` in the address bar (null: the view's link again, written at once). */
  pinHash(hash) {
    if (hash === this.pinnedHash) return;
    this.pinnedHash = hash;
    if (this.state) this.writeUrl();
  }

  writeUrl() {
    clearTimeout(this.urlTimer);
    this.urlTimer = null;
    const hash = this.pinnedHash || encodeHash(this.state, this.view, this.keptDesigns());
    if (hash !== location.hash) {
      this.lastHash = hash;
      history.replaceState(null, '', hash);
    }
  }

  /** The kept designs' `[[ks N/m, cs N s/m], ...]` (what the link and the session file hold). */
  keptDesigns() {
    return this.saved.map((s) => [s.ks, s.cs]);
  }

  /** The session file's object: `{ridelab: "session", version, state, view, kept}`. */
  session() {
    // A measured road's file is not kept (the road panel says so): the session keeps its class.
    const { roadProfile, ...state } = this.state;
    return { ridelab: 'session', version: 1, state, view: { ...this.view }, kept: this.keptDesigns() };
  }
}
