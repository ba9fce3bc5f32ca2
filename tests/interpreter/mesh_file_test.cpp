// Mesh files as surfaces (mesh_file.h): read with Assimp, confined to the model's folder, checked,
// and placed by the turtle like a `.s` surface.
#include "hirsute/interpreter/mesh_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../../interpreter/surface_mesh.h"
#include "hirsute/hairs/plant/hair_attributes.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"
#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

// A unit cube as an OBJ: 6 quads (12 triangles), texture coordinates and normals per face.
constexpr const char* kCube =
    "mtllib cube.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n"
    "f 1/1/1 4/4/1 3/3/1 2/2/1\n"
    "f 5/1/2 6/2/2 7/3/2 8/4/2\n"
    "f 1/1/3 2/2/3 6/3/3 5/4/3\n"
    "f 4/1/4 8/4/4 7/3/4 3/2/4\n"
    "f 1/1/5 5/2/5 8/3/5 4/4/5\n"
    "f 2/1/6 3/2/6 7/3/6 6/4/6\n";

class MeshFileTest : public testing::TemporaryFolderTest {
 protected:
  MeshFileTest() : TemporaryFolderTest("hirsute_mesh_") {}

  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }
  SurfaceMeshData load(const std::string& name, std::size_t limit = kDefaultMaxMeshTriangles) {
    return loadMeshFile(file(name), folder_, limit, diagnostics);
  }
  Diagnostic error(const std::string& name, std::size_t limit = kDefaultMaxMeshTriangles) {
    try {
      load(name, limit);
    } catch (const DiagnosticError& e) {
      return e.diagnostic();
    }
    ADD_FAILURE() << name << ": expected a DiagnosticError";
    return {};
  }
  std::string warnings() const {
    std::string text;
    for (const Diagnostic& d : diagnostics.warnings()) text += d.text() + "\n";
    return text;
  }

  Diagnostics diagnostics;
};

TEST_F(MeshFileTest, AnObjGivesItsTrianglesNormalsAndTextureCoordinates) {
  write("cube.obj", kCube);
  write("cube.mtl", "newmtl skin\nKd 1 1 1\n");
  EXPECT_TRUE(isMeshFile(file("cube.obj")));
  const SurfaceMeshData mesh = load("cube.obj");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings();
  EXPECT_EQ(mesh.triangles(), 12u);
  EXPECT_TRUE(mesh.fileUvs);
  EXPECT_EQ(mesh.boundsMin, glm::dvec3(0.0));
  EXPECT_EQ(mesh.boundsMax, glm::dvec3(1.0));
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  // Every triangle winds counter-clockwise about its vertices' normals (the file's outward ones).
  for (std::size_t t = 0; t < mesh.triangles(); ++t) {
    const glm::dvec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                     c = mesh.positions[mesh.indices[3 * t + 2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), mesh.normals[mesh.indices[3 * t]]), 0) << t;
  }
  for (const glm::vec2& uv : mesh.uv) {
    EXPECT_TRUE(uv.x == 0 || uv.x == 1);
    EXPECT_TRUE(uv.y == 0 || uv.y == 1);
  }
}

