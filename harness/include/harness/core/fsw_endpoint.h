// fsw_endpoint: where the loop's flight software runs.  The loop hands the
// endpoint one FswAcsSensorMsg per control period and applies the
// FswAcsActuatorMsg it returns; the FswAcsHealthMsg is recorded.  Everything
// the harness needs of the FSW is in these three messages (it never reads
// the application's state).
//
//   InProcessFsw   fsw_acs_cycle() on a state in this process (the default)
//   (next)         a UDP or serial link to an FSW process or a board, a
//                  processor under emulation: implement FswEndpoint and pass
//                  it to Run (RunConfig::fsw); the loop does not change.
#ifndef HARNESS_FSW_ENDPOINT_H
#define HARNESS_FSW_ENDPOINT_H

#include <stdexcept>
#include <string>
#include <vector>

#include "sim/state_io.h"

extern "C" {
#include "fsw/fsw_acs.h"
}

namespace harness {

// What an endpoint throws when it cannot deliver a cycle (a link down, a
// board that does not answer): the run fails with its message.
class FswEndpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class FswEndpoint {
 public:
  virtual ~FswEndpoint() = default;
  // What runs the FSW (the data-flow map's description of the component).
  virtual std::string describe() const = 0;
  // One control cycle.  An endpoint that cannot deliver throws
  // FswEndpointError; the run then fails with that message.
  virtual void cycle(const FswAcsSensorMsg& in, FswAcsActuatorMsg& out, FswAcsHealthMsg& health) = 0;
  // Per-module health counters for fsw_health.txt (empty when the endpoint
  // cannot see them).
  virtual std::vector<std::string> module_health_lines() const { return {}; }
  // A ground/executive command (mode, actuation; FswAcsCmdMsg) for the next
  // cycle: scenario events (docs/events.md).  Endpoints that cannot deliver
  // one say so (accepts_commands false; command throws FswEndpointError).
  virtual bool accepts_commands() const { return false; }
  virtual void command(const FswAcsCmdMsg&) { throw FswEndpointError(describe() + ": takes no FSW commands"); }
  // Its state for a checkpoint (docs/checkpoint.md).  An endpoint whose FSW
  // runs elsewhere (another process, a board) has its state there: it
  // cannot be checkpointed (checkpointable false; state_io throws
  // FswEndpointError).
  virtual bool checkpointable() const { return false; }
  virtual void state_io(sim::StateIO&)
  {
    throw FswEndpointError(describe() + ": the flight software's state lives outside this process; a run with it "
                                        "cannot be checkpointed (docs/checkpoint.md)");
  }
};

// The FSW application in this process.
class InProcessFsw : public FswEndpoint {
 public:
  // cfg must pass fsw_acs_check (std::invalid_argument naming the field otherwise).
  explicit InProcessFsw(const FswAcsConfig& cfg);
  std::string describe() const override { return "fsw_c application (fsw_acs_cycle, in process)"; }
  void cycle(const FswAcsSensorMsg& in, FswAcsActuatorMsg& out, FswAcsHealthMsg& health) override;
  std::vector<std::string> module_health_lines() const override;
  bool accepts_commands() const override { return true; }
  // Passed to fsw_acs_cycle with the next cycle (then NULL again: the mode stays).
  void command(const FswAcsCmdMsg& cmd) override
  {
    cmd_ = cmd;
    have_cmd_ = true;
  }
  bool checkpointable() const override { return true; }
  // The application's state through its own image (fsw/fsw_acs_save.h),
  // then the pending command.
  void state_io(sim::StateIO& io) override;

 private:
  FswAcsConfig cfg_;
  FswAcsState st_;
  FswAcsCmdMsg cmd_{};
  bool have_cmd_ = false;
};

// Lines describing the last health message (status, mode, stages): the same
// for every endpoint.
std::vector<std::string> fsw_health_summary(const FswAcsHealthMsg& h);

}  // namespace harness

#endif  // HARNESS_FSW_ENDPOINT_H
