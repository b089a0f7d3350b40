// scene_io.cpp — scene files: JSON text <-> Scene, with validation and atomic saves.
//
// Index
//   [SECTION] Error paths       — building "contours[1].segments[4]" style locations
//   [SECTION] Reading           — typed field readers that throw SceneError with the path
//   [SECTION] Validation        — the rules shared by the parser and validate_scene()
//   [SECTION] Writing           — Scene -> JSON, lossless, and the atomic file save
#include "haptics/scene_io.hpp"

#include "haptics/atomic_file.hpp"

#include "haptics/bezier.hpp"
#include "haptics/contour_crossing.hpp"
#include "haptics/parameter_limits.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>
#include <sys/stat.h>
#include <unistd.h>

namespace contactlab {
namespace {

using nlohmann::json;

//-------------------------------------------------------------------------------------------------
// [SECTION] Error paths
//-------------------------------------------------------------------------------------------------

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
    throw SceneError(path.empty() ? problem : path + ": " + problem);
}

std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
}
std::string index(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

std::string fmt(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

using namespace limits;  // parameter_limits.hpp: the ranges scene files and the servo share

//-------------------------------------------------------------------------------------------------
// [SECTION] Reading
//-------------------------------------------------------------------------------------------------

const char* type_name(const json& j) {
    switch (j.type()) {
        case json::value_t::null: return "null";
        case json::value_t::object: return "an object";
        case json::value_t::array: return "an array";
        case json::value_t::string: return "a string";
        case json::value_t::boolean: return "a boolean";
        case json::value_t::binary: return "binary data";
        case json::value_t::discarded: return "nothing";
        default: return "a number";
    }
}

void expect_object(const json& j, const std::string& path) {
    if (!j.is_object()) fail(path, std::string("expected an object, found ") + type_name(j));
}

// Rejects keys the format does not define (a misspelt key would otherwise be silently ignored).
void reject_unknown_keys(const json& j, const std::string& path,
                         std::initializer_list<const char*> known) {
    for (auto it = j.begin(); it != j.end(); ++it) {
        bool ok = false;
        for (const char* k : known) ok = ok || it.key() == k;
        if (!ok) fail(join(path, it.key()), "unknown key");
    }
}

const json& require(const json& j, const std::string& path, const char* key) {
    auto it = j.find(key);
    if (it == j.end()) fail(join(path, key), "missing");
    return *it;
}

double read_number(const json& j, const std::string& path) {
    if (!j.is_number()) fail(path, std::string("expected a number, found ") + type_name(j));
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(path, "not a finite number");
    return v;
}

double read_number(const json& obj, const std::string& path, const char* key) {
    return read_number(require(obj, path, key), join(path, key));
}

Vec2 read_point(const json& obj, const std::string& path, const char* key) {
    const json& j = require(obj, path, key);
    const std::string p = join(path, key);
    if (!j.is_array() || j.size() != 2) fail(p, "expected a point [x, y] (m)");
    const Vec2 v{read_number(j[0], index(p, 0)), read_number(j[1], index(p, 1))};
    if (std::abs(v.x) > kMaxCoordinate || std::abs(v.y) > kMaxCoordinate)
        fail(p, "coordinate beyond +-" + fmt(kMaxCoordinate) + " m");
    return v;
}

std::string read_string(const json& obj, const std::string& path, const char* key) {
    const json& j = require(obj, path, key);
    if (!j.is_string()) fail(join(path, key), std::string("expected a string, found ") + type_name(j));
    return j.get<std::string>();
}

Segment read_segment(const json& j, const std::string& path) {
    expect_object(j, path);
    const std::string type = read_string(j, path, "type");
    if (type == "line") {
        reject_unknown_keys(j, path, {"type", "from", "to"});
        return LineSegment{read_point(j, path, "from"), read_point(j, path, "to")};
    }
    if (type == "arc") {
        reject_unknown_keys(j, path, {"type", "center", "radius", "start_angle", "end_angle"});
        ArcSegment a;
        a.center = read_point(j, path, "center");
        a.radius = read_number(j, path, "radius");
        a.start_angle = read_number(j, path, "start_angle");
        a.end_angle = read_number(j, path, "end_angle");
        return a;
    }
    if (type == "quad") {
        reject_unknown_keys(j, path, {"type", "p0", "p1", "p2"});
        return QuadSegment{read_point(j, path, "p0"), read_point(j, path, "p1"), read_point(j, path, "p2")};
    }
    if (type == "cubic") {
        reject_unknown_keys(j, path, {"type", "p0", "p1", "p2", "p3"});
        return CubicSegment{read_point(j, path, "p0"), read_point(j, path, "p1"), read_point(j, path, "p2"),
                            read_point(j, path, "p3")};
    }
    fail(join(path, "type"),
         "unknown segment type \"" + type + "\" (expected \"line\", \"arc\", \"quad\" or \"cubic\")");
}

Contour read_contour(const json& j, const std::string& path) {
    expect_object(j, path);
    reject_unknown_keys(j, path, {"closed", "segments"});
    Contour c;
    const json& closed = require(j, path, "closed");
    if (!closed.is_boolean()) fail(join(path, "closed"), "expected true or false");
    c.closed = closed.get<bool>();
    const json& segs = require(j, path, "segments");
    const std::string sp = join(path, "segments");
    if (!segs.is_array()) fail(sp, std::string("expected an array, found ") + type_name(segs));
    for (std::size_t i = 0; i < segs.size(); ++i) c.segments.push_back(read_segment(segs[i], index(sp, i)));
    return c;
}

Scene read_scene(const json& root) {
    Scene s;
    expect_object(root, "");
    reject_unknown_keys(root, "", {"version", "description", "finger", "contours", "force",
                                   "contact_location", "curves", "anticipation", "wearable"});
    const json& version = require(root, "", "version");
    // Only scalars are echoed back: dump() recurses, and a version nested 100000 arrays deep
    // would overflow the stack.
    if (!version.is_number_integer() || version.get<long long>() != kSceneFormatVersion)
        fail("version", "unsupported format version " +
                            (version.is_structured() ? std::string(type_name(version)) : version.dump()) +
                            " (this build reads " + std::to_string(kSceneFormatVersion) + ")");
    if (auto it = root.find("description"); it != root.end() && !it->is_string())
        fail("description", "expected a string");

    if (auto it = root.find("finger"); it != root.end()) {
        expect_object(*it, "finger");
        reject_unknown_keys(*it, "finger", {"radius", "length"});
        s.finger.radius = read_number(*it, "finger", "radius");
        s.finger.length = read_number(*it, "finger", "length");
    }

    const json& contours = require(root, "", "contours");
    if (!contours.is_array()) fail("contours", std::string("expected an array, found ") + type_name(contours));
    for (std::size_t i = 0; i < contours.size(); ++i)
        s.contours.push_back(read_contour(contours[i], index("contours", i)));

    if (auto it = root.find("force"); it != root.end()) {
        const json& f = *it;
        expect_object(f, "force");
        const std::string model = read_string(f, "force", "model");
        if (model == "spring") {
            reject_unknown_keys(f, "force", {"model", "stiffness", "max_force", "damping", "friction", "contacts", "passivity"});
            s.force.law.model = ForceModel::spring;
            s.force.stiffness = read_number(f, "force", "stiffness");
        } else if (model == "ellipsoid") {
            // Either the two stiffnesses, or seed 004's eccentricity and total stiffness.
            reject_unknown_keys(f, "force", {"model", "k_tangential", "k_normal", "eccentricity", "total_stiffness",
                                             "total_stiffness_formula", "field_angle", "max_force", "damping", "friction", "passivity",
                                             "contacts"});
            if (f.contains("field_angle")) s.force.law.field_angle = read_number(f, "force", "field_angle");
            s.force.law.model = ForceModel::ellipsoid;
            if (f.contains("k_tangential") || f.contains("k_normal")) {
                if (f.contains("eccentricity") || f.contains("total_stiffness"))
                    fail("force", "give k_tangential and k_normal, or eccentricity and total_stiffness, not both");
                s.force.law.k_tangential = read_number(f, "force", "k_tangential");
                s.force.law.k_normal = read_number(f, "force", "k_normal");
            } else {
                const double e = read_number(f, "force", "eccentricity");
                const double k = read_number(f, "force", "total_stiffness");
                if (!(e > 0.0) || e > 1e3) fail("force.eccentricity", "must lie in (0, 1000], got " + fmt(e));
                TotalStiffness formula = TotalStiffness::printed;
                if (f.contains("total_stiffness_formula")) {
                    const std::string name = read_string(f, "force", "total_stiffness_formula");
                    if (name == "diagonal_rms") {
                        formula = TotalStiffness::diagonal_rms;
                    } else if (name != "printed") {
                        fail("force.total_stiffness_formula",
                             "unknown formula \"" + name + "\" (expected \"printed\" or \"diagonal_rms\")");
                    }
                }
                s.force.law.k_tangential = tangential_stiffness_from(k, e, formula);
                s.force.law.k_normal = e * s.force.law.k_tangential;
            }
            s.force.stiffness = s.force.law.k_normal;  // the normal stiffness, for consumers of "Ke"
        } else {
            fail("force.model", "unknown force model \"" + model + "\" (expected \"spring\" or \"ellipsoid\")");
        }
        s.force.max_force = read_number(f, "force", "max_force");
        if (f.contains("damping")) s.force.law.damping = read_number(f, "force", "damping");
        if (f.contains("contacts")) {
            const std::string contacts = read_string(f, "force", "contacts");
            if (contacts == "sum") {
                s.force.law.contacts = ContactForce::sum;
            } else if (contacts != "proxy") {
                fail("force.contacts", "unknown contact force \"" + contacts + "\" (expected \"proxy\" or \"sum\")");
            }
        }
        if (f.contains("passivity")) {
            const std::string mode = read_string(f, "force", "passivity");
            if (mode == "control") {
                s.force.passivity = PassivityMode::control;
            } else if (mode != "fault") {
                fail("force.passivity", "unknown passivity mode \"" + mode + "\" (expected \"fault\" or \"control\")");
            }
        }
        if (auto fr = f.find("friction"); fr != f.end()) {
            expect_object(*fr, "force.friction");
            reject_unknown_keys(*fr, "force.friction", {"static", "dynamic"});
            s.force.law.mu_static = read_number(*fr, "force.friction", "static");
            s.force.law.mu_dynamic = read_number(*fr, "force.friction", "dynamic");
        }
    }

    if (auto it = root.find("contact_location"); it != root.end()) {
        expect_object(*it, "contact_location");
        reject_unknown_keys(*it, "contact_location", {"rule"});
        const std::string rule = read_string(*it, "contact_location", "rule");
        if (rule == "centroid") {
            s.contact_location.rule = ContactRule::centroid;
        } else if (rule == "least_displacement") {
            s.contact_location.rule = ContactRule::least_displacement;
        } else {
            fail("contact_location.rule",
                 "unknown rule \"" + rule + "\" (expected \"centroid\" or \"least_displacement\")");
        }
    }

    if (auto it = root.find("curves"); it != root.end()) {
        expect_object(*it, "curves");
        reject_unknown_keys(*it, "curves", {"mode", "tolerance"});
        const std::string mode = read_string(*it, "curves", "mode");
        const std::optional<CurveMode> named = curve_mode_named(mode);
        if (!named) fail("curves.mode", "unknown curve mode \"" + mode + "\" (expected \"exact\" or \"flatten\")");
        s.curves.mode = *named;
        if (it->contains("tolerance")) s.curves.tolerance = read_number(*it, "curves", "tolerance");
    }

    if (auto it = root.find("anticipation"); it != root.end()) {
        expect_object(*it, "anticipation");
        reject_unknown_keys(*it, "anticipation", {"segments_per_tick"});
        const double n = read_number(*it, "anticipation", "segments_per_tick");
        if (!(n >= 0.0 && n <= kMaxAnticipationSegmentsPerTick && n == std::floor(n)))
            fail("anticipation.segments_per_tick", "must be a whole number in [0, " +
                                                       std::to_string(kMaxAnticipationSegmentsPerTick) + "] (0: exact), got " + fmt(n));
        s.anticipation.segments_per_tick = static_cast<int>(n);
    }

    if (auto it = root.find("wearable"); it != root.end()) {
        expect_object(*it, "wearable");
        reject_unknown_keys(*it, "wearable", {"finger_stiffness"});
        const json& k = require(*it, "wearable", "finger_stiffness");
        const std::string kp = join("wearable", "finger_stiffness");
        if (!k.is_array() || k.size() != 6) fail(kp, "expected 6 rows of 6 numbers (the 6x6 stiffness of seed 003's eq. 8)");
        for (std::size_t r = 0; r < 6; ++r) {
            const std::string rp = index(kp, r);
            if (!k[r].is_array() || k[r].size() != 6) fail(rp, "expected a row of 6 numbers");
            for (std::size_t c = 0; c < 6; ++c) s.wearable.finger_stiffness[r * 6 + c] = read_number(k[r][c], index(rp, c));
        }
        s.wearable.has_finger_stiffness = true;
    }
    return s;
}

// Finds the JSON path of the value nlohmann's parser stopped at. A number that overflows a double
// ("1e999") is refused inside the parser (out_of_range.406) with neither a path nor a position;
// replaying the text through this SAX handler tracks the path up to that point, so the message can
// say where the number is, like every other problem. Used only after a parse has failed.
struct ErrorLocator : json::json_sax_t {
    struct Level {
        bool array = false;
        std::size_t count = 0;  // arrays: values begun so far
        std::string key;        // objects: the last key read
    };
    std::vector<Level> levels;

    bool begin_value() {
        if (!levels.empty() && levels.back().array) ++levels.back().count;
        return true;
    }
    bool open(bool array) {
        begin_value();
        levels.push_back(Level{array, 0, {}});
        return true;
    }
    bool close() {
        levels.pop_back();
        return true;
    }
    bool null() override { return begin_value(); }
    bool boolean(bool) override { return begin_value(); }
    bool number_integer(json::number_integer_t) override { return begin_value(); }
    bool number_unsigned(json::number_unsigned_t) override { return begin_value(); }
    bool number_float(json::number_float_t, const json::string_t&) override { return begin_value(); }
    bool string(json::string_t&) override { return begin_value(); }
    bool binary(json::binary_t&) override { return begin_value(); }
    bool start_object(std::size_t) override { return open(false); }
    bool key(json::string_t& k) override {
        levels.back().key = k;
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override { return open(true); }
    bool end_array() override { return close(); }
    bool parse_error(std::size_t, const std::string&, const json::exception&) override { return false; }

    // The failing value has not begun: in the innermost array its index is `count`; in the outer
    // ones the open container is the last value begun, `count - 1`.
    std::string path() const {
        std::string p;
        for (std::size_t i = 0; i < levels.size(); ++i) {
            const Level& l = levels[i];
            p = l.array ? index(p, i + 1 == levels.size() ? l.count : l.count - 1) : join(p, l.key);
        }
        return p;
    }
};

//-------------------------------------------------------------------------------------------------
// [SECTION] Validation
//-------------------------------------------------------------------------------------------------

// The coordinate bound read_point() applies, repeated here so that a scene built in memory cannot
// be saved into a file that load_scene_file() would then refuse.
void check_point_bound(Vec2 p, const std::string& path) {
    if (std::abs(p.x) > kMaxCoordinate || std::abs(p.y) > kMaxCoordinate)
        fail(path, "coordinate beyond +-" + fmt(kMaxCoordinate) + " m");
}

void validate_segment(const Segment& seg, const std::string& path) {
    auto finite = [](Vec2 v) { return is_finite(v); };
    if (auto* l = std::get_if<LineSegment>(&seg)) {
        if (!finite(l->from) || !finite(l->to)) fail(path, "not a finite number");
        check_point_bound(l->from, join(path, "from"));
        check_point_bound(l->to, join(path, "to"));
        if (glm::length(l->to - l->from) < kMinSegmentLength) fail(path, "zero-length line");
        return;
    }
    if (segment_is_curve(seg)) {
        const Bezier b = segment_bezier(seg);
        static const char* const names[4] = {"p0", "p1", "p2", "p3"};
        for (int i = 0; i <= b.degree; ++i) {
            if (!finite(b.p[i])) fail(join(path, names[i]), "not a finite number");
            check_point_bound(b.p[i], join(path, names[i]));
        }
        // Coincident or collinear control points are fine (the proxy handles cusps and
        // reversals); a curve that goes nowhere is not.
        if (segment_length(seg) < kMinSegmentLength) fail(path, "zero-length curve");
        return;
    }
    const auto& a = std::get<ArcSegment>(seg);
    if (!finite(a.center) || !std::isfinite(a.radius) || !std::isfinite(a.start_angle) ||
        !std::isfinite(a.end_angle))
        fail(path, "not a finite number");
    check_point_bound(a.center, join(path, "center"));
    if (!(a.radius > 0.0)) fail(join(path, "radius"), "arc radius must be > 0 m, got " + fmt(a.radius));
    if (a.radius > kMaxCoordinate) fail(join(path, "radius"), "arc radius beyond " + fmt(kMaxCoordinate) + " m");
    if (std::abs(a.start_angle) > 64.0 * kPi || std::abs(a.end_angle) > 64.0 * kPi)
        fail(path, "arc angles must lie within +-64 pi rad");
    const double sweep = std::abs(a.end_angle - a.start_angle);
    if (a.radius * sweep < kMinSegmentLength) fail(path, "zero-length arc");
    if (sweep > kTwoPi * (1.0 + 1e-12)) fail(path, "arc sweeps more than 2 pi rad (" + fmt(sweep) + ")");
}

void validate_contour(const Contour& c, const std::string& path) {
    const std::string sp = join(path, "segments");
    if (c.segments.empty()) fail(sp, "a contour needs at least one segment");
    for (std::size_t i = 0; i < c.segments.size(); ++i) validate_segment(c.segments[i], index(sp, i));
    const std::size_t n = c.segments.size();
    // Consecutive segments must join: the end of one is the start of the next.
    for (std::size_t i = 0; i + 1 < n + (c.closed ? 1 : 0); ++i) {
        const std::size_t j = (i + 1) % n;
        const double gap = glm::length(segment_start(c.segments[j]) - segment_end(c.segments[i]));
        if (gap > kSceneJoinTolerance)
            fail(index(sp, j), "gap of " + fmt(gap) + " m after segments[" + std::to_string(i) +
                                   "] (segments must join end to start)");
    }
}

// Closed contours are outlines of solids: one that crosses itself or another closed one has no
// consistent solid side (contour_crossing.hpp). Messages print the point in mm, as the UI does.
void check_crossings(const std::vector<Contour>& contours) {
    const std::optional<ContourCrossing> x = find_contour_crossing(contours);
    if (!x) return;
    // To the micrometre; a coordinate that rounds to zero prints as 0.000, never -0.000.
    auto mm = [](double v) { return std::abs(v) < 5e-7 ? 0.0 : v * 1e3; };
    char at[96];
    std::snprintf(at, sizeof at, "(%.3f, %.3f) mm", mm(x->point.x), mm(x->point.y));
    const std::string path = index("contours", static_cast<std::size_t>(x->contour_b));
    std::string what;
    if (x->contour_a == x->contour_b) {
        what = "crosses itself at " + std::string(at) +
               (x->segment_a == x->segment_b ? " (within segment " + std::to_string(x->segment_a) + ")"
                                             : " (segments " + std::to_string(x->segment_a) + " and " +
                                                   std::to_string(x->segment_b) + ")");
    } else {
        const std::string other = index("contours", static_cast<std::size_t>(x->contour_a));
        what = "crosses " + other + " at " + at + " (" + index(path + ".segments", static_cast<std::size_t>(x->segment_b)) +
               " and " + index(other + ".segments", static_cast<std::size_t>(x->segment_a)) + ")";
    }
    throw ContourCrossingError(path + ": " + what, x->point);
}

//-------------------------------------------------------------------------------------------------
// [SECTION] Writing
//-------------------------------------------------------------------------------------------------

json point_json(Vec2 p) { return json::array({p.x, p.y}); }

json segment_json(const Segment& seg) {
    if (auto* l = std::get_if<LineSegment>(&seg))
        return {{"type", "line"}, {"from", point_json(l->from)}, {"to", point_json(l->to)}};
    if (auto* q = std::get_if<QuadSegment>(&seg))
        return {{"type", "quad"}, {"p0", point_json(q->p0)}, {"p1", point_json(q->p1)}, {"p2", point_json(q->p2)}};
    if (auto* c = std::get_if<CubicSegment>(&seg))
        return {{"type", "cubic"},
                {"p0", point_json(c->p0)},
                {"p1", point_json(c->p1)},
                {"p2", point_json(c->p2)},
                {"p3", point_json(c->p3)}};
    const auto& a = std::get<ArcSegment>(seg);
    return {{"type", "arc"},
            {"center", point_json(a.center)},
            {"radius", a.radius},
            {"start_angle", a.start_angle},
            {"end_angle", a.end_angle}};
}

}  // namespace

void validate_scene(const Scene& s) {
    if (s.version != kSceneFormatVersion) fail("version", "unsupported format version " + std::to_string(s.version));
    const FingerDef& f = s.finger;
    if (!std::isfinite(f.radius) || f.radius < kMinFingerRadius || f.radius > kMaxFingerRadius)
        fail("finger.radius", "must lie in [" + fmt(kMinFingerRadius) + ", " + fmt(kMaxFingerRadius) +
                                  "] m, got " + fmt(f.radius));
    if (!std::isfinite(f.length) || !(f.length > 0.0))
        fail("finger.length", "pad length must be > 0 m, got " + fmt(f.length));
    if (f.length >= kTwoPi * f.radius)
        fail("finger.length", "pad (" + fmt(f.length) + " m) is longer than its circle (2 pi R = " +
                                  fmt(kTwoPi * f.radius) + " m)");
    for (std::size_t i = 0; i < s.contours.size(); ++i) validate_contour(s.contours[i], index("contours", i));
    check_crossings(s.contours);
    if (!std::isfinite(s.force.stiffness) || !(s.force.stiffness > 0.0) || s.force.stiffness > kMaxStiffness)
        fail("force.stiffness", "must lie in (0, " + fmt(kMaxStiffness) + "] N/m, got " + fmt(s.force.stiffness));
    if (!std::isfinite(s.force.max_force) || !(s.force.max_force > 0.0) || s.force.max_force > kMaxForceLimit)
        fail("force.max_force", "must lie in (0, " + fmt(kMaxForceLimit) + "] N, got " + fmt(s.force.max_force));
    const ForceLaw& law = s.force.law;
    if (law.model == ForceModel::ellipsoid) {
        for (const auto& [name, k] : {std::pair{"force.k_tangential", law.k_tangential}, std::pair{"force.k_normal", law.k_normal}})
            if (!std::isfinite(k) || !(k > 0.0) || k > kMaxStiffness)
                fail(name, "must lie in (0, " + fmt(kMaxStiffness) + "] N/m, got " + fmt(k));
    }
    if (!std::isfinite(law.field_angle) || std::abs(law.field_angle) > kPi)
        fail("force.field_angle", "must lie in [-pi, pi] rad, got " + fmt(law.field_angle));
    if (!std::isfinite(law.damping) || law.damping < 0.0 || law.damping > kMaxDamping)
        fail("force.damping", "must lie in [0, " + fmt(kMaxDamping) + "] N s/m, got " + fmt(law.damping));
    if (!std::isfinite(law.mu_static) || law.mu_static < 0.0 || law.mu_static > kMaxFriction)
        fail("force.friction.static", "must lie in [0, " + fmt(kMaxFriction) + "], got " + fmt(law.mu_static));
    if (!std::isfinite(law.mu_dynamic) || law.mu_dynamic < 0.0 || law.mu_dynamic > law.mu_static)
        fail("force.friction.dynamic", "must lie in [0, static = " + fmt(law.mu_static) + "], got " + fmt(law.mu_dynamic));
    // Flattening finer than 1e-9 m would need millions of chords for a centimetre curve (and the
    // exact mode is better there); coarser than 1 cm is not the curve any more.
    if (!std::isfinite(s.curves.tolerance) || s.curves.tolerance < kMinCurveTolerance ||
        s.curves.tolerance > kMaxCurveTolerance)
        fail("curves.tolerance", "must lie in [" + fmt(kMinCurveTolerance) + ", " + fmt(kMaxCurveTolerance) +
                                     "] m, got " + fmt(s.curves.tolerance));
    if (s.anticipation.segments_per_tick < 0 || s.anticipation.segments_per_tick > kMaxAnticipationSegmentsPerTick)
        fail("anticipation.segments_per_tick", "must lie in [0, " + std::to_string(kMaxAnticipationSegmentsPerTick) + "], got " +
                                                   std::to_string(s.anticipation.segments_per_tick));
    // The wearable's K: finite, symmetric (a spring's), positive on the diagonal. Positive
    // definiteness is checked where Eigen is (haptics/wearable/finger_stiffness.hpp, check_stiffness).
    if (s.wearable.has_finger_stiffness) {
        const auto& k = s.wearable.finger_stiffness;
        double scale = 0.0;
        for (const double v : k) {
            if (!std::isfinite(v)) fail("wearable.finger_stiffness", "has a non-finite entry");
            scale = std::max(scale, std::abs(v));
        }
        for (int r = 0; r < 6; ++r) {
            if (!(k[r * 6 + r] > 0.0))
                fail("wearable.finger_stiffness", "diagonal entry " + std::to_string(r) + " must be > 0, got " + fmt(k[r * 6 + r]));
            for (int c = r + 1; c < 6; ++c)
                if (std::abs(k[r * 6 + c] - k[c * 6 + r]) > 1e-9 * scale)
                    fail("wearable.finger_stiffness", "must be symmetric (a spring's stiffness): entries " + std::to_string(r) +
                                                          "," + std::to_string(c) + " and " + std::to_string(c) + "," +
                                                          std::to_string(r) + " differ");
        }
    }
}

namespace {
Scene parse_scene_checked(std::string_view text, const std::string& origin, bool validate) {
    try {
        json root;
        // Translates a byte offset (0-based) into a line and column a user can find.
        auto invalid_json_at = [&](std::size_t offset, const std::string& what) {
            std::size_t line = 1, col = 1;
            const std::size_t upto = std::min(offset, text.size());
            for (std::size_t i = 0; i < upto; ++i) {
                if (text[i] == '\n') { ++line; col = 1; } else { ++col; }
            }
            throw SceneError("line " + std::to_string(line) + ", column " + std::to_string(col) +
                             ": invalid JSON (" + what + ")");
        };
        // nlohmann's lexer reads a NUL byte as the end of the input, so "{...}\0junk" would pass.
        // JSON allows no raw NUL anywhere (not even inside strings): refuse it where it stands.
        if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos)
            invalid_json_at(nul, "NUL byte");
        try {
            root = json::parse(text.begin(), text.end());
        } catch (const json::parse_error& e) {
            std::string what = e.what();
            if (auto p = what.find("syntax error"); p != std::string::npos) what = what.substr(p);
            invalid_json_at(e.byte > 0 ? e.byte - 1 : 0, what);
        } catch (const json::out_of_range& e) {
            if (e.id != 406) throw;
            ErrorLocator where;
            json::sax_parse(text.begin(), text.end(), &where);
            std::string what = e.what();
            if (auto p = what.find("number overflow"); p != std::string::npos) what = what.substr(p);
            fail(where.path(), "not a finite number (" + what + ")");
        }
        Scene s = read_scene(root);
        if (validate) validate_scene(s);
        return s;
    } catch (const SceneError& e) {
        throw SceneError(origin + ": " + e.what());
    } catch (const std::exception& e) {  // anything nlohmann throws that we did not foresee
        throw SceneError(origin + ": " + e.what());
    }
}

std::string read_file_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError(path + ": cannot open (" + std::strerror(errno) + ")");
    std::ostringstream buf;
    buf << in.rdbuf();
    if (in.bad()) throw SceneError(path + ": read error");
    return buf.str();
}
}  // namespace

