// Scene files (haptics/scene_io.hpp): the shipped scenes load, saves round-trip exactly and are
// atomic, and every rejected file gets a message of the form "ORIGIN: JSON.PATH: problem".
#include "haptics/proxy.hpp"
#include "haptics/scene_io.hpp"

#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace contactlab;
namespace fs = std::filesystem;

namespace {

const fs::path kScenesDir = fs::path(CONTACTLAB_SOURCE_DIR) / "scenes";

std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void write_text(const fs::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary);
    out << text;
}

// A fresh directory from mkdtemp, removed with everything in it at the end of the test.
struct TempDir {
    fs::path path;
    TempDir() {
        std::string tmpl = (fs::temp_directory_path() / "contactlab_scene_io_XXXXXX").string();
        REQUIRE(::mkdtemp(tmpl.data()) != nullptr);
        path = tmpl;
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    std::set<std::string> names() const {
        std::set<std::string> out;
        for (const auto& e : fs::directory_iterator(path)) out.insert(e.path().filename().string());
        return out;
    }
};

// The message of the SceneError that parsing `text` throws ("" if it parses, which fails the test).
std::string error_of(const std::string& text) {
    try {
        parse_scene(text, "t.json");
    } catch (const SceneError& e) {
        return e.what();
    }
    FAIL("parsed without error: " << text);
    return "";
}

std::string validate_error_of(const Scene& s) {
    try {
        validate_scene(s);
    } catch (const SceneError& e) {
        return e.what();
    }
    FAIL("validate_scene accepted the scene");
    return "";
}

// The message must be "t.json: PATH: ..." and mention `problem`. An empty path means the problem
// concerns the whole document (then the message is "t.json: problem...").
void check_error(const std::string& text, const std::string& path, const std::string& problem) {
    const std::string msg = error_of(text);
    const std::string prefix = "t.json: " + (path.empty() ? std::string() : path + ": ");
    CAPTURE(msg);
    CHECK(msg.rfind(prefix, 0) == 0);
    CHECK(msg.find(problem) != std::string::npos);
}

// A scene document with the given contours array and extra top-level members (",\"k\": v...").
std::string doc(const std::string& contours, const std::string& extra = "") {
    return R"({"version": 1, "contours": )" + contours + extra + "}";
}
std::string line_json(double x0, double y0, double x1, double y1) {
    std::ostringstream s;
    s.precision(17);
    s << R"({"type": "line", "from": [)" << x0 << ", " << y0 << R"(], "to": [)" << x1 << ", " << y1 << "]}";
    return s.str();
}
// One open contour of the given segment objects.
std::string open_contour(const std::string& segments) {
    return R"({"closed": false, "segments": [)" + segments + "]}";
}
// A valid one-line floor (m) and a document holding just that.
const std::string kFloor = open_contour(line_json(-0.1, 0.0, 0.1, 0.0));
const std::string kFloorDoc = doc("[" + kFloor + "]");

// Every field compared with ==, and the sign of zeros too (-0.0 == 0.0 would hide a lost sign).
void check_same_double(double a, double b) {
    CHECK(a == b);
    CHECK(std::signbit(a) == std::signbit(b));
}
void check_same_point(Vec2 a, Vec2 b) {
    check_same_double(a.x, b.x);
    check_same_double(a.y, b.y);
}
void check_same_scene(const Scene& a, const Scene& b) {
    CHECK(a.version == b.version);
    check_same_double(a.finger.radius, b.finger.radius);
    check_same_double(a.finger.length, b.finger.length);
    CHECK(a.force.law.model == b.force.law.model);
    check_same_double(a.force.law.k_tangential, b.force.law.k_tangential);
    check_same_double(a.force.law.k_normal, b.force.law.k_normal);
    check_same_double(a.force.law.damping, b.force.law.damping);
    check_same_double(a.force.law.mu_static, b.force.law.mu_static);
    check_same_double(a.force.law.mu_dynamic, b.force.law.mu_dynamic);
    CHECK(a.force.law.contacts == b.force.law.contacts);
    check_same_double(a.force.stiffness, b.force.stiffness);
    check_same_double(a.force.max_force, b.force.max_force);
    CHECK(a.contact_location.rule == b.contact_location.rule);
    REQUIRE(a.contours.size() == b.contours.size());
    for (std::size_t i = 0; i < a.contours.size(); ++i) {
        const Contour& ca = a.contours[i];
        const Contour& cb = b.contours[i];
        CHECK(ca.closed == cb.closed);
        REQUIRE(ca.segments.size() == cb.segments.size());
        for (std::size_t k = 0; k < ca.segments.size(); ++k) {
            CAPTURE(i);
            CAPTURE(k);
            REQUIRE(ca.segments[k].index() == cb.segments[k].index());
            if (auto* la = std::get_if<LineSegment>(&ca.segments[k])) {
                const auto& lb = std::get<LineSegment>(cb.segments[k]);
                check_same_point(la->from, lb.from);
                check_same_point(la->to, lb.to);
            } else {
                const auto& aa = std::get<ArcSegment>(ca.segments[k]);
                const auto& ab = std::get<ArcSegment>(cb.segments[k]);
                check_same_point(aa.center, ab.center);
                check_same_double(aa.radius, ab.radius);
                check_same_double(aa.start_angle, ab.start_angle);
                check_same_double(aa.end_angle, ab.end_angle);
            }
        }
    }
}

// A valid scene full of values whose decimal text is awkward: 0.1 + 0.2, 1/3, -0.0, subnormal and
// near-subnormal coordinates, angles that are not short decimals. Joins are exact (shared values).
Scene awkward_scene() {
    Scene s;
    s.finger.radius = 0.1 / 3.0;                   // m
    s.finger.length = std::nextafter(0.02, 1.0);   // m, one ulp above 2 cm
    s.force.stiffness = 1234.5678901234567;        // N/m
    s.force.max_force = 0.1 + 0.2;                 // N (0.30000000000000004)
    const double tiny = 1e-300;                    // m: valid, far below the join tolerance
    const double denorm = std::numeric_limits<double>::denorm_min();
    Contour open;
    open.segments.push_back(LineSegment{{-1.0 / 3.0, -0.0}, {tiny, denorm}});
    open.segments.push_back(LineSegment{{tiny, denorm}, {0.1 + 0.2, 2.0 / 3.0}});
    // An arc starting exactly where the line ends would need a sin/cos-exact point; start a second
    // contour instead, so the arc's own values can be as awkward as they like.
    s.contours.push_back(open);
    Contour circle;
    circle.closed = true;  // a full circle closes on itself
    circle.segments.push_back(ArcSegment{{0.7, -0.0}, 0.1 / 7.0, -kPi / 3.0, -kPi / 3.0 + kTwoPi});
    s.contours.push_back(circle);
    Contour bump;  // clockwise arc (solid inside), then a line from its exact end point
    const ArcSegment a{{-0.5, 0.25}, 0.03, kPi, kPi / 7.0};
    bump.segments.push_back(a);
    bump.segments.push_back(LineSegment{segment_end(Segment{a}), {1e-7, -123.456}});
    s.contours.push_back(bump);
    return s;
}

}  // namespace

