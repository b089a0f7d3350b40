// scene_loader_fuzz.cpp — libFuzzer target for parse_scene (CONTACTLAB_FUZZ=ON, clang only).
// Run from the build directory, working on a scratch copy of the seed corpus:
//   cp -r ../tests/fuzz/corpus /tmp/corpus_work
//   tests/fuzz/scene_loader_fuzz -max_total_time=240 /tmp/corpus_work
// A property violation aborts, so libFuzzer saves the input as crash-*; minimise it with
// -minimize_crash=1 and add it to tests/fuzz/corpus so the replay test keeps it fixed.
#include "scene_loader_check.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string problem =
        contactlab::fuzz::check_scene_input({reinterpret_cast<const char*>(data), size});
    if (!problem.empty()) {
        std::fprintf(stderr, "scene_loader_fuzz: %s\n", problem.c_str());
        std::abort();
    }
    return 0;
}
