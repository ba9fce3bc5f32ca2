// The window's keys and mouse (cpfg-manual §1.3.1, and the keys beyond cpfg), one line a key, as
// the help overlay and `docs/viewer.md` show them. viewer_window.cpp's onKey is their code.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace hirsute {

const std::vector<std::pair<std::string, std::string>>& viewerKeyMap();

}  // namespace hirsute
