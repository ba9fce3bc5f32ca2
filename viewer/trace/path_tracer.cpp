#include "hirsute/viewer/trace/path_tracer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hirsute/viewer/trace/denoise.h"
#include "hirsute/viewer/trace/hair_bsdf.h"
#include "hirsute/viewer/trace/subsurface.h"
#include "hirsute/viewer/trace/surface_bsdf.h"
#include "hirsute/viewer/trace/texture_lookup.h"
#include "hirsute/viewer/view/view_lighting.h"

namespace hirsute::trace {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kMaxPassThroughs = 64;  // transparent layers a ray crosses before it stops

// An intersection context that skips the shape a ray leaves, so that a ray from a hair or a
// triangle does not find it again at a distance of rounding error.
void skipTheShapeLeft(const RTCFilterFunctionNArguments* args);

struct LeavingContext {
  RTCIntersectContext base;
  unsigned geometry, primitive;

  LeavingContext(unsigned leftGeometry, unsigned leftPrimitive)
      : geometry(leftGeometry), primitive(leftPrimitive) {
    rtcInitIntersectContext(&base);
    base.filter = &skipTheShapeLeft;
  }
};

void skipTheShapeLeft(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const LeavingContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    if (RTCHitN_geomID(args->hit, args->N, i) == context->geometry &&
        RTCHitN_primID(args->hit, args->N, i) == context->primitive) {
      args->valid[i] = 0;
    }
  }
}

// The context of a shadow ray through partly transparent shapes: every shape the ray meets
// before `far` is reported to the filter, which multiplies the light let through by its
// transparency and lets the ray go on, in one traversal rather than one a layer. The order of
// the factors does not matter; a shape met twice (a round curve's two walls) counts once.
struct ShadowContext {
  RTCIntersectContext base;
  unsigned leftGeometry, leftPrimitive;
  const void* tracer;
  float through = 1;
  static constexpr int kRemembered = 8;
  unsigned seenGeometry[kRemembered], seenPrimitive[kRemembered];
  int seen = 0;

  bool counted(unsigned geometry, unsigned primitive) {
    const int count = std::min(seen, kRemembered);
    for (int k = 0; k < count; ++k) {
      if (seenGeometry[k] == geometry && seenPrimitive[k] == primitive) return true;
    }
    seenGeometry[seen % kRemembered] = geometry;
    seenPrimitive[seen % kRemembered] = primitive;
    ++seen;
    return false;
  }
};

// A ray from `origin` along `direction` between `near` and `far`.
RTCRay rayOf(const glm::vec3& origin, const glm::vec3& direction, float near, float far) {
  RTCRay ray{};
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = direction.x;
  ray.dir_y = direction.y;
  ray.dir_z = direction.z;
  ray.tnear = near;
  ray.tfar = far;
  ray.mask = 0xffffffffu;
  return ray;
}

struct Hit {
  bool found = false;
  float distance = 0;
  unsigned geometry = 0, primitive = 0;
  float u = 0, v = 0;
  glm::vec3 normal{0.0f};  // Embree's geometric normal (not unit)
};

class Tracer {
 public:
  Tracer(const TraceScene& scene, const TraceLights& lights, const TraceOptions& options)
      : scene_(scene), lights_(lights), options_(options), epsilon_(1e-5f) {}

  void setScale(float diagonal) { epsilon_ = std::max(1e-7f, 2e-6f * diagonal); }

