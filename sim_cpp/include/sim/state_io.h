// state_io: one list of a component's run state, walked both ways (save and
// restore) by a checkpoint (docs/checkpoint.md).
//
// A component that changes while a run goes has a state_io(StateIO&) member
// naming every member that changes (or that a setter may change during the
// run): the same function saves and restores, so the two cannot disagree.
// Members fixed by the configuration (parameters, geometry) are not in it:
// a checkpoint is restored into a run built from the same scenario.
#ifndef SIM_STATE_IO_H
#define SIM_STATE_IO_H

#include <cstddef>
#include <string>
#include <type_traits>

namespace sim {

class StateIO {
 public:
  virtual ~StateIO() = default;
  // True while restoring (bytes() then writes into p).
  virtual bool loading() const = 0;
  // n bytes at p, under a name (the part's label in error messages).
  virtual void bytes(const char* what, void* p, std::size_t n) = 0;

  // A plain value: arithmetic, enum, a fixed-size array or struct of those,
  // an Eigen fixed-size matrix (their bytes are the value; none holds a pointer).
  template <class T>
  void value(const char* what, T& v)
  {
    static_assert(!std::is_pointer<T>::value, "state_io: a pointer is not state");
    bytes(what, static_cast<void*>(&v), sizeof(T));
  }
};

}  // namespace sim

#endif  // SIM_STATE_IO_H
