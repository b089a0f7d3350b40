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
