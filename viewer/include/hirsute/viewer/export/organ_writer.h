// An organ's part in the file formats (docs/design.md, "Organs"): printScene() visits the
// organs of organWriters() after the scene's own elements, and each printer hands itself to the
// organ's writer for its format. The writers live in the organs' folders (hairs/NAME/export/) and
// use the printers' public drawing calls; a printer never names an organ.
//
// Adding a format adds a virtual here and a writer in each organ; adding an organ adds a class
// derived from OrganWriter in its folder (its nameWriter(), hairs/organs/organ_list.h), whose
// line in that list gives the order the organs are written in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "hirsute/core/output_target.h"
#include "hirsute/core/progress.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

class PovWriter;
class ObjWriter;
class BlenderWriter;

// A table an organ writes on its own (`hirsute export --NAME FILE`): one row an instance.
struct OrganTable {
  const char* option;  // the export command's option ("--NAME")
  const char* help;    // its help
  // Writes the table of `scene` to `target`, committed with `group`; returns the rows. Throws
  // std::runtime_error when the file cannot be written, std::invalid_argument for a value that
  // is not finite.
  std::uint64_t (*write)(const Scene& scene, const std::filesystem::path& target,
                         Progress* progress, OutputGroup* group);
};

class OrganWriter {
 public:
  virtual ~OrganWriter() = default;

  // The instances of the organ in `scene` that the progress counts; none: the organ is not
  // visited.
  virtual std::size_t items(const Scene& scene) const = 0;
  virtual void writePov(const Scene& scene, PovWriter& pov) const = 0;
  virtual void writeObj(const Scene& scene, ObjWriter& obj) const = 0;
  // The scene file for Blender: the organ's strands as curve groups with a radius and colour at
  // each point, its surfaces as meshes (blender_writer.h).
  virtual void writeBlender(const Scene& scene, BlenderWriter& blender) const = 0;
  // POV-Ray: what the file's first comment says of the organ ("12 hairs"; empty: nothing), and
  // the depth of rays its layers of transparency need (max_trace_level; 0: POV-Ray's default).
  virtual std::string povSummary(const Scene& /*scene*/) const { return {}; }
  virtual int povTraceLevel(const Scene& /*scene*/) const { return 0; }
  // The organ's own table, if it has one.
  virtual std::optional<OrganTable> table() const { return std::nullopt; }
};

// Every organ's writers, in the order they are written (hairs/organs/organ_list.h).
std::span<const OrganWriter* const> organWriters();

}  // namespace hirsute
