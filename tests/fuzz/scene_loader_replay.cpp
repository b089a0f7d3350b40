// scene_loader_replay.cpp — runs the fuzzer's check over saved inputs, without libFuzzer, so every
// build (sanitizers included) keeps the corpus and past crashes passing.
//   scene_loader_replay DIR_OR_FILE...   exit 0: all passed; 1: a check failed; 2: usage / no inputs
// Each file's name is printed before it runs, so a crash (ASan report) names its input.
#include "scene_loader_check.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s CORPUS_DIR_OR_FILE...\n", argv[0]);
        return 2;
    }
    std::vector<fs::path> inputs;
    for (int i = 1; i < argc; ++i) {
        const fs::path arg = argv[i];
        std::error_code ec;
        if (fs::is_directory(arg, ec)) {
            for (const auto& e : fs::directory_iterator(arg))
                if (e.is_regular_file()) inputs.push_back(e.path());
        } else if (fs::is_regular_file(arg, ec)) {
            inputs.push_back(arg);
        } else {
            std::fprintf(stderr, "scene_loader_replay: %s: no such file or directory\n", argv[i]);
            return 2;
        }
    }
    // An empty run would pass while testing nothing (a mistyped corpus path, say).
    if (inputs.empty()) {
        std::fprintf(stderr, "scene_loader_replay: no inputs found\n");
        return 2;
    }
    std::sort(inputs.begin(), inputs.end());

    std::size_t failures = 0;
    for (const fs::path& p : inputs) {
        std::printf("%s\n", p.filename().string().c_str());
        std::fflush(stdout);
        std::ifstream in(p, std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        if (!in) {
            std::fprintf(stderr, "scene_loader_replay: %s: cannot read\n", p.string().c_str());
            ++failures;
            continue;
        }
        const std::string problem = contactlab::fuzz::check_scene_input(bytes.str());
        if (!problem.empty()) {
            std::fprintf(stderr, "FAIL %s: %s\n", p.string().c_str(), problem.c_str());
            ++failures;
        }
    }
    std::printf("replayed %zu inputs, %zu failed\n", inputs.size(), failures);
    return failures == 0 ? 0 : 1;
}
