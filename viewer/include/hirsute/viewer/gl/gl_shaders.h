// The renderer's GLSL 3.30 core shaders, embedded as strings. A surface program is put together
// from pieces: the version line, the defines SHADING (0 unlit, 1 flat, 2 smooth) and TEXTURED,
// the material and lighting code, and the geometry's vertex main (mesh, sphere instance, disc
// instance) or the fragment main.
#pragma once

namespace hirsute::shaders {

inline constexpr char kVersion[] = "#version 330 core\n";

// Materials, and light as cpfg gives it. With a colour map, cpfg shades by moving along the
// palette (manual §8.1.3): the index col + i·N·L for the `light direction:` L and `diffuse
// reflection:` i, kept within [col − i, col + i] and the colour's bank of 256. With materials it
// lights as OpenGL's fixed pipeline (glLightModel defaults: global ambient 0.2, infinite viewer,
// the alpha of the diffuse colour).
inline constexpr char kMaterialAndLighting[] = R"(
uniform samplerBuffer uMaterials;  // four texels a material: ambient+alpha, diffuse+shininess,
uniform int uMaterialCount;        // specular, emission
uniform vec3 uForward;
uniform bool uColorMap;
uniform vec3 uColorMapLight;        // normalized
uniform float uDiffuseReflection;
uniform int uLightCount;
uniform vec4 uLightPosition[8];     // w = 0: the direction towards a directional light
uniform vec3 uLightAmbient[8];
uniform vec3 uLightDiffuse[8];
uniform vec3 uLightSpecular[8];
uniform vec4 uLightSpot[8];         // direction, cos(cutoff); w < -1: no spot
uniform vec4 uLightAttenuation[8];  // constant, linear, quadratic, spot exponent

const vec3 kGlobalAmbient = vec3(0.2);

int paletteIndex(int material) {
  return clamp(material, 0, uMaterialCount - 1);
}

vec3 paletteColor(int index) {
  return texelFetch(uMaterials, index * 4 + 1).rgb;
}

// The colour itself: cpfg's `filled` draws the diffuse colour.
vec4 unlit(int material) {
  int index = paletteIndex(material);
  return vec4(paletteColor(index), texelFetch(uMaterials, index * 4).a);
}

// `n` is the normal of the side being seen, normalized.
vec4 shade(int material, vec3 position, vec3 n, bool onePerPolygon) {
  int index = paletteIndex(material);
  float alpha = texelFetch(uMaterials, index * 4).a;
  if (uColorMap) {
    int bankStart = index / 256 * 256;
    int bankEnd = min(bankStart + 255, uMaterialCount - 1);
    float shadeIndex = clamp(float(index) + uDiffuseReflection * dot(n, uColorMapLight),
                             float(bankStart), float(bankEnd));
    if (onePerPolygon) return vec4(paletteColor(int(floor(shadeIndex + 0.5))), alpha);
    int below = int(floor(shadeIndex));
    vec3 c = mix(paletteColor(below), paletteColor(min(below + 1, bankEnd)), shadeIndex - float(below));
    return vec4(c, alpha);
  }
  vec3 ambient = texelFetch(uMaterials, index * 4).rgb;
  vec4 diffuse = texelFetch(uMaterials, index * 4 + 1);
  vec3 specular = texelFetch(uMaterials, index * 4 + 2).rgb;
  vec3 color = texelFetch(uMaterials, index * 4 + 3).rgb + kGlobalAmbient * ambient;
  vec3 v = -uForward;
  for (int i = 0; i < uLightCount; ++i) {
    vec3 l;
    float attenuation = 1.0;
    if (uLightPosition[i].w == 0.0) {
      l = normalize(uLightPosition[i].xyz);
    } else {
      vec3 d = uLightPosition[i].xyz - position;
      float distance = length(d);
      l = d / max(distance, 1e-20);
      vec4 k = uLightAttenuation[i];
      attenuation = 1.0 / max(k.x + k.y * distance + k.z * distance * distance, 1e-20);
      if (uLightSpot[i].w >= -1.0) {
        float s = dot(-l, normalize(uLightSpot[i].xyz));
        attenuation *= s < uLightSpot[i].w ? 0.0 : pow(max(s, 0.0), k.w);
      }
    }
    float nl = max(dot(n, l), 0.0);
    vec3 c = uLightAmbient[i] * ambient + uLightDiffuse[i] * diffuse.rgb * nl;
    if (nl > 0.0) {
      float nh = max(dot(n, normalize(l + v)), 0.0);
      c += uLightSpecular[i] * specular * (diffuse.a > 0.0 ? pow(nh, diffuse.a) : 1.0);
    }
    color += attenuation * c;
  }
  return vec4(clamp(color, 0.0, 1.0), alpha);
}
)";

