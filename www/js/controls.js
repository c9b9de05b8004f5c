// The controls as a view: puts a state into the inputs, shows a refused entry's message
// next to its field in the page's units (kN/m, kNs/m, mm) and in plain words, and
// remembers which fields hold a refused entry (those keep what the user typed).

import { fmt, fmtInput } from './format.js';

/** The name of input `el` as its label says it ("Speed, m/s"), for messages that name the field. */
export function fieldName(el) {
  const label = el.getAttribute('aria-label') || (el.labels && el.labels[0] ? el.labels[0].textContent : '') || el.id;
  return label.trim().replace(/\s+/g, ' ');
}

const $ = (id) => document.getElementById(id);

/** The input element of each field (the engine's error `field`, or a page field). */
export const FIELD_INPUT = {
  ks: 'ks-num', cs: 'cs-num', speed: 'speed', class: 'class', tracks: 'tracks', swsLimit: 'sws-limit', car: 'car',
  carFile: 'car-file', carEditor: 'car-apply',
  tpSeed: 'tp-seed', tpBump: 'tp-bump', tpRebound: 'tp-rebound', tpKnee: 'tp-knee', tpBumpHigh: 'tp-bump-high', tpReboundHigh: 'tp-rebound-high', session: 'session-load',
  box: 'ks-min', bounceBand: 'bb-lo', dampingBand: 'db-lo', surrogate: 'sur-approach', plan: 'sur-plan',
  comfort: 'comfort', pick: 'pick-rule',
};

/** Fields whose control is a menu: a refused choice goes back to the state's value. */
const MENUS = new Set(['class', 'tracks', 'car', 'surrogate', 'plan', 'comfort', 'pick']);

/**
 * A core or parser message in the page's words: serde's wording and positions made
 * plain, no `state:` prefixes, N/m and N s/m of the design variables in kN/m and kNs/m.
 */
export function plainWords(text) {
  return String(text)
    .replace(/^state: (Error: )?/, '')
    .replace(/^time options: /, '')
    .replace(/^invalid JSON: EOF while parsing a value at line 1 column 0$/, 'the file is empty')
    .replace(/^invalid JSON: /, 'not a valid car file: ')
    .replace(/^car: /, '')
    .replace(/EOF while parsing an? (value|object|list|string)/, 'the text ends too early')
    .replace(/missing field `([^`]+)`/g, "'$1' is missing")
    .replace(/unknown field `([^`]+)`, expected (one of )?(.*?)(?= at line|$)/, (m, f, one, list) => `'${f}' is not a known field (expected ${one || ''}${list.replace(/`/g, '')})`)
    .replace(/invalid type: string "([^"]*)", expected f64/g, "'$1' is not a number")
    .replace(/invalid type: ([a-z ]+?)( `[^`]*`| "[^"]*"| [^,]+)?, expected f64/g, (m, kind, v) => `${v ? v.trim().replace(/`/g, "'") : kind} is not a number`)
    .replace(/expected f64/g, 'expected a number')
    .replace(/expected u64/g, 'expected a whole number')
    .replace(/ at line (\d+) column (\d+)/, ' (line $1, column $2)')
    .replace(/^([\w.]+): '\1' is not a known field/, "'$1' is not a known field");
}

/** N/m (or N s/m) as kN/m (kNs/m): the shortest text of 6 significant digits, a typographic minus. */
export const kN = (v) => String(+(Number(v) / 1000).toPrecision(6)).replace(/^-/, '−');

