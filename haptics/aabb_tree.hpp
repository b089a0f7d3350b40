// aabb_tree.hpp — a static bounding-volume hierarchy over the environment's segments.
//
// Why: a servo tick must not pay for segments far from the finger. Queries are "every item whose
// box overlaps this box" (proxy motion) and "distance to the nearest item" (collision
// anticipation), both pruned by node boxes so their cost grows with log N, not N.
#pragma once

#include "haptics/vec2.hpp"

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace contactlab {

struct Aabb {
    Vec2 lo{std::numeric_limits<double>::infinity()};
    Vec2 hi{-std::numeric_limits<double>::infinity()};

    void grow(Vec2 p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    void grow(const Aabb& b) { lo = glm::min(lo, b.lo); hi = glm::max(hi, b.hi); }
    bool overlaps(const Aabb& b) const {
        return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y;
    }
    Vec2 center() const { return 0.5 * (lo + hi); }
    // Distance (m) from p to the box; 0 inside.
    double distance_to(Vec2 p) const {
        const Vec2 d = glm::max(glm::max(lo - p, p - hi), Vec2(0.0));
        return glm::length(d);
    }
    // Its square (m^2): comparisons without a square root.
    double distance_squared_to(Vec2 p) const {
        const Vec2 d = glm::max(glm::max(lo - p, p - hi), Vec2(0.0));
        return glm::dot(d, d);
    }
    // Squared distance (m^2) from p to the box's farthest point; its root is max_distance_to's.
    double max_distance_squared_to(Vec2 p) const {
        const Vec2 d = glm::max(glm::abs(p - lo), glm::abs(hi - p));
        return glm::dot(d, d);
    }
    // Distance (m) from p to the box's farthest point (glm::length's root of the same square).
    double max_distance_to(Vec2 p) const { return std::sqrt(max_distance_squared_to(p)); }
    // Distance (m) between the two boxes; 0 when they overlap.
    double gap_to(const Aabb& b) const { return std::sqrt(gap_squared_to(b)); }
    double gap_squared_to(const Aabb& b) const {
        const Vec2 d = glm::max(glm::max(lo - b.hi, b.lo - hi), Vec2(0.0));
        return glm::dot(d, d);
    }
    bool contains(Vec2 p) const { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; }
    // Whether b lies inside this box (an empty b lies anywhere).
    bool contains(const Aabb& b) const {
        return b.lo.x > b.hi.x || b.lo.y > b.hi.y || (lo.x <= b.lo.x && lo.y <= b.lo.y && hi.x >= b.hi.x && hi.y >= b.hi.y);
    }
    // The box grown by `by` (m) on every side.
    Aabb grown(double by) const { return {lo - Vec2(by), hi + Vec2(by)}; }
};

// Bounding box of the arc of radius r (m) about c over the CCW angles [start, start + width] (rad):
// its ends and the axis extremes it passes.
Aabb arc_bounds(Vec2 c, double r, double start, double width);

// A cone of directions: the CCW arc of angles [start, start + width] (rad). Empty when width < 0,
// every direction when width >= 2 pi.
struct NormalCone {
    double start = 0.0;
    double width = -1.0;
};
// The smallest cone holding both.
NormalCone merge_cones(const NormalCone& a, const NormalCone& b);
// Whether the two cones share a direction.
inline bool cones_meet(const NormalCone& a, const NormalCone& b) {
    if (a.width < 0.0 || b.width < 0.0) return false;
    if (a.width >= kTwoPi || b.width >= kTwoPi) return true;
    return wrap_2pi(b.start - a.start) <= a.width || wrap_2pi(a.start - b.start) <= b.width;
}

// An item's offset at a reference pad radius rho (m): `outer` bounds every point q + rho n and
// `inner` every q - rho n, over the item's points q and the free-side normals n its c-space
// pieces offset along there (a line's normal, an arc's radial normals, a convex vertex's cone).
struct OffsetBoxes {
    Aabb outer;
    Aabb inner;
};

class AabbTree {
public:
    static constexpr int kMaxDepth = 64;
    static constexpr int kMaxStack = 2 * kMaxDepth;  // nodes a depth-first search may hold
    AabbTree() = default;
    explicit AabbTree(const std::vector<Aabb>& item_boxes);
    // With each item's cone of free-side normals, for query_pad_reach.
    AabbTree(const std::vector<Aabb>& item_boxes, const std::vector<NormalCone>& item_normals);
    // ... and each item's offset boxes at radius rho (m): query_pad_reach then bounds a node's
    // pieces by the box of its items' offsets, not by its box swept round its cone. Why: along a
    // curved contour a node's normals turn, and the swept box is far larger than the offset curve
    // it holds, so a query near a densely sampled contour visited most of the tree (a quarter of
    // the tick at 100,000 segments on 0.4 m). Pads of another radius r stay exact: the offset at
    // r is the offset at rho moved by (r - rho) n, the node's box grown by that over its cone.
    AabbTree(const std::vector<Aabb>& item_boxes, const std::vector<NormalCone>& item_normals,
             const std::vector<OffsetBoxes>& item_offsets, double rho);
    // ... and, per item, the pad radius (m) from which its outer offset makes no piece (+inf: at
    // every radius). A bowl arc of radius rho with no vertex pieces offsets to nothing under a pad
    // of radius r >= rho (cspace.cpp: only the pad's ends reach it), yet its offset box lies about
    // the bowl's centre. Why: at the bottom of a valley tighter than the pad, thousands of such
    // arcs offset to within micrometres of the resting proxy; gathered, they built no piece and
    // made a tick's gather 70 us on 100,000 curves. The query leaves them to the pad-end test.
    AabbTree(const std::vector<Aabb>& item_boxes, const std::vector<NormalCone>& item_normals,
             const std::vector<OffsetBoxes>& item_offsets, double rho, const std::vector<double>& item_outer_limits);

    // Appends to `out` the index of every item whose box overlaps `box`. `out` keeps its capacity,
    // so a caller that reserves once does not allocate per query.
    void query(const Aabb& box, std::vector<int>& out) const;

    // Appends every item whose pieces may come within reach of a pad of radius r centred at p,
    // each item once: those that may have a point q with a free-side normal n (within its cone)
    // such that q + r n lies within `reach` of p (the pad's outer side: the items' offset by r can
    // come within reach of a finger at p), with `inner` also those where q - r n does (the pad's
    // concave side touching the contour from the solid's side, cspace.hpp's inner pieces), and
    // those within end_reach (m) of any of the `end_count` points `ends` (the pad's ends). Nodes
    // are pruned by distance (farther than r + reach), by the offset of their normal cone, and,
    // without cones, by the annulus: items wholly within r - reach of p offset to beyond reach.
    // Conservative: may return more, never fewer. Why: under a pad pressed into a densely sampled
    // contour, the box around the pad holds thousands of tiny segments of which only those near
    // the contact can matter; and one walk of the tree for all of it (four walks were a fifth of a
    // small scene's tick).
    // `outer_normals`: as nearest_pad_item's (offsets along normals the pad cannot press along
    // make no piece); {0, 2 pi} for every normal.
    void query_pad_reach(Vec2 p, double r, double reach, bool inner, const Vec2* ends, int end_count,
                         double end_reach, const NormalCone& outer_normals, std::vector<int>& out) const;
    // query_pad_reach in parts: start_pad_reach fixes the query (its arguments as above) and
    // continue_pad_reach appends what a part of the walk finds, visiting about `budget` nodes and
    // items (a node's items are finished whole; how many in *visited); budget <= 0: to the end. True when the query
    // ended; the appended items are then query_pad_reach's, in its order (the same depth-first
    // walk, stopped and resumed). Why: beside a valley shaped like the pad a query made ahead of
    // the tick that needs it (Proxy's staged gather) visits ~1,500 segments, 80-100 us: in parts
    // it shares the ticks before that one.
    struct PadReach {
        Vec2 p{0.0};
        double r = 0.0, reach = 0.0, end_reach = 0.0;  // m
        bool inner = false;
        Vec2 ends[2]{};
        int end_count = 0;
        NormalCone outer, inner_normals;  // pad_normals' of the query's outer normals
        int stack[kMaxStack]{};
        int top = 0;
        bool active = false;  // started and not yet ended
    };
    void start_pad_reach(PadReach& q, Vec2 p, double r, double reach, bool inner, const Vec2* ends, int end_count,
                         double end_reach, const NormalCone& outer_normals) const;
    bool continue_pad_reach(PadReach& q, int budget, std::vector<int>& out, int* visited = nullptr) const;

    // Smallest exact distance (m) from p to any item, where `item_distance(i)` is the exact distance
    // to item i. Nodes farther than the best distance so far are skipped.
    template <typename ItemDistance>
    double nearest_distance(Vec2 p, ItemDistance&& item_distance) const;

    // Nearest-first search for the pieces of a pad of radius r (m) at p: calls item_distance(i)
    // (the exact distance, m, from p to item i's pieces) for the items whose lower bound does not
    // exceed the least distance found so far, nearer nodes first, and returns that least distance.
    // A node's lower bound is the least of the distance to its offset boxes (moved to radius r,
    // as query_pad_reach), with `inner` to its inner ones, and from each of the `end_count`
    // points `ends` (the pad's ends: an end piece is its segment moved by minus the end's offset)
    // to its box; a leaf's items are bounded alike by their own boxes. Items at the same
    // distance as the best so far are still visited (ties: the caller picks). `outer_normals`:
    // the free-side normals the pad can press along (its span turned by pi; inner pieces the
    // opposite ones): offsets along other normals make no piece, so they bound nothing. Why:
    // 1 cm above a densely sampled contour the pieces within the nearest one's reach were
    // thousands (a quarter of a millisecond a tick), and over a slope steeper than the pad's
    // half-angle most offsets are of normals the pad cannot press along.
    template <typename ItemDistance>
    double nearest_pad_item(Vec2 p, double r, bool inner, const Vec2* ends, int end_count,
                            const NormalCone& outer_normals, ItemDistance&& item_distance) const;

    // nearest_pad_item spread over several calls: the same nodes in the same order, stopped once
    // `budget` items were asked and continued from there by the next call with the same search
    // (its query fixed at start: p, r, inner, ends, normals). Why: 1 cm above a dense valley
    // whose curvature matches the pad's, thousands of segments' offsets lie within micrometres
    // of the nearest (a caustic) and an exact search asks all of them: 0.2 ms in one tick.
    struct PadSearch {
        Vec2 p{0.0};
        double r = 0.0;
        bool inner = false;
        Vec2 ends[2]{};
        int end_count = 0;
        NormalCone outer_normals;
        double best = std::numeric_limits<double>::infinity();  // m, the least distance so far
        // m, the least lower bound of the nodes and items it pruned (each beyond the best then):
        // with the items it asked, a bound under every item's distance (Proxy::anticipate's hold).
        double pruned = std::numeric_limits<double>::infinity();
        int stack[kMaxStack]{};
        double bound[kMaxStack]{};  // each stacked node's lower bound (m)
        int top = 0;
        bool active = false;  // started and not yet finished
    };
    void start_pad_search(PadSearch& s, Vec2 p, double r, bool inner, const Vec2* ends, int end_count,
                          const NormalCone& outer_normals) const;
    // Continues s, asking item_distance for at most about `budget` items (a leaf is finished
    // whole: up to kLeafSize - 1 more); budget <= 0: to the end. True when the search ended
    // (s.best is then nearest_pad_item's answer); s.active is false from then on.
    template <typename ItemDistance>
    bool continue_pad_search(PadSearch& s, int budget, ItemDistance&& item_distance) const;

    int size() const { return static_cast<int>(items_.size()); }

    // Whether the tree bounds what it was built from (validation.hpp): every item once, each
    // node's box (and offset boxes and normal cone, where it has them) holding its children's and
    // its items'. O(N); called after a build when validation is on.
    bool consistent(const std::vector<Aabb>& item_boxes) const;

private:
    struct Node {
        Aabb box;
        NormalCone normals;  // of every item below; full when the tree has no cones
        // The cone's end directions and which axis directions (bit k: angle k pi/2) it holds,
        // computed once at build: query_pad_reach bounds the cone's arc with no sine, cosine
        // or fmod per node visited (they were a quarter of a dense contour's tick).
        Vec2 cone_from{1.0, 0.0}, cone_to{1.0, 0.0};
        std::uint8_t cone_axes = 0;
        OffsetBoxes offset;  // of every item below, at rho_ (when has_offsets_)
        // The outer box of the items below with no outer limit, and the greatest limit (m) of
        // those with one (0: none): under a pad of radius r >= outer_limit, `outer_firm` bounds
        // every outer piece below (offset_box).
        Aabb outer_firm;
        double outer_limit = 0.0;
        int left = -1;   // child node index; -1 for a leaf
        int right = -1;
        int first = 0;   // leaf: items_[first, first + count)
        int count = 0;
    };
    int build(const std::vector<Aabb>& boxes, const std::vector<NormalCone>* normals,
              const std::vector<OffsetBoxes>* offsets, const std::vector<double>* limits, int first, int count);
    // Whether the item at leaf position pos may have outer pieces under a pad of radius r (m).
    bool item_outer_at(std::size_t pos, double r) const { return item_outer_limits_.empty() || r < item_outer_limits_[pos]; }
    // Whether items below node n may have an offset point q + r n (side +1) or q - r n (side -1)
    // within reach of p: query_pad_reach's test.
    bool offset_may_reach(const Node& n, Vec2 p, double r, double reach, double side) const;
    // nearest_pad_item's normals: those each side's pieces may have.
    struct PadNormals {
        NormalCone outer, inner;
    };
    // The outer normals a microradian wider, and the inner ones opposite.
    static PadNormals pad_normals(const NormalCone& outer_normals);
    // The node's offset box on `side` at radius r: its box at rho_ moved by +-(r - rho_) n over its
    // cone. Without offset boxes, the node's box grown by r.
    Aabb offset_box(const Node& n, double r, double side) const;
    // The box of d n (m) over the node's cone.
    static Aabb cone_sweep(const Node& n, double d);
    // Offset boxes at rho_ (the node's, or one of its items') moved to radius r over n's cone.
    Aabb moved_offset(const Node& n, const OffsetBoxes& at_rho, double r, double side) const;
    Aabb moved_box(const Node& n, const Aabb& box_at_rho, double r, double side) const;  // one side's box
    // pad_lower_bound for the item at `position` in items_, under `leaf`: its own boxes.
    double item_lower_bound(const Node& leaf, int position, Vec2 p, double r, bool inner, const Vec2* ends,
                            int end_count, const PadNormals& normals) const;
    // nearest_pad_item's lower bound (m) on the distance from p to any piece of the node's items.
    double pad_lower_bound(const Node& n, Vec2 p, double r, bool inner, const Vec2* ends, int end_count,
                           const PadNormals& normals) const;
    // Appends the items of every leaf reached through nodes for which may_hold(node) is true, and
    // for which item_may_hold(leaf, position in items_) is, left child first.
    template <typename MayHold, typename ItemMayHold>
    void collect(MayHold&& may_hold, ItemMayHold&& item_may_hold, std::vector<int>& out) const;

    std::vector<Node> nodes_;
    std::vector<int> items_;
    bool has_offsets_ = false;
    // With offsets: each item's box and offset boxes, in items_ order (nearest_pad_item's bound
    // per item: over a dense contour a leaf's bound is loose by its own size, and building a
    // segment's pieces costs ten box tests).
    std::vector<Aabb> item_boxes_;
    std::vector<OffsetBoxes> item_offsets_;
    std::vector<NormalCone> item_normals_;
    std::vector<double> item_outer_limits_;  // m, in leaf order; empty: no limits
    double rho_ = 0.0;  // m, the radius of the nodes' offset boxes
    static constexpr int kLeafSize = 4;
};

template <typename MayHold, typename ItemMayHold>
void AabbTree::collect(MayHold&& may_hold, ItemMayHold&& item_may_hold, std::vector<int>& out) const {
    if (nodes_.empty()) return;
    int stack[kMaxStack];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        if (!may_hold(n)) continue;
        if (n.left < 0) {
            for (int i = n.first; i < n.first + n.count; ++i)
                if (item_may_hold(n, i)) out.push_back(items_[i]);
            continue;
        }
        // The left child first (pushed last): along a contour drawn left to right its items come
        // first, so a query's output is already in order there (items within a leaf are sorted).
        stack[top++] = n.right;
        stack[top++] = n.left;
    }
}

template <typename ItemDistance>
double AabbTree::nearest_distance(Vec2 p, ItemDistance&& item_distance) const {
    double best = std::numeric_limits<double>::infinity();
    if (nodes_.empty()) return best;
    int stack[kMaxStack];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        if (n.box.distance_to(p) >= best) continue;
        if (n.left < 0) {
            for (int i = n.first; i < n.first + n.count; ++i) {
                best = std::min(best, item_distance(items_[i]));
            }
            continue;
        }
        // Visit the nearer child first (pushed last) so `best` shrinks early.
        const Node& l = nodes_[n.left];
        const Node& r = nodes_[n.right];
        if (l.box.distance_to(p) < r.box.distance_to(p)) {
            stack[top++] = n.right;
            stack[top++] = n.left;
        } else {
            stack[top++] = n.left;
            stack[top++] = n.right;
        }
    }
    return best;
}