// A mesh without texture coordinates: a disc gets CGAL's least-squares conformal map (the angles
// of its triangles kept, in [0, 1]²); any other shape its x and y.
TEST_F(MeshFileTest, AMeshWithoutCoordinatesIsParameterisedOrMappedFlat) {
  std::ostringstream grid;
  // A curved 8 × 8 grid of squares, each cut in two (a paraboloid: no map keeps every angle): a
  // disc.
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 8; ++j) grid << "v " << j / 8.0 << ' ' << i / 8.0 << ' ' << 0.3 * ((j / 8.0) * (j / 8.0) + (i / 8.0) * (i / 8.0)) << '\n';
  }
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      const int a = i * 9 + j + 1, b = a + 1, c = a + 9, d = c + 1;
      grid << "f " << a << ' ' << b << ' ' << d << "\nf " << a << ' ' << d << ' ' << c << '\n';
    }
  }
  write("grid.obj", grid.str());
  const SurfaceMeshData disc = load("grid.obj");
  EXPECT_EQ(disc.uvSource, MeshUvSource::Conformal);
  // Conformal: each triangle's (u, v) is its world shape scaled and turned, not mirrored, so
  // its angles are kept (within the map's discretisation).
  double worst = 0;
  for (std::size_t t = 0; t < disc.triangles(); ++t) {
    const std::uint32_t* c = &disc.indices[3 * t];
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 e1 = disc.positions[c[(k + 1) % 3]] - disc.positions[c[k]];
      const glm::dvec3 e2 = disc.positions[c[(k + 2) % 3]] - disc.positions[c[k]];
      const glm::dvec2 f1 = glm::dvec2(disc.uv[c[(k + 1) % 3]] - disc.uv[c[k]]);
      const glm::dvec2 f2 = glm::dvec2(disc.uv[c[(k + 2) % 3]] - disc.uv[c[k]]);
      const double world = std::acos(glm::dot(e1, e2) / (glm::length(e1) * glm::length(e2)));
      const double plane = std::acos(glm::dot(f1, f2) / (glm::length(f1) * glm::length(f2)));
      worst = std::max(worst, std::abs(world - plane) * 180 / 3.14159265);
    }
  }
  for (const glm::vec2& uv : disc.uv) {
    EXPECT_GE(uv.x, -1e-6f);
    EXPECT_LE(uv.x, 1 + 1e-6f);
    EXPECT_GE(uv.y, -1e-6f);
    EXPECT_LE(uv.y, 1 + 1e-6f);
  }
  std::printf("conformal map: angles kept within %.1f degrees\n", worst);
  EXPECT_LT(worst, 3.0);
}

TEST_F(MeshFileTest, TheFormatIsChosenByTheFileAndAMeshWithoutCoordinatesIsMappedFlat) {
  write("tile.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n2 0 0\n2 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  write("tile.stl",
        "solid tile\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 2 0 0\nvertex 2 1 0\n"
        "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 2 1 0\n"
        "vertex 0 1 0\nendloop\nendfacet\nendsolid tile\n");
  for (const char* name : {"tile.ply", "tile.stl"}) {
    const SurfaceMeshData mesh = load(name);
    EXPECT_EQ(mesh.triangles(), 2u) << name;
    EXPECT_FALSE(mesh.fileUvs) << name;
    // A disc: parameterised; the normals computed: +z.
    EXPECT_EQ(mesh.uvSource, MeshUvSource::Conformal) << name;
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      EXPECT_NEAR(mesh.normals[v].z, 1, 1e-6) << name;
    }
  }
  // A closed box (no border) is no disc: (u, v) are x and y over their bounds.
  write("box.obj",
        "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nv 0 0 1\nv 2 0 1\nv 2 1 1\nv 0 1 1\n"
        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n");
  const SurfaceMeshData box = load("box.obj");
  EXPECT_EQ(box.uvSource, MeshUvSource::Planar);
  for (std::size_t v = 0; v < box.positions.size(); ++v) {
    EXPECT_NEAR(box.uv[v].x, box.positions[v].x / 2, 1e-6);
    EXPECT_NEAR(box.uv[v].y, box.positions[v].y, 1e-6);
  }
  EXPECT_FALSE(isMeshFile(file("leaf.s")));
  EXPECT_FALSE(isMeshFile(file("notes.txt")));
}

TEST_F(MeshFileTest, FilesTheMeshNamesOutsideTheFolderAreNotRead) {
  fs::create_directories(file("model"));
  write("outside.mtl", "newmtl skin\nKd 1 0 0\n");
  std::ofstream(file("model/cube.obj")) << "mtllib ../outside.mtl\n" << kCube;
  const SurfaceMeshData mesh =
      loadMeshFile(file("model/cube.obj"), file("model"), kDefaultMaxMeshTriangles, diagnostics);
  EXPECT_EQ(mesh.triangles(), 12u);
  EXPECT_NE(warnings().find("leaves the model's folder"), std::string::npos) << warnings();
}

