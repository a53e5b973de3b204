// Bundles src/main.js (+ three.js from node_modules) into ONE minified IIFE, dist/viewer.js, which
// volmap-view inlines into a self-contained HTML page (no server, no CDN, works from file://).
// esbuild escapes "</script" inside string literals; volmap-view still refuses a bundle containing it.
import * as esbuild from 'esbuild';
import { mkdirSync } from 'node:fs';

mkdirSync(new URL('./dist/', import.meta.url), { recursive: true });
await esbuild.build({
  entryPoints: [new URL('./src/main.js', import.meta.url).pathname],
  bundle: true,
  minify: true,
  format: 'iife',
  target: ['es2020'],
  legalComments: 'none',
  outfile: new URL('./dist/viewer.js', import.meta.url).pathname,
  logLevel: 'warning',
});
console.log('viewer: wrote dist/viewer.js');