  Hit intersect(const glm::vec3& origin, const glm::vec3& direction, float near, float far,
                unsigned leftGeometry, unsigned leftPrimitive) const {
    LeavingContext context(leftGeometry, leftPrimitive);
    RTCRayHit rh{};
    rh.ray = rayOf(origin, direction, near, far);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_.embree(), &context.base, &rh);
    Hit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.found = true;
    hit.distance = rh.ray.tfar;
    hit.geometry = rh.hit.geomID;
    hit.primitive = rh.hit.primID;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    hit.normal = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
    return hit;
  }

  // The tint at a hit (rgb, opacity), white and opaque where the shape has none.
  glm::vec4 tintAt(const TraceShape& shape, const Hit& hit) const {
    if (!shape.tint) return glm::vec4(1.0f);
    if (shape.curve) {
      const std::uint32_t first = shape.curveSegments[hit.primitive];
      return glm::mix(shape.tint[first], shape.tint[first + 1], hit.u);
    }
    const std::uint32_t* t = shape.triangleIndices + 3 * static_cast<std::size_t>(hit.primitive);
    return (1 - hit.u - hit.v) * shape.tint[t[0]] + hit.u * shape.tint[t[1]] +
           hit.v * shape.tint[t[2]];
  }

  float opacityAt(const TraceShape& shape, const Hit& hit) const {
    return scene_.material(shape.material).opacity * tintAt(shape, hit).a;
  }

  // The share of light that reaches `far` along the ray: 0 past an opaque shape, reduced by each
  // partly transparent one.
  float transmittance(glm::vec3 origin, const glm::vec3& direction, float far,
                      unsigned leftGeometry, unsigned leftPrimitive) const {
    if (!scene_.hasTransparency()) {
      LeavingContext context(leftGeometry, leftPrimitive);
      RTCRay ray = rayOf(origin, direction, epsilon_, far);
      rtcOccluded1(scene_.embree(), &context.base, &ray);
      return ray.tfar < 0 ? 0.0f : 1.0f;
    }
    ShadowContext context{};
    rtcInitIntersectContext(&context.base);
    context.base.filter = &Tracer::attenuate;
    context.leftGeometry = leftGeometry;
    context.leftPrimitive = leftPrimitive;
    context.tracer = this;
    RTCRay ray = rayOf(origin, direction, epsilon_, far);
    rtcOccluded1(scene_.embree(), &context.base, &ray);
    return ray.tfar < 0 ? 0.0f : context.through;
  }

  // The shadow ray's filter (ShadowContext): a shape that lets no light through, or the light
  // left falling below 1/1000, stops the ray; any other is passed, its transparency counted.
  static void attenuate(const RTCFilterFunctionNArguments* args) {
    auto* context = reinterpret_cast<ShadowContext*>(args->context);
    const auto* tracer = static_cast<const Tracer*>(context->tracer);
    for (unsigned i = 0; i < args->N; ++i) {
      if (args->valid[i] == 0) continue;
      Hit hit;
      hit.geometry = RTCHitN_geomID(args->hit, args->N, i);
      hit.primitive = RTCHitN_primID(args->hit, args->N, i);
      if (hit.geometry == context->leftGeometry && hit.primitive == context->leftPrimitive) {
        args->valid[i] = 0;
        continue;
      }
      hit.u = RTCHitN_u(args->hit, args->N, i);
      hit.v = RTCHitN_v(args->hit, args->N, i);
      const float opacity = tracer->opacityAt(tracer->scene_.shape(hit.geometry), hit);
      if (opacity >= 1) continue;  // opaque: occluded
      if (!context->counted(hit.geometry, hit.primitive)) context->through *= 1 - opacity;
      if (context->through < 1e-3f) {
        context->through = 0;
        continue;
      }
      args->valid[i] = 0;
    }
  }

  // Where a ray meets the spherical light, or a negative distance.
  float lightDistance(const glm::vec3& origin, const glm::vec3& direction) const {
    if (!lights_.sphere) return -1;
    const glm::vec3 toCentre = lights_.centre - origin;
    const float along = glm::dot(toCentre, direction);
    const float across2 = glm::dot(toCentre, toCentre) - along * along;
    const float r2 = lights_.radius * lights_.radius;
    if (across2 > r2) return -1;
    const float t = along - std::sqrt(r2 - across2);
    return t > 0 ? t : -1;
  }

  // The density, in solid angle, of sampling `direction` towards the light from `origin`.
  float lightPdf(const glm::vec3& origin) const {
    const float d2 = glm::dot(lights_.centre - origin, lights_.centre - origin);
    const float sin2 = lights_.radius * lights_.radius / d2;
    if (sin2 >= 1) return 0;
    const float cosMax = std::sqrt(1 - sin2);
    return 1 / (2 * kPi * (1 - cosMax));
  }

  glm::vec3 skyRadiance(const glm::vec3& direction) const {
    if (lights_.environment) return lights_.environment->radiance(direction);
    return glm::dot(direction, lights_.up) > 0 ? lights_.sky : glm::vec3(0.0f);
  }

  // The veins at a hit (veins.h): the colour goes towards the veins' on them, and the normal
  // leans as on a surface raised by their height.
  void addVeins(const TraceMaterial& material, const TraceShape& shape, const Hit& hit,
                SurfaceMaterial& surface, glm::vec3& normal) const {
    const std::uint32_t* t = shape.triangleIndices + 3 * static_cast<std::size_t>(hit.primitive);
    const SurfacePoint& a = shape.surface[t[0]];
    const SurfacePoint& b = shape.surface[t[1]];
    const SurfacePoint& c = shape.surface[t[2]];
    if (a.z < 0 || b.z < 0 || c.z < 0) return;  // a vertex of no surface
    const float w = 1 - hit.u - hit.v;
    const glm::vec2 uv = w * glm::vec2(a) + hit.u * glm::vec2(b) + hit.v * glm::vec2(c);
    const VeinMap& map = scene_.veinMap(material.veins, a.z);
    const float share = material.veinStrength * map.height(uv);
    const glm::vec3 towards = glm::mix(glm::vec3(1.0f), material.veinColour, share);
    surface.reflectance *= towards;
    surface.transmittance *= towards;
    // A vein lighter than its surface still returns no more light than it receives.
    const glm::vec3 total = surface.reflectance + surface.transmittance;
    for (int k = 0; k < 3; ++k) {
      if (total[k] > 1) {
        surface.reflectance[k] /= total[k];
        surface.transmittance[k] /= total[k];
      }
    }
    const float height = material.veinBump * material.veinWidth * a.w;
    if (height == 0) return;
    const glm::vec3 p0 = shape.positions[t[0]];
    const glm::vec3 e1 = shape.positions[t[1]] - p0, e2 = shape.positions[t[2]] - p0;
    const glm::vec2 d1 = glm::vec2(b) - glm::vec2(a), d2 = glm::vec2(c) - glm::vec2(a);
    const float det = d1.x * d2.y - d1.y * d2.x;
    if (std::abs(det) < 1e-12f) return;
    const glm::vec3 dpdu = (d2.y * e1 - d1.y * e2) / det;
    const glm::vec3 dpdv = (d1.x * e2 - d2.x * e1) / det;
    const glm::vec2 slope = height * map.slope(uv);
    const glm::vec3 bumped = glm::cross(dpdu + slope.x * normal, dpdv + slope.y * normal);
    const float length = glm::length(bumped);
    if (!(length > 0)) return;
    const glm::vec3 unit = bumped / length;
    normal = glm::dot(unit, normal) < 0 ? -unit : unit;
  }

  // The light arriving directly from both lights, each sampled once (a choice between them
  // would leave half the hits without the one that matters, the sun of a backlit leaf).
  template <class Bsdf>
  glm::vec3 directLight(const Bsdf& bsdf, const glm::vec3& point, const glm::vec3& wo,
                        const Hit& hit, Random& random) const {
    glm::vec3 total(0.0f);
    if (lights_.sphere) total += lightSample(bsdf, point, wo, hit, random.uniform2(), true);
    if (luminance(lights_.sky) > 0 || lights_.environment) {
      total += lightSample(bsdf, point, wo, hit, random.uniform2(), false);
    }
    return total;
  }

  // One sample towards the sphere or the sky, weighted against the material's own sampling.
  template <class Bsdf>
  glm::vec3 lightSample(const Bsdf& bsdf, const glm::vec3& point, const glm::vec3& wo,
                        const Hit& hit, const glm::vec2& u, bool sphere) const {
    glm::vec3 wi, radiance;
    float pdf, far;
    if (sphere) {
      const glm::vec3 toCentre = lights_.centre - point;
      const float distance = glm::length(toCentre);
      const float sin2 = lights_.radius * lights_.radius / (distance * distance);
      if (sin2 >= 1) return glm::vec3(0.0f);
      const float cosMax = std::sqrt(1 - sin2);
      wi = Frame::around(toCentre / distance).toWorld(sampleUniformCone(u, cosMax));
      pdf = 1 / (2 * kPi * (1 - cosMax));
      radiance = lights_.radiance;
      far = distance - lights_.radius;
    } else if (lights_.environment) {
      const EnvironmentSample e = lights_.environment->sample(u);
      wi = e.direction;
      pdf = e.pdf;
      radiance = e.radiance;
      far = std::numeric_limits<float>::infinity();
    } else {
      wi = Frame::around(lights_.up).toWorld(sampleUniformHemisphere(u));
      pdf = kUniformHemispherePdf;
      radiance = lights_.sky;
      far = std::numeric_limits<float>::infinity();
    }
    if (!(pdf > 0) || luminance(radiance) <= 0) return glm::vec3(0.0f);
    const glm::vec3 value = bsdf.value(wo, wi);
    if (luminance(value) <= 0) return glm::vec3(0.0f);
    // The sky lies behind the light: a sky sample towards the light sees the light instead.
    if (!sphere && lightDistance(point, wi) > 0) return glm::vec3(0.0f);
    const float through = transmittance(point, wi, far, hit.geometry, hit.primitive);
    if (through <= 0) return glm::vec3(0.0f);
    const float weight = powerHeuristic(pdf, bsdf.pdf(wo, wi));
    return value * radiance * (through * weight / pdf);
  }

  // The radiance a path brings back; `first`, when given, receives the colour and facing
  // normal of the first shape the camera ray stops at (zero where it stops at none).
  glm::vec3 radiance(glm::vec3 origin, glm::vec3 direction, float near, float far, Random& random,
                     FirstHit* first = nullptr) const {
    glm::vec3 total(0.0f), throughput(1.0f);
    unsigned leftGeometry = RTC_INVALID_GEOMETRY_ID, leftPrimitive = RTC_INVALID_GEOMETRY_ID;
    float lastPdf = 0;
    int passThroughs = 0;
    for (int bounce = 0;;) {
      const Hit hit = intersect(origin, direction, near, far, leftGeometry, leftPrimitive);
      const bool camera = bounce == 0;
      // Lights seen by a scattered ray, weighted against having sampled them directly.
      if (!camera) {
        const float toLight = lightDistance(origin, direction);
        if (toLight > 0 && (!hit.found || toLight < hit.distance)) {
          const float weight = powerHeuristic(lastPdf, lightPdf(origin));
          total += throughput * lights_.radiance * weight;
          break;
        }
      }
      if (!hit.found) {
        if (camera && !(lights_.environment && lights_.skySeen)) {
          total += throughput * options_.background;
        } else if (camera) {
          total += throughput * skyRadiance(direction);
        } else {
          const float skyPdf =
              lights_.environment ? lights_.environment->pdf(direction) : kUniformHemispherePdf;
          const float weight = powerHeuristic(lastPdf, skyPdf);
          total += throughput * skyRadiance(direction) * weight;
        }
        break;
      }
      const TraceShape& shape = scene_.shape(hit.geometry);
      const TraceMaterial& material = scene_.material(shape.material);
      const glm::vec3 point = origin + hit.distance * direction;
      const glm::vec4 tint = tintAt(shape, hit);
      // A partly transparent shape is passed through in proportion to its transparency.
      const float opacity = material.opacity * tint.a;
      if (opacity < 1 && random.uniform() >= opacity) {
        if (++passThroughs > kMaxPassThroughs) break;
        origin = point;
        far -= hit.distance;
        near = 0;
        leftGeometry = hit.geometry;
        leftPrimitive = hit.primitive;
        continue;
      }
      total += throughput * material.emission;
      const glm::vec3 wo = -direction;
      glm::vec3 wi, value;
      float pdf;
      if (material.hair) {
        glm::vec3 tangent(0, 1, 0);
        if (shape.curve) {
          const std::uint32_t segment = shape.curveSegments[hit.primitive];
          const glm::vec3 along =
              glm::vec3(shape.curveVertices[segment + 1]) - glm::vec3(shape.curveVertices[segment]);
          if (glm::length(along) > 0) tangent = glm::normalize(along);
        }
        // The lights, then the material's own direction: the lobe, then the direction's two
        // angles as one point of a square.
        auto scatter = [&](const auto& bsdf) {
          total += throughput * directLight(bsdf, point, wo, hit, random);
          const float lobe = random.uniform();
          const glm::vec2 angles = random.uniform2();
          const glm::vec4 u(lobe, angles.x, random.uniform(), angles.y);
          const HairSample s = bsdf.sample(wo, u);
          wi = s.direction;
          value = s.value;
          pdf = s.pdf;
        };
        if (material.chiang) {
          FibreMaterial fibre = material.chiangFibre;
          const glm::vec3 colour = material.fibreColour * glm::vec3(tint);
          if (!material.absorptionFixed) {
            fibre.absorption = absorptionFromColour(colour, fibre.azimuthalRoughness);
          }
          // Where the ray met the fibre across its width: from the round tube's normal there;
          // a ribbon turned towards the ray (a barb) has none, so h is drawn over its width.
          const float offset = shape.curve && !shape.flatCurve
                                   ? fibreOffset(tangent, hit.normal, wo)
                                   : 2 * random.uniform() - 1;
          if (camera && first) *first = {colour, tangent};
          scatter(FibreBsdf(fibre, tangent, wo, offset));
        } else {
          HairMaterial fibre = material.fibre;
          fibre.diffuse *= glm::vec3(tint);
          if (camera && first) *first = {fibre.diffuse + fibre.specular, tangent};
          scatter(HairBsdf(fibre, tangent));
        }
      } else {
        SurfaceMaterial surface = material.surface;
        surface.reflectance *= glm::vec3(tint);
        surface.transmittance *= glm::vec3(tint);
        glm::vec3 normal = hit.normal;
        if (shape.normals) {
          const std::uint32_t* t =
              shape.triangleIndices + 3 * static_cast<std::size_t>(hit.primitive);
          normal = (1 - hit.u - hit.v) * shape.normals[t[0]] + hit.u * shape.normals[t[1]] +
                   hit.v * shape.normals[t[2]];
        }
        normal = glm::length(normal) > 0 ? glm::normalize(normal) : -direction;
        if (shape.texcoords) {
          // The texture modulates the colour, as GL draws it.
          const std::uint32_t* t =
              shape.triangleIndices + 3 * static_cast<std::size_t>(hit.primitive);
          const glm::vec2 uv = (1 - hit.u - hit.v) * shape.texcoords[t[0]] +
                               hit.u * shape.texcoords[t[1]] + hit.v * shape.texcoords[t[2]];
          const glm::vec3 texel = linearColour(bilinearColourAt(scene_.texture(shape.texture), uv));
          surface.reflectance *= texel;
          surface.transmittance *= texel;
        }
        if (material.veins >= 0 && shape.surface) addVeins(material, shape, hit, surface, normal);
        if (glm::dot(normal, wo) < 0) normal = -normal;
        if (camera && first) *first = {surface.reflectance + surface.transmittance, normal};
        // Light that walks inside a leaf leaves by one face or the other (subsurface.h).
        if (material.subsurface.present()) {
          walkIntoSheet(material.subsurface, material.surface, surface, random);
        }
        const SurfaceBsdf bsdf(surface, normal);
        total += throughput * directLight(bsdf, point, wo, hit, random);
        const float lobe = random.uniform();
        const glm::vec2 direction2 = random.uniform2();
        const glm::vec3 u(lobe, direction2);
        const SurfaceSample s = bsdf.sample(wo, u);
        wi = s.direction;
        value = s.value;
        pdf = s.pdf;
      }
      if (!(pdf > 0) || luminance(value) <= 0) break;
      throughput *= value / pdf;
      lastPdf = pdf;
      if (++bounce > options_.maxBounces) break;
      // Russian roulette after the first bounce (Arvo and Kirk 1990): a path in a hairy
      // plant's fuzz scatters many times, most of them carrying little. (From the first, its
      // random choice spoilt the stratification of the light a first hit gathers.)
      if (bounce > 1) {
        const float keep =
            std::min(0.95f, std::max(throughput.r, std::max(throughput.g, throughput.b)));
        if (random.uniform() >= keep) break;
        throughput /= keep;
      }
      origin = point;
      direction = wi;
      near = epsilon_;
      far = std::numeric_limits<float>::infinity();
      leftGeometry = hit.geometry;
      leftPrimitive = hit.primitive;
      passThroughs = 0;
    }
    return total;
  }

 private:
  const TraceScene& scene_;
  const TraceLights& lights_;
  const TraceOptions& options_;
  float epsilon_;
};

