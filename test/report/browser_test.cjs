#!/usr/bin/env node
// Loads generated reports in headless Debian Chromium (through playwright-core,
// no downloaded browser) and checks that each renders without console errors
// or page errors, fetches nothing, draws what its data holds, and that the
// screenshots are not blank.
//
//   NODE_PATH=<build>/report/npm/node_modules node browser_test.cjs HTML_DIR OUT_DIR
// Exit: 0 pass, 1 fail, 77 skipped (no chromium).
'use strict';
const path = require('path');
const { stats, parseArgs, runCases } = require('./browser_common.cjs');

const { htmlDir, outDir } = parseArgs('browser_test.cjs');

// expectations per generated report
const CASES = [
  { file: 's1.html', plots: ['pointing', 'rates', 'wheels', 'wheeltorque', 'x-sigma_BN', 'x-wheel_cmd', 'x-E_rot'], absent: ['ontime', 'force', 'propellant'],
    replay: 'ok', dataflow: 'ok', spectrum: true, shot: true, events: 2 },
  { file: 's2.html', plots: ['pointing', 'rates', 'ontime', 'force', 'propellant'], absent: ['wheels', 'wheeltorque'],
    replay: 'ok', dataflow: 'ok', spectrum: true, shot: true,
    story: { warnings: 1, pass: 1, fail: 1, rows: 3, row: 'on_time_main_s480 s' } },
  // an Earth-orbit run: the environment cards, two eclipses shaded
  { file: 's3.html', plots: ['pointing', 'rates', 'illumination', 'disturbance', 'envmomentum', 'field', 'mtqdipole', 'wheels',
    'x-torque_gravity_gradient', 'x-H_wheels_N'], absent: ['ontime', 'force', 'propellant'], replay: 'ok', dataflow: 'absent', eclipses: 2 },
  { file: 'hostile.html', plots: ['pointing', 'rates', 'wheels', 'wheeltorque', 'x-extra_thing'], replay: 'ok',
    dataflow: 'unreadable', events: 1, title: 'hostile </script><script>window.__pwned=1</script><!-- "quotes"' },
  { file: 'long.html', plots: ['pointing', 'rates', 'wheels'], replay: 'ok', dataflow: 'absent', spectrum: true },
  { file: 'reduced.html', plots: ['pointing', 'rates', 'wheels'], replay: 'ok', dataflow: 'absent', spectrum: true, fullRate: true },
  { file: 'minimal.html', plots: [], replay: 'ok', dataflow: 'absent' },
  { file: 'empty.html', plots: [], replay: 'ok', dataflow: 'absent' },
  { file: 'interrupted.html', plots: ['pointing'], replay: 'ok', dataflow: 'absent',
    incomplete: 'Incomplete run: stopped (SIGINT) at t = 1.5 s of 10 s' },
];

