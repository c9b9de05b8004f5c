// The car parameter editor: one number field per car-file value, in the page's units
// (springs and tyres in kN/m, dampers in kNs/m; the file holds SI), the edited car
// applied as a custom car, and the car file downloaded as JSON. The core validates the
// edited car (`parseCar`) and names the field at fault; the message goes beside it.

import { kN, plainWords } from './controls.js';

/** `[path, label, unit, factor]`: the display value is the file's value over `factor`. */
const GROUPS = [
  ['Body', [
    ['sprung_mass', 'sprung mass', 'kg', 1],
    ['pitch_inertia', 'pitch inertia', 'kg m²', 1],
    ['roll_inertia', 'roll inertia', 'kg m²', 1],
    ['a', 'front axle to CG, a', 'm', 1],
    ['b', 'rear axle to CG, b', 'm', 1],
    ['track_front', 'front track', 'm', 1],
    ['track_rear', 'rear track', 'm', 1],
  ]],
  ['Front corner', [
    ['front.unsprung_mass', 'unsprung mass', 'kg', 1],
    ['front.spring', 'spring (datum Ks)', 'kN/m', 1000],
    ['front.damper', 'damper (datum Cs)', 'kNs/m', 1000],
    ['front.tire_stiffness', 'tyre stiffness', 'kN/m', 1000],
    ['front.tire_damping', 'tyre damping', 'kNs/m', 1000],
  ]],
  ['Rear corner', [
    ['rear.unsprung_mass', 'unsprung mass', 'kg', 1],
    ['rear.spring', 'spring', 'kN/m', 1000],
    ['rear.damper', 'damper', 'kNs/m', 1000],
    ['rear.tire_stiffness', 'tyre stiffness', 'kN/m', 1000],
    ['rear.tire_damping', 'tyre damping', 'kNs/m', 1000],
  ]],
];

const FIELDS = new Map(GROUPS.flatMap(([, fields]) => fields.map((f) => [f[0], f])));

const get = (obj, path) => path.split('.').reduce((o, k) => (o == null ? undefined : o[k]), obj);
const set = (obj, path, v) => {
  const keys = path.split('.');
  const last = keys.pop();
  keys.reduce((o, k) => o[k], obj)[last] = v;
};
const idOf = (path) => `car-${path.replace('.', '-')}`;

/** A core message about car field `path` in the editor's words and units. */
export function carFieldMessage(path, message) {
  const f = FIELDS.get(path);
  let text = plainWords(message).replace(new RegExp(`^${path.replace('.', '\\.')}: `), '');
  if (f && f[3] !== 1) {
    text = text.replace(/\(got ([-\d.e+]+)\)/, (m, v) => `(got ${kN(v)} ${f[2]})`).replace(/ \(N s\/m\)| \(N\/m\)/, '');
  }
  return f ? `${f[1]}: ${text}` : text;
}

export class CarEditor {
  /** `root`: the container of the fields. */
  constructor(root) {
    this.root = root;
    this.car = null;
    for (const [title, fields] of GROUPS) {
      const fs = document.createElement('fieldset');
      const lg = document.createElement('legend');
      lg.textContent = title;
      fs.append(lg);
      for (const [path, label, unit] of fields) {
        const row = document.createElement('div');
        row.className = 'field car-field';
        const l = document.createElement('label');
        l.htmlFor = idOf(path);
        l.innerHTML = `${label} <span class="unit">${unit}</span>`;
        const input = document.createElement('input');
        input.type = 'text';
        input.inputMode = 'decimal';
        input.autocomplete = 'off';
        input.id = idOf(path);
        input.dataset.path = path;
        input.size = 9;
        const msg = document.createElement('span');
        msg.className = 'msg';
        msg.id = `msg-${idOf(path)}`;
        msg.setAttribute('role', 'alert');
        row.append(l, input, msg);
        fs.append(row);
      }
      root.append(fs);
    }
  }

  /** Shows `car` (the car-file object). */
  show(car) {
    this.car = car;
    for (const input of this.root.querySelectorAll('input[data-path]')) {
      const f = FIELDS.get(input.dataset.path);
      input.value = String(+(get(car, input.dataset.path) / f[3]).toPrecision(12));
    }
    this.mark('', '');
  }

  /** Marks the input of a core field path (`front.spring`, ...) with `message`; '' clears all. */
  mark(path, message) {
    for (const input of this.root.querySelectorAll('input[data-path]')) {
      const hit = input.dataset.path === path;
      if (hit) input.setAttribute('aria-invalid', 'true');
      else input.removeAttribute('aria-invalid');
      document.getElementById(`msg-${input.id}`).textContent = hit ? message : '';
    }
  }

  /** True when the core field path names one of the editor's fields. */
  has(path) {
    return FIELDS.has(path);
  }

  /**
   * The edited car-file object (SI), or `{error, path}` when a field is not a number (the
   * core checks ranges when the car is applied).
   */
  read() {
    const car = structuredClone(this.car);
    for (const input of this.root.querySelectorAll('input[data-path]')) {
      const text = input.value.trim().replace(',', '.');
      const v = text === '' ? NaN : Number(text);
      const path = input.dataset.path;
      if (!Number.isFinite(v)) return { error: `${FIELDS.get(path)[1]}: '${input.value}' is not a number`, path };
      const factor = FIELDS.get(path)[3];
      const si = factor === 1 ? v : Math.round(v * factor * 1e6) / 1e6;
      // No infinity reaches the core (it would arrive as null).
      if (!Number.isFinite(si)) return { error: `${FIELDS.get(path)[1]}: '${input.value}' is too large a number`, path };
      set(car, path, si);
    }
    if (!/\(edited\)$/.test(car.name)) car.name = `${car.name} (edited)`;
    return { car };
  }
}
