// The rows of the whole image a stream holds (render/row_bands.h): bands of
// x rows dealt out in turn to y MPI ranks, this rank z. Local row j is row
// imageRow(j) of the whole image; the camera and the AO samples use it, so a
// rank's pixels trace the whole image's rays. Unset (0) or one rank: the
// whole image.
uniform ivec3 uRowBands;

uint imageRow(uint j) {
  if (uRowBands.y <= 1) return j;
  uint h = uint(uRowBands.x), n = uint(uRowBands.y), r = uint(uRowBands.z);
  return ((j / h) * n + r) * h + j % h;
}
