// The plot helpers of the report: tick labels, offsets, constant series,
// enumerated values, display units and device names, on hand-made inputs.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { tickLabels, plotOffset, constantValue, enumLabel, displayUnit, deviceName } from '../../../report/src/plotmath.js';

const distinct = (a) => new Set(a).size === a.length;

test('tick labels never repeat, however small the step against the value', () => {
  const l = tickLabels([1.0000001, 1.0000002, 1.0000003]);
  assert.deepEqual(l, ['1.0000001', '1.0000002', '1.0000003']);
  assert.deepEqual(tickLabels([0, 0.5, 1, 1.5]), ['0', '0.5', '1', '1.5']);
  // each label is its tick's value: 0.25 is not rounded to 0.3
  assert.deepEqual(tickLabels([0, 0.25, 0.5, 0.75, 1]), ['0', '0.25', '0.5', '0.75', '1']);
  assert.deepEqual(tickLabels([-0.2, -0.1, 0, 0.1]), ['-0.2', '-0.1', '0', '0.1']);
  // uPlot's increments carry rounding: 3 * 0.1 and a zero of 1e-17
  assert.deepEqual(tickLabels([1e-17, 0.1, 0.2, 0.30000000000000004]), ['0', '0.1', '0.2', '0.3']);
  // scientific notation for large and small magnitudes, still distinct
  assert.deepEqual(tickLabels([2e-5, 4e-5, 6e-5]), ['2e-5', '4e-5', '6e-5']);
  assert.deepEqual(tickLabels([1.23456e7, 1.23457e7, 1.23458e7]), ['1.23456e7', '1.23457e7', '1.23458e7']);
  for (const base of [12345.678, 0.00123, 3.986004415e14, -7.5]) {
    const ticks = [0, 1, 2, 3, 4].map((k) => base + k * Math.abs(base) * 1e-9);
    assert.ok(distinct(tickLabels(ticks)), `labels repeat near ${base}: ${tickLabels(ticks)}`);
  }
  assert.deepEqual(tickLabels([null, 1, NaN]), ['', '1', '']);
});

test('offset: a series varying by 1e-7 of its value is plotted from a round offset', () => {
  // 1.0000001 .. 1.0000003: span 2e-7, the offset keeps the digits above it
  const off = plotOffset(1.0000001, 1.0000003);
  assert.ok(Math.abs(off - 1.000000) < 1e-6, String(off));
  assert.ok(1.0000001 - off > 0 && 1.0000003 - off < 1e-6);
  assert.equal(plotOffset(0, 1), 0);      // reads well as it is
  assert.equal(plotOffset(10, 12), 0);
  assert.equal(plotOffset(-5, 5), 0);
  assert.equal(plotOffset(4, 4), 0);      // constant: a flat line at its value
  const h = plotOffset(1234.5678901, 1234.5678905);
  assert.ok(Math.abs(h - 1234.567890) < 1e-6, String(h));
});

test('constant series: one value (or rounding noise) is constant; a step is not', () => {
  assert.deepEqual(constantValue([2, 2, 2, null, 2]), { value: 2, spread: 0 });
  assert.deepEqual(constantValue([0]), { value: 0, spread: 0 });
  assert.equal(constantValue([0, 0, 1]), null);
  assert.equal(constantValue([null, null]), null);
  assert.equal(constantValue([1, 1 + 1e-9]), null);
  const c = constantValue([100, 100 + 1e-13]);
  assert.ok(c && Math.abs(c.value - 100) < 1e-12);
});

test('enumerated values carry their names', () => {
  assert.equal(enumLabel('fsw_status', 0), 'FSW_OK (0)');
  assert.equal(enumLabel('fsw_stage_rw_sat', 2), 'FSW_W_SAT (2)');
  assert.equal(enumLabel('fsw_stage_css', -5), 'FSW_E_BAD_INPUT (-5)');
  assert.equal(enumLabel('fsw_mode', 3), 'nadir (3)');
  assert.equal(enumLabel('fsw_policy', 2), 'magnetorquers (2)');
  assert.equal(enumLabel('sun_valid', 1), 'yes (1)');
  assert.equal(enumLabel('fsw_rw_failed_2', 0), 'no (0)');
  assert.equal(enumLabel('fsw_status', 9), 'unknown (9)');
  assert.equal(enumLabel('E_rot', 1), '');
  assert.equal(enumLabel('fsw_status', 0.5), '');
});

test('one display unit per quantity', () => {
  assert.deepEqual(displayUnit('N*m'), { unit: 'N m', scale: 1 });
  assert.deepEqual(displayUnit('N m'), { unit: 'N m', scale: 1 });
  assert.deepEqual(displayUnit('kg*m^2/s'), { unit: 'N m s', scale: 1 });
  assert.deepEqual(displayUnit('N*m*s'), { unit: 'N m s', scale: 1 });
  assert.deepEqual(displayUnit('-'), { unit: '', scale: 1 });
  const r = displayUnit('rad/s');
  assert.equal(r.unit, 'deg/s');
  assert.ok(Math.abs(r.scale * Math.PI - 180) < 1e-12);
  assert.deepEqual(displayUnit('A*m^2'), { unit: 'A m^2', scale: 1 });
});

test('devices are named as the scenario names them', () => {
  const g = { wheel_names: ['rw1', 'rw2'], thrusters: [{ name: 'main' }, { name: 'acs1' }], magnetorquer_names: ['mtq_x'] };
  assert.equal(deviceName('wheel_speed_rpm_1', g), 'rw2');
  assert.equal(deviceName('meas_wheel_speed_rpm_0', g), 'rw1');
  assert.equal(deviceName('fsw_rw_failed_1', g), 'rw2');
  assert.equal(deviceName('thruster_force_0', g), 'main');
  assert.equal(deviceName('mtq_dipole_0', g), 'mtq_x');
  assert.equal(deviceName('wheel_speed_rpm_5', g), null);
  assert.equal(deviceName('E_rot', g), null);
  assert.equal(deviceName('wheel_torque_0', {}), null);
});
