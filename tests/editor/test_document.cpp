// test_document.cpp — undo/redo of every edit, validation messages, atomic save, recovery file.
#include "engine/editor/document.hpp"
#include "engine/editor/scene_edit.hpp"
#include "haptics/scene_io.hpp"
#include "process.hpp"

#include <doctest/doctest.h>

#include <filesystem>

using namespace contactlab;
using namespace contactlab::editor;

namespace {

Scene floor_scene() {
    Scene s;
    Contour c;
    c.segments.push_back(LineSegment{{-0.05, 0.0}, {0.05, 0.0}});
    s.contours.push_back(c);
    return s;
}

}  // namespace

TEST_CASE("every edit can be undone and redone, in order") {
    Document d(floor_scene());
    CHECK_FALSE(d.dirty());
    CHECK(d.valid());
    Scene k = d.scene();
    k.force.stiffness = 500.0;
    d.edit(k, "Ke");
    d.edit(add_line(d.scene(), {0.05, 0.0}, {0.08, -0.02}, 1e-9), "add line");
    CHECK(segment_count(d.scene()) == 2);
    CHECK(d.scene().force.stiffness == 500.0);
    CHECK(d.undo_label() == "add line");
    REQUIRE(d.undo());
    CHECK(segment_count(d.scene()) == 1);
    REQUIRE(d.undo());
    CHECK(d.scene().force.stiffness == 1000.0);
    CHECK_FALSE(d.undo());
    REQUIRE(d.redo());
    REQUIRE(d.redo());
    CHECK(segment_count(d.scene()) == 2);
    CHECK(d.scene().force.stiffness == 500.0);
    CHECK_FALSE(d.redo());
}

TEST_CASE("a drag is one undo step and a click without a move records nothing") {
    Document d(floor_scene());
    d.begin_continuous("move point");
    d.end_continuous();
    CHECK(d.undo_depth() == 0);
    d.begin_continuous("move point");
    for (int i = 1; i <= 5; ++i) d.update_continuous(move_handle(d.scene(), {0, 0, 1}, {0.05 + 0.001 * i, 0.0}));
    d.end_continuous();
    CHECK(d.undo_depth() == 1);
    CHECK(segment_end(d.scene().contours[0].segments[0]).x == doctest::Approx(0.055));
    d.undo();
    CHECK(segment_end(d.scene().contours[0].segments[0]).x == 0.05);
}

TEST_CASE("invalid geometry is reported, kept out of last_valid, refused by save") {
    cli_test::TempDir dir;
    Document d(floor_scene());
    d.edit(move_handle(d.scene(), {0, 0, 1}, {-0.05, 0.0}), "move point");  // zero-length line
    CHECK_FALSE(d.valid());
    CHECK(d.problem().find("contours[0].segments[0]") != std::string::npos);
    CHECK(segment_end(d.last_valid().contours[0].segments[0]).x == 0.05);
    CHECK_THROWS_AS(d.save(dir.file("bad.json")), SceneError);
    CHECK_FALSE(std::filesystem::exists(dir.file("bad.json")));
    d.undo();
    CHECK(d.valid());
}

TEST_CASE("a contour that crosses itself may be drawn, is reported with the point, and kept from the servo and the file") {
    cli_test::TempDir dir;
    Document d(Scene{}, dir.file("bow.json"));  // its recovery file beside it, in dir
    // The line tool's chain: an open zig-zag that crosses itself is a terrain profile, valid.
    const Vec2 pts[] = {{0.0, 0.0}, {0.01, 0.01}, {0.01, 0.0}, {0.0, 0.01}, {0.0, 0.0}};  // m
    for (int i = 0; i < 3; ++i) d.edit(add_segment(d.scene(), LineSegment{pts[i], pts[i + 1]}, 1e-9), "add line");
    REQUIRE(d.valid());
    CHECK_FALSE(d.problem_point());
    // Back to its start the chain closes: a bow-tie, not a solid.
    d.edit(add_segment(d.scene(), LineSegment{pts[3], pts[4]}, 1e-9), "add line");
    REQUIRE(d.scene().contours.size() == 1);
    REQUIRE(d.scene().contours[0].closed);
    CHECK_FALSE(d.valid());
    CHECK(d.problem() == "contours[0]: crosses itself at (5.000, 5.000) mm (segments 0 and 2)");
    REQUIRE(d.problem_point());
    CHECK(glm::length(*d.problem_point() - Vec2{0.005, 0.005}) < 1e-15);  // m: two lines at right angles
    // The servo and the drawer stay on the open chain.
    CHECK_FALSE(d.last_valid().contours[0].closed);
    CHECK(d.last_valid().contours[0].segments.size() == 3);
    try {
        d.save(dir.file("bow.json"));
        FAIL("a crossing scene was saved");
    } catch (const SceneError& e) {
        CHECK(std::string(e.what()) == "not saved: the scene is invalid: contours[0]: crosses itself at (5.000, 5.000) mm (segments 0 and 2)");
    }
    CHECK_FALSE(std::filesystem::exists(dir.file("bow.json")));
    // The recovery file keeps the drawing as it is, crossing and all.
    const std::string rec = d.autosave();
    REQUIRE_FALSE(rec.empty());
    CHECK(load_work_in_progress(rec).contours[0].closed);
    d.discard_recovery();
    d.undo();
    CHECK(d.valid());
    CHECK_FALSE(d.problem_point());
}

