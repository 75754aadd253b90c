#pragma once
// Assimp 5.2 does not reject every face that names a vertex the file lacks:
// its 3DS reader clamps the index to the last vertex ("3DS: Vertex index
// overflow", a warning) and its FBX reader drops the whole mesh ("polygon
// vertex index out of range", an error), and both go on. Only its log says
// so; this listens to the log while one file is read and keeps the first
// such message, which the loader then reports as the file's error. (COLLADA
// and X are checked otherwise: Assimp rejects COLLADA's bad index itself,
// and drops X's silently, which the loader sees as a face of too few
// corners; STL has no indices.)
//
// Assimp's logger is one per process: one watch at a time, on one thread, as
// passtrace loads its scene.

#include <memory>
#include <string>

namespace passtrace {

class AssimpIndexWatch {
 public:
  AssimpIndexWatch();
  ~AssimpIndexWatch();
  AssimpIndexWatch(const AssimpIndexWatch&) = delete;
  AssimpIndexWatch& operator=(const AssimpIndexWatch&) = delete;

  // The first message about an out-of-range index, without Assimp's
  // "Warn, T0: " prefix; empty if none.
  const std::string& finding() const;

 private:
  struct Listener;
  std::unique_ptr<Listener> listener_;
  bool ownsLogger_ = false;
};

}  // namespace passtrace
