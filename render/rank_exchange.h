#pragma once
// What the MPI ranks of a run (render/ranks.h) send rank 0, packed as bytes
// and put back together there: a frame's band of rows, and at the end of a
// run each rank's share — the angles or sequence frames it rendered, the
// files they made, its host and times. Rank 0 merges the shares in angle or
// frame order, so its sums are the single process's, term for term.

#include <string>
#include <vector>

#include "render/frame_result.h"
#include "render/run_report.h"

namespace passtrace {

// One angle's fastest repeat (session.cpp sums them as a single process does).
struct AngleOutcome {
  size_t angle = 0;
  FrameStats stats;
};

// One frame of a --frames sequence.
struct SequenceOutcome {
  SequenceFrame record;
  FrameStats stats;
  AccelStats structure;
};

struct FileBytes {
  std::string path, bytes;
};

// Everything one rank hands rank 0 when its work is done.
struct RankShare {
  RankRun run;
  std::vector<AngleOutcome> angles;
  std::vector<SequenceOutcome> frames;
  std::vector<FileBytes> files;  // written by rank 0, with its own
};

std::string packShare(const RankShare& share);
RankShare unpackShare(const std::string& bytes);

// A rank's rows of one frame (RowBands::interleaved(fullHeight, ranks, rank)):
// pixels, per-pixel steps, the primary hits if captured, and its counters.
std::string packBand(const FrameResult& band);
// The whole frame from every rank's band, parts[r] from rank r: the counters
// summed (the most of each maximum; passes the most any rank ran), frameMs
// the slowest rank's.
FrameResult assembleBands(const std::vector<std::string>& parts, int fullHeight);

}  // namespace passtrace
