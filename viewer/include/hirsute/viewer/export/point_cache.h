// An animation as a point cache in the PC2 format, which Blender's Mesh Cache modifier, Maya,
// Houdini and 3ds Max play over one base mesh: the base mesh is the first frame's OBJ, written
// as one object beside the cache (its stem with .obj, and its .mtl), and every frame is the
// positions of that OBJ's vertices, one for one. docs/export.md, "Point caches", has the layout.
//
// PC2 (3ds Max's Point Cache 2): a 32-byte header, the signature "POINTCACHE2\0", int32 version
// 1, int32 points, float32 start frame, float32 sample rate (frames a sample), int32 samples;
// then float32 x y z of every point, sample after sample. Little-endian.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "hirsute/core/output_folder.h"
#include "hirsute/core/output_target.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/export/export_file.h"

namespace hirsute {

inline constexpr std::size_t kPc2HeaderBytes = 32;

class PointCacheWriter {
 public:
  // `target` is the cache; `frames` the samples it will hold (frame 1 its first), each a frame
  // apart; `maxBytes` what the cache and its base mesh may take. Files are written in `group`,
  // which renames them into place when the run commits it. Throws std::runtime_error when a
  // file cannot be opened, std::invalid_argument when `target` ends in .obj or .mtl (the base
  // mesh's names).
  PointCacheWriter(std::filesystem::path target, int frames, std::uint64_t maxBytes,
                   OutputGroup* group);
  ~PointCacheWriter();

  // The scene of the next frame. The first writes the base mesh and the header. Throws
  // std::invalid_argument when the frame has another number of vertices than the first (a point
  // cache moves the same points every frame), when the cache would take more than `maxBytes`,
  // or for a coordinate that is not finite; std::runtime_error when a file cannot be written.
  void addFrame(const Scene& scene);
  // After the last frame: checks that every frame came, and flushes the cache (its group then
  // commits it). Throws std::logic_error when frames are missing.
  void finish();

  std::uint64_t points() const { return points_; }
  std::uint64_t bytes() const { return cache_.bytesWritten(); }
  std::uint64_t baseMeshBytes() const { return baseMeshBytes_; }
  const std::filesystem::path& baseMesh() const { return baseMesh_; }

 private:
  std::filesystem::path target_, baseMesh_;
  int frames_ = 0, written_ = 0;
  std::uint64_t maxBytes_ = 0, points_ = 0, baseMeshBytes_ = 0;
  OutputGroup* group_ = nullptr;
  OutputFolder folder_;
  ExportFile cache_;
  std::vector<glm::vec3> positions_;
};

}  // namespace hirsute
