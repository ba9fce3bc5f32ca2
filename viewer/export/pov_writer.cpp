#include "hirsute/viewer/export/pov_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <stdexcept>

#include "hirsute/viewer/export/texture_file.h"
#include "hirsute/viewer/view/view_lighting.h"

namespace hirsute {
namespace {

// GL's default global ambient light (glLightModel GL_LIGHT_MODEL_AMBIENT), which cpfg leaves as is.
constexpr float kGlobalAmbient = 0.2f;
// The least a diffuse colour component is written with: no eye sees diffuse light this dark, and
// ambient and emission, written as ratios to it, stay finite (writeMaterial).
constexpr float kDarkestPigment = 1e-3f;

// Colours are written for POV-Ray's linear light arithmetic (assumed_gamma 1): a colour from the
// colour map or material file is what the screen shows, so it is decoded from sRGB first, and
// POV-Ray encodes the result again, so that a fully lit surface shows its colour unchanged.
float srgbToLinear(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 srgbToLinear(const glm::vec3& c) {
  return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)};
}

std::string materialName(int material) {
  std::string name(material < 0 ? "Mn" : "M");
  name += std::to_string(material < 0 ? -static_cast<long>(material) : material);
  return name;
}

// Equal at the printed precision: both would be read back as the same number.
bool samePrinted(float a, float b, int decimals) {
  double unit = std::pow(10.0, decimals);
  return std::llround(static_cast<double>(a) * unit) == std::llround(static_cast<double>(b) * unit);
}

bool samePrinted(const glm::vec3& a, const glm::vec3& b, int decimals) {
  return samePrinted(a.x, b.x, decimals) && samePrinted(a.y, b.y, decimals) &&
         samePrinted(a.z, b.z, decimals);
}

// POV-Ray strings and comments take any text but a quote, a backslash or a line break.
std::string commentText(const std::string& text) {
  std::string out;
  for (char c : text) out += (c == '\n' || c == '\r' || c == '"' || c == '\\') ? ' ' : c;
  return out;
}

}  // namespace

PovWriter::PovWriter(std::filesystem::path target, PovOptions options)
    : target_(std::move(target)),
      options_(std::move(options)),
      out_(options_.folder
               ? ExportFile(*options_.folder, target_.filename().string(), options_.group)
               : ExportFile(target_, options_.group)) {}

PovWriter::~PovWriter() = default;

const OutputFolder& PovWriter::sideFolder() {
  if (options_.folder) return *options_.folder;
  if (!sideFolder_) sideFolder_.emplace(target_.parent_path());
  return *sideFolder_;
}

void PovWriter::vector(const glm::vec3& v, NumberFormat format) {
  out_.put('<');
  number(v.x, format);
  out_.put(',');
  number(v.y, format);
  out_.put(',');
  number(v.z, format);
  out_.put('>');
}

void PovWriter::beginScene(const Scene& scene, std::span<const OrganWriter* const> organs) {
  scene_ = &scene;
  Bounds bounds = options_.fitBounds ? *options_.fitBounds : scene.bounds();
  position_.decimals = positionDecimals(bounds);
  camera_ = fitCamera(options_.view, bounds, glm::ivec2(options_.width, options_.height));
  float pixels = static_cast<float>(camera_.viewport.y);
  worldPerPixel_ = camera_.projection == Projection::Perspective
                       ? 2 * glm::distance(camera_.eye, camera_.target) *
                             std::tan(glm::radians(camera_.fieldOfViewY) / 2) / pixels
                       : 2 * camera_.halfHeight / pixels;
  writeHeader(scene, organs);
  writeCamera();
  writeLights(bounds);
}

// Materials are declared where first used, so that only those the scene uses are written and
// an instance placed later (declareMesh / placeObject) may bring its own.
const std::string& PovWriter::useTexture(int material, int texture) {
  if (material == lastMaterial_ && texture == lastTexture_) return lastName_;
  std::string name = textureName(material, texture);
  if (declaredTextures_.insert({material, texture}).second) {
    writeMaterial(name, material, materialOrDefault(*scene_, material), texture);
  }
  lastMaterial_ = material;
  lastTexture_ = texture;
  lastName_ = std::move(name);
  return lastName_;
}

