// The title of the pointing-error plot names what the column measures
// (docs/harness.md, "The reference of pointing_error_deg").
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { pointingTitle } from '../../../report/src/pointing.js';

test('the FSW mode names the reference', () => {
  assert.equal(pointingTitle({ meta: { fsw_mode: 'sun_safe' }, events: [] }),
    'Pointing error: Sun-axis angle (sun_axis_B from the Sun direction)');
  assert.equal(pointingTitle({ meta: { fsw_mode: 'inertial' } }), 'Pointing error (principal angle from the inertial reference)');
  assert.equal(pointingTitle({ meta: { fsw_mode: 'nadir' } }), 'Pointing error (principal angle from the orbit frame)');
  assert.match(pointingTitle({ meta: { fsw_mode: 'detumble' } }), /leaves detumbling for/);
  assert.equal(pointingTitle({}), 'Pointing error');
  assert.equal(pointingTitle(undefined), 'Pointing error');
});

test('an FSW mode or reference command in the events: the reference in force', () => {
  const slew = { actions: 'fsw mode_inertial; fsw reference_x 0.1; fsw reference_y -0.05; fsw reference_z 0.2' };
  const title = 'Pointing error (from the reference in force: the FSW commands of the events)';
  assert.equal(pointingTitle({ meta: { fsw_mode: 'sun_safe' }, events: [slew] }), title);
  assert.equal(pointingTitle({ meta: { fsw_mode: 'inertial' }, events: [{ actions: 'fsw reference_z 0.2' }] }), title);
  // other events (a gain, a wheel) change nothing in it
  assert.equal(pointingTitle({ meta: { fsw_mode: 'sun_safe' }, events: [{ actions: 'fsw gain_K 7' }, { actions: 'rw2 fail_off' }] }),
    'Pointing error: Sun-axis angle (sun_axis_B from the Sun direction)');
  assert.equal(pointingTitle({ meta: { fsw_mode: 'sun_safe' }, events: [null, { name: 'x' }] }),
    'Pointing error: Sun-axis angle (sun_axis_B from the Sun direction)');
});
