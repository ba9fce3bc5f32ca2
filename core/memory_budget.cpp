#include "hirsute/core/memory_budget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <limits>

namespace hirsute {

std::size_t memoryBudgetBytes() {
  std::size_t budget = std::numeric_limits<std::size_t>::max();
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGESIZE);
  if (pages > 0 && pageSize > 0)
    budget = static_cast<std::size_t>(pages) * static_cast<std::size_t>(pageSize);
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit limit{};
    if (getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      budget = std::min(budget, static_cast<std::size_t>(limit.rlim_cur));
  }
  return budget;
}

std::string memorySizeText(double bytes) {
  char text[32];
  if (bytes >= 1e9)
    std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  else
    std::snprintf(text, sizeof text, "%.0f MB", std::max(1.0, bytes / 1e6));
  return text;
}

}  // namespace hirsute
