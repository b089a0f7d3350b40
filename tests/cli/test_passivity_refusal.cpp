// test_passivity_refusal.cpp — "passivity": "control" on simulated devices: sim-cld declares its
// arm's endpoint mass and runs the controller; a device without a mass model (sim-wearable) is
// refused with exit 2 before any tick, never run silently as "fault"; device files are for real
// devices only.
#include "process.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <string>

using namespace cli_test;

namespace {

std::string control_scene(const TempDir& dir) {
    std::string text = read_text(scene("block.json"));
    const std::string key = "\"force\": {";
    const std::size_t at = text.find(key);
    REQUIRE(at != std::string::npos);
    text.insert(at + key.size(), " \"passivity\": \"control\",");
    const std::string path = dir.file("control.json");
    std::ofstream(path) << text;
    return path;
}

}  // namespace

TEST_CASE("control on sim-cld runs on the simulated arm's endpoint mass") {
    TempDir dir;
    const ProcessResult p = run_contactlab({"simulate", control_scene(dir), "--task", "contour-block", "--duration", "0.2",
                                            "-o", dir.file("out.csv")});
    INFO(p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "effective mass"));
}

TEST_CASE("control on a device with no mass model is refused with exit 2 and nothing written") {
    TempDir dir;
    const std::string hand = dir.file("hand.csv");
    std::ofstream(hand) << "t,x,y,phi\n0,0,0.05,0\n0.1,0,0.05,0\n";
    const std::string out = dir.file("out.csv");
    const ProcessResult p = run_contactlab({"simulate", control_scene(dir), "--device", "sim-wearable", "--hand", hand,
                                            "-o", out});
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, "device sim-wearable declares no effective mass"));
    CHECK(contains(p.err, "\"passivity\": \"fault\""));
    CHECK_FALSE(std::ifstream(out).good());
}

TEST_CASE("--device-file is for real devices only") {
    TempDir dir;
    const ProcessResult p = run_contactlab({"simulate", scene("block.json"), "--task", "contour-block", "--device-file",
                                            dir.file("d.json"), "-o", dir.file("out.csv")});
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, "--device-file: only real devices (usb:...) take a device file"));
}
