// The glTF module (libhirsute-gltf.so): a GltfScene (gltf_scene.h) turned into glTF 2.0 bytes by
// Assimp's exporter (its "gltf2" and "glb2" formats, written into memory with ExportToBlob, never
// into a file: the program writes the bytes through its OutputTarget).
//
// Assimp 5.2's glTF exporter writes no camera (its glTF2Exporter has no ExportCameras); the
// view's camera is added to the JSON it writes: one entry of "cameras" and the property
// "camera" on the node that stands for it (glTF 2.0, sections 5.12 and 5.25).
#include <assimp/scene.h>
#include <fmt/format.h>

#include <algorithm>
#include <assimp/Exporter.hpp>
#include <cmath>
#include <cstring>
#include <memory>
#include <regex>
#include <stdexcept>
#include <string>

#include "hirsute/viewer/export/gltf_scene.h"

namespace hirsute {
namespace {

// The camera's node, named so that no mesh of ours is (theirs are "mesh…").
constexpr char kCameraNode[] = "hirsute.camera";
// The name Assimp gives the file ExportToBlob writes (its AI_BLOBIO_MAGIC), and so the URI its
// JSON gives the buffer.
constexpr char kBlobBufferUri[] = "\"$blobfile.bin\"";

aiString text(const std::string& s) {
  aiString out;
  out.Set(s);
  return out;
}

aiMaterial* material(const GltfMaterial& m) {
  auto out = std::make_unique<aiMaterial>();
  const aiString name = text(m.name);
  out->AddProperty(&name, AI_MATKEY_NAME);
  const aiColor4D base(m.baseColour.r, m.baseColour.g, m.baseColour.b, 1.0f);
  out->AddProperty(&base, 1, AI_MATKEY_BASE_COLOR);
  const aiColor4D diffuse = base;
  out->AddProperty(&diffuse, 1, AI_MATKEY_COLOR_DIFFUSE);
  // The exporter multiplies the base colour's alpha by the opacity and blends below 1.
  const float opacity = std::clamp(m.baseColour.a, 0.0f, 1.0f);
  out->AddProperty(&opacity, 1, AI_MATKEY_OPACITY);
  if (m.emission != glm::vec3(0.0f)) {
    const aiColor3D emission(m.emission.r, m.emission.g, m.emission.b);
    out->AddProperty(&emission, 1, AI_MATKEY_COLOR_EMISSIVE);
  }
  const float metallic = 0.0f;
  out->AddProperty(&metallic, 1, AI_MATKEY_METALLIC_FACTOR);
  return out.release();
}

aiMesh* mesh(const GltfMesh& m) {
  auto out = std::make_unique<aiMesh>();
  out->mName = text(m.name);
  out->mMaterialIndex = static_cast<unsigned>(m.material);
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  const auto count = static_cast<unsigned>(m.positions.size());
  out->mNumVertices = count;
  out->mVertices = new aiVector3D[count];
  for (unsigned i = 0; i < count; ++i)
    out->mVertices[i] = {m.positions[i].x, m.positions[i].y, m.positions[i].z};
  if (m.normals.size() == count) {
    out->mNormals = new aiVector3D[count];
    for (unsigned i = 0; i < count; ++i)
      out->mNormals[i] = {m.normals[i].x, m.normals[i].y, m.normals[i].z};
  }
  const auto faces = static_cast<unsigned>(m.indices.size() / 3);
  out->mNumFaces = faces;
  out->mFaces = new aiFace[faces];
  for (unsigned f = 0; f < faces; ++f) {
    out->mFaces[f].mNumIndices = 3;
    out->mFaces[f].mIndices =
        new unsigned[3]{m.indices[3 * f], m.indices[3 * f + 1], m.indices[3 * f + 2]};
  }
  return out.release();
}

aiNode* node(const std::string& name, aiNode* parent) {
  auto* out = new aiNode(name);
  out->mParent = parent;
  return out;
}

// The camera's node transform: its columns are the camera's right, up and backward axes and its
// location (glTF's camera looks down -Z).
aiMatrix4x4 cameraTransform(const GltfCamera& c) {
  const glm::vec3 back = -glm::normalize(c.forward);
  const glm::vec3 right = glm::normalize(glm::cross(c.up, back));
  const glm::vec3 up = glm::cross(back, right);
  return aiMatrix4x4(right.x, up.x, back.x, c.location.x,  //
                     right.y, up.y, back.y, c.location.y,  //
                     right.z, up.z, back.z, c.location.z,  //
                     0, 0, 0, 1);
}

std::unique_ptr<aiScene> assimpScene(const GltfScene& scene) {
  auto out = std::make_unique<aiScene>();
  out->mRootNode = new aiNode("hirsute");
  // glTF needs a material for each primitive: a scene without one gets the default grey.
  std::vector<GltfMaterial> materials = scene.materials;
  if (materials.empty()) materials.push_back({"default", glm::vec4(0.8f, 0.8f, 0.8f, 1.0f), {}});
  out->mNumMaterials = static_cast<unsigned>(materials.size());
  out->mMaterials = new aiMaterial*[out->mNumMaterials];
  for (unsigned i = 0; i < out->mNumMaterials; ++i) out->mMaterials[i] = material(materials[i]);
  out->mNumMeshes = static_cast<unsigned>(scene.meshes.size());
  out->mMeshes = new aiMesh*[out->mNumMeshes];
  // One node a mesh (glTF's node holds one mesh), and the camera's node after them.
  aiNode* root = out->mRootNode;
  root->mNumChildren = out->mNumMeshes + 1;
  root->mChildren = new aiNode*[root->mNumChildren];
  for (unsigned i = 0; i < out->mNumMeshes; ++i) {
    const GltfMesh& m = scene.meshes[i];
    if (m.material < 0 || static_cast<std::size_t>(m.material) >= materials.size())
      throw std::invalid_argument("a glTF mesh names a material it does not have");
    out->mMeshes[i] = mesh(m);
    aiNode* child = root->mChildren[i] = node(m.name, root);
    child->mNumMeshes = 1;
    child->mMeshes = new unsigned[1]{i};
  }
  aiNode* camera = root->mChildren[out->mNumMeshes] = node(kCameraNode, root);
  camera->mTransformation = cameraTransform(scene.camera);
  return out;
}

std::string number(float value) {
  if (!std::isfinite(value)) throw std::invalid_argument("a camera value is not a finite number");
  return fmt::format("{}", value);
}

std::string cameraJson(const GltfCamera& c) {
  if (c.perspective) {
    return fmt::format(
        R"("cameras":[{{"name":"camera","type":"perspective","perspective":{{"aspectRatio":{},"yfov":{},"znear":{},"zfar":{}}}}}],)",
        number(c.aspect), number(c.fieldOfViewY), number(std::max(c.clipStart, 1e-6f)),
        number(c.clipEnd));
  }
  return fmt::format(
      R"("cameras":[{{"name":"camera","type":"orthographic","orthographic":{{"xmag":{},"ymag":{},"znear":{},"zfar":{}}}}}],)",
      number(c.halfWidth), number(c.halfHeight), number(std::max(c.clipStart, 0.0f)),
      number(c.clipEnd));
}

// Adds the camera to Assimp's JSON: the "cameras" array first in the top object, and the
// property "camera" on the node named kCameraNode.
std::string withCamera(std::string json, const GltfCamera& camera) {
  static const std::regex cameraNode(std::string(R"re("name"\s*:\s*")re") + kCameraNode + "\"");
  std::smatch found;
  if (!std::regex_search(json, found, cameraNode))
    throw std::runtime_error("Assimp's glTF has no node for the camera");
  json.insert(static_cast<std::size_t>(found.position(0) + found.length(0)), ",\"camera\":0");
  const std::size_t top = json.find('{');
  if (top == std::string::npos) throw std::runtime_error("Assimp's glTF is not a JSON object");
  json.insert(top + 1, "\n    " + cameraJson(camera));
  return json;
}

// A URI of a plain file name: RFC 3986's unreserved bytes as they are, the others percent-encoded
// (a space, '%', '#', bytes above 127), so that any file name reads back.
std::string uriOf(const std::string& name) {
  std::string out;
  for (char c : name) {
    const auto byte = static_cast<unsigned char>(c);
    if (std::isalnum(byte) || c == '-' || c == '.' || c == '_' || c == '~') {
      out += c;
    } else {
      out += fmt::format("%{:02X}", byte);
    }
  }
  return out;
}

std::uint32_t readU32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);
  return value;
}