// What every surface vertex shader ends with. Smooth shading lights the vertices, as OpenGL's
// fixed pipeline (and so cpfg) does, both sides of two-sided polygons (one-sided polygons show
// their front colour from behind too); flat shading and the unlit colour are per polygon.
inline constexpr char kSurfaceVertexOutput[] = R"(
uniform mat4 uViewProjection;
uniform bool uTwoSided;
#if SHADING == 2
out vec4 vFront;
out vec4 vBack;
#elif SHADING == 1
out vec3 vPosition;
flat out int vMaterial;
#else
flat out vec4 vColor;
#endif
#if TEXTURED
out vec2 vTexcoord;
#endif

void emit(vec3 position, vec3 normal, int material, vec2 texcoord) {
  gl_Position = uViewProjection * vec4(position, 1.0);
#if SHADING == 2
  vec3 n = normalize(normal);
  vFront = shade(material, position, n, false);
  vBack = uTwoSided ? shade(material, position, -n, false) : vFront;
#elif SHADING == 1
  vPosition = position;
  vMaterial = material;
#else
  vColor = unlit(material);
#endif
#if TEXTURED
  vTexcoord = texcoord;
#endif
}
)";

// Triangle meshes: one material a draw.
inline constexpr char kMeshVertexMain[] = R"(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aTexcoord;
uniform int uMaterial;
void main() {
  emit(aPosition, aNormal, uMaterial, aTexcoord);
}
)";

// cpfg's @O: instances of a unit sphere (its vertices are their own normals).
inline constexpr char kSphereVertexMain[] = R"(
layout(location = 0) in vec3 aUnit;
layout(location = 3) in vec3 aCenter;
layout(location = 4) in float aRadius;
layout(location = 5) in int aMaterial;
void main() {
  emit(aCenter + aRadius * aUnit, aUnit, aMaterial, vec2(0.0));
}
)";

// cpfg's @c (a disc across its normal) and @o (normal zero: a disc in the plane of the screen):
// instances of a unit disc in the xy plane.
inline constexpr char kDiscVertexMain[] = R"(
layout(location = 0) in vec2 aUnit;
layout(location = 3) in vec3 aCenter;
layout(location = 4) in vec3 aNormal;
layout(location = 5) in float aRadius;
layout(location = 6) in int aMaterial;
uniform vec3 uRight;
uniform vec3 uUp;
void main() {
  vec3 n, s, t;
  if (dot(aNormal, aNormal) > 0.0) {
    n = normalize(aNormal);
    s = normalize(cross(abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0), n));
    t = cross(n, s);
  } else {
    n = -uForward;
    s = uRight;
    t = uUp;
  }
  emit(aCenter + aRadius * (aUnit.x * s + aUnit.y * t), n, aMaterial, vec2(0.0));
}
)";

inline constexpr char kSurfaceFragmentMain[] = R"(
uniform bool uTwoSided;
#if SHADING == 2
in vec4 vFront;
in vec4 vBack;
#elif SHADING == 1
in vec3 vPosition;
flat in int vMaterial;
#else
flat in vec4 vColor;
#endif
#if TEXTURED
in vec2 vTexcoord;
uniform sampler2D uTexture;
#endif
out vec4 fragColor;

