// The lesson panel's authoring half (js/lessonpanel.js mixes these methods into its
// class): a new lesson from the current view, the editor (title, question, options,
// reveal, outline and hidden ids; add, move, delete a step; use the current view), every
// edit saved as the user's own lesson in this browser (js/ownlessons.js), the user's
// stored lessons opened again (a draft that does not pass its checks yet opens in the
// editor), and the lesson exported or imported as a JSON file or a link.

import { PLACEHOLDERS, checkLesson, lessonHash, lessonJson, readLesson } from './lessons.js';
import { encodeHash } from './urlstate.js';
import { download } from './exports.js';

const $ = (id) => document.getElementById(id);

/** Throws `{message}` naming the step and field when a highlighted or hidden id is no element of the page. */
export function checkIds(lesson) {
  for (const [i, s] of lesson.steps.entries()) {
    for (const key of ['highlight', 'hide']) {
      s[key].forEach((id, j) => {
        if (!$(id)) throw { message: `steps[${i}].${key}[${j}]: no element '${id}' on the page` };
      });
    }
  }
}

/** A deep copy of a checked lesson (the panel edits its own). */
export const copy = (lesson) => JSON.parse(JSON.stringify(lesson));

/** The authoring methods of LessonPanel (`this` is the panel). */
export const AUTHORING = {
  /**
   * Opens one of the user's stored lessons; a draft that does not pass the format's
   * checks yet opens in the editor with what is wrong said, its view left as it is.
   */
  async openOwn({ id, lesson }) {
    if (!this.own.mayLeave('Open another lesson')) return false;
    if (await this.start(lesson, 0, '', { ownId: id })) return true;
    const problem = $('lesson-msg').textContent;
    this.lesson = copy(lesson);
    this.own.adopt(id, this.lesson);
    this.linkHash = null;
    this.k = 0;
    this.revealed = false;
    this.picked = null;
    $('lesson-list').hidden = true;
    $('lesson-step').hidden = false;
    for (const x of ['lesson-edit-toggle', 'lesson-export', 'lesson-copy', 'lesson-menu']) $(x).hidden = false;
    if ($('lesson-edit').hidden) this.toggleEdit();
    this.pinLink();
    this.show();
    this.say(`A draft: ${problem}`, 'bad');
    return true;
  },

  listPlaceholders() {
    $('le-placeholders').replaceChildren(...Object.entries(PLACEHOLDERS).flatMap(([name, p]) => {
      const dt = document.createElement('dt');
      dt.textContent = `{${name}}`;
      const dd = document.createElement('dd');
      dd.textContent = p.about;
      return [dt, dd];
    }));
  },

  /** A new lesson of one step, the current view; saved as the user's at once. */
  newLesson() {
    return this.start({ ridelab: 'lesson', version: 1, title: 'My lesson', steps: [this.viewStep()] }).then((ok) => {
      if (!ok) return;
      this.edited();
      if ($('lesson-edit').hidden) this.toggleEdit();
    });
  },

  /**
   * The lesson was edited: it is the user's now (no longer the link's it came from), and
   * saved in the browser; a failure to save is said under the panel.
   */
  edited() {
    if (this.linkHash) {
      this.linkHash = null;
      this.pinLink();
    }
    const was = this.own.unsaved;
    const failed = this.own.edited(this.lesson);
    if (!failed) return;
    this.say(failed, 'bad');
    // Brought into view when it starts (the panel may be scrolled to the editor).
    if (!was) $('lesson-msg').scrollIntoView({ block: 'nearest' });
  },

  /** A step of the current view, with a question and reveal to edit. */
  viewStep() {
    return {
      view: encodeHash(this.store.state, { ...this.store.view, projector: false }).slice(1),
      question: 'What do you predict?',
      options: [],
      reveal: 'BAcc {hifi.bacc}, DTL {hifi.dtl}, SWS {hifi.sws} (HiFi).',
      highlight: [],
      hide: [],
    };
  },

  toggleEdit() {
    const ed = $('lesson-edit');
    ed.hidden = !ed.hidden;
    $('lesson-edit-toggle').setAttribute('aria-pressed', String(!ed.hidden));
    if (!ed.hidden) this.showEditor();
  },

  showEditor() {
    const s = this.step;
    const set = (id, v) => {
      if (document.activeElement !== $(id)) $(id).value = v;
    };
    set('le-title', this.lesson.title);
    set('le-question', s.question);
    set('le-options', s.options.join('\n'));
    set('le-reveal', s.reveal);
    set('le-highlight', s.highlight.join(', '));
    set('le-hide', s.hide.join(', '));
    $('le-view').textContent = [...new URLSearchParams(s.view)].map(([k, v]) => `${k}=${v}`).join('&') || '(the default view)';
    $('le-up').disabled = this.k === 0;
    $('le-down').disabled = this.k === this.lesson.steps.length - 1;
    $('le-delete').disabled = this.lesson.steps.length === 1;
  },

  wireEditor() {
    const list = (v) => v.split(/[\s,]+/).filter(Boolean);
    const fields = {
      'le-title': (v) => (this.lesson.title = v),
      'le-question': (v) => (this.step.question = v),
      'le-options': (v) => (this.step.options = v.split('\n').map((x) => x.trim()).filter(Boolean)),
      'le-reveal': (v) => (this.step.reveal = v),
      'le-highlight': (v) => (this.step.highlight = list(v)),
      'le-hide': (v) => (this.step.hide = list(v)),
    };
    for (const [id, put] of Object.entries(fields)) {
      $(id).addEventListener('input', (ev) => {
        put(ev.target.value);
        this.picked = this.picked !== null && this.picked < this.step.options.length ? this.picked : null;
        this.show();
        this.checkDraft();
        this.edited();
      });
    }
    const move = (d) => {
      const s = this.lesson.steps;
      const j = this.k + d;
      [s[this.k], s[j]] = [s[j], s[this.k]];
      this.k = j;
      this.show();
      this.edited();
    };
    $('le-add').addEventListener('click', () => {
      this.lesson.steps.splice(this.k + 1, 0, this.viewStep());
      this.edited();
      this.go(this.k + 1);
    });
    $('le-use-view').addEventListener('click', () => {
      this.step.view = this.viewStep().view;
      this.show();
      this.edited();
    });
    $('le-up').addEventListener('click', () => move(-1));
    $('le-down').addEventListener('click', () => move(1));
    $('le-delete').addEventListener('click', () => {
      this.lesson.steps.splice(this.k, 1);
      this.edited();
      this.go(Math.min(this.k, this.lesson.steps.length - 1));
    });
  },

  /** Says what is wrong with the lesson being edited, if anything; the checked lesson or null. */
  checkDraft() {
    try {
      const l = checkLesson(this.lesson);
      checkIds(l);
      this.say('');
      return l;
    } catch (e) {
      this.say(e.message, 'bad');
      return null;
    }
  },

  /** The lesson as a JSON file. */
  exportFile() {
    const l = this.checkDraft();
    if (!l) return;
    const name = l.title.toLowerCase().replace(/[^a-z0-9]+/g, '-').replace(/^-|-$/g, '') || 'lesson';
    const file = `ridelab-lesson-${name}.json`;
    download(file, new Blob([lessonJson(l)], { type: 'application/json' }));
    const note = this.own.downloaded(file);
    if (note) this.say(note);
  },

  /** The lesson as a link, copied (and shown, to copy by hand where the clipboard is off). */
  async copyLink() {
    const l = this.checkDraft();
    if (!l) return;
    const url = `${location.href.split('#')[0]}${lessonHash(l)}`;
    $('lesson-link').value = url;
    $('lesson-link').hidden = false;
    try {
      await navigator.clipboard.writeText(url);
      this.say('The lesson\'s link is copied; opening it starts the lesson at its first step.');
    } catch {
      this.say('Copy the lesson\'s link from the box below.');
    }
  },

  /** A lesson file chosen: started, or refused with the step and field named (the page stays). */
  async importFile(input) {
    const file = input.files && input.files[0];
    if (!file) return;
    input.value = '';
    let lesson;
    try {
      lesson = readLesson(await file.text());
    } catch (e) {
      this.say(`${file.name}: ${e.message}`, 'bad');
      return;
    }
    if (await this.start(lesson, 0, file.name)) this.edited();
  },
};
