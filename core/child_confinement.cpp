#include "hirsute/core/child_confinement.h"

#include <fcntl.h>
#include <linux/landlock.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdint>

namespace hirsute {
namespace {

#if defined(SYS_landlock_create_ruleset) && defined(LANDLOCK_ACCESS_FS_READ_FILE)
constexpr bool kHaveLandlock = true;

// The file-system accesses of Landlock ABI 1..3 that this process knows and the kernel handles.
std::uint64_t handledAccess(long abi) {
  std::uint64_t access =
      LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_WRITE_FILE | LANDLOCK_ACCESS_FS_READ_FILE |
      LANDLOCK_ACCESS_FS_READ_DIR | LANDLOCK_ACCESS_FS_REMOVE_DIR | LANDLOCK_ACCESS_FS_REMOVE_FILE |
      LANDLOCK_ACCESS_FS_MAKE_CHAR | LANDLOCK_ACCESS_FS_MAKE_DIR | LANDLOCK_ACCESS_FS_MAKE_REG |
      LANDLOCK_ACCESS_FS_MAKE_SOCK | LANDLOCK_ACCESS_FS_MAKE_FIFO | LANDLOCK_ACCESS_FS_MAKE_BLOCK |
      LANDLOCK_ACCESS_FS_MAKE_SYM;
#ifdef LANDLOCK_ACCESS_FS_REFER
  if (abi >= 2) access |= LANDLOCK_ACCESS_FS_REFER;
#endif
#ifdef LANDLOCK_ACCESS_FS_TRUNCATE
  if (abi >= 3) access |= LANDLOCK_ACCESS_FS_TRUNCATE;
#endif
  (void)abi;
  return access;
}

// The accesses Landlock takes on a file that is not a folder (others make a rule invalid).
std::uint64_t fileAccess(std::uint64_t access) {
  std::uint64_t file =
      LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_WRITE_FILE | LANDLOCK_ACCESS_FS_READ_FILE;
#ifdef LANDLOCK_ACCESS_FS_TRUNCATE
  file |= LANDLOCK_ACCESS_FS_TRUNCATE;
#endif
  return access & file;
}

// Allows `access` beneath `path` (or on it, when it is a file); a path that does not exist is
// left out.
bool allowBeneath(int ruleset, const char* path, std::uint64_t access) {
  FileDescriptor where(::open(path, O_PATH | O_CLOEXEC));
  if (!where) return true;
  struct stat status {};
  if (fstat(where.get(), &status) != 0) return false;
  if (!S_ISDIR(status.st_mode)) access = fileAccess(access);
  landlock_path_beneath_attr rule{};
  rule.allowed_access = access;
  rule.parent_fd = where.get();
  return syscall(SYS_landlock_add_rule, ruleset, LANDLOCK_RULE_PATH_BENEATH, &rule, 0) == 0;
}
#else
constexpr bool kHaveLandlock = false;
#endif

}  // namespace

ChildConfinement::ChildConfinement(const std::filesystem::path& folder)
    : ChildConfinement(
          ConfinementRules{{folder.empty() ? std::filesystem::path(".") : folder}, {}, {}, {}}) {}

ChildConfinement::ChildConfinement(const ConfinementRules& rules) {
  if constexpr (!kHaveLandlock) return;
#if defined(SYS_landlock_create_ruleset) && defined(LANDLOCK_ACCESS_FS_READ_FILE)
  const long abi =
      syscall(SYS_landlock_create_ruleset, nullptr, 0, LANDLOCK_CREATE_RULESET_VERSION);
  if (abi < 1) return;
  landlock_ruleset_attr attributes{};
  attributes.handled_access_fs = handledAccess(abi);
  FileDescriptor ruleset(
      static_cast<int>(syscall(SYS_landlock_create_ruleset, &attributes, sizeof attributes, 0)));
  if (!ruleset) return;
  const std::uint64_t read = LANDLOCK_ACCESS_FS_READ_FILE | LANDLOCK_ACCESS_FS_READ_DIR;
  const std::uint64_t run = read | LANDLOCK_ACCESS_FS_EXECUTE;
  // Everything a folder of one's own needs but running programs from it and making devices.
  const std::uint64_t write =
      attributes.handled_access_fs &
      ~(LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_MAKE_CHAR | LANDLOCK_ACCESS_FS_MAKE_BLOCK);
  const std::uint64_t device = fileAccess(attributes.handled_access_fs) &
                               ~static_cast<std::uint64_t>(LANDLOCK_ACCESS_FS_EXECUTE);
  bool made = true;
  for (const std::filesystem::path& path : rules.read)
    made = made && allowBeneath(ruleset.get(), path.c_str(), read);
  for (const std::filesystem::path& path : rules.write)
    made = made && allowBeneath(ruleset.get(), path.c_str(), write);
  for (const std::filesystem::path& path : rules.run)
    made = made && allowBeneath(ruleset.get(), path.c_str(), run);
  for (const std::filesystem::path& path : rules.devices)
    made = made && allowBeneath(ruleset.get(), path.c_str(), device);
  for (const char* system : {"/usr", "/lib", "/lib64", "/lib32", "/bin", "/sbin"})
    made = made && allowBeneath(ruleset.get(), system, run);
  made = made && allowBeneath(ruleset.get(), "/etc/ld.so.cache", LANDLOCK_ACCESS_FS_READ_FILE);
  if (made) ruleset_ = std::move(ruleset);
#endif
}

int ChildConfinement::applyInChild() const noexcept {
  if (!ruleset_) return 0;
#ifdef SYS_landlock_restrict_self
  if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) return -1;
  return syscall(SYS_landlock_restrict_self, ruleset_.get(), 0) == 0 ? 0 : -1;
#else
  return 0;
#endif
}

}  // namespace hirsute
