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
  // s1: the constant statuses and flags in one table with their names, the
  // varying stage statuses in one card, the conserved H_C_N drawn from an
  // offset; the Sun vector, the reference frame and the sensors' fields of view
  { file: 's1.html', plots: ['pointing', 'rates', 'wheels', 'wheeltorque', 'x-sigma_BN', 'x-wheel_cmd', 'x-E_rot', 'x-fsw_stage', 'x-fsw_status'],
    absent: ['ontime', 'force', 'propellant', 'x-fsw_safe_output', 'x-sun_valid', 'x-fsw_rw_failed', 'x-fsw_mode', 'x-fsw_stage_css'],
    constants: ['fsw_stage_css', 'FSW_OK (0)', 'fsw_mode', 'sun-safe (0)', 'sun_valid', 'yes (1)', 'fsw_rw_failed_3 (rw4)'], offset: ['x-H_C_N'],
    legend: { wheels: ['rw1', 'rw4'] }, scene: ['sun-vector', 'reference-frame', 'fov:css:0', 'fov:star_tracker', 'fov:star_tracker_sun_exclusion', 'wheel:rw1'],
    replay: 'ok', dataflow: 'ok', spectrum: true, shot: true, events: 2, alias: true },
  // s2: the orbit inset (Mars, the trajectory, the burn arc) and the burn on the timeline
  { file: 's2.html', plots: ['pointing', 'rates', 'ontime', 'force', 'propellant', 'x-r_BN_N'], alias: false, absent: ['wheels', 'wheeltorque'],
    legend: { force: ['acs_0', 'acs_7'] }, scene: ['sun-vector', 'central-body', 'trajectory', 'burn-arc', 'spacecraft-position', 'plume:acs_0',
      'fov:star_tracker'], burnBand: true, replay: 'ok', dataflow: 'ok', spectrum: true, shot: true,
    story: { warnings: 1, pass: 1, fail: 1, rows: 3, row: 'on_time_main_s480 s' } },
  // wheels at 50 to 75 Hz recorded at 10 Hz: the spectrum says so and which key to set
  { file: 'alias.html', plots: ['pointing', 'rates', 'wheels', 'x-sigma_BN'], replay: 'ok', spectrum: true, alias: true },
  // an Earth-orbit run: the environment cards, two eclipses shaded
  { file: 's3.html', plots: ['pointing', 'rates', 'illumination', 'disturbance', 'envmomentum', 'field', 'mtqdipole', 'wheels',
    'x-torque_gravity_gradient', 'x-H_wheels_N'], absent: ['ontime', 'force', 'propellant'], replay: 'ok', dataflow: 'absent', eclipses: 2 },
  { file: 'hostile.html', plots: ['pointing', 'rates', 'wheels', 'wheeltorque', 'x-extra_thing'], replay: 'ok',
    dataflow: 'unreadable', events: 1, title: 'hostile </script><script>window.__pwned=1</script><!-- "quotes"' },
  { file: 'long.html', plots: ['pointing', 'rates', 'wheels'], replay: 'ok', dataflow: 'absent', spectrum: true, alias: false },
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
      axes: window.kestrelAxisTicks ? window.kestrelAxisTicks() : [],
      titles: [...document.querySelectorAll('#plots h3, #plots-other h3')].map((e) => e.textContent),
      constants: [...document.querySelectorAll('#constants-table tbody tr')].map((tr) => tr.textContent),
      offsets: [...document.querySelectorAll('.offset-note')].map((e) => e.closest('.card').id.replace(/^plot-/, '')),
      legends: Object.fromEntries([...document.querySelectorAll('#plots .card')].map((c) => [c.id.replace(/^plot-/, ''),
        [...c.querySelectorAll('.u-legend .u-label')].map((e) => e.textContent)])),
      scene: r.sceneObjects || [],
      burnBand: !!document.querySelector('#replay .burn-band'),
      alias: (() => { const w = document.getElementById('spectrum-alias-warning'); return w && !w.hidden ? w.textContent : ''; })(),
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
  // honest axes: no value repeats on an axis, one unit per quantity
  for (const p of st.axes) p.axes.forEach((a, i) => {
    if (new Set(a).size !== a.length) fail(`${p.id} axis ${i}: repeated tick labels [${a.join(', ')}]`);
  });
  for (const h of st.titles) if (/\[[^\]]*(rad\/s|\*|kg m\^2\/s)[^\]]*\]/.test(h)) fail(`a second unit spelling on the page: '${h}'`);
  const rows = st.constants.join(' | ');
  for (const x of c.constants || []) if (!rows.includes(x)) fail(`constants table lacks '${x}': ${rows.slice(0, 300)}`);
  if (!c.constants && st.constants.length && c.file !== 'alias.html' && c.file !== 'hostile.html') fail(`unexpected constants table: ${rows.slice(0, 200)}`);
  for (const x of c.offset || []) if (!st.offsets.includes(x)) fail(`${x} not drawn from an offset (offsets: ${st.offsets.join(', ')})`);
  for (const [card, names] of Object.entries(c.legend || {}))
    for (const nm of names) if (!(st.legends[card] || []).includes(nm)) fail(`${card} legend lacks ${nm}: ${(st.legends[card] || []).join(', ')}`);
  for (const o of c.scene || []) if (!st.scene.includes(o)) fail(`3D scene lacks ${o}`);
  if (!!c.burnBand !== st.burnBand) fail(`burn band ${st.burnBand ? 'shown' : 'missing'}`);
  // the wheel lines alias where the wheels outrun half the recording rate (s1: rw2 at 20 Hz recorded at 10 Hz)
  if (c.alias === true && !/rates\.(record_divisor|dt)/.test(st.alias)) fail(`no aliasing warning naming the key to set: '${st.alias}'`);
  if (c.alias === false && st.alias) fail(`aliasing warning where nothing aliases: '${st.alias.slice(0, 200)}'`);
  if (c.alias) console.log(`  ${st.alias.slice(0, 160)}...`);
  console.log(`  ${st.axes.length} plots' axes, ${st.constants.length} constant series, scene: ${st.scene.filter((x) => !/^(wheel|thruster|plume|fov:css):/.test(x)).join(' ')}`);
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
