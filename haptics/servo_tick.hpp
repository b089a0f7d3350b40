// servo_tick.hpp — one haptic servo tick on plain structs (DESIGN.md "Haptic rendering" 1-7).
//
// Measured finger configuration in, commands out: proxy (contact force and contact location),
// roller PID (seed 000 eq. 2), safety (clamp, saturate, NaN guard, engage gate, ramp, stall and
// instability faults), then a lock-free snapshot for readers. haptics/ knows nothing of devices:
// drivers/ adapts a Device to ServoInput/ServoCommand and decides how ticks are paced (a thread at
// a fixed rate, or virtual time).
//
// Thread contract: tick() is called by one thread (the servo). publish_params(), scenes() and
// snapshot() are for any other single publisher / many readers. tick() does not allocate, lock,
// or do I/O (tests/servo/test_no_alloc.cpp counts allocations over 100,000 ticks).
#pragma once

#include "haptics/energy_balance.hpp"
#include "haptics/limit_cycle_detector.hpp"
#include "haptics/passivity_controller.hpp"
#include "haptics/roller_controller.hpp"
#include "haptics/safety.hpp"
#include "haptics/servo_scene.hpp"
#include "haptics/servo_seqlock.hpp"

#include <cstdint>
#include <limits>
#include <string>

namespace contactlab {

// What the UI may change while the servo runs. Published as a whole; applied at a tick boundary,
// Ke and the force clamp slew-limited so an edit never steps the force.
struct ServoParams {
    double stiffness = 1000.0;         // Ke, N/m
    double max_force = 1.5;            // N (also capped by ServoConfig::device_max_force)
    double stiffness_slew = 20000.0;   // N/m per s: how fast Ke follows an edit
    double max_force_slew = 10.0;      // N per s
    RollerGains roller;                // live gains (bumpless: integral kept in output units)
    // Roller travel the contact location may use (m), centred in the device's own travel
    // (ServoConfig::roller_travel) and never beyond it; 0 uses all of the device's. Seed 002's
    // CLD uses 18 mm of a 20 mm screw; a smaller value keeps l_d off worn or padded ends.
    double roller_travel = 0.0;
    SafetyParams safety;
    // Net energy the loop may generate before it is called unstable, as a multiple of the most
    // the spring holds in its linear range, max_force^2 / (2 Ke) (1.1 mJ at 1.5 N, 1000 N/m).
    double passivity_threshold = 2.0;
    // What a loop that generates energy gets: a fault (force to zero, ramp back; the default), or
    // the passivity controller's added damping (haptics/passivity_controller.hpp), with a fault
    // only when the device's damping limit (ServoConfig::max_damping) cannot hold the budget.
    PassivityMode passivity = PassivityMode::fault;
    // Sustained force oscillation past the discrete bound (haptics/limit_cycle_detector.hpp): what
    // the energy sums cannot resolve when the spring's linear range is about one encoder count.
    LimitCycleParams limit_cycle;
};

// Which detector raised ServoFault::instability (for reports and tables; the fault is the same).
enum class InstabilityCause : std::uint8_t {
    none,
    energy,       // the passivity observer's energy sum (whole loop or linear range)
    limit_cycle,  // a sustained force oscillation with K T / 2 > b (haptics/limit_cycle_detector.hpp)
};

// What the device declares; fixed while a device is connected.
struct ServoConfig {
    double period = 1e-3;                       // s, nominal tick period
    double device_max_force = 1.5;              // N, magnitude clamp
    Vec2 axis_max{1.5, 1.5};                    // N, per-axis saturation (after the clamp)
    double device_damping = 1.0;                // N s/m, for the passivity observer
    // N s/m: the most damping the passivity controller may add (a sampled damper past about m / T
    // rings; drivers/ derives it from the device's effective mass). 0: the controller cannot act.
    double max_damping = 0.0;
    bool has_roller = true;
    RollerTravel roller_travel;                 // m
};

// One measurement (SI). The tick validates it: NaN/Inf anywhere gives zero force and a fault.
struct ServoInput {
    double t = 0.0;                 // s, time of the measurement (device clock or virtual)
    Vec2 finger{0.0};               // x_f, m
    double phi = 0.0;               // rad
    double roller_l = 0.0;          // m, measured contact-element position (if has_roller)
    bool device_fault = false;      // the device says it is not in a state to take force
};

struct ServoCommand {
    Vec2 force{0.0};                // N on the finger, after every safety stage
    double roller_target = 0.0;     // m, l_d within travel
    double roller_drive = 0.0;      // roller motor drive (device units, V for the sim)
};

// What readers (UI, tests) see. Trivially copyable, published through a seqlock every tick.
struct ServoSnapshot {
    std::uint64_t ticks = 0;
    double t = 0.0;                 // s
    double dt = 0.0;                // s, time since the previous tick
    Vec2 finger{0.0};               // m
    double phi = 0.0;               // rad
    Vec2 proxy{0.0};                // m
    bool contact = false;
    int contact_count = 0;
    double depth = 0.0;             // m
    Vec2 rendered_force{0.0};       // N, the proxy's force before safety
    Vec2 force{0.0};                // N, as commanded to the device
    double l_d = 0.0;               // m
    double roller_l = 0.0;          // m
    double roller_target = 0.0;     // m
    double roller_drive = 0.0;
    double stiffness = 0.0;         // N/m, Ke in effect (after slew)
    double max_force = 0.0;         // N in effect
    double observer_energy = 0.0;   // J, the observer's whole-loop sum
    double observer_linear_energy = 0.0;  // J, its linear-range sum
    double observer_threshold = 0.0;      // J: either sum above this is an instability
    double observer_used = 0.0;           // the share of that the larger sum has used (PassivityObserver::used)
    EnergyTerms energy;             // J, this tick's balance (haptics/energy_balance.hpp)
    double passivity_damping = 0.0; // N s/m the passivity controller added this tick
    bool passivity_saturated = false;  // ... and it was capped at ServoConfig::max_damping
    int oscillation_half_cycles = 0;  // consecutive fast force half-cycles (limit-cycle detector)
    InstabilityCause instability_cause = InstabilityCause::none;  // of the last instability fault
    ServoState state = ServoState::idle;
    ServoFault fault = ServoFault::none;
    std::uint32_t fault_count = 0;
    std::uint32_t scene_swaps = 0;
};

class ServoTick {
public:
    // Throws std::invalid_argument naming the field when config or params cannot be honoured.
    ServoTick(const ServoConfig& config, const ServoParams& params);
    ~ServoTick();
    ServoTick(const ServoTick&) = delete;
    ServoTick& operator=(const ServoTick&) = delete;