// Consecutive primitives of one material share one texture statement: `union{…texture{M1}}`
// is a seventh shorter than a texture in every cylinder, and parses faster. POV-Ray splits the
// union into its members for its bounding hierarchy (split_union is on), so it renders the same.
// POV-Ray warns about a union of one member, so a run's first primitive waits for the second.
void PovWriter::emit(int material, const Primitive& primitive) {
  if (runLength_ > 0 && runMaterial_ == material) {
    if (runLength_ == 1) {
      out_.put("union{");
      writePrimitive(pending_, nullptr);
    }
    writePrimitive(primitive, nullptr);
    ++runLength_;
    return;
  }
  closeRun();
  useTexture(material, -1);  // declared before the run
  pending_ = primitive;
  runMaterial_ = material;
  runLength_ = 1;
}

void PovWriter::closeRun() {
  if (runLength_ == 0) return;
  const std::string& texture = useTexture(runMaterial_, -1);
  if (runLength_ == 1) {
    writePrimitive(pending_, &texture);
  } else {
    out_.put("texture{");
    out_.put(texture);
    out_.put("}}\n");
  }
  runLength_ = 0;
}

void PovWriter::writePrimitive(const Primitive& p, const std::string* texture) {
  switch (p.kind) {
    case Primitive::Cylinder:
      out_.put("cylinder{");
      vector(p.a, position_);
      out_.put(',');
      vector(p.b, position_);
      out_.put(',');
      number(p.radiusA, position_);
      break;
    case Primitive::Cone:
      out_.put("cone{");
      vector(p.a, position_);
      out_.put(',');
      number(p.radiusA, position_);
      out_.put(',');
      vector(p.b, position_);
      out_.put(',');
      number(p.radiusB, position_);
      break;
    case Primitive::Sphere:
      out_.put("sphere{");
      vector(p.a, position_);
      out_.put(',');
      number(p.radiusA, position_);
      break;
    case Primitive::Disc:
      out_.put("disc{");
      vector(p.a, position_);
      out_.put(',');
      vector(p.b, normal_);
      out_.put(',');
      number(p.radiusA, position_);
      break;
  }
  if (texture) {
    out_.put(" texture{");
    out_.put(*texture);
    out_.put('}');
  }
  out_.put("}\n");
}

void PovWriter::writeHeader(const Scene& scene, std::span<const OrganWriter* const> organs) {
  std::string file = target_.filename().string();
  std::string image = target_.stem().string() + ".png";
  out_.put("// Hirsute: a POV-Ray 3.7 scene of ");
  out_.putInteger(static_cast<std::int64_t>(scene.triangleCount()));
  out_.put(" triangles and ");
  out_.putInteger(static_cast<std::int64_t>(scene.lines.size()));
  out_.put(" line segments");
  int traceLevel = 0;
  for (const OrganWriter* organ : organs) {
    if (organ->items(scene) == 0) continue;
    const std::string summary = organ->povSummary(scene);
    if (!summary.empty()) {
      out_.put(", ");
      out_.put(summary);
    }
    traceLevel = std::max(traceLevel, organ->povTraceLevel(scene));
  }
  out_.put(" (docs/export.md).\n// Render: povray +I");
  out_.put(file);
  out_.put(" +O");
  out_.put(image);
  out_.put(" +W");
  out_.putInteger(options_.width);
  out_.put(" +H");
  out_.putInteger(options_.height);
  out_.put(" +A0.3 -D\n#version 3.7;\n");

  // GL adds each light's ambient times the material's ambient colour; POV-Ray has one ambient
  // light, their sum (attenuation of point lights aside).
  glm::vec3 ambient(kGlobalAmbient);
  for (const LightSource& light :
       exportedLights(options_.view, options_.materialMode, -camera_.forward))
    ambient += light.ambient;
  if (options_.traceLights) {
    // The tracer's sky lights the plant through radiosity, and there is no ambient term.
    ambient = glm::vec3(0.0f);
  }
  out_.put("global_settings{assumed_gamma 1 ambient_light rgb");
  vector(ambient, colour_);
  if (options_.traceLights) {
    out_.put(
        " radiosity{pretrace_start 0.08 pretrace_end 0.04 count 35 nearest_count 5 "
        "error_bound 1.8 recursion_limit 2 low_error_factor 0.5 gray_threshold 0 "
        "brightness 1 adc_bailout 0.005 normal on}");
  }
  if (traceLevel > 0) {
    out_.put(" max_trace_level ");
    out_.putInteger(traceLevel);
  }
  out_.put("}\n");
  // cpfg takes the background from entry 0 of the palette: the colour of a colour map, the
  // emission of a material file.
  glm::vec3 background(0.0f);
  if (!scene.materials.empty()) {
    background =
        options_.materialMode ? scene.materials.front().emission : scene.materials.front().diffuse;
  }
  out_.put("background{rgb");
  vector(srgbToLinear(background), NumberFormat{5, false});
  out_.put("}\n");
}

