// The user's own lessons, kept in this browser (localStorage) as they are edited, so that
// a reload, a new build of the page or another lesson opened loses none of them. Each is
// `{id, lesson, savedAt}` (`lesson` in the lesson format of js/lessons.js, possibly a
// draft that does not pass its checks yet; `savedAt` ms since 1970). Writing can fail
// (storage full, storage off in a private window): `save` then says why, and the lesson
// panel says so on screen and guards the page's exits (js/lessonpanel.js).

/** The localStorage key of the list. */
const KEY = 'ridelab.lessons';

/** Why a write or read of localStorage failed, in the page's words. */
function why(e) {
  const name = e && e.name;
  if (name === 'QuotaExceededError' || name === 'NS_ERROR_DOM_QUOTA_REACHED') return "this browser's storage for the page is full";
  if (name === 'SecurityError') return 'this browser does not let the page store anything (private window or blocked storage)';
  return `this browser refused to store it (${(e && e.message) || e})`;
}

/**
 * A stored draft in the lesson format's shape (title, steps with view, question, options,
 * reveal, highlight, hide), or null when it is not one. Drafts need not pass the
 * format's checks (the editor shows what is wrong), only have its shape.
 */
function draftOf(v) {
  if (!v || typeof v !== 'object' || typeof v.title !== 'string' || !Array.isArray(v.steps) || v.steps.length === 0) return null;
  const str = (x) => (typeof x === 'string' ? x : '');
  const strs = (x) => (Array.isArray(x) ? x.filter((y) => typeof y === 'string') : []);
  return {
    ridelab: 'lesson',
    version: 1,
    title: v.title,
    // Other keys of a step (fields the format may add) are kept as they are.
    steps: v.steps.map((s) => ({
      ...(s && typeof s === 'object' ? s : {}),
      view: str(s && s.view),
      question: str(s && s.question),
      options: strs(s && s.options),
      reveal: str(s && s.reveal),
      highlight: strs(s && s.highlight),
      hide: strs(s && s.hide),
    })),
  };
}

export class LessonStore {
  /** `storage`: the Storage to use (the page's localStorage; a stand-in in tests). */
  constructor(storage = null) {
    this.storage = storage;
    /** Why the last read found stored lessons it could not use ('' when none). */
    this.readProblem = '';
  }

  /** The page's localStorage, or the error its access throws (storage off). */
  area() {
    return this.storage || globalThis.localStorage;
  }

  /** The stored lessons, newest first; an entry that is no lesson is left out (and `readProblem` says so). */
  list() {
    this.readProblem = '';
    let raw;
    try {
      raw = this.area().getItem(KEY);
    } catch (e) {
      this.readProblem = `Your lessons cannot be read: ${why(e)}.`;
      return [];
    }
    if (!raw) return [];
    let items;
    try {
      items = JSON.parse(raw);
    } catch {
      this.readProblem = 'Your stored lessons could not be read (not JSON); they are kept as they are.';
      return [];
    }
    if (!Array.isArray(items)) return [];
    const out = [];
    let bad = 0;
    for (const it of items) {
      const lesson = it && typeof it.id === 'string' ? draftOf(it.lesson) : null;
      if (lesson) out.push({ id: it.id, lesson, savedAt: Number(it.savedAt) || 0 });
      else bad++;
    }
    if (bad) this.readProblem = `${bad} stored lesson${bad === 1 ? '' : 's'} could not be read and ${bad === 1 ? 'is' : 'are'} left out.`;
    return out.sort((a, b) => b.savedAt - a.savedAt);
  }

  /** Writes `items`: `{ok: true}` or `{ok: false, reason}`. */
  write(items) {
    try {
      this.area().setItem(KEY, JSON.stringify(items));
      return { ok: true };
    } catch (e) {
      return { ok: false, reason: why(e) };
    }
  }

  /** Stores `lesson` under `id` (replacing its earlier version): `{ok}` or `{ok: false, reason}`. */
  save(id, lesson) {
    // A list that cannot be read is not overwritten (nothing stored is lost).
    const items = this.list();
    if (this.readProblem && !items.length && this.hasRaw()) return { ok: false, reason: this.readProblem };
    const rest = items.filter((x) => x.id !== id);
    return this.write([{ id, lesson, savedAt: Date.now() }, ...rest]);
  }

  /** Deletes lesson `id`: `{ok}` or `{ok: false, reason}`. */
  remove(id) {
    return this.write(this.list().filter((x) => x.id !== id));
  }

  /** True when something is stored under the key. */
  hasRaw() {
    try {
      return this.area().getItem(KEY) !== null;
    } catch {
      return false;
    }
  }

  /** A new lesson id, unique in this browser. */
  static newId() {
    return `own-${Date.now().toString(36)}-${Math.random().toString(36).slice(2, 8)}`;
  }
}
