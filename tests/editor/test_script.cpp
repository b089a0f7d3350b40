// test_script.cpp — the --script language is checked before any window opens.
#include "engine/editor/script.hpp"

#include <doctest/doctest.h>

using namespace contactlab::editor;

TEST_CASE("scripts: comments and blank lines are skipped and errors name the line") {
    CHECK_NOTHROW(Script::parse("# a comment\n\ntool line\nclick 1 2\nwait 0.5\nquit\n"));
    try {
        Script::parse("tool line\nfrobnicate 3\n", "s.txt");
        FAIL("no error");
    } catch (const ScriptError& e) {
        CHECK(std::string(e.what()) == "s.txt:2: unknown command \"frobnicate\"");
    }
    try {
        Script::parse("click 1\n", "s.txt");
        FAIL("no error");
    } catch (const ScriptError& e) {
        CHECK(std::string(e.what()) == "s.txt:1: click takes 2 argument(s), got 1");
    }
}
