// contact_display.hpp — what the wearable platform shows of a 2-D contact: the servo's finger
// force F (N, world plane, pushing the finger out of the surface, so along the surface's normal)
// becomes a platform pose under the pad, as in seed 003's curvature display (§4): the platform
// tilts to the surface's orientation relative to the finger and presses with the contact force.
//
//   roll  = angle(F) - (phi + pi/2), wrapped to (-pi, pi]: the surface's slope seen from the pad,
//           positive where it rises toward the fingertip (the platform's +y side up)
//   press = |F| / k_n (m into the pad, the fingertip's normal stiffness, eq. 8)
//
// both clamped to what the platform can show. In free space (|F| below min_force) the platform
// is sent to rest (no tilt, no press): the cables go slack.
#pragma once

namespace contactlab::wearable {

struct ContactDisplayDef {
    double normal_stiffness = 2000.0;  // N/m, k_n of the fingertip (seed: 2 N/mm)
    double max_press = 0.0015;         // m into the pad (the platform's chords stay < 2 R_i)
    double max_tilt = 0.5;             // rad
    double min_force = 1e-4;           // N: below, no contact
};

struct PlatformPoseCommand {
    bool contact = false;
    double press = 0.0;  // m, p_z offset from the rest pose, + into the pad
    double roll = 0.0;   // rad
    double pitch = 0.0;  // rad (the plane's contact has none)
};

// Non-finite inputs give no contact (rest).
PlatformPoseCommand contact_to_platform(double fx, double fy, double phi, const ContactDisplayDef& def = {}) noexcept;

}  // namespace contactlab::wearable
