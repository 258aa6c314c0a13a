// The S1 pyramid's HR16-class wheel i (0..3) for the plant benchmarks:
// elevation 40 deg, azimuth 45 + 90 i deg, 0.8 m out and 1.7907 m up,
// 9 kg rotor, J_s 0.0795775 kg m^2, imbalances U_s 2.8e-6 kg m, U_d 7.7e-7 kg m^2.
#ifndef KESTREL_BENCH_S1_WHEEL_H
#define KESTREL_BENCH_S1_WHEEL_H

#include <cmath>

#include "sim/reaction_wheel.h"
#include "sim/units.h"

inline sim::ReactionWheelParams s1_wheel(int i, sim::WheelModel model)
{
  sim::ReactionWheelParams w;
  w.model = model;
  const double el = sim::rad_from_deg(40.0);
  const double az = sim::rad_from_deg(45.0 + 90.0 * i);
  w.gs_hat_nom_B = Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  w.r_WB_B = Eigen::Vector3d(0.8 * std::cos(az), 0.8 * std::sin(az), 1.7907);
  w.m_w = 9.0;
  w.J_s = 0.0795775;
  w.U_s = 2.8e-6;
  w.U_d = 7.7e-7;
  return w;
}

#endif
