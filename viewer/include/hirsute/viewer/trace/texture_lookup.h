// How the path tracer reads a texture where a ray meets a textured surface: bilinear between the
// four nearest texels, as GL's linear filter magnifies it (OpenGL 4.6 core profile, Sec. 8.14.2:
// texel centres at (i + 1/2) / n, repeating at the edges), on the stored 8-bit values before
// they are made linear, as GL filters an RGBA8 texture. Minified textures need no mipmaps here:
// a pixel's many samples average the texels it covers.
#pragma once

#include <glm/glm.hpp>

#include "hirsute/interpreter/scene.h"

namespace hirsute::trace {

// The colour at (u, v), 0..1 (v = 0 is the image's last row, as Texture::colourAt has it). Black
// for an empty texture.
glm::vec3 bilinearColourAt(const Texture& texture, const glm::vec2& uv);

}  // namespace hirsute::trace
