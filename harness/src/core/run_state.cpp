// run_state.cpp: a run's whole state for a checkpoint (Run::state_io,
// docs/checkpoint.md), part by part in a fixed order, and why a run cannot
// be saved now (Run::checkpoint_refusal).
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "core/run_impl.h"

namespace harness {

namespace {

// A task's state for a checkpoint: a task whose operator() is const keeps
// none of its own (what it drives, the plant or the sensors, is saved with
// them); any other must have state_io (Run::state_io calls it).  Checked at
// compile time for every task type, so that a task with state cannot be
// added without being in the checkpoint.
template <class T, class = void>
struct HasStateIo : std::false_type {};
template <class T>
struct HasStateIo<T, std::void_t<decltype(std::declval<T&>().state_io(std::declval<sim::StateIO&>()))>>
    : std::true_type {};
template <class T, class = void>
struct ConstCall : std::false_type {};
template <class T>
struct ConstCall<T, std::void_t<decltype(std::declval<const T&>()(uint64_t{0}))>> : std::true_type {};
template <class... T>
constexpr bool kTasksCheckpointed = ((ConstCall<T>::value || HasStateIo<T>::value) && ...);
static_assert(kTasksCheckpointed<TruthTask, BurnMonitor, SampleSensorsTask, CssTask, FswInputTask, FswTask, ActuatorTask,
                                 PlantInputTask, MetricsTask, EventTask, MagnetometerTask, MagnetorquerTask, MtqStateTask>,
              "a task with state of its own (non-const operator()) needs state_io, called by Run::state_io");

}  // namespace

std::string Run::checkpoint_refusal() const
{
  const Impl& m = *impl_;
  if (!m.failure.empty()) return "the run failed: " + m.failure;
  if (m.tick > m.n_ticks) return "the run has ended";
  if (!m.fsw->checkpointable())
    return "the flight software (" + m.fsw->describe() + ") keeps state the harness cannot save";
  if (m.n_truth_sources > 0) return "sensors of the caller's own (Python) are in the loop: their state is not the harness's to save";
  return "";
}

void Run::state_io(sim::StateIO& io)
{
  Impl& m = *impl_;
  if (!io.loading()) {
    const std::string why = checkpoint_refusal();
    if (!why.empty()) throw std::logic_error("checkpoint: " + why);
  }
  if (io.loading() && m.tick != 0) throw std::logic_error("checkpoint: restore into a run that has not started");
  uint64_t n_ticks = m.n_ticks;
  io.value("run.num_ticks", n_ticks);
  if (n_ticks != m.n_ticks) throw std::runtime_error("checkpoint: the run has another number of ticks");
  io.value("run.tick", m.tick);
  io.value("run.max_jitter_Omega", m.max_jitter_Omega);
  m.plant.state_io(io);
  m.fsw->state_io(io);
  m.sensors->state_io(io);
  m.flow.state_io(io);
  m.rec.state_io(io);
  if (m.burn) m.burn->state_io(io);
  m.fsw_task->state_io(io);
  m.metrics->state_io(io);
  if (m.events) m.events->state_io(io);
}
}  // namespace harness
