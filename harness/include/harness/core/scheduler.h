// scheduler: fixed-rate scheduler on an integer tick counter with rate groups.
// The clock is the tick index k (uint64); time is t_ns = k * tick_ns, never a
// summed double.  A rate group (divisor d, offset o, o < d) is due at every
// tick k with k % d == o.  Tasks run in registration order within a tick.
#ifndef HARNESS_SCHEDULER_H
#define HARNESS_SCHEDULER_H

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace harness {

struct RateGroup {
  std::string name;
  uint32_t divisor = 1;  // [ticks] period, >= 1
  uint32_t offset = 0;   // [ticks] phase, < divisor

  bool due(uint64_t tick) const { return tick % divisor == offset; }
  // Number of due ticks k in [0, n_ticks).
  uint64_t count_due(uint64_t n_ticks) const
  {
    return n_ticks > offset ? (n_ticks - offset - 1) / divisor + 1 : 0;
  }
};

// Throws std::invalid_argument naming the group if divisor == 0 or
// offset >= divisor.
void validate(const RateGroup& g);

class Scheduler {
 public:
  using TaskFn = std::function<void(uint64_t tick)>;

  explicit Scheduler(uint64_t tick_ns);  // tick_ns > 0

  // Registers a task in group g (validated); returns its index.
  size_t add_task(std::string name, const RateGroup& g, TaskFn fn);
  // A task due whenever any of its groups is (e.g. `truth`: when one of its
  // readers is due); at least one group.
  size_t add_task(std::string name, std::vector<RateGroup> groups, TaskFn fn);

  // Runs every task due at `tick`, in registration order.  Returns the number run.
  size_t run_tick(uint64_t tick);

  uint64_t tick_ns() const { return tick_ns_; }
  uint64_t t_ns(uint64_t tick) const { return tick * tick_ns_; }
  size_t num_tasks() const { return tasks_.size(); }
  const std::vector<RateGroup>& groups(size_t task) const { return tasks_[task].groups; }
  const std::string& task_name(size_t task) const { return tasks_[task].name; }
  uint64_t run_count(size_t task) const { return tasks_[task].runs; }

  // Times every task call (steady clock, ~20 ns per reading) from now on;
  // off by default (`kestrel bench` turns it on for its split).
  void set_profiling(bool on) { profiling_ = on; }
  bool profiling() const { return profiling_; }
  uint64_t elapsed_ns(size_t task) const { return tasks_[task].ns; }  // [ns] while profiling

 private:
  struct Task {
    std::string name;
    std::vector<RateGroup> groups;
    TaskFn fn;
    bool every = false;  // one of its groups has divisor 1: due at every tick, no test
    uint64_t runs = 0;
    uint64_t ns = 0;
  };
  uint64_t tick_ns_;
  bool profiling_ = false;
  std::vector<Task> tasks_;
};

}  // namespace harness

#endif  // HARNESS_SCHEDULER_H
