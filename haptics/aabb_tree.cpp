// aabb_tree.cpp — median-split build and box query of the static BVH.
#include "haptics/aabb_tree.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace contactlab {

namespace {
constexpr double kTwoPiTree = 6.283185307179586;
double wrap_0_2pi(double a) {
    a = std::fmod(a, kTwoPiTree);
    return a < 0.0 ? a + kTwoPiTree : a;
}
}  // namespace

NormalCone merge_cones(const NormalCone& a, const NormalCone& b) {
    if (a.width < 0.0) return b;
    if (b.width < 0.0) return a;
    if (a.width >= kTwoPiTree || b.width >= kTwoPiTree) return {0.0, kTwoPiTree};
    // The smallest covering arc starts at one of the two starts.
    const double from_a = std::max(a.width, wrap_0_2pi(b.start - a.start) + b.width);
    const double from_b = std::max(b.width, wrap_0_2pi(a.start - b.start) + a.width);
    NormalCone c = from_a <= from_b ? NormalCone{a.start, from_a} : NormalCone{b.start, from_b};
    if (c.width >= kTwoPiTree) c = {0.0, kTwoPiTree};
    return c;
}

AabbTree::AabbTree(const std::vector<Aabb>& item_boxes) {
    items_.resize(item_boxes.size());
    std::iota(items_.begin(), items_.end(), 0);
    if (!items_.empty()) {
        nodes_.reserve(2 * items_.size() / kLeafSize + 2);
        build(item_boxes, nullptr, 0, static_cast<int>(items_.size()));
    }
}

AabbTree::AabbTree(const std::vector<Aabb>& item_boxes, const std::vector<NormalCone>& item_normals) {
    items_.resize(item_boxes.size());
    std::iota(items_.begin(), items_.end(), 0);
    if (!items_.empty()) {
        nodes_.reserve(2 * items_.size() / kLeafSize + 2);
        build(item_boxes, &item_normals, 0, static_cast<int>(items_.size()));
    }
}

int AabbTree::build(const std::vector<Aabb>& boxes, const std::vector<NormalCone>* normals, int first, int count) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Aabb box;
    NormalCone cone = normals ? NormalCone{} : NormalCone{0.0, kTwoPiTree};
    for (int i = first; i < first + count; ++i) {
        box.grow(boxes[items_[i]]);
        if (normals) cone = merge_cones(cone, (*normals)[static_cast<std::size_t>(items_[i])]);
    }
    nodes_[index].box = box;
    nodes_[index].normals = cone;
    if (count <= kLeafSize) {
        nodes_[index].first = first;
        nodes_[index].count = count;
        return index;
    }
    // Split at the median of box centres along the longer axis: balanced, so depth ~ log2(N/4)
    // stays far below kMaxDepth even for a million segments.
    const Vec2 extent = box.hi - box.lo;
    const int axis = extent.x >= extent.y ? 0 : 1;
    const int half = count / 2;
    std::nth_element(items_.begin() + first, items_.begin() + first + half,
                     items_.begin() + first + count, [&](int a, int b) {
                         return boxes[a].center()[axis] < boxes[b].center()[axis];
                     });
    const int left = build(boxes, normals, first, half);
    const int right = build(boxes, normals, first + half, count - half);
    nodes_[index].left = left;
    nodes_[index].right = right;
    return index;
}

void AabbTree::query(const Aabb& box, std::vector<int>& out) const {
    if (nodes_.empty()) return;
    int stack[kMaxDepth * 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        if (!n.box.overlaps(box)) continue;
        if (n.left < 0) {
            for (int i = n.first; i < n.first + n.count; ++i) out.push_back(items_[i]);
            continue;
        }
        stack[top++] = n.left;
        stack[top++] = n.right;
    }
}

// Bounding box of the arc {p + r u(theta) : theta in [start, start + width]}: its ends and the
// axis extremes it passes.
namespace {
Aabb arc_box(Vec2 p, double r, double start, double width) {
    Aabb b;
    b.grow(p + r * Vec2{std::cos(start), std::sin(start)});
    b.grow(p + r * Vec2{std::cos(start + width), std::sin(start + width)});
    for (int k = 0; k < 4; ++k) {
        const double axis = k * 0.25 * kTwoPiTree;
        if (wrap_0_2pi(axis - start) <= width) b.grow(p + r * Vec2{std::cos(axis), std::sin(axis)});
    }
    return b;
}
double max_distance(const Aabb& b, Vec2 p) {
    const Vec2 d = glm::max(glm::abs(p - b.lo), glm::abs(b.hi - p));
    return glm::length(d);
}
double box_gap(const Aabb& a, const Aabb& b) {
    const Vec2 d = glm::max(glm::max(a.lo - b.hi, b.lo - a.hi), Vec2(0.0));
    return glm::length(d);
}
}  // namespace

void AabbTree::query_offset_reach(Vec2 p, double r, double reach, std::vector<int>& out) const {
    if (nodes_.empty()) return;
    int stack[kMaxDepth * 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        if (n.box.distance_to(p) > r + reach) continue;
        if (n.normals.width < 0.5 * kTwoPiTree) {
            // q + r n within reach of p  <=>  q within reach of p - r n: the node's box must come
            // within reach of the arc of points p - r n, n in the cone.
            if (box_gap(arc_box(p, r, n.normals.start + 0.5 * kTwoPiTree, n.normals.width), n.box) > reach) continue;
        } else if (max_distance(n.box, p) < r - reach) {
            continue;  // every q within r - reach of p: |q + r n - p| >= r - |q - p| > reach
        }
        if (n.left < 0) {
            for (int i = n.first; i < n.first + n.count; ++i) out.push_back(items_[i]);
            continue;
        }
        stack[top++] = n.left;
        stack[top++] = n.right;
    }
}

}  // namespace contactlab
