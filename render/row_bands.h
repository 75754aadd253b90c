#pragma once
// The rows of an image one MPI rank renders (render/ranks.h): bands of
// `bandHeight` rows dealt out in turn, band b to rank b mod ranks, so that
// every rank gets rows from the whole height (a frame's costly rows, the
// bunny or a room's clutter, are shared out rather than all falling to one
// rank). A renderer traces a local image of localHeight() rows whose row j is
// row globalRow(j) of the whole image: the camera and the AO samples use the
// global row (render/camera.h, kernels_glsl/row_bands.glsl), so each pixel's
// rays are bit for bit those of the whole image's. The default is the whole
// image.

#include <algorithm>
#include <cstddef>

namespace passtrace {

struct RowBands {
  int fullHeight = 0;   // the whole image's rows; 0 = the local image is the whole
  int bandHeight = 16;  // rows per band: whole tiles of the CPU renderer (4 or 8 rows)
  int ranks = 1, rank = 0;

  // Bands of 16 rows, fewer where the image is too short for every rank to get one.
  static RowBands interleaved(int fullHeight, int ranks, int rank) {
    return RowBands{fullHeight, std::max(1, std::min(16, fullHeight / std::max(1, ranks))), ranks, rank};
  }
  bool whole() const { return ranks <= 1; }
  // Rows of the whole image this rank renders.
  int localHeight() const {
    if (whole()) return fullHeight;
    const int bands = (fullHeight + bandHeight - 1) / bandHeight;
    int rows = 0;
    for (int b = rank; b < bands; b += ranks) rows += std::min(bandHeight, fullHeight - b * bandHeight);
    return rows;
  }
  // The whole image's row of local row j. Every owned band but the last is
  // full (the whole image's last band is the last of its rank).
  int globalRow(int j) const {
    if (whole()) return j;
    return ((j / bandHeight) * ranks + rank) * bandHeight + j % bandHeight;
  }
  // The whole image's index (row by row) of local pixel i.
  size_t globalPixel(size_t i, int width) const {
    if (whole()) return i;
    return size_t(globalRow(int(i / size_t(width)))) * size_t(width) + i % size_t(width);
  }
};

}  // namespace passtrace
