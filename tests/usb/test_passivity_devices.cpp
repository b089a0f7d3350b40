// test_passivity_devices.cpp — "passivity": "control" on the real devices, through the real
// `contactlab simulate` against emulated boards: it runs where the device declares its effective
// mass (a version 2 hapio info frame, or the user's device file) and is refused with exit 2
// before the servo starts where it declares none, never silently run as "fault".
#include "hapio_emulator.hpp"
#include "haply_emulator.hpp"
#include "usb_fixture.hpp"

#include "../cli/process.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <string>

using namespace contactlab::test;
using namespace cli_test;

namespace {

// scenes/block.json with the passivity controller asked for.
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

std::string mass_file(const TempDir& dir, const std::string& body) {
    const std::string path = dir.file("device.json");
    std::ofstream(path) << body;
    return path;
}

}  // namespace

TEST_CASE("control on a version 1 hapio board without a device file: refused with exit 2 before the servo starts") {
    HapioEmulator emu;
    preload_umockdev_in_children();
    TempDir dir;
    const ProcessResult p = run_contactlab({"simulate", control_scene(dir), "--device", "usb:hapio", "--duration", "0.2",
                                            "-o", dir.file("out.csv")});
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, "device usb:hapio declares no effective mass"));
    CHECK(contains(p.err, "info version 1"));
    CHECK(contains(p.err, "--device-file"));
    // The board streamed (the transport answers its frames with the idle command) but no servo
    // tick ever enabled its motors.
    CHECK_FALSE(emu.motors_enabled());
    CHECK((emu.last_command().flags & contactlab::drivers::hapio::kCommandEnable) == 0);
}

TEST_CASE("control on a version 1 hapio board with the user's device file runs") {
    HapioEmulator emu;
    preload_umockdev_in_children();
    TempDir dir;
    const ProcessResult p = run_contactlab({"simulate", control_scene(dir), "--device", "usb:hapio", "--device-file",
                                            mass_file(dir, R"({"effective_mass_kg": 0.08, "source": "measured"})"),
                                            "--duration", "0.3", "-o", dir.file("out.csv")});
    INFO(p.err);
    CHECK(p.exit_code == 0);
    CHECK(emu.commands_applied() > 50);
}

TEST_CASE("control on a version 2 hapio board runs on the mass its info frame declares") {
    HapioEmulator::Config c;
    c.info.version = contactlab::drivers::hapio::kInfoVersion2;
    c.info.mass_mg = 80000;  // 0.08 kg
    HapioEmulator emu(c);
    preload_umockdev_in_children();
    TempDir dir;
    const ProcessResult p = run_contactlab({"simulate", control_scene(dir), "--device", "usb:hapio", "--duration", "0.3",
                                            "-o", dir.file("out.csv")});
    INFO(p.err);
    CHECK(p.exit_code == 0);
}

TEST_CASE("control on the 2DIY: refused without a device file, runs with one") {
    HaplyEmulator emu;
    preload_umockdev_in_children();
    TempDir dir;
    const std::string scene_path = control_scene(dir);
    const ProcessResult a = run_contactlab({"simulate", scene_path, "--device", "usb:haply", "--duration", "0.2", "-o",
                                            dir.file("a.csv")});
    CHECK(a.exit_code == 2);
    CHECK(contains(a.err, "device usb:haply declares no effective mass"));
    const std::uint64_t before = emu.exchanges();
    const ProcessResult b = run_contactlab({"simulate", scene_path, "--device", "usb:haply", "--device-file",
                                            mass_file(dir, R"({"effective_mass_kg": 0.05})"), "--duration", "0.3",
                                            "-o", dir.file("b.csv")});
    INFO(b.err);
    CHECK(b.exit_code == 0);
    CHECK(emu.exchanges() > before + 50);
}

TEST_CASE("a device file that is not right names the file and the field, and exits 2") {
    HaplyEmulator emu;
    preload_umockdev_in_children();
    TempDir dir;
    const std::string scene_path = control_scene(dir);
    struct Case {
        const char* body;
        const char* says;
    };
    for (const Case& c : {Case{R"({"effective_mass_kg": -1})", "effective_mass_kg must lie in (0, 10] kg, got -1"},
                          Case{R"({"mass": 0.1})", "unknown key \"mass\""},
                          Case{R"({})", "effective_mass_kg is missing"},
                          Case{R"({"effective_mass_kg": "0.1"})", "effective_mass_kg must be a number"},
                          Case{"{", "not JSON"}}) {
        const ProcessResult p = run_contactlab({"simulate", scene_path, "--device", "usb:haply", "--device-file",
                                                mass_file(dir, c.body), "--duration", "0.2", "-o", dir.file("x.csv")});
        INFO(c.body << ": " << p.err);
        CHECK(p.exit_code == 2);
        CHECK(contains(p.err, "device.json: "));
        CHECK(contains(p.err, c.says));
    }
}
