// run.cpp: a run's tick protocol (the schedule of its tasks) and its
// stepping.  The parts live in their own files: run_impl.h (Run::Impl),
// run_wiring.cpp (the parts wired together), run_state.cpp (checkpoints),
// run_summary.cpp (the summary), plant_builder (plant, burn schedule),
// fsw_config (the FSW's configuration), sensor_suite (sensor models), tasks
// (the tick protocol's tasks), telemetry_columns (what is recorded).
#include "harness/core/run.h"
#include "harness/core/loop_error.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "core/run_impl.h"
#include "sim/environment.h"

#ifndef KESTREL_VERSION
#define KESTREL_VERSION "0.0.0"
#endif

namespace harness {

const char* version() { return KESTREL_VERSION; }

namespace {

// TruthReaders: due when a reader of `truth` is (the FSW input, metrics and
// recorder; every tick when the burn monitor runs), not at every tick.
enum class Group { EveryTick, Fsw, Record, TruthReaders };
struct Slot {
  const char* task;
  Group group;
};
// The tick protocol: the order of the tasks within a tick (run.h).  A task a
// run does not need (no thrusters, no sampled sensors, ...) is skipped.
constexpr Slot kTickProtocol[] = {
    {"events", Group::EveryTick},
    {"truth", Group::TruthReaders},      {"mtq_state", Group::Record},
    {"burn_monitor", Group::EveryTick},  {"sample_sensors", Group::EveryTick},
    {"magnetometer", Group::EveryTick},  {"css", Group::Fsw},
    {"sensors", Group::Fsw},             {"fsw_acs", Group::Fsw},
    {"actuators", Group::Fsw},           {"plant_input", Group::Fsw},
    {"magnetorquers", Group::Fsw},       {"metrics", Group::Record},
    {"recorder", Group::Record},
};

}  // namespace

// The tick protocol's table: each task the run has, in its rate groups.
void Run::Impl::schedule(const RateGroup& fsw_group, const RateGroup& rec_group)
{
  const RateGroup every{"every_tick", 1, 0};
  auto fn_of = [this](const std::string& name) -> Scheduler::TaskFn {
    if (name == "events" && events) return [t = &*events](uint64_t k) { (*t)(k); };
    if (name == "truth") return [t = &*truth](uint64_t k) { (*t)(k); };
    if (name == "burn_monitor" && burn) return [t = &*burn](uint64_t k) { (*t)(k); };
    if (name == "sample_sensors" && sample) return [t = &*sample](uint64_t k) { (*t)(k); };
    if (name == "magnetometer" && magnetometer) return [t = &*magnetometer](uint64_t k) { (*t)(k); };
    if (name == "magnetorquers" && magnetorquers) return [t = &*magnetorquers](uint64_t k) { (*t)(k); };
    if (name == "mtq_state" && mtq_state) return [t = &*mtq_state](uint64_t k) { (*t)(k); };
    if (name == "css" && css) return [t = &*css](uint64_t k) { (*t)(k); };
    if (name == "sensors") return [t = &*fsw_input](uint64_t k) { (*t)(k); };
    if (name == "fsw_acs") return [t = &*fsw_task](uint64_t k) { (*t)(k); };
    if (name == "actuators") return [t = &*actuators](uint64_t k) { (*t)(k); };
    if (name == "plant_input") return [t = &*plant_input](uint64_t k) { (*t)(k); };
    if (name == "metrics") return [t = &*metrics](uint64_t k) { (*t)(k); };
    if (name == "recorder") return [r = &rec](uint64_t) { r->sample(); };
    return nullptr;
  };
  for (const Slot& s : kTickProtocol) {
    Scheduler::TaskFn fn = fn_of(s.task);
    if (!fn) continue;
    std::vector<RateGroup> g;
    if (s.group == Group::EveryTick || (s.group == Group::TruthReaders && burn)) g = {every};
    else if (s.group == Group::TruthReaders) g = {fsw_group, rec_group};
    else g = {s.group == Group::Fsw ? fsw_group : rec_group};
    sched.add_task(s.task, std::move(g), std::move(fn));
  }
}

FswAcsConfig fsw_acs_config_of(const Scenario& sc)
{
  return make_fsw_setup(sc, build_plant(sc)->mass_props()).cfg;
}

Run::Run(const Scenario& sc, RunConfig cfg) : impl_(std::make_unique<Impl>(sc)) { impl_->wire(cfg); }

Run::~Run() = default;

void Run::add_sink(RecordSink& sink)
{
  if (impl_->tick > 0) throw std::logic_error("Run::add_sink: the run has started");
  impl_->rec.add_sink(sink);
}

// The plant over one tick: rates.plant_substeps steps of dt / n (docs/harness.md).
bool Run::Impl::step_plant()
{
  for (int i : jitter_wheels) max_jitter_Omega = std::max(max_jitter_Omega, std::fabs(plant.Omega(i)));
  const bool timed = sched.profiling();
  const auto t0 = timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  bool ok = true;
  for (uint32_t s = 0; s < sc.rates.plant_substeps && ok; ++s) ok = plant.step(substep_ns) == sim::StepStatus::Ok;
  if (timed)
    plant_ns += static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
  return ok;
}

bool wheel_jitters(const sim::ReactionWheelParams& p)
{
  return p.model != sim::WheelModel::Balanced && (p.U_s > 0.0 || p.U_d > 0.0);
}

uint32_t substeps_for(double Omega_abs, double dt)
{
  const double n = std::ceil(Omega_abs * dt / kJitterStepLimit);
  return n < 1.0 ? 1u : n > 1e9 ? 1000000000u : static_cast<uint32_t>(n);
}

std::vector<std::string> jitter_step_warnings(const Scenario& sc)
{
  std::vector<std::string> out;
  const double h = sc.rates.dt / sc.rates.plant_substeps;
  for (size_t i = 0; i < sc.wheels.size(); ++i) {
    const sim::ReactionWheelParams& p = sc.wheels[i].params;
    const double step = std::fabs(p.Omega_0) * h;
    if (!wheel_jitters(p) || !(step > kJitterStepLimit)) continue;
    std::ostringstream w;
    w.precision(3);
    w << "wheels[" << i << "] (" << sc.wheels[i].name << "): its imbalance jitter is under-resolved: |Omega_0| h = "
      << step << " rad per plant step (h = " << h << " s) > " << kJitterStepLimit
      << " rad; rates.plant_substeps: " << substeps_for(std::fabs(p.Omega_0), sc.rates.dt)
      << " or more keeps it within (docs/performance.md)";
    out.push_back(w.str());
  }
  return out;
}

std::string jitter_reached_warning(double max_step)
{
  std::ostringstream w;
  w.precision(3);
  w << "a jittering wheel reached |Omega| h = " << max_step << " rad per plant step (> " << kJitterStepLimit
    << "): its imbalance jitter is under-resolved; raise rates.plant_substeps (docs/performance.md)";
  return w.str();
}

bool Run::step_ticks(uint64_t n)
{
  Impl& m = *impl_;
  if (!m.failure.empty()) return false;
  // an error of a part outside the run's own code stops the run at this tick, rows kept
  const auto fail = [&](const char* who, const std::exception& e) {
    m.failure = std::string(who) + "at t = " + std::to_string(static_cast<double>(m.sched.t_ns(m.tick)) * 1e-9) +
                " s: " + e.what();
    finish();
    return false;
  };
  for (uint64_t i = 0; i < n && m.tick <= m.n_ticks; ++i) {
    try {
      m.sched.run_tick(m.tick);
    } catch (const FswEndpointError& e) {  // e.g. a remote FSW endpoint's link
      return fail("FSW endpoint ", e);
    } catch (const InLoopError& e) {  // e.g. a Python sensor at a recorded row
      return fail("", e);
    }
    if (m.rec.overflow() > 0) {
      m.failure = "recorder overflow at tick " + std::to_string(m.tick) + " (internal error)";
      finish();
      return false;
    }
    if (m.tick < m.n_ticks) {
      bool stepped = false;
      try {
        stepped = m.step_plant();
      } catch (const InLoopError& e) {  // e.g. a Python effector (docs/python.md)
        return fail("plant ", e);
      }
      if (!stepped) {
        m.failure = "plant state became non-finite at t = " +
                    std::to_string(static_cast<double>(m.sched.t_ns(m.tick)) * 1e-9) + " s";
        ++m.tick;
        finish();
        return false;
      }
    }
    ++m.tick;
  }
  if (m.tick > m.n_ticks) finish();  // the last row reaches the sinks
  return true;
}

void Run::finish() { impl_->rec.finish(impl_->failure.empty() && impl_->tick > impl_->n_ticks); }
bool Run::done() const { return impl_->tick > impl_->n_ticks || !impl_->failure.empty(); }
uint64_t Run::tick() const { return impl_->tick; }
uint64_t Run::total_ticks() const { return impl_->n_ticks + 1; }
const std::string& Run::failure() const { return impl_->failure; }
const Scenario& Run::scenario() const { return impl_->sc; }
const Recorder& Run::recorder() const { return impl_->rec; }
const DataFlow& Run::dataflow() const { return impl_->flow; }
const Scheduler& Run::scheduler() const { return impl_->sched; }
sim::Plant& Run::plant() { return impl_->plant; }
const sim::Plant& Run::plant() const { return impl_->plant; }

void Run::add_event(const EventSpec& e)
{
  Impl& m = *impl_;
  if (!m.events) throw std::logic_error("Run::add_event: the run was built without RunConfig::accept_events");
  m.sc.events.push_back(e);
  try {
    m.events->add();
  } catch (...) {
    m.sc.events.pop_back();
    throw;
  }
}

bool Run::fsw_accepts_commands() const { return impl_->fsw->accepts_commands(); }

bool Run::accepts_events() const { return impl_->accept_events; }

std::array<double, 2> Run::fsw_gains() const
{
  const Impl& m = *impl_;
  if (m.events) return {static_cast<double>(m.events->command().K), static_cast<double>(m.events->command().P)};
  return {static_cast<double>(m.fsw_setup.cfg.mrp_fb.K), static_cast<double>(m.fsw_setup.cfg.mrp_fb.P)};
}

const std::vector<AppliedEvent>& Run::events_applied() const
{
  static const std::vector<AppliedEvent> kNone;
  return impl_->events ? impl_->events->log() : kNone;
}

const MemorySink& Run::memory() const
{
  if (!impl_->mem) throw std::logic_error("Run::memory: this run does not keep its rows in memory");
  return *impl_->mem;
}


PointingReference Run::final_pointing_reference() const { return impl_->metrics->ref; }
bool Run::pointing_reference_commanded() const { return impl_->metrics->ref_commanded; }

const char* describe(PointingReference r)
{
  switch (r) {
    case PointingReference::Inertial: return "principal angle from the inertial reference";
    case PointingReference::SunAxis: return "Sun-axis angle";
    case PointingReference::OrbitFrame: return "principal angle from the orbit-frame reference";
  }
  return "?";
}

std::vector<std::array<double, 3>> Run::wheel_axes_B() const
{
  std::vector<std::array<double, 3>> out;
  for (const WheelSpec& w : impl_->sc.wheels)
    out.push_back({w.params.gs_hat_nom_B(0), w.params.gs_hat_nom_B(1), w.params.gs_hat_nom_B(2)});
  return out;
}

std::vector<std::string> Run::fsw_health_lines() const
{
  std::vector<std::string> out = fsw_health_summary(impl_->health_ch->value());
  for (std::string& l : impl_->fsw->module_health_lines()) out.push_back(std::move(l));
  return out;
}

void Run::set_profiling(bool on) { impl_->sched.set_profiling(on); }

std::vector<std::pair<std::string, uint64_t>> Run::profile() const
{
  const Impl& m = *impl_;
  std::vector<std::pair<std::string, uint64_t>> out;
  for (size_t i = 0; i < m.sched.num_tasks(); ++i) out.emplace_back(m.sched.task_name(i), m.sched.elapsed_ns(i));
  out.emplace_back("plant", m.plant_ns);
  return out;
}

double Run::max_jitter_step() const
{
  return impl_->max_jitter_Omega * static_cast<double>(impl_->substep_ns) * 1e-9;
}

}  // namespace harness
