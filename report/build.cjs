#!/usr/bin/env node
// Build-time step of the Kestrel report (run by report/CMakeLists.txt).
//
//   NODE_PATH=<dir>/node_modules node build.cjs --out <dir> [--cpp <file.cpp>]
//
// Bundles src/main.js (uPlot, three.js and the report code) with esbuild into
// one script and one style sheet, inlines both into template.html together
// with the licence texts of the bundled packages, and splits the page at the
// data placeholder into a prefix and a suffix.  Writes
//   <out>/report_prefix.html, <out>/report_suffix.html   (for inspection)
//   <out>/report_bundle.js, <out>/report_bundle.css        (for inspection)
//   <file.cpp>: the prefix and suffix as C++ raw string literals
// Nothing is fetched at build time beyond what `npm ci` installed, and the
// generated page references nothing outside itself.
'use strict';
const fs = require('fs');
const path = require('path');

function arg(name, def) {
  const i = process.argv.indexOf(name);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : def;
}
const here = __dirname;
const outDir = path.resolve(arg('--out', path.join(here, '..', 'build', 'report-dev')));
const cppOut = arg('--cpp', null);
const nodePaths = (process.env.NODE_PATH || '').split(path.delimiter).filter(Boolean);
if (fs.existsSync(path.join(here, 'node_modules'))) nodePaths.push(path.join(here, 'node_modules'));

function resolvePkgFile(rel) {
  for (const p of nodePaths) {
    const f = path.join(p, rel);
    if (fs.existsSync(f)) return f;
  }
  throw new Error(`build.cjs: ${rel} not found in NODE_PATH (${nodePaths.join(', ')})`);
}

const esbuild = require(resolvePkgFile('esbuild'));

const PLACEHOLDER = '@@KESTREL_REPORT_DATA@@';

function fail(msg) {
  console.error('build.cjs: ' + msg);
  process.exit(1);
}

// esbuild: one entry of src/ with uPlot and three.js into one script and one
// style sheet, checked for what could end an inline element early.
async function bundle(entry, name) {
  const res = await esbuild.build({
    entryPoints: [path.join(here, 'src', entry)],
    bundle: true,
    minify: true,
    format: 'iife',
    target: ['es2020'],
    charset: 'ascii',
    legalComments: 'none', // licence texts are embedded whole, below
    nodePaths,
    outdir: outDir,
    entryNames: name,
    write: false,
    logLevel: 'warning',
    define: { 'process.env.NODE_ENV': '"production"' },
  });
  let js = '';
  let css = '';
  for (const f of res.outputFiles) {
    if (f.path.endsWith('.js')) js = f.text;
    else if (f.path.endsWith('.css')) css = f.text;
  }
  if (!js) fail(`esbuild produced no JavaScript for ${entry}`);
  // Inline <script>/<style> must not contain their own end tags or an HTML
  // comment opener (which changes how the HTML parser tokenises the script).
  js = js.replace(/<\/(script)/gi, '<\\/$1').replace(/<!--/g, '<\\!--');
  if (/<\/script/i.test(js) || js.includes('<!--')) fail(`${entry}: bundle still contains </script or <!--`);
  if (/<\/style/i.test(css)) fail(`${entry}: style sheet contains </style`);
  fs.writeFileSync(path.join(outDir, name + '.js'), js);
  fs.writeFileSync(path.join(outDir, name + '.css'), css);
  return { js, css };
}