void putU32(std::string& bytes, std::uint32_t value) {
  bytes.append(reinterpret_cast<const char*>(&value), 4);
}

// A GLB (glTF 2.0, section 4.4) with its JSON chunk replaced by `json`, padded with spaces to 4
// bytes as the chunk must be; the binary chunk as it was.
std::string glbWithJson(const std::string& glb, std::string json) {
  if (glb.size() < 20 || glb.compare(0, 4, "glTF") != 0 || glb.compare(16, 4, "JSON") != 0)
    throw std::runtime_error("Assimp's GLB has no JSON chunk at its start");
  const std::uint32_t jsonLength = readU32(glb, 12);
  if (20 + static_cast<std::size_t>(jsonLength) > glb.size())
    throw std::runtime_error("Assimp's GLB is shorter than its JSON chunk");
  const std::string rest = glb.substr(20 + jsonLength);
  json.append((4 - json.size() % 4) % 4, ' ');
  std::string out = "glTF";
  putU32(out, 2);
  putU32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + rest.size()));
  putU32(out, static_cast<std::uint32_t>(json.size()));
  out += "JSON";
  out += json;
  out += rest;
  return out;
}

std::string jsonOfGlb(const std::string& glb) {
  if (glb.size() < 20 || glb.compare(16, 4, "JSON") != 0)
    throw std::runtime_error("Assimp's GLB has no JSON chunk at its start");
  const std::uint32_t length = readU32(glb, 12);
  if (20 + static_cast<std::size_t>(length) > glb.size())
    throw std::runtime_error("Assimp's GLB is shorter than its JSON chunk");
  return glb.substr(20, length);
}

