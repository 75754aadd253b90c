#pragma once
// The processes of one run: MPI ranks when a launcher (mpirun, srun) started
// passtrace, else one. The session divides a run's work among them (camera
// angles, a sequence's frames, a frame's rows: render/session.cpp) and
// gathers it on rank 0, which alone writes the outputs.
//
// Every collective step goes through agree(): a rank that failed says so
// there instead of doing its next step, and every rank then stops with the
// message of the lowest rank that failed. So an error on one rank ends the
// run on all of them with one line, and no rank waits for a partner that
// will never come. A rank that dies is the launcher's to notice (Open MPI
// ends the job); a rank that waits longer than PASSTRACE_RANK_TIMEOUT seconds
// (if set) for the others ends the job itself.
//
// Built without MPI, or started without a launcher: one rank and no MPI call
// (MPI_Init alone costs about 0.4 s).

#include <stdexcept>
#include <string>
#include <vector>

namespace passtrace::ranks {

// MPI_Init when a launcher started this process; otherwise nothing.
void start(int& argc, char**& argv);
// MPI_Finalize, if started.
void stop();

int count();  // ranks in the run; 1 without MPI
int index();  // this rank's, 0 .. count() - 1
inline bool isRoot() { return index() == 0; }
std::string host();  // this machine's name

// Thrown by agree() on every rank when some rank failed: what() is
// "rank R: message" for the lowest such rank.
struct RankFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Every rank calls it at the same points of a run, `error` empty when its
// work went well. Returns when every rank's did; else throws RankFailure on
// all. After a failure no rank calls it again (failed() is true).
void agree(const std::string& error = {});
bool failed();

// agree(), then rank 0 receives every rank's bytes in rank order (its own
// first); the other ranks get an empty list.
std::vector<std::string> gatherOnRoot(const std::string& bytes);

}  // namespace passtrace::ranks
