// A tiny static file server for dist/ (node's http module only): correct MIME types
// (application/wasm for .wasm), no directory listing, nothing outside the root.
// Usage as a script: node tests/e2e/server.mjs [ROOT] [PORT]
import http from 'node:http';
import fs from 'node:fs';
import zlib from 'node:zlib';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const MIME = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.wasm': 'application/wasm',
  '.json': 'application/json',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.ico': 'image/x-icon',
  '.txt': 'text/plain; charset=utf-8',
};

/** What a static host compresses (the page's text and its wasm). */
const COMPRESSED = new Set(['.html', '.js', '.mjs', '.css', '.wasm', '.json', '.svg', '.txt']);

/**
 * Serves `root` on 127.0.0.1 at a free port; resolves `{url, close, requests}`.
 * `gzip`: serve as static hosts do (the benchmarks' network runs): text and wasm
 * gzip-compressed (level 9, once per file) to a client that accepts it, each response
 * revalidated by ETag (`no-cache`) instead of never stored (`no-store`, the default).
 */
export function startServer(root, port = 0, { gzip = false } = {}) {
  const base = path.resolve(root);
  const requests = [];
  const packed = new Map();
  const server = http.createServer((req, res) => {
    requests.push(req.url);
    let rel;
    try {
      rel = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    } catch {
      res.writeHead(400).end('bad request');
      return;
    }
    if (rel.endsWith('/')) rel += 'index.html';
    const file = path.resolve(base, '.' + rel);
    if (file !== base && !file.startsWith(base + path.sep)) {
      res.writeHead(403).end('forbidden');
      return;
    }
    fs.stat(file, (err, st) => {
      if (err || !st.isFile()) {
        res.writeHead(404, { 'content-type': 'text/plain' }).end('not found');
        return;
      }
      const ext = path.extname(file).toLowerCase();
      const type = MIME[ext] || 'application/octet-stream';
      if (gzip) {
        const etag = `"${st.size.toString(16)}-${st.mtimeMs.toString(16)}"`;
        if (req.headers['if-none-match'] === etag) {
          res.writeHead(304, { etag, 'cache-control': 'no-cache' }).end();
          return;
        }
        const squeeze = COMPRESSED.has(ext) && /\bgzip\b/.test(req.headers['accept-encoding'] || '');
        const key = `${file}\0${etag}`;
        if (squeeze && !packed.has(key)) packed.set(key, zlib.gzipSync(fs.readFileSync(file), { level: 9 }));
        const body = squeeze ? packed.get(key) : fs.readFileSync(file);
        res.writeHead(200, {
          'content-type': type,
          'content-length': body.length,
          'cache-control': 'no-cache',
          etag,
          vary: 'accept-encoding',
          ...(squeeze ? { 'content-encoding': 'gzip' } : {}),
        });
        res.end(req.method === 'HEAD' ? undefined : body);
        return;
      }
      res.writeHead(200, {
        'content-type': type,
        'content-length': st.size,
        'cache-control': 'no-store',
      });
      if (req.method === 'HEAD') res.end();
      else fs.createReadStream(file).pipe(res);
    });
  });
  return new Promise((resolve, reject) => {
    server.on('error', reject);
    server.listen(port, '127.0.0.1', () => {
      const { port: p } = server.address();
      resolve({
        url: `http://127.0.0.1:${p}/`,
        requests,
        close: () => new Promise((r) => server.close(() => r())),
      });
    });
  });
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const root = process.argv[2] || 'dist';
  const { url } = await startServer(root, Number(process.argv[3] || 0));
  console.log(`serving ${root} at ${url}`);
}
