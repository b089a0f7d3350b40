// test_recovery.cpp — crash recovery in the real editor (issue 19 item 8): the process is killed
// with SIGKILL under xvfb-run (no exit handler runs, as in a crash or a power cut), then started
// again on the same scene. Every start, named, new or untitled, offers the recovery file; a new
// session never writes over a file it has not offered; the offers of several crashed sessions do
// not clobber each other; Recover, Discard and Keep both do what they say.
#include "process.hpp"
#include "xvfb_editor.hpp"

#include "haptics/scene_io.hpp"

#include <doctest/doctest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

using namespace cli_test;
using namespace editor_test;

namespace {

// Runs `edit SCENE --autosave 0.2 --script SCRIPT` (SCRIPT draws, then waits), waits until the
// recovery file `rec` holds `segments` segments, then kills the editor with SIGKILL.
void draw_then_crash(const TempDir& dir, const std::string& scene, const std::string& draw, const std::string& rec,
                     std::size_t segments) {
    const std::string script = dir.file("crash-" + std::to_string(segments) + ".txt");
    write_text(script, draw + "wait 60\nquit\n");
    std::vector<std::string> args = {"edit"};
    if (!scene.empty()) args.push_back(scene);
    for (const char* a : {"--autosave", "0.2", "--software", "--timeout", "90", "--script"}) args.push_back(a);
    args.push_back(script);
    const std::string log = dir.file("crash.log");
    const pid_t xvfb = start_under_xvfb(args, log);
    pid_t editor = 0;
    bool written = false;
    for (int i = 0; i < 1200 && !written; ++i) {  // up to 60 s on a busy machine
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        if (!editor) editor = find_contactlab(script);
        std::error_code ec;
        if (!std::filesystem::exists(rec, ec)) continue;
        try {
            const contactlab::Scene sc = contactlab::load_work_in_progress(rec);
            std::size_t n = 0;
            for (const auto& c : sc.contours) n += c.segments.size();
            written = n == segments;
        } catch (const std::exception&) {
        }
    }
    INFO("editor log: " << read_text(log));
    REQUIRE(written);
    REQUIRE(editor > 0);
    REQUIRE(::kill(editor, SIGKILL) == 0);
    int status = 0;
    while (::waitpid(xvfb, &status, 0) < 0 && errno == EINTR) {}
    CHECK(find_contactlab(script) == 0);
}

std::size_t segments_in(const std::string& file) {
    std::size_t n = 0;
    for (const auto& c : contactlab::load_work_in_progress(file).contours) n += c.segments.size();
    return n;
}

}  // namespace

TEST_CASE("recovery: a killed session on a new scene is offered at the next start and never overwritten") {
    TempDir dir;
    const std::string scene = dir.file("new.json");  // never saved
    const std::string rec = scene + ".recovery.json";
    // Session 1: one line, killed.
    draw_then_crash(dir, scene, "tool line\nclick -40 0\nclick 40 0\nrclick 40 0\n", rec, 1);
    const std::string crashed = read_text(rec);

    // Session 2 starts on the same (still missing) file: the offer is made; the user draws two
    // lines without answering, autosaves run, and the session quits with its work unsaved.
    const std::string s2 = dir.file("second.txt");
    write_text(s2,
               "expect recovery_offers 1\nexpect error 1\n"
               "tool line\nclick -40 10\nclick 0 10\nclick 40 10\nrclick 40 10\nwait 1\nquit\n");
    const auto p2 = run_under_xvfb({"edit", scene, "--autosave", "0.2", "--software", "--timeout", "60", "--script", s2});
    INFO("session 2: " << p2.err);
    CHECK(p2.exit_code == 0);
    CHECK(contains(p2.err, "unsaved work from an earlier session: " + rec));
    CHECK(read_text(rec) == crashed);  // the offered file, byte for byte
    REQUIRE(std::filesystem::exists(scene + ".recovery-2.json"));
    CHECK(segments_in(scene + ".recovery-2.json") == 2);

    // Session 3: both offered, oldest first. Recover the killed session's line, keep session 2's
    // work as a scene of its own, save.
    const std::string s3 = dir.file("third.txt");
    write_text(s3,
               "expect recovery_offers 2\n"
               "recovery recover\nexpect error 0\nexpect segments 1\nexpect dirty 1\n"
               "recovery keep\nexpect error 0\nexpect recovery_offers 0\nexpect segments 1\n"
               "save " + scene + "\nexpect error 0\nquit\n");
    const auto p3 = run_under_xvfb({"edit", scene, "--software", "--timeout", "60", "--script", s3});
    INFO("session 3: " << p3.err);
    CHECK(p3.exit_code == 0);
    CHECK_FALSE(contains(p3.err, "FAILED"));
    CHECK(segments_in(scene) == 1);
    const auto names = dir.entries();
    std::string kept;
    for (const auto& n : names)
        if (n.rfind("new.recovered-", 0) == 0) kept = n;
    INFO("files: " << names.size());
    REQUIRE_FALSE(kept.empty());
    CHECK(segments_in(dir.file(kept)) == 2);
    for (const auto& n : names) CHECK_MESSAGE(n.find(".recovery") == std::string::npos, n);
}

TEST_CASE("recovery: a killed untitled session is offered at the next untitled start, and discard removes it") {
    TempDir dir;
    const std::string old_tmpdir = std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "";
    setenv("TMPDIR", dir.path().c_str(), 1);  // where untitled sessions keep their recovery files
    const std::string rec = dir.file("contactlab-untitled.recovery.json");
    draw_then_crash(dir, "", "tool line\nclick -40 0\nclick 40 0\nrclick 40 0\n", rec, 1);
    const std::string s2 = dir.file("untitled.txt");
    write_text(s2, "expect recovery_offers 1\nrecovery discard\nexpect error 0\nexpect recovery_offers 0\nexpect segments 0\nquit\n");
    const auto p = run_under_xvfb({"edit", "--software", "--timeout", "60", "--script", s2});
    setenv("TMPDIR", old_tmpdir.c_str(), 1);
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    CHECK_FALSE(std::filesystem::exists(rec));
}
