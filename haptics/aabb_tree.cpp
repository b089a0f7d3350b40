// aabb_tree.cpp — median-split build and box query of the static BVH.
#include "haptics/aabb_tree.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace contactlab {

NormalCone merge_cones(const NormalCone& a, const NormalCone& b) {
    if (a.width < 0.0) return b;
    if (b.width < 0.0) return a;
    if (a.width >= kTwoPi || b.width >= kTwoPi) return {0.0, kTwoPi};
    // The smallest covering arc starts at one of the two starts.
    const double from_a = std::max(a.width, wrap_2pi(b.start - a.start) + b.width);
    const double from_b = std::max(b.width, wrap_2pi(a.start - b.start) + a.width);
    NormalCone c = from_a <= from_b ? NormalCone{a.start, from_a} : NormalCone{b.start, from_b};
    if (c.width >= kTwoPi) c = {0.0, kTwoPi};
    return c;
}

AabbTree::AabbTree(const std::vector<Aabb>& item_boxes) {
    items_.resize(item_boxes.size());
    std::iota(items_.begin(), items_.end(), 0);
    if (!items_.empty()) {
        nodes_.reserve(2 * items_.size() / kLeafSize + 2);
        build(item_boxes, nullptr, nullptr, nullptr, 0, static_cast<int>(items_.size()));
    }
}

AabbTree::AabbTree(const std::vector<Aabb>& item_boxes, const std::vector<NormalCone>& item_normals) {
    items_.resize(item_boxes.size());
    std::iota(items_.begin(), items_.end(), 0);
    if (!items_.empty()) {
        nodes_.reserve(2 * items_.size() / kLeafSize + 2);
        build(item_boxes, &item_normals, nullptr, nullptr, 0, static_cast<int>(items_.size()));
    }
}

AabbTree::AabbTree(const std::vector<Aabb>& item_boxes, const std::vector<NormalCone>& item_normals,
                   const std::vector<OffsetBoxes>& item_offsets, double rho)
    : AabbTree(item_boxes, item_normals, item_offsets, rho, {}) {}

AabbTree::AabbTree(const std::vector<Aabb>& item_boxes, const std::vector<NormalCone>& item_normals,
                   const std::vector<OffsetBoxes>& item_offsets, double rho, const std::vector<double>& item_outer_limits)
    : has_offsets_(true), rho_(rho) {
    items_.resize(item_boxes.size());
    std::iota(items_.begin(), items_.end(), 0);
    const std::vector<double>* limits = item_outer_limits.empty() ? nullptr : &item_outer_limits;
    if (!items_.empty()) {
        nodes_.reserve(2 * items_.size() / kLeafSize + 2);
        build(item_boxes, &item_normals, &item_offsets, limits, 0, static_cast<int>(items_.size()));
    }
    if (limits) {
        item_outer_limits_.reserve(items_.size());
        for (const int i : items_) item_outer_limits_.push_back((*limits)[static_cast<std::size_t>(i)]);
    }
    // In leaf order, beside items_: a leaf's items are read together.
    item_boxes_.reserve(items_.size());
    item_offsets_.reserve(items_.size());
    item_normals_.reserve(items_.size());
    for (const int i : items_) {
        item_boxes_.push_back(item_boxes[static_cast<std::size_t>(i)]);
        item_offsets_.push_back(item_offsets[static_cast<std::size_t>(i)]);
        item_normals_.push_back(item_normals[static_cast<std::size_t>(i)]);
    }
}

int AabbTree::build(const std::vector<Aabb>& boxes, const std::vector<NormalCone>* normals,
                    const std::vector<OffsetBoxes>* offsets, const std::vector<double>* limits, int first, int count) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Aabb box;
    OffsetBoxes offset;
    Aabb outer_firm;
    double outer_limit = 0.0;  // m
    NormalCone cone = normals ? NormalCone{} : NormalCone{0.0, kTwoPi};
    for (int i = first; i < first + count; ++i) {
        const auto item = static_cast<std::size_t>(items_[i]);
        box.grow(boxes[item]);
        if (normals) cone = merge_cones(cone, (*normals)[item]);
        if (offsets) {
            offset.outer.grow((*offsets)[item].outer);
            offset.inner.grow((*offsets)[item].inner);
            const double limit = limits ? (*limits)[item] : std::numeric_limits<double>::infinity();
            if (limit == std::numeric_limits<double>::infinity()) outer_firm.grow((*offsets)[item].outer);
            else outer_limit = std::max(outer_limit, limit);
        }
    }
    nodes_[index].box = box;
    nodes_[index].offset = offset;
    nodes_[index].outer_firm = outer_firm;
    nodes_[index].outer_limit = outer_limit;
    nodes_[index].normals = cone;
    if (cone.width >= 0.0 && cone.width < kPi) {
        nodes_[index].cone_from = unit_at(cone.start);
        nodes_[index].cone_to = unit_at(cone.start + cone.width);
        for (int k = 0; k < 4; ++k)
            if (wrap_2pi(0.5 * kPi * k - cone.start) <= cone.width) nodes_[index].cone_axes |= std::uint8_t(1u << k);
    }
    if (count <= kLeafSize) {
        nodes_[index].first = first;
        nodes_[index].count = count;
        // Ascending within the leaf: a query walking leaves in the contour's order then returns
        // sorted ids, which the proxy then only has to check (collect()).
        std::sort(items_.begin() + first, items_.begin() + first + count);
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
    const int left = build(boxes, normals, offsets, limits, first, half);
    const int right = build(boxes, normals, offsets, limits, first + half, count - half);
    nodes_[index].left = left;
    nodes_[index].right = right;
    return index;
}

