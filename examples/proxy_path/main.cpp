// proxy_path — a fingertip moves along a straight line onto a scene's surface; the proxy (the
// virtual finger that stays on the surface, as in `contactlab trace`) reports the force and where
// on the pad the contact is, each step.
//
//   proxy_path [SCENE.json]     default: the installed scenes/flat.json (a floor at y = 0)
//
// On flat.json the finger (R = 26 mm, tilted by phi = 0.2 rad) starts 4 mm above the floor and
// ends 1 mm into it: zero force in free air, then F = Ke * depth straight up (Ke = 1000 N/m, so
// 1.000 N at the last step), touching the pad at l = -R phi = -5.2 mm.
#include "haptics/environment.hpp"  // build_environment: the scene compiled for collision queries
#include "haptics/proxy.hpp"        // Proxy, ProxyDef, ProxyOutput
#include "haptics/scene_io.hpp"     // load_scene_file, SceneError

#include <cmath>
#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    using namespace contactlab;
    const std::string path = argc > 1 ? argv[1] : CONTACTLAB_DATA_DIR "/scenes/flat.json";

    // 1. The scene: contours, finger shape, force law (SI units throughout).
    Scene scene;
    try {
        scene = load_scene_file(path);
    } catch (const SceneError& e) {
        std::fprintf(stderr, "proxy_path: %s\n", e.what());
        return 1;
    }

    // 2. The environment (segments + spatial index) and a proxy over it. The environment must
    //    outlive the proxy.
    const Environment env = build_environment(scene);
    Proxy proxy(env, proxy_def_of(scene));

    // 3. The finger centre x_f moves in a straight line from `from` to `to`; the pad hangs R below.
    const double R = scene.finger.radius;
    const Vec2 from{-0.05, R + 0.004}, to{0.05, R - 0.001};  // m
    const double phi = 0.2;                                  // rad, finger tilt (driven, fixed here)
    const int steps = 20;

    std::printf("scene %s, R = %.1f mm, Ke = %.0f N/m\n", path.c_str(), R * 1e3, scene.force.stiffness);
    std::printf("step  x_f(mm)  y_f(mm)  contact  |F|(N)   l_d(mm)  point_x(mm)  point_y(mm)\n");
    for (int i = 0; i <= steps; ++i) {
        const Vec2 x = from + (to - from) * (double(i) / steps);
        // One servo tick (1 ms apart): the proxy slides from where it was toward x_f without
        // crossing the surface, and the spring between them is the force on the finger.
        const ProxyOutput& o = proxy.update(x, phi);
        // In free air l_d is where the pad is about to touch (collision anticipation, seed 000).
        const double f = std::hypot(o.force.x, o.force.y);
        std::printf("%4d  %7.2f  %7.2f  %7d  %6.3f  %8.3f", i, x.x * 1e3, x.y * 1e3, o.contact ? 1 : 0, f, o.l_d * 1e3);
        if (o.contact_count > 0) {  // the first contact's point on the contour
            std::printf("  %11.3f  %11.3f\n", o.contacts[0].point.x * 1e3, o.contacts[0].point.y * 1e3);
        } else {
            std::printf("  %11s  %11s\n", "-", "-");
        }
    }
    return 0;
}
