// random_stream.cpp — the seeded random stream (random_stream.hpp).
#include "engine/experiments/base/random_stream.hpp"

#include <cmath>

namespace contactlab::experiments {

std::uint64_t mix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

double uniform01(std::uint64_t& state) {
    state = mix64(state);
    return static_cast<double>(state >> 11) * 0x1.0p-53;
}

double normal01(std::uint64_t& state) {
    const double u1 = 1.0 - uniform01(state), u2 = uniform01(state);  // u1 in (0, 1]
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
}

}  // namespace contactlab::experiments