// POV-Ray warns unless its camera vectors are perpendicular to 1e-10, more than printed numbers
// keep; so it is given the eye, the sky (the screen's up) and look_at, and builds the frame
// itself. Its default frame is left-handed: right = -x makes it right-handed, as GL's is.
void PovWriter::writeCamera() {
  const Camera& c = camera_;
  NumberFormat unit{6, false};
  out_.put("#declare Aspect=image_width/image_height;\n");
  if (c.projection == Projection::Perspective) {
    // An image plane of height 1 at the distance that gives the vertical viewing angle.
    float focalLength = 0.5f / std::tan(glm::radians(c.fieldOfViewY) / 2);
    out_.put("camera{perspective location");
    vector(c.eye, position_);
    out_.put(" direction z*");
    number(focalLength, unit);
    out_.put(" right -x*Aspect up y sky");
    vector(c.up, unit);
    out_.put(" look_at");
    vector(c.target, position_);
    out_.put("}\n");
    return;
  }
  // Orthographic rays start on the plane through the location: there, at the near clipping
  // plane, as in GL. At another aspect than the fitted one, the window grows to hold the fitted
  // window, as cpfg's does when its window is resized.
  glm::vec3 location = c.eye + c.forward * c.nearPlane;
  out_.put("#declare ViewHeight=max(");
  number(2 * c.halfHeight, position_);
  out_.put(',');
  number(2 * c.halfWidth, position_);
  out_.put("/Aspect);\ncamera{orthographic location");
  vector(location, position_);
  out_.put(" right -x*ViewHeight*Aspect up y*ViewHeight sky");
  vector(c.up, unit);
  out_.put(" look_at");
  vector(location + c.forward * std::max(c.farPlane - c.nearPlane, 1e-3f), position_);
  out_.put("}\n");
}

// The tracer's spherical light as a circular area light of its size where it stands, its
// colour the irradiance over π (POV-Ray's diffuse finish is ρ E cos θ, without Lambert's 1/π);
// the sky as a dome about the plant, emitting the sky's radiance over the hemisphere about
// `trace up:` and nothing below, which only radiosity sees (no_image) and which casts no
// shadow. A white surface facing the light, or the sky, then looks as it does in the tracer.
void PovWriter::writeTraceLights(const Bounds& bounds) {
  const TraceSettings& look = options_.view.trace;
  const ViewLighting lighting =
      viewLighting(options_.view, options_.materialMode, -camera_.forward);
  const SphereLight light =
      sphereLight(look, bounds, traceLightFallback(lighting, bounds, -camera_.forward));
  NumberFormat format{5, false};
  if (light.present) {
    // `orient` turns the light's disc to face each point it lights; its two axes only have to
    // be of one length, which printed numbers keep exactly along x and z.
    const glm::vec3 a(2 * light.radius, 0, 0), b(0, 0, 2 * light.radius);
    out_.put("light_source{");
    vector(light.centre, position_);
    out_.put(" rgb");
    vector(look.lightIrradiance / 3.14159265f, format);  // E / π
    out_.put(" area_light");
    vector(a, position_);
    out_.put(',');
    vector(b, position_);
    out_.put(",5,5 adaptive 1 jitter circular orient}\n");
  }
  const glm::vec3 sky = srgbToLinear(look.sky);
  if (sky != glm::vec3(0.0f)) {
    const glm::vec3 up = glm::length(look.up) > 0 ? glm::normalize(look.up) : glm::vec3(0, 1, 0);
    const float radius = 100 * std::max(bounds.diagonal(), 1e-3f);
    out_.put("sphere{0,");
    number(radius, position_);
    out_.put(" hollow no_image no_shadow texture{pigment{function{select(x*");
    number(up.x, format);
    out_.put("+y*");
    number(up.y, format);
    out_.put("+z*");
    number(up.z, format);
    out_.put(",0,1)} colour_map{[0 rgb 0][1 rgb");
    vector(sky, format);
    out_.put("]}} finish{emission 1 diffuse 0 ambient 0}} translate");
    vector(bounds.empty() ? glm::vec3(0.0f) : bounds.center(), position_);
    out_.put("}\n");
  }
}