//-------------------------------------------------------------------------------------------------
// Shipped scenes
//-------------------------------------------------------------------------------------------------

TEST_CASE("scene io: every shipped scene loads, validates and round-trips") {
    const std::set<std::string> expected = {"flat.json", "block.json", "bowl.json", "steps.json",
                                            "thin_wall.json"};
    std::set<std::string> found;
    for (const auto& e : fs::directory_iterator(kScenesDir)) {
        if (e.path().extension() != ".json") continue;
        found.insert(e.path().filename().string());
        CAPTURE(e.path().string());
        Scene s;
        REQUIRE_NOTHROW(s = load_scene_file(e.path().string()));
        CHECK_NOTHROW(validate_scene(s));
        CHECK(!s.contours.empty());
        const std::string text = scene_to_json_text(s);
        const Scene back = parse_scene(text, e.path().string());
        check_same_scene(s, back);
        CHECK(scene_to_json_text(back) == text);
        // The file states its purpose (scenes/README.md lists it).
        CHECK(read_text(e.path()).find("\"description\"") != std::string::npos);
    }
    for (const std::string& name : expected) {
        CAPTURE(name);
        CHECK(found.count(name) == 1);
    }
}

TEST_CASE("scene io: shipped scenes hold what their descriptions say") {
    const Scene flat = load_scene_file((kScenesDir / "flat.json").string());
    REQUIRE(flat.contours.size() == 1);
    REQUIRE(flat.contours[0].segments.size() == 1);
    const auto& floor = std::get<LineSegment>(flat.contours[0].segments[0]);
    CHECK(floor.from == Vec2{-0.3, 0.0});  // travelled left to right: solid below
    CHECK(floor.to == Vec2{0.3, 0.0});
    CHECK(flat.finger.radius == 0.026);
    CHECK(flat.finger.length == 0.02);
    CHECK(flat.force.stiffness == 1000.0);
    CHECK(flat.force.max_force == 1.5);

    const Scene bowl = load_scene_file((kScenesDir / "bowl.json").string());
    REQUIRE(bowl.contours.size() == 1);
    REQUIRE(bowl.contours[0].segments.size() == 3);
    const auto& a = std::get<ArcSegment>(bowl.contours[0].segments[1]);
    CHECK(a.radius == 0.05);
    CHECK(a.end_angle > a.start_angle);  // counter-clockwise: concave, free inside

    const Scene block = load_scene_file((kScenesDir / "block.json").string());
    REQUIRE(block.contours.size() == 1);
    CHECK(block.contours[0].segments.size() == 3);
    const Scene thin = load_scene_file((kScenesDir / "thin_wall.json").string());
    REQUIRE(thin.contours.size() == 1);
    const auto& up = std::get<LineSegment>(thin.contours[0].segments[1]);
    const auto& down = std::get<LineSegment>(thin.contours[0].segments[3]);
    CHECK(std::abs((down.from.x - up.from.x) - 0.001) < 1e-12);  // 1 mm thick
}