runCases('browser test', htmlDir, CASES, async (c, { page }, fail) => {
  await page.waitForTimeout(300); // a few animation frames of the 3D view
  const st = await page.evaluate(() => {
    const r = window.kestrelReport;
    return {
      errors: r.errors, replay: r.replay || null, dataflow: r.dataflow || null,
      cards: [...document.querySelectorAll('#plots .card, #plots-other .card')].map((e) => e.id.replace(/^plot-/, '')),
      uplots: document.querySelectorAll('#plots .uplot canvas, #plots-other .uplot canvas').length,
      spectrum: !!document.querySelector('#spectrum .uplot'),
      fullRate: !!document.getElementById('spectrum-full-rate'),
      pwned: window.__pwned !== undefined,
      title: document.getElementById('meta').textContent,
      dfNodes: document.querySelectorAll('#dataflow svg rect.node').length,
      dfRows: document.querySelectorAll('#dataflow table tbody tr').length,
      othersShown: getComputedStyle(document.getElementById('others-title')).display !== 'none',
      incomplete: (document.getElementById('incomplete') || {}).textContent || '',
      eventRows: document.querySelectorAll('#events-table tr').length,
      eventsShown: !document.getElementById('sec-events').hidden,
      eclipses: r.eclipses || 0,
      warnings: document.querySelectorAll('#run-warnings li').length,
      reqPass: document.querySelectorAll('#requirements-table tr.pass').length,
      reqFail: document.querySelectorAll('#requirements-table tr.fail').length,
      summaryRows: [...document.querySelectorAll('#run-summary tr')].map((tr) => [...tr.children].slice(0, 2).map((x) => x.textContent).join('')),
    };
  });
  console.log(`  cards [${st.cards.join(', ')}], spectrum ${st.spectrum}, replay ${st.replay}, dataflow ${st.dataflow} ` +
    `(${st.dfNodes} nodes, ${st.dfRows} rows)`);
  for (const e of st.errors) fail(`section error: ${e}`);
  if (st.pwned) fail('script from the data was executed');
  for (const p of c.plots) if (!st.cards.some((x) => x === p || x.startsWith(p))) fail(`no ${p} plot`);
  for (const p of c.absent || []) if (st.cards.includes(p)) fail(`${p} plot drawn though absent from the data`);
  if (st.uplots < c.plots.length) fail(`${st.uplots} plot canvases for ${c.plots.length} plots`);
  if (c.spectrum && !st.spectrum) fail('no jitter spectrum');
  if (!!c.fullRate !== st.fullRate) fail(`full-rate spectrum note ${st.fullRate ? 'shown' : 'missing'}`);
  const wantOthers = c.plots.some((p) => p.startsWith('x-'));
  if (st.othersShown !== wantOthers) fail(`'Other recorded series' heading ${st.othersShown ? 'shown' : 'hidden'}`);
  if (c.replay && st.replay !== c.replay) fail(`replay ${st.replay}, expected ${c.replay}`);
  if (c.dataflow && st.dataflow !== c.dataflow) fail(`dataflow ${st.dataflow}, expected ${c.dataflow}`);
  if (c.dataflow === 'ok' && (st.dfNodes < 5 || st.dfRows < 3)) fail('data-flow map nearly empty');
  if (c.incomplete && !st.incomplete.startsWith(c.incomplete)) fail(`incomplete-run notice missing: '${st.incomplete}'`);
  if (!c.incomplete && st.incomplete) fail(`incomplete-run notice on a complete run: '${st.incomplete}'`);
  // applied scenario events: a header row plus one row each, the section shown only with events
  const wantEv = c.events || 0;
  if (st.eventRows !== (wantEv ? wantEv + 1 : 0)) fail(`${st.eventRows} rows in the events table, expected ${wantEv} events`);
  if (st.eventsShown !== wantEv > 0) fail(`events section ${st.eventsShown ? 'shown' : 'hidden'}`);
  // eclipse bands: only where the data has illumination (S1/S2: none)
  if (st.eclipses !== (c.eclipses || 0)) fail(`${st.eclipses} eclipse intervals, expected ${c.eclipses || 0}`);
  for (const p of ['illumination', 'disturbance', 'envmomentum', 'field', 'mtqdipole'])
    if (!c.plots.includes(p) && st.cards.includes(p)) fail(`${p} plot drawn though absent from the data`);
  // the run's own summary (summary.txt's items, requirement lines in their own table), warnings, PASS/FAIL
  const sy = c.story || { warnings: 0, pass: 0, fail: 0, rows: 0 };
  if (st.warnings !== sy.warnings) fail(`${st.warnings} warnings shown, expected ${sy.warnings}`);
  if (st.reqPass !== sy.pass || st.reqFail !== sy.fail) fail(`requirements ${st.reqPass} PASS ${st.reqFail} FAIL, expected ${sy.pass}/${sy.fail}`);
  if (st.summaryRows.length !== sy.rows) fail(`${st.summaryRows.length} run-summary rows, expected ${sy.rows}`);
  if (sy.row && !st.summaryRows.includes(sy.row)) fail(`run summary lacks '${sy.row}': ${st.summaryRows.join(' | ')}`);
  if (c.title && !st.title.includes(c.title)) fail(`scenario text not shown verbatim: ${st.title.slice(0, 120)}`);
  if (c.shot) {
    // a click on a time plot moves the replay to that time
    const box = await page.locator('#plot-pointing .u-over').boundingBox();
    await page.mouse.click(box.x + box.width * 0.75, box.y + box.height / 2);
    const rt = await page.evaluate(() => document.querySelector('#replay .readout').textContent);
    const tClick = Number((/t = ([-0-9.e+]+) s/.exec(rt) || [])[1]);
    console.log(`  click at 3/4 of the pointing plot -> replay ${rt.split('\u00b7')[0].trim()}`);
    if (!(tClick > 0)) fail('clicking a plot did not move the replay');

    const base = c.file.replace(/\.html$/, '');
    // play the replay for a moment so the view shows a later attitude, then shoot
    await page.click('#replay button.play');
    await page.waitForTimeout(500);
    await page.click('#replay button.play');
    // then to the middle of the run (S2: during the burn, thrusters pulsing)
    await page.evaluate(() => {
      const s = document.querySelector('#replay input.timeline');
      s.value = '5000';
      s.dispatchEvent(new Event('input'));
      window.scrollTo(0, 0);
    });
    await page.waitForTimeout(200);
    const full = await page.screenshot({ fullPage: true, path: path.join(outDir, `${base}.png`) });
    const fs1 = stats(full);
    console.log(`  screenshot ${base}.png ${fs1.width}x${fs1.height}: luminance std ${fs1.std.toFixed(1)}, ${fs1.colours} colours`);
    if (fs1.height < 1500 || fs1.std < 20 || fs1.colours < 200) fail('screenshot looks blank');
    const canvas = await page.locator('#replay canvas').screenshot({ path: path.join(outDir, `${base}_replay.png`) });
    const cs = stats(canvas);
    console.log(`  3D view ${cs.width}x${cs.height}: luminance std ${cs.std.toFixed(1)}, ${cs.colours} colours`);
    if (cs.std < 8 || cs.colours < 50) fail('3D view looks blank');
  }
});