/** A core message shown next to field `field`, with the display name and unit. */
export function explain(failure, field) {
  const msg = plainWords(failure.message || String(failure));
  const got = (unit) => (m, v) => `(got ${kN(v)} ${unit})`;
  if (field === 'ks') return msg.replace(/^(front\.spring|ks): /, 'Ks (front spring): ').replace(/\(got ([-\d.e+]+)\)/, got('kN/m')).replace(/ \(N\/m\)/, '');
  if (field === 'cs') return msg.replace(/^(front\.damper|cs): /, 'Cs (front damper): ').replace(/\(got ([-\d.e+]+)\)/, got('kNs/m')).replace(/ \(N s\/m\)/, '');
  if (field === 'swsLimit') {
    const mm = (v) => String(+(Number(v) * 1000).toPrecision(6));
    return msg
      .replace(/^sws_limit: must be a finite number > 0 \(m\)/, 'SWS limit: must be a number > 0 (mm)')
      .replace(/^sws_limit: ([-\d.e+]+) m is outside ([-\d.e+]+)\.\.([-\d.e+]+) m/, (m, v, lo, hi) => `SWS limit: ${mm(v)} mm is outside ${mm(lo)}..${mm(hi)} mm`);
  }
  if (field === 'bounceBand') return msg.replace(/^bounce_band: /, 'Bounce band (Hz): ');
  if (field === 'dampingBand') return msg.replace(/^damping_band: /, 'Damping band: ');
  if (field === 'surrogate') return msg.replace(/^(approach|scheme): /, 'Surrogate: ');
  if (field === 'plan') return msg.replace(/^plan: /, 'Sample plan: ');
  if (field === 'comfort') return msg.replace(/^comfort: /, 'Comfort objective: ');
  if (field === 'pick') return msg.replace(/^pick: /, 'Pick: ');
  if (field === 'box') {
    return msg
      .replace(/^(ks|cs)-range: minimum ([-\d.e+]+) must be below maximum ([-\d.e+]+)/, (m, v, lo, hi) =>
        `Design box: ${v === 'ks' ? 'Ks' : 'Cs'} from ${kN(lo)} must be below ${kN(hi)} ${v === 'ks' ? 'kN/m' : 'kNs/m'}`)
      .replace(/^(ks|cs)-range: /, (m, v) => `Design box (${v === 'ks' ? 'Ks' : 'Cs'}): `);
  }
  return msg;
}

export class Controls {
  constructor() {
    /** Fields that hold a refused entry. */
    this.bad = new Set();
  }

  /** The top banner (`text` empty hides it), with a button when `action` is `{label, run}`. */
  banner(text, kind = 'warn', action = null) {
    const b = $('banner');
    $('banner-text').textContent = text;
    b.className = kind === 'error' ? 'banner error' : 'banner';
    b.hidden = !text;
    const btn = $('banner-action');
    btn.hidden = !action;
    btn.textContent = action ? action.label : '';
    btn.onclick = action ? action.run : null;
  }

  /** Sets or clears (`text` empty) the message of `field`, and marks its input. */
  setMsg(field, text) {
    const m = $(`msg-${field}`);
    if (m) m.textContent = text || '';
    const input = $(FIELD_INPUT[field]);
    if (input) {
      if (text) input.setAttribute('aria-invalid', 'true');
      else input.removeAttribute('aria-invalid');
    }
    if (text && !MENUS.has(field)) this.bad.add(field);
    else this.bad.delete(field);
  }

  /** Clears every field's message. */
  clearAll() {
    for (const f of Object.keys(FIELD_INPUT)) this.setMsg(f, '');
  }

  /** Shows an engine failure next to the field it names (or the field being edited). */
  fail(failure, source) {
    const field = failure.field && FIELD_INPUT[failure.field] ? failure.field : source;
    if (field && FIELD_INPUT[field]) this.setMsg(field, explain(failure, field));
    else this.banner(plainWords(failure.message || String(failure)));
    if (source && source !== field && FIELD_INPUT[source]) {
      // The edit was refused because of another field; keep the edited one marked too.
      this.setMsg(source, `not applied: ${explain(failure, field)}`);
    }
  }

  /** A short note beside the car menu (`text` empty clears it). */
  note(text) {
    $('note-car').textContent = text || '';
  }

  /**
   * Puts the design (Ks, Cs) into its fields and sliders: all a slider move changes, so
   * a drag rewrites these and nothing else. The sliders span the design box (and the
   * design, if it lies outside); no step grid (step "any"), so they sit exactly at any
   * value, the datum's included.
   */
  syncDesign(s, desc) {
    if (!this.bad.has('ks')) setValue($('ks-num'), fmtInput(s.ks / 1000, 3));
    if (!this.bad.has('cs')) setValue($('cs-num'), fmtInput(s.cs / 1000, 3));
    const box = desc.designBox;
    const ksR = $('ks-range');
    const csR = $('cs-range');
    setAttr(ksR, 'min', String(Math.min(box.ks_min, s.ks) / 1000));
    setAttr(ksR, 'max', String(Math.max(box.ks_max, s.ks) / 1000));
    setAttr(csR, 'min', String(Math.min(box.cs_min, s.cs) / 1000));
    setAttr(csR, 'max', String(Math.max(box.cs_max, s.cs) / 1000));
    setValue(ksR, String(s.ks / 1000));
    setValue(csR, String(s.cs / 1000));
    setAttr(ksR, 'aria-valuetext', `${fmtInput(s.ks / 1000, 3)} kN/m`);
    setAttr(csR, 'aria-valuetext', `${fmtInput(s.cs / 1000, 3)} kNs/m`);
  }