// The variance of the mean of `count` samples with sum `sum` and sum of squares `squares`; with
// fewer than two samples nothing is known of it, and it counts as large.
glm::dvec3 varianceOfMean(const glm::dvec3& sum, const glm::dvec3& squares, std::uint32_t count) {
  if (count < 2) return glm::dvec3(1e30);
  const double n = count;
  const glm::dvec3 mean = sum / n;
  return glm::max(glm::dvec3(0.0), (squares - n * mean * mean) / (n - 1)) / n;
}

}  // namespace

TraceLights traceLights(const TraceSettings& look, const Bounds& plant, const glm::vec3& fallback) {
  TraceLights lights;
  lights.sky = linearColour(look.sky);
  lights.up = glm::length(look.up) > 0 ? glm::normalize(look.up) : glm::vec3(0, 1, 0);
  const SphereLight sphere = sphereLight(look, plant, fallback);
  lights.sphere = sphere.present;
  lights.centre = sphere.centre;
  lights.radius = sphere.radius;
  lights.radiance = sphere.radiance;
  return lights;
}

glm::vec3 traceRay(const TraceScene& scene, const TraceLights& lights, const glm::vec3& origin,
                   const glm::vec3& direction, Random& random, const TraceOptions& options) {
  Tracer tracer(scene, lights, options);
  return tracer.radiance(origin, direction, 0, std::numeric_limits<float>::infinity(), random);
}

