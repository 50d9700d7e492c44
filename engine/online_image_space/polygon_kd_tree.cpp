#include "engine/online_image_space/polygon_kd_tree.hpp"

#include <algorithm>
#include <stdexcept>

namespace cullcheck::online {
namespace {

double coordinate(Vec2 p, int axis) { return axis == 0 ? p.x : p.y; }

}  // namespace

PolygonKdTree::PolygonKdTree(const ScenePolygons& polygons, std::uint32_t leaf_size)
    : polygons_(polygons), leaf_size_(std::max<std::uint32_t>(1, leaf_size)), leaf_of_(polygons.size(), -1) {
  std::vector<std::uint32_t> items(polygons.size());
  for (std::uint32_t i = 0; i < items.size(); ++i) items[i] = i;
  nodes_.reserve(2 * (items.size() / leaf_size_ + 1));
  build(items, 0, items.size(), -1);
}

std::int32_t PolygonKdTree::build(std::vector<std::uint32_t>& items, std::size_t begin, std::size_t end, std::int32_t parent,
                                  std::int32_t reuse) {
  std::int32_t index = reuse;
  if (index < 0) {
    index = static_cast<std::int32_t>(nodes_.size());
    nodes_.emplace_back();
  }
  nodes_[index].parent = parent;
  nodes_[index].child[0] = nodes_[index].child[1] = -1;
  Box3 box;
  Box2 anchors;
  for (std::size_t i = begin; i < end; ++i) {
    const Box3& b = polygons_.box[items[i]];
    box.extend(b.lo), box.extend(b.hi), anchors.extend(polygons_.anchor(items[i]));
  }
  nodes_[index].box = box;
  nodes_[index].count = static_cast<std::uint32_t>(end - begin);
  const bool all_at_one_point = end > begin && anchors.lo == anchors.hi;
  if (end - begin <= leaf_size_ || all_at_one_point) {
    std::vector<std::uint32_t> mine(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(end));
    std::sort(mine.begin(), mine.end());
    for (std::uint32_t p : mine) leaf_of_[p] = index;
    nodes_[index].polygons = std::move(mine);
    return index;
  }
  const int axis = anchors.hi.x - anchors.lo.x >= anchors.hi.y - anchors.lo.y ? 0 : 1;
  // The anchor coordinate, then the polygon index: a total order, so the halves do not depend on
  // how nth_element arranges equal keys.
  const auto before = [&](std::uint32_t a, std::uint32_t b) {
    const double ca = coordinate(polygons_.anchor(a), axis), cb = coordinate(polygons_.anchor(b), axis);
    return ca < cb || (ca == cb && a < b);
  };
  std::size_t mid = begin + (end - begin) / 2;
  std::nth_element(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(mid), items.begin() + std::ptrdiff_t(end), before);
  const double split = coordinate(polygons_.anchor(items[mid]), axis);
  // Anchors equal to the splitter go right, as insertion routes them: move the left half's
  // copies of the split value over (they are the largest of that half).
  std::sort(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(mid), before);
  while (mid > begin && coordinate(polygons_.anchor(items[mid - 1]), axis) == split) --mid;
  if (mid == begin) {  // every anchor of the lower half equals the splitter: split above it instead
    std::sort(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(end), before);
    while (mid < end && coordinate(polygons_.anchor(items[mid]), axis) == split) ++mid;
    if (mid == end) {  // unreachable (the anchors differ along `axis`), kept as a leaf for safety
      std::vector<std::uint32_t> mine(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(end));
      std::sort(mine.begin(), mine.end());
      for (std::uint32_t p : mine) leaf_of_[p] = index;
      nodes_[index].polygons = std::move(mine);
      return index;
    }
    nodes_[index].split = coordinate(polygons_.anchor(items[mid]), axis);
  } else {
    nodes_[index].split = split;
  }
  nodes_[index].axis = axis;
  const std::int32_t left = build(items, begin, mid, index);
  const std::int32_t right = build(items, mid, end, index);
  nodes_[index].child[0] = left;
  nodes_[index].child[1] = right;
  return index;
}

void PolygonKdTree::insert(std::uint32_t polygon) {
  if (polygon >= polygons_.size()) throw std::out_of_range("kd-tree insert: no polygon " + std::to_string(polygon));
  if (leaf_of_.size() < polygons_.size()) leaf_of_.resize(polygons_.size(), -1);
  if (leaf_of_[polygon] >= 0) throw std::invalid_argument("kd-tree insert: polygon " + std::to_string(polygon) + " is already in");
  const Box3& b = polygons_.box[polygon];
  const Vec2 anchor = polygons_.anchor(polygon);
  std::int32_t n = 0;
  for (;;) {
    Node& node = nodes_[std::size_t(n)];
    node.box.extend(b.lo), node.box.extend(b.hi);
    ++node.count;
    // Its box grew, so its stamp no longer holds; the children's boxes were behind the mask as
    // part of it, so they take the stamp and only the one on the way down loses it next.
    if (!node.leaf())
      for (std::int32_t c : node.child) nodes_[std::size_t(c)].stamp = std::max(nodes_[std::size_t(c)].stamp, node.stamp);
    node.stamp = -std::numeric_limits<double>::infinity();
    if (node.leaf()) break;
    n = node.child[coordinate(anchor, node.axis) < node.split ? 0 : 1];
  }
  auto& list = nodes_[std::size_t(n)].polygons;
  list.insert(std::upper_bound(list.begin(), list.end(), polygon), polygon);
  leaf_of_[polygon] = n;
  if (list.size() <= 2 * std::size_t(leaf_size_)) return;
  // Split the full leaf where it stands: its polygons become a subtree rooted in the same node
  // (so the parent's child index stays right), keeping its box and time stamp.
  std::vector<std::uint32_t> items = std::move(nodes_[std::size_t(n)].polygons);
  nodes_[std::size_t(n)].polygons.clear();
  const Box3 box = nodes_[std::size_t(n)].box;
  build(items, 0, items.size(), nodes_[std::size_t(n)].parent, n);
  nodes_[std::size_t(n)].box = box;
}

void PolygonKdTree::erase(std::uint32_t polygon) {
  if (!alive(polygon)) throw std::invalid_argument("kd-tree erase: polygon " + std::to_string(polygon) + " is not in the tree");
  std::int32_t n = leaf_of_[polygon];
  auto& list = nodes_[std::size_t(n)].polygons;
  list.erase(std::lower_bound(list.begin(), list.end(), polygon));
  leaf_of_[polygon] = -1;
  for (; n >= 0; n = nodes_[std::size_t(n)].parent) --nodes_[std::size_t(n)].count;
}

}  // namespace cullcheck::online
