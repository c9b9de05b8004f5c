// The Time tab's controls (js/timepanel.js draws it): the seed and the front damper law
// (bump and rebound rates, a knee with the slopes above it) read from their fields,
// checked with messages that name the field, shown as the force-velocity chart and run
// as the time response.

import { DAMPER_V_MAX } from './timepanel.js';
import { fmtInput, parseNumber } from './format.js';
import { FIELD_INPUT, fieldName } from './controls.js';

const $ = (id) => document.getElementById(id);

/**
 * A number field of the time panel: `{value}` (undefined when empty and `optional`) or null
 * after a message. `scale`: the factor to SI the caller applies (1000 for kNs/m); a value
 * that overflows it is refused here, as no finite number reaches the core.
 */
function readField(controls, id, field, { optional = false, integer = false, zeroOk = false, scale = 1 } = {}) {
  const text = $(id).value.trim();
  if (optional && text === '') {
    controls.setMsg(field, '');
    return { value: undefined };
  }
  const name = fieldName($(id));
  const p = parseNumber(text);
  if (p.error) {
    controls.setMsg(field, `${name}: ${p.error}`);
    return null;
  }
  if (!Number.isFinite(p.value * scale)) {
    controls.setMsg(field, `${name}: '${text}' is too large a number`);
    return null;
  }
  if (integer && !(Number.isInteger(p.value) && p.value >= 0 && p.value <= 2 ** 32)) {
    controls.setMsg(field, `${name}: must be a whole number from 0 to ${2 ** 32}`);
    return null;
  }
  if (!integer && !(p.value > 0 || (zeroOk && p.value === 0))) {
    controls.setMsg(field, `${name}: ${zeroOk ? 'must be ≥ 0' : 'must be > 0'}`);
    return null;
  }
  controls.setMsg(field, '');
  return p;
}

/** The page's field of each field of the core's damper law. */
const LAW_FIELDS = { bump: 'tpBump', rebound: 'tpRebound', 'knee.velocity': 'tpKnee', 'knee.bump': 'tpBumpHigh', 'knee.rebound': 'tpReboundHigh' };

/** A core message on the damper law in the page's units (kNs/m rather than N s/m; long numbers in exponent form). */
function lawMessage(msg) {
  return msg
    .replace(/^[\w.]+: /, '')
    .replace(/-?\d{16,}(\.\d+)?/g, (x) => Number(x).toPrecision(6).replace(/\.?0+e/, 'e'))
    .replace(/([-\d.e+]+) N s\/m/g, (_, x) => `${fmtInput(Number(x) / 1000, 4)} kNs/m`)
    .replace(/\(got ([-\d.e+]+)\)$/, (m, x) => (/N s\/m|kNs\/m/.test(msg) ? `(got ${fmtInput(Number(x) / 1000, 4)} kNs/m)` : m));
}

/**
 * The time panel's damper fields as the core's law (N s/m, m/s): `{law}` with `law`
 * null for the design's linear damper, or null after a message beside the field.
 * `live` (while the fields are being filled in): a law still incomplete is no error yet.
 */
function damperLaw(controls, { live = false } = {}) {
  const bump = readField(controls, 'tp-bump', 'tpBump', { optional: true, scale: 1000 });
  const rebound = readField(controls, 'tp-rebound', 'tpRebound', { optional: true, scale: 1000 });
  const knee = readField(controls, 'tp-knee', 'tpKnee', { optional: true });
  const bumpHigh = readField(controls, 'tp-bump-high', 'tpBumpHigh', { optional: true, zeroOk: true, scale: 1000 });
  const reboundHigh = readField(controls, 'tp-rebound-high', 'tpReboundHigh', { optional: true, zeroOk: true, scale: 1000 });
  if (!bump || !rebound || !knee || !bumpHigh || !reboundHigh) return null;
  if ((bump.value === undefined) !== (rebound.value === undefined)) {
    if (!live) controls.setMsg(bump.value === undefined ? 'tpBump' : 'tpRebound', 'give both bump and rebound, or neither');
    return null;
  }
  const high = [knee, bumpHigh, reboundHigh];
  const given = high.filter((f) => f.value !== undefined).length;
  if (given && (given < 3 || bump.value === undefined)) {
    if (live) return null;
    const field = bump.value === undefined ? 'tpBump' : ['tpKnee', 'tpBumpHigh', 'tpReboundHigh'][high.findIndex((f) => f.value === undefined)];
    controls.setMsg(field, 'a knee needs the knee speed, both slopes above it, and bump and rebound');
    return null;
  }
  if (bump.value === undefined) return { law: null };
  const law = { bump: bump.value * 1000, rebound: rebound.value * 1000, knee: null };
  if (given) law.knee = { velocity: knee.value, bump: bumpHigh.value * 1000, rebound: reboundHigh.value * 1000 };
  return { law };
}

export function wireTime({ store, controller: ctl, controls, compute, ui }) {
  /** The force-velocity chart of the fields' law (the design's Cs when empty); false when there is none to draw. */
  const showDamper = ({ live = false } = {}) => {
    const d = damperLaw(controls, { live });
    if (!d) return false;
    const law = d.law || { bump: store.state.cs, rebound: store.state.cs, knee: null };
    try {
      ui.damper.draw(compute.damperCurve(law, DAMPER_V_MAX), !d.law);
      return true;
    } catch (e) {
      const field = LAW_FIELDS[e.field] || 'tpBump';
      controls.setMsg(field, `${fieldName($(FIELD_INPUT[field]))}: ${lawMessage(e.message || String(e))}`);
      return false;
    }
  };
  ui.damper.refresh = () => showDamper({ live: true });
  for (const id of ['tp-bump', 'tp-rebound', 'tp-knee', 'tp-bump-high', 'tp-rebound-high']) $(id).addEventListener('change', ui.damper.refresh);
  $('tp-run').addEventListener('click', () => {
    const seed = readField(controls, 'tp-seed', 'tpSeed', { integer: true });
    if (!seed || !showDamper()) return;
    const { law } = damperLaw(controls);
    const opts = { seed: seed.value };
    // With a bump / rebound law the run's Cs is their mean (the core's rule, as in `ridelab simulate`).
    if (law) opts.damper = law;
    const kns = (x) => fmtInput(x / 1000, 4);
    const what = law
      ? `${law.knee ? 'digressive' : 'asymmetric'} damper ${kns(law.bump)} / ${kns(law.rebound)} kNs/m` +
        `${law.knee ? ` to ${fmtInput(law.knee.velocity, 4)} m/s, ${kns(law.knee.bump)} / ${kns(law.knee.rebound)} kNs/m above` : ''}` +
        `, so Cs = their mean ${kns((law.bump + law.rebound) / 2)} kNs/m`
      : 'linear damper';
    // On a measured road the profile itself is played back: no seed.
    const road = store.state.roadProfile ? `${store.state.roadProfile.replace(/#[0-9a-f]+$/, '')} played back from its start` : `seed ${seed.value}`;
    ctl.runTime(opts, `${what}, ${road}`);
  });
  $('tp-play').addEventListener('click', () => ui.time.toggle());
  $('tp-rate').addEventListener('change', (ev) => {
    ui.time.rate = Number(ev.target.value);
    ui.time.drawFrame();
  });
}
