// Continuous collision detection: the degenerate cases built here (coplanar sliding, parallel
// edges, contact exactly at t = 1 or t = 0, motionless touching, degenerate primitives), planted
// contacts in seeded random motions, and the public queries with ground truth in
// ../shared/ccd-queries (skipped when absent), none of whose collisions may be missed.
#include "hirsute/hairs/dynamics/continuous_collision.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "hirsute/hairs/dynamics/ccd_query_file.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

// The unit right triangle in the plane z = 0, not moving.
MovingPrimitives vertexOverUnitTriangle(const Vector3d& from, const Vector3d& to) {
  MovingPrimitives m;
  m.start = {from, Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  m.end = {to, Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  return m;
}

MovingPrimitives edges(const Vector3d& a0, const Vector3d& a1, const Vector3d& b0,
                       const Vector3d& b1, const Vector3d& a0End, const Vector3d& a1End,
                       const Vector3d& b0End, const Vector3d& b1End) {
  MovingPrimitives m;
  m.start = {a0, a1, b0, b1};
  m.end = {a0End, a1End, b0End, b1End};
  return m;
}

TEST(VertexFaceCcd, VertexThroughTheFaceHitsAtTheCrossing) {
  const CcdResult r = vertexFaceCcd(vertexOverUnitTriangle({0.25, 0.25, 1}, {0.25, 0.25, -1}));
  ASSERT_TRUE(r.contact);
  EXPECT_LE(r.timeOfImpact, 0.5);
  EXPECT_GE(r.timeOfImpact, 0.5 - 1e-6);
  EXPECT_FALSE(r.budgetExhausted);
}

TEST(VertexFaceCcd, VertexPassingBesideTheFaceMisses) {
  EXPECT_FALSE(vertexFaceCcd(vertexOverUnitTriangle({0.8, 0.8, 1}, {0.8, 0.8, -1})).contact);
  EXPECT_FALSE(vertexFaceCcd(vertexOverUnitTriangle({0.25, 0.25, 1}, {0.25, 0.25, 1e-6})).contact);
}

TEST(VertexFaceCcd, CoplanarSlidingIsAContactFromTheEdgeOn) {
  // In the face's plane the whole step: it enters the triangle at x = 0, t = 1/3.
  const CcdResult r = vertexFaceCcd(vertexOverUnitTriangle({-1, 0.25, 0}, {2, 0.25, 0}));
  ASSERT_TRUE(r.contact);
  EXPECT_LE(r.timeOfImpact, 1.0 / 3.0);
  EXPECT_GE(r.timeOfImpact, 1.0 / 3.0 - 1e-6);
  // The same slide beyond the hypotenuse never touches.
  EXPECT_FALSE(vertexFaceCcd(vertexOverUnitTriangle({-1, 2, 0}, {2, 2, 0})).contact);
}

TEST(VertexFaceCcd, ContactExactlyAtTheEndOfTheStep) {
  const CcdResult r = vertexFaceCcd(vertexOverUnitTriangle({0.25, 0.25, 1}, {0.25, 0.25, 0}));
  ASSERT_TRUE(r.contact);
  EXPECT_LE(r.timeOfImpact, 1.0);
  EXPECT_GE(r.timeOfImpact, 1.0 - 1e-6);
  // Arriving on the hypotenuse's far corner at t = 1.
  EXPECT_TRUE(vertexFaceCcd(vertexOverUnitTriangle({0, 1, 1}, {0, 1, 0})).contact);
}

TEST(VertexFaceCcd, ContactAtTheStartIsTimeZero) {
  const CcdResult r = vertexFaceCcd(vertexOverUnitTriangle({0.5, 0.5, 0}, {0.5, 0.5, 1}));
  ASSERT_TRUE(r.contact);
  EXPECT_EQ(r.timeOfImpact, 0.0);
}

// Primitives already within the separation where the step starts are a contact at 0 found
// without a search (no box examined); just beyond it, the search runs and finds the later
// contact.
TEST(Ccd, ATouchAtTheStartIsFoundWithoutASearch) {
  const CcdOptions options{.minimumSeparation = 0.01};
  // A vertex 0.005 over the face, and 0.005 beyond the hypotenuse (diagonally, within 0.01 on
  // each axis of its nearest point), moving away.
  for (const Vector3d& at : {Vector3d(0.3, 0.3, 0.005), Vector3d(0.5036, 0.5036, 0.005)}) {
    const CcdResult r = vertexFaceCcd(vertexOverUnitTriangle(at, at + Vector3d(0, 0, 1)), options);
    ASSERT_TRUE(r.contact) << at.transpose();
    EXPECT_EQ(r.timeOfImpact, 0.0);
    EXPECT_EQ(r.checks, 0);
  }
  const CcdResult later =
      vertexFaceCcd(vertexOverUnitTriangle({0.3, 0.3, 0.02}, {0.3, 0.3, -0.02}), options);
  ASSERT_TRUE(later.contact);
  EXPECT_GT(later.checks, 0);
  EXPECT_GE(later.timeOfImpact, 0.25 - 1e-4);  // F changes by 0.04 over the step
  EXPECT_LE(later.timeOfImpact, 0.25);
  // Two parallel edges 0.008 apart, sliding along each other.
  const CcdResult side =
      edgeEdgeCcd(edges({0, 0, 0}, {1, 0, 0}, {0.2, 0.008, 0}, {1.2, 0.008, 0}, {0.1, 0, 0},
                        {1.1, 0, 0}, {0.2, 0.008, 0}, {1.2, 0.008, 0}),
                  options);
  ASSERT_TRUE(side.contact);
  EXPECT_EQ(side.timeOfImpact, 0.0);
  EXPECT_EQ(side.checks, 0);
}

TEST(VertexFaceCcd, MotionlessTouchingAndMotionlessApart) {
  const CcdResult r = vertexFaceCcd(vertexOverUnitTriangle({0.5, 0, 0}, {0.5, 0, 0}));
  ASSERT_TRUE(r.contact);
  EXPECT_EQ(r.timeOfImpact, 0.0);
  EXPECT_FALSE(vertexFaceCcd(vertexOverUnitTriangle({0.2, 0.2, 1e-3}, {0.2, 0.2, 1e-3})).contact);
}

TEST(VertexFaceCcd, MinimumSeparationMakesANearPassAContact) {
  const MovingPrimitives pass = vertexOverUnitTriangle({0.2, 0.2, 0.01}, {0.4, 0.2, 0.01});
  EXPECT_FALSE(vertexFaceCcd(pass, CcdOptions{.minimumSeparation = 0.005}).contact);
  const CcdResult r = vertexFaceCcd(pass, CcdOptions{.minimumSeparation = 0.02});
  ASSERT_TRUE(r.contact);
  EXPECT_EQ(r.timeOfImpact, 0.0);
}

TEST(VertexFaceCcd, DegenerateTriangleIsTheSegmentItCovers) {
  // All three corners on the x axis: the vertex crossing the axis at x = 0.5 touches it.
  MovingPrimitives m;
  m.start = {Vector3d(0.5, 1, 0), Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, 0, 0)};
  m.end = {Vector3d(0.5, -1, 0), Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, 0, 0)};
  EXPECT_TRUE(vertexFaceCcd(m).contact);
  m.end[0] = Vector3d(0.5, -1, 0.001);
  m.start[0] = Vector3d(0.5, 1, 0.001);
  EXPECT_FALSE(vertexFaceCcd(m).contact);
}

