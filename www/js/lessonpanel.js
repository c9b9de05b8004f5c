// The lesson panel: a lesson's steps beside the workbench in large type (js/lessons.js
// holds the format). Each step sets its view through the controller (as a link would),
// asks its question, lets the class commit a prediction, then reveals the answer with
// the numbers the page has computed for the current car and road, re-read whenever the
// views change, and outlines what to look at. With the panel focused, Space reveals or
// goes on, the arrow keys (and Page Up / Down) step, 1..6 pick an option. Teachers
// author here too: add the current view as a step, edit, reorder, delete, and export or
// import the lesson as a JSON file or a link; what they make is saved in the browser as
// they edit and listed under "Your lessons" (js/ownlessons.js). A lesson opened from a
// link keeps its link in the address bar while it is open, so a reload opens it again.

import { SHIPPED } from './lessonbook.js';
import { PLACEHOLDERS, checkLesson, readLessonHash, resolve } from './lessons.js';
import { decodeHash } from './urlstate.js';
import { explain } from './controls.js';
import { OwnLessons } from './ownlessons.js';
import { AUTHORING, checkIds, copy } from './lessonauthor.js';

const $ = (id) => document.getElementById(id);

export class LessonPanel {
  /**
   * `root`: the panel (#lesson); `bench`: the workbench grid (gets `lesson-open`);
   * `store`, `controller`, `compute`: the page's (read, and views set through the
   * controller); `onResize()`: called after the panel opened or closed.
   */
  constructor({ root, bench, store, controller, compute, onResize }) {
    Object.assign(this, { root, bench, store, controller, compute, onResize });
    this.lesson = null;
    this.k = 0;
    this.revealed = false;
    this.picked = null;
    /** True while a step's view is being loaded (its numbers are not the page's yet). */
    this.loading = false;
    /** The reveal was just made: bring it into the panel's view once drawn. */
    this.scrollToAnswer = false;
    /** Steps started (the latest one's view wins). */
    this.goes = 0;
    this.lit = [];
    this.veiled = [];
    /** The `#lesson=` hash the lesson in the panel was opened from (kept in the address bar while it is open), or null. */
    this.linkHash = null;
    this.own = new OwnLessons({
      list: $('lesson-own'),
      box: $('lesson-own-box'),
      say: (text, kind) => this.say(text, kind),
      onOpen: (it) => this.act(() => this.openOwn(it)),
    });
    this.own.render();
    this.listShipped();
    this.listPlaceholders();
    $('lessons-open').addEventListener('click', () => (this.isOpen ? this.close() : this.open()));
    $('lesson-close').addEventListener('click', () => this.close());
    $('lesson-menu').addEventListener('click', () => this.showList());
    $('lesson-back').addEventListener('click', () => this.act(() => this.go(this.k - 1)));
    $('lesson-next').addEventListener('click', () => this.act(() => this.go(this.k + 1)));
    $('lesson-reveal').addEventListener('click', () => this.act(() => this.reveal()));
    $('lesson-new').addEventListener('click', () => this.act(() => this.newLesson()));
    $('lesson-edit-toggle').addEventListener('click', () => this.toggleEdit());
    $('lesson-export').addEventListener('click', () => this.exportFile());
    $('lesson-copy').addEventListener('click', () => this.copyLink());
    $('lesson-file').addEventListener('change', (ev) => this.importFile(ev.target));
    this.wireEditor();
    root.addEventListener('keydown', (ev) => this.onKey(ev));
  }

  get isOpen() {
    return !this.root.hidden;
  }

  /** The step shown. */
  get step() {
    return this.lesson ? this.lesson.steps[this.k] : null;
  }

  /** Runs a button's action and gives the keyboard back to the panel. */
  act(fn) {
    this.root.focus({ preventScroll: true });
    return fn();
  }

  /** Opens the panel (the list, or the lesson running) and gives it the keyboard. */
  open() {
    this.root.hidden = false;
    this.bench.classList.add('lesson-open');
    $('lessons-open').setAttribute('aria-expanded', 'true');
    this.onResize();
    if (!this.lesson) this.showList();
    else this.show();
    this.pinLink();
    this.root.focus({ preventScroll: true });
  }

