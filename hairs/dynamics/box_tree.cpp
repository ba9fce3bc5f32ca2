// A bounding-volume hierarchy of boxes per group, refitted from search to search.
#include "hirsute/hairs/dynamics/box_tree.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace hirsute::dynamics {
namespace {

constexpr int kLeafSize = 4;

// Whether the box holds anything: false for a box with a NaN coordinate, which overlaps nothing.
bool holdsPoints(const Box& box) {
  return (box.min.array() <= box.max.array()).all();
}

Box emptyBox() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {Eigen::Vector3d::Constant(inf), Eigen::Vector3d::Constant(-inf)};
}

// Where a box is for sorting: its centre, a coordinate that is not finite (an unbounded box)
// taken as 0. Only the tree's shape depends on it, never what a search finds.
Eigen::Vector3d centreOf(const Box& box) {
  Eigen::Vector3d c = 0.5 * (box.min + box.max);
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(c[k])) c[k] = 0;
  return c;
}

// The pairs of chunks filled on the threads, one chunk after the other.
std::vector<std::pair<int, int>> joined(
    const std::vector<std::vector<std::pair<int, int>>>& chunks) {
  std::size_t total = 0;
  for (const auto& chunk : chunks) total += chunk.size();
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(total);
  for (const auto& chunk : chunks) pairs.insert(pairs.end(), chunk.begin(), chunk.end());
  return pairs;
}

}  // namespace

void BoxTree::build(Tree& tree, const std::vector<Box>& boxes) {
  tree.nodes.clear();
  const int n = static_cast<int>(tree.order.size());
  if (n == 0) return;
  std::vector<Eigen::Vector3d> centres(boxes.size());
  for (int i : tree.order) centres[i] = centreOf(boxes[i]);
  struct Task {
    int node, begin, end;
  };
  tree.nodes.reserve(2 * (n / kLeafSize + 1));
  tree.nodes.emplace_back();
  std::vector<Task> tasks{{0, 0, n}};
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    Eigen::Array3d lo = Eigen::Array3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Array3d hi = -lo;
    for (int k = task.begin; k < task.end; ++k) {
      lo = lo.min(centres[tree.order[k]].array());
      hi = hi.max(centres[tree.order[k]].array());
    }
    int axis = 0;
    const double spread = (hi - lo).maxCoeff(&axis);
    if (task.end - task.begin <= kLeafSize || !(spread > 0)) {
      tree.nodes[task.node].first = task.begin;
      tree.nodes[task.node].count = task.end - task.begin;
      continue;
    }
    // Split at the median along the centres' widest spread (ties by box number: the same
    // boxes always make the same tree).
    const int middle = (task.begin + task.end) / 2;
    std::nth_element(tree.order.begin() + task.begin, tree.order.begin() + middle,
                     tree.order.begin() + task.end, [&](int a, int b) {
                       const double x = centres[a][axis], y = centres[b][axis];
                       return x < y || (x == y && a < b);
                     });
    const int child = static_cast<int>(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.nodes.emplace_back();
    tree.nodes[task.node].first = child;
    tree.nodes[task.node].count = 0;
    tasks.push_back({child, task.begin, middle});
    tasks.push_back({child + 1, middle, task.end});
  }
  ++builds_;
}

void BoxTree::refit(Tree& tree, const std::vector<Box>& boxes) {
  tree.leafBoxes.resize(tree.order.size());
  for (std::size_t k = 0; k < tree.order.size(); ++k) tree.leafBoxes[k] = boxes[tree.order[k]];
  // Children come after their parent: from the last node back, each node's children are done.
  for (int i = static_cast<int>(tree.nodes.size()) - 1; i >= 0; --i) {
    Node& node = tree.nodes[i];
    Box box = emptyBox();
    int largest = -1;
    const auto take = [&](const Box& b) {
      if (!holdsPoints(b)) return;
      box.min = box.min.cwiseMin(b.min);
      box.max = box.max.cwiseMax(b.max);
    };
    if (node.count > 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        take(tree.leafBoxes[k]);
        largest = std::max(largest, tree.order[k]);
      }
    } else {
      for (int c = node.first; c < node.first + 2; ++c) {
        take(tree.nodes[c].box);
        largest = std::max(largest, tree.nodes[c].largest);
      }
    }
    node.box = box;
    node.largest = largest;
  }
}

