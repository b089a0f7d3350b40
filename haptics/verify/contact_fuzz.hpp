// contact_fuzz.hpp — the proxy against the brute-force reference over seeded random cases: the
// property test (a small run in CI) and `contactlab fuzz-contact` (the long soak).
//
// Each row feeds one hand sample to the proxy (proxy.hpp, exactly as the servo does) and checks,
// against solid_reference.hpp:
//   pad_inside       the proxy's pad is inside a solid by more than kMaxProxyPenetration;
//   contact_lost     the hand's pad is inside a solid by more than kHandInside, yet the output is
//                    not in contact (the surface was lost: the finger fell through);
//   too_shallow      ... in contact, but the proxy is nearer the hand than the hand's pad is deep
//                    (the reference's depth minus the proxy's allowance): the proxy sits inside;
//   force_mismatch   in contact, the force is not Ke (x_fd - x_f) (the frictionless spring);
//   energy_raised    the proxy's walk raised the spring's energy at the new finger position: a
//                    god-object moves along the constraint toward the finger, so with the finger
//                    angle unchanged |x_k - x_fd,k| <= |x_k - x_fd,k-1| (the previous row's proxy),
//                    and after a turn no further than where the turn's re-projection left it
//                    (ProxyOutput::turned). Tolerance kEnergyDistanceSlack, plus on exact curves
//                    twice kExactCurveTolerance: the walk runs on the curve's arc spline and each
//                    tick's output is then refined onto the true curve (Proxy::refine_on_curves),
//                    so two outputs each sit up to that far from the spline the walk minimised on.
#pragma once

#include "haptics/verify/random_contact_scenes.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace contactlab::verify {

inline constexpr double kMaxProxyPenetration = 1e-7;  // m: the proxy's pad may be this deep, no more
inline constexpr double kHandInside = 1e-5;           // m: a hand pad deeper than this must be in contact
inline constexpr double kReferenceResolution = 1e-8;  // m: the pad search's resolution

// m: how much further from the finger than before the walk may leave the proxy: the proxy's own
// "on a piece" tolerance (kOnTolerance in proxy.cpp), far below any force a hand feels (1e-6 N at
// 1000 N/m).
inline constexpr double kEnergyDistanceSlack = 1e-9;

enum class Violation : int { pad_inside, contact_lost, too_shallow, force_mismatch, energy_raised };
inline constexpr int kViolationKinds = 5;
const char* to_string(Violation v);

struct FuzzFailure {
    std::uint64_t case_seed = 0;
    int row = 0;
    Violation kind = Violation::pad_inside;
    HandSample hand;
    double hand_depth = 0.0;   // m: the hand pad's deepest point (reference)
    double proxy_depth = 0.0;  // m: the proxy pad's deepest point (reference; 0 if not computed)
    double output_depth = 0.0; // m: |x_fd - x_f| reported by the proxy
    bool contact = false;
    std::string summary;       // the case's scene summary
};

struct FuzzReport {
    std::int64_t rows = 0;
    std::int64_t cases = 0;
    std::int64_t contact_rows = 0;  // rows the proxy reported in contact
    std::int64_t inside_rows = 0;   // rows whose hand pad was deeper than kHandInside
    std::int64_t failing_cases = 0; // cases with at least one violation
    std::array<std::int64_t, kViolationKinds> violations{};
    double max_proxy_penetration = 0.0;  // m, over every row in contact
    double max_hand_depth = 0.0;         // m, the deepest the hands went
    // m: the largest amount the walk moved the proxy further from the finger (energy_raised's
    // measure; <= 0 when every walk moved it closer or kept it).
    double max_walk_distance_gain = -1.0;
    std::int64_t same_angle_rows = 0;    // rows checked against the previous proxy (phi unchanged)
    std::vector<FuzzFailure> failures;   // the first failure of the first few failing cases, in case order
    std::int64_t total_violations() const;
};

struct FuzzOptions {
    std::int64_t rows = 20000;
    std::uint64_t seed = 1;
    int jobs = 1;             // threads; the report does not depend on it
    int keep_failures = 20;   // failing cases whose first failure is kept
    // Called from the caller's thread as cases finish (rows done so far, of options.rows).
    std::function<void(std::int64_t done, std::int64_t total)> progress;
};

FuzzReport run_contact_fuzz(const FuzzOptions& options);
// One case, every row (what run_contact_fuzz does per case; `rows` may truncate the path).
FuzzReport run_contact_case(const ContactCase& c, int rows, int keep_failures);

}  // namespace contactlab::verify