  /** The address bar holds the lesson link while its lesson is open, else the view's link. */
  pinLink() {
    const on = this.isOpen && this.linkHash && this.lesson && $('lesson-list').hidden;
    this.store.pinHash(on ? this.linkHash : null);
  }

  close() {
    this.unmark();
    this.root.hidden = true;
    this.bench.classList.remove('lesson-open');
    $('lessons-open').setAttribute('aria-expanded', 'false');
    this.onResize();
    this.pinLink();
  }

  // ---------------------------------------------------------------- choosing a lesson

  listShipped() {
    const ul = $('lesson-shipped');
    ul.replaceChildren(...SHIPPED.map(({ id, lesson }, i) => {
      const li = document.createElement('li');
      const b = document.createElement('button');
      b.type = 'button';
      b.dataset.lesson = id;
      b.textContent = `${i + 1}. ${lesson.title} (${lesson.steps.length} steps)`;
      b.addEventListener('click', () => this.act(() => this.start(lesson)));
      li.append(b);
      return li;
    }));
  }

  /** The list of lessons in place of the step. */
  showList() {
    this.unmark();
    $('lesson-list').hidden = false;
    $('lesson-step').hidden = true;
    $('lesson-edit').hidden = true;
    $('lesson-title').textContent = 'Lessons';
    $('lesson-count').textContent = '';
    for (const id of ['lesson-edit-toggle', 'lesson-export', 'lesson-copy', 'lesson-menu']) $(id).hidden = true;
    this.own.render();
    this.pinLink();
  }

  /**
   * Starts `lesson` (a lesson object, checked here) at step `k`. Resolves false with a
   * message in the panel, and the page as it was, when the lesson is malformed, or when
   * the lesson in the panel is an unsaved one of the user's and they keep it.
   * `ownId`: the user's stored lesson it is; `link`: the `#lesson=` hash it came from.
   */
  async start(lesson, k = 0, origin = '', { ownId = null, link = null } = {}) {
    if (!this.own.mayLeave('Open another lesson')) return false;
    let checked;
    try {
      checked = await this.checkPage(checkLesson(lesson));
    } catch (e) {
      this.say(`${origin ? `${origin}: ` : ''}${e.message || e}`, 'bad');
      return false;
    }
    this.lesson = copy(checked);
    this.own.adopt(ownId, this.lesson);
    this.linkHash = link;
    this.say('');
    if (!this.isOpen) this.open();
    $('lesson-list').hidden = true;
    $('lesson-step').hidden = false;
    for (const id of ['lesson-edit-toggle', 'lesson-export', 'lesson-copy', 'lesson-menu']) $(id).hidden = false;
    this.pinLink();
    await this.go(k);
    return true;
  }

  /**
   * What only the page can check: each highlighted or hidden id is an element, each
   * view a state the core accepts. Throws `{message}` naming the step and field.
   */
  async checkPage(lesson) {
    checkIds(lesson);
    for (const [i, s] of lesson.steps.entries()) {
      const st = { ...this.store.defaults, ...decodeHash(s.view).state };
      try {
        await this.compute.checkState(st);
      } catch (e) {
        throw { message: `steps[${i}].view: ${explain(e, e.field)}` };
      }
    }
    return lesson;
  }

  /** A lesson link (`#lesson=...`): opens it and resolves true, or false when `hash` is none. */
  async openLink(hash) {
    let link;
    try {
      link = readLessonHash(hash, SHIPPED.map((x) => x.id));
    } catch (e) {
      this.open();
      this.say(`The lesson link: ${e.message}`, 'bad');
      return true;
    }
    if (!link) return false;
    await this.start(link.lesson || SHIPPED.find((x) => x.id === link.id).lesson, 0, 'The lesson link', { link: `#${hash.replace(/^#/, '')}` });
    return true;
  }

  // ---------------------------------------------------------------- stepping

