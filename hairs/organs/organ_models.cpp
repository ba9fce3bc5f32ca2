// The organs' module tables and view-file lines, registered (organ_list.h): what the turtle and
// the view file declare (organ_modules.h, view_lines.h) and find here at link time, so that the
// interpreter names no organ.
#include "hirsute/interpreter/organ_modules.h"
#include "hirsute/interpreter/view_lines.h"
#include "organ_list.h"

namespace hirsute {

#define HIRSUTE_DECLARE(folder, name)          \
  const OrganModuleTable& name##ModuleTable(); \
  std::span<const ViewLineCommand> name##ViewLines();
HIRSUTE_ORGANS(HIRSUTE_DECLARE)
#undef HIRSUTE_DECLARE

std::span<const OrganModuleTable* const> organModuleTables() {
#define HIRSUTE_TABLE(folder, name) &name##ModuleTable(),
  static const OrganModuleTable* const tables[] = {HIRSUTE_ORGANS(HIRSUTE_TABLE)};
#undef HIRSUTE_TABLE
  return tables;
}

std::span<const std::span<const ViewLineCommand>> organViewLines() {
#define HIRSUTE_LINES(folder, name) name##ViewLines(),
  static const std::span<const ViewLineCommand> lines[] = {HIRSUTE_ORGANS(HIRSUTE_LINES)};
#undef HIRSUTE_LINES
  return lines;
}

}  // namespace hirsute
