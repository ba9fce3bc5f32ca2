// The shape of shell fur (Silva, Bando, Chen & Nishita 2010, Sec. 3.2-3.3): the one-particle
// strand that bends it, the curl that winds it and the clump displacement that gathers it when
// wet. The GL shaders (viewer/gl/fur_drawing.cpp) and the explicit strands of the exports
// (fur_strands.h) evaluate the same formulas; these are the reference the tests measure.
#pragma once

#include <glm/glm.hpp>

namespace hirsute::fur {

// The strand rooted at a surface point (Sec. 3.2.1): root p_root, unit normal n (the growth
// direction), rest length L0; its rest tip p_0 = p_root + L0 n.
struct StrandRoot {
  glm::vec3 root{0.0f};
  glm::vec3 normal{0, 0, 1};
  float length = 1;

  glm::vec3 restTip() const { return root + length * normal; }
};

// The hemisphere constraint of Eq. 3: the nearest point to `tip` with |p - p_root| <= L0 and
// (p - p_root) . n >= 0. (The set is a half ball whose flat side passes through its centre, so
// clamping the normal component and then the length is the exact projection.)
glm::vec3 constrainTip(const StrandRoot& strand, const glm::vec3& tip);

// Where the particle rests under a constant force per unit mass `force` (gravity, wind): the
// spring k pulls it to p_0, so the minimum of k/2 |p - p_0|² - m force . p over the hemisphere
// is the projection of p_0 + (m / k) force (the energy is isotropic about its minimum).
glm::vec3 restingTip(const StrandRoot& strand, float stiffness, float mass, const glm::vec3& force);

// One time step of Eq. 2 for the particle: spring to p_0, `force` per unit mass, damping
// `damping` per second, semi-implicit Euler, then Eq. 3 (the velocity loses the part the
// constraint removed).
struct StrandState {
  glm::vec3 tip{0.0f};
  glm::vec3 velocity{0.0f};
};
void stepStrand(const StrandRoot& strand, float stiffness, float mass, float damping,
                const glm::vec3& force, float dt, StrandState& state);

// The strand's centre line at normalized length h in [0, 1]: the quadratic Bézier through
// p_root, p_0 and p (Sec. 3.2.1), and its derivative in h.
glm::vec3 bendPoint(const StrandRoot& strand, const glm::vec3& tip, float h);
glm::vec3 bendTangent(const StrandRoot& strand, const glm::vec3& tip, float h);

// The curl of Eq. 4 in the surface's tangent plane (u, v unit, spanning it): alpha(h) = (1 -
// wetness) K_alpha h, with K_alpha = curlRadius · L0 (the module gives it as a fraction of the
// length), winding omega = curlFrequency radians over the length.
glm::vec3 curlOffset(float h, float wetness, float curlRadius, float curlFrequency, float length,
                     const glm::vec3& u, const glm::vec3& v);
glm::vec3 curlTangent(float h, float wetness, float curlRadius, float curlFrequency, float length,
                      const glm::vec3& u, const glm::vec3& v);

// The profile of Eq. 5: how far along its way to the clump a strand is at height h of N layers,
// (1 - w) h + w (1 + ln h / ln N), 0 at the first layer's root side and 1 at the tip. (The
// paper's k = -ln N is taken with the sign that makes the profile rise from 0 at h = 1/N to 1
// at h = 1; at h <= 1/N the log part is 0, and with N = 1 it is h.)
float clumpProfile(float h, float w, int layers);

// The scale of Eq. 5's displacement, d = clumpScale · (c_pixel - c_mask): profile · rho ·
// r_mask, with r_mask counted in texels of a 256² mask (the paper's resolution; r in the
// surface's [0, 1] units times 256), so that a clump's size, not the mask's resolution, decides
// how tightly it gathers.
inline constexpr float kClumpTexels = 256;
float clumpScale(float h, float w, int layers, float wetness, float radius);

// Where in the surface's parametrization the strand rooted at `root` (a point of a clump with
// centre `centre`) lies at height h: the fragment at x shows the fur at x + d(x), so the strand
// from `root` is seen at centre + (root - centre) / (1 + clumpScale).
glm::vec2 clumpedPosition(const glm::vec2& root, const glm::vec2& centre, float scale);

// Kajiya-Kay shading of Eq. 6 times the shadow factor: the colour at height h of a strand with
// unit tangent t, lit from unit direction l, seen from unit direction e (both towards them).
glm::vec3 furShade(const glm::vec3& colour, const glm::vec3& t, const glm::vec3& l,
                   const glm::vec3& e, float specular, float phong, float kShadow, float h);

// The shadow factor gamma = (K_shadow - 1 + h) / K_shadow of Sec. 4.
inline float shadowFactor(float h, float kShadow) { return (kShadow - 1 + h) / kShadow; }

}  // namespace hirsute::fur