//-------------------------------------------------------------------------------------------------
// Round trip and defaults
//-------------------------------------------------------------------------------------------------

TEST_CASE("scene io: text round trip is lossless for awkward doubles, -0.0 included") {
    const Scene s = awkward_scene();
    REQUIRE_NOTHROW(validate_scene(s));
    const std::string text = scene_to_json_text(s);
    const Scene back = parse_scene(text);
    check_same_scene(s, back);
    CHECK(scene_to_json_text(back) == text);  // and the text itself is stable
}

TEST_CASE("scene io: save then load is lossless") {
    TempDir dir;
    const Scene s = awkward_scene();
    const std::string path = (dir.path / "awkward.json").string();
    save_scene_file(s, path);
    check_same_scene(s, load_scene_file(path));
    CHECK(read_text(path) == scene_to_json_text(s));
}

TEST_CASE("scene io: omitted finger, force and contact_location take the documented defaults") {
    const Scene s = parse_scene(kFloorDoc);
    CHECK(s.version == 1);
    CHECK(s.finger.radius == 0.026);  // m
    CHECK(s.finger.length == 0.020);  // m
    CHECK(s.force.law.model == ForceModel::spring);
    CHECK(s.force.stiffness == 1000.0);  // N/m
    CHECK(s.force.max_force == 1.5);     // N
    CHECK(s.contact_location.rule == ContactRule::centroid);
    CHECK_NOTHROW(parse_scene(doc("[]")));  // no contours at all is a valid (empty) scene
    CHECK_NOTHROW(parse_scene("\xEF\xBB\xBF" + kFloorDoc));  // a UTF-8 byte-order mark is skipped
}

TEST_CASE("scene io: joins within 1e-9 m are accepted, a full 2 pi arc is accepted") {
    const double eps = 0.5 * kSceneJoinTolerance;  // m
    CHECK_NOTHROW(parse_scene(doc("[" + open_contour(line_json(0, 0, 1, 0) + "," + line_json(1, eps, 2, 0)) + "]")));
    const std::string circle =
        R"({"closed": true, "segments": [{"type": "arc", "center": [0, 0], "radius": 0.05,
            "start_angle": 0, "end_angle": 6.283185307179586}]})";
    CHECK_NOTHROW(parse_scene(doc("[" + circle + "]")));
}

//-------------------------------------------------------------------------------------------------
// Atomic save
//-------------------------------------------------------------------------------------------------

TEST_CASE("scene io: save creates the file and leaves no temporary behind") {
    TempDir dir;
    const std::string path = (dir.path / "scene.json").string();
    save_scene_file(parse_scene(kFloorDoc), path);
    CHECK(dir.names() == std::set<std::string>{"scene.json"});
    CHECK_NOTHROW(load_scene_file(path));
}

TEST_CASE("scene io: save replaces an existing file by rename, never rewriting it in place") {
    TempDir dir;
    const fs::path path = dir.path / "scene.json";
    write_text(path, "old contents\n");
    // A hard link keeps the old inode reachable: an in-place rewrite would change what it reads.
    fs::create_hard_link(path, dir.path / "old_link");
    struct stat before {};
    REQUIRE(::stat(path.c_str(), &before) == 0);

    const Scene s = awkward_scene();
    save_scene_file(s, path.string());

    struct stat after {};
    REQUIRE(::stat(path.c_str(), &after) == 0);
    CHECK(after.st_ino != before.st_ino);
    CHECK(read_text(dir.path / "old_link") == "old contents\n");
    check_same_scene(s, load_scene_file(path.string()));
    CHECK(dir.names() == std::set<std::string>{"scene.json", "old_link"});
}

