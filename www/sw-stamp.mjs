// Trunk post-build hook (Trunk.toml): writes the build's id and file list into sw.js in
// the staging directory, so each build has its own offline cache and a new build
// replaces the old one. The id is a SHA-256 over every file of the build (paths and
// contents, sw.js left out), so it changes exactly when something the page loads does.
// It also lists the first screen's modules and wasm as preloads in index.html, so the
// browser fetches them at once instead of discovering each import after its parent. The
// build's hook, www/bundle.mjs, bundles the scripts first and then stamps; run alone
// (a test's next build), this stamps a build as it is.
//   node www/sw-stamp.mjs [DIR]      (DIR defaults to $TRUNK_STAGING_DIR)
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

/** The files of the build in `dir` (paths relative to it, '/' separated, sorted), sw.js left out. */
export function buildFiles(dir) {
  const out = [];
  const walk = (d) => {
    for (const e of fs.readdirSync(d, { withFileTypes: true })) {
      const p = path.join(d, e.name);
      if (e.isDirectory()) walk(p);
      else if (e.isFile()) out.push(path.relative(dir, p).split(path.sep).join('/'));
    }
  };
  walk(dir);
  return out.filter((f) => f !== 'sw.js').sort();
}

/** The build id of `dir`: 16 hex digits of SHA-256 over each file's path and contents. */
export function buildId(dir) {
  const h = crypto.createHash('sha256');
  for (const f of buildFiles(dir)) {
    h.update(f);
    h.update('\0');
    h.update(fs.readFileSync(path.join(dir, f)));
    h.update('\0');
  }
  return h.digest('hex').slice(0, 16);
}

/** The static imports (`import ... from './x.js'`, `export ... from`) of a module's text: dynamic `import()` left out. */
function staticImports(text) {
  const out = [];
  const re = /(?:^|[;}\s])(?:import|export)\s*(?:[\w*{}\s,$]*?\sfrom\s*|[\w*{}\s,$]*?from(?=["']))?["']([^"']+)["']/g;
  for (const m of text.matchAll(re)) if (m[1].startsWith('.')) out.push(m[1]);
  return out;
}

/**
 * The modules the page's entry `entry` (a path in `dir`) loads before it runs: its static
 * import graph, paths relative to `dir`. What a module loads with `import()` (a panel's
 * code on first use) is not among them.
 */
export function firstScreenModules(dir, entry = 'js/app.js') {
  const seen = new Set();
  const walk = (f) => {
    if (seen.has(f) || !fs.existsSync(path.join(dir, f))) return;
    seen.add(f);
    const text = fs.readFileSync(path.join(dir, f), 'utf8');
    for (const spec of staticImports(text)) walk(path.posix.normalize(path.posix.join(path.posix.dirname(f), spec)));
  };
  walk(entry);
  return [...seen].sort();
}

/**
 * The preload tags of a build: the first screen's core wasm and every module the page's
 * entry imports statically (`modules`, [`firstScreenModules`]), the first screen's core
 * (ridelab-first.js) among them. The workers' larger module (ridelab.js) is left to them:
 * it loads after the first map (issue #29); so is a module the page imports on first use.
 */
export function preloadTags(modules) {
  return [
    '<link rel="preload" href="ridelab-first_bg.wasm" as="fetch" type="application/wasm" crossorigin>',
    ...modules.map((f) => `<link rel="modulepreload" href="${f}">`),
  ];
}

/** Writes the preload tags into `dir`/index.html before its first `<link>` (once). */
export function addPreloads(dir) {
  const page = path.join(dir, 'index.html');
  const html = fs.readFileSync(page, 'utf8');
  if (html.includes('rel="modulepreload"')) return 0;
  const tags = preloadTags(firstScreenModules(dir));
  const at = html.indexOf('<link');
  if (at < 0) throw new Error(`sw-stamp: ${page} has no <link> to put the preloads before`);
  fs.writeFileSync(page, `${html.slice(0, at)}${tags.join('\n  ')}\n  ${html.slice(at)}`);
  return tags.length;
}

/**
 * Stamps the build in `dir`: the first screen's preloads into index.html (once), the
 * build's id and file list into sw.js (whose placeholders must still be there).
 */
export function stamp(dir) {
  const preloads = addPreloads(dir);
  const sw = path.join(dir, 'sw.js');
  const text = fs.readFileSync(sw, 'utf8');
  if (!text.includes("'__RIDELAB_BUILD__'") || !text.includes("['__RIDELAB_FILES__']")) {
    throw new Error(`sw-stamp: ${sw} has no placeholders (stamped twice?)`);
  }
  // The page itself is cached as './' (what a navigation asks for) besides index.html.
  const files = ['./', ...buildFiles(dir)];
  const id = buildId(dir);
  fs.writeFileSync(sw, text.replace("'__RIDELAB_BUILD__'", `'${id}'`).replace("['__RIDELAB_FILES__']", JSON.stringify(files)));
  console.log(`sw-stamp: ${preloads} preloads; build ${id}, ${files.length} files cached for offline use`);
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const dir = process.argv[2] || process.env.TRUNK_STAGING_DIR;
  if (!dir) throw new Error('sw-stamp: give the build directory (or run as a Trunk hook)');
  stamp(dir);
}