TraceImage traceImage(const TraceScene& scene, const Camera& camera, const TraceLights& lights,
                      const TraceOptions& options) {
  const Clock::time_point start = Clock::now();
  TraceImage image;
  image.width = camera.viewport.x;
  image.height = camera.viewport.y;
  const std::size_t pixels =
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  image.radiance.assign(pixels, glm::vec3(0.0f));
  TraceOptions linear = options;
  linear.background = radianceShownAs(linearColour(options.background), options.display);
  Tracer tracer(scene, lights, linear);
  const PixelFilter filter(options.filter);
  const bool box = options.filter == PixelFilterKind::Box;
  const float focus = options.focusDistance > 0
                          ? options.focusDistance
                          : std::max(glm::dot(camera.target - camera.eye, camera.forward), 1e-6f);
  const float aspect = static_cast<float>(image.width) / static_cast<float>(image.height);
  const bool perspective = camera.projection == Projection::Perspective;
  const float tanHalf = std::tan(glm::radians(camera.fieldOfViewY) / 2);
  tracer.setScale(glm::length(glm::vec3(camera.halfWidth, camera.halfHeight, 0)) +
                  std::abs(camera.farPlane - camera.nearPlane) * 1e-3f);

  const int threads = options.threads > 0
                          ? options.threads
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int passes = std::max(1, options.samples);
  const bool adaptive = options.noise > 0;
  const int firstJudged = std::max(2, options.firstSamples);  // a variance needs two samples
  std::vector<glm::vec3> sum(pixels, glm::vec3(0.0f));
  std::vector<glm::dvec3> squares(adaptive || options.denoise ? pixels : 0, glm::dvec3(0.0));
  // The denoiser's features: the sums of the first hits' colours and normals and their squares.
  const std::size_t featurePixels = options.denoise ? pixels : 0;
  std::vector<glm::vec3> albedoSum(featurePixels, glm::vec3(0.0f)),
      albedoSquares = albedoSum, normalSum = albedoSum, normalSquares = albedoSum;
  image.samples.assign(pixels, 0);

  // The tiles still sampled, in raster order; the threads take them one at a time.
  const int tilesX = (image.width + kTileSize - 1) / kTileSize;
  const int tilesY = (image.height + kTileSize - 1) / kTileSize;
  std::vector<int> active(static_cast<std::size_t>(tilesX) * static_cast<std::size_t>(tilesY));
  for (std::size_t t = 0; t < active.size(); ++t) active[t] = static_cast<int>(t);
  std::size_t activePixels = pixels;
  auto tileRect = [&](int tile) {
    const int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
    return glm::ivec4(x0, y0, std::min(x0 + kTileSize, image.width),
                      std::min(y0 + kTileSize, image.height));
  };
  // A tile stops when the noisiest of its pixels is under the target: the tile, not the
  // pixel, so that one whose first samples happen to agree goes on with its neighbours.
  auto quietTile = [&](const glm::ivec4& rect, std::uint32_t count) {
    for (int y = rect.y; y < rect.w; ++y) {
      for (int x = rect.x; x < rect.z; ++x) {
        const std::size_t index =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
            static_cast<std::size_t>(x);
        if (pixelNoise(sum[index], squares[index], count, options.display) > options.noise) {
          return false;
        }
      }
    }
    return true;
  };

  if (options.progress) {
    options.progress->begin("tracing", Progress::Unit::Steps, passes, "samples a pixel");
  }
  double lastPass = 0;
  double sampled = 0;  // samples taken, over every pixel: the work done, for the time left
  for (int pass = 0; pass < passes && !active.empty(); ++pass) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    if (options.seconds > 0 && pass > 0 && elapsed + lastPass > options.seconds) break;
    const Clock::time_point passStart = Clock::now();
    std::atomic<std::size_t> nextTile{0};
    // A tile is judged by the thread that sampled it, as soon as it has: its pixels are its
    // own, and its fate depends on them alone.
    const bool judged = adaptive && pass + 1 >= firstJudged;
    const auto count = static_cast<std::uint32_t>(pass + 1);
    std::vector<std::uint8_t> stops(judged ? active.size() : 0, 0);
    auto work = [&] {
      for (std::size_t k; (k = nextTile.fetch_add(1)) < active.size();) {
        const glm::ivec4 rect = tileRect(active[k]);
        for (int y = rect.y; y < rect.w; ++y) {
          for (int x = rect.x; x < rect.z; ++x) {
            const std::size_t index =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                static_cast<std::size_t>(x);
            Random random =
                Random::stratified(options.seed, index, static_cast<std::uint32_t>(pass));
            // The point in the pixel, or about it by the filter's density (pixel_filter.h).
            const glm::vec2 u = random.uniform2();
            const PixelFilter::Sample filtered = filter.sample(u);
            const glm::vec2 jitter = box ? u : filtered.offset + 0.5f;
            const float sx =
                (static_cast<float>(x) + jitter.x) / static_cast<float>(image.width) * 2 - 1;
            const float sy =
                1 - (static_cast<float>(y) + jitter.y) / static_cast<float>(image.height) * 2;
            glm::vec3 origin, direction;
            float near, far;
            if (perspective) {
              origin = camera.eye;
              direction = glm::normalize(camera.forward + sx * tanHalf * aspect * camera.right +
                                         sy * tanHalf * camera.up);
              const float along = glm::dot(direction, camera.forward);
              near = std::max(0.0f, camera.nearPlane / along);
              far = camera.farPlane / along;
            } else {
              // The near plane may lie behind the eye (cpfg's front distance): rays start on it.
              origin = camera.eye + sx * camera.halfWidth * camera.right +
                       sy * camera.halfHeight * camera.up + camera.nearPlane * camera.forward;
              direction = camera.forward;
              near = 0;
              far = camera.farPlane - camera.nearPlane;
            }
            if (options.aperture > 0) {
              // A thin lens (pbrt-v4, Sec. 5.2.3): the ray leaves a point of the lens disc
              // (about the eye, or the ray's start on the near plane) towards where the pinhole
              // ray meets the plane in focus, so that plane stays sharp and the rest blurs.
              const float start = glm::dot(origin - camera.eye, camera.forward);
              const glm::vec3 focused =
                  origin + direction * ((focus - start) / glm::dot(direction, camera.forward));
              const glm::vec2 lens = sampleUniformDisk(random.uniform2()) * (options.aperture / 2);
              origin += lens.x * camera.right + lens.y * camera.up;
              direction = glm::normalize(focused - origin);
              const float along = glm::dot(direction, camera.forward);
              if (perspective) {
                near = std::max(0.0f, camera.nearPlane / along);
                far = camera.farPlane / along;
              } else {
                far = (camera.farPlane - camera.nearPlane) / along;
              }
            }
            FirstHit first;
            glm::vec3 value = tracer.radiance(origin, direction, near, far, random,
                                              options.denoise ? &first : nullptr);
            // A path that found no number is dropped rather than spoiling the pixel.
            if (!std::isfinite(value.x + value.y + value.z)) value = glm::vec3(0.0f);
            value *= filtered.weight;
            sum[index] += value;
            if (!squares.empty()) squares[index] += glm::dvec3(value) * glm::dvec3(value);
            if (options.denoise) {
              albedoSum[index] += first.albedo;
              albedoSquares[index] += first.albedo * first.albedo;
              normalSum[index] += first.normal;
              normalSquares[index] += first.normal * first.normal;
            }
            ++image.samples[index];
          }
        }
        if (judged) stops[k] = quietTile(rect, count) ? 1 : 0;
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads && static_cast<std::size_t>(t) < active.size(); ++t) {
      pool.emplace_back(work);
    }
    work();
    for (std::thread& t : pool) t.join();
    lastPass = std::chrono::duration<double>(Clock::now() - passStart).count();
    image.passes = pass + 1;
    sampled += static_cast<double>(activePixels);
    if (judged) {
      std::size_t kept = 0;
      for (std::size_t k = 0; k < active.size(); ++k) {
        if (stops[k] == 0) {
          active[kept++] = active[k];
          continue;
        }
        const glm::ivec4 rect = tileRect(active[k]);
        activePixels -=
            static_cast<std::size_t>(rect.z - rect.x) * static_cast<std::size_t>(rect.w - rect.y);
      }
      active.resize(kept);
    }
    if (options.progress) {
      if (adaptive) {
        const double share = static_cast<double>(activePixels) / static_cast<double>(pixels);
        options.progress->note(", " + std::to_string(static_cast<int>(std::ceil(100 * share))) +
                               "% of pixels active");
      }
      // The share of the work done: at most the pixels still active sample every pass left (a
      // tile that stops makes the rest cheaper), and no more than the time budget allows.
      const double left = static_cast<double>(activePixels) * (passes - pass - 1);
      double share = sampled / std::max(1.0, sampled + left);
      if (options.seconds > 0) {
        const double spent = std::chrono::duration<double>(Clock::now() - start).count();
        share = std::max(share, std::min(1.0, spent / options.seconds));
      }
      options.progress->update(pass + 1, share);
    }
  }
  for (std::size_t i = 0; i < pixels; ++i) {
    image.radiance[i] = sum[i] / static_cast<float>(std::max<std::uint32_t>(1, image.samples[i]));
  }
  if (options.denoise) {
    if (options.progress) options.progress->begin("denoising", Progress::Unit::None);
    const Clock::time_point denoiseStart = Clock::now();
    NoisyImage noisy;
    noisy.width = image.width;
    noisy.height = image.height;
    noisy.colour = image.radiance;
    noisy.colourVariance.resize(pixels);
    noisy.albedo.resize(pixels);
    noisy.albedoVariance.resize(pixels);
    noisy.normal.resize(pixels);
    noisy.normalVariance.resize(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
      const std::uint32_t n = image.samples[i];
      noisy.colourVariance[i] = glm::vec3(varianceOfMean(glm::dvec3(sum[i]), squares[i], n));
      noisy.albedo[i] = albedoSum[i] / static_cast<float>(std::max<std::uint32_t>(1, n));
      noisy.albedoVariance[i] =
          glm::vec3(varianceOfMean(glm::dvec3(albedoSum[i]), glm::dvec3(albedoSquares[i]), n));
      noisy.normal[i] = normalSum[i] / static_cast<float>(std::max<std::uint32_t>(1, n));
      noisy.normalVariance[i] =
          glm::vec3(varianceOfMean(glm::dvec3(normalSum[i]), glm::dvec3(normalSquares[i]), n));
    }
    DenoiseOptions denoising;
    denoising.threads = threads;
    std::optional<ProgressHeartbeat> heartbeat;
    if (options.progress) heartbeat.emplace(*options.progress);
    image.radiance = denoise(noisy, denoising);
    heartbeat.reset();
    image.denoiseSeconds = std::chrono::duration<double>(Clock::now() - denoiseStart).count();
  }
  image.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return image;
}

