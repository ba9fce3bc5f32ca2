#include "hirsute/viewer/export/point_cache.h"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "hirsute/viewer/export/obj_writer.h"

namespace hirsute {

static_assert(std::endian::native == std::endian::little,
              "PC2 is little-endian, written as the machine holds its numbers");

namespace {

// The cache's name, refused before anything is opened when it is one its base mesh takes.
std::filesystem::path cacheName(std::filesystem::path target) {
  const std::string extension = target.extension().string();
  if (extension == ".obj" || extension == ".mtl")
    throw std::invalid_argument(target.string() +
                                ": the point cache's base mesh takes its name with .obj and "
                                ".mtl; name the cache FILE.pc2");
  return target;
}

}  // namespace

PointCacheWriter::PointCacheWriter(std::filesystem::path target, int frames, std::uint64_t maxBytes,
                                   OutputGroup* group)
    : target_(cacheName(std::move(target))),
      baseMesh_(target_.parent_path() / (target_.stem().string() + ".obj")),
      frames_(frames),
      maxBytes_(maxBytes),
      group_(group),
      folder_(target_.parent_path()),
      cache_(target_, group) {}

PointCacheWriter::~PointCacheWriter() = default;

void PointCacheWriter::addFrame(const Scene& scene) {
  if (written_ >= frames_) throw std::logic_error("more frames than the point cache announced");
  positions_.clear();
  ObjOptions options;
  options.positions = &positions_;
  options.oneObject = true;
  if (written_ == 0) {
    // The base mesh: the first frame, one object, its side files beside the cache.
    options.group = group_;
    options.folder = &folder_;
    baseMeshBytes_ = writeObj(scene, baseMesh_, options).bytes;
    points_ = positions_.size();
    const std::uint64_t total =
        kPc2HeaderBytes + static_cast<std::uint64_t>(frames_) * points_ * 3 * sizeof(float);
    if (total + baseMeshBytes_ > maxBytes_) {
      throw std::invalid_argument(fmt::format(
          "{}: {} frames of {} points make a point cache of {} bytes, more than "
          "--max-output-bytes {} with its base mesh; write fewer frames or raise the limit",
          target_.string(), frames_, points_, total, maxBytes_));
    }
    char header[kPc2HeaderBytes] = "POINTCACHE2";  // 12 bytes with its terminating zero
    const std::int32_t version = 1, points = static_cast<std::int32_t>(points_), samples = frames_;
    const float startFrame = 1, sampleRate = 1;  // frame 1 the first sample, a frame apart
    if (points_ > 0x7fffffff) throw std::invalid_argument("more points than PC2 can count");
    std::memcpy(header + 12, &version, 4);
    std::memcpy(header + 16, &points, 4);
    std::memcpy(header + 20, &startFrame, 4);
    std::memcpy(header + 24, &sampleRate, 4);
    std::memcpy(header + 28, &samples, 4);
    cache_.putBytes(header, sizeof header);
  } else {
    // The frame's OBJ, written nowhere: only its vertices are kept, in the base mesh's order.
    writeObj(scene, "/dev/null", options);
    if (positions_.size() != points_) {
      throw std::invalid_argument(fmt::format(
          "{}: frame {} has {} points and frame 1 had {}: a point cache moves the same points "
          "every frame",
          target_.string(), written_ + 1, positions_.size(), points_));
    }
  }
  for (const glm::vec3& p : positions_) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("a coordinate is not a finite number");
  }
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  cache_.putBytes(positions_.data(), positions_.size() * sizeof(glm::vec3));
  ++written_;
}

void PointCacheWriter::finish() {
  if (written_ != frames_) throw std::logic_error("the point cache is missing frames");
  cache_.commit();
}

}  // namespace hirsute
