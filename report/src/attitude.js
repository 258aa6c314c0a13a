// Attitude helpers (pure).  q_BN is scalar-first [q0, q1, q2, q3] and passive:
// dcm_BN maps N-frame components to B-frame components.  The rotation that
// turns the body, drawn in the N frame, from N to its attitude is
// R = dcm_BN^T = dcm_NB, and the Hamilton rotation matrix of (q0; q1, q2, q3)
// is exactly dcm_BN^T, so a renderer quaternion (x, y, z, w) = (q1, q2, q3, q0).

export function dcmBN(q) {
  const [q0, q1, q2, q3] = q;
  return [
    [q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 + q0 * q3), 2 * (q1 * q3 - q0 * q2)],
    [2 * (q1 * q2 - q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 + q0 * q1)],
    [2 * (q1 * q3 + q0 * q2), 2 * (q2 * q3 - q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3],
  ];
}

// [x, y, z, w] for a renderer (three.js Quaternion), normalised; null if bad.
export function rendererQuat(q) {
  if (!Array.isArray(q) || q.length !== 4) return null;
  const n = Math.hypot(q[0], q[1], q[2], q[3]);
  if (!(n > 0) || !Number.isFinite(n)) return null;
  return [q[1] / n, q[2] / n, q[3] / n, q[0] / n];
}

// Rotate a vector with a renderer quaternion [x, y, z, w] (Hamilton, active).
export function rotate(qr, v) {
  const [x, y, z, w] = qr;
  const tx = 2 * (y * v[2] - z * v[1]);
  const ty = 2 * (z * v[0] - x * v[2]);
  const tz = 2 * (x * v[1] - y * v[0]);
  return [v[0] + w * tx + (y * tz - z * ty), v[1] + w * ty + (z * tx - x * tz), v[2] + w * tz + (x * ty - y * tx)];
}

// Valid attitude samples: { t: [], q: [[x,y,z,w]...] } sorted, finite.
export function attitudeSamples(att) {
  const out = { t: [], q: [] };
  if (!att || !Array.isArray(att.t) || !Array.isArray(att.q_BN)) return out;
  const n = Math.min(att.t.length, att.q_BN.length);
  for (let i = 0; i < n; i++) {
    const t = att.t[i];
    const q = rendererQuat(att.q_BN[i]);
    if (typeof t !== 'number' || !Number.isFinite(t) || !q) continue;
    if (out.t.length && t <= out.t[out.t.length - 1]) continue;
    out.t.push(t);
    out.q.push(q);
  }
  return out;
}

// Scalar-first Euler parameters of an MRP set sigma (the same rotation).
export function mrpToQuat(s) {
  const s2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
  const d = 1 + s2;
  return [(1 - s2) / d, (2 * s[0]) / d, (2 * s[1]) / d, (2 * s[2]) / d];
}

// The renderer rotation of the reference frame R, drawn in N, from the
// body's (rendererQuat(q_BN), the rotation dcm_NB) and the tracking error
// sigma_BR: dcm_NR = dcm_NB dcm_BR, and rendererQuat(q_BR) is dcm_BR^T, so
// dcm_BR is its conjugate.  Returns [x, y, z, w]; null if an input is bad.
export function referenceQuat(qBody, sigmaBR) {
  if (!Array.isArray(qBody) || !Array.isArray(sigmaBR) || sigmaBR.length < 3 || !sigmaBR.every(Number.isFinite)) return null;
  const r = rendererQuat(mrpToQuat(sigmaBR));
  if (!r) return null;
  const [bx, by, bz, bw] = [-r[0], -r[1], -r[2], r[3]]; // conjugate: dcm_BR
  const [ax, ay, az, aw] = qBody;
  // Hamilton product qBody * conj (applies dcm_BR first, then dcm_NB)
  return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
    aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz];
}
