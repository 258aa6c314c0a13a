#!/usr/bin/env node
// Loads generated Monte Carlo reports (make_mc_data.cjs -> kestrel_report --mc)
// in headless Debian Chromium and checks: no console or page errors, nothing
// fetched, one envelope card per channel with a plot canvas, the retained runs
// drawn, a histogram per metric with the threshold marked where a criterion
// has one, the table's rows and their default order (failing first, then
// invalid draws, then passing, each by run index: mc_expect.json, computed by
// the generator), sorting by a header click (and reversing), the scatter's
// selects redrawing it, the report links (relative ones only), the hostile
// strings shown verbatim and never executed; the S1 page's screenshot is not
// blank.
//
//   NODE_PATH=<build>/report/npm/node_modules node mc_browser_test.cjs HTML_DIR OUT_DIR
// Exit: 0 pass, 1 fail, 77 skipped (no chromium).
'use strict';
const fs = require('fs');
const path = require('path');
const { stats, parseArgs, runCases } = require('./browser_common.cjs');

const { htmlDir, outDir } = parseArgs('mc_browser_test.cjs');

const S1_CHANNELS = ['pointing_error', 'omega_BN_B', 'wheel_speed'];
const CASES = [
  { file: 'mc.html', cards: S1_CHANNELS, hist: 3, thresholds: 2, expect: 'mc_expect.json', links: 59, shot: true },
  { file: 'mc_thrusters.html', cards: [...S1_CHANNELS, 'thruster_force'], hist: 3, thresholds: 2, rows: 12, links: 12 },
  { file: 'mc_big.html', cards: S1_CHANNELS, hist: 3, thresholds: 2, rows: 1000, links: 998 },
  { file: 'mc_minimal.html', cards: [], hist: 0, thresholds: 0, rows: 0, links: 0 },
  { file: 'mc_empty.html', cards: [], hist: 0, thresholds: 0, rows: 0, links: 0 },
  // hostile: 6 runs + {index:'nine'} (kept, given the position as index); null and 'x' dropped.
  // Links: the 5 valid runs (0-3, 5) have one; in the table order (failing first) the first
  // three rows are runs 2 (javascript:), 4 (invalid, https:) and 0 (//): runs 1, 3, 5 keep theirs.
  { file: 'mc_hostile.html', cards: [...S1_CHANNELS, 'ghost'], hist: 3, thresholds: 2, rows: 7, links: 3,
    title: 'hostile </script><script>window.__pwned=1</script><!-- "q" \'s\' &' },
];