TEST(EdgeEdgeCcd, CrossingEdgesHitHalfWay) {
  const CcdResult r = edgeEdgeCcd(edges({-1, 0, 0}, {1, 0, 0}, {0, -1, 1}, {0, 1, 1},  //
                                        {-1, 0, 0}, {1, 0, 0}, {0, -1, -1}, {0, 1, -1}));
  ASSERT_TRUE(r.contact);
  EXPECT_LE(r.timeOfImpact, 0.5);
  EXPECT_GE(r.timeOfImpact, 0.5 - 1e-6);
  // The same fall beside the first edge's end.
  EXPECT_FALSE(edgeEdgeCcd(edges({-1, 0, 0}, {1, 0, 0}, {2, -1, 1}, {2, 1, 1},  //
                                 {-1, 0, 0}, {1, 0, 0}, {2, -1, -1}, {2, 1, -1}))
                   .contact);
}

TEST(EdgeEdgeCcd, ParallelEdgesMeetingAtTheEnd) {
  // Parallel all the step, overlapping along x, closing to touch at t = 1.
  const CcdResult r = edgeEdgeCcd(edges({0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {1.5, 1, 0},  //
                                        {0, 0, 0}, {1, 0, 0}, {0.5, 0, 0}, {1.5, 0, 0}));
  ASSERT_TRUE(r.contact);
  EXPECT_GE(r.timeOfImpact, 1.0 - 1e-6);
  // Stopping short, or parallel but beside each other, they never touch.
  EXPECT_FALSE(edgeEdgeCcd(edges({0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {1.5, 1, 0},  //
                                 {0, 0, 0}, {1, 0, 0}, {0.5, 1e-3, 0}, {1.5, 1e-3, 0}))
                   .contact);
  EXPECT_FALSE(edgeEdgeCcd(edges({0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 1, 0},  //
                                 {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}))
                   .contact);
}

TEST(EdgeEdgeCcd, CollinearEdgesSlidingIntoEachOther) {
  const CcdResult r = edgeEdgeCcd(edges({0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {4, 0, 0},  //
                                        {0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 0, 0}));
  ASSERT_TRUE(r.contact);
  EXPECT_LE(r.timeOfImpact, 0.5);  // b0 reaches x = 1 at t = 0.5
  EXPECT_GE(r.timeOfImpact, 0.5 - 1e-6);
}

TEST(EdgeEdgeCcd, MotionlessSharedEndAndZeroLengthEdge) {
  const Vector3d a0(0, 0, 0), a1(1, 1, 1), b1(2, -1, 0);
  const CcdResult shared = edgeEdgeCcd(edges(a0, a1, a1, b1, a0, a1, a1, b1));
  ASSERT_TRUE(shared.contact);
  EXPECT_EQ(shared.timeOfImpact, 0.0);
  // A point moving through the middle of the other edge.
  EXPECT_TRUE(edgeEdgeCcd(edges({0.5, 0.5, 1}, {0.5, 0.5, 1}, a0, a1,  //
                                {0.5, 0.5, 0}, {0.5, 0.5, 0}, a0, a1))
                  .contact);
}

TEST(Ccd, BadOptionsAreRefused) {
  const MovingPrimitives m = vertexOverUnitTriangle({0, 0, 1}, {0, 0, -1});
  EXPECT_THROW(vertexFaceCcd(m, CcdOptions{.minimumSeparation = -1}), std::invalid_argument);
  MovingPrimitives broken = m;
  broken.end[2].x() = std::nan("");
  EXPECT_THROW(vertexFaceCcd(broken), std::invalid_argument);
}

// Seeded random motions with a planted exact contact at t = 1: the vertex arrives on a corner of
// the triangle, or an end of one edge arrives on an end of the other. None may be missed, and the
// time of impact is never after the planted one.
TEST(Ccd, PlantedContactsAreNeverMissed) {
  std::mt19937_64 random(12);
  std::uniform_real_distribution<double> coordinate(-3, 3);
  auto point = [&] { return Vector3d(coordinate(random), coordinate(random), coordinate(random)); };
  for (int i = 0; i < 300; ++i) {
    MovingPrimitives m;
    for (int k = 0; k < 4; ++k) {
      m.start[k] = point();
      m.end[k] = point();
    }
    const int corner = 1 + i % 3;
    m.end[0] = m.end[corner];
    EXPECT_TRUE(vertexFaceCcd(m).contact) << "vertex-face " << i;
    m.end[0] = m.end[2 + i % 2];
    EXPECT_TRUE(edgeEdgeCcd(m).contact) << "edge-edge " << i;
  }
}

// Seeded random falls through the plane z = 0, where the first contact is known: a vertex above
// a point of a triangle lying in the plane, and an edge parallel to the y axis across the x axis
// edge, both falling from z0 > 0 to z1 < 0, meeting at t = z0 / (z0 - z1). The time of impact is
// never after it, and close before it.
TEST(Ccd, TimeOfImpactIsNeverLate) {
  std::mt19937_64 random(56);
  std::uniform_real_distribution<double> unit(0, 1), above(0.01, 2), below(-2, 0),
      across(-0.9, 0.9);
  for (int i = 0; i < 200; ++i) {
    const double z0 = above(random), z1 = below(random);
    const double contact = z0 / (z0 - z1);
    const Vector3d f0(across(random), across(random), 0), f1(across(random), across(random), 0),
        f2(across(random), across(random), 0);
    double u = unit(random), v = unit(random);
    if (u + v > 1) {
      u = 1 - u;
      v = 1 - v;
    }
    // Kept off the edges, so that rounding cannot put the point outside.
    u = 0.05 + 0.9 * u;
    v = 0.05 + 0.9 * v;
    const Vector3d onFace = f0 + u * (f1 - f0) + v * (f2 - f0);
    MovingPrimitives fall;
    fall.start = {Vector3d(onFace.x(), onFace.y(), z0), f0, f1, f2};
    fall.end = {Vector3d(onFace.x(), onFace.y(), z1), f0, f1, f2};
    const CcdResult vf = vertexFaceCcd(fall);
    ASSERT_TRUE(vf.contact) << i;
    EXPECT_LE(vf.timeOfImpact, contact) << i;
    EXPECT_GE(vf.timeOfImpact, contact - 1e-4) << i;

    const double x = across(random);
    const CcdResult ee = edgeEdgeCcd(edges({-1, 0, 0}, {1, 0, 0}, {x, -1, z0}, {x, 1, z0},  //
                                           {-1, 0, 0}, {1, 0, 0}, {x, -1, z1}, {x, 1, z1}));
    ASSERT_TRUE(ee.contact) << i;
    EXPECT_LE(ee.timeOfImpact, contact) << i;
    EXPECT_GE(ee.timeOfImpact, contact - 1e-4) << i;
  }
}

// Seeded random motions where the two primitives stay in separate half-spaces x < 0 and x > 1:
// a contact reported there is a false positive of the kind that would stall a simulation.
TEST(Ccd, SeparatedMotionsAreNoContacts) {
  std::mt19937_64 random(34);
  std::uniform_real_distribution<double> coordinate(-3, 3), left(-3, -1e-6), right(1 + 1e-6, 4);
  for (int i = 0; i < 2000; ++i) {
    MovingPrimitives m;
    for (int k = 0; k < 4; ++k) {
      const bool first = k < 2;  // edge-edge: edge a on the left, edge b on the right
      for (auto* x : {&m.start[k], &m.end[k]}) {
        *x = Vector3d(first ? left(random) : right(random), coordinate(random), coordinate(random));
      }
    }
    EXPECT_FALSE(edgeEdgeCcd(m).contact) << i;
    m.start[1].x() = right(random);
    m.end[1].x() = right(random);  // vertex-face: only [0] on the left
    EXPECT_FALSE(vertexFaceCcd(m).contact) << i;
  }
}

// Seeded random near misses and contacts in a small cube, at separations from none to a third
// of the cube: a pair the plane test calls separated is never one the CCD finds in contact, and
// the test decides a good part of those the CCD finds none in (else it would be of no use).
TEST(Ccd, SeparatedOverStepNeverHidesAContact) {
  std::mt19937_64 random(78);
  std::uniform_real_distribution<double> coordinate(-1, 1), separation(0, 0.3), shift(-3, 3);
  int separated = 0, apart = 0, throughStep = 0;
  for (int i = 0; i < 4000; ++i) {
    MovingPrimitives m;
    const Vector3d offset(shift(random), shift(random), shift(random));
    for (int k = 0; k < 4; ++k) {
      m.start[k] = offset + Vector3d(coordinate(random), coordinate(random), coordinate(random));
      m.end[k] = m.start[k] + 0.3 * Vector3d(coordinate(random), coordinate(random), 0);
    }
    CcdOptions options;
    options.minimumSeparation = i % 4 == 0 ? 0.0 : separation(random);
    for (const bool vertexFace : {true, false}) {
      const bool contact =
          (vertexFace ? vertexFaceCcd(m, options) : edgeEdgeCcd(m, options)).contact;
      const bool planeApart = separatedOverStep(m, vertexFace, options);
      EXPECT_FALSE(contact && planeApart) << i << (vertexFace ? " vertex-face" : " edge-edge");
      // Each end on its own decides at least what the hulls of both do, never a contact.
      const bool apartAtEachEnd = separatedThroughStep(m, vertexFace, options);
      EXPECT_FALSE(contact && apartAtEachEnd) << i << (vertexFace ? " vertex-face" : " edge-edge");
      EXPECT_TRUE(apartAtEachEnd || !planeApart) << i;
      const Vector3d along = m.start[vertexFace ? 1 : 2] - m.start[0];
      EXPECT_FALSE(contact && separatedThroughStep(m, vertexFace, options, &along)) << i;
      throughStep += apartAtEachEnd;
      apart += !contact;
      separated += planeApart;
    }
  }
  EXPECT_GT(separated, apart / 4);
  EXPECT_GT(throughStep, separated);
}

std::filesystem::path publicQueries() {
  return std::filesystem::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "ccd-queries";
}

std::vector<std::filesystem::path> queryFiles(const std::filesystem::path& root) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    const std::string folder = entry.path().parent_path().filename().string();
    if (entry.path().extension() == ".csv" && (folder == "edge-edge" || folder == "vertex-face")) {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(PublicCcdQueries, NoCollisionIsMissed) {
  if (!std::filesystem::exists(publicQueries())) {
    GTEST_SKIP() << "no public CCD queries at " << publicQueries();
  }
  const std::vector<std::filesystem::path> files = queryFiles(publicQueries());
  ASSERT_FALSE(files.empty()) << "no query files under " << publicQueries();
  std::size_t queries = 0, colliding = 0, falsePositives = 0, exhausted = 0, checks = 0,
              planeSeparated = 0;
  for (const std::filesystem::path& path : files) {
    const CcdQueryFile file = readCcdQueryFile(path);
    for (const CcdQuery& query : file.queries) {
      const CcdResult result = runCcdQuery(file.kind, query);
      ++queries;
      colliding += query.collides;
      exhausted += result.budgetExhausted;
      checks += static_cast<std::size_t>(result.checks);
      CcdOptions options;
      options.minimumSeparation = 2 * query.roundingError;  // as runCcdQuery
      if (separatedOverStep(query.motion, file.kind == CcdQueryKind::VertexFace, options)) {
        ++planeSeparated;
        EXPECT_FALSE(result.contact) << path << ":" << query.line << ": separated, yet a contact";
      }
      if (separatedThroughStep(query.motion, file.kind == CcdQueryKind::VertexFace, options)) {
        EXPECT_FALSE(query.collides) << path << ":" << query.line << ": apart at each end, yet "
                                     << "a collision";
      }
      if (query.collides) {
        EXPECT_TRUE(result.contact) << path << ":" << query.line << ": a collision missed";
      } else {
        falsePositives += result.contact;
      }
    }
  }
  std::printf(
      "[   INFO   ] %zu queries (%zu colliding): %zu false positives, %zu out of budget, %.0f box "
      "checks a query; %zu separated by a plane before the search\n",
      queries, colliding, falsePositives, exhausted,
      static_cast<double>(checks) / static_cast<double>(queries), planeSeparated);
  RecordProperty("false_positives", static_cast<int>(falsePositives));
  EXPECT_GT(colliding, 0u);
  // A detector that answers "contact" to everything has no false negatives either.
  EXPECT_LT(falsePositives, (queries - colliding) / 10);
}

}  // namespace
}  // namespace hirsute::dynamics
