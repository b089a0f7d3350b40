// servo_params_check.hpp — whether the servo tick can honour a set of parameters, and if not,
// which one and why, in words a user can act on ("stiffness: must lie in (0, 1e+07] N/m, got -1").
//
// The tick itself survives anything (a NaN published by mistake is ignored, an absurd value is
// clamped by the device's force limit), but surviving is not honouring: callers that take values
// from a user (the editor's panel, command-line options) check first and show the message instead
// of publishing. An empty string means the parameters are fine.
#pragma once

#include "haptics/roller_controller.hpp"
#include "haptics/servo_tick.hpp"

#include <string>

namespace contactlab {

std::string roller_gains_problem(const RollerGains& g);
std::string servo_config_problem(const ServoConfig& c);
// Checks p against the device's config c too: e.g. a watchdog shorter than two periods would
// fault on every tick at low rates.
std::string servo_params_problem(const ServoParams& p, const ServoConfig& c);

}  // namespace contactlab
