#include "hirsute/viewer/interaction/file_watcher.h"

#include <algorithm>
#include <string>

namespace hirsute {
namespace {

std::filesystem::path normal(const std::filesystem::path& p) {
  std::error_code ec;
  std::filesystem::path absolute = std::filesystem::absolute(p, ec);
  return (ec ? p : absolute).lexically_normal();
}

}  // namespace

bool FileWatcher::isModelFile(const std::filesystem::path& file) {
  static const std::set<std::string> kExtensions = {
      ".l",   ".v", ".a",   ".map", ".mat", ".con",  ".s",      ".func", ".fset", ".crv", ".inc",
      ".pnl", ".h", ".txt", ".dat", ".e",   ".cset", ".csetng", ".srf",  ".bsp",  ".tga", ".rgb"};
  std::string name = file.filename().string();
  if (name.empty() || name[0] == '.') return false;
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return kExtensions.count(extension) > 0;
}

FileWatcher::FileWatcher(std::vector<std::filesystem::path> files,
                         std::vector<std::filesystem::path> folders) {
  for (auto& f : files) files_.push_back(normal(f));
  for (auto& f : folders) {
    std::filesystem::path n = normal(f.empty() ? std::filesystem::path(".") : f);
    if (std::find(folders_.begin(), folders_.end(), n) == folders_.end()) folders_.push_back(n);
  }
  stamps_ = scan();
}

void FileWatcher::watch(const std::filesystem::path& file) {
  const std::filesystem::path n = normal(file);
  if (std::find(files_.begin(), files_.end(), n) != files_.end()) return;
  files_.push_back(n);
  // Only the new file's stamp is taken now: a change elsewhere still waiting stays one.
  std::error_code ec;
  Stamp s;
  s.time = std::filesystem::last_write_time(n, ec);
  if (ec) return;
  s.size = std::filesystem::file_size(n, ec);
  if (!ec && !ignored_.count(n)) stamps_[n] = s;
}

void FileWatcher::ignore(const std::filesystem::path& file) {
  const std::filesystem::path n = normal(file);
  ignored_.insert(n);
  // Only the ignored file leaves the stamps: a model file edited while a screenshot is written
  // is still a change.
  stamps_.erase(n);
}

void FileWatcher::acknowledge(const std::filesystem::path& file) {
  const std::filesystem::path n = normal(file);
  std::error_code ec;
  Stamp s;
  s.time = std::filesystem::last_write_time(n, ec);
  if (!ec) s.size = std::filesystem::file_size(n, ec);
  if (!ec && !ignored_.count(n)) stamps_[n] = s;
}

std::map<std::filesystem::path, FileWatcher::Stamp> FileWatcher::scan() const {
  std::map<std::filesystem::path, Stamp> stamps;
  auto add = [&](const std::filesystem::path& p) {
    if (ignored_.count(p)) return;
    std::error_code ec;
    Stamp s;
    s.time = std::filesystem::last_write_time(p, ec);
    if (ec) return;  // absent: a missing file shows as a change when it comes or goes
    s.size = std::filesystem::file_size(p, ec);
    if (ec) return;
    stamps[p] = s;
  };
  for (const auto& f : files_) add(f);
  for (const auto& folder : folders_) {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
      std::error_code typeError;
      if (entry.is_regular_file(typeError) && isModelFile(entry.path())) add(normal(entry.path()));
    }
  }
  return stamps;
}

bool FileWatcher::poll(Clock::time_point now) {
  auto current = scan();
  if (current != stamps_) {
    stamps_ = std::move(current);
    lastChange_ = now;
    return false;
  }
  if (lastChange_ && now - *lastChange_ >= kSettle) {
    lastChange_.reset();
    return true;
  }
  return false;
}

std::vector<std::filesystem::path> FileWatcher::watched() const {
  std::vector<std::filesystem::path> out;
  for (const auto& [path, stamp] : stamps_) out.push_back(path);
  return out;
}

}  // namespace hirsute
