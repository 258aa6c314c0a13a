// Accuracy per cost of the fully-coupled wheel jitter (issue 20, item 3).
//
// Fully-coupled jitter is a forced oscillation at each wheel's spin
// frequency: with wheels near 3,000 rpm and the usual tick dt = 0.01 s the
// RK4 step turns a wheel by |Omega| h ~ 3 rad, and the jitter it computes is
// wrong however fast it is.  This program measures how wrong, against cost:
//
//   vehicle    the S1 hub (750 kg, diag(900, 800, 600) kg m^2), deep space,
//              four HR16-class fully-coupled wheels (m_w 9 kg, J_s 0.0796,
//              U_s 2.8e-6 kg m, U_d 7.7e-7 kg m^2) in the S1 pyramid, no
//              friction and no motor torque: the jitter alone
//   speeds     2,200, -2,500, 2,800, -2,950 rpm (36.7 to 49.2 Hz: all below
//              the 50 Hz Nyquist frequency of the 100 Hz comparison grid, so
//              the amplitude fits below cannot confuse two wheels)
//   reference  the same plant stepped at h = 1e-5 s (|Omega| h = 0.003 rad;
//              the RK4 error scales with (|Omega| h)^4: ~1e-10 relative)
//   compared   at every multiple of 0.01 s over T = 4 s (400 samples), for
//              each h of the sweep: body rate, fitted jitter amplitude at
//              each wheel frequency, attitude
//   cost       process CPU time of the steps (min/median/max of 5 repeats)
//              per simulated second; the harness's other per-tick work does
//              not depend on h (the FSW, sensors and recording keep their
//              rates with rates.plant_substeps)
//
// Columns: h, max|Omega| h, sub-steps per 0.01 s tick, plant CPU cost,
// body-rate error RMS / jitter RMS, worst relative error of the fitted
// jitter amplitude over the four wheel frequencies, pointing error RMS vs
// the reference [arcsec] beside the reference's pointing jitter RMS.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "sim/plant.h"
#include "sim/units.h"
#include "s1_wheel.h"

