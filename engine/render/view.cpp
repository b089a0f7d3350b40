// view.cpp — fitting a world box into an image.
#include "engine/render/view.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::render {

View fit_view(const Aabb& box, int width, int height, double margin) {
    View v;
    v.width = width;
    v.height = height;
    Aabb b = box;
    if (!(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y) || !std::isfinite(b.lo.x) || !std::isfinite(b.hi.x)) {
        b = Aabb{};
        b.grow(Vec2(-0.1, -0.1));
        b.grow(Vec2(0.1, 0.1));
    }
    const Vec2 size = glm::max(b.hi - b.lo, Vec2(1e-6));
    const double usable = std::max(1.0 - 2.0 * margin, 0.1);
    v.center = b.center();
    v.px_per_m = std::min(width * usable / size.x, height * usable / size.y);
    return v;
}

}  // namespace contactlab::render
