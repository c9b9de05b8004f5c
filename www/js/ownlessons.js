// "Your lessons": the lessons a user authored (or imported) in the lesson panel, saved in
// this browser as they are edited (js/lessonstore.js) and listed beside the shipped
// ones. Nothing authored is lost silently: a lesson whose last edit could not be stored
// is "unsaved", the panel says why on screen, and opening another lesson, a lesson link
// or a reload (the new build's "Use it now") asks first, as does leaving the page
// (beforeunload) — only then.

import { LessonStore } from './lessonstore.js';

/** "3 steps, saved 14:05" of a stored lesson. */
function subtitle({ lesson, savedAt }) {
  const n = lesson.steps.length;
  const t = savedAt ? new Date(savedAt).toLocaleTimeString([], { hour: '2-digit', minute: '2-digit' }) : '';
  return `${n} step${n === 1 ? '' : 's'}${t ? `, saved ${t}` : ''}`;
}

export class OwnLessons {
  /**
   * `list`: the `<ol>` of the user's lessons; `box`: what holds it and its heading
   * (hidden while there are none); `say(text, kind)`: the panel's message line;
   * `onOpen(item)`: a stored lesson chosen (`{id, lesson}`); `store`: a LessonStore.
   */
  constructor({ list, box, say, onOpen, store = new LessonStore() }) {
    Object.assign(this, { list, box, say, onOpen, store });
    /** The id of the lesson in the panel when it is one of the user's, else null. */
    this.id = null;
    /** Why the lesson in the panel is not stored (its last edit could not be written), or null. */
    this.unsaved = null;
    /** Its title, for the questions asked before it would be lost. */
    this.title = '';
    window.addEventListener('beforeunload', (ev) => {
      if (!this.unsaved) return;
      ev.preventDefault();
      ev.returnValue = '';
    });
  }

  /** Lists the stored lessons (newest first), each with Open and Delete. */
  render() {
    const items = this.store.list();
    this.box.hidden = items.length === 0 && !this.store.readProblem;
    this.list.replaceChildren(...items.map((it) => {
      const li = document.createElement('li');
      const open = document.createElement('button');
      open.type = 'button';
      open.dataset.own = it.id;
      open.textContent = `${it.lesson.title} (${subtitle(it)})`;
      open.addEventListener('click', () => this.onOpen(it));
      const del = document.createElement('button');
      del.type = 'button';
      del.className = 'small';
      del.textContent = '×';
      del.setAttribute('aria-label', `Delete your lesson "${it.lesson.title}"`);
      del.title = 'Delete it from this browser (download it first to keep a copy)';
      del.addEventListener('click', () => this.remove(it));
      li.append(open, ' ', del);
      return li;
    }));
    if (this.store.readProblem) this.say(this.store.readProblem, 'bad');
  }

  /** Deletes a stored lesson once the user confirms. */
  remove(it) {
    if (!window.confirm(`Delete your lesson "${it.lesson.title}" from this browser? It cannot be undone (download it first to keep a copy).`)) return;
    const r = this.store.remove(it.id);
    if (!r.ok) this.say(`Your lesson "${it.lesson.title}" could not be deleted: ${r.reason}.`, 'bad');
    if (this.id === it.id) this.id = null;
    this.render();
  }

  /** The panel now shows `lesson`, the user's stored lesson `id` or (null) another one. */
  adopt(id, lesson) {
    this.id = id;
    this.unsaved = null;
    this.title = lesson ? lesson.title : '';
  }

  /**
   * The lesson in the panel was edited (or made, or imported): stored as the user's, a
   * new one of theirs if it was not yet. Returns '' when stored, else the message the
   * panel shows (why, and what to do).
   */
  edited(lesson) {
    if (!this.id) this.id = LessonStore.newId();
    this.title = lesson.title;
    const r = this.store.save(this.id, lesson);
    this.unsaved = r.ok ? null : r.reason;
    return r.ok ? '' : `Not saved in this browser: ${r.reason}. "Download (JSON)" keeps it as a file.`;
  }

  /**
   * The lesson in the panel was downloaded as `file`: kept there, so leaving loses nothing
   * now. Returns the note to show when it is not in this browser's storage, else ''.
   */
  downloaded(file) {
    if (!this.unsaved) return '';
    const note = `Downloaded as ${file}; this browser still could not store it (${this.unsaved}).`;
    this.unsaved = null;
    return note;
  }

  /**
   * True when the lesson in the panel may be left (`what`: the action, "Open another
   * lesson"): always when it is stored, else when the user says so.
   */
  mayLeave(what) {
    if (!this.unsaved) return true;
    const ok = window.confirm(`Your lesson "${this.title}" is not saved in this browser (${this.unsaved}). ${what} anyway and lose your edits? Cancel, then "Download (JSON)", keeps it.`);
    if (ok) this.unsaved = null;
    return ok;
  }
}
