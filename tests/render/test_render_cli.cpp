// test_render_cli.cpp — the real `contactlab render` command: PNG of the requested size, identical
// bytes across runs, bad options and a missing Vulkan driver exit 2 with a useful message.
#include "../cli/process.hpp"
#include "engine/render/image.hpp"

#include <doctest/doctest.h>

#include <cstdlib>

using namespace cli_test;

TEST_CASE("render cli: writes a PNG of the requested size, identical inputs give identical bytes") {
    TempDir dir;
    const std::string a = dir.file("a.png"), b = dir.file("b.png");
    const std::vector<std::string> common = {"render", scene("steps.json"), "--width", "200", "--height", "120",
                                             "--finger", "0.03,0.07,0.3", "--overlay", "cspace,zones",
                                             "--theme", "light", "--software", "--validation"};
    auto args = common;
    args.insert(args.end(), {"--output", a});
    const ProcessResult r1 = run_contactlab(args);
    INFO(r1.err);
    REQUIRE(r1.exit_code == 0);
    CHECK(contains(r1.err, "llvmpipe"));
    args = common;
    args.insert(args.end(), {"--output", b});
    REQUIRE(run_contactlab(args).exit_code == 0);
    const auto img = contactlab::render::read_png(a);
    CHECK(img.width == 200);
    CHECK(img.height == 120);
    CHECK(read_text(a) == read_text(b));
}

TEST_CASE("render cli: --view X Y W H (mm) frames that part of the world, --wearable alone zooms on the fingertip") {
    TempDir dir;
    const std::string whole = dir.file("whole.png"), view = dir.file("view.png"), tip = dir.file("tip.png");
    const std::vector<std::string> common = {"render", scene("flat.json"), "--width", "320", "--height", "180",
                                             "--finger", "0,0.0245,0.2", "--software", "--validation", "--no-text"};
    auto run = [&](std::vector<std::string> extra, const std::string& out) {
        auto args = common;
        args.insert(args.end(), extra.begin(), extra.end());
        args.insert(args.end(), {"--output", out});
        const ProcessResult r = run_contactlab(args);
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
    };
    run({}, whole);
    // Negative numbers after --view are values, not options.
    run({"--wearable", "--view", "-20", "-5", "40", "22.5"}, view);
    run({"--wearable"}, tip);
    const auto a = contactlab::render::read_png(whole), b = contactlab::render::read_png(view),
               c = contactlab::render::read_png(tip);
    CHECK(b.width == 320);
    CHECK(b.height == 180);
    // The zoomed pictures differ from the whole scene's and from each other (different frames).
    CHECK(read_text(whole) != read_text(view));
    CHECK(read_text(view) != read_text(tip));
}

TEST_CASE("render cli: bad options exit 2 naming the option") {
    TempDir dir;
    const std::string out = dir.file("x.png");
    struct Case {
        std::vector<std::string> extra;
        std::string message;
    };
    const Case cases[] = {
        {{"--theme", "sepia"}, "--theme"},
        {{"--overlay", "cspace,bogus"}, "bogus"},
        {{"--finger", "0.1,abc,0"}, "--finger"},
        {{"--finger", "0.1,0.2"}, "--finger"},
        {{"--width", "0"}, "--width"},
        {{"--view", "0", "0", "0", "10"}, "--view"},
        {{"--view", "0,0,10"}, "--view"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args = {"render", scene("flat.json"), "--output", out, "--software"};
        args.insert(args.end(), c.extra.begin(), c.extra.end());
        const ProcessResult r = run_contactlab(args);
        CAPTURE(c.message);
        CHECK(r.exit_code == 2);
        CHECK(contains(r.err, c.message));
        CHECK_FALSE(std::filesystem::exists(out));
    }
    const ProcessResult missing = run_contactlab({"render", scene("nope.json"), "--output", out});
    CHECK(missing.exit_code == 2);
}

TEST_CASE("render cli: no Vulkan driver exits 2 and names mesa-vulkan-drivers") {
    TempDir dir;
    const std::string saved = std::getenv("VK_DRIVER_FILES") ? std::getenv("VK_DRIVER_FILES") : "";
    setenv("VK_DRIVER_FILES", "/nonexistent/contactlab_no_icd.json", 1);
    const ProcessResult r = run_contactlab({"render", scene("flat.json"), "--output", dir.file("x.png")});
    setenv("VK_DRIVER_FILES", saved.c_str(), 1);
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, "mesa-vulkan-drivers"));
    CHECK_FALSE(std::filesystem::exists(dir.file("x.png")));
}