TEST_CASE("scene io: save into a missing directory throws SceneError and creates nothing") {
    TempDir dir;
    const fs::path path = dir.path / "no_such_dir" / "scene.json";
    try {
        save_scene_file(parse_scene(kFloorDoc), path.string());
        FAIL("save into a missing directory succeeded");
    } catch (const SceneError& e) {
        CHECK(std::string(e.what()).find(path.string()) != std::string::npos);
    }
    CHECK(!fs::exists(dir.path / "no_such_dir"));
    CHECK(dir.names().empty());
}

TEST_CASE("scene io: a failed rename removes its temporary and keeps the target") {
    TempDir dir;
    // The target is a non-empty directory: the temporary is written, then rename() must fail.
    const fs::path target = dir.path / "scene.json";
    fs::create_directory(target);
    write_text(target / "keep", "x");
    CHECK_THROWS_AS(save_scene_file(parse_scene(kFloorDoc), target.string()), SceneError);
    CHECK(dir.names() == std::set<std::string>{"scene.json"});
    CHECK(read_text(target / "keep") == "x");
}

TEST_CASE("scene io: an invalid scene is refused before any file is touched") {
    TempDir dir;
    const fs::path path = dir.path / "scene.json";
    write_text(path, "keep me\n");
    Scene bad = parse_scene(kFloorDoc);
    bad.force.stiffness = -1.0;  // N/m
    CHECK_THROWS_AS(save_scene_file(bad, path.string()), SceneError);
    CHECK(read_text(path) == "keep me\n");
    CHECK(dir.names() == std::set<std::string>{"scene.json"});
}

//-------------------------------------------------------------------------------------------------
// Error messages: "ORIGIN: JSON.PATH: problem"
//-------------------------------------------------------------------------------------------------

TEST_CASE("scene io error: zero-length line names contours[1].segments[4]") {
    std::string segs;
    for (int i = 0; i < 4; ++i) segs += line_json(i, 1, i + 1, 1) + ",";
    segs += line_json(4, 1, 4, 1);  // from == to
    const std::string text = doc("[" + kFloor + "," + open_contour(segs) + "]");
    CHECK(error_of(text) == "t.json: contours[1].segments[4]: zero-length line");
}

TEST_CASE("scene io error: gap between consecutive segments") {
    const std::string segs = line_json(0, 0, 1, 0) + "," + line_json(1, 1e-6, 2, 0);  // 1 um gap
    check_error(doc("[" + open_contour(segs) + "]"), "contours[0].segments[1]",
                "gap of 1e-06 m after segments[0]");
}

TEST_CASE("scene io error: closed contour must return from its last segment to its first") {
    const std::string tri = line_json(0, 0, 1, 0) + "," + line_json(1, 0, 0, 1) + "," +
                            line_json(0, 1, 0, 0.001);  // stops 1 mm short of the start
    check_error(doc(R"([{"closed": true, "segments": [)" + tri + "]}]"), "contours[0].segments[0]",
                "gap of 0.001 m after segments[2]");
    // The same chain left open is fine.
    CHECK_NOTHROW(parse_scene(doc("[" + open_contour(tri) + "]")));
}

//-------------------------------------------------------------------------------------------------
// Closed contours that cross (contour_crossing.hpp): the contour, the point in mm, the segments
//-------------------------------------------------------------------------------------------------

namespace {
std::string closed_contour(const std::string& segments) {
    return R"({"closed": true, "segments": [)" + segments + "]}";
}
// A closed polyline through the points (m), back to the first.
std::string closed_polyline(const std::vector<Vec2>& pts) {
    std::string segs;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const Vec2 a = pts[i], b = pts[(i + 1) % pts.size()];
        segs += (i ? "," : "") + line_json(a.x, a.y, b.x, b.y);
    }
    return closed_contour(segs);
}
const std::vector<Vec2> kBowTie = {{0.0, 0.0}, {0.01, 0.01}, {0.01, 0.0}, {0.0, 0.01}};  // m
}  // namespace

TEST_CASE("scene io error: a closed contour that crosses itself, with the point in mm and the segments") {
    // The bow-tie's diagonals (segments 0 and 2) cross at (5, 5) mm.
    CHECK(error_of(doc("[" + closed_polyline(kBowTie) + "]")) ==
          "t.json: contours[0]: crosses itself at (5.000, 5.000) mm (segments 0 and 2)");
    // A figure 8 of two full circles of 1 cm, tangent at the origin, wound opposite ways.
    const std::string eight =
        R"({"type": "arc", "center": [-0.01, 0], "radius": 0.01, "start_angle": 0, "end_angle": -6.283185307179586},)"
        R"({"type": "arc", "center": [0.01, 0], "radius": 0.01, "start_angle": 3.141592653589793, "end_angle": 9.42477796076938})";
    CHECK(error_of(doc("[" + kFloor + "," + closed_contour(eight) + "]")) ==
          "t.json: contours[1]: crosses itself at (0.000, 0.000) mm (segments 0 and 1)");
    // The same chains open are terrain profiles: they may cross themselves.
    std::string zigzag;
    for (std::size_t i = 0; i + 1 < kBowTie.size(); ++i)
        zigzag += (i ? "," : "") + line_json(kBowTie[i].x, kBowTie[i].y, kBowTie[i + 1].x, kBowTie[i + 1].y);
    CHECK_NOTHROW(parse_scene(doc("[" + open_contour(zigzag) + "]")));
}

