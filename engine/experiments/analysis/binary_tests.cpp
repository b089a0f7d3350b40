// binary_tests.cpp — sign-flip permutation test and participant bootstrap (binary_tests.hpp).
#include "engine/experiments/analysis/binary_tests.hpp"

#include "engine/experiments/analysis/intervals.hpp"
#include "engine/experiments/base/random_stream.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace contactlab::experiments {

const char* const kBinaryRule =
    "for binary outcomes, beside the t test: per participant the proportion over their trials in each condition, the "
    "difference d = a - b; an exact paired permutation test (each participant's condition labels swapped: all 2^n sign "
    "flips of d, Monte Carlo with 100000 seeded draws beyond 20 participants) and a participant-level bootstrap "
    "percentile interval of the mean d (4000 resamples of participants, seed 1, reported from 5 participants): both stay "
    "inside [-1, 1] and assume nothing about normality";

double sign_flip_p(const std::vector<double>& d, std::uint64_t seed, bool& exact, long& assignments) {
    const std::size_t n = d.size();
    double observed = 0.0, scale = 0.0;
    for (double v : d) observed += v, scale += std::abs(v);
    observed = std::abs(observed);
    // Sums that equal the observed one up to rounding count as "at least as extreme".
    const double tol = 1e-9 * std::max(scale, 1e-300);
    auto extreme = [&](std::uint64_t signs) {
        double s = 0.0;
        for (std::size_t i = 0; i < n; ++i) s += (signs >> i & 1u) ? -d[i] : d[i];
        return std::abs(s) >= observed - tol;
    };
    long hits = 0;
    if (n <= kExactPermutationMax) {
        exact = true;
        assignments = 1L << n;
        for (std::uint64_t s = 0; s < static_cast<std::uint64_t>(assignments); ++s) hits += extreme(s);
        return static_cast<double>(hits) / static_cast<double>(assignments);
    }
    exact = false;
    assignments = kMonteCarloDraws;
    std::uint64_t rng = mix64(seed ^ 0x5167F11Bull);
    for (int b = 0; b < kMonteCarloDraws; ++b) {
        double s = 0.0;
        for (std::size_t i = 0; i < n; ++i) s += uniform01(rng) < 0.5 ? -d[i] : d[i];
        hits += std::abs(s) >= observed - tol;
    }
    return (1.0 + static_cast<double>(hits)) / (1.0 + static_cast<double>(kMonteCarloDraws));
}

BinaryComparison compare_binary(const std::vector<BinaryPair>& pairs, double confidence, std::uint64_t seed) {
    BinaryComparison r;
    r.confidence = confidence;
    std::vector<double> d;
    for (const BinaryPair& p : pairs)
        if (p.n_a > 0 && p.n_b > 0)
            d.push_back(static_cast<double>(p.k_a) / static_cast<double>(p.n_a) - static_cast<double>(p.k_b) / static_cast<double>(p.n_b));
    r.participants = d.size();
    if (d.size() < 2) {
        r.undefined = "undefined, because " + std::to_string(d.size()) + " participant(s) have trials in both conditions, 2 needed";
        r.ci_undefined = r.undefined;
        return r;
    }
    double sum = 0.0;
    for (double v : d) sum += v;
    r.mean_difference = sum / static_cast<double>(d.size());
    r.p = sign_flip_p(d, seed, r.exact, r.assignments);
    // The two assignments "as observed" and "all flipped" always count: 2 / 2^n at best.
    r.min_p = r.exact ? 2.0 / static_cast<double>(r.assignments) : 1.0 / (1.0 + kMonteCarloDraws);
    if (d.size() < kMinBootstrapParticipants) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "not reported: %zu participants, %zu needed (resampling so few gives at most a handful of distinct means, "
                      "and the percentile interval is then far narrower than the truth's spread)",
                      d.size(), kMinBootstrapParticipants);
        r.ci_undefined = buf;
        return r;
    }
    std::uint64_t rng = mix64(seed ^ 0xB1A4B00Full);
    std::vector<double> means;
    means.reserve(kParticipantBootstrap);
    for (int b = 0; b < kParticipantBootstrap; ++b) {
        double s = 0.0;
        for (std::size_t i = 0; i < d.size(); ++i) s += d[std::min(d.size() - 1, static_cast<std::size_t>(uniform01(rng) * d.size()))];
        means.push_back(s / static_cast<double>(d.size()));
    }
    r.ci_low = quantile(means, (1.0 - confidence) / 2.0);
    r.ci_high = quantile(means, (1.0 + confidence) / 2.0);
    if (!(r.ci_low < r.ci_high)) r.ci_undefined = "undefined, because every participant's difference is the same: the resamples do not vary";
    return r;
}

}  // namespace contactlab::experiments
