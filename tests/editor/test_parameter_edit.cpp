// test_parameter_edit.cpp — the one path every tunable parameter's edit takes
// (engine/editor/parameter_edit.hpp): at each limit the value is accepted and shown; one step
// past it the value is refused, nothing changes (the field shows what is in effect), the status
// line says so as an error and names the parameter, and the field's own error line is set.
// The limits are haptics/parameter_limits.hpp's, the ones scene files obey.
#include "engine/editor/parameter_edit.hpp"
#include "haptics/parameter_limits.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace contactlab;
using namespace contactlab::editor;
namespace L = contactlab::limits;

namespace {

struct Edge {
    const char* name;
    double accepted;  // at the limit (or the nearest legal value)
    double refused;   // just past it
};

// Starts from the defaults, in the ellipsoid model so that k_t and k_n are live.
EditorState fresh() {
    EditorState s;
    Scene sc = s.doc.scene();
    set_force_model(sc.force, ForceModel::ellipsoid);
    s.doc.edit(sc, "model");
    return s;
}

void check_refused(EditorState& s, const char* name, double value) {
    const double before = *parameter_value(s, name);
    const std::size_t undo = s.doc.undo_depth();
    CHECK_FALSE(set_parameter(s, name, value));
    CHECK(*parameter_value(s, name) == before);  // the field shows the value in effect
    CHECK(s.doc.undo_depth() == undo);           // nothing recorded
    CHECK(s.message_is_error);
    CHECK(s.message.find(name) != std::string::npos);
    CHECK(s.field_error_name == name);
    CHECK_FALSE(s.field_error.empty());
}

}  // namespace

TEST_CASE("parameter edit: every tunable parameter is accepted at its limits and refused past them") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Edge edges[] = {
        {"ke", L::kMaxStiffness, L::kMaxStiffness * 1.001},
        {"ke", 1e-3, 0.0},
        {"ke", 1e-3, -1.0},
        {"max_force", L::kMaxForceLimit, L::kMaxForceLimit * 1.001},
        {"max_force", 1e-6, 0.0},
        {"k_t", L::kMaxStiffness, L::kMaxStiffness * 1.001},
        {"k_t", 1e-3, -1.0},
        {"k_n", L::kMaxStiffness, L::kMaxStiffness * 1.001},
        {"k_n", 1e-3, 0.0},
        {"eccentricity", 1e3, 1e3 * 1.001},
        {"eccentricity", 1e-2, 0.0},
        {"total_k", 1e3, -5.0},
        {"damping", L::kMaxDamping, L::kMaxDamping * 1.001},
        {"damping", 0.0, -1e-6},
        {"mu_s", L::kMaxFriction, L::kMaxFriction * 1.001},
        {"mu_s", 0.0, -0.1},
        {"mu_d", 0.0, -0.1},
        {"finger_r", L::kMaxFingerRadius, L::kMaxFingerRadius * 1.001},
        {"finger_r", 0.004, L::kMinFingerRadius * 0.999},  // 4 mm: the default 20 mm pad still fits (< 2 pi R)
        {"pad_l", 1e-6, 0.0},
        {"tolerance", L::kMaxCurveTolerance, L::kMaxCurveTolerance * 1.001},
        {"tolerance", L::kMinCurveTolerance, L::kMinCurveTolerance * 0.999},
        {"kp", 0.0, -1.0},
        {"ki", 0.0, -1.0},
        {"kd", 0.0, -1e-9},
        {"max_drive", 1e3, 1e3 * 1.001},
        {"max_drive", 1e-3, 0.0},
        {"travel_mm", 1000.0, 1000.1},
        {"travel_mm", 0.0, -0.1},
        {"roller_kff", 0.0, -1.0},
        {"ff_cutoff_hz", 1e6, 1e6 * 1.001},
        {"ff_cutoff_hz", 1e-3, 0.0},
        {"wearable_force_kp", 0.0, -1e-9},
        {"wearable_force_kd", 0.0, -1e-9},
        {"wearable_position_kp", 0.0, -1.0},
        {"wearable_position_kd", 0.0, -1e-6},
        {"wearable_fit", 0.0, 0.5},
        {"fsr_noise", 0.1, 0.1001},
        {"fsr_noise", 0.0, -1e-6},
    };
    for (const Edge& e : edges) {
        const std::string name = e.name;
        CAPTURE(name);
        CAPTURE(e.accepted);
        CAPTURE(e.refused);
        EditorState s = fresh();
        REQUIRE(set_parameter(s, e.name, e.accepted));
        CHECK_FALSE(s.message_is_error);
        CHECK(s.field_error_name.empty());
        // eccentricity and total_k are computed back from k_t and k_n: equal to rounding.
        CHECK(*parameter_value(s, e.name) == doctest::Approx(e.accepted).epsilon(1e-12));
        check_refused(s, e.name, e.refused);
        check_refused(s, e.name, nan);
    }
    // Every parameter the panel offers is in the table above.
    for (const ParameterInfo& p : tunable_parameters()) {
        bool covered = false;
        for (const Edge& e : edges) covered |= std::string(e.name) == p.name;
        CHECK_MESSAGE(covered, p.name);
    }
}

