// minimal_protocol.hpp — the smallest protocol that loads, and that protocol with one piece of
// its text replaced: where the tests that change one field and expect a refusal start from.
#pragma once

#include <doctest/doctest.h>

#include <string>

namespace protocol_test {

inline const char* const kMinimal = R"({"format": "contactlab experiment protocol", "version": 1, "name": "x", "seed": "003",
  "task": "curvature", "conditions": [{"name": "A", "motion": "A"}], "stimuli": [0.01, 0.02], "answers": ["10", "20"]})";

// kMinimal with `from` replaced by `to` (which must be there).
inline std::string with(const std::string& from, const std::string& to) {
    std::string s = kMinimal;
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
}

}  // namespace protocol_test
