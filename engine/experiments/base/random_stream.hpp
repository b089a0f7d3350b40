// random_stream.hpp — the seeded random stream every experiment room draws from: trial orders
// (trial_plan.hpp), each trial's stimulus details and perceptual noise, the model observer's
// answers, the bootstrap and the power analysis' simulated samples. Written here, not taken from
// the standard library, whose distributions are implementation-defined: the same seed gives the
// same draws on any machine and compiler, so a run's results are reproducible bytes.
#pragma once

#include <cstdint>

namespace contactlab::experiments {

// splitmix64: a well-mixed 64-bit value from any 64-bit input.
std::uint64_t mix64(std::uint64_t x);
// Uniform in [0, 1) from a state advanced by mix64.
double uniform01(std::uint64_t& state);
// Standard normal (Box-Muller) from the same state.
double normal01(std::uint64_t& state);

}  // namespace contactlab::experiments