TEST_F(MeshFileTest, BadMeshesAreErrorsInTheirOwnFile) {
  write("nan.obj", "v 0 0 0\nv 1 0 0\nv 1 nan 0\nf 1 2 3\n");
  const Diagnostic nan = error("nan.obj");
  EXPECT_EQ(nan.where.line, 3);
  EXPECT_EQ(nan.where.column, 5);
  EXPECT_NE(nan.message.find("'nan' is not a finite coordinate"), std::string::npos) << nan.text();

  write("empty.obj", "# nothing\n");
  EXPECT_NE(error("empty.obj").message.find("cannot read the mesh"), std::string::npos);
  write("points.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\n");
  const std::string points = error("points.obj").message;
  EXPECT_TRUE(points.find("no triangles") != std::string::npos ||
              points.find("cannot read the mesh") != std::string::npos)
      << points;
  write("broken.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n");
  EXPECT_NE(error("broken.ply").message.find("element 'vertex' announces 3 rows"), std::string::npos)
      << error("broken.ply").text();

  write("cube.obj", kCube);
  const Diagnostic limit = error("cube.obj", 11);
  EXPECT_NE(limit.message.find("12 triangles, more than the limit of 11"), std::string::npos)
      << limit.text();
  EXPECT_NE(limit.message.find("--max-mesh-triangles"), std::string::npos);
}

TEST_F(MeshFileTest, DegenerateTrianglesAreLeftOutAndNonManifoldEdgesReported) {
  // Two good triangles, one with two corners at one point, one with its corners on a line, and
  // a fan of three triangles on the edge 1-2.
  write("fan.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 0 0 1\nv 0 0 -1\n"
        "f 1 2 3\nf 1 1 3\nf 1 2 4\nf 1 2 5\nf 2 1 6\n");
  const SurfaceMeshData mesh = load("fan.obj");
  EXPECT_EQ(mesh.triangles(), 3u);
  const std::string text = warnings();
  EXPECT_NE(text.find("degenerate triangles (no area) left out"), std::string::npos) << text;
  EXPECT_NE(text.find("1 edge is shared by more than two triangles"), std::string::npos) << text;
}

// A mesh sequence: the frames from the lowest number on, each with the first one's vertices.
TEST_F(MeshFileTest, AMeshSequenceHasAFrameForEachFileAndTheFirstsTriangles) {
  const auto tile = [](double z) {
    std::string text = "v 0 0 0\nv 1 0 0\nv 1 1 ";
    text += std::to_string(z);
    text += "\nv 0 1 0\nf 1 2 3 4\n";
    return text;
  };
  write("tile.0003.obj", tile(0));
  write("tile.0004.obj", tile(0.5));
  write("tile.0005.obj", tile(1));
  EXPECT_TRUE(isMeshSequence(file("tile.####.obj")));
  EXPECT_FALSE(isMeshSequence(file("tile.obj")));
  const SurfaceMeshData mesh = loadMeshSequence(file("tile.####.obj"), folder_,
                                                kDefaultMaxMeshTriangles, diagnostics);
  ASSERT_EQ(mesh.frames(), 3u);
  EXPECT_EQ(mesh.triangles(), 2u);
  double highest[3] = {0, 0, 0};
  for (std::size_t k = 0; k < 3; ++k) {
    for (const glm::dvec3& p : mesh.positionsAt(k)) highest[k] = std::max(highest[k], p.z);
  }
  EXPECT_EQ(highest[0], 0);
  EXPECT_EQ(highest[1], 0.5);
  EXPECT_EQ(highest[2], 1);
  // Past the last frame, the last.
  EXPECT_EQ(&mesh.positionsAt(7), &mesh.positionsAt(2));

  write("gap.0001.obj", tile(0));
  write("gap.0003.obj", tile(0));
  write("more.0001.obj", tile(0));
  write("more.0002.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 2 0\nf 1 2 3 4\nf 2 5 3\n");
  const auto error = [&](const std::string& pattern) {
    try {
      loadMeshSequence(file(pattern), folder_, kDefaultMaxMeshTriangles, diagnostics);
    } catch (const DiagnosticError& e) {
      return e.diagnostic().text();
    }
    return std::string("no error");
  };
  EXPECT_NE(error("gap.####.obj").find("gap.0002.obj: error: frame 2 of the mesh sequence is missing"),
            std::string::npos)
      << error("gap.####.obj");
  EXPECT_NE(error("more.####.obj").find("more.0002.obj: error: this frame of the mesh sequence has 5 "
                                        "vertices, the first 4"),
            std::string::npos)
      << error("more.####.obj");
  EXPECT_NE(error("none.####.obj").find("no frame of the mesh sequence"), std::string::npos);
}

