// test_crossing_scenes.cpp — closed contours that cross themselves are not solids: `contactlab
// trace`, `render` and `simulate` refuse a bow-tie and a figure 8 with exit code 2 and a message
// naming the contour, the point (mm) and the segments, and write nothing.
#include "process.hpp"

#include <doctest/doctest.h>

#include <functional>

using namespace cli_test;

namespace {

struct CrossingFile {
    const char* name;
    const char* contours;  // the JSON contours array
    const char* message;   // what the error must say after the file name
};

// A bow-tie of four lines (diagonals crossing at (5, 5) mm) and a figure 8 of two full circles of
// 1 cm tangent at the origin, wound opposite ways, each above the default finger's start.
const CrossingFile kFiles[] = {
    {"bowtie.json",
     R"([{"closed": true, "segments": [
        {"type": "line", "from": [0, 0], "to": [0.01, 0.01]},
        {"type": "line", "from": [0.01, 0.01], "to": [0.01, 0]},
        {"type": "line", "from": [0.01, 0], "to": [0, 0.01]},
        {"type": "line", "from": [0, 0.01], "to": [0, 0]}]}])",
     "contours[0]: crosses itself at (5.000, 5.000) mm (segments 0 and 2)"},
    {"figure8.json",
     R"([{"closed": true, "segments": [
        {"type": "arc", "center": [-0.01, 0], "radius": 0.01, "start_angle": 0, "end_angle": -6.283185307179586},
        {"type": "arc", "center": [0.01, 0], "radius": 0.01, "start_angle": 3.141592653589793,
         "end_angle": 9.42477796076938}]}])",
     "contours[0]: crosses itself at (0.000, 0.000) mm (segments 0 and 1)"},
};

// Runs `contactlab ARGS` on each file, ARGS made by `args(dir, scene, output)`, and checks the
// refusal: exit 2, the file's message after its name, and no output written.
void expect_refused(const std::function<std::vector<std::string>(const TempDir&, const std::string&, const std::string&)>& args,
                    const char* output_name) {
    for (const CrossingFile& f : kFiles) {
        CAPTURE(f.name);
        TempDir dir;
        const std::string path = dir.file(f.name), out = dir.file(output_name);
        write_text(path, std::string(R"({"version": 1, "contours": )") + f.contours + "}\n");
        const ProcessResult p = run_contactlab(args(dir, path, out));
        INFO("stderr: " << p.err);
        CHECK(p.exit_code == 2);
        CHECK(contains(p.err, path + ": " + f.message));
        CHECK_FALSE(fs::exists(out));
    }
}

}  // namespace

TEST_CASE("crossing scenes: trace refuses a bow-tie and a figure 8 with exit 2") {
    expect_refused(
        [](const TempDir& dir, const std::string& scene, const std::string& out) {
            write_text(dir.file("in.csv"), "t,x,y,phi\n0,0.05,0.08,0\n0.001,0.05,0.079,0\n");
            return std::vector<std::string>{"trace", scene, "--input", dir.file("in.csv"), "--output", out};
        },
        "out.csv");
}

TEST_CASE("crossing scenes: render refuses a bow-tie and a figure 8 with exit 2") {
    expect_refused(
        [](const TempDir&, const std::string& scene, const std::string& out) {
            return std::vector<std::string>{"render", scene, "--output", out, "--software"};
        },
        "out.png");
}

TEST_CASE("crossing scenes: simulate refuses a bow-tie and a figure 8 with exit 2") {
    expect_refused(
        [](const TempDir& dir, const std::string& scene, const std::string& out) {
            write_text(dir.file("hand.csv"), "t,x,y,phi\n0,0.05,0.08,0\n0.5,0.05,0.07,0\n");
            return std::vector<std::string>{"simulate", scene, "--hand", dir.file("hand.csv"), "--output", out};
        },
        "out.csv");
}