  /**
   * Puts `state` into every control that does not hold a refused entry (menus always
   * show the state); `desc` gives the design box, `view` the view settings,
   * `custom` the custom car's label, `swsDragging` leaves the SWS slider alone.
   */
  sync(state, desc, view, { customLabel = null, swsDragging = false } = {}) {
    const s = state;
    const put = (field, id, value) => {
      if (!this.bad.has(field)) setValue($(id), value);
    };
    this.syncDesign(s, desc);
    put('speed', 'speed', fmtInput(s.speed, 3));
    $('speed-kmh').textContent = `(${fmt(s.speed * 3.6, 3)} km/h)`;
    // A measured road (the road panel's, `roadProfile`) is the road menu's last entry.
    setValue($('class'), s.roadProfile ? 'measured' : s.class);
    setValue($('tracks'), s.tracks);
    put('swsLimit', 'sws-limit', s.swsLimit == null ? '' : fmtInput(s.swsLimit * 1000, 4));
    // The SWS slider spans 1 to 20 mm (and the limit, if outside); no limit: its top.
    const swsMm = s.swsLimit == null ? null : s.swsLimit * 1000;
    const sws = $('sws-range');
    sws.min = String(Math.min(1, swsMm ?? 1));
    sws.max = String(Math.max(20, swsMm ?? 20));
    if (!swsDragging) setValue(sws, String(swsMm ?? sws.max));
    const box = desc.designBox;
    if (!this.bad.has('box')) {
      setValue($('ks-min'), fmtInput(box.ks_min / 1000, 4));
      setValue($('ks-max'), fmtInput(box.ks_max / 1000, 4));
      setValue($('cs-min'), fmtInput(box.cs_min / 1000, 4));
      setValue($('cs-max'), fmtInput(box.cs_max / 1000, 4));
    }
    for (const [field, lo, hi, band] of [['bounceBand', 'bb-lo', 'bb-hi', s.bounceBand], ['dampingBand', 'db-lo', 'db-hi', s.dampingBand]]) {
      put(field, lo, band ? fmtInput(band[0], 4) : '');
      put(field, hi, band ? fmtInput(band[1], 4) : '');
    }
    const nw = s.noWorse || [false, false, false];
    ['nw-bacc', 'nw-dtl', 'nw-sws'].forEach((id, i) => ($(id).checked = !!nw[i]));
    ensureOption($('sur-approach'), s.surrogate);
    ensureOption($('sur-plan'), s.plan);
    setValue($('sur-approach'), s.surrogate);
    setValue($('sur-plan'), s.plan);
    setValue($('comfort'), s.comfort === 'wk' ? 'wk' : 'bacc');
    const rule = pickParts(s.pick);
    setValue($('pick-rule'), rule.rule);
    $('pick-weight').disabled = rule.rule !== 'asf';
    if (rule.rule === 'asf') $('pick-weight').value = String(rule.weight);
    $('pick-weight-out').textContent = `W = ${Number($('pick-weight').value).toFixed(2)}`;
    const car = $('car');
    let opt = car.querySelector('option[value="custom"]');
    if (customLabel) {
      if (!opt) {
        opt = document.createElement('option');
        opt.value = 'custom';
        car.append(opt);
      }
      if (opt.textContent !== customLabel) opt.textContent = customLabel;
    } else if (opt) {
      opt.remove();
    }
    setValue(car, s.car);
    setValue($('map-scale'), view.scale);
    // Error maps are in % of the HiFi whatever the colour setting.
    $('map-scale').disabled = view.model === 'error';
    setValue($('map-model'), view.model);
    setValue($('map-palette'), view.palette);
    $('show-plan').checked = view.plan;
    $('projector').checked = view.projector;
    setValue($('op-scale'), view.ratio ? 'ratio' : 'abs');
  }
}

/** Sets a control's value only when it differs (a write restyles the control). */
function setValue(el, value) {
  if (el.value !== value) el.value = value;
}

/** Sets an attribute only when it differs. */
function setAttr(el, name, value) {
  if (el.getAttribute(name) !== value) el.setAttribute(name, value);
}

/**
 * The state's pick rule as the Objectives tab shows it: `{rule: 'minmax' | 'knee' | 'asf',
 * weight}` (`weight`: the comfort weight W of `asf:W`, else null).
 */
function pickParts(pick) {
  const m = /^asf:(.*)$/.exec(pick || '');
  if (m) return { rule: 'asf', weight: Number(m[1]) };
  return { rule: pick === 'knee' ? 'knee' : 'minmax', weight: null };
}

/** Adds `value` to a select's options when a link or session names one not listed. */
function ensureOption(select, value) {
  if (value && ![...select.options].some((o) => o.value === value)) {
    const o = document.createElement('option');
    o.value = value;
    o.textContent = value;
    select.append(o);
  }
}
