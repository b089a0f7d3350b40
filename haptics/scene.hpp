// scene.hpp — the scene model: what a scene file holds, in SI units (m, N, rad).
//
// A scene is a finger definition, contours (ordered chains of segments, solid on the RIGHT of the
// direction of travel), a force model and a contact-location rule. scene_io.hpp reads and writes it
// as JSON (format documented in scenes/README.md); environment.hpp compiles it for the servo.
#pragma once

#include "haptics/force_law.hpp"
#include "haptics/passivity_controller.hpp"
#include "haptics/vec2.hpp"

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace contactlab {

// A straight segment travelled from `from` to `to` (m).
struct LineSegment {
    Vec2 from{0.0, 0.0};
    Vec2 to{0.0, 0.0};
};

// A circular arc travelled from start_angle to end_angle (rad, counter-clockwise from +x). If
// end_angle > start_angle the arc runs counter-clockwise (solid outside the circle: concave as seen
// by the finger, e.g. a bowl); otherwise clockwise (solid inside: a convex bump).
// |end_angle - start_angle| is in (0, 2 pi].
struct ArcSegment {
    Vec2 center{0.0, 0.0};
    double radius = 0.0;  // m, > 0
    double start_angle = 0.0;
    double end_angle = 0.0;
};

// A quadratic Bezier curve through p0 and p2, pulled toward p1 (m). Travel from p0 to p2.
struct QuadSegment {
    Vec2 p0{0.0}, p1{0.0}, p2{0.0};
};

// A cubic Bezier curve from p0 to p3 with control points p1, p2 (m).
struct CubicSegment {
    Vec2 p0{0.0}, p1{0.0}, p2{0.0}, p3{0.0};
};

using Segment = std::variant<LineSegment, ArcSegment, QuadSegment, CubicSegment>;

// True for the Bezier segment types; bezier_of converts them (bezier.hpp).
bool segment_is_curve(const Segment& s);

Vec2 segment_start(const Segment& s);
Vec2 segment_end(const Segment& s);
// Unit tangent (direction of travel) at the start and at the end of the segment.
Vec2 segment_start_tangent(const Segment& s);
Vec2 segment_end_tangent(const Segment& s);
double segment_length(const Segment& s);  // m

struct Bezier;
// The Bezier curve of a quad or cubic segment (segment_is_curve(s) must hold).
Bezier segment_bezier(const Segment& s);

struct Contour {
    // A closed contour returns from its last segment to the first; drawn clockwise it is solid
    // inside. An open contour is a terrain-like profile: solid on the right, its two ends capped.
    bool closed = false;
    std::vector<Segment> segments;
};

// The finger's pad (seed 000): an arc of a circle of radius `radius` around the finger centre x_f,
// `length` long, centred on the direction phi - pi/2.
struct FingerDef {
    double radius = 0.026;  // R, m (seed 000: 2.6 cm)
    double length = 0.020;  // L, m (seed 000: 2.0 cm); 0 < L < 2 pi R
};

struct ForceDef {
    double stiffness = 1000.0;  // Ke, N/m (spring)
    double max_force = 1.5;     // N; the magnitude is clamped here, direction kept (seed 000)
    ForceLaw law;               // model, ellipsoid stiffnesses, damping, friction (force_law.hpp)
    // A loop that generates energy (too stiff for the device and rate): fault and ramp back, or
    // the passivity controller's damping (haptics/passivity_controller.hpp). "passivity" in JSON.
    PassivityMode passivity = PassivityMode::fault;
};

// Switches the force model keeping the stiffness the user feels pressing straight in: to the
// ellipsoid, k_normal = Ke and k_tangential = Ke / e with the eccentricity e = k_normal /
// k_tangential the scene already had (1 for a fresh scene: the same wall, anisotropy then added
// by e); back to the spring, Ke = k_normal. Setting the model alone left k_n = k_t = 1000 N/m
// under a 1500 N/m spring: the wall softened by a third on a click (issue 19).
void set_force_model(ForceDef& force, ForceModel model);

// How curves (quad, cubic) become the lines and arcs the proxy touches (bezier.hpp):
//   exact   — an arc spline within 1e-10 m of the curve (G1, so force and l_d stay continuous);
//   flatten — chords within `tolerance` m: cheaper to build and to touch, error up to tolerance.
enum class CurveMode { exact, flatten };

struct CurveDef {
    CurveMode mode = CurveMode::exact;
    double tolerance = 1e-4;  // m, used by flatten only
};

// The names scene files, protocols and command lines give the curve modes: "exact", "flatten".
const char* curve_mode_name(CurveMode mode);
// The mode a name stands for; nullopt for any other name.
std::optional<CurveMode> curve_mode_named(std::string_view name);

// Free-space anticipation of the nearest contact (proxy.hpp, ProxyDef::anticipation_budget):
// 0 segments a tick is the exact search every tick; N > 0 spreads a search that needs more than N
// segments' pieces over the next ticks, the anticipated contact late by the ticks it took.
struct AnticipationDef {
    int segments_per_tick = 0;
};
inline constexpr int kMaxAnticipationSegmentsPerTick = 1000000;

// Which contact location l_d a tick with several contacts reports (proxy.hpp).
enum class ContactRule {
    centroid,            // seed 000: the centroid of the contacts
    least_displacement,  // seed 002: the contact nearest the previous l_d (least roller travel)
};

struct ContactLocationDef {
    ContactRule rule = ContactRule::centroid;
};

// Seed 003's wearable platform (haptics/wearable/). The fingertip's 6x6 stiffness K of eq. 8, row
// major, on the pose xi = [p_x p_y p_z alpha beta gamma]: N/m on the translations, N m/rad on the
// angles, N/rad and N (m/m) in the off-diagonal blocks. Absent (has_finger_stiffness false), the
// platform uses the seed's K = k I read in millimetres (finger_stiffness.hpp).
struct WearableDef {
    bool has_finger_stiffness = false;
    std::array<double, 36> finger_stiffness{};
};

inline constexpr int kSceneFormatVersion = 1;

struct Scene {
    int version = kSceneFormatVersion;
    FingerDef finger;
    std::vector<Contour> contours;
    ForceDef force;
    ContactLocationDef contact_location;
    CurveDef curves;
    AnticipationDef anticipation;
    WearableDef wearable;
};

}  // namespace contactlab