TEST_CASE("scene io error: two closed contours that cross name both, the later one first") {
    // Squares of 1 cm at (0,0) and (5,3) mm: the second's left side crosses the first's top.
    auto square = [](double x, double y) {
        return closed_polyline({{x, y}, {x, y + 0.01}, {x + 0.01, y + 0.01}, {x + 0.01, y}});
    };
    CHECK(error_of(doc("[" + square(0, 0) + "," + square(0.005, 0.003) + "]")) ==
          "t.json: contours[1]: crosses contours[0] at (5.000, 10.000) mm (contours[1].segments[0] and "
          "contours[0].segments[1])");
    CHECK_NOTHROW(parse_scene(doc("[" + square(0, 0) + "," + square(0.012, 0) + "]")));
    // Touching at a corner is not crossing (scenes/README.md).
    CHECK_NOTHROW(parse_scene(doc("[" + square(0, 0) + "," + square(0.01, 0.01) + "]")));
    // An open chain through a closed square is allowed.
    CHECK_NOTHROW(parse_scene(doc("[" + square(0, 0) + "," + open_contour(line_json(-0.005, 0.005, 0.015, 0.005)) + "]")));
}

TEST_CASE("scene io error: a crossing scene built in memory is refused by validate_scene and by save") {
    Scene s = parse_scene(kFloorDoc);
    Contour bow;
    bow.closed = true;
    for (std::size_t i = 0; i < kBowTie.size(); ++i) bow.segments.push_back(LineSegment{kBowTie[i], kBowTie[(i + 1) % 4]});
    s.contours.push_back(bow);
    CHECK(validate_error_of(s) == "contours[1]: crosses itself at (5.000, 5.000) mm (segments 0 and 2)");
    // The error carries the point (m) for the editor's mark.
    try {
        validate_scene(s);
    } catch (const ContourCrossingError& e) {
        CHECK(glm::length(e.point - Vec2{0.005, 0.005}) < 1e-15);
    }
    TempDir dir;
    const fs::path path = dir.path / "bow.json";
    CHECK_THROWS_AS(save_scene_file(s, path.string()), SceneError);
    CHECK(dir.names().empty());
    // Work in progress (an editor recovery file) may cross: it is the user's drawing.
    write_text(path, scene_to_json_text(s));
    CHECK(load_work_in_progress(path.string()).contours.size() == 2);
    CHECK_THROWS_AS(load_scene_file(path.string()), SceneError);
}

TEST_CASE("scene io error: numbers that overflow a double are not finite, with their path") {
    // JSON has no inf; 1e999 is how one arrives. The parser refuses it, naming where it was.
    check_error(doc(R"([{"closed": false, "segments": [{"type": "line", "from": [0, 0], "to": [1, 1e999]}]}])"),
                "contours[0].segments[0].to[1]", "not a finite number");
    check_error(doc("[" + kFloor + "]", R"(, "force": {"model": "spring", "stiffness": -1e999, "max_force": 1})"),
                "force.stiffness", "not a finite number");
    check_error(R"({"version": 1, "finger": {"radius": 1e400, "length": 0.02}, "contours": []})",
                "finger.radius", "not a finite number");
    // A scene built in memory is checked by the same rules.
    Scene s = parse_scene(kFloorDoc);
    std::get<LineSegment>(s.contours[0].segments[0]).to.x = std::numeric_limits<double>::infinity();
    CHECK(validate_error_of(s) == "contours[0].segments[0]: not a finite number");
    s = parse_scene(kFloorDoc);
    s.finger.radius = std::numeric_limits<double>::quiet_NaN();
    CHECK(validate_error_of(s).rfind("finger.radius: ", 0) == 0);
}

TEST_CASE("scene io error: unknown segment type") {
    check_error(doc("[" + open_contour(R"({"type": "bezier", "from": [0, 0], "to": [1, 0]})") + "]"),
                "contours[0].segments[0].type", "unknown segment type \"bezier\"");
}

