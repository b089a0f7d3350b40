// usb_fixture.hpp — helpers for the emulated-USB tests: waiting on another thread's progress and
// placing the emulated arm's encoders at a finger position.
#pragma once

#include "drivers/usb/hapio_cld_model.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <thread>

namespace contactlab::test {

// Child processes (the real `contactlab`) get umockdev's preload library through LD_PRELOAD; this
// process has it linked in already. Under ASan the child would abort on the preload coming before
// the ASan runtime, so that check is switched off for children (umockdev only wraps libc calls).
inline void preload_umockdev_in_children() {
    ::setenv("LD_PRELOAD", "libumockdev-preload.so.0", 1);
    const char* asan = std::getenv("ASAN_OPTIONS");
    std::string opts = asan != nullptr && *asan ? std::string(asan) + ":" : std::string();
    ::setenv("ASAN_OPTIONS", (opts + "verify_asan_link_order=0").c_str(), 1);
}

// Polls `done` every 0.5 ms for at most `timeout` s (the transport runs on its own thread).
template <class Pred>
bool wait_until(Pred done, double timeout = 5.0) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
    while (std::chrono::steady_clock::now() < end) {
        if (done()) return true;
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    return done();
}

// Joint angles (rad) that put the arm's endpoint at x (m), one of the two IK branches.
inline void arm_ik(const drivers::hapio::CldCalibration& c, Vec2 x, double& q1, double& q2) {
    const Vec2 d = x - c.base;
    const double r2 = glm::dot(d, d);
    const double c2 = (r2 - c.l1 * c.l1 - c.l2 * c.l2) / (2.0 * c.l1 * c.l2);
    q2 = -std::acos(std::clamp(c2, -1.0, 1.0));
    q1 = std::atan2(d.y, d.x) - std::atan2(c.l2 * std::sin(q2), c.l1 + c.l2 * std::cos(q2));
}

// Encoder counts (shoulder, elbow, finger angle, roller) for finger x (m), phi (rad), roller l (m).
inline std::array<std::int32_t, 4> counts_at(const drivers::hapio::CldCalibration& c, Vec2 x, double phi = 0.0,
                                             double roller = 0.0) {
    double q1 = 0.0, q2 = 0.0;
    arm_ik(c, x, q1, q2);
    return {static_cast<std::int32_t>(std::lround((q1 - c.q1_offset) / kTwoPi * c.joint_counts)),
            static_cast<std::int32_t>(std::lround((q2 - c.q2_offset) / kTwoPi * c.joint_counts)),
            static_cast<std::int32_t>(std::lround(phi / kTwoPi * c.angle_counts)),
            static_cast<std::int32_t>(std::lround(roller * c.roller_counts_per_m))};
}

}  // namespace contactlab::test