TEST_CASE("save writes the scene atomically and round-trips and autosave writes the recovery file") {
    cli_test::TempDir dir;
    const std::string path = dir.file("scene.json");
    Document d(floor_scene(), path);
    Scene k = d.scene();
    k.force.stiffness = 750.0;
    d.edit(k, "Ke");
    const std::string rec = d.autosave();
    CHECK(rec == path + ".recovery.json");
    CHECK(load_scene_file(rec).force.stiffness == 750.0);
    CHECK(d.autosave().empty());  // nothing changed since
    d.save();
    CHECK_FALSE(d.dirty());
    CHECK(load_scene_file(path).force.stiffness == 750.0);
    CHECK_FALSE(std::filesystem::exists(rec));  // the recovery file goes once the work is saved
    // Only the scene is left: no temporary file beside it.
    CHECK(dir.entries() == std::vector<std::string>{"scene.json"});
}

TEST_CASE("recovery files: sessions claim their own, save removes only its own, recover adopts one") {
    cli_test::TempDir dir;
    const std::string path = dir.file("new.json");  // a scene never saved
    Document a(Scene{}, path), b(Scene{}, path);
    a.edit(floor_scene(), "add line");
    Scene two = floor_scene();
    two.contours.push_back(two.contours.front());
    two.contours.back().segments.front() = LineSegment{{-0.05, 0.02}, {0.05, 0.02}};
    b.edit(two, "add lines");
    // Two sessions on one file (or a crashed one and a new one) never share a recovery file.
    const std::string ra = a.autosave(), rb = b.autosave();
    CHECK(ra == path + ".recovery.json");
    CHECK(rb == path + ".recovery-2.json");
    CHECK(Document::recovery_files_for(path) == std::vector<std::string>{ra, rb});
    // Later autosaves keep writing the session's own file, atomically (no temporary left).
    Scene k = a.scene();
    k.force.stiffness = 640.0;
    a.edit(k, "Ke");
    CHECK(a.autosave() == ra);
    CHECK(load_scene_file(ra).force.stiffness == 640.0);
    CHECK(load_scene_file(rb).contours.size() == 2);
    CHECK(dir.entries() == std::vector<std::string>{"new.json.recovery-2.json", "new.json.recovery.json"});

    // a saves: its recovery file goes, b's stays (it is b's work, unsaved).
    a.save();
    CHECK_FALSE(std::filesystem::exists(ra));
    CHECK(std::filesystem::exists(rb));

    // A third session recovers b's file: b's scene, undoable, and the file is now its own.
    Document c(load_scene_file(path), path);
    c.recover(rb);
    CHECK(c.scene().contours.size() == 2);
    CHECK(c.dirty());
    CHECK(c.own_recovery() == rb);
    c.undo();
    CHECK(c.scene().contours.size() == 1);
    CHECK(c.autosave() == rb);  // the session's own file follows its edits
    CHECK(load_scene_file(rb).contours.size() == 1);
    c.save();
    CHECK(dir.entries() == std::vector<std::string>{"new.json"});
}

TEST_CASE("recovery files: recovering into a session that already has one moves the work there") {
    cli_test::TempDir dir;
    const std::string path = dir.file("s.json");
    Document old_session(Scene{}, path), now(Scene{}, path);
    old_session.edit(floor_scene(), "add line");
    const std::string old_file = old_session.autosave();
    Scene k = now.scene();
    k.force.stiffness = 900.0;
    now.edit(k, "Ke");
    const std::string own = now.autosave();
    REQUIRE(own != old_file);
    now.recover(old_file);
    CHECK(now.own_recovery() == own);
    CHECK_FALSE(std::filesystem::exists(old_file));
    CHECK(load_scene_file(own).contours.size() == 1);
}

TEST_CASE("recovery files: work that does not validate yet is still recovered") {
    cli_test::TempDir dir;
    const std::string path = dir.file("w.json");
    Document d(Scene{}, path);
    Scene bad = floor_scene();
    bad.contours.front().segments.push_back(LineSegment{{0.05, 0.0}, {0.05, 0.0}});  // zero length
    d.edit(bad, "add point");
    REQUIRE_FALSE(d.valid());
    const std::string rec = d.autosave();
    CHECK_THROWS_AS(load_scene_file(rec), SceneError);
    Document e(Scene{}, path);
    e.recover(rec);
    CHECK_FALSE(e.valid());
    CHECK(e.scene().contours.front().segments.size() == 2);
    // Not a scene at all: refused, nothing changed.
    cli_test::write_text(rec, "{ not json");
    Document f(Scene{}, path);
    CHECK_THROWS_AS(f.recover(rec), SceneError);
    CHECK(f.scene().contours.empty());
    CHECK_FALSE(f.dirty());
}
