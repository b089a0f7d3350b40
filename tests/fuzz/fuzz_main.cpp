// fuzz_main.cpp — a bounded fuzzer that builds with any compiler, so every CI configuration runs
// the fuzz targets (libFuzzer needs clang; CONTACTLAB_FUZZ=ON builds those entry points too).
//   contactlab_fuzz --target NAME [--seconds S] [--seed N] [--save DIR] [CORPUS_DIR_OR_FILE...]
// First every corpus input and the target's own seeds run once (the regression cases: a failure
// names the file). Then, for S seconds (default 0: replay only), inputs picked from that corpus are
// mutated (bit flips, byte sets, inserts, deletes, splices, interesting bytes, float patterns) and
// checked. The mutations come from a fixed-seed generator: a run is reproducible by its seed.
// A failing mutant is written to DIR (--save, default the working directory) as
// fuzz-NAME-<hash>; name it and add it to the target's corpus to keep it fixed.
// Exit 0: all passed; 1: a check failed; 2: usage.
#include "fuzz_targets.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using contactlab::fuzz::Target;

namespace {

struct Input {
    std::string name, bytes;
};

bool read_file(const fs::path& p, std::string& out) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    out = s.str();
    return static_cast<bool>(in) || in.eof();
}

std::string mutate(const std::string& in, const std::vector<Input>& corpus, std::mt19937_64& rng) {
    std::string s = in;
    const int steps = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < steps; ++k) {
        const std::size_t n = s.size();
        switch (rng() % 8) {
            case 0:  // flip a bit
                if (n) s[rng() % n] ^= static_cast<char>(1u << (rng() % 8));
                break;
            case 1:  // set a byte
                if (n) s[rng() % n] = static_cast<char>(rng() & 0xff);
                break;
            case 2:  // insert bytes
                s.insert(n ? rng() % (n + 1) : 0, std::string(1 + rng() % 8, static_cast<char>(rng() & 0xff)));
                break;
            case 3:  // delete bytes
                if (n) {
                    const std::size_t at = rng() % n;
                    s.erase(at, 1 + rng() % std::min<std::size_t>(8, n - at));
                }
                break;
            case 4: {  // splice with another input
                const std::string& o = corpus[rng() % corpus.size()].bytes;
                if (!o.empty()) s = s.substr(0, n ? rng() % (n + 1) : 0) + o.substr(rng() % o.size());
                break;
            }
            case 5: {  // interesting bytes
                static const unsigned char kBytes[] = {0x00, 0x01, 0x7f, 0x80, 0xff, '{', '}', '"', ',', ':', '-', 'e'};
                if (n) s[rng() % n] = static_cast<char>(kBytes[rng() % sizeof kBytes]);
                break;
            }
            case 6: {  // a float32 pattern (NaN, infinities, huge, tiny) at some offset
                static const std::uint32_t kFloats[] = {0x7fc00000u, 0x7f800000u, 0xff800000u, 0x7f7fffffu, 0x00000001u, 0x80000000u};
                if (n >= 4) {
                    const std::uint32_t v = kFloats[rng() % 6];
                    const std::size_t at = rng() % (n - 3);
                    for (int i = 0; i < 4; ++i) s[at + i] = static_cast<char>(v >> (8 * i));
                }
                break;
            }
            default:  // truncate
                if (n) s.resize(rng() % n);
                break;
        }
    }
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    const Target* target = nullptr;
    double seconds = 0.0;
    std::uint64_t seed = 1;
    fs::path save = ".";
    std::vector<fs::path> paths;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--target" && i + 1 < argc) {
            target = contactlab::fuzz::find_target(argv[++i]);
            if (target == nullptr) {
                std::fprintf(stderr, "contactlab_fuzz: unknown target '%s' (scene, hapio, falcon, haply)\n", argv[i]);
                return 2;
            }
        } else if (a == "--seconds" && i + 1 < argc) {
            seconds = std::atof(argv[++i]);
        } else if (a == "--seed" && i + 1 < argc) {
            seed = std::strtoull(argv[++i], nullptr, 10);
        } else if (a == "--save" && i + 1 < argc) {
            save = argv[++i];
        } else {
            paths.emplace_back(a);
        }
    }
    if (target == nullptr || !(seconds >= 0.0 && seconds <= 3600.0)) {
        std::fprintf(stderr, "usage: %s --target NAME [--seconds S (0..3600)] [--seed N] [--save DIR] [CORPUS...]\n", argv[0]);
        return 2;
    }
    std::vector<Input> corpus;
    for (const fs::path& p : paths) {
        std::error_code ec;
        std::vector<fs::path> files;
        if (fs::is_directory(p, ec)) {
            for (const auto& e : fs::directory_iterator(p))
                if (e.is_regular_file()) files.push_back(e.path());
        } else if (fs::is_regular_file(p, ec)) {
            files.push_back(p);
        } else {
            std::fprintf(stderr, "contactlab_fuzz: %s: no such file or directory\n", p.string().c_str());
            return 2;
        }
        std::sort(files.begin(), files.end());
        for (const fs::path& f : files) {
            Input in{f.filename().string(), {}};
            if (!read_file(f, in.bytes)) {
                std::fprintf(stderr, "contactlab_fuzz: %s: cannot read\n", f.string().c_str());
                return 2;
            }
            corpus.push_back(std::move(in));
        }
    }
    int k = 0;
    for (std::string& s : target->seeds()) corpus.push_back({"seed-" + std::to_string(k++), std::move(s)});
    // An empty run would pass while testing nothing (a mistyped corpus path, say).
    if (corpus.empty()) {
        std::fprintf(stderr, "contactlab_fuzz: target %s has no inputs: give its corpus\n", target->name);
        return 2;
    }
    std::size_t failures = 0;
    for (const Input& in : corpus) {
        const std::string problem = target->check(in.bytes);
        if (!problem.empty()) {
            std::fprintf(stderr, "FAIL %s/%s: %s\n", target->name, in.name.c_str(), problem.c_str());
            ++failures;
        }
    }
    std::uint64_t runs = 0;
    std::mt19937_64 rng(seed);
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (failures == 0 && seconds > 0.0 && std::chrono::steady_clock::now() < end) {
        for (int batch = 0; batch < 64 && failures == 0; ++batch, ++runs) {
            const std::string m = mutate(corpus[rng() % corpus.size()].bytes, corpus, rng);
            const std::string problem = target->check(m);
            if (problem.empty()) continue;
            ++failures;
            const std::string file = (save / ("fuzz-" + std::string(target->name) + "-" +
                                              std::to_string(std::hash<std::string>{}(m)))).string();
            std::ofstream(file, std::ios::binary) << m;
            std::fprintf(stderr, "FAIL %s after %llu mutations (seed %llu): %s\n  input saved to %s\n", target->name,
                         static_cast<unsigned long long>(runs), static_cast<unsigned long long>(seed), problem.c_str(),
                         file.c_str());
        }
    }
    std::printf("%s: %zu corpus inputs, %llu mutations in %.1f s, %zu failed\n", target->name, corpus.size(),
                static_cast<unsigned long long>(runs), seconds, failures);
    return failures == 0 ? 0 : 1;
}
