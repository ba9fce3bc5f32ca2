#include "hirsute/viewer/export/texture_file.h"

#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "hirsute/viewer/export/export_file.h"

// stb's writer compiled into this file alone, with internal linkage, so that another library in
// the same program may include its own copy.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace hirsute {

std::string textureFileName(const std::filesystem::path& target, int index) {
  return target.stem().string() + "_texture" + std::to_string(index + 1) + ".png";
}

void writeTexturePng(const Texture& texture, const OutputFolder& folder, const std::string& name,
                     OutputGroup* group) {
  std::size_t size =
      static_cast<std::size_t>(texture.width) * static_cast<std::size_t>(texture.height) * 4;
  if (texture.width <= 0 || texture.height <= 0 || texture.rgba.size() != size) {
    throw std::invalid_argument(texture.file + ": the texture has no pixels to export");
  }
  int length = 0;
  unsigned char* png = stbi_write_png_to_mem(texture.rgba.data(), texture.width * 4, texture.width,
                                             texture.height, 4, &length);
  if (!png) {
    throw std::runtime_error(folder.pathOf(name).string() + ": cannot encode the texture as PNG");
  }
  std::unique_ptr<unsigned char, void (*)(void*)> owned(png, std::free);
  ExportFile out(folder, name, group);
  out.putBytes(png, static_cast<std::size_t>(length));
  out.commit();
}

}  // namespace hirsute