    // --- servo thread -----------------------------------------------------------------------
    // Device became ready (the force ramps in over safety.ramp_time) / went away.
    void connect(double t) noexcept;
    void disconnect() noexcept;
    const ServoCommand& tick(const ServoInput& in) noexcept;
    const ProxyOutput& proxy_output() const noexcept { return proxy_out_; }
    // This tick's energy balance (all zero while no force is applied).
    const EnergyTerms& energy_terms() const noexcept { return energy_terms_; }
    const PassivityObserver& observer() const noexcept { return observer_; }
    ServoState state() const noexcept { return safety_.state(); }
    ServoFault fault() const noexcept { return safety_.fault(); }

    // --- other threads ----------------------------------------------------------------------
    // Publishes p for the next tick boundary. Parameters the tick cannot honour with this device
    // (servo_params_check.hpp) are not published: the message says which and why, and the servo
    // carries on with what it had. Returns "" when published. Allocation-free when p is valid.
    std::string publish_params(const ServoParams& p);
    SceneExchange& scenes() noexcept { return scenes_; }
    ServoSnapshot snapshot() const noexcept { return snapshot_.load(); }
    // Asks the servo to leave a latched fault (applied at the next tick boundary).
    void request_clear_fault() noexcept { clear_request_.store(true, std::memory_order_release); }
    // Before the servo thread starts (not thread-safe): the proxy's history from a servo this one
    // replaces (another rate, another device). The first scene's proxy then starts there, pushed
    // out to the surface if needed (Proxy::place), instead of at the first finger sample: a finger
    // resting in a wall keeps feeling it across the switch (issue 15).
    void seed_proxy(Vec2 proxy, double phi) noexcept;
    // Before the servo thread starts (not thread-safe): whether each tick publishes its snapshot
    // (on by default). A caller that never reads snapshot(), such as a simulated trial in virtual
    // time, turns it off: the seqlock's copy of the snapshot every tick is then saved (the tick's
    // commands, proxy_output(), energy_terms() and observer() are the same either way).
    void set_publish_snapshots(bool on) noexcept { publish_snapshots_ = on; }

    const ServoConfig& config() const noexcept { return config_; }

private:
    void apply_params(double dt) noexcept;
    void swap_scene(const ServoInput& in) noexcept;
    void fault_tick(const ServoInput& in, double dt, ServoFault f) noexcept;

    ServoConfig config_;
    ServoParams target_;   // last published
    ServoParams current_;  // in effect (slewed)
    Seqlock<ServoParams> params_in_;
    std::uint64_t params_seen_ = 0;
    SceneExchange scenes_;
    ServoScene* scene_ = nullptr;
    std::uint32_t scene_swaps_ = 0;
    RollerController roller_;
    SafetySupervisor safety_;
    PassivityObserver observer_;
    EnergyBalance balance_;
    PassivityController controller_;
    EnergyTerms energy_terms_;
    LimitCycleDetector limit_cycle_;
    InstabilityCause instability_cause_ = InstabilityCause::none;
    Seqlock<ServoSnapshot> snapshot_;
    std::atomic<bool> clear_request_{false};
    ProxyOutput proxy_out_;
    ServoCommand cmd_;
    Vec2 applied_{0.0};  // N, force commanded on the previous tick (held until now)
    double last_t_ = std::numeric_limits<double>::quiet_NaN();
    std::uint64_t ticks_ = 0;
    bool seeded_ = false;  // seed_proxy() was called: the first scene's proxy starts at seed_
    Vec2 seed_{0.0};
    double seed_phi_ = 0.0;
    bool publish_snapshots_ = true;
};

}  // namespace contactlab
