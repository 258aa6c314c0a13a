// The 3D replay's quaternion convention: q_BN scalar-first, passive (dcm_BN).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { dcmBN, rendererQuat, rotate, attitudeSamples } from '../../../report/src/attitude.js';

test('rendered body axes are the rows of dcm_BN (b_i in N components)', () => {
  const q = [0.7, -0.2, 0.5, 0.3];
  const n = Math.hypot(...q);
  const qn = q.map((v) => v / n);
  const C = dcmBN(qn);
  const qr = rendererQuat(q);
  for (let i = 0; i < 3; i++) {
    const e = [0, 0, 0]; e[i] = 1;
    const bN = rotate(qr, e); // body axis i drawn in the N frame
    for (let j = 0; j < 3; j++) assert.ok(Math.abs(bN[j] - C[i][j]) < 1e-12, `b${i + 1}[${j}]`);
  }
});

test('a +90 deg rotation about n3 puts b1 on n2', () => {
  const h = Math.SQRT1_2;
  const bN = rotate(rendererQuat([h, 0, 0, h]), [1, 0, 0]);
  assert.ok(Math.abs(bN[0]) < 1e-12 && Math.abs(bN[1] - 1) < 1e-12);
});

test('attitudeSamples drops bad samples', () => {
  const s = attitudeSamples({ t: [0, 1, 1, 2, 'x', 4], q_BN: [[1, 0, 0, 0], [2, 0, 0, 0], [1, 0, 0, 0], [0, 0, 0, 0], [1, 0, 0, 0], [1, 0, 0]] });
  assert.deepEqual(s.t, [0, 1]);
  assert.deepEqual(s.q[1], [0, 0, 0, 1]);
  assert.deepEqual(attitudeSamples(undefined), { t: [], q: [] });
});

test('reference frame R drawn in N from the body attitude and sigma_BR', async () => {
  const { referenceQuat, rotate, rendererQuat, mrpToQuat } = await import('../../../report/src/attitude.js');
  const near = (a, b) => a.every((v, i) => Math.abs(v - b[i]) < 1e-12);
  // no tracking error: R is B
  const qb = rendererQuat([0.8, 0.2, -0.4, 0.4]);
  assert.ok(near(referenceQuat(qb, [0, 0, 0]), qb));
  // B = N, and B turned +90 deg about b3 from R: dcm_BR = [[0,1,0],[-1,0,0],[0,0,1]], whose
  // first column (r1 in B, = in N) is (0, -1, 0); r2 is (1, 0, 0)
  const s = [0, 0, Math.tan(Math.PI / 8)];
  const qr = referenceQuat([0, 0, 0, 1], s);
  assert.ok(near(rotate(qr, [1, 0, 0]), [0, -1, 0]));
  assert.ok(near(rotate(qr, [0, 1, 0]), [1, 0, 0]));
  // MRP -> Euler parameters: 90 deg about z is (cos 45, 0, 0, sin 45)
  assert.ok(near(mrpToQuat(s), [Math.SQRT1_2, 0, 0, Math.SQRT1_2]));
  assert.equal(referenceQuat(qb, [0, NaN, 0]), null);
});
