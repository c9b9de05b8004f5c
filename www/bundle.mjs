// Bundles the page's JavaScript in a build directory (issue #29) with esbuild (npm,
// package.json), minified, and minifies its style sheet and page. The 48 modules under
// js/ become a few files: the page's entry `js/app.js` and the chunks it imports fetch as
// 9 files instead of 29 (one response each, and one gzip stream over modules that share
// most of their words: about 12 KB less to fetch before the first map). Code shared by
// several entries lives once, in a chunk, so every module keeps one instance however it
// is reached.
//
// The entries keep their paths: the page's (`app.js`), the workers' (`worker.js`), the
// parts the page loads on first use (`panels.js`, `roadstudy.js`), and the modules a
// script on the page may import by path, the browser suite among them (`lessons.js` for
// a lesson's link, `svgexport.js`, ...). The wasm-bindgen loaders (ridelab.js,
// ridelab-first.js) stay where they are, each minified on its own: they find their wasm
// beside them by `import.meta.url`. style.css is minified by esbuild too (its comments
// are a third of it) and its integrity hash in index.html written again; index.html loses
// its comments and indentation. sw.js is left as it is (www/sw-stamp.mjs fills it in
// after this). The sources in www/ stay as written; dist/ only is changed.
//   node www/bundle.mjs DIR      (DIR defaults to $TRUNK_STAGING_DIR; then stamps sw.js)
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import * as esbuild from 'esbuild';
import { stamp } from './sw-stamp.mjs';

/** The modules of js/ that keep their path in the bundle (see the head of this file). */
export const ENTRIES = [
  'app.js', 'worker.js', 'panels.js', 'roadstudy.js',
  'chartspecs.js', 'engine.js', 'exports.js', 'format.js', 'lessonbook.js', 'lessons.js', 'svgexport.js',
];

/** The wasm-bindgen loaders at the top of the build, imported by path from js/. */
const LOADERS = ['ridelab.js', 'ridelab-first.js'];

/** Browsers with module workers and top-level await. */
const TARGET = 'es2022';

/** The bytes of the `.js` files directly under `dir`. */
function scriptBytes(dir) {
  return fs.readdirSync(dir).filter((f) => f.endsWith('.js')).reduce((n, f) => n + fs.statSync(path.join(dir, f)).size, 0);
}

/**
 * Bundles `dir`/js in place and minifies the loaders beside it; resolves to
 * `{modules, files, before, after}` (js/ modules in and files out, bytes before and after).
 */
export async function bundleScripts(dir) {
  const js = path.join(dir, 'js');
  const modules = fs.readdirSync(js).filter((f) => f.endsWith('.js')).length;
  const before = scriptBytes(js) + LOADERS.reduce((n, f) => n + fs.statSync(path.join(dir, f)).size, 0);
  const out = path.join(dir, '.js-bundle');
  fs.rmSync(out, { recursive: true, force: true });
  await esbuild.build({
    entryPoints: ENTRIES.map((f) => path.join(js, f)),
    bundle: true,
    splitting: true,
    format: 'esm',
    minify: true,
    target: TARGET,
    outdir: out,
    chunkNames: 'chunk-[hash]',
    external: LOADERS.map((f) => `../${f}`),
    legalComments: 'none',
    logLevel: 'warning',
  });
  fs.rmSync(js, { recursive: true });
  fs.renameSync(out, js);
  for (const f of LOADERS) {
    const file = path.join(dir, f);
    const r = await esbuild.transform(fs.readFileSync(file, 'utf8'), { minify: true, format: 'esm', target: TARGET, legalComments: 'none' });
    fs.writeFileSync(file, r.code);
  }
  const files = fs.readdirSync(js).length;
  const after = scriptBytes(js) + LOADERS.reduce((n, f) => n + fs.statSync(path.join(dir, f)).size, 0);
  return { modules, files, before, after };
}

/**
 * Minifies `dir`/style.css (esbuild) and writes its new SHA-384 into the integrity
 * attribute Trunk gave its link in `dir`/index.html; resolves to `{before, after}` bytes.
 */
export async function minifyStyle(dir) {
  const file = path.join(dir, 'style.css');
  const css = fs.readFileSync(file, 'utf8');
  const r = await esbuild.transform(css, { loader: 'css', minify: true, legalComments: 'none', logLevel: 'warning' });
  fs.writeFileSync(file, r.code);
  const page = path.join(dir, 'index.html');
  const html = fs.readFileSync(page, 'utf8');
  const link = /(<link rel="stylesheet" href="\.\/style\.css" integrity=")sha384-[^"]+(")/;
  if (!link.test(html)) throw new Error(`bundle: ${page} has no style.css link with an integrity hash`);
  const sri = `sha384-${crypto.createHash('sha384').update(r.code).digest('base64')}`;
  fs.writeFileSync(page, html.replace(link, `$1${sri}$2`));
  return { before: Buffer.byteLength(css), after: Buffer.byteLength(r.code) };
}

/**
 * `dir`/index.html without its comments and its lines' indentation (a line break stays
 * where there was one, so text and inline elements keep their spaces; the page has no
 * `pre`, and its text areas are empty); resolves to `{before, after}` bytes.
 */
export function minifyPage(dir) {
  const page = path.join(dir, 'index.html');
  const html = fs.readFileSync(page, 'utf8');
  if (/<pre[\s>]|<textarea[^>]*>[^<]/.test(html)) throw new Error(`bundle: ${page} has preformatted text; its indentation would change`);
  const out = html.replace(/<!--[\s\S]*?-->/g, '').replace(/\n[ \t]+/g, '\n').replace(/\n{2,}/g, '\n');
  fs.writeFileSync(page, out);
  return { before: Buffer.byteLength(html), after: Buffer.byteLength(out) };
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const dir = process.argv[2] || process.env.TRUNK_STAGING_DIR;
  if (!dir) throw new Error('bundle: give the build directory (or run as a Trunk hook)');
  // Bundled first: the build id sw-stamp writes hashes what the page fetches.
  const r = await bundleScripts(dir);
  console.log(`bundle: ${r.modules} modules -> ${r.files} files in js/, scripts ${r.before} -> ${r.after} bytes`);
  const css = await minifyStyle(dir);
  const page = minifyPage(dir);
  console.log(`bundle: style.css ${css.before} -> ${css.after} bytes, index.html ${page.before} -> ${page.after} bytes`);
  stamp(dir);
}
