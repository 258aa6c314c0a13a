// mc_comm: the ranks of a Monte Carlo campaign started by `mpirun`
// (OpenMPI; docs/monte-carlo.md).  Without MPI in the build, or when kestrel
// is not started by an MPI launcher, there is one rank and every call is
// trivial.  Private to the harness library.
#ifndef HARNESS_SRC_MC_COMM_H
#define HARNESS_SRC_MC_COMM_H

#include <string>
#include <vector>

namespace harness {

class McComm {
 public:
  // Initialises MPI when the process was started by an MPI launcher
  // (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK in the environment).
  McComm();
  ~McComm();  // MPI_Finalize
  McComm(const McComm&) = delete;
  McComm& operator=(const McComm&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool active() const { return active_; }
  // Rank 0's text on every rank.
  std::string broadcast(const std::string& text) const;
  // Every rank's text, on rank 0 (in rank order); empty elsewhere.
  std::vector<std::string> gather(const std::string& text) const;
  static bool built_with_mpi();

 private:
  int rank_ = 0, size_ = 1;
  bool active_ = false;
};

}  // namespace harness

#endif  // HARNESS_SRC_MC_COMM_H
