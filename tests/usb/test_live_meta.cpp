// test_live_meta.cpp — a live experiment session in the real editor (under Xvfb) on an emulated
// Haply 2DIY: the results' meta names the device the trials were felt on by its serial, the
// board's USB serial number as the editor read it from the emulated sysfs.
#include "haply_emulator.hpp"
#include "usb_fixture.hpp"

#include "../cli/process.hpp"
#include "../editor/xvfb_editor.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <string>

using namespace contactlab::test;
using namespace cli_test;

TEST_CASE("live session on the emulated 2DIY: the results' meta records the board's serial") {
    HaplyEmulator emu;
    preload_umockdev_in_children();
    TempDir dir;
    const std::string proto = (source_dir() / "scenes/experiments/003-curvature.json").string();
    const std::string results = dir.file("p1.csv");
    const std::string script = dir.file("s.txt");
    write_text(script, "expect device usb:haply\nwait_state engaged 10\nanswer 20\nexpect experiment_done 1\nquit\n");
    const ProcessResult p = editor_test::run_under_xvfb({"edit", "--device", "usb:haply", "--experiment", proto,
                                                         "--participant", "P1", "--results", results, "--software", "--validation",
                                                         "--timeout", "90", "--script", script});
    INFO(p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    CHECK(emu.exchanges() > 10);
    const auto meta = nlohmann::json::parse(read_text(results + ".meta.json"));
    INFO(meta.dump(2));
    CHECK(meta["device_serials"]["usb:haply"] == "HAPLY-0042");
}

TEST_CASE("the editor on the emulated 2DIY: the handle places the finger, the keys turn its angle") {
    HaplyEmulator emu;  // the handle at the workspace's centre: the scene's origin
    preload_umockdev_in_children();
    TempDir dir;
    const std::string script = dir.file("s.txt");
    // q turns the finger by one 2-degree step, e twice back; the cursor moving does not move it.
    write_text(script, "expect device usb:haply\nwait_state engaged 10\nexpect finger_x 0 0.001\nexpect finger_y 0 0.001\n"
                       "finger 30 40\nframes 3\nexpect finger_x 0 0.001\n"
                       "key q\nframes 3\nwait 0.1\nexpect finger_phi 2 1e-9\nkey e\nkey e\nframes 3\nwait 0.1\n"
                       "expect finger_phi -2 1e-9\nquit\n");
    const ProcessResult p = editor_test::run_under_xvfb({"edit", "scenes/block.json", "--device", "usb:haply",
                                                         "--software", "--validation", "--timeout", "60", "--script",
                                                         script},
                                                        source_dir().string());
    INFO(p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
}

TEST_CASE("the editor refuses the passivity controller on the 2DIY, which declares no effective mass") {
    HaplyEmulator emu;
    preload_umockdev_in_children();
    TempDir dir;
    std::string text = read_text(scene("block.json"));
    const std::string key = "\"force\": {";
    REQUIRE(text.find(key) != std::string::npos);
    text.insert(text.find(key) + key.size(), " \"passivity\": \"control\",");
    const std::string scene_path = dir.file("control.json");
    write_text(scene_path, text);
    const std::string script = dir.file("s.txt");
    write_text(script, "expect device mouse\nexpect error 1\nwait_state engaged 5\nquit\n");
    const ProcessResult p = editor_test::run_under_xvfb({"edit", scene_path, "--device", "usb:haply", "--software",
                                                         "--timeout", "60", "--script", script});
    INFO(p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    CHECK(contains(p.err, "device usb:haply declares no effective mass"));
    CHECK(contains(p.err, "the mouse drives the finger"));
}