void PovWriter::writeLights(const Bounds& bounds) {
  if (options_.traceLights) {
    writeTraceLights(bounds);
    return;
  }
  std::vector<LightSource> lights =
      exportedLights(options_.view, options_.materialMode, -camera_.forward);
  glm::vec3 centre = bounds.empty() ? options_.view.viewReference : bounds.center();
  float far = 10 * std::max(bounds.diagonal(), 1.0f);
  for (const LightSource& light : lights) {
    if (light.diffuse == glm::vec3(0.0f)) continue;  // it only adds ambient light (above)
    out_.put("light_source{");
    if (light.directional) {
      glm::vec3 towards =
          glm::length(light.vector) > 0 ? glm::normalize(light.vector) : glm::vec3(0, 0, 1);
      vector(centre + towards * far, position_);
      out_.put(" rgb");
      vector(srgbToLinear(light.diffuse), colour_);
      out_.put(" parallel point_at");
      vector(centre, position_);
    } else {
      vector(light.vector, position_);
      out_.put(" rgb");
      vector(srgbToLinear(light.diffuse), colour_);
      if (light.spot && light.spotCutoff < 90) {
        // GL's spot: (cos angle)^exponent inside the cutoff cone, nothing outside.
        float cutoff = std::max(light.spotCutoff, 0.0f);
        out_.put(" spotlight radius ");
        number(cutoff, colour_);
        out_.put(" falloff ");
        number(cutoff, colour_);
        out_.put(" tightness ");
        number(std::clamp(light.spotExponent, 0.0f, 100.0f), colour_);
        out_.put(" point_at");
        glm::vec3 aim = glm::length(light.spotDirection) > 0 ? glm::normalize(light.spotDirection)
                                                             : glm::vec3(0, 0, -1);
        vector(light.vector + aim, position_);
      }
    }
    out_.put("}\n");
  }
}

std::string PovWriter::textureName(int material, int texture) const {
  std::string name = materialName(material);
  if (texture >= 0) {
    name += 'T';
    name += std::to_string(texture + 1);
  }
  return name;
}