namespace {

constexpr double kT = 4.0;          // [s] simulated span
constexpr double kSample = 0.01;    // [s] comparison grid
constexpr int kSamples = 400;       // kT / kSample
constexpr double kRpm[4] = {2200.0, -2500.0, 2800.0, -2950.0};

double cpu_seconds()
{
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::unique_ptr<sim::Plant> make_plant()
{
  sim::SpacecraftParams p;
  p.hub.m_h = 750.0;
  p.hub.I_hBc_B = Eigen::Vector3d(900.0, 800.0, 600.0).asDiagonal();
  p.mu = 0.0;
  for (int i = 0; i < 4; ++i) {
    sim::ReactionWheelParams w = s1_wheel(i, sim::WheelModel::FullyCoupled);
    w.Omega_0 = sim::rad_s_from_rpm(kRpm[i]);
    p.wheels.push_back(w);
  }
  return std::make_unique<sim::Plant>(sim::PlantParams{p, {}}, sim::InitialConditions{});
}

struct Trace {
  std::vector<Eigen::Vector3d> omega, sigma;  // at the kSamples + 1 grid points
  double cpu = 0.0;                           // [s] of the stepping
};

Trace simulate(int64_t h_ns)
{
  const std::unique_ptr<sim::Plant> owner = make_plant();
  sim::Plant& plant = *owner;
  const int64_t grid_ns = static_cast<int64_t>(kSample * 1e9);
  const int64_t per = grid_ns / h_ns;  // steps per grid interval (h divides 0.01 s)
  Trace tr;
  tr.omega.reserve(kSamples + 1);
  tr.sigma.reserve(kSamples + 1);
  tr.omega.push_back(plant.omega_BN_B());
  tr.sigma.push_back(plant.sigma_BN());
  double cpu = 0.0;
  for (int k = 0; k < kSamples; ++k) {
    const double c0 = cpu_seconds();
    for (int64_t s = 0; s < per; ++s) plant.step(h_ns);
    cpu += cpu_seconds() - c0;
    tr.omega.push_back(plant.omega_BN_B());
    tr.sigma.push_back(plant.sigma_BN());
  }
  tr.cpu = cpu;
  return tr;
}

// Least-squares fit, per axis, of a + b t + sum_i (c_i cos w_i t + s_i sin w_i t)
// at the four wheel frequencies; returns the amplitude |(c_i, s_i)| over the
// three axes, per wheel.
std::vector<double> jitter_amplitudes(const std::vector<Eigen::Vector3d>& x)
{
  const int n = static_cast<int>(x.size());
  Eigen::MatrixXd A(n, 10);
  for (int k = 0; k < n; ++k) {
    const double t = k * kSample;
    A(k, 0) = 1.0;
    A(k, 1) = t;
    for (int i = 0; i < 4; ++i) {
      const double w = std::fabs(sim::rad_s_from_rpm(kRpm[i]));
      A(k, 2 + 2 * i) = std::cos(w * t);
      A(k, 3 + 2 * i) = std::sin(w * t);
    }
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  std::vector<double> amp(4, 0.0);
  for (int ax = 0; ax < 3; ++ax) {
    Eigen::VectorXd y(n);
    for (int k = 0; k < n; ++k) y(k) = x[static_cast<size_t>(k)](ax);
    const Eigen::VectorXd c = qr.solve(y);
    for (int i = 0; i < 4; ++i) amp[static_cast<size_t>(i)] += c(2 + 2 * i) * c(2 + 2 * i) + c(3 + 2 * i) * c(3 + 2 * i);
  }
  for (double& a : amp) a = std::sqrt(a);
  return amp;
}

// RMS about the mean of a vector series (per component, summed).
double rms_about_mean(const std::vector<Eigen::Vector3d>& x)
{
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& v : x) m += v;
  m /= static_cast<double>(x.size());
  double s = 0.0;
  for (const auto& v : x) s += (v - m).squaredNorm();
  return std::sqrt(s / static_cast<double>(x.size()));
}

}  // namespace

int main()
{
  const double Om_max = sim::rad_s_from_rpm(2950.0);
  const double rad_to_arcsec = 180.0 / M_PI * 3600.0;
  std::printf("Fully-coupled jitter, accuracy per cost: S1 hub, 4 wheels at 2200/-2500/2800/-2950 rpm, T = %.0f s,\n"
              "reference h = 1e-5 s, compared every 0.01 s; CPU = process CPU time of the plant steps\n\n", kT);
  const Trace ref = simulate(10'000);
  const std::vector<double> a_ref = jitter_amplitudes(ref.omega);
  std::vector<Eigen::Vector3d> w_dev(ref.omega.size());
  const double jit_rms = rms_about_mean(ref.omega);
  // pointing jitter of the reference: the attitude's wander about its mean, as an angle (4 |d sigma|)
  const double point_rms = 4.0 * rms_about_mean(ref.sigma) * rad_to_arcsec;
  std::printf("reference: body-rate jitter RMS %.3e rad/s, pointing jitter RMS %.3f arcsec; amplitudes",
              jit_rms, point_rms);
  for (double a : a_ref) std::printf(" %.3e", a);
  std::printf(" rad/s\n\n");
  std::printf("%9s %9s %9s %24s %12s %12s %12s\n", "h [s]", "|W|max h", "substeps", "CPU us / sim s min/med/max",
              "rate err", "ampl err", "point err");
  std::printf("%9s %9s %9s %24s %12s %12s %12s\n", "", "[rad]", "@0.01 s", "", "RMS/jitter", "worst", "RMS [\"]");
  const int64_t steps_ns[] = {10'000'000, 5'000'000, 2'500'000, 2'000'000, 1'250'000, 1'000'000, 500'000, 250'000, 100'000};
  for (int64_t h_ns : steps_ns) {
    std::vector<double> cost;
    Trace tr;
    for (int r = 0; r < 5; ++r) {
      tr = simulate(h_ns);
      cost.push_back(tr.cpu / kT * 1e6);
    }
    std::sort(cost.begin(), cost.end());
    double e_rate = 0.0, e_point = 0.0;
    for (size_t k = 0; k < tr.omega.size(); ++k) {
      e_rate += (tr.omega[k] - ref.omega[k]).squaredNorm();
      e_point += (tr.sigma[k] - ref.sigma[k]).squaredNorm();
    }
    e_rate = std::sqrt(e_rate / static_cast<double>(tr.omega.size())) / jit_rms;
    e_point = 4.0 * std::sqrt(e_point / static_cast<double>(tr.sigma.size())) * rad_to_arcsec;
    const std::vector<double> a = jitter_amplitudes(tr.omega);
    double e_amp = 0.0;
    for (size_t i = 0; i < 4; ++i) e_amp = std::max(e_amp, std::fabs(a[i] - a_ref[i]) / a_ref[i]);
    const double h = static_cast<double>(h_ns) * 1e-9;
    std::printf("%9.2e %9.3f %9lld %8.0f/%7.0f/%7.0f %12.2e %12.2e %12.2e\n", h, Om_max * h,
                static_cast<long long>(10'000'000 / h_ns), cost[0], cost[2], cost[4], e_rate, e_amp, e_point);
  }
  return 0;
}
