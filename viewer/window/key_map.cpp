#include "hirsute/viewer/window/key_map.h"

namespace hirsute {

const std::vector<std::pair<std::string, std::string>>& viewerKeyMap() {
  static const std::vector<std::pair<std::string, std::string>> keys = {
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
      {"H", "show / hide hairs"},
      {"E", "show / hide feathers"},
      {"U", "show / hide fur"},
      {"ctrl + left click", "a droplet of water on the fur where the mouse points"},
      {"J", "spray 20 droplets at random on the fur"},
      {"Y", "let the fur dry (wetness fades over 10 s: curls return, clumps open) / stop"},
      {"G", "a gust of wind through the fur"},
      {"D", "start / pause the feathers' dynamics (wind, gravity, collisions; docs/dynamics.md)"},
      {"W", "wireframe on / off"},
      {"S", "save a PNG screenshot (MODEL-N.png in the current folder)"},
      {"C", "show / hide the constants panel"},
      {"F1, ?", "show / hide this help"},
      {"Q, Escape", "quit"},
  };
  return keys;
}

}  // namespace hirsute
