// Unit tests of the Monte Carlo report's pure computations (report/src/mcdata.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { normalizeMc, status, rowComparator, histogram, bandPairs, safeLink, niceTicks } from '../../../report/src/mcdata.js';

const row = (index, pass, invalid, drawn = [], metrics = [], seed = String(index)) =>
  ({ index, pass, invalid, seed, reason: '', drawn, metrics, report: null });

test('status: an invalid draw is invalid whatever pass says', () => {
  assert.equal(status(row(0, true, false)), 'pass');
  assert.equal(status(row(0, false, false)), 'fail');
  assert.equal(status(row(0, true, true)), 'invalid');
  assert.equal(status(row(0, false, true)), 'invalid');
});

test('default order: failing, invalid, passing, each by run index', () => {
  const rows = [row(4, true, false), row(3, false, true), row(9, false, false), row(1, true, false), row(2, false, false)];
  assert.deepEqual(rows.sort(rowComparator(null)).map((r) => r.index), [2, 9, 3, 1, 4]);
});

test('sorting by a column: ascending, descending, missing values last both ways, ties in default order', () => {
  const rows = [row(0, true, false, [3]), row(1, false, false, [null]), row(2, true, false, [1]),
    row(3, false, false, [3]), row(4, true, true, [null]), row(5, true, false, [-2])];
  const col = { kind: 'drawn', i: 0 };
  assert.deepEqual([...rows].sort(rowComparator(col, 1)).map((r) => r.index), [5, 2, 3, 0, 1, 4]);
  assert.deepEqual([...rows].sort(rowComparator(col, -1)).map((r) => r.index), [3, 0, 2, 5, 1, 4]);
});

test('seeds sort as 64-bit integers, not as text or doubles', () => {
  // 2^64 - 1 and 2^64 - 2 are the same double; 9 < 10 although '9' > '10'
  const rows = [row(0, true, false, [], [], '18446744073709551615'), row(1, true, false, [], [], '9'),
    row(2, true, false, [], [], '18446744073709551614'), row(3, true, false, [], [], '10')];
  assert.deepEqual(rows.sort(rowComparator({ kind: 'seed' }, 1)).map((r) => r.index), [1, 3, 2, 0]);
});

test('histogram: hand-counted bins, pass and fail apart, the last bin closed', () => {
  // 5 bins over [0, 10]: width 2; 10 falls in the last bin
  const h = histogram([0, 1.9, 2, 5, 9.99, 10, null, 7], [false, true, false, false, true, false, false, true], null, 5);
  assert.deepEqual(h.edges, [0, 2, 4, 6, 8, 10]);
  assert.deepEqual(h.pass, [1, 1, 1, 0, 1]);
  assert.deepEqual(h.fail, [1, 0, 0, 1, 1]);
  assert.equal(h.n, 7);
});

test('histogram: widened to hold the threshold, default bin count by the square-root rule', () => {
  const v = Array.from({ length: 100 }, (_, k) => k / 100); // [0, 0.99]
  const h = histogram(v, v.map(() => false), 2);
  assert.equal(h.pass.length, 10); // ceil(sqrt(100))
  assert.equal(h.edges[0], 0);
  assert.equal(h.edges[10], 2);
  assert.equal(h.pass.reduce((a, b) => a + b), 100);
  assert.equal(histogram([5, 5], [false, false]).pass.length, 5); // at least 5 bins, a constant gets a width
  assert.equal(histogram([null], [false]), null);
});

test('band pairs: symmetric levels become bands, outer first; the odd one a line', () => {
  assert.deepEqual(bandPairs([0, 5, 50, 95, 100]), { bands: [[0, 4], [1, 3]], lines: [2] });
  // unsorted levels and a non-number (null after normalisation)
  assert.deepEqual(bandPairs([95, null, 5, 50]), { bands: [[2, 0]], lines: [3] });
  assert.deepEqual(bandPairs([50]), { bands: [], lines: [0] });
  assert.deepEqual(bandPairs([]), { bands: [], lines: [] });
});

test('report links: relative paths only', () => {
  assert.equal(safeLink('runs/000042/report.html'), 'runs/000042/report.html');
  assert.equal(safeLink('../other/report.html'), '../other/report.html');
  for (const bad of ['javascript:alert(1)', 'JavaScript:x', 'https://x/y', '//host/x', '/etc/passwd', 'data:text/html,x',
    'a\\b', 'a\nb', '', null, 7]) assert.equal(safeLink(bad), null, String(bad));
});

test('nice ticks are round and cover the range', () => {
  assert.deepEqual(niceTicks(0, 10, 5), [0, 2, 4, 6, 8, 10]);
  assert.deepEqual(niceTicks(-1, 1, 4), [-1, -0.5, 0, 0.5, 1]);
  assert.deepEqual(niceTicks(3, 3), [3]);
});

test('normalize: malformed entries dropped, numbers aligned with their names', () => {
  const D = normalizeMc({
    scenario: 's', master_seed: '18446744073709551615', runs: 'many',
    drawn: [{ name: 'a' }, 7, { name: 'b', unit: 'm' }], metrics: [{ name: 'm' }],
    criteria: [{ name: 'c', metric: 'm', op: 'below', threshold: 'x' }],
    table: [null, { index: 3, seed: 5, pass: 'yes', drawn: ['1', 2, 3], metrics: [], report: 'javascript:x' }],
    series: { t: [0, 'x'], channels: [{ name: 'p', columns: ['p0', 1] }, { name: 'q', columns: [] }], runs: [{ index: 1.5 }] },
  });
  assert.equal(D.meta.scenario, 's');
  assert.equal(D.meta.master_seed, '18446744073709551615');
  assert.equal(D.meta.runs, undefined);
  assert.deepEqual(D.drawn, [{ name: 'a', unit: '' }, { name: 'b', unit: 'm' }]);
  assert.equal(D.criteria[0].threshold, null);
  assert.equal(D.table.length, 1);
  assert.deepEqual(D.table[0], { index: 3, seed: '5', pass: false, invalid: false, reason: '', drawn: [null, 2], metrics: [null], report: null });
  assert.deepEqual(D.series.t, [0, null]);
  assert.deepEqual(D.series.channels, [{ name: 'p', unit: '', columns: ['p0'] }]);
  assert.deepEqual(D.series.runs, []);
});