template <typename ItemDistance>
double AabbTree::nearest_pad_item(Vec2 p, double r, bool inner, const Vec2* ends, int end_count,
                                  const NormalCone& outer_normals, ItemDistance&& item_distance) const {
    PadSearch s;
    start_pad_search(s, p, r, inner, ends, end_count, outer_normals);
    continue_pad_search(s, 0, item_distance);
    return s.best;
}

inline void AabbTree::start_pad_search(PadSearch& s, Vec2 p, double r, bool inner, const Vec2* ends, int end_count,
                                       const NormalCone& outer_normals) const {
    s.p = p;
    s.r = r;
    s.inner = inner;
    s.end_count = std::min(end_count, 2);
    for (int k = 0; k < s.end_count; ++k) s.ends[k] = ends[k];
    s.outer_normals = outer_normals;
    s.best = std::numeric_limits<double>::infinity();
    s.pruned = std::numeric_limits<double>::infinity();
    s.top = 0;
    s.active = !nodes_.empty();
    if (!s.active) return;
    s.stack[0] = 0;
    s.bound[0] = pad_lower_bound(nodes_[0], p, r, inner, s.ends, s.end_count, pad_normals(outer_normals));
    s.top = 1;
}

template <typename ItemDistance>
bool AabbTree::continue_pad_search(PadSearch& s, int budget, ItemDistance&& item_distance) const {
    if (!s.active) return true;
    const PadNormals normals = pad_normals(s.outer_normals);
    // Bounds and exact distances are computed differently, so a bound may exceed an exact
    // distance it equals by a rounding: only a bound this much (m) beyond the best prunes, and
    // ties stay the caller's to break.
    constexpr double kRounding = 1e-12;
    int asked = 0;
    while (s.top > 0) {
        if (budget > 0 && asked >= budget) return false;  // the rest next call
        --s.top;
        if (s.bound[s.top] > s.best + kRounding) {
            s.pruned = std::min(s.pruned, s.bound[s.top]);
            continue;
        }
        const Node& n = nodes_[s.stack[s.top]];
        if (n.left < 0) {
            for (int i = n.first; i < n.first + n.count; ++i) {
                const double item_bound = item_lower_bound(n, i, s.p, s.r, s.inner, s.ends, s.end_count, normals);  // m
                if (item_bound > s.best + kRounding) {
                    s.pruned = std::min(s.pruned, item_bound);
                    continue;
                }
                s.best = std::min(s.best, item_distance(items_[i]));
                ++asked;
            }
            continue;
        }
        // The nearer child is pushed last, so visited first: `best` shrinks early.
        const double bl = pad_lower_bound(nodes_[n.left], s.p, s.r, s.inner, s.ends, s.end_count, normals);
        const double br = pad_lower_bound(nodes_[n.right], s.p, s.r, s.inner, s.ends, s.end_count, normals);
        const bool left_first = bl <= br;
        s.stack[s.top] = left_first ? n.right : n.left;
        s.bound[s.top++] = left_first ? br : bl;
        s.stack[s.top] = left_first ? n.left : n.right;
        s.bound[s.top++] = left_first ? bl : br;
    }
    s.active = false;
    return true;
}

}  // namespace contactlab
