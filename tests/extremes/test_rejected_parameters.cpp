// test_rejected_parameters.cpp — values the model cannot honour are refused with a message that
// names the parameter, its range and the value given: in a scene (validate_scene, the path every
// scene file and editor edit goes through) and for the live servo (servo_params_problem).
#include "extremes_fixture.hpp"

#include "haptics/scene_io.hpp"
#include "haptics/servo_params_check.hpp"

#include <doctest/doctest.h>

#include <functional>
#include <limits>
#include <string>

using namespace contactlab;
using namespace contactlab::extremes;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The message validate_scene throws for the nominal floor scene after `edit`, or "" if none.
std::string scene_problem(const std::function<void(Scene&)>& edit) {
    Scene s = floor_at({0.0, 0.0});
    edit(s);
    try {
        validate_scene(s);
    } catch (const SceneError& e) {
        return e.what();
    }
    return {};
}

bool mentions(const std::string& message, const std::string& part) { return message.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("the nominal scene and its extremes within range are accepted") {
    CHECK(scene_problem([](Scene&) {}).empty());
    CHECK(scene_problem([](Scene& s) { s.force.stiffness = 1e-6 * kNominalStiffness; }).empty());
    CHECK(scene_problem([](Scene& s) { s.finger.radius = 1e-4; s.finger.length = 1e-4; }).empty());
    CHECK(scene_problem([](Scene& s) { s.finger.radius = 1.0; s.finger.length = 0.999999 * 2.0 * kPi; }).empty());
    CHECK(scene_problem([](Scene& s) {
              s.contours[0].segments = {line({0.0, 0.0}, {1e-9, 0.0})};  // 1e-9 m, the shortest
          }).empty());
}

TEST_CASE("scene parameters out of range name the field, the range and the value") {
    struct Case {
        const char* field;
        std::function<void(Scene&)> edit;
    };
    const Case cases[] = {
        {"force.stiffness", [](Scene& s) { s.force.stiffness = 1e6 * kNominalStiffness; }},
        {"force.stiffness", [](Scene& s) { s.force.stiffness = -1.0; }},
        {"force.stiffness", [](Scene& s) { s.force.stiffness = kNaN; }},
        {"force.max_force", [](Scene& s) { s.force.max_force = 1e6 * kNominalMaxForce; }},
        {"force.max_force", [](Scene& s) { s.force.max_force = 0.0; }},
        {"finger.radius", [](Scene& s) { s.finger.radius = 1e-5; }},
        {"finger.radius", [](Scene& s) { s.finger.radius = 26.0; }},  // millimetres typed as metres
        {"finger.length", [](Scene& s) { s.finger.length = 2.0 * kPi * s.finger.radius; }},
        {"finger.length", [](Scene& s) { s.finger.length = kInf; }},
        {"force.damping", [](Scene& s) { s.force.law.damping = 1e6; }},
        {"force.friction.static", [](Scene& s) { s.force.law.mu_static = 1e3; }},
        {"force.friction.dynamic", [](Scene& s) { s.force.law.mu_static = 0.1; s.force.law.mu_dynamic = 0.5; }},
        {"force.k_normal", [](Scene& s) { s.force.law.model = ForceModel::ellipsoid; s.force.law.k_normal = 1e12; }},
        {"force.k_tangential", [](Scene& s) { s.force.law.model = ForceModel::ellipsoid; s.force.law.k_tangential = 0.0; }},
        {"contours[0].segments[0]", [](Scene& s) { s.contours[0].segments = {line({0.0, 0.0}, {1e-10, 0.0})}; }},
        {"contours[0].segments[0].to", [](Scene& s) { s.contours[0].segments = {line({0.0, 0.0}, {1e7, 0.0})}; }},
        {"contours[0].segments[0]", [](Scene& s) {
             s.contours[0].segments = {CubicSegment{{0.1, 0.0}, {0.1, 0.0}, {0.1, 0.0}, {0.1, 0.0}}};  // all coincident
         }},
        {"contours[0].segments[0]", [](Scene& s) { s.contours[0].segments = {ArcSegment{{0.0, 0.0}, 0.1, 0.0, 7.0}}; }},
        {"curves.tolerance", [](Scene& s) { s.curves.tolerance = 1e-12; }},
    };
    for (const Case& c : cases) {
        const std::string message = scene_problem(c.edit);
        CAPTURE(c.field);
        CAPTURE(message);
        CHECK(mentions(message, c.field));
    }
    // The value given and the range are in the message, so the user knows what to change.
    const std::string ke = scene_problem([](Scene& s) { s.force.stiffness = 1e9; });
    CHECK(mentions(ke, "1e+09"));
    CHECK(mentions(ke, "1e+07"));
    CHECK(mentions(ke, "N/m"));
}

TEST_CASE("servo parameters: the defaults are honoured at every rate from 100 Hz to 100 kHz once the watchdog fits") {
    for (double rate : {100.0, 250.0, 1e3, 1e4, 2e4, 1e5}) {
        ServoConfig c;
        c.period = 1.0 / rate;
        ServoParams p;
        p.safety.watchdog_timeout = std::max(0.005, 3.0 / rate);  // s: three periods, at least 5 ms
        CAPTURE(rate);
        CHECK(servo_config_problem(c).empty());
        CHECK(servo_params_problem(p, c).empty());
    }
}

TEST_CASE("servo parameters the tick cannot honour name the field and the value") {
    const ServoConfig c;
    struct Case {
        const char* field;
        std::function<void(ServoParams&)> edit;
    };
    const Case cases[] = {
        {"stiffness", [](ServoParams& p) { p.stiffness = kNaN; }},
        {"stiffness", [](ServoParams& p) { p.stiffness = 1e7 * kNominalStiffness; }},
        {"stiffness", [](ServoParams& p) { p.stiffness = -1.0; }},
        {"max_force", [](ServoParams& p) { p.max_force = kInf; }},
        {"stiffness_slew", [](ServoParams& p) { p.stiffness_slew = 0.0; }},
        {"passivity_threshold", [](ServoParams& p) { p.passivity_threshold = kNaN; }},
        {"safety.ramp_time", [](ServoParams& p) { p.safety.ramp_time = -1.0; }},
        {"safety.watchdog_timeout", [](ServoParams& p) { p.safety.watchdog_timeout = 1e-4; }},  // < 2 periods at 1 kHz
        {"roller.ki", [](ServoParams& p) { p.roller.ki = kInf; }},
        {"roller.kp", [](ServoParams& p) { p.roller.kp = -3.0; }},
        {"roller.d_cutoff_hz", [](ServoParams& p) { p.roller.d_cutoff_hz = 0.0; }},
        {"roller.ff_cutoff_hz", [](ServoParams& p) { p.roller.ff_cutoff_hz = 0.0; }},
        {"roller.max_drive", [](ServoParams& p) { p.roller.max_drive = kNaN; }},
    };
    for (const Case& k : cases) {
        ServoParams p;
        k.edit(p);
        const std::string message = servo_params_problem(p, c);
        CAPTURE(k.field);
        CAPTURE(message);
        CHECK(mentions(message, std::string(k.field) + ":"));
    }
    // Huge but finite Ki is a choice (anti-windup copes, test_roller_extremes.cpp), not an error.
    ServoParams huge_ki;
    huge_ki.roller.ki *= 1e6;
    CHECK(servo_params_problem(huge_ki, c).empty());
}

TEST_CASE("servo configurations: rates outside 100 Hz..100 kHz and broken device limits are named") {
    ServoConfig c;
    c.period = 1.0 / 50.0;
    CHECK(mentions(servo_config_problem(c), "period:"));
    CHECK(mentions(servo_config_problem(c), "100 Hz"));
    c.period = 1.0 / 1e6;
    CHECK(mentions(servo_config_problem(c), "period:"));
    c = ServoConfig{};
    c.device_max_force = kNaN;
    CHECK(mentions(servo_config_problem(c), "device_max_force:"));
    c = ServoConfig{};
    c.roller_travel = {0.01, -0.01};
    CHECK(mentions(servo_config_problem(c), "roller_travel"));
}