void main() {
#if SHADING == 2
  vec4 color = gl_FrontFacing ? vFront : vBack;
#elif SHADING == 1
  // One normal a polygon: the derivatives span the polygon, and their cross product faces the
  // viewer; a one-sided polygon seen from behind is lit on its front side.
  vec3 n = normalize(cross(dFdx(vPosition), dFdy(vPosition)));
  if (!gl_FrontFacing && !uTwoSided) n = -n;
  vec4 color = shade(vMaterial, vPosition, n, true);
#else
  vec4 color = vColor;
#endif
#if TEXTURED
  color *= texture(uTexture, vTexcoord);  // cpfg's default texture mode: modulate
#endif
  fragColor = color;
}
)";

// Line segments, drawn in their colour. The Scene's LineSegments go up as they are (nine floats
// each: from, to, widthFrom, widthTo, material) into a buffer texture, and the vertex shaders,
// drawn without attributes, read them by gl_VertexID.
inline constexpr char kLineVertexCommon[] = R"(
uniform samplerBuffer uLines;
uniform mat4 uViewProjection;
flat out vec4 vColor;
float lineFloat(int i) {
  return texelFetch(uLines, i).r;
}
)";

// Pixel-style segments at most a pixel wide are GL lines, as cpfg draws them (glLineWidth below
// one is one): two vertices a segment.
inline constexpr char kThinLineVertexMain[] = R"(
void main() {
  int base = (gl_VertexID >> 1) * 9;
  int at = base + (gl_VertexID & 1) * 3;
  vColor = unlit(floatBitsToInt(lineFloat(base + 8)));
  gl_Position = uViewProjection * vec4(lineFloat(at), lineFloat(at + 1), lineFloat(at + 2), 1.0);
}
)";

// Wider segments are quads, two triangles a segment, since core profile has no wide lines.
// Pixel style widths are in pixels across the segment on the screen (cpfg's glLineWidth);
// polygon style widths are in world units across a ribbon facing the eye.
inline constexpr char kWideLineVertexMain[] = R"(
uniform bool uPixelWidth;
uniform vec2 uViewport;
uniform bool uPerspective;
uniform float uNear;
uniform vec3 uEye;
uniform vec3 uRight;
const int kCorner[6] = int[6](0, 1, 2, 2, 1, 3);  // 0, 1 at the start, 2, 3 at the end
void main() {
  int base = (gl_VertexID / 6) * 9;
  int corner = kCorner[gl_VertexID % 6];
  bool atTo = corner >= 2;
  float side = (corner & 1) == 0 ? 0.5 : -0.5;
  vec3 from = vec3(lineFloat(base), lineFloat(base + 1), lineFloat(base + 2));
  vec3 to = vec3(lineFloat(base + 3), lineFloat(base + 4), lineFloat(base + 5));
  float width = lineFloat(base + (atTo ? 7 : 6));
  vColor = unlit(floatBitsToInt(lineFloat(base + 8)));
  vec3 p = atTo ? to : from;
  if (!uPixelWidth) {
    vec3 towardsEye = uPerspective ? uEye - p : -uForward;
    vec3 across = cross(to - from, towardsEye);
    across = dot(across, across) > 1e-30 ? normalize(across) : uRight;
    gl_Position = uViewProjection * vec4(p + across * (side * width), 1.0);
    return;
  }
  vec4 a = uViewProjection * vec4(from, 1.0);
  vec4 b = uViewProjection * vec4(to, 1.0);
  // An end behind the eye moves along the segment onto the near plane.
  if (a.w < uNear && b.w < uNear) {
    gl_Position = vec4(0.0, 0.0, 0.0, -1.0);
    return;
  }
  if (a.w < uNear) a = mix(a, b, (uNear - a.w) / (b.w - a.w));
  if (b.w < uNear) b = mix(b, a, (uNear - b.w) / (a.w - b.w));
  vec2 d = (b.xy / b.w - a.xy / a.w) * uViewport;
  vec2 across = dot(d, d) > 1e-12 ? normalize(vec2(-d.y, d.x)) : vec2(0.0, 1.0);
  vec4 q = atTo ? b : a;
  q.xy += across * (side * width) * 2.0 / uViewport * q.w;
  gl_Position = q;
}
)";

// Lines and line-like instances in a colour of their own, unlit.
inline constexpr char kLineFragmentMain[] = R"(
flat in vec4 vColor;
out vec4 fragColor;
void main() {
  fragColor = vColor;
}
)";

}  // namespace hirsute::shaders
