// parameter_limits.hpp — the ranges ContactLab honours for every physical parameter, shared by
// scene validation (scene_io.cpp) and the servo's parameter check (servo_params_check.hpp), so a
// value a scene file may hold is also one the live panel may publish, and the other way round.
#pragma once

namespace contactlab::limits {

// Finger (m). The lower bound keeps c-space pieces well conditioned; the upper bound catches
// values typed in millimetres by mistake (26 instead of 0.026).
inline constexpr double kMinFingerRadius = 1e-4;
inline constexpr double kMaxFingerRadius = 1.0;
inline constexpr double kMinSegmentLength = 1e-9;   // m: shorter lines/arcs are "zero-length"
inline constexpr double kMaxCoordinate = 1e6;       // m: beyond this, double spacing > 1e-10 m
inline constexpr double kMaxStiffness = 1e7;        // N/m: far above any device's stable stiffness
// The live servo takes up to 1e6 x the nominal 1000 N/m: stability probes deliberately go 1000x
// past the passivity bound (7e4 N/m at 20 kHz) to prove the instability is reported; a scene file
// asking for more than kMaxStiffness is a typo.
inline constexpr double kMaxServoStiffness = 1e9;   // N/m
inline constexpr double kMaxForceLimit = 1e4;       // N
inline constexpr double kMinCurveTolerance = 1e-9;  // m, flatten mode's chord tolerance
inline constexpr double kMaxCurveTolerance = 1e-2;  // m
inline constexpr double kMaxDamping = 1e3;          // N s/m
inline constexpr double kMaxFriction = 10.0;        // friction coefficients
// Servo rates (Hz) the tick is specified for. Real-time threads are offered 100 Hz..20 kHz
// (scheduling on a desktop kernel does not hold 100 kHz); virtual time goes to 100 kHz.
inline constexpr double kMinServoRate = 100.0;
inline constexpr double kMaxServoRate = 1e5;
inline constexpr double kMaxRealtimeServoRate = 2e4;

}  // namespace contactlab::limits
