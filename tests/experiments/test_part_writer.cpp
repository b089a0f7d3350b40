// test_part_writer.cpp — a participant's part written off the trials' thread (part_writer.hpp):
// the last texts handed over are the ones on disk once finish() returns, checksums and rows
// alike, and a write that fails is reported to the trials' thread with the file's name.
#include "engine/experiments/runs/part_writer.hpp"
#include "process.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace contactlab::experiments;
using cli_test::TempDir;

namespace {

std::string read_all(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("part writer: after finish() the files hold the last texts handed over, whatever was skipped") {
    TempDir dir;
    const std::string sums = dir.file("p.sums"), part = dir.file("p.csv");
    PartWriter w(sums, part);
    std::string s, p = "a,b\n";
    for (int k = 0; k < 200; ++k) {
        s += std::to_string(k) + " -\n";
        p += std::to_string(k) + ",x\n";
        w.commit(s, p);
    }
    w.finish();
    CHECK(read_all(sums) == s);
    CHECK(read_all(part) == p);
    // Nothing more handed over: finish() again returns at once, the files unchanged.
    w.finish();
    CHECK(read_all(part) == p);
}

TEST_CASE("part writer: a failed write is reported by finish() and the next commit, naming the file") {
    TempDir dir;
    const std::string missing = dir.file("no-such-folder/p.csv");
    PartWriter w(dir.file("no-such-folder/p.sums"), missing);
    w.commit("0 -\n", "a\n0\n");
    std::string what;
    try {
        w.finish();
    } catch (const std::exception& e) {
        what = e.what();
    }
    CHECK(what.find("no-such-folder/p.sums") != std::string::npos);
    CHECK_THROWS_AS(w.commit("1 -\n", "a\n1\n"), std::runtime_error);
}
