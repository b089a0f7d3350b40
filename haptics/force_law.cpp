// force_law.cpp — the pseudo-ellipsoidal field and seed 004's eccentricity/total stiffness.
#include "haptics/force_law.hpp"

#include <cmath>

namespace contactlab {

Vec2 ellipsoid_force(Vec2 p, Vec2 n, double k_tangential, double k_normal, double field_angle) {
    const double len = glm::length(p);
    if (!(len > 0.0)) return Vec2{0.0};
    if (field_angle != 0.0) {  // the k_normal axis turned counter-clockwise from n
        const double c = std::cos(field_angle), s = std::sin(field_angle);
        n = Vec2{c * n.x - s * n.y, s * n.x + c * n.y};
    }
    const Vec2 t = -perp_left(n);  // any unit tangent: only |E p| matters
    const double ep = std::hypot(k_tangential * glm::dot(p, t), k_normal * glm::dot(p, n));
    return -(ep / len) * p;
}

double tangential_stiffness_from(double k, double e, TotalStiffness formula) {
    // printed:      k^2 = (k1^2 + 2 e^2 k1^2) / 3  ->  k1 = k sqrt(3 / (1 + 2 e^2))
    // diagonal_rms: k^2 = (2 k1^2 + e^2 k1^2) / 3  ->  k1 = k sqrt(3 / (2 + e^2))
    return formula == TotalStiffness::printed ? k * std::sqrt(3.0 / (1.0 + 2.0 * e * e))
                                              : k * std::sqrt(3.0 / (2.0 + e * e));
}

}  // namespace contactlab
