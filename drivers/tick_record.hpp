// tick_record.hpp — one servo tick as recorded (plain data, pushed through an SPSC ring).
#pragma once

#include "haptics/energy_balance.hpp"
#include "haptics/safety.hpp"
#include "haptics/vec2.hpp"

#include <cstdint>

namespace contactlab::drivers {

struct TickRecord {
    std::uint64_t tick = 0;
    double t = 0.0;              // s, device (or virtual) time of the reading
    double period = 0.0;         // s, time since the previous tick (wall clock in real time)
    Vec2 finger{0.0};            // m, measured x_f
    double phi = 0.0;            // rad, measured
    double roller_l = 0.0;       // m, measured roller position
    Vec2 proxy{0.0};             // m
    bool contact = false;
    double depth = 0.0;          // m
    Vec2 force{0.0};             // N, commanded to the device (after safety)
    double l_d = 0.0;            // m
    double roller_target = 0.0;  // m
    double roller_drive = 0.0;   // V (sim) or device units
    EnergyTerms energy;          // J, the tick's energy balance (haptics/energy_balance.hpp)
    double observer_energy = 0.0;  // J, the passivity observer's sum after this tick
    double observer_margin = 0.0;  // J, what the loop may still generate before a report
    double observer_used = 0.0;    // the share of the observer's budget used (1: a report)
    ServoState state = ServoState::idle;
    ServoFault fault = ServoFault::none;
};

}  // namespace contactlab::drivers
