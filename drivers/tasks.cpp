// tasks.cpp — the contour-following block task as a hand path.
#include "drivers/tasks.hpp"

#include <cmath>
#include <functional>

namespace contactlab::drivers {

HandPath contour_block_task(const BlockTaskParams& p) {
    const double r = p.finger_radius - p.press;  // m, intended centre height above the top
    const Vec2 start{-p.d - 0.01, p.finger_radius + 0.01};
    struct Leg {
        double duration;                              // s
        std::function<PathSample(double u)> at;       // u in [0, 1]
    };
    std::vector<Leg> legs;
    // Descend onto the top, then settle.
    const Vec2 on_top{start.x, r};
    legs.push_back({0.3, [=](double u) { return PathSample{0, start + (on_top - start) * u, 0.0}; }});
    legs.push_back({0.2, [=](double) { return PathSample{0, on_top, 0.0}; }});
    // Slide along the top and past the edge.
    const Vec2 past{p.overshoot, r};
    legs.push_back({(past.x - on_top.x) / p.speed, [=](double u) { return PathSample{0, on_top + (past - on_top) * u, 0.0}; }});
    // Tip around the corner: the centre swings about the corner from above to beside it.
    const double a0 = std::atan2(past.y, past.x), rho0 = glm::length(past);
    const double a1 = 0.0, rho1 = r;
    const double arc = 0.5 * (rho0 + rho1) * (a0 - a1);
    const double descent_speed = p.descent_speed > 0.0 ? p.descent_speed : p.speed;
    legs.push_back({arc / descent_speed, [=](double u) {
                        const double a = a0 + (a1 - a0) * u, rho = rho0 + (rho1 - rho0) * u;
                        return PathSample{0, rho * Vec2{std::cos(a), std::sin(a)}, -0.5 * kPi * u};
                    }});
    // Down the far face, then hold.
    const Vec2 side{r, 0.0}, bottom{r, -p.descent};
    legs.push_back({p.descent / descent_speed, [=](double u) { return PathSample{0, side + (bottom - side) * u, -0.5 * kPi}; }});
    legs.push_back({0.3, [=](double) { return PathSample{0, bottom, -0.5 * kPi}; }});

    double total = 0.0;
    for (const Leg& l : legs) total += l.duration;
    std::vector<PathSample> out;
    const long n = static_cast<long>(std::floor(total / p.sample_period));
    out.reserve(static_cast<std::size_t>(n) + 1);
    std::size_t leg = 0;
    double leg_start = 0.0;
    for (long k = 0; k <= n; ++k) {
        const double t = k * p.sample_period;
        while (leg + 1 < legs.size() && t > leg_start + legs[leg].duration) leg_start += legs[leg++].duration;
        const double u = std::min(1.0, (t - leg_start) / legs[leg].duration);
        PathSample s = legs[leg].at(u);
        s.t = t;
        out.push_back(s);
    }
    return HandPath(std::move(out));
}

Scene block_scene() {
    Scene s;
    s.finger.radius = 0.026;  // m
    s.finger.length = 0.020;  // m
    Contour c;
    c.segments.push_back(LineSegment{{-0.16, 0.0}, {0.0, 0.0}});   // the top, solid below
    c.segments.push_back(LineSegment{{0.0, 0.0}, {0.0, -0.1}});    // the far face
    c.segments.push_back(LineSegment{{0.0, -0.1}, {0.16, -0.1}});  // the floor beyond
    s.contours.push_back(c);
    s.force.stiffness = 1000.0;  // N/m
    s.force.max_force = 1.5;     // N
    s.contact_location.rule = ContactRule::centroid;
    return s;
}

}  // namespace contactlab::drivers
