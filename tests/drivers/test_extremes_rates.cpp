// test_extremes_rates.cpp — the closed loop at the rate extremes beyond the stability table's
// 100 Hz-20 kHz: 100 kHz in virtual time (the real-time thread stops at 20 kHz), with the real
// simulated arm. Below the declared passivity bound a press never faults; far above it the
// instability is reported, the output goes to zero, and nothing is ever NaN or over the clamp.
#include "drivers/sim/stability_probes.hpp"

#include <doctest/doctest.h>

#include <string>

using namespace contactlab;
using drivers::sim::ContactScenario;
using drivers::sim::PassivityBounds;
using drivers::sim::ScenarioOptions;
using drivers::sim::ScenarioRun;

TEST_CASE("100 kHz in virtual time: below the bound a press and a slide settle, far above it the loop is reported") {
    constexpr double rate = 1e5;  // Hz
    for (ContactScenario sc : {ContactScenario::press, ContactScenario::slide}) {
        CAPTURE(std::string(drivers::sim::to_string(sc)));
        const PassivityBounds bounds = drivers::sim::passivity_bounds(rate, sc);
        ScenarioOptions opt;
        opt.seconds = 1.0;
        // 0.8 x the bound the servo can compute (the device's declared damping): never a fault.
        const ScenarioRun below = drivers::sim::run_contact_scenario(sc, rate, 0.8 * bounds.declared, opt);
        REQUIRE(below.opened);
        CHECK(below.finite);
        CHECK_FALSE(below.faulted);
        CHECK(below.max_force <= 1.5 * (1.0 + 1e-12));
        // 20 x the arm's actual bound: reported within 0.5 s of contact (as at 20 kHz), then zero.
        const ScenarioRun above = drivers::sim::run_contact_scenario(sc, rate, 20.0 * bounds.normal, opt);
        REQUIRE(above.opened);
        CHECK(above.finite);
        REQUIRE(above.faulted);
        CHECK(above.fault == ServoFault::instability);
        CHECK(above.fault_time >= 0.0);
        CHECK(above.fault_time <= 0.5);
        CHECK(above.max_force_after_fault == 0.0);
        CHECK(above.max_force <= 1.5 * (1.0 + 1e-12));
    }
}
