// test_main.cpp — doctest runner for the render tests; takes --update-snapshots off the command
// line (doctest would ignore it) and forces lavapipe before any Vulkan call.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "snapshot.hpp"

#include <cstdlib>
#include <cstring>
#include <vector>

int main(int argc, char** argv) {
    std::vector<char*> args;
    for (int i = 0; i < argc; ++i) {
        if (std::strcmp(argv[i], "--update-snapshots") == 0) render_test::g_update_snapshots = true;
        else args.push_back(argv[i]);
    }
    // Tests are pinned to lavapipe: only its driver manifest is loaded (no GPU driver probed).
    setenv("VK_DRIVER_FILES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json", 1);
    doctest::Context context;
    context.applyCommandLine(static_cast<int>(args.size()), args.data());
    return context.run();
}
