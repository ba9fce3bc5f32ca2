// The organs' writers, registered: one line an organ, in the order the formats write them.
#include "hirsute/hairs/feathers/feather_writer.h"
#include "hirsute/hairs/fur/fur_writer.h"
#include "hirsute/hairs/plant/plant_hair_writer.h"
#include "hirsute/viewer/export/organ_writer.h"

namespace hirsute {

std::span<const OrganWriter* const> organWriters() {
  static const OrganWriter* const writers[] = {
      &plantHairWriter(),
      &featherWriter(),
      &furWriter(),
  };
  return writers;
}

}  // namespace hirsute