TEST_CASE("scene io error: wrong or missing version") {
    check_error(R"({"version": 2, "contours": []})", "version", "unsupported format version 2");
    check_error(R"({"version": 1.0, "contours": []})", "version", "unsupported format version");
    check_error(R"({"version": "1", "contours": []})", "version", "unsupported format version \"1\"");
    check_error(R"({"contours": []})", "version", "missing");
}

TEST_CASE("scene io error: finger radius out of range") {
    const std::string c = R"(, "contours": [])";
    check_error(R"({"version": 1, "finger": {"radius": -0.026, "length": 0.02})" + c + "}", "finger.radius",
                "must lie in [0.0001, 1] m, got -0.026");
    // 26 typed in millimetres instead of 0.026 m.
    check_error(R"({"version": 1, "finger": {"radius": 26, "length": 0.02})" + c + "}", "finger.radius",
                "got 26");
    check_error(R"({"version": 1, "finger": {"radius": 0.026, "length": 0})" + c + "}", "finger.length",
                "pad length must be > 0 m");
}

TEST_CASE("scene io error: pad longer than its circle") {
    check_error(R"({"version": 1, "finger": {"radius": 0.01, "length": 0.07}, "contours": []})", "finger.length",
                "is longer than its circle");
}

TEST_CASE("scene io error: unknown keys are rejected wherever they are") {
    check_error(doc("[" + kFloor + "]", R"(, "colour": "red")"), "colour", "unknown key");
    check_error(R"({"version": 1, "finger": {"radius": 0.026, "length": 0.02, "radious": 1}, "contours": []})",
                "finger.radious", "unknown key");
    check_error(doc("[" + open_contour(R"({"type": "line", "from": [0, 0], "to": [1, 0], "radius": 1})") + "]"),
                "contours[0].segments[0].radius", "unknown key");
    check_error(doc(R"([{"closed": false, "segments": [], "name": "x"}])"), "contours[0].name", "unknown key");
    check_error(doc("[]", R"(, "contact_location": {"rule": "centroid", "weight": 1})"), "contact_location.weight",
                "unknown key");
}

TEST_CASE("scene io error: missing keys") {
    check_error(R"({"version": 1})", "contours", "missing");
    check_error(doc(R"([{"segments": []}])"), "contours[0].closed", "missing");
    check_error(doc("[" + open_contour(R"({"type": "line", "from": [0, 0]})") + "]"), "contours[0].segments[0].to",
                "missing");
    check_error(doc("[" + open_contour(R"({"from": [0, 0], "to": [1, 0]})") + "]"), "contours[0].segments[0].type",
                "missing");
    check_error(doc("[" + open_contour(R"({"type": "arc", "center": [0, 0], "radius": 1, "start_angle": 0})") + "]"),
                "contours[0].segments[0].end_angle", "missing");
    check_error(doc("[]", R"(, "force": {"model": "spring", "stiffness": 1000})"), "force.max_force", "missing");
    check_error(R"({"version": 1, "finger": {"radius": 0.026}, "contours": []})", "finger.length", "missing");
}

TEST_CASE("scene io error: wrong types") {
    check_error("[1, 2]", "", "expected an object, found an array");
    check_error(doc("{}"), "contours", "expected an array, found an object");
    check_error(doc("[[]]"), "contours[0]", "expected an object, found an array");
    check_error(doc(R"([{"closed": "yes", "segments": []}])"), "contours[0].closed", "expected true or false");
    check_error(doc(R"([{"closed": false, "segments": {}}])"), "contours[0].segments", "expected an array");
    check_error(doc(R"([{"closed": false, "segments": [7]}])"), "contours[0].segments[0]",
                "expected an object, found a number");
    check_error(doc("[" + open_contour(R"({"type": "line", "from": [0], "to": [1, 0]})") + "]"),
                "contours[0].segments[0].from", "expected a point [x, y] (m)");
    check_error(doc("[" + open_contour(R"({"type": "line", "from": [0, "0"], "to": [1, 0]})") + "]"),
                "contours[0].segments[0].from[1]", "expected a number, found a string");
    check_error(doc("[" + open_contour(R"({"type": "line", "from": [0, 0], "to": [1, null]})") + "]"),
                "contours[0].segments[0].to[1]", "expected a number, found null");
    check_error(doc("[" + open_contour(R"({"type": 3, "from": [0, 0], "to": [1, 0]})") + "]"),
                "contours[0].segments[0].type", "expected a string, found a number");
    check_error(doc("[" + open_contour(R"({"type": "arc", "center": [0, 0], "radius": true, "start_angle": 0,
                                          "end_angle": 1})") + "]"),
                "contours[0].segments[0].radius", "expected a number, found a boolean");
    check_error(doc("[]", R"(, "description": 5)"), "description", "expected a string");
    check_error(doc("[]", R"(, "force": [])"), "force", "expected an object, found an array");
    check_error(doc("[]", R"(, "force": {"model": 1, "stiffness": 1000, "max_force": 1})"), "force.model",
                "expected a string, found a number");
}