  /** Shows step `k` (clamped): its view, its question, the prediction not yet made. */
  async go(k) {
    if (!this.lesson) return;
    this.k = Math.max(0, Math.min(this.lesson.steps.length - 1, k));
    this.revealed = false;
    this.scrollToAnswer = false;
    this.picked = null;
    this.unmark();
    const step = this.step;
    // An id typed in the editor may be no element yet (the editor says so).
    for (const el of step.hide.map($).filter(Boolean)) {
      el.classList.add('lesson-veil');
      // Out of reach of the pointer, the keyboard and screen readers too.
      el.inert = true;
      this.veiled.push(el);
    }
    this.loading = true;
    this.show();
    // Steps taken quickly one after another: the last one's view is the one shown.
    const token = ++this.goes;
    await this.applyView(step.view);
    if (token !== this.goes) return;
    this.loading = false;
    this.show();
  }

  /** Loads a step's view as a link would, keeping projector mode as it is unless the view says. */
  applyView(view) {
    const p = new URLSearchParams(view);
    if (!p.has('proj') && !p.has('large') && this.store.view.projector) p.set('proj', '1');
    return this.controller.loadHash(`#${p}`);
  }

  /** The class commits option `i` as its prediction (it may change its mind until the reveal). */
  commit(i) {
    if (this.revealed || !this.step || i < 0 || i >= this.step.options.length) return;
    this.picked = i;
    this.show();
  }

  /** Reveals the answer once the class has answered (a step without options needs none). */
  reveal() {
    const step = this.step;
    if (!step || this.revealed) return;
    if (step.options.length && this.picked === null) {
      $('lesson-hint').textContent = 'Pick the class\'s prediction first (click an option or press its number).';
      return;
    }
    this.revealed = true;
    this.scrollToAnswer = true;
    this.unveil();
    for (const el of step.highlight.map($).filter(Boolean)) {
      el.classList.add('spotlight');
      this.lit.push(el);
    }
    this.show();
  }

  /** Space: reveal, or on to the next step once revealed. */
  advance() {
    if (!this.step) return;
    if (this.revealed) this.go(this.k + 1);
    else this.reveal();
  }

  /** Shows what the step hid. */
  unveil() {
    for (const el of this.veiled) {
      el.classList.remove('lesson-veil');
      el.inert = false;
    }
    this.veiled = [];
  }

  /** No outline, nothing hidden. */
  unmark() {
    for (const el of this.lit) el.classList.remove('spotlight');
    this.lit = [];
    this.unveil();
  }

  onKey(ev) {
    if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
    const t = ev.target;
    if (t.closest('input, textarea, select')) return;
    if ((ev.key === ' ' || ev.key === 'Enter') && t.closest('button, summary')) return;
    // The list of lessons has no steps.
    if (!this.lesson || $('lesson-step').hidden) return;
    const k = ev.key;
    if (k === ' ') this.advance();
    else if (k === 'ArrowRight' || k === 'ArrowDown' || k === 'PageDown') this.go(this.k + 1);
    else if (k === 'ArrowLeft' || k === 'ArrowUp' || k === 'PageUp') this.go(this.k - 1);
    else if (/^[1-6]$/.test(k)) this.commit(Number(k) - 1);
    else return;
    ev.preventDefault();
    ev.stopPropagation();
  }

  // ---------------------------------------------------------------- showing

  /** The data the placeholders read: the store's results for the current state. */
  data() {
    const st = this.store;
    const fitOk = st.fit && st.fitKey === st.tags?.fit;
    return {
      state: st.state,
      desc: st.desc,
      lofi: st.lofi,
      hifi: st.hifiCurrent() ? st.hifi : null,
      sur: st.surrogate,
      front: st.front,
      fit: fitOk ? st.fit : null,
      maps: st.shownMaps()?.maps ?? null,
    };
  }