// An animated file: a glTF strip skinned to two bones (scripts/make-meshes.py), the upper bone
// (at y = 1) turning 90 degrees about x over one second, sampled at 24 frames a second.
TEST_F(MeshFileTest, AnAnimatedFileGivesAFrameForEachTwentyFourthOfASecond) {
  fs::copy_file(fs::path(HIRSUTE_SOURCE_DIR) / "tests/fixtures/interpreter/bending-strip.gltf",
                file("strip.gltf"));
  const SurfaceMeshData mesh = load("strip.gltf");
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings();
  ASSERT_EQ(mesh.frames(), 25u);
  EXPECT_EQ(mesh.triangles(), 16u);
  EXPECT_TRUE(mesh.fileUvs);
  const auto top = [&](std::size_t frame) {
    glm::dvec3 highest(0, -1, 0);
    for (const glm::dvec3& p : mesh.positionsAt(frame)) {
      if (p.x > 0 && (p.y + p.z > highest.y + highest.z)) highest = p;
    }
    return highest;
  };
  const double s = std::sqrt(0.5);
  EXPECT_NEAR(glm::distance(top(0), glm::dvec3(0.25, 2, 0)), 0, 1e-5);
  EXPECT_NEAR(glm::distance(top(12), glm::dvec3(0.25, 1 + s, s)), 0, 1e-5);
  EXPECT_NEAR(glm::distance(top(24), glm::dvec3(0.25, 1, 1)), 0, 1e-5);
  // The foot (weighted to the lower bone alone) stays; the normals turn with the upper bone.
  for (std::size_t frame : {0u, 12u, 24u}) {
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      if (mesh.positions[v].y <= 0.5) {
        EXPECT_NEAR(glm::distance(mesh.positionsAt(frame)[v], mesh.positions[v]), 0, 1e-6);
      }
      if (mesh.positions[v].y >= 1.5) {
        const glm::dvec3 turned = frame == 24 ? glm::dvec3(0, -1, 0) : frame == 12 ? glm::dvec3(0, -s, s) : glm::dvec3(0, 0, 1);
        EXPECT_NEAR(glm::distance(mesh.normalsAt(frame)[v], turned), 0, 1e-5) << frame;
      }
    }
  }
}

// Placed by ~X like a `.s` surface: the file's x, y, z along the turtle's L, H and U, scaled;
// normals stay unit and outward, a mirroring scale keeps the triangles counter-clockwise.
TEST_F(MeshFileTest, TheTurtlePlacesTheMeshInItsFrame) {
  write("cube.obj", kCube);
  Surface surface;
  surface.mesh = std::make_shared<const SurfaceMeshData>(load("cube.obj"));
  for (double mirror : {1.0, -1.0}) {
    Scene scene;
    SurfacePlacement placement;
    placement.position = glm::dvec3(5, 0, 0);
    placement.heading = glm::dvec3(0, 0, 1);
    placement.left = glm::dvec3(0, 1, 0);
    placement.up = glm::dvec3(1, 0, 0);
    placement.scale = glm::dvec3(2 * mirror, 2, 2);
    SurfaceAppearance appearance;
    appearance.material = [](int) { return 3; };
    OrganAttributeIndices organs;
    organs.of<HairAttributes>() = 0;
    EXPECT_EQ(appendSurface(scene, surface, placement, appearance, organs), 12u);
    ASSERT_EQ(scene.organSurfaces.size(), 1u);
    const OrganSurface& record = scene.organSurfaces[0];
    EXPECT_EQ(record.kind, OrganSurfaceKind::Mesh);
    EXPECT_EQ(record.indexCount, 36u);
    const TriangleMesh& mesh = scene.meshes[static_cast<std::size_t>(record.mesh)];
    EXPECT_EQ(mesh.material, 3);
    const glm::vec3 centre(5 + 1, 1 * mirror, 1);  // x → L·2·mirror, y → H·2, z → U·2
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      EXPECT_NEAR(glm::length(mesh.normals[v]), 1, 1e-5);
    }
    for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
      const glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                      c = mesh.positions[mesh.indices[i + 2]];
      const glm::vec3 face = glm::cross(b - a, c - a);
      EXPECT_GT(glm::dot(face, mesh.normals[mesh.indices[i]]), 0) << mirror;
      EXPECT_GT(glm::dot(face, (a + b + c) / 3.0f - centre), 0) << mirror << ": outward";
    }
  }
}