template <class Visit>
void BoxTree::forEachOverlapping(const Box& box, int group, const BoxGroups& groups, int above,
                                 std::vector<int>& stack, const Visit& visit) const {
  const auto moves = [&](int g) { return (groups.moving >> g) & 1; };
  if (!groups.pairsWith[group] || !holdsPoints(box)) return;
  for (int h = 0; h < 8; ++h) {
    if (!((groups.pairsWith[group] >> h) & 1) || (!moves(group) && !moves(h))) continue;
    const Tree& tree = trees_[h];
    if (tree.nodes.empty()) continue;
    stack.assign(1, 0);
    while (!stack.empty()) {
      const Node& node = tree.nodes[stack.back()];
      stack.pop_back();
      if (node.largest <= above || !node.box.overlaps(box)) continue;
      if (node.count == 0) {
        stack.push_back(node.first);
        stack.push_back(node.first + 1);
        continue;
      }
      for (int k = node.first; k < node.first + node.count; ++k)
        if (tree.leafBoxes[k].overlaps(box)) visit(tree.order[k]);
    }
  }
}

std::vector<std::pair<int, int>> BoxTree::overlappingPairs(
    const std::vector<Box>& boxes, const std::vector<char>& moving,
    const std::function<bool(int, int)>& wanted) {
  BoxGroups::ofMoving(moving, twoGroups_);
  return overlappingPairs(boxes, twoGroups_, wanted);
}

std::vector<std::pair<int, int>> BoxTree::overlappingPairs(
    const std::vector<Box>& boxes, const BoxGroups& groups,
    const std::function<bool(int, int)>& wanted) {
  treesHoldGrown_ = false;
  // A group has a tree when it pairs with anything; still groups too, so that every pair can be
  // found from its smaller box number, which makes the pairs come out sorted.
  const bool sameShape =
      groups.of == lastGroups_ && groups.moving == lastMoving_ && sinceBuild_ < kRefitsPerBuild;
  if (!sameShape) {
    for (Tree& tree : trees_) tree.order.clear();
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
      if (groups.pairsWith[groups.of[i]]) trees_[groups.of[i]].order.push_back(i);
    for (Tree& tree : trees_) build(tree, boxes);
    lastGroups_ = groups.of;
    lastMoving_ = groups.moving;
    sinceBuild_ = 0;
  } else {
    ++refits_;
    ++sinceBuild_;
  }
  for (Tree& tree : trees_) refit(tree, boxes);

  // Each box looks for the boxes of larger numbers it pairs with. Its pairs are sorted, and the
  // boxes' lists one after the other are the sorted list of all pairs.
  const auto search = [&](int i, std::vector<std::pair<int, int>>& out, std::vector<int>& stack) {
    const std::size_t start = out.size();
    forEachOverlapping(boxes[i], groups.of[i], groups, i, stack, [&](int j) {
      if (j > i && wanted(i, j)) out.emplace_back(i, j);
    });
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(start), out.end());
  };
  const std::size_t count = boxes.size();
  constexpr std::size_t kGrain = 512;
  std::vector<std::vector<std::pair<int, int>>> chunks((count + kGrain - 1) / kGrain);
  const auto searchChunk = [&](std::size_t begin, std::size_t end) {
    std::vector<int> stack;
    for (std::size_t b = begin; b < end; b += kGrain) {
      auto& out = chunks[b / kGrain];
      for (std::size_t i = b; i < std::min(end, b + kGrain); ++i)
        search(static_cast<int>(i), out, stack);
    }
  };
  if (pool_ != nullptr)
    pool_->forEach(count, kGrain, searchChunk);
  else
    searchChunk(0, count);
  return joined(chunks);
}

