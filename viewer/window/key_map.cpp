#include "hirsute/viewer/window/key_map.h"

#include <span>
#include <stdexcept>
#include <string_view>

#include "hirsute/viewer/interaction/live_organ.h"

namespace hirsute {
namespace {

using KeyLines = std::vector<std::pair<std::string, std::string>>;

// The letters the window keeps for itself (viewer_window.cpp's onKey): no organ may take one.
constexpr std::string_view kWindowLetters = "NPFARWSCMKQ";

// Each organ's lines (live_organ.h): its key, its ctrl + click, its actions' keys.
void addOrganKeys(KeyLines& keys) {
  std::string taken(kWindowLetters);
  auto take = [&taken](char key, std::string_view organ) {
    if (key < 'A' || key > 'Z' || taken.find(key) != std::string::npos) {
      throw std::logic_error("the organ " + std::string(organ) + " takes the key " +
                             std::string(1, key) + ", which is not an upper-case letter or taken");
    }
    taken += key;
  };
  for (const LiveOrganType* organ : liveOrgans()) {
    take(organ->showKey(), organ->name());
    keys.emplace_back(std::string(1, organ->showKey()),
                      "show / hide " + std::string(organ->name()));
    if (!organ->pointHelp().empty()) keys.emplace_back("ctrl + left click", organ->pointHelp());
    for (const LiveAction& action : organ->actions()) {
      if (action.key == 0) continue;
      take(action.key, organ->name());
      keys.emplace_back(std::string(1, action.key), std::string(action.help));
    }
  }
}

KeyLines makeKeyMap() {
  KeyLines keys = {
      {"left drag", "rotate (horizontal: about the vertical axis; vertical: about the horizontal)"},
      {"middle drag, wheel", "zoom (drag up or wheel forward zooms in)"},
      {"right drag, shift + left drag", "pan"},
      {"shift + middle drag", "roll"},
      {"Right, N", "next derivation step"},
      {"Left, P", "previous derivation step"},
      {"Home", "first frame of the animation"},
      {"End", "last frame of the animation (the derivation length)"},
      {"F", "animation step: the next frame of the .a file"},
      {"Space, A", "run / stop the animation"},
      {"R", "reset the view (and fit the plant again)"},
  };
  addOrganKeys(keys);
  const KeyLines after = {
      {"W", "wireframe on / off"},
      {"S", "save a PNG screenshot (MODEL-N.png in the current folder)"},
      {"C", "show / hide the constants panel"},
      {"M", "show / hide the colours and materials editor"},
      {"K", "show / hide the model's control panels (.pnl)"},
      {"F1, ?", "show / hide this help"},
      {"F6, F7, F8", "show / hide the function, contour and surface editors"},
      {"Q, Escape", "quit"},
  };
  keys.insert(keys.end(), after.begin(), after.end());
  return keys;
}

}  // namespace

const std::vector<std::pair<std::string, std::string>>& viewerKeyMap() {
  static const KeyLines keys = makeKeyMap();
  return keys;
}

}  // namespace hirsute
