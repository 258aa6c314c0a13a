#include "harness/core/scheduler.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>

namespace harness {

void validate(const RateGroup& g)
{
  if (g.divisor == 0)
    throw std::invalid_argument("rate group '" + g.name + "': divisor must be >= 1");
  if (g.offset >= g.divisor)
    throw std::invalid_argument("rate group '" + g.name + "': offset " + std::to_string(g.offset) +
                                " must be < divisor " + std::to_string(g.divisor));
}

Scheduler::Scheduler(uint64_t tick_ns) : tick_ns_(tick_ns)
{
  if (tick_ns == 0) throw std::invalid_argument("scheduler: tick_ns must be > 0");
}

size_t Scheduler::add_task(std::string name, const RateGroup& g, TaskFn fn)
{
  return add_task(std::move(name), std::vector<RateGroup>{g}, std::move(fn));
}

size_t Scheduler::add_task(std::string name, std::vector<RateGroup> groups, TaskFn fn)
{
  if (groups.empty()) throw std::invalid_argument("scheduler: task '" + name + "' has no rate group");
  for (const RateGroup& g : groups) validate(g);
  if (!fn) throw std::invalid_argument("scheduler: task '" + name + "' has no function");
  const bool every = std::any_of(groups.begin(), groups.end(), [](const RateGroup& g) { return g.divisor == 1; });
  tasks_.push_back(Task{std::move(name), std::move(groups), std::move(fn), every, 0, 0});
  return tasks_.size() - 1;
}

size_t Scheduler::run_tick(uint64_t tick)
{
  size_t n = 0;
  for (Task& t : tasks_) {
    // a group of divisor 1 (offset 0) is due at every tick: the test is the flag
    if (t.every || std::any_of(t.groups.begin(), t.groups.end(), [tick](const RateGroup& g) { return g.due(tick); })) {
      if (profiling_) {
        const auto t0 = std::chrono::steady_clock::now();
        t.fn(tick);
        t.ns += static_cast<uint64_t>(
            std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
      } else {
        t.fn(tick);
      }
      ++t.runs;
      ++n;
    }
  }
  return n;
}

}  // namespace harness
