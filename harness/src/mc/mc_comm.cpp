// mc_comm.cpp: see mc_comm.h.
#include "mc/mc_comm.h"

#include <chrono>
#include <cstdlib>
#include <thread>
#include <stdexcept>

#ifdef KESTREL_HAVE_MPI
#define OMPI_SKIP_MPICXX 1  // the C API only (the C++ bindings need libmpi_cxx)
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace harness {

bool McComm::built_with_mpi()
{
#ifdef KESTREL_HAVE_MPI
  return true;
#else
  return false;
#endif
}

#ifdef KESTREL_HAVE_MPI

namespace {
bool launched_by_mpi()
{
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
         std::getenv("PMIX_RANK") != nullptr;
}

void check(int rc, const char* what)
{
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI error in ") + what);
}
}  // namespace

McComm::McComm()
{
  if (!launched_by_mpi()) return;
  int init = 0;
  MPI_Initialized(&init);
  if (!init) check(MPI_Init(nullptr, nullptr), "MPI_Init");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  active_ = true;
}

McComm::~McComm()
{
  if (active_) MPI_Finalize();
}

std::string McComm::broadcast(const std::string& text) const
{
  if (!active_) return text;
  unsigned long long n = text.size();
  check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD), "MPI_Bcast");
  std::string out = rank_ == 0 ? text : std::string(static_cast<size_t>(n), '\0');
  if (n > 0) check(MPI_Bcast(&out[0], static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return out;
}

std::vector<std::string> McComm::gather(const std::string& text) const
{
  if (!active_) return {text};
  // A rank that finished its runs first waits here without spinning: Open
  // MPI's blocking collectives poll at full speed, which would take a core
  // from the ranks still running (2 ranks on 2 cores).
  MPI_Request req;
  check(MPI_Ibarrier(MPI_COMM_WORLD, &req), "MPI_Ibarrier");
  for (int flag = 0;;) {
    check(MPI_Test(&req, &flag, MPI_STATUS_IGNORE), "MPI_Test");
    if (flag) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  // sizes first, then the texts (MPI_Gatherv counts are int: a rank's
  // records stay far below 2 GB -- a few kB per run)
  if (text.size() > 0x7fffffffULL) throw std::runtime_error("MPI gather: a rank's records exceed 2 GB");
  int n = static_cast<int>(text.size());
  std::vector<int> sizes(static_cast<size_t>(size_), 0);
  check(MPI_Gather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
  std::vector<int> displs(static_cast<size_t>(size_), 0);
  long long total = 0;
  for (int r = 0; r < size_; ++r) {
    displs[static_cast<size_t>(r)] = static_cast<int>(total);
    total += sizes[static_cast<size_t>(r)];
  }
  if (total > 0x7fffffffLL) throw std::runtime_error("MPI gather: the records exceed 2 GB; use shards and merge");
  std::string all(rank_ == 0 ? static_cast<size_t>(total) : 0, '\0');
  check(MPI_Gatherv(text.data(), n, MPI_CHAR, rank_ == 0 ? &all[0] : nullptr, sizes.data(), displs.data(), MPI_CHAR, 0,
                    MPI_COMM_WORLD),
        "MPI_Gatherv");
  std::vector<std::string> out;
  if (rank_ != 0) return out;
  for (int r = 0; r < size_; ++r)
    out.push_back(all.substr(static_cast<size_t>(displs[static_cast<size_t>(r)]), static_cast<size_t>(sizes[static_cast<size_t>(r)])));
  return out;
}

#else

McComm::McComm() = default;
McComm::~McComm() = default;
std::string McComm::broadcast(const std::string& text) const { return text; }
std::vector<std::string> McComm::gather(const std::string& text) const { return {text}; }

#endif

}  // namespace harness