TEST_CASE("parameter edit: limits that depend on another parameter name both") {
    EditorState s = fresh();
    // mu_d <= mu_s (Coulomb: kinetic below static).
    REQUIRE(set_parameter(s, "mu_s", 0.5));
    check_refused(s, "mu_d", 0.6);
    CHECK(s.field_error.find("static") != std::string::npos);
    REQUIRE(set_parameter(s, "mu_d", 0.5));
    // The pad must fit on its circle: L < 2 pi R (R = 10 mm here).
    REQUIRE(set_parameter(s, "finger_r", 0.010));
    check_refused(s, "pad_l", 2.0 * 3.14159265358979 * 0.010 + 1e-6);
    CHECK(s.field_error.find("circle") != std::string::npos);
    REQUIRE(set_parameter(s, "pad_l", 0.06));
}

TEST_CASE("parameter edit: an accepted value clears the field's error and is one undoable edit") {
    EditorState s;
    check_refused(s, "ke", 1e9);
    CHECK(*parameter_value(s, "ke") == 1000.0);
    const std::size_t undo = s.doc.undo_depth();
    REQUIRE(set_parameter(s, "ke", 1500.0));
    CHECK(s.field_error_name.empty());
    CHECK(s.message == "ke = 1500 N/m");
    CHECK(s.doc.undo_depth() == undo + 1);
    CHECK(s.doc.last_valid().force.stiffness == 1500.0);  // what the servo is sent
    REQUIRE(s.doc.undo());
    CHECK(*parameter_value(s, "ke") == 1000.0);
    // Roller gains are live, not in the scene: no undo entry.
    REQUIRE(set_parameter(s, "kp", 2e4));
    CHECK(s.roller.kp == 2e4);
    CHECK(s.doc.undo_depth() == undo);
}

TEST_CASE("parameter edit: the ellipsoid's Ke is its normal stiffness and keeps e") {
    EditorState s = fresh();
    REQUIRE(set_parameter(s, "eccentricity", 2.0));
    const double e = *parameter_value(s, "eccentricity");
    REQUIRE(set_parameter(s, "ke", 1800.0));
    CHECK(*parameter_value(s, "k_n") == 1800.0);
    CHECK(*parameter_value(s, "eccentricity") == doctest::Approx(e).epsilon(1e-12));
    REQUIRE(set_parameter(s, "k_n", 1200.0));
    CHECK(*parameter_value(s, "ke") == 1200.0);
}

TEST_CASE("parameter edit: a half-drawn invalid shape does not block a parameter edit") {
    EditorState s;
    Scene sc = s.doc.scene();
    Contour c;
    c.segments.push_back(LineSegment{Vec2(0.0, 0.0), Vec2(0.0, 0.0)});  // zero length: invalid
    sc.contours.push_back(c);
    s.doc.edit(sc, "add line");
    REQUIRE_FALSE(s.doc.valid());
    CHECK(set_parameter(s, "ke", 1200.0));
    CHECK(*parameter_value(s, "ke") == 1200.0);
}
