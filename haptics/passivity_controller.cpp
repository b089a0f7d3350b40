// passivity_controller.cpp — the adaptive damper (see passivity_controller.hpp).
#include "haptics/passivity_controller.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab {

const char* to_string(PassivityMode m) noexcept {
    switch (m) {
        case PassivityMode::fault: return "fault";
        case PassivityMode::control: return "control";
    }
    return "?";
}

Vec2 PassivityController::step(double observed, Vec2 dx, Vec2 line, double dt, double max_damping) noexcept {
    damping_ = 0.0;
    saturated_ = false;
    if (!(observed > 0.0) || !(dt > 0.0) || !(glm::dot(line, line) > 0.0) || !(max_damping > 0.0)) return Vec2{0.0};
    const double along = glm::dot(line, dx);  // m this tick
    if (along == 0.0) {  // still along the line: no damper can dissipate (none added, none reported)
        saturated_ = true;
        return Vec2{0.0};
    }
    const double v = along / dt;                            // m/s
    const double needed = observed * dt / (along * along);  // N s/m: alpha = W / (v^2 T)
    damping_ = std::min(needed, max_damping);
    saturated_ = needed > max_damping;
    if (!std::isfinite(damping_)) damping_ = 0.0;
    return -damping_ * v * line;
}

}  // namespace contactlab
