// `render --trace --denoise`: the traced picture filtered by non-local means, guided by each
// pixel's own noise and by what its camera rays saw first (docs/trace.md, "Denoising").
//
// A pixel becomes a weighted mean of the pixels in a square window about it. Two pixels are
// alike when their neighbourhoods (patches) differ by no more than their noise explains
// (non-local means with the variance of each pixel's mean, after Rousselle, Knaus and Zwicker
// 2012), and when their first hits' colour and direction differ by no more than those features'
// own noise explains (the feature weights of Rousselle, Manzi and Zwicker 2013); a pair's
// weight is the smaller of the two. A pixel whose samples all agree, among neighbours whose
// samples agree too (the background), has no noise and keeps its value; among noisy neighbours
// (a hole in a sparse fuzz, every sample having missed its hairs) it counts as noisy as they are,
// and is filtered with them; and one whose neighbours differ by more than
// noise (an edge, a hair standing against the sky) keeps its own.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace hirsute::trace {

// One picture's per-pixel means and the variances of those means (the samples' variance over
// their count), each width × height, row 0 at the top.
struct NoisyImage {
  int width = 0, height = 0;
  std::vector<glm::vec3> colour, colourVariance;  // linear radiance
  std::vector<glm::vec3> albedo, albedoVariance;  // the colour of the first surface or hair hit
  std::vector<glm::vec3> normal, normalVariance;  // its facing normal (a hair: its tangent)
};

struct DenoiseOptions {
  int window = 7;            // pixels searched either side: a (2·window + 1)² square
  int patch = 3;             // a patch's pixels either side of its centre
  float colourScale = 0.45f;   // k of the colour distance: larger filters more
  float featureScale = 0.6f;   // k of the feature distances
  int threads = 0;           // 0: one a core
};

// The picture filtered as above: a colour a pixel, in the order of `image.colour`.
std::vector<glm::vec3> denoise(const NoisyImage& image, const DenoiseOptions& options = {});

}  // namespace hirsute::trace