// GL's lighting (cpfg's material mode) in POV-Ray's terms. POV-Ray multiplies ambient and emission
// by the pigment, so they are written as ratios to the diffuse colour, which is kept above a
// floor (invisible as diffuse light) so that a black diffuse colour can still glow.
void PovWriter::writeMaterial(std::string_view name, int index, const Material& material,
                              int texture) {
  glm::vec3 diffuse = glm::max(srgbToLinear(material.diffuse), glm::vec3(kDarkestPigment));
  glm::vec3 ambient = srgbToLinear(material.ambient) / diffuse;
  glm::vec3 emission = srgbToLinear(material.emission) / diffuse;
  NumberFormat format{4, false};
  out_.put("#declare ");
  out_.put(name);
  out_.put("=texture{");
  // A scene written to a device or FIFO has no folder for its images: drawn untextured.
  if (texture >= 0 && !out_.writesInPlace()) {
    // The image replaces the diffuse colour (cpfg's textures are usually on white surfaces).
    std::string file = textureFileName(target_, texture);
    if (std::find(texturesWritten_.begin(), texturesWritten_.end(), texture) ==
        texturesWritten_.end()) {
      writeTexturePng(scene_->textures.at(static_cast<std::size_t>(texture)), sideFolder(), file,
                      options_.group);
      texturesWritten_.push_back(texture);
    }
    out_.put("uv_mapping pigment{image_map{png \"");
    out_.put(file);
    out_.put("\" interpolate 2");
    if (material.transparency > 0) {
      out_.put(" transmit all ");
      number(std::clamp(material.transparency, 0.0f, 1.0f), format);
    }
    out_.put("}}");
    ambient = srgbToLinear(material.ambient);
    emission = srgbToLinear(material.emission);
  } else if (material.transparency > 0) {
    out_.put("pigment{rgbt<");
    number(diffuse.x, format);
    out_.put(',');
    number(diffuse.y, format);
    out_.put(',');
    number(diffuse.z, format);
    out_.put(',');
    number(std::clamp(material.transparency, 0.0f, 1.0f), format);
    out_.put(">}");
  } else {
    out_.put("pigment{rgb");
    vector(diffuse, format);
    out_.put('}');
  }
  out_.put("finish{ambient rgb");
  vector(ambient, format);
  // With the tracer's lights, a translucent colour passes its share to the side away from the
  // light (backside diffuse) and reflects the rest, as the tracer's surfaces do.
  float through = 0;
  if (options_.traceLights) {
    for (const auto& [colour, share] : options_.view.trace.translucent) {
      if (colour == index) through = std::clamp(share, 0.0f, 1.0f);
    }
  }
  if (through > 0) {
    out_.put(" diffuse ");
    number(1 - through, format);
    out_.put(',');
    number(through, format);
  } else {
    out_.put(" diffuse 1");
  }
  float specular = std::max({material.specular.x, material.specular.y, material.specular.z});
  if (specular > 0) {
    // GL's Blinn-Phong exponent n corresponds to POV-Ray's roughness 1/n.
    out_.put(" specular ");
    number(std::min(specular, 1.0f), format);
    out_.put(" roughness ");
    number(std::clamp(1.0f / std::max(material.shininess, 1.0f), 0.0005f, 1.0f), format);
  }
  if (emission != glm::vec3(0.0f)) {
    out_.put(" emission rgb");
    vector(emission, format);
  }
  out_.put("}}\n");
}

std::string PovWriter::declareMesh(const TriangleMesh& mesh) {
  std::size_t vertexCount = mesh.positions.size();
  std::size_t triangles = mesh.triangleCount();
  if (triangles == 0 || vertexCount == 0)
    throw std::invalid_argument("a mesh without triangles cannot be declared");
  for (std::uint32_t index : mesh.indices) {
    if (index >= vertexCount)
      throw std::invalid_argument("a mesh's triangle refers to a vertex it does not have");
  }
  closeRun();
  std::string name("Mesh");
  name += std::to_string(meshesDeclared_++);
  writeMesh2(name, mesh);
  return name;
}

void PovWriter::writeMesh2(std::string_view name, const TriangleMesh& mesh) {
  std::size_t vertexCount = mesh.positions.size();
  std::size_t triangles = mesh.triangleCount();
  out_.put("#declare ");
  out_.put(name);
  out_.put("=mesh2{vertex_vectors{");
  out_.putInteger(static_cast<std::int64_t>(vertexCount));
  out_.put(',');
  for (std::size_t i = 0; i < vertexCount; ++i) {
    if (i % 4 == 0) out_.put('\n');
    vector(mesh.positions[i], position_);
  }
  out_.put('}');

  if (mesh.normals.size() == vertexCount) {
    VertexNormals normals(mesh);  // POV-Ray rejects a zero normal
    out_.put("\nnormal_vectors{");
    out_.putInteger(static_cast<std::int64_t>(vertexCount));
    out_.put(',');
    for (std::size_t i = 0; i < vertexCount; ++i) {
      if (i % 4 == 0) out_.put('\n');
      vector(normals[i], normal_);
    }
    out_.put('}');
  }

  if (drawnTextured(*scene_, mesh)) {
    // t = 0 is the image's bottom row, in image_map as in the GL renderer.
    out_.put("\nuv_vectors{");
    out_.putInteger(static_cast<std::int64_t>(vertexCount));
    out_.put(',');
    for (std::size_t i = 0; i < vertexCount; ++i) {
      if (i % 4 == 0) out_.put('\n');
      out_.put('<');
      number(mesh.texcoords[i].x, texcoord_);
      out_.put(',');
      number(mesh.texcoords[i].y, texcoord_);
      out_.put('>');
    }
    out_.put('}');
  }

  out_.put("\nface_indices{");
  out_.putInteger(static_cast<std::int64_t>(triangles));
  out_.put(',');
  for (std::size_t t = 0; t < triangles; ++t) {
    if (t % 4 == 0) out_.put('\n');
    out_.put('<');
    out_.putInteger(mesh.indices[3 * t]);
    out_.put(',');
    out_.putInteger(mesh.indices[3 * t + 1]);
    out_.put(',');
    out_.putInteger(mesh.indices[3 * t + 2]);
    out_.put('>');
  }
  out_.put("}}\n");
  stats_.triangles += triangles;
}