double TraceImage::meanSamples() const {
  double total = 0;
  for (const std::uint32_t n : samples) total += n;
  return samples.empty() ? 0.0 : total / static_cast<double>(samples.size());
}

float displayLevel(float linear) {
  const float v = std::clamp(linear, 0.0f, 1.0f);
  return 255 * (v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f);
}

float pixelNoise(const glm::vec3& sum, const glm::dvec3& squares, std::uint32_t count,
                 const DisplayTransform& display) {
  if (count < 2) return 0;
  const double scale = std::exp2(display.exposure);
  const glm::dvec3 variance = varianceOfMean(glm::dvec3(sum), squares, count);
  float noise = 0;
  for (int c = 0; c < 3; ++c) {
    if (variance[c] == 0) continue;  // every sample alike: the background
    const double mean = sum[c] / static_cast<double>(count);
    const double error = std::sqrt(variance[c]);
    const float levels =
        displayLevel(toneMap(static_cast<float>(scale * (mean + error)), display.tone)) -
        displayLevel(toneMap(static_cast<float>(scale * (mean - error)), display.tone));
    noise = std::max(noise, levels / 2);
  }
  return noise;
}

RgbaImage sampleCountImage(const TraceImage& image, int maximum) {
  RgbaImage out(image.width, image.height);
  const double top = std::max(1, maximum);
  for (std::size_t i = 0; i < image.samples.size(); ++i) {
    const auto grey = static_cast<std::uint8_t>(
        std::lround(255 * std::min(1.0, static_cast<double>(image.samples[i]) / top)));
    out.rgba[4 * i] = out.rgba[4 * i + 1] = out.rgba[4 * i + 2] = grey;
    out.rgba[4 * i + 3] = 255;
  }
  return out;
}

RgbaImage displayImage(const TraceImage& image, const DisplayTransform& transform) {
  RgbaImage out(image.width, image.height);
  auto encode = [](float v) { return static_cast<std::uint8_t>(std::lround(displayLevel(v))); };
  for (std::size_t i = 0; i < image.radiance.size(); ++i) {
    const glm::vec3 c = displayLight(image.radiance[i], transform);
    out.rgba[4 * i] = encode(c.r);
    out.rgba[4 * i + 1] = encode(c.g);
    out.rgba[4 * i + 2] = encode(c.b);
    out.rgba[4 * i + 3] = 255;
  }
  return out;
}

}  // namespace hirsute::trace