TEST_CASE("scene io error: invalid JSON syntax reports line and column") {
    // Line 3, column 16 is the stray comma.
    CHECK(error_of("{\n  \"version\": 1,\n  \"contours\": [,]\n}").rfind(
              "t.json: line 3, column 16: invalid JSON (syntax error", 0) == 0);
    check_error("", "line 1, column 1", "unexpected end of input");
    check_error("{\"version\": 1,\n\"contours\": [", "line 2, column 14", "unexpected end of input");
    check_error(kFloorDoc + " x", "line 1, column " + std::to_string(kFloorDoc.size() + 2), "invalid JSON");
    // JSON allows no raw NUL; nlohmann alone would stop reading at one and accept what came before.
    check_error(std::string("{\"version\": 1,\0 \"contours\": []}", 31), "line 1, column 15",
                "invalid JSON (NUL byte)");
    check_error(kFloorDoc + std::string(1, '\0') + "junk", "line 1, column " + std::to_string(kFloorDoc.size() + 1),
                "invalid JSON (NUL byte)");
    // Column 48 is the byte 0xff, which is not UTF-8.
    check_error("{\"version\": 1, \"contours\": [], \"description\": \"\xff\"}", "line 1, column 48",
                "ill-formed UTF-8");
}

TEST_CASE("scene io error: arc with zero or negative radius") {
    const auto arc = [](const std::string& radius) {
        return doc("[" + open_contour(R"({"type": "arc", "center": [0, 0], "radius": )" + radius +
                                      R"(, "start_angle": 0, "end_angle": 1})") + "]");
    };
    check_error(arc("0"), "contours[0].segments[0].radius", "arc radius must be > 0 m, got 0");
    check_error(arc("-0.05"), "contours[0].segments[0].radius", "arc radius must be > 0 m, got -0.05");
}

TEST_CASE("scene io error: arc sweeping more than 2 pi, or not at all") {
    const auto arc = [](const std::string& a0, const std::string& a1) {
        return doc("[" + open_contour(R"({"type": "arc", "center": [0, 0], "radius": 0.05, "start_angle": )" + a0 +
                                      R"(, "end_angle": )" + a1 + "}") + "]");
    };
    check_error(arc("0", "7"), "contours[0].segments[0]", "arc sweeps more than 2 pi rad (7)");
    check_error(arc("1", "-6"), "contours[0].segments[0]", "arc sweeps more than 2 pi rad (7)");
    check_error(arc("1", "1"), "contours[0].segments[0]", "zero-length arc");
    check_error(arc("0", "1000"), "contours[0].segments[0]", "arc angles must lie within +-64 pi rad");
}

TEST_CASE("scene io error: stiffness must be > 0 and not absurd") {
    const auto force = [](const std::string& k, const std::string& fmax) {
        return doc("[]", R"(, "force": {"model": "spring", "stiffness": )" + k + R"(, "max_force": )" + fmax + "}");
    };
    check_error(force("0", "1.5"), "force.stiffness", "must lie in (0, 1e+07] N/m, got 0");
    check_error(force("-1000", "1.5"), "force.stiffness", "got -1000");
    check_error(force("1e9", "1.5"), "force.stiffness", "got 1e+09");
    check_error(force("1000", "0"), "force.max_force", "must lie in (0, 10000] N, got 0");
    check_error(force("1000", "-1.5"), "force.max_force", "got -1.5");
    check_error(force("1000", "1e6"), "force.max_force", "got 1e+06");
}

TEST_CASE("scene io: every force-law field round-trips, contacts defaults to proxy") {
    const Scene a = parse_scene(doc("[" + kFloor + "]",
        R"(, "force": {"model": "ellipsoid", "k_tangential": 412.5, "k_normal": 1300.25, "max_force": 2,
              "damping": 0.75, "friction": {"static": 0.6, "dynamic": 0.45}, "contacts": "sum"})"));
    CHECK(a.force.law.contacts == ContactForce::sum);
    CHECK(a.force.law.k_tangential == 412.5);
    CHECK(a.force.law.mu_dynamic == 0.45);
    check_same_scene(a, parse_scene(scene_to_json_text(a)));
    CHECK(parse_scene(kFloorDoc).force.law.contacts == ContactForce::proxy);
    check_error(doc("[]", R"(, "force": {"model": "spring", "stiffness": 1000, "max_force": 1, "contacts": "max"})"),
                "force.contacts", "unknown contact force \"max\" (expected \"proxy\" or \"sum\")");
}

