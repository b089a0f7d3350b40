// libfuzzer_entry.cpp — the libFuzzer entry point of one fuzz target (CONTACTLAB_FUZZ=ON, clang),
// compiled once per target with CONTACTLAB_FUZZ_TARGET set to its name (fuzz_targets.hpp).
// Run from the build directory on a scratch copy of its corpus, e.g.
//   cp -r ../tests/fuzz/corpus_haply /tmp/work && tests/fuzz/haply_fuzz -max_total_time=240 /tmp/work
// A property violation aborts, so libFuzzer saves the input as crash-*; minimise it with
// -minimize_crash=1, give it a name that says what it is and add it to the target's corpus: the
// bounded runs ctest makes (contactlab_fuzz) replay it in every build.
#include "fuzz_targets.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const contactlab::fuzz::Target* target = contactlab::fuzz::find_target(CONTACTLAB_FUZZ_TARGET);
    const std::string problem = target->check({reinterpret_cast<const char*>(data), size});
    if (!problem.empty()) {
        std::fprintf(stderr, "%s_fuzz: %s\n", target->name, problem.c_str());
        std::abort();
    }
    return 0;
}