GltfBytes encode(const GltfScene& scene, bool binary, const std::string& bufferName) {
  GltfBytes out;
  try {
    std::unique_ptr<aiScene> assimp = assimpScene(scene);
    Assimp::Exporter exporter;
    const aiExportDataBlob* blob = exporter.ExportToBlob(assimp.get(), binary ? "glb2" : "gltf2");
    if (blob == nullptr) {
      out.error = std::string("Assimp's glTF exporter failed: ") + exporter.GetErrorString();
      return out;
    }
    const std::string bytes(static_cast<const char*>(blob->data), blob->size);
    if (binary) {
      out.file = glbWithJson(bytes, withCamera(jsonOfGlb(bytes), scene.camera));
      return out;
    }
    std::string json = withCamera(bytes, scene.camera);
    // The buffer: the blob after the JSON, named "bin"; the JSON names it as Assimp's blob file.
    if (blob->next != nullptr) {
      out.buffer.assign(static_cast<const char*>(blob->next->data), blob->next->size);
      const std::size_t uri = json.find(kBlobBufferUri);
      if (uri == std::string::npos)
        throw std::runtime_error("Assimp's glTF does not name its buffer as expected");
      json.replace(uri, std::strlen(kBlobBufferUri), "\"" + uriOf(bufferName) + "\"");
    }
    out.file = std::move(json);
  } catch (const std::exception& e) {
    // std::invalid_argument: the scene's fault; the others: Assimp's output not as expected.
    out.error = e.what();
  }
  return out;
}

}  // namespace
}  // namespace hirsute

extern "C" __attribute__((visibility("default"))) const hirsute::GltfFunctions*
hirsuteGltfFunctions() {
  static const hirsute::GltfFunctions functions{&hirsute::encode};
  return &functions;
}
