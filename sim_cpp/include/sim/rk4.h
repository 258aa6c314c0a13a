// rk4: classic fixed-step fourth-order Runge-Kutta (docs/dynamics.md §7.1).
// Butcher c = 0, 1/2, 1/2, 1; b = 1/6, 1/3, 1/3, 1/6.  Works for any State that
// supports x + a*k (double, fixed-size Eigen vectors, sim::StateVector); each
// stage is materialised as a State so no Eigen expression outlives its operands.
#ifndef SIM_RK4_H
#define SIM_RK4_H

namespace sim {

// f(t, x) -> x_dot.  Returns x(t + dt).
template <class State, class Deriv>
State rk4_step(const State& x, double t, double dt, Deriv&& f)
{
  const double h2 = 0.5 * dt;
  const State k1 = f(t, x);
  const State x2 = x + h2 * k1;
  const State k2 = f(t + h2, x2);
  const State x3 = x + h2 * k2;
  const State k3 = f(t + h2, x3);
  const State x4 = x + dt * k3;
  const State k4 = f(t + dt, x4);
  const State x_next = x + (dt / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  return x_next;
}

}  // namespace sim

#endif  // SIM_RK4_H