void PovWriter::placeObject(std::string_view name, int material, int textureIndex,
                            const glm::mat4* transform) {
  closeRun();
  const std::string& texture = useTexture(material, textureIndex);
  out_.put("object{");
  out_.put(name);
  out_.put(" texture{");
  out_.put(texture);
  out_.put('}');
  if (transform) {
    // POV-Ray's matrix is row-vector: its rows are the images of x, y, z and the translation,
    // which are glm's columns.
    const glm::mat4& m = *transform;
    out_.put(" matrix<");
    for (int column = 0; column < 4; ++column) {
      for (int row = 0; row < 3; ++row) {
        if (column + row > 0) out_.put(',');
        number(m[column][row], column == 3 ? position_ : NumberFormat{6, false});
      }
    }
    out_.put('>');
  }
  out_.put("}\n");
  ++stats_.objects;
}

void PovWriter::mesh(const TriangleMesh& mesh) {
  std::string name = declareMesh(mesh);
  placeObject(name, shownMaterial(mesh.material, true),
              drawnTextured(*scene_, mesh) ? mesh.texture : -1);
}

int PovWriter::shownMaterial(int material, bool lit) const {
  if (!lit) return material;
  return litPaletteEntry(
      material, litPaletteOffset(options_.view, options_.materialMode, options_.colorMapFile),
      static_cast<int>(scene_->materials.size()));
}

void PovWriter::line(const LineSegment& line, LineStyle style) {
  // Pixel widths are drawn as the width in world units that a pixel spans at the fitted image
  // size, at the view reference point; polygon and cylinder widths are world units already.
  float toWorld = style == LineStyle::Pixel ? worldPerPixel_ : 1.0f;
  float radiusFrom = std::max(line.widthFrom, 0.0f) * toWorld / 2;
  float radiusTo = std::max(line.widthTo, 0.0f) * toWorld / 2;
  int decimals = position_.decimals;
  if (samePrinted(line.from, line.to, decimals) ||
      (samePrinted(radiusFrom, 0, decimals) && samePrinted(radiusTo, 0, decimals))) {
    ++stats_.linesSkipped;
    return;
  }
  if (samePrinted(radiusFrom, radiusTo, decimals)) {
    emit(line.material, {Primitive::Cylinder, line.from, line.to, radiusFrom, radiusFrom});
    ++stats_.cylinders;
  } else {
    emit(line.material, {Primitive::Cone, line.from, line.to, radiusFrom, radiusTo});
    ++stats_.cones;
  }
}

void PovWriter::sphere(const Sphere& sphere) {
  if (samePrinted(sphere.radius, 0, position_.decimals) || sphere.radius < 0) return;
  emit(shownMaterial(sphere.material, true),
       {Primitive::Sphere, sphere.center, glm::vec3(0.0f), sphere.radius, 0});
  ++stats_.spheres;
}

