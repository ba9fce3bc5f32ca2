// Files the user names on the command line (a scan, an environment file, a CCD query file), as
// opposed to the files a model names, which open through its folder (model_folder.h).
//
// The name is the user's own choice, so it may be a link to anywhere; but only a regular file is
// read. A FIFO would block the run until a writer came, and a device such as /dev/zero never
// ends: both are refused at once, with what they are.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <filesystem>
#include <string>

#include "hirsute/core/model_folder.h"

namespace hirsute {

// What kind of file a mode is, for a message: "a FIFO", "a character device", "a folder", ….
std::string fileKindOf(mode_t mode);

// Opens `file` for reading when it is a regular file; otherwise an empty descriptor and
// `failure` set to why, in words that complete "cannot read FILE: " ("it is a FIFO, not a
// regular file", "No such file or directory").
FileDescriptor openInputFile(const std::filesystem::path& file, std::string& failure);

// Reads the whole regular file into `text`; false with `failure` set when it cannot be opened,
// cannot be read, or holds more than maxBytes ("it is larger than N bytes", found before more
// than maxBytes are read).
bool readInputFile(const std::filesystem::path& file, std::string& text, std::string& failure,
                   std::size_t maxBytes);

// Reads what is left of an open file into `text`, as readInputFile does.
bool readDescriptor(int fd, std::string& text, std::string& failure, std::size_t maxBytes);

}  // namespace hirsute
