// loop_error: what a component supplied to the loop from outside the harness
// (a Python effector, docs/python.md "Python in the loop") throws when it
// cannot deliver at a tick.  The run then fails at that tick with the
// message, the rows recorded so far kept (as for FswEndpointError).
#ifndef HARNESS_LOOP_ERROR_H
#define HARNESS_LOOP_ERROR_H

#include <stdexcept>

namespace harness {

class InLoopError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace harness

#endif  // HARNESS_LOOP_ERROR_H
