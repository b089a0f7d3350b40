// aabb_tree.cpp — median-split build and box query of the static BVH.
#include "haptics/aabb_tree.hpp"

#include <algorithm>
#include <numeric>

namespace contactlab {

AabbTree::AabbTree(const std::vector<Aabb>& item_boxes) {
    items_.resize(item_boxes.size());
    std::iota(items_.begin(), items_.end(), 0);
    if (!items_.empty()) {
        nodes_.reserve(2 * items_.size() / kLeafSize + 2);
        build(item_boxes, 0, static_cast<int>(items_.size()));
    }
}

int AabbTree::build(const std::vector<Aabb>& boxes, int first, int count) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Aabb box;
    for (int i = first; i < first + count; ++i) box.grow(boxes[items_[i]]);
    nodes_[index].box = box;
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
    const int left = build(boxes, first, half);
    const int right = build(boxes, first + half, count - half);
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

}  // namespace contactlab
