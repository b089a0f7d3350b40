// start_inside_warning.cpp — see start_inside_warning.hpp.
#include "engine/app/start_inside_warning.hpp"

#include "haptics/verify/solid_reference.hpp"

#include <cstdio>

namespace contactlab::app {

std::string start_inside_warning(const char* command, const Scene& scene, double t, Vec2 x, double phi) {
    if (scene.contours.empty()) return "";
    const verify::SolidReference ref(scene);
    const auto pad = ref.pad_depth(x, phi, scene.finger.radius, scene.finger.length, 1e-8);
    if (!(pad.depth > kStartInsideReport)) return "";
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "%s: warning: the first hand sample (t = %.6g s, x = (%.6g, %.6g) m, phi = %.6g rad) has the pad "
                  "%.3f mm inside a solid; the proxy starts there with no history, so that solid is not felt until the "
                  "pad has left it",
                  command, t, x.x, x.y, phi, pad.depth * 1e3);
    return buf;
}

}  // namespace contactlab::app
