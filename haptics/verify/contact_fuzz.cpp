// contact_fuzz.cpp — the proxy against the brute-force reference (see contact_fuzz.hpp).
#include "haptics/verify/contact_fuzz.hpp"

#include "haptics/bezier.hpp"
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/verify/solid_reference.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

namespace contactlab::verify {

const char* to_string(Violation v) {
    switch (v) {
        case Violation::pad_inside: return "pad_inside";
        case Violation::contact_lost: return "contact_lost";
        case Violation::too_shallow: return "too_shallow";
        case Violation::force_mismatch: return "force_mismatch";
        case Violation::energy_raised: return "energy_raised";
    }
    return "?";
}

std::int64_t FuzzReport::total_violations() const {
    std::int64_t n = 0;
    for (std::int64_t v : violations) n += v;
    return n;
}

namespace {
void merge(FuzzReport& into, const FuzzReport& r, int keep) {
    into.rows += r.rows;
    into.cases += r.cases;
    into.contact_rows += r.contact_rows;
    into.failing_cases += r.failing_cases;
    into.inside_rows += r.inside_rows;
    for (int k = 0; k < kViolationKinds; ++k) into.violations[static_cast<std::size_t>(k)] += r.violations[static_cast<std::size_t>(k)];
    into.max_proxy_penetration = std::max(into.max_proxy_penetration, r.max_proxy_penetration);
    into.max_hand_depth = std::max(into.max_hand_depth, r.max_hand_depth);
    into.max_walk_distance_gain = std::max(into.max_walk_distance_gain, r.max_walk_distance_gain);
    into.same_angle_rows += r.same_angle_rows;
    for (const FuzzFailure& f : r.failures)
        if (static_cast<int>(into.failures.size()) < keep) into.failures.push_back(f);
}
}  // namespace

FuzzReport run_contact_case(const ContactCase& c, int rows, int keep_failures) {
    FuzzReport rep;
    rep.cases = 1;
    const Environment env = build_environment(c.scene);
    Proxy proxy(env, proxy_def_of(c.scene));
    const SolidReference ref(c.scene);
    const double R = c.scene.finger.radius, L = c.scene.finger.length;  // m
    const double ke = c.scene.force.stiffness;                          // N/m
    const int n = std::min(rows, static_cast<int>(c.path.size()));
    Vec2 last_proxy{0.0};
    double last_phi = 0.0;
    const bool exact_curves = !env.curves.empty() && c.scene.curves.mode == CurveMode::exact;
    const double energy_slack = kEnergyDistanceSlack + (exact_curves ? 2.0 * kExactCurveTolerance : 0.0);  // m
    for (int row = 0; row < n; ++row) {
        const HandSample& h = c.path[static_cast<std::size_t>(row)];
        const ProxyOutput& out = proxy.update(h.finger, h.phi);
        // The walk's energy: the previous proxy (the same angle) or the turn's (a new one) is the
        // walk's start; the spring's energy is monotone in |x - x_fd|.
        const bool same_angle = row > 0 && h.phi == last_phi;
        const Vec2 walk_start = same_angle ? last_proxy : out.turned;
        const double gain = glm::length(h.finger - out.proxy) - glm::length(h.finger - walk_start);  // m
        rep.same_angle_rows += same_angle ? 1 : 0;
        if (row > 0) rep.max_walk_distance_gain = std::max(rep.max_walk_distance_gain, gain);
        last_proxy = out.proxy;
        last_phi = h.phi;
        ++rep.rows;
        const double hand = ref.pad_depth(h.finger, h.phi, R, L, kReferenceResolution).depth;  // m
        rep.max_hand_depth = std::max(rep.max_hand_depth, hand);
        // Free output: the proxy is the hand, so its pad is the hand's pad.
        const double proxy_pad = out.contact ? ref.pad_depth(out.proxy, h.phi, R, L, kReferenceResolution).depth : hand;
        if (out.contact) {
            ++rep.contact_rows;
            rep.max_proxy_penetration = std::max(rep.max_proxy_penetration, proxy_pad);
        }
        if (hand > kHandInside) ++rep.inside_rows;
        auto fail = [&](Violation v) {
            ++rep.violations[static_cast<std::size_t>(v)];
            rep.failing_cases = 1;
            if (static_cast<int>(rep.failures.size()) >= keep_failures) return;
            rep.failures.push_back({c.seed, row, v, h, hand, proxy_pad, out.depth, out.contact, c.summary});
        };
        if (proxy_pad > kMaxProxyPenetration) fail(Violation::pad_inside);
        if (hand > kHandInside) {
            // The pads at the hand and at the proxy differ by a translation of |x_fd - x_f|, and the
            // depth is 1-Lipschitz: the proxy's pad clear of the solid (within its allowance) needs
            // |x_fd - x_f| >= hand - allowance - the reference's resolution.
            if (!out.contact) fail(Violation::contact_lost);
            else if (out.depth < hand - kMaxProxyPenetration - 2.0 * kReferenceResolution) fail(Violation::too_shallow);
        }
        if (out.contact && glm::length(out.force - ke * (out.proxy - h.finger)) > 1e-9 * ke * std::max(out.depth, 1e-3))
            fail(Violation::force_mismatch);
        if (row > 0 && gain > energy_slack) fail(Violation::energy_raised);
    }
    return rep;
}

FuzzReport run_contact_fuzz(const FuzzOptions& options) {
    // The cases and their row counts follow from the seed alone, whatever the number of jobs.
    struct Job { std::uint64_t seed; int rows; };
    std::vector<Job> jobs;
    for (std::int64_t total = 0, k = 0; total < options.rows; ++k) {
        const std::uint64_t s = case_seed(options.seed, static_cast<std::uint64_t>(k));
        const int rows = static_cast<int>(std::min<std::int64_t>(case_rows(s), options.rows - total));
        jobs.push_back({s, rows});
        total += rows;
    }
    std::vector<FuzzReport> reports(jobs.size());
    std::atomic<std::size_t> next{0};
    std::atomic<std::int64_t> done{0};
    auto worker = [&] {
        for (std::size_t i = next++; i < jobs.size(); i = next++) {
            reports[i] = run_contact_case(make_contact_case(jobs[i].seed), jobs[i].rows, 1);
            done += jobs[i].rows;
        }
    };
    std::vector<std::thread> threads;
    for (int t = 0; t < std::max(1, options.jobs); ++t) threads.emplace_back(worker);
    if (options.progress) {
        while (done.load() < options.rows) {
            options.progress(done.load(), options.rows);
            std::this_thread::sleep_for(std::chrono::milliseconds(200));
        }
        options.progress(done.load(), options.rows);
    }
    for (std::thread& t : threads) t.join();
    FuzzReport total;
    for (const FuzzReport& r : reports) merge(total, r, options.keep_failures);
    return total;
}

}  // namespace contactlab::verify
