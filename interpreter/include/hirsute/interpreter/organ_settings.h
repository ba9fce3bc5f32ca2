// An organ's settings from the view file (docs/design.md, "Organs"): what its view-file
// lines (view_lines.h) set and its stage, drawing and writers read. Each organ declares its own
// type, derived from OrganSettingsOf, beside its part (NAME_settings.h); ViewSettings holds
// one of each type asked for and reaches it by type (by_type.h), so that it names no organ.
#pragma once

#include <memory>

#include "hirsute/interpreter/by_type.h"

namespace hirsute {

class OrganSettings {
 public:
  virtual ~OrganSettings() = default;
  virtual std::unique_ptr<OrganSettings> clone() const = 0;
};

// The base of an organ's settings: copied as a value; a default-made one holds the defaults.
template <class Settings>
class OrganSettingsOf : public OrganSettings {
 public:
  std::unique_ptr<OrganSettings> clone() const override {
    return std::make_unique<Settings>(static_cast<const Settings&>(*this));
  }
};

using OrganSettingsSet = ByType<OrganSettings>;

}  // namespace hirsute