Scene parse_scene(std::string_view text, const std::string& origin) { return parse_scene_checked(text, origin, true); }

Scene load_scene_file(const std::string& path) { return parse_scene_checked(read_file_text(path), path, true); }

Scene load_work_in_progress(const std::string& path) { return parse_scene_checked(read_file_text(path), path, false); }

std::string scene_to_json_text(const Scene& s) {
    json root;
    root["version"] = s.version;
    root["finger"] = {{"radius", s.finger.radius}, {"length", s.finger.length}};
    json contours = json::array();
    for (const Contour& c : s.contours) {
        json segs = json::array();
        for (const Segment& seg : c.segments) segs.push_back(segment_json(seg));
        contours.push_back({{"closed", c.closed}, {"segments", std::move(segs)}});
    }
    root["contours"] = std::move(contours);
    const ForceLaw& law = s.force.law;
    if (law.model == ForceModel::spring) {
        root["force"] = {{"model", "spring"}, {"stiffness", s.force.stiffness}, {"max_force", s.force.max_force}};
    } else {
        root["force"] = {{"model", "ellipsoid"},
                         {"k_tangential", law.k_tangential},
                         {"k_normal", law.k_normal},
                         {"max_force", s.force.max_force}};
        if (law.field_angle != 0.0) root["force"]["field_angle"] = law.field_angle;
    }
    if (law.damping != 0.0) root["force"]["damping"] = law.damping;
    if (law.contacts == ContactForce::sum) root["force"]["contacts"] = "sum";
    if (s.force.passivity == PassivityMode::control) root["force"]["passivity"] = "control";
    if (law.mu_static != 0.0 || law.mu_dynamic != 0.0)
        root["force"]["friction"] = {{"static", law.mu_static}, {"dynamic", law.mu_dynamic}};
    root["contact_location"] = {
        {"rule", s.contact_location.rule == ContactRule::centroid ? "centroid" : "least_displacement"}};
    root["curves"] = {{"mode", curve_mode_name(s.curves.mode)},
                      {"tolerance", s.curves.tolerance}};
    if (s.anticipation.segments_per_tick != 0)
        root["anticipation"] = {{"segments_per_tick", s.anticipation.segments_per_tick}};
    if (s.wearable.has_finger_stiffness) {
        json rows = json::array();
        for (int r = 0; r < 6; ++r) {
            json row = json::array();
            for (int c = 0; c < 6; ++c) row.push_back(s.wearable.finger_stiffness[r * 6 + c]);
            rows.push_back(std::move(row));
        }
        root["wearable"] = {{"finger_stiffness", std::move(rows)}};
    }
    // nlohmann writes doubles with the shortest text that reads back to the same value.
    return root.dump(2) + "\n";
}

void save_scene_file(const Scene& s, const std::string& path) {
    validate_scene(s);
    const std::string text = scene_to_json_text(s);
    try {
        write_file_atomically(path, text);
    } catch (const FileWriteError& e) {
        throw SceneError(e.what());
    }
}

}  // namespace contactlab