namespace {
bool cone_holds(const NormalCone& outer, const NormalCone& inner) {
    if (inner.width < 0.0 || outer.width >= kTwoPi) return true;
    if (outer.width < 0.0) return false;
    constexpr double kRounding = 1e-12;  // rad: merge_cones' wraps
    return wrap_2pi(inner.start - outer.start + kRounding) + inner.width <= outer.width + 2.0 * kRounding;
}
}  // namespace

bool AabbTree::consistent(const std::vector<Aabb>& item_boxes) const {
    if (items_.size() != item_boxes.size()) return false;
    std::vector<char> seen(items_.size(), 0);
    for (const int i : items_) {
        if (i < 0 || i >= static_cast<int>(seen.size()) || seen[static_cast<std::size_t>(i)]) return false;
        seen[static_cast<std::size_t>(i)] = 1;
    }
    if (items_.empty()) return nodes_.empty();
    // Each node against every item below it (a subtree's items are one run of items_). Cones are
    // checked against the items, not the children: merge_cones is not associative, so a child
    // merged in another order may hold a wider cone than its parent, both holding every item.
    bool ok = true;
    auto check = [&](auto&& self, int index, int depth) -> std::pair<int, int> {  // [first, end) of items_
        if (index < 0 || index >= static_cast<int>(nodes_.size()) || depth > 64) {
            ok = false;
            return {0, 0};
        }
        const Node& n = nodes_[static_cast<std::size_t>(index)];
        std::pair<int, int> range{n.first, n.first + n.count};
        if (n.left >= 0) {
            const auto l = self(self, n.left, depth + 1), r = self(self, n.right, depth + 1);
            if (l.second != r.first) ok = false;
            range = {l.first, r.second};
        }
        for (int k = range.first; k < range.second && ok; ++k) {
            const auto at = static_cast<std::size_t>(k);
            ok = n.box.contains(item_boxes[static_cast<std::size_t>(items_[at])]);
            if (has_offsets_)  // the per-item arrays are in leaf order
                ok = ok && n.box.contains(item_boxes_[at]) && n.offset.outer.contains(item_offsets_[at].outer) &&
                     n.offset.inner.contains(item_offsets_[at].inner) && cone_holds(n.normals, item_normals_[at]) &&
                     (item_outer_limits_.empty() || item_outer_limits_[at] <= n.outer_limit ||
                      n.outer_firm.contains(item_offsets_[at].outer));
        }
        return range;
    };
    const auto all = check(check, 0, 0);
    return ok && all.first == 0 && all.second == static_cast<int>(items_.size());
}

void AabbTree::query(const Aabb& box, std::vector<int>& out) const {
    collect([&](const Node& n) { return n.box.overlaps(box); }, [](const Node&, int) { return true; }, out);
}

Aabb arc_bounds(Vec2 c, double r, double start, double width) {
    Aabb b;
    b.grow(c + r * unit_at(start));
    b.grow(c + r * unit_at(start + width));
    for (int k = 0; k < 4; ++k) {
        const double axis = 0.5 * kPi * k;
        if (wrap_2pi(axis - start) <= width) b.grow(c + r * unit_at(axis));
    }
    return b;
}

Aabb AabbTree::cone_sweep(const Node& n, double d) {
    Aabb sweep;  // the box of d n over the cone
    if (n.normals.width < kPi) {
        sweep.grow(d * n.cone_from);
        sweep.grow(d * n.cone_to);
        if (n.cone_axes & 1u) sweep.grow(Vec2{d, 0.0});
        if (n.cone_axes & 2u) sweep.grow(Vec2{0.0, d});
        if (n.cone_axes & 4u) sweep.grow(Vec2{-d, 0.0});
        if (n.cone_axes & 8u) sweep.grow(Vec2{0.0, -d});
    } else {
        sweep = Aabb{Vec2(-std::abs(d)), Vec2(std::abs(d))};
    }
    return sweep;
}

