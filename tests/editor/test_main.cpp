// test_main.cpp — doctest runner for the editor tests. Every run gets a TMPDIR of its own, so an
// untitled editor session's recovery file (engine/editor/recovery.hpp) never reaches another
// test, nor the user's /tmp, where the next untitled start would offer it.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdlib>
#include <stdlib.h>  // mkdtemp
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
    const char* base = std::getenv("TMPDIR");
    std::string dir = std::string(base && *base ? base : "/tmp") + "/contactlab-editor-tests-XXXXXX";
    const bool own = ::mkdtemp(dir.data()) != nullptr;
    if (own) setenv("TMPDIR", dir.c_str(), 1);
    doctest::Context context(argc, argv);
    const int result = context.run();
    if (own) {
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
    }
    return result;
}
