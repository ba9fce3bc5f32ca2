// The window's keys and mouse (cpfg-manual §1.3.1, and the keys beyond cpfg), one line a key, as
// the help overlay and `docs/viewer.md` show them: the window's own (viewer_window.cpp's onKey)
// and each organ's (live_organ.h). Throws std::logic_error when an organ takes a key already
// taken.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace hirsute {

const std::vector<std::pair<std::string, std::string>>& viewerKeyMap();

}  // namespace hirsute