runCases('Monte Carlo browser test', htmlDir, CASES, async (c, { page, ms }, fail) => {
  const st = await page.evaluate(() => ({
    errors: window.kestrelReport.errors,
    ms: window.kestrelReport.ms || {},
    runLines: window.kestrelReport.runLines,
    cards: [...document.querySelectorAll('#mc-series .card')].map((e) => e.id.replace(/^mc-plot-/, '')),
    canvases: document.querySelectorAll('#mc-series .uplot canvas').length,
    hist: document.querySelectorAll('#mc-hist svg').length,
    thresholds: document.querySelectorAll('#mc-hist svg line.threshold').length,
    rows: [...document.querySelectorAll('#mc-runs tbody tr')].map((r) => Number(r.dataset.run)),
    firstStatus: (document.querySelector('#mc-runs tbody tr td.st') || {}).textContent || '',
    links: [...document.querySelectorAll('#mc-runs a')].map((a) => a.getAttribute('href')),
    pwned: window.__pwned !== undefined,
    meta: document.getElementById('meta').textContent,
    title: document.title,
    criteria: document.querySelectorAll('#mc-criteria tbody tr').length,
    criteriaText: (document.getElementById('mc-criteria') || {}).textContent || '',
    reasonCells: [...document.querySelectorAll('#mc-runs td.reason')].map((e) => e.textContent),
    hasHtmlFromData: !!document.querySelector('#criteria img, #mc-runs b, #mc-runs img'),
    driverCards: [...document.querySelectorAll('#mc-drivers .card h3')].map((e) => e.textContent),
    driverFailing: (document.querySelector('#mc-drivers .failing-runs') || {}).textContent || '',
  }));
  console.log(`  loaded in ${ms} ms: cards [${st.cards.join(', ')}], ${st.canvases} canvases, ${st.runLines} run lines, ` +
    `${st.hist} histograms (${st.thresholds} thresholds), ${st.rows.length} rows, ${st.links.length} links; ` +
    `section ms ${JSON.stringify(st.ms)}`);
  for (const e of st.errors) fail(`section error: ${e}`);
  if (st.pwned) fail('script from the data was executed');
  if (st.hasHtmlFromData) fail('markup from the data became elements');
  if (st.cards.join() !== c.cards.join()) fail(`cards [${st.cards}], expected [${c.cards}]`);
  if (st.canvases < c.cards.length) fail(`${st.canvases} plot canvases for ${c.cards.length} cards`);
  if (st.hist !== c.hist) fail(`${st.hist} histograms, expected ${c.hist}`);
  if (st.thresholds !== c.thresholds) fail(`${st.thresholds} threshold lines, expected ${c.thresholds}`);
  if (st.links.length !== c.links) fail(`${st.links.length} report links, expected ${c.links}`);
  for (const h of st.links) if (/^[a-z]+:|^\//i.test(h)) fail(`non-relative link ${h}`);
  if (c.rows !== undefined && st.rows.length !== c.rows) fail(`${st.rows.length} table rows, expected ${c.rows}`);
  if (c.title) {
    if (!st.meta.includes(c.title)) fail(`scenario not shown verbatim: ${st.meta.slice(0, 120)}`);
    if (!st.criteriaText.includes('</script><script>window.__pwned=1</script>')) fail('criterion name not shown verbatim');
    if (!st.reasonCells.some((r) => r.includes('</script><script>'))) fail('reason not shown verbatim');
  }

  if (c.expect) {
    const E = JSON.parse(fs.readFileSync(path.resolve(htmlDir, c.expect), 'utf8'));
    if (st.rows.length !== E.rows) fail(`${st.rows.length} table rows, expected ${E.rows}`);
    if (st.rows.join() !== E.order.join()) fail(`default order ${st.rows.slice(0, 10)}..., expected ${E.order.slice(0, 10)}...`);
    if (st.firstStatus !== 'FAIL') fail(`first row is '${st.firstStatus}', expected FAIL`);
    if (!st.meta.includes(`failed ${E.failedHeader}`)) fail(`header lacks 'failed ${E.failedHeader}': ${st.meta}`);
    if (st.runLines !== 3 * E.retained) fail(`${st.runLines} run lines, expected ${E.retained} retained runs x 3 cards`);
    if (st.criteria !== 2) fail(`${st.criteria} criteria rows, expected 2`);
    // what drives the failures: one card per criterion, the failing runs listed, the top driver named
    if (st.driverCards.length !== 2) fail(`${st.driverCards.length} driver cards, expected 2`);
    else if (!st.driverCards[0].includes('driven most by events[0].t') || !st.driverCards[1].includes('no run failed it'))
      fail(`driver verdicts: ${st.driverCards.join(' | ')}`);
    if (st.driverFailing !== 'Failing runs: #7, #19, #33, #41, #52') fail(`failing runs shown: '${st.driverFailing}'`);

    // sort by the first drawn value (column 5: run, seed, result, reason, drawn 0), then reverse
    const rowsNow = () => page.evaluate(() => [...document.querySelectorAll('#mc-runs tbody tr')].map((r) => Number(r.dataset.run)));
    await page.click('#mc-runs thead th:nth-child(5)');
    const asc = await rowsNow();
    if (asc.join() !== E.byDrawn0.join()) fail(`sorted by drawn[0]: ${asc.slice(0, 8)}..., expected ${E.byDrawn0.slice(0, 8)}...`);
    await page.click('#mc-runs thead th:nth-child(5)');
    const desc = await rowsNow();
    if (desc.join() !== [...E.byDrawn0].reverse().join()) fail('a second click does not reverse the order');
    // sort by run index, then by result: failing first again
    await page.click('#mc-runs thead th:nth-child(1)');
    const byIndex = await rowsNow();
    if (byIndex.join() !== [...E.order].sort((a, b) => a - b).join()) fail('sorting by run index failed');
    await page.click('#mc-runs thead th:nth-child(3)');
    const byResult = await rowsNow();
    if (byResult.join() !== E.order.join()) fail('sorting by result does not give failing, invalid, passing');

    // scatter: one point per valid run, failing ones red; changing the selects redraws it
    const sc = () => page.evaluate(() => {
      const svg = document.getElementById('mc-scatter-svg');
      return { m: svg.dataset.metric, d: svg.dataset.drawn, pts: svg.querySelectorAll('circle.pt').length,
        fail: [...svg.querySelectorAll('circle.pt.fail')].map((e) => Number(e.dataset.run)).sort((a, b) => a - b),
        thr: svg.querySelectorAll('line.threshold').length, first: svg.querySelector('circle.pt').getAttribute('cx') };
    });
    const s0 = await sc();
    if (s0.pts !== E.rows - E.invalid.length) fail(`${s0.pts} scatter points, expected ${E.rows - E.invalid.length}`);
    if (s0.fail.join() !== E.failing.join()) fail(`failing points ${s0.fail}, expected ${E.failing}`);
    if (s0.thr !== 1) fail('the settled threshold is not drawn on the scatter');
    await page.selectOption('#mc-scatter-drawn', '1');
    await page.selectOption('#mc-scatter-metric', '2');
    const s1 = await sc();
    if (s1.m !== '2' || s1.d !== '1') fail(`scatter shows metric ${s1.m} against drawn ${s1.d} after selecting 2 and 1`);
    if (s1.first === s0.first) fail('scatter not redrawn after changing the drawn value');
    if (s1.thr !== 0) fail('a threshold drawn for a metric without a criterion');
    // a click on a failing point marks its row
    await page.click(`#mc-scatter-svg circle.pt.fail[data-run="${E.failing[0]}"]`);
    const picked = await page.evaluate(() => [...document.querySelectorAll('#mc-runs tr.picked')].map((r) => Number(r.dataset.run)));
    if (picked.join() !== String(E.failing[0])) fail(`picked rows ${picked}, expected ${E.failing[0]}`);
    // a column switch in a multi-column card redraws it
    const before = await page.evaluate(() => document.querySelector('#mc-plot-omega_BN_B .u-legend').textContent);
    await page.selectOption('#mc-plot-omega_BN_B select.column', 'omega_BN_B_z');
    const after = await page.evaluate(() => ({ n: document.querySelectorAll('#mc-plot-omega_BN_B .uplot').length, h: document.querySelector('#mc-plot-omega_BN_B h3').textContent }));
    if (after.n !== 1 || !after.h.includes('deg/s')) fail(`column switch: ${after.n} plots, title ${after.h}`);
    if (!before.includes('p50')) fail('percentile levels not in the legend');
  }
  if (c.shot) {
    await page.evaluate(() => window.scrollTo(0, 0));
    const shot = await page.screenshot({ fullPage: true, path: path.join(outDir, c.file.replace(/\.html$/, '.png')) });
    const s = stats(shot);
    console.log(`  screenshot ${s.width}x${s.height}: luminance std ${s.std.toFixed(1)}, ${s.colours} colours`);
    if (s.height < 1500 || s.std < 20 || s.colours < 200) fail('screenshot looks blank');
    const card = await page.locator('#mc-plot-pointing_error canvas').first().screenshot();
    const cs = stats(card);
    // red pixels: the failing runs are drawn on top
    const { PNG } = require('pngjs');
    const png = PNG.sync.read(card);
    let red = 0;
    for (let i = 0; i < png.width * png.height; i++) {
      const [r, g, b] = [png.data[4 * i], png.data[4 * i + 1], png.data[4 * i + 2]];
      if (r > 170 && g < 90 && b < 90) red++;
    }
    console.log(`  pointing card: luminance std ${cs.std.toFixed(1)}, ${cs.colours} colours, ${red} red pixels`);
    if (red < 200) fail('no failing runs visible in red on the pointing card');
  }
});