Aabb AabbTree::moved_offset(const Node& n, const OffsetBoxes& at_rho, double r, double side) const {
    return moved_box(n, side > 0.0 ? at_rho.outer : at_rho.inner, r, side);
}

Aabb AabbTree::moved_box(const Node& n, const Aabb& box, double r, double side) const {
    // q + r n = (q + rho n) + (r - rho) n, and q - r n = (q - rho n) - (r - rho) n: the offset box
    // at rho, moved by d n for every n of the node's cone (which holds its items' cones).
    const double d = side > 0.0 ? r - rho_ : rho_ - r;  // m
    if (d == 0.0) return box;
    const Aabb sweep = cone_sweep(n, d);
    return Aabb{box.lo + sweep.lo, box.hi + sweep.hi};
}

Aabb AabbTree::offset_box(const Node& n, double r, double side) const {
    if (!has_offsets_) return n.box.grown(r);
    // Under a pad at least as wide as every limited item's limit, only the firm items have outer
    // pieces (with no limited item below, outer_firm is offset.outer, the same bits).
    if (side > 0.0 && r >= n.outer_limit) return moved_box(n, n.outer_firm, r, side);
    return moved_offset(n, n.offset, r, side);
}

// Every piece's point is a place of the finger where the pad (radius r) touches the piece's
// segment, so within r of it and of any box holding the segment: no piece is nearer p than the
// box's distance less r. The offset boxes above are swept over the items' normal cones, so where
// those are wide (a jittered floor's segments lean every way) they reach r sideways and bound
// nothing off to the side; this one does.
// Returns the greater of that and `lower` (m), with no square root when `lower` is the greater.
// Only where the items' normals spread wider than kWideCone: under a narrower cone the offset box
// is the tighter bound already, and asking this one too cost 8 % of a hover over dense arcs.
namespace {
constexpr double kWideCone = 0.5;  // rad
double max_with_reach_bound(double lower, const Aabb& box, const NormalCone& normals, Vec2 p, double r) {
    if (normals.width <= kWideCone) return lower;
    const double d2 = box.distance_squared_to(p);  // m^2
    const double at_least = lower + r;              // m
    if (at_least * at_least >= d2) return lower;
    return std::max(lower, std::sqrt(d2) - r);
}
}  // namespace

double AabbTree::pad_lower_bound(const Node& n, Vec2 p, double r, bool inner, const Vec2* ends, int end_count,
                                 const PadNormals& normals) const {
    double lower = std::numeric_limits<double>::infinity();
    if (cones_meet(n.normals, normals.outer)) lower = offset_box(n, r, 1.0).distance_to(p);
    if (inner && cones_meet(n.normals, normals.inner)) lower = std::min(lower, offset_box(n, r, -1.0).distance_to(p));
    for (int k = 0; k < end_count; ++k) lower = std::min(lower, n.box.distance_to(ends[k]));
    return max_with_reach_bound(lower, n.box, n.normals, p, r);
}

double AabbTree::item_lower_bound(const Node& leaf, int position, Vec2 p, double r, bool inner, const Vec2* ends,
                                  int end_count, const PadNormals& normals) const {
    if (!has_offsets_) return 0.0;
    const auto pos = static_cast<std::size_t>(position);
    double lower = std::numeric_limits<double>::infinity();
    if (item_outer_at(pos, r) && cones_meet(item_normals_[pos], normals.outer))
        lower = moved_offset(leaf, item_offsets_[pos], r, 1.0).distance_to(p);
    if (inner && cones_meet(item_normals_[pos], normals.inner))
        lower = std::min(lower, moved_offset(leaf, item_offsets_[pos], r, -1.0).distance_to(p));
    for (int k = 0; k < end_count; ++k) lower = std::min(lower, item_boxes_[pos].distance_to(ends[k]));
    return max_with_reach_bound(lower, item_boxes_[pos], item_normals_[pos], p, r);
}

bool AabbTree::offset_may_reach(const Node& n, Vec2 p, double r, double reach, double side) const {
    // (Squared distances: no square root per node.)
    const double reach2 = reach * reach;  // m^2
    if (n.box.distance_squared_to(p) > (r + reach) * (r + reach)) return false;
    if (has_offsets_ && offset_box(n, r, side).distance_squared_to(p) > reach2) return false;
    if (n.normals.width < kPi) {
        // q + r n within reach of p  <=>  q within reach of p - r n: the node's box must come
        // within reach of the arc of points p - r n, n in the cone (p + r n for side -1). The
        // arc's box holds its ends and the axis extremes it passes (arc_bounds, without trig).
        const double s = side > 0.0 ? -r : r;  // m: p + s n
        Aabb arc;
        arc.grow(p + s * n.cone_from);
        arc.grow(p + s * n.cone_to);
        if (n.cone_axes & 1u) arc.grow(p + Vec2{s, 0.0});
        if (n.cone_axes & 2u) arc.grow(p + Vec2{0.0, s});
        if (n.cone_axes & 4u) arc.grow(p - Vec2{s, 0.0});
        if (n.cone_axes & 8u) arc.grow(p - Vec2{0.0, s});
        return arc.gap_squared_to(n.box) <= reach2;
    }
    // Every q within r - reach of p: |q + r n - p| >= r - |q - p| > reach.
    return !(n.box.max_distance_to(p) < r - reach);
}