// The page's parts are ASCII and reference nothing outside themselves.
function checkPart(p) {
  for (let i = 0; i < p.length; i++) {
    if (p.charCodeAt(i) > 0x7e && p.charCodeAt(i) !== 0) fail(`non-ASCII character at ${i}: keep the page ASCII`);
    if (p.charCodeAt(i) === 0) fail('NUL byte in the page');
  }
  const ext = p.match(/\b(?:src|href)\s*=\s*["']?(?:https?:|\/\/)/i);
  if (ext) fail(`external reference in the page: ${ext[0]}`);
}

function fill(template, subst) {
  let html = fs.readFileSync(path.join(here, template), 'utf8');
  for (const [k, v] of Object.entries(subst)) {
    if (!html.includes(k)) fail(`${template} lacks ${k}`);
    html = html.split(k).join(v);
  }
  return html;
}

async function main() {
  fs.mkdirSync(outDir, { recursive: true });
  const { js, css } = await bundle('main.js', 'report_bundle');
  const licences = [];
  for (const pkg of ['uplot', 'three']) {
    const pj = JSON.parse(fs.readFileSync(resolvePkgFile(path.join(pkg, 'package.json')), 'utf8'));
    let text = '';
    for (const name of ['LICENSE', 'LICENSE.md', 'LICENSE.txt']) {
      try { text = fs.readFileSync(resolvePkgFile(path.join(pkg, name)), 'utf8'); break; } catch (e) { /* next */ }
    }
    licences.push(`${pj.name} ${pj.version} (${pj.license})\n\n${text.trim()}`);
  }
  const esc = (s) => s.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;')
    .replace(/[^\x09\x0a\x0d\x20-\x7e]/gu, (c) => `&#x${c.codePointAt(0).toString(16)};`);
  const licHtml = licences.map((l) => `<pre>${esc(l)}</pre>`).join('\n');

  const version = JSON.parse(fs.readFileSync(path.join(here, 'package.json'), 'utf8')).version;
  const html = fill('template.html', {
    '<!--KESTREL_CSS-->': `<style>\n${css}</style>`,
    '<!--KESTREL_JS-->': `<script>\n${js}</script>`,
    '<!--KESTREL_LICENSES-->': licHtml,
    '@@KESTREL_REPORT_VERSION@@': esc(version),
  });
  // the live view's page (live.html, src/live.js): the same libraries, no data
  const live = await bundle('live.js', 'live_bundle');
  const liveHtml = fill('live.html', {
    '<!--KESTREL_CSS-->': `<style>\n${live.css}</style>`,
    '<!--KESTREL_JS-->': `<script>\n${live.js}</script>`,
    '<!--KESTREL_LICENSES-->': licHtml,
    '@@KESTREL_REPORT_VERSION@@': esc(version),
  });
  checkPart(liveHtml);
  fs.writeFileSync(path.join(outDir, 'live.html'), liveHtml);
  const parts = html.split(PLACEHOLDER);
  if (parts.length !== 2) fail(`template.html must hold ${PLACEHOLDER} exactly once`);
  for (const p of parts) checkPart(p);
  fs.writeFileSync(path.join(outDir, 'report_prefix.html'), parts[0]);
  fs.writeFileSync(path.join(outDir, 'report_suffix.html'), parts[1]);

  if (cppOut) {
    fs.mkdirSync(path.dirname(path.resolve(cppOut)), { recursive: true });
    fs.writeFileSync(cppOut, cppSource(parts[0], parts[1], liveHtml));
  }
  console.log(`report bundle: js ${js.length} B, css ${css.length} B, page ${parts[0].length + parts[1].length} B; live page ${liveHtml.length} B`);
}

function rawLiterals(s) {
  let delim = 'KRPT';
  for (let n = 0; s.includes(`)${delim}"`); n++) delim = `KRPT${n}`;
  const CH = 16000; // chunk the literal; split only between ASCII bytes (the page is ASCII)
  const out = [];
  for (let i = 0; i < s.length; i += CH) out.push(`R"${delim}(${s.slice(i, i + CH)})${delim}"`);
  if (out.length === 0) out.push('""');
  return out.join('\n');
}

function cppSource(prefix, suffix, live) {
  return `// Generated by report/build.cjs at build time: do not edit, do not commit.
// The Kestrel report page (template + bundled uPlot/three.js + report code),
// split at the data placeholder.
#include <cstddef>

namespace report {
namespace detail {

extern const char kPagePrefix[];
extern const std::size_t kPagePrefixSize;
extern const char kPageSuffix[];
extern const std::size_t kPageSuffixSize;
extern const bool kHasBundle;
extern const char kLivePage[];
extern const std::size_t kLivePageSize;

const bool kHasBundle = true;

const char kPagePrefix[] =
${rawLiterals(prefix)};
const std::size_t kPagePrefixSize = sizeof(kPagePrefix) - 1;

const char kPageSuffix[] =
${rawLiterals(suffix)};
const std::size_t kPageSuffixSize = sizeof(kPageSuffix) - 1;

const char kLivePage[] =
${rawLiterals(live)};
const std::size_t kLivePageSize = sizeof(kLivePage) - 1;

}  // namespace detail
}  // namespace report
`;
}

main().catch((e) => fail(e && e.stack ? e.stack : String(e)));
