// The surfaces of a Scene as glTF 2.0 (`hirsute export --gltf`), in two halves: GltfWriter
// (gltf_writer.h) gathers the meshes, their materials and the view's camera into a GltfScene, and
// the glTF module (libhirsute-gltf.so, gltf_assimp.cpp) turns it into the file's bytes through
// Assimp's exporter. The module is loaded on the first glTF written (loadable_module.h), so that
// the program starts without Assimp.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace hirsute {

// Values as glTF holds them: colours in linear light, Y up, metres being whatever the model's
// units are.
struct GltfMaterial {
  std::string name;
  glm::vec4 baseColour{1.0f};  // linear RGB and alpha (1 - the material's transparency)
  glm::vec3 emission{0.0f};    // linear
};

struct GltfMesh {
  std::string name;
  int material = 0;  // index into GltfScene::materials
  // Normals: empty, or one per position. (A Scene's meshes carry no vertex colours: a mesh's
  // colour is its material's.)
  std::vector<glm::vec3> positions, normals;
  std::vector<std::uint32_t> indices;
};

// glTF's camera looks down its node's -Z with +Y up (glTF 2.0, section 5.12): the node's
// transform is built from these.
struct GltfCamera {
  bool perspective = true;
  glm::vec3 location{0.0f}, forward{0.0f, 0.0f, -1.0f}, up{0.0f, 1.0f, 0.0f};
  float fieldOfViewY = 0.8f;            // radians (perspective)
  float halfWidth = 1, halfHeight = 1;  // world units (orthographic)
  float aspect = 4.0f / 3.0f;
  float clipStart = 0.01f, clipEnd = 100.0f;
};

struct GltfScene {
  std::vector<GltfMaterial> materials;
  std::vector<GltfMesh> meshes;
  GltfCamera camera;
};

// What the module returns: the file's bytes and, for the text form (.gltf), the bytes of the
// buffer file the JSON names (`bufferName`, beside it); empty `error` on success.
struct GltfBytes {
  std::string file, buffer;
  std::string error;
};

// The module's function table; its entry point hirsuteGltfFunctions returns it. `binary` writes
// one .glb; else a .gltf whose buffer is the file `bufferName` (a plain name beside it).
struct GltfFunctions {
  GltfBytes (*encode)(const GltfScene& scene, bool binary, const std::string& bufferName);
};

}  // namespace hirsute
