// The Earth-orbit helpers of the report: eclipse intervals from the recorded
// illumination, magnitudes of recorded vectors.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { eclipseIntervals, magnitude, sumMagnitude } from '../../../report/src/environment.js';

test('eclipse intervals: from the first shadowed sample to the first sunlit one', () => {
  const t = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9];
  const f = [1, 1, 0.6, 0, 0, 0.4, 1, 1, 0.9, 0.8];
  assert.deepEqual(eclipseIntervals(t, f), [{ t0: 2, t1: 6, min: 0 }, { t0: 8, t1: 9, min: 0.8 }]);
  assert.deepEqual(eclipseIntervals(t, t.map(() => 1)), []);
  // gaps (null) are skipped, not taken as sunlit
  assert.deepEqual(eclipseIntervals([0, 1, 2, 3], [0.5, null, 0.5, 1]), [{ t0: 0, t1: 3, min: 0.5 }]);
});

test('magnitudes of recorded vectors, and of a sum from its first sample', () => {
  const S = { a_x: [3, 0], a_y: [4, 0], a_z: [0, 2], b_x: [1, 1], b_y: [0, 0], b_z: [0, 1] };
  assert.deepEqual(magnitude(S, 'a', 2), [5, 2]);
  assert.equal(magnitude(S, 'missing', 2), null);
  assert.deepEqual(sumMagnitude(S, ['a', 'b'], 2), [Math.hypot(4, 4, 0), Math.hypot(1, 0, 3)]);
  assert.deepEqual(sumMagnitude(S, ['a'], 2, true), [0, Math.hypot(-3, -4, 2)]);
  assert.deepEqual(magnitude({ a_x: [null], a_y: [0], a_z: [0] }, 'a', 1), [null]);
});
