// An output file that appears only when complete: written to a temporary file beside the
// target and renamed over it on commit(); removed if never committed.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace hirsute::cli {

class OutputFile {
 public:
  // An empty path or "-" writes to standard output.
  explicit OutputFile(const std::string& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::FILE* stream() const { return stream_; }
  // Flushes, closes and renames into place; returns false (with errno set) on failure.
  bool commit();
  const std::string& target() const { return target_; }

 private:
  std::string target_;
  std::string temporary_;
  std::FILE* stream_ = nullptr;
  bool toStdout_ = false;
  bool committed_ = false;
};

}  // namespace hirsute::cli
