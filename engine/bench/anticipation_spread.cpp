// anticipation_spread.cpp — see anticipation_spread.hpp.
#include "engine/bench/anticipation_spread.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::bench {

SpreadError anticipation_spread_error(const Environment& env, const ProxyDef& def, const std::vector<FingerSample>& path,
                                      int budget) {
    SpreadError e;
    if (path.empty()) return e;
    ProxyDef exact_def = def;
    exact_def.anticipation_budget = 0;
    ProxyDef spread_def = def;
    spread_def.anticipation_budget = budget;
    Proxy exact(env, exact_def), spread(env, spread_def);
    exact.reset(path.front().x, path.front().phi);
    spread.reset(path.front().x, path.front().phi);
    std::vector<double> errors;
    errors.reserve(path.size());
    for (const FingerSample& s : path) {
        const ProxyOutput& a = exact.update(s.x, s.phi);
        const ProxyOutput& b = spread.update(s.x, s.phi);
        if (a.contact || b.contact) continue;
        errors.push_back(std::abs(a.l_d - b.l_d));
        e.behind_max = std::max(e.behind_max, b.work.anticipation_behind);
        e.asked_max = std::max(e.asked_max, b.work.anticipated_segments);
    }
    e.free_ticks = static_cast<int>(errors.size());
    if (errors.empty()) return e;
    std::sort(errors.begin(), errors.end());
    e.l_d_error_max = errors.back();
    e.l_d_error_p99 = errors[std::min(errors.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(errors.size())))];
    return e;
}

}  // namespace contactlab::bench
