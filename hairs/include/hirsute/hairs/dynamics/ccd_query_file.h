// The CCD query files of Wang et al. 2021's benchmark (docs/design.md, "Tests and CI"): eight
// rows per query, each a vertex as three exact rationals and the ground truth; the query kind is
// the name of the folder the file is in (`edge-edge` or `vertex-face`). Read for
// `hirsute bench ccd` and the tests.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "hirsute/hairs/dynamics/continuous_collision.h"

namespace hirsute::dynamics {

enum class CcdQueryKind { VertexFace, EdgeEdge };

struct CcdQuery {
  // The rows in the file's order: the four vertices at t = 0, then at t = 1, each coordinate the
  // double nearest to its rational.
  MovingPrimitives motion;
  // The largest distance, over the 24 coordinates, between a rational and its double (rounded
  // up): the exact query and the rounded one differ by at most twice this in F (the two
  // primitives each move by at most it), so a minimum separation of twice this covers the
  // rounding.
  double roundingError = 0;
  bool collides = false;  // the ground truth
  int line = 0;           // the line of its first row
};

struct CcdQueryFile {
  CcdQueryKind kind = CcdQueryKind::VertexFace;
  std::vector<CcdQuery> queries;
};

// Limits: a line longer than this, or an integer of more digits, is an error.
inline constexpr std::size_t kMaxCcdQueryLineLength = 4096;
inline constexpr std::size_t kMaxCcdQueryDigits = 400;

// Throws DiagnosticError (`file:line:col: error: …`) for an unreadable file or one that is no
// regular file (a FIFO or a device, refused before it is read), a folder that names
// no query kind, a row that is not 7 comma-separated integers, a zero denominator, a ground truth
// that is not 0 or 1 or differs between a query's rows, a coordinate beyond the range of double,
// and a row count that is not a multiple of 8.
CcdQueryFile readCcdQueryFile(const std::filesystem::path& path);

// The CCD of the query's kind with a minimum separation of `eta` plus twice the query's rounding
// error, so that an exact query that collides is never missed.
CcdResult runCcdQuery(CcdQueryKind kind, const CcdQuery& query, CcdOptions options = {});

}  // namespace hirsute::dynamics
