#include "render/ranks.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#ifdef PASSTRACE_WITH_MPI
#include <mpi.h>  // its C interface (render/CMakeLists.txt: MPI_CXX_SKIP_MPICXX)
#endif

namespace passtrace::ranks {
namespace {

bool started = false, failedRun = false;
int rankCount = 1, rankIndex = 0;

#ifdef PASSTRACE_WITH_MPI
// The variables Open MPI's mpirun, PMIx (srun --mpi=pmix) and PMI-1/2
// launchers (MPICH's hydra, srun --mpi=pmi2) give their processes.
bool launchedByMpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

// Seconds a rank waits for the others in agree(): PASSTRACE_RANK_TIMEOUT, or
// unbounded (a rank's share of the work may take hours). A rank that has
// failed waits at most 60 s to tell the others, then ends the job: its own
// error is never lost behind a rank that hangs.
double waitLimit(bool failing) {
  double limit = 0;
  if (const char* text = std::getenv("PASSTRACE_RANK_TIMEOUT")) limit = std::atof(text);
  if (failing && (limit <= 0 || limit > 60)) limit = 60;
  return limit;
}

// Waits for `request`, polling: spinning at first (a step's partners are
// usually close behind), then sleeping so that a waiting rank leaves its
// core to the ranks still working beside it.
void waitFor(MPI_Request& request, const std::string& error) {
  const auto start = std::chrono::steady_clock::now();
  const double limit = waitLimit(!error.empty());
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (limit > 0 && waited > limit) {
      const std::string why = error.empty() ? "the other ranks did not arrive within PASSTRACE_RANK_TIMEOUT (" +
                                                  std::to_string(int(limit)) + " s)"
                                            : error;
      std::fprintf(stderr, "passtrace: error: rank %d: %s\n", rankIndex, why.c_str());
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    if (waited < 0.01) std::this_thread::yield();
    else std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}
#endif

}  // namespace

void start(int& argc, char**& argv) {
#ifdef PASSTRACE_WITH_MPI
  if (started || !launchedByMpi()) return;
  MPI_Init(&argc, &argv);
  started = true;
  MPI_Comm_size(MPI_COMM_WORLD, &rankCount);
  MPI_Comm_rank(MPI_COMM_WORLD, &rankIndex);
#else
  (void)argc, (void)argv;
#endif
}

void stop() {
#ifdef PASSTRACE_WITH_MPI
  if (started) MPI_Finalize();
  started = false;
#endif
}

int count() { return rankCount; }
int index() { return rankIndex; }
bool failed() { return failedRun; }

std::string host() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

void agree(const std::string& error) {
  if (rankCount == 1) {
    if (error.empty()) return;
    failedRun = true;
    throw RankFailure(error);
  }
#ifdef PASSTRACE_WITH_MPI
  int mine = error.empty() ? 0 : 1;
  std::vector<int> all(size_t(rankCount), 0);
  MPI_Request request;
  MPI_Iallgather(&mine, 1, MPI_INT, all.data(), 1, MPI_INT, MPI_COMM_WORLD, &request);
  waitFor(request, error);
  int first = -1;
  for (int r = 0; r < rankCount && first < 0; ++r)
    if (all[size_t(r)]) first = r;
  if (first < 0) return;
  failedRun = true;
  // The first failing rank's message, to every rank.
  std::string message = rankIndex == first ? error : std::string();
  unsigned long long length = message.size();
  MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, first, MPI_COMM_WORLD);
  message.resize(size_t(length));
  MPI_Bcast(message.data(), int(length), MPI_CHAR, first, MPI_COMM_WORLD);
  throw RankFailure("rank " + std::to_string(first) + ": " + message);
#endif
}

std::vector<std::string> gatherOnRoot(const std::string& bytes) {
  agree();
  if (rankCount == 1) return {bytes};
  std::vector<std::string> all;
#ifdef PASSTRACE_WITH_MPI
  // Point to point, in pieces of at most 1 GiB: MPI counts are ints, and a
  // rank's share of a 16K image is several GiB.
  constexpr size_t kPiece = size_t(1) << 30;
  if (rankIndex == 0) {
    all.resize(size_t(rankCount));
    all[0] = bytes;
    for (int r = 1; r < rankCount; ++r) {
      unsigned long long length = 0;
      MPI_Recv(&length, 1, MPI_UNSIGNED_LONG_LONG, r, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      std::string& in = all[size_t(r)];
      in.resize(size_t(length));
      for (size_t at = 0; at < in.size(); at += kPiece)
        MPI_Recv(in.data() + at, int(std::min(kPiece, in.size() - at)), MPI_CHAR, r, 1, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
    }
  } else {
    unsigned long long length = bytes.size();
    MPI_Send(&length, 1, MPI_UNSIGNED_LONG_LONG, 0, 0, MPI_COMM_WORLD);
    for (size_t at = 0; at < bytes.size(); at += kPiece)
      MPI_Send(bytes.data() + at, int(std::min(kPiece, bytes.size() - at)), MPI_CHAR, 0, 1, MPI_COMM_WORLD);
  }
#endif
  return all;
}

}  // namespace passtrace::ranks