namespace {

bool within(const Box& box, const Box& grown) {
  return (box.min.array() >= grown.min.array()).all() &&
         (box.max.array() <= grown.max.array()).all();
}

Box grownBy(const Box& box, double slack) {
  return {(box.min.array() - slack).matrix(), (box.max.array() + slack).matrix()};
}

}  // namespace

void BoxTree::searchList(const std::vector<Box>& boxes, const BoxGroups& groups,
                         const KeptList& list) {
  grown_.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) grown_[i] = grownBy(boxes[i], list.slack);
  grownVertices_.clear();
  if (list.vertices != nullptr)
    for (const Box& vertex : *list.vertices) grownVertices_.push_back(grownBy(vertex, list.slack));
  // Each vertex within the slack of where it is: the two sides' allowances are twice it.
  const double strays = 2 * list.slack;
  kept_ = overlappingPairs(grown_, groups, [&](int a, int b) {
    return list.tested(a, b) && !(list.apart && list.apart(a, b, strays));
  });
  treesHoldGrown_ = true;
  repairedBoxes_ = 0;
  ++listSearches_;
}

bool BoxTree::repairList(const std::vector<Box>& boxes, const BoxGroups& groups,
                         const KeptList& list) {
  if (list.boxParts == nullptr || !treesHoldGrown_) return false;
  const std::vector<int>& boxParts = *list.boxParts;
  const std::vector<Box>* vertices = list.vertices;
  const std::vector<int>* vertexParts = list.vertexParts;
  if (boxParts.size() != boxes.size() ||
      (vertices != nullptr && (vertexParts == nullptr || vertexParts->size() != vertices->size())))
    return false;
  int parts = 0;
  for (int part : boxParts) parts = std::max(parts, part + 1);
  if (vertexParts != nullptr)
    for (int part : *vertexParts) parts = std::max(parts, part + 1);
  // The parts a box or vertex of which left its grown box (a box with a NaN overlaps nothing,
  // wherever it is).
  std::vector<char> left(parts, 0);
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (holdsPoints(boxes[i]) && !within(boxes[i], grown_[i])) left[boxParts[i]] = 1;
  if (vertices != nullptr)
    for (std::size_t v = 0; v < vertices->size(); ++v)
      if (!within((*vertices)[v], grownVertices_[v])) left[(*vertexParts)[v]] = 1;
  std::vector<int> moved;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
    if (left[boxParts[i]]) moved.push_back(i);
  // Most of the coat moving is searched faster whole; and pairs found by a repair may be kept
  // that a search would leave out (the allowance of a part that stayed is larger), so after
  // as many boxes searched again as there are, the list is made anew.
  repairedBoxes_ += moved.size();
  if (4 * moved.size() > boxes.size() || repairedBoxes_ > boxes.size()) return false;

  // How far each part that stayed may still go, in every coordinate, from where its vertices
  // are now: to the far side of their grown boxes.
  std::vector<double> allowance(parts, list.slack);
  if (vertices != nullptr)
    for (std::size_t v = 0; v < vertices->size(); ++v) {
      const int part = (*vertexParts)[v];
      if (left[part]) continue;
      const Box& now = (*vertices)[v];
      const Box& grown = grownVertices_[v];
      allowance[part] = std::max(
          {allowance[part], (grown.max - now.max).maxCoeff(), (now.min - grown.min).maxCoeff()});
    }
  for (int i : moved) grown_[i] = grownBy(boxes[i], list.slack);
  if (vertices != nullptr)
    for (std::size_t v = 0; v < vertices->size(); ++v)
      if (left[(*vertexParts)[v]]) grownVertices_[v] = grownBy((*vertices)[v], list.slack);
  std::erase_if(kept_, [&](const std::pair<int, int>& pair) {
    return left[boxParts[pair.first]] || left[boxParts[pair.second]];
  });
  for (Tree& tree : trees_) refit(tree, grown_);

  // Each moved box against every grown box of the groups it pairs with; a pair of two moved
  // boxes from the smaller.
  const auto search = [&](int i, std::vector<std::pair<int, int>>& out, std::vector<int>& stack) {
    forEachOverlapping(grown_[i], groups.of[i], groups, -1, stack, [&](int j) {
      const bool bothMoved = left[boxParts[j]];
      if (j == i || (bothMoved && j < i)) return;
      const int a = std::min(i, j), b = std::max(i, j);
      const double strays = list.slack + (bothMoved ? list.slack : allowance[boxParts[j]]);
      if (list.tested(a, b) && !(list.apart && list.apart(a, b, strays))) out.emplace_back(a, b);
    });
  };
  constexpr std::size_t kGrain = 256;
  std::vector<std::vector<std::pair<int, int>>> chunks((moved.size() + kGrain - 1) / kGrain);
  forEach(pool_, moved.size(), kGrain, [&](std::size_t begin, std::size_t end) {
    std::vector<int> stack;
    for (std::size_t b = begin; b < end; b += kGrain) {
      auto& out = chunks[b / kGrain];
      for (std::size_t k = b; k < std::min(end, b + kGrain); ++k) search(moved[k], out, stack);
    }
  });
  std::vector<std::pair<int, int>> found = joined(chunks);
  std::sort(found.begin(), found.end());
  const auto middle = static_cast<std::ptrdiff_t>(kept_.size());
  kept_.insert(kept_.end(), found.begin(), found.end());
  std::inplace_merge(kept_.begin(), kept_.begin() + middle, kept_.end());
  ++listRepairs_;
  return true;
}