AabbTree::PadNormals AabbTree::pad_normals(const NormalCone& outer_normals) {
    // A hair wider than the pad: its tests accept a little past the threshold (cspace.cpp).
    constexpr double kMargin = 1e-6;  // rad
    if (outer_normals.width + 2.0 * kMargin >= kTwoPi) return {{0.0, kTwoPi}, {0.0, kTwoPi}};
    PadNormals normals;
    normals.outer = {wrap_2pi(outer_normals.start - kMargin), outer_normals.width + 2.0 * kMargin};
    normals.inner = {wrap_2pi(normals.outer.start + kPi), normals.outer.width};
    return normals;
}

void AabbTree::query_pad_reach(Vec2 p, double r, double reach, bool inner, const Vec2* ends, int end_count,
                               double end_reach, const NormalCone& outer_normals, std::vector<int>& out) const {
    PadReach q;
    start_pad_reach(q, p, r, reach, inner, ends, end_count, end_reach, outer_normals);
    continue_pad_reach(q, 0, out);
}

void AabbTree::start_pad_reach(PadReach& q, Vec2 p, double r, double reach, bool inner, const Vec2* ends,
                               int end_count, double end_reach, const NormalCone& outer_normals) const {
    const PadNormals normals = pad_normals(outer_normals);
    q.p = p;
    q.r = r;
    q.reach = reach;
    q.end_reach = end_reach;
    q.inner = inner;
    q.end_count = std::min(end_count, 2);
    for (int k = 0; k < q.end_count; ++k) q.ends[k] = ends[k];
    q.outer = normals.outer;
    q.inner_normals = normals.inner;
    q.top = 0;
    if (!nodes_.empty()) q.stack[q.top++] = 0;
    q.active = true;
}

bool AabbTree::continue_pad_reach(PadReach& q, int budget, std::vector<int>& out, int* visited_out) const {
    const Vec2 p = q.p;
    const double r = q.r, reach = q.reach;
    const double end_reach2 = q.end_reach * q.end_reach;  // m^2
    const double reach2 = reach * reach;                  // m^2
    int visited = 0;
    while (q.top > 0) {
        if (budget > 0 && visited >= budget) {
            if (visited_out) *visited_out = visited;
            return false;
        }
        const Node& n = nodes_[q.stack[--q.top]];
        ++visited;
        // (Boxes first: most nodes fail there, and the cone test costs more.)
        bool may_hold = offset_may_reach(n, p, r, reach, 1.0) && cones_meet(n.normals, q.outer);
        // The inner side's cone first: it faces away from the outer one, so along a contour
        // whose outer side the pad presses it rarely meets the node's, and the offset test it
        // spares is the dearer one (the same answer: both tests are pure). The outer side
        // keeps boxes first: far nodes fail there, over a dense contour most of them.
        if (!may_hold && q.inner && cones_meet(n.normals, q.inner_normals) && offset_may_reach(n, p, r, reach, -1.0))
            may_hold = true;
        for (int k = 0; k < q.end_count && !may_hold; ++k)
            if (n.box.distance_squared_to(q.ends[k]) <= end_reach2) may_hold = true;
        if (!may_hold) continue;
        if (n.left >= 0) {
            // The left child first (pushed last), as collect's.
            q.stack[q.top++] = n.right;
            q.stack[q.top++] = n.left;
            continue;
        }
        for (int i = n.first; i < n.first + n.count; ++i) {
            ++visited;
            // The leaf's test with each item's own boxes and cone (a leaf spans several items).
            bool item = !has_offsets_;
            const auto pos = static_cast<std::size_t>(i);
            if (!item && item_outer_at(pos, r) && moved_offset(n, item_offsets_[pos], r, 1.0).distance_squared_to(p) <= reach2 &&
                cones_meet(item_normals_[pos], q.outer))
                item = true;
            if (!item && q.inner && cones_meet(item_normals_[pos], q.inner_normals) &&
                moved_offset(n, item_offsets_[pos], r, -1.0).distance_squared_to(p) <= reach2)
                item = true;
            for (int k = 0; k < q.end_count && !item; ++k)
                if (item_boxes_[pos].distance_squared_to(q.ends[k]) <= end_reach2) item = true;
            if (item) out.push_back(items_[i]);
        }
    }
    q.active = false;
    if (visited_out) *visited_out = visited;
    return true;
}

}  // namespace contactlab