  /** `text` with its placeholders filled in, into element `el`; true when every number is there. */
  fill(el, text) {
    if (this.loading) {
      el.textContent = '…';
      return false;
    }
    const parts = resolve(text, this.data());
    el.replaceChildren(...parts.map((p) => {
      if (!('name' in p)) return document.createTextNode(p.text);
      const span = document.createElement('span');
      span.className = p.pending ? 'live pending' : 'live';
      span.dataset.ph = p.name;
      span.textContent = p.pending ? '…' : p.text;
      if (!p.pending && p.value !== undefined) span.dataset.value = String(p.value);
      span.title = PLACEHOLDERS[p.name].about;
      return span;
    }));
    return parts.every((p) => !p.pending);
  }

  /** Redraws the step: title, count, question, options, reveal, buttons. */
  show() {
    const step = this.step;
    if (!step || !this.isOpen) return;
    const n = this.lesson.steps.length;
    $('lesson-title').textContent = this.lesson.title;
    $('lesson-count').textContent = `Step ${this.k + 1} of ${n}`;
    let ready = this.fill($('lesson-question'), step.question);
    const opts = $('lesson-options');
    // Once revealed every option stays: the right one (the step's `answer`, 1..) marked
    // "right answer", the class's prediction marked right or wrong.
    const right = this.revealed && step.answer ? step.answer - 1 : null;
    opts.replaceChildren(...step.options.map((o, i) => {
      const b = document.createElement('button');
      b.type = 'button';
      b.className = 'lesson-option';
      b.textContent = `${i + 1}. ${o}`;
      b.setAttribute('aria-pressed', String(this.picked === i));
      if (right !== null) {
        const verdict = i === right ? (this.picked === i ? 'right' : 'answer') : this.picked === i ? 'wrong' : '';
        if (verdict) {
          b.dataset.verdict = verdict;
          const tag = document.createElement('span');
          tag.className = 'verdict';
          tag.textContent = { right: '✓ right: the class\'s prediction', answer: '✓ right answer', wrong: '✗ wrong: the class\'s prediction' }[verdict];
          b.append(' ', tag);
        }
      }
      b.addEventListener('click', () => this.act(() => this.commit(i)));
      return b;
    }));
    opts.hidden = step.options.length === 0;
    opts.dataset.revealed = String(this.revealed);
    const hint = $('lesson-hint');
    if (this.revealed) {
      const next = this.k < n - 1 ? 'Space or → for the next step.' : 'The last step: ← goes back, "All lessons" lists them.';
      const said = right === null || this.picked === null ? '' : this.picked === right ? 'The class was right. ' : `The class chose ${this.picked + 1}; the right answer is ${right + 1}. `;
      hint.textContent = said + next;
    }
    else if (step.options.length && this.picked === null) hint.textContent = 'The class predicts: pick an option (1..' + step.options.length + '), then Reveal (Space).';
    else hint.textContent = step.options.length ? `The class chose ${this.picked + 1}. Reveal (Space) when ready.` : 'Discuss, then Reveal (Space).';
    const rv = $('lesson-answer');
    rv.hidden = !this.revealed;
    if (this.revealed) ready = this.fill(rv, step.reveal) && ready;
    else rv.replaceChildren();
    if (this.scrollToAnswer && ready) {
      this.scrollToAnswer = false;
      rv.scrollIntoView({ block: 'nearest' });
    }
    $('lesson-reveal').disabled = this.revealed || (step.options.length > 0 && this.picked === null);
    $('lesson-back').disabled = this.k === 0;
    $('lesson-next').disabled = this.k === n - 1;
    this.root.dataset.ready = String(ready && !this.loading);
    if (!$('lesson-edit').hidden) this.showEditor();
  }

  /** The views changed (the controller's hook): the numbers follow. */
  viewsChanged() {
    if (this.lesson && this.isOpen && !this.loading) this.show();
  }

  /** A line under the panel (`kind`: 'bad' for a refusal). */
  say(text, kind = '') {
    const el = $('lesson-msg');
    el.textContent = text;
    el.className = `lesson-msg ${kind}`;
  }
}

// The authoring half (js/lessonauthor.js): the editor, saving, export and import.
Object.assign(LessonPanel.prototype, AUTHORING);
