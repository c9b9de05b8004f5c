// The car parameter editor: one number field per car-file value (SI units shown), the
// edited car applied as a custom car, and the car file downloaded as JSON. The core
// validates the edited car (`parseCar`) and names the field at fault.

const GROUPS = [
  ['Body', [
    ['sprung_mass', 'sprung mass', 'kg'],
    ['pitch_inertia', 'pitch inertia', 'kg m²'],
    ['roll_inertia', 'roll inertia', 'kg m²'],
    ['a', 'front axle to CG, a', 'm'],
    ['b', 'rear axle to CG, b', 'm'],
    ['track_front', 'front track', 'm'],
    ['track_rear', 'rear track', 'm'],
  ]],
  ['Front corner', [
    ['front.unsprung_mass', 'unsprung mass', 'kg'],
    ['front.spring', 'spring (datum Ks)', 'N/m'],
    ['front.damper', 'damper (datum Cs)', 'N s/m'],
    ['front.tire_stiffness', 'tyre stiffness', 'N/m'],
    ['front.tire_damping', 'tyre damping', 'N s/m'],
  ]],
  ['Rear corner', [
    ['rear.unsprung_mass', 'unsprung mass', 'kg'],
    ['rear.spring', 'spring', 'N/m'],
    ['rear.damper', 'damper', 'N s/m'],
    ['rear.tire_stiffness', 'tyre stiffness', 'N/m'],
    ['rear.tire_damping', 'tyre damping', 'N s/m'],
  ]],
];

const get = (obj, path) => path.split('.').reduce((o, k) => (o == null ? undefined : o[k]), obj);
const set = (obj, path, v) => {
  const keys = path.split('.');
  const last = keys.pop();
  keys.reduce((o, k) => o[k], obj)[last] = v;
};
const idOf = (path) => `car-${path.replace('.', '-')}`;

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
        row.append(l, input);
        fs.append(row);
      }
      root.append(fs);
    }
  }

  /** Shows `car` (the car-file object). */
  show(car) {
    this.car = car;
    for (const input of this.root.querySelectorAll('input[data-path]')) {
      input.value = String(get(car, input.dataset.path));
      input.removeAttribute('aria-invalid');
    }
  }

  /** Marks the input of a core field path (`front.spring`, ...) as invalid. */
  mark(path) {
    for (const input of this.root.querySelectorAll('input[data-path]')) {
      if (input.dataset.path === path) input.setAttribute('aria-invalid', 'true');
      else input.removeAttribute('aria-invalid');
    }
  }

  /**
   * The edited car-file object, or `{error, path}` when a field is not a number (the
   * core checks ranges when the car is applied).
   */
  read() {
    const car = structuredClone(this.car);
    for (const input of this.root.querySelectorAll('input[data-path]')) {
      const text = input.value.trim().replace(',', '.');
      const v = text === '' ? NaN : Number(text);
      if (!Number.isFinite(v)) return { error: `${input.dataset.path}: '${input.value}' is not a number`, path: input.dataset.path };
      set(car, input.dataset.path, v);
    }
    if (!/\(edited\)$/.test(car.name)) car.name = `${car.name} (edited)`;
    return { car };
  }
}