void PovWriter::disc(const Disc& disc) {
  if (samePrinted(disc.radius, 0, position_.decimals) || disc.radius < 0) return;
  // A screen-aligned disc (cpfg's @o) faces the camera.
  glm::vec3 normal = glm::length(disc.normal) > 0 ? glm::normalize(disc.normal) : -camera_.forward;
  emit(shownMaterial(disc.material, true), {Primitive::Disc, disc.center, normal, disc.radius, 0});
  ++stats_.discs;
}

void PovWriter::label(const Label& label) {
  closeRun();
  // POV-Ray draws text only from a TrueType font file, and none can be relied on to be
  // installed; the label is kept as a comment where it stood.
  out_.put("// label \"");
  out_.put(commentText(label.text));
  out_.put("\" at ");
  vector(label.position, position_);
  out_.put('\n');
}

void PovWriter::endScene() {
  closeRun();
  out_.commit();
  stats_.bytes = out_.bytesWritten();
}

void PovWriter::organ(const OrganWriter& organ, const Scene& scene) {
  closeRun();
  organ.writePov(scene, *this);
}

void PovWriter::count(std::string_view what, std::size_t count, std::size_t triangles) {
  const auto found = stats_.organs.find(what);
  if (found != stats_.organs.end()) {
    found->second += count;
  } else {
    stats_.organs.emplace(std::string(what), count);
  }
  stats_.triangles += triangles;
}

PovWriter::Shade PovWriter::shadeOf(const glm::vec3& c, float alpha) {
  auto q = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)); };
  return {q(c.r), q(c.g), q(c.b),
          static_cast<int>(std::lround(std::clamp(alpha, 0.0f, 1.0f) * kShadeAlphaLevels))};
}

void PovWriter::writeShadedMesh(std::string_view comment, const std::vector<glm::vec3>& points,
                                const std::vector<Shade>& shades,
                                const std::vector<std::uint32_t>& faces, std::string_view finish,
                                std::string_view declaredName) {
  std::map<Shade, int> textureOf;
  for (const Shade& s : shades) textureOf.emplace(s, 0);
  int n = 0;
  for (auto& [shade, index] : textureOf) index = n++;
  out_.put("\n// ");
  out_.put(comment);
  if (!declaredName.empty()) {
    out_.put("\n#declare ");
    out_.put(declaredName);
    out_.put("=mesh2{\nvertex_vectors{");
  } else {
    out_.put("\nmesh2{\nvertex_vectors{");
  }
  out_.putInteger(static_cast<std::int64_t>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    out_.put(i % 4 == 0 ? ",\n" : ",");
    vector(points[i], position_);
  }
  out_.put("}\ntexture_list{");
  out_.putInteger(n);
  for (const auto& [shade, index] : textureOf) {
    // A shade is a display colour, as GL shows it (the fur's Kajiya-Kay colour, a barb's type
    // colour): decoded to linear light like every other colour of the scene (srgbToLinear).
    // Four decimals, as for materials: a step of one display level near black is 0.0003.
    const glm::vec3 linear = srgbToLinear(glm::vec3(shade.r, shade.g, shade.b) / 255.0f);
    const NumberFormat format{4, false};
    out_.put(",\ntexture{pigment{rgbt<");
    number(linear.r, format);
    out_.put(',');
    number(linear.g, format);
    out_.put(',');
    number(linear.b, format);
    out_.put(',');
    number(1.0 - static_cast<double>(shade.a) / kShadeAlphaLevels, colour_);
    out_.put(">}finish{");
    out_.put(finish);
    out_.put("}}");
  }
  out_.put("}\nface_indices{");
  out_.putInteger(static_cast<std::int64_t>(faces.size() / 3));
  for (std::size_t t = 0; t + 2 < faces.size(); t += 3) {
    out_.put(t % 12 == 0 ? ",\n<" : ",<");
    for (int c = 0; c < 3; ++c) {
      if (c > 0) out_.put(',');
      out_.putInteger(faces[t + static_cast<std::size_t>(c)]);
    }
    out_.put('>');
    for (int c = 0; c < 3; ++c) {
      out_.put(',');
      out_.putInteger(textureOf[shades[faces[t + static_cast<std::size_t>(c)]]]);
    }
  }
  out_.put("}\n}\n");
  stats_.triangles += faces.size() / 3;
}

}  // namespace hirsute
