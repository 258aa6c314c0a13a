// No heap allocation inside the step (style guide §5, issue 6): a counting
// global operator new proves that step(), derivatives(), latch_wheel_commands(),
// mass_props(), energy_momentum() and the accessors allocate nothing once the
// run exists.  (Thrusters and tanks: test_thruster.cpp ThrusterNoHeap.)
#include <atomic>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "sim/plant.h"
#include "sim_test_util.h"

namespace {
std::atomic<long> g_news{0};
}

void* operator new(std::size_t n)
{
  g_news.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

TEST(NoHeap, CounterSeesAllocations)  // the probe itself works
{
  const long before = g_news.load();
  auto* v = new std::vector<double>(100);
  delete v;
  EXPECT_GE(g_news.load() - before, 2);
}

TEST(NoHeap, StepAndAccessorsDoNotAllocate)
{
  sim::SpacecraftParams p;
  p.hub = simtest::reference_hub();
  p.wheels = simtest::pyramid_wheels(sim::WheelModel::FullyCoupled);
  p.wheels[0].model = sim::WheelModel::Balanced;
  p.wheels[1].model = sim::WheelModel::SimpleJitter;
  p.hub.I_hBc_B += 0.2 * Eigen::Matrix3d::Identity();  // room for the balanced/simple J_s
  for (auto& w : p.wheels) {
    w.friction.tau_c = 1e-3;
    w.friction.beta_st = 0.5;
    w.friction.tau_st = 2e-3;
  }
  p.mu = sim::kMuEarth;
  sim::Plant sc({p, {}}, simtest::leo_ic());
  const sim::WheelArray cmd{0.01, -0.02, 0.03, 0.04};

  const long before = g_news.load();
  double sink = 0.0;
  for (int k = 0; k < 100; ++k) {
    sc.latch_wheel_commands(cmd);
    ASSERT_EQ(sc.step(simtest::ns(1e-3)), sim::StepStatus::Ok);
    const sim::StateVector xd = sc.derivatives(0.0, sc.state());
    sink += xd(0) + sc.energy_momentum().E_rot + sc.mass_props().m_sc + sc.tau_f(0) + sc.u_s(1) +
            sc.sensor_truth(Eigen::Vector3d(1.0, 0.0, 0.0)).Omega[2];
  }
  EXPECT_EQ(g_news.load() - before, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