std::vector<std::pair<int, int>> BoxTree::coherentPairs(
    const std::vector<Box>& boxes, const BoxGroups& groups, const KeptList& list,
    const std::function<bool(int, int)>& wanted) {
  if (list.apart && list.vertices == nullptr)
    throw std::invalid_argument("a kept list's plane test needs the vertices' boxes");
  const bool sameList = keptValid_ && list.version == keptVersion_ && groups.of == keptGroups_ &&
                        groups.pairsWith == keptPairsWith_ && groups.moving == keptMoving_ &&
                        grown_.size() == boxes.size() &&
                        (list.vertices == nullptr ? grownVertices_.empty()
                                                  : list.vertices->size() == grownVertices_.size());
  bool inside = sameList;
  // (A box with a NaN overlaps nothing, wherever it is.)
  for (std::size_t i = 0; inside && i < boxes.size(); ++i)
    inside = !holdsPoints(boxes[i]) || within(boxes[i], grown_[i]);
  for (std::size_t v = 0; inside && list.vertices != nullptr && v < list.vertices->size(); ++v)
    inside = within((*list.vertices)[v], grownVertices_[v]);
  if (inside) {
    ++listFilters_;
  } else if (!(sameList && repairList(boxes, groups, list))) {
    searchList(boxes, groups, list);
    keptGroups_ = groups.of;
    keptPairsWith_ = groups.pairsWith;
    keptMoving_ = groups.moving;
    keptVersion_ = list.version;
    keptValid_ = true;
  }
  // The kept list is sorted; its chunks filtered one after the other stay so.
  constexpr std::size_t kGrain = 4096;
  std::vector<std::vector<std::pair<int, int>>> chunks((kept_.size() + kGrain - 1) / kGrain);
  forEach(pool_, kept_.size(), kGrain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; b += kGrain) {
      auto& out = chunks[b / kGrain];
      for (std::size_t k = b; k < std::min(end, b + kGrain); ++k) {
        const auto [i, j] = kept_[k];
        if (boxes[i].overlaps(boxes[j]) && wanted(i, j)) out.emplace_back(i, j);
      }
    }
  });
  return joined(chunks);
}

}  // namespace hirsute::dynamics