std::string plyHeader(const std::string& format, int vertices, int faces,
                      const std::string& vertexProperties =
                          "property float x\nproperty float y\n"
                          "property float z\n") {
  return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(vertices) + "\n" +
         vertexProperties + "element face " + std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

// What trips Assimp's PLY reader (an assertion on a face of no corners, reading past the end of
// a file shorter than its header) is refused before Assimp reads it, at the line and column.
TEST_F(MeshFileTest, PlyFilesAreCheckedBeforeAssimpReadsThem) {
  const std::string corners = "0 0 0\n1 0 0\n0 1 0\n";
  write("no-corners.ply", plyHeader("ascii", 3, 2) + corners + "3 0 1 2\n0\n");
  const Diagnostic none = error("no-corners.ply");
  EXPECT_EQ(none.where.line, 14);
  EXPECT_EQ(none.where.column, 1);
  EXPECT_NE(none.message.find("face 2 has 0 corners (a face has at least 3)"), std::string::npos)
      << none.text();

  write("two-corners.ply", plyHeader("ascii", 3, 1) + corners + "2 0 1\n");
  EXPECT_NE(error("two-corners.ply").message.find("face 1 has 2 corners"), std::string::npos);

  write("far-index.ply", plyHeader("ascii", 3, 1) + corners + "3 0 1 7\n");
  const Diagnostic far = error("far-index.ply");
  EXPECT_EQ(far.where.line, 13);
  EXPECT_EQ(far.where.column, 7);
  EXPECT_NE(far.message.find("face 1 names vertex 7; there are 3"), std::string::npos)
      << far.text();

  write("short.ply", plyHeader("ascii", 3, 1) + corners);
  EXPECT_NE(error("short.ply").message.find("the file ends before its header's elements do"),
            std::string::npos);

  write("nan.ply", plyHeader("ascii", 3, 1) + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  const Diagnostic nan = error("nan.ply");
  EXPECT_EQ(nan.where.line, 11);
  EXPECT_EQ(nan.where.column, 3);
  EXPECT_NE(nan.message.find("non-finite coordinate y"), std::string::npos) << nan.text();

  // A binary file whose header announces a billion vertices in a few bytes, and one whose face
  // list runs past its end.
  write("billion.ply", plyHeader("binary_little_endian", 1'000'000'000, 1) + std::string(40, '\0'));
  EXPECT_NE(error("billion.ply").message.find("announces 1000000000 rows"), std::string::npos)
      << error("billion.ply").text();
  std::string binary = plyHeader("binary_little_endian", 3, 1) + std::string(36, '\0');
  binary += static_cast<char>(200);  // a face of 200 corners, and 4 bytes of them
  binary += std::string(4, '\0');
  write("past-end.ply", binary);
  EXPECT_NE(error("past-end.ply").message.find("runs past the file's end"), std::string::npos)
      << error("past-end.ply").text();

  write("header.ply", "ply\nformat ascii 1.0\nelement vertex x\nend_header\n");
  EXPECT_EQ(error("header.ply").where.line, 3);
  write("no-end.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  EXPECT_NE(error("no-end.ply").message.find("no 'end_header'"), std::string::npos);

  // The triangles are counted from the file.
  write("square.ply", plyHeader("ascii", 4, 1) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  EXPECT_EQ(load("square.ply").triangles(), 2u);
  EXPECT_NE(error("square.ply", 1).message.find("2 triangles, more than the limit of 1"),
            std::string::npos);
}

// Node hierarchies are walked by Assimp with recursion: a glTF's children and a COLLADA file's
// nested elements deeper than kMaxMeshNesting are refused, and a glTF whose nodes form a cycle.
TEST_F(MeshFileTest, DeepOrCyclicNodeHierarchiesAreRefused) {
  const auto gltf = [](const std::string& nodes) {
    return "{\"asset\": {\"version\": \"2.0\"}, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [" +
           nodes + "]}";
  };
  std::string chain;
  for (int i = 0; i < 300; ++i) chain += "{\"children\": [" + std::to_string(i + 1) + "]},\n";
  chain += "{}";
  write("chain.gltf", gltf(chain));
  EXPECT_NE(error("chain.gltf").message.find("the node hierarchy is more than 256 nodes deep"),
            std::string::npos)
      << error("chain.gltf").text();
  write("cycle.gltf", gltf("{\"children\": [1]}, {\"children\": [2]}, {\"children\": [0]}"));
  EXPECT_NE(error("cycle.gltf").message.find("(a cycle)"), std::string::npos)
      << error("cycle.gltf").text();
  write("nested.gltf", gltf("{\"extras\": " + std::string(300, '[') + std::string(300, ']') + "}"));
  const Diagnostic nested = error("nested.gltf");
  EXPECT_EQ(nested.where.line, 1);
  EXPECT_NE(nested.message.find("the JSON nests more than 256 deep"), std::string::npos)
      << nested.text();

  std::string collada =
      "<?xml version=\"1.0\"?>\n<COLLADA version=\"1.4.1\">\n<library_visual_scenes>"
      "<visual_scene id=\"s\">\n";
  for (int i = 0; i < 300; ++i) collada += "<node id=\"n" + std::to_string(i) + "\">\n";
  for (int i = 0; i < 300; ++i) collada += "</node>\n";
  collada += "</visual_scene></library_visual_scenes></COLLADA>\n";
  write("deep.dae", collada);
  const Diagnostic deep = error("deep.dae");
  EXPECT_EQ(deep.where.line, 257);
  EXPECT_NE(deep.message.find("the XML's elements nest more than 256 deep"), std::string::npos)
      << deep.text();
}

// Assimp makes a mesh of each OBJ group; 200 000 of them cost it minutes and gigabytes.
TEST_F(MeshFileTest, AnObjOfTooManyGroupsIsRefusedAtOnce) {
  constexpr std::size_t kMaxObjGroups = 10'000;  // mesh_file_checks.h
  std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (std::size_t i = 0; i <= kMaxObjGroups; ++i) {
    text += (i % 2 == 0 ? "g part" : "usemtl m") + std::to_string(i) + "\nf 1 2 3\n";
  }
  write("groups.obj", text);
  const Diagnostic many = error("groups.obj");
  EXPECT_EQ(many.where.line, 4 + 2 * static_cast<int>(kMaxObjGroups));
  EXPECT_NE(many.message.find("more than 10000 groups, objects or materials"), std::string::npos)
      << many.text();
}

// A vertex colour's red blends the key feathers from 0 to 1 (docs/meshes.md): one just outside
// is clamped with a warning (a red below 0 once switched the blend to u without a word), one that
// is no number is an error.
TEST_F(MeshFileTest, VertexColoursAreClampedToTheUnitWithAWarning) {
  const std::string colours = "property float red\nproperty float green\nproperty float blue\n";
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  write("colours.ply",
        plyHeader("ascii", 3, 1, xyz + colours) +
            "0 0 0 -0.001 0.5 0.5\n1 0 0 1.5 0.5 0.5\n0 1 0 0.25 0.5 0.5\n3 0 1 2\n");
  const SurfaceMeshData mesh = load("colours.ply");
  ASSERT_EQ(mesh.colours.size(), 3u);
  std::vector<float> reds;
  for (const glm::vec3& c : mesh.colours) reds.push_back(c.r);
  std::sort(reds.begin(), reds.end());
  EXPECT_EQ(reds, (std::vector<float>{0.0f, 0.25f, 1.0f}));
  EXPECT_NE(warnings().find("2 vertex colours outside [0, 1] clamped to it"), std::string::npos)
      << warnings();

  write("nan-colour.ply", plyHeader("ascii", 3, 1, xyz + colours) +
                              "0 0 0 nan 0.5 0.5\n1 0 0 1 0.5 0.5\n0 1 0 0.25 0.5 0.5\n3 0 1 2\n");
  EXPECT_NE(error("nan-colour.ply").message.find("has a non-finite colour"), std::string::npos)
      << error("nan-colour.ply").text();
}

// A glTF's positions are binary: a NaN among them is an error naming the vertex, not a
// degenerate triangle left out.
TEST_F(MeshFileTest, ANonFiniteGltfPositionIsAnError) {
  fs::copy_file(fs::path(HIRSUTE_SOURCE_DIR) / "tests/bad_input/mesh_gltf_nan.gltf",
                file("nan.gltf"));
  const Diagnostic nan = error("nan.gltf");
  EXPECT_NE(nan.message.find("has a non-finite coordinate"), std::string::npos) << nan.text();
}

// The program reads meshes in a child process: a crash of Assimp there (a DirectX file nested
// deeper than its recursion reaches, which no check before it looks at) is an error naming the
// file and the cause.
TEST_F(MeshFileTest, ACrashOfTheReaderIsAnError) {
  std::string text = "xof 0303txt 0032\n";
  for (int i = 0; i < 200'000; ++i) text += "Frame f {\n";
  write("deep.x", text);
  const auto start = std::chrono::steady_clock::now();
  const Diagnostic crash = error("deep.x");
  EXPECT_NE(crash.message.find("the mesh reader (Assimp) crashed on this file with a "
                               "segmentation fault"),
            std::string::npos)
      << crash.text();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10);
}

// The child process gives what this process gives: the same mesh, bit for bit, and the same
// warnings, for every kind of file (an OBJ with its atlas, a PLY with colours and a degenerate
// triangle, an animated glTF, a mesh sequence) and the same errors.
TEST_F(MeshFileTest, TheChildProcessReadsWhatThisProcessReads) {
  write("cube.obj", kCube);
  write("cube.mtl", "newmtl skin\nKd 1 1 1\n");
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  write("colours.ply", plyHeader("ascii", 4, 2, xyz + "property uchar red\n") +
                           "0 0 0 0\n1 0 0 255\n0 1 0 128\n2 0 0 9\n3 0 1 2\n3 0 1 3\n");
  fs::copy_file(fs::path(HIRSUTE_SOURCE_DIR) / "tests/fixtures/interpreter/bending-strip.gltf",
                file("strip.gltf"));
  fs::copy_file(fs::path(HIRSUTE_SOURCE_DIR) / "models/mesh-leaf/leaf.ply", file("leaf.ply"));
  fs::copy_file(fs::path(HIRSUTE_SOURCE_DIR) / "tests/fixtures/hairs/torus.ply", file("torus.ply"));
  write("nan.obj", "v 0 0 0\nv 1 0 0\nv 1 nan 0\nf 1 2 3\n");
  const auto same = [](const SurfaceMeshData& a, const SurfaceMeshData& b) {
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.uv, b.uv);
    EXPECT_EQ(a.colours, b.colours);
    EXPECT_EQ(a.indices, b.indices);
    EXPECT_EQ(a.fileUvs, b.fileUvs);
    EXPECT_EQ(a.uvSource, b.uvSource);
    EXPECT_EQ(a.boundsMin, b.boundsMin);
    EXPECT_EQ(a.boundsMax, b.boundsMax);
    EXPECT_EQ(a.laterPositions, b.laterPositions);
    EXPECT_EQ(a.laterNormals, b.laterNormals);
    EXPECT_EQ(a.atlasUv, b.atlasUv);  // a closed mesh without (u, v): the fur's atlas
    EXPECT_EQ(a.atlasChart, b.atlasChart);
  };
  const auto texts = [](const Diagnostics& d) {
    std::vector<std::string> out;
    for (const Diagnostic& w : d.warnings()) out.push_back(w.text());
    return out;
  };
  for (const char* name : {"cube.obj", "colours.ply", "strip.gltf", "leaf.ply", "torus.ply"}) {
    SCOPED_TRACE(name);
    Diagnostics inChild, inProcess;
    const SurfaceMeshData a = loadMeshFile(file(name), folder_, kDefaultMaxMeshTriangles, inChild,
                                           MeshReading::ChildProcess);
    const SurfaceMeshData b = loadMeshFile(file(name), folder_, kDefaultMaxMeshTriangles, inProcess,
                                           MeshReading::InProcess);
    EXPECT_GT(a.triangles(), 0u);
    if (std::string(name) == "torus.ply") {
      EXPECT_FALSE(a.atlasUv.empty());
    }
    same(a, b);
    EXPECT_EQ(texts(inChild), texts(inProcess));
  }
  Diagnostics inChild, inProcess;
  const SurfaceMeshData a =
      loadMeshFile(file("colours.ply"), folder_, kDefaultMaxMeshTriangles, inChild);
  EXPECT_EQ(a.colours.size(), 4u);
  EXPECT_NE(texts(inChild).at(0).find("degenerate triangle"), std::string::npos);
  std::string childError, processError;
  for (MeshReading reading : {MeshReading::ChildProcess, MeshReading::InProcess}) {
    try {
      loadMeshFile(file("nan.obj"), folder_, kDefaultMaxMeshTriangles, inChild, reading);
    } catch (const DiagnosticError& e) {
      (reading == MeshReading::ChildProcess ? childError : processError) = e.diagnostic().text();
    }
  }
  EXPECT_FALSE(childError.empty());
  EXPECT_EQ(childError, processError);
}

}  // namespace
}  // namespace hirsute
