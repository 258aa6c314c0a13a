#!/usr/bin/env node
// Build-time step of the Kestrel report (run by report/CMakeLists.txt).
//
//   NODE_PATH=<dir>/node_modules node build.cjs --out <dir> [--cpp <file.cpp>]
//
// Two pages: the run report (src/main.js with uPlot, three.js and the report
// code, into template.html) and the Monte Carlo report (src/mc_main.js with
// uPlot, into mc_template.html).  For each, esbuild bundles the entry point
// into one script and one style sheet, inlines both into the template
// together with the licence texts of the bundled packages, and the page is
// split at the data placeholder into a prefix and a suffix.  Writes
//   <out>/{report,mc}_prefix.html, <out>/{report,mc}_suffix.html (for inspection)
//   <out>/{report,mc}_bundle.js, <out>/{report,mc}_bundle.css    (for inspection)
//   <file.cpp>: the prefixes and suffixes as C++ raw string literals
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

// One page: esbuild bundles `entry`, the bundle, its style sheet and the
// licence texts of `licPkgs` are inlined into `template`, and the page is
// split at the data placeholder.  Returns [prefix, suffix]; writes the parts
// and the bundle to outDir as <name>_prefix.html ... for inspection.  A page
// without data (`split: false`, the live view) is returned whole, [page].
async function buildPage({ name, entry, template, licPkgs, split = true }) {
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
    entryNames: `${name}_bundle`,
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
  if (!js) fail(`${entry}: esbuild produced no JavaScript`);
  // Inline <script>/<style> must not contain their own end tags or an HTML
  // comment opener (which changes how the HTML parser tokenises the script).
  js = js.replace(/<\/(script)/gi, '<\\/$1').replace(/<!--/g, '<\\!--');
  if (/<\/script/i.test(js) || js.includes('<!--')) fail(`${entry}: bundle still contains </script or <!--`);
  if (/<\/style/i.test(css)) fail(`${entry}: style sheet contains </style`);
  fs.writeFileSync(path.join(outDir, `${name}_bundle.js`), js);
  fs.writeFileSync(path.join(outDir, `${name}_bundle.css`), css);

  const licences = [];
  for (const pkg of licPkgs) {
    const pj = JSON.parse(fs.readFileSync(resolvePkgFile(path.join(pkg, 'package.json')), 'utf8'));
    let text = '';
    for (const lic of ['LICENSE', 'LICENSE.md', 'LICENSE.txt']) {
      try { text = fs.readFileSync(resolvePkgFile(path.join(pkg, lic)), 'utf8'); break; } catch (e) { /* next */ }
    }
    licences.push(`${pj.name} ${pj.version} (${pj.license})\n\n${text.trim()}`);
  }
  const esc = (s) => s.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;')
    .replace(/[^\x09\x0a\x0d\x20-\x7e]/gu, (c) => `&#x${c.codePointAt(0).toString(16)};`);
  const licHtml = licences.map((l) => `<pre>${esc(l)}</pre>`).join('\n');

  let html = fs.readFileSync(path.join(here, template), 'utf8');
  const version = JSON.parse(fs.readFileSync(path.join(here, 'package.json'), 'utf8')).version;
  const subst = {
    '<!--KESTREL_CSS-->': `<style>\n${css}</style>`,
    '<!--KESTREL_JS-->': `<script>\n${js}</script>`,
    '<!--KESTREL_LICENSES-->': licHtml,
    '@@KESTREL_REPORT_VERSION@@': esc(version),
  };
  for (const [k, v] of Object.entries(subst)) {
    if (!html.includes(k)) fail(`${template} lacks ${k}`);
    html = html.split(k).join(v);
  }
  const parts = split ? html.split(PLACEHOLDER) : [html];
  if (split && parts.length !== 2) fail(`${template} must hold ${PLACEHOLDER} exactly once`);
  for (const p of parts) {
    for (let i = 0; i < p.length; i++) {
      if (p.charCodeAt(i) > 0x7e && p.charCodeAt(i) !== 0) fail(`${template}: non-ASCII character at ${i}: keep the page ASCII`);
      if (p.charCodeAt(i) === 0) fail(`${template}: NUL byte in the page`);
    }
    // Nothing outside the file: no external script/style/image references.
    const ext = p.match(/\b(?:src|href)\s*=\s*["']?(?:https?:|\/\/)/i);
    if (ext) fail(`${template}: external reference in the page: ${ext[0]}`);
  }
  if (split) {
    fs.writeFileSync(path.join(outDir, `${name}_prefix.html`), parts[0]);
    fs.writeFileSync(path.join(outDir, `${name}_suffix.html`), parts[1]);
  } else {
    fs.writeFileSync(path.join(outDir, `${name}.html`), parts[0]);
  }
  console.log(`${name} page: js ${js.length} B, css ${css.length} B, page ${parts.reduce((n, p) => n + p.length, 0)} B`);
  return parts;
}

async function main() {
  fs.mkdirSync(outDir, { recursive: true });
  // the run report (uPlot and three.js) and the Monte Carlo report (uPlot)
  const run = await buildPage({ name: 'report', entry: 'main.js', template: 'template.html', licPkgs: ['uplot', 'three'] });
  const mc = await buildPage({ name: 'mc', entry: 'mc_main.js', template: 'mc_template.html', licPkgs: ['uplot'] });
  // the live view's page (live.html, src/live.js): the same libraries, no data
  const live = await buildPage({ name: 'live', entry: 'live.js', template: 'live.html', licPkgs: ['uplot', 'three'],
    split: false });
  if (cppOut) {
    fs.mkdirSync(path.dirname(path.resolve(cppOut)), { recursive: true });
    fs.writeFileSync(cppOut, cppSource(run, mc, live[0]));
  }
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

function cppSource(run, mc, live) {
  const parts = [['kPagePrefix', run[0]], ['kPageSuffix', run[1]], ['kMcPagePrefix', mc[0]], ['kMcPageSuffix', mc[1]],
    ['kLivePage', live]];
  const decl = parts.map(([n]) => `extern const char ${n}[];\nextern const std::size_t ${n}Size;\n`).join('');
  const defs = parts.map(([n, text]) => `const char ${n}[] =\n${rawLiterals(text)};\nconst std::size_t ${n}Size = sizeof(${n}) - 1;\n`).join('\n');
  return `// Generated by report/build.cjs at build time: do not edit, do not commit.
// The Kestrel report pages (templates + bundled uPlot/three.js + report code),
// each split at the data placeholder: the run report (kPage*) and the Monte
// Carlo report (kMcPage*); and the live view's page (kLivePage), whole.
#include <cstddef>

namespace report {
namespace detail {

${decl}extern const bool kHasBundle;

const bool kHasBundle = true;

${defs}
}  // namespace detail
}  // namespace report
`;
}

main().catch((e) => fail(e && e.stack ? e.stack : String(e)));
