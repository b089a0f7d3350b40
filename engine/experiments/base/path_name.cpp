// path_name.cpp — names that become parts of file names (path_name.hpp).
#include "engine/experiments/base/path_name.hpp"

#include <cstdio>

namespace contactlab::experiments {
namespace {

bool control(unsigned char c) { return c < 0x20 || c == 0x7f; }

}  // namespace

std::string path_name_problem(const std::string& name) {
    if (name.empty()) return "must not be empty";
    if (name.find('/') != std::string::npos) return "must not hold '/'";
    if (name.find('\\') != std::string::npos) return "must not hold '\\'";
    if (name.find("..") != std::string::npos) return "must not hold \"..\"";
    for (const char ch : name)
        if (control(static_cast<unsigned char>(ch))) return "must not hold a control character";
    return {};
}

std::string escaped_name(const std::string& name) {
    std::string out;
    for (const char ch : name) {
        if (!control(static_cast<unsigned char>(ch))) {
            out += ch;
            continue;
        }
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(static_cast<unsigned char>(ch)));
        out += buf;
    }
    return out;
}

}  // namespace contactlab::experiments