TEST_CASE("scene io error: unknown force model or contact rule") {
    check_error(doc("[]", R"(, "force": {"model": "damper", "stiffness": 1000, "max_force": 1})"), "force.model",
                "unknown force model \"damper\"");
    check_error(doc("[]", R"(, "contact_location": {"rule": "deepest"})"), "contact_location.rule",
                "unknown rule \"deepest\"");
}

TEST_CASE("scene io error: empty contour and coordinates beyond 1e6 m") {
    check_error(doc(R"([{"closed": false, "segments": []}])"), "contours[0].segments",
                "a contour needs at least one segment");
    check_error(doc("[" + open_contour(line_json(0, 0, 2e6, 0)) + "]"), "contours[0].segments[0].to",
                "coordinate beyond +-1e+06 m");
    // validate_scene applies the same bound, so save never writes a file that load refuses.
    Scene s = parse_scene(kFloorDoc);
    std::get<LineSegment>(s.contours[0].segments[0]).from.x = -2e6;  // m
    CHECK(validate_error_of(s) == "contours[0].segments[0].from: coordinate beyond +-1e+06 m");
}

TEST_CASE("scene io error: load_scene_file names the file, for missing and bad files") {
    TempDir dir;
    const std::string missing = (dir.path / "missing.json").string();
    try {
        load_scene_file(missing);
        FAIL("loaded a missing file");
    } catch (const SceneError& e) {
        CHECK(std::string(e.what()).rfind(missing + ": cannot open", 0) == 0);
    }
    const fs::path bad = dir.path / "bad.json";
    write_text(bad, doc("[" + open_contour(line_json(0, 0, 0, 0)) + "]"));
    try {
        load_scene_file(bad.string());
        FAIL("loaded a bad file");
    } catch (const SceneError& e) {
        CHECK(std::string(e.what()) == bad.string() + ": contours[0].segments[0]: zero-length line");
    }
}

TEST_CASE("scene io error: deep nesting is refused without exhausting the stack") {
    const std::size_t depth = 100000;
    const std::string deep = std::string(depth, '[') + std::string(depth, ']');
    check_error(R"({"version": )" + deep + R"(, "contours": []})", "version", "unsupported format version");
    check_error(doc("[]", R"(, "description": )" + deep), "description", "expected a string");
    check_error(doc(deep), "contours[0]", "expected an object, found an array");
}

TEST_CASE("scene io: anticipation.segments_per_tick reads, writes only when set, and refuses what is not a count") {
    // Absent: 0, the exact search every tick (ProxyDef::anticipation_budget), and not written back,
    // so every scene saved before the option reads and saves to the same bytes.
    const Scene plain = parse_scene(kFloorDoc);
    CHECK(plain.anticipation.segments_per_tick == 0);
    CHECK(proxy_def_of(plain).anticipation_budget == 0);
    CHECK(scene_to_json_text(plain).find("anticipation") == std::string::npos);
    // Set: read, handed to the proxy, round-tripped.
    std::string text = kFloorDoc;
    text.insert(text.rfind('}'), R"(, "anticipation": {"segments_per_tick": 256})");
    const Scene spread = parse_scene(text);
    CHECK(spread.anticipation.segments_per_tick == 256);
    CHECK(proxy_def_of(spread).anticipation_budget == 256);
    CHECK(parse_scene(scene_to_json_text(spread)).anticipation.segments_per_tick == 256);
    auto with = [&](const std::string& value) {
        std::string t = kFloorDoc;
        t.insert(t.rfind('}'), R"(, "anticipation": )" + value);
        return t;
    };
    CHECK(error_of(with(R"({"segments_per_tick": -1})")).find("t.json: anticipation.segments_per_tick: must be a whole number in [0, 1000000]") == 0);
    CHECK(error_of(with(R"({"segments_per_tick": 2.5})")).find("t.json: anticipation.segments_per_tick: must be a whole number") == 0);
    CHECK(error_of(with(R"({"segments_per_tick": 1e9})")).find("t.json: anticipation.segments_per_tick: must be a whole number") == 0);
    CHECK(error_of(with(R"({"segments_per_tick": "fast"})")).find("t.json: anticipation.segments_per_tick") == 0);
    CHECK(error_of(with(R"({"budget": 3})")).find("t.json: anticipation") == 0);
    Scene bad = plain;
    bad.anticipation.segments_per_tick = -5;
    CHECK(validate_error_of(bad).find("anticipation.segments_per_tick: must lie in [0, 1000000], got -5") != std::string::npos);
}
