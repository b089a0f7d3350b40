// contact_display.hpp — what the wearable platform shows of a 2-D contact: the servo's finger
// force F (N, world plane, pushing the finger out of the surface, so along the surface's normal)
// becomes a platform pose under the pad, as in seed 003's curvature display (§4): the platform
// tilts to the surface's orientation relative to the finger and presses with the contact force.
//
//   roll  = angle(F) - (phi + pi/2), wrapped to (-pi, pi]: the surface's slope seen from the pad,
//           positive where it rises toward the fingertip (the platform's +y side up)
//   press = |F| / k_n (m into the pad, the fingertip's normal stiffness, eq. 8)
//
// both clamped to what the platform can show: press to max_press, roll to max_tilt and then to
// the platform's reach at that press (its cables must wrap the finger: inverse kinematics). The
// seed's platform reaches -0.44..+0.88 rad of roll at rest and more pressed: a surface sloping
// down toward the fingertip by more than 25 degrees, touched lightly, asked for a pose it cannot
// take, and the device faulted ("a platform pose outside the workspace"). On a slope the force
// ramps in from zero after every fault, so a finger held there never got out of it. In free
// space (|F| below min_force) the platform is sent to rest (no tilt, no press): the cables go slack.
#pragma once

#include "haptics/wearable/finger_stiffness.hpp"
#include "haptics/wearable/statics.hpp"

namespace contactlab::wearable {

struct ContactDisplayDef {
    double normal_stiffness = 2000.0;  // N/m, k_n of the fingertip (seed: 2 N/mm)
    double max_press = 0.0015;         // m into the pad (the platform's chords stay < 2 R_i)
    double max_tilt = 0.5;             // rad
    double min_force = 1e-4;           // N: below, no contact
    PlatformDef platform;              // whose reach bounds the tilt (the seed's platform)
};

struct PlatformPoseCommand {
    bool contact = false;
    double press = 0.0;  // m, p_z offset from the rest pose, + into the pad
    double roll = 0.0;   // rad
    double pitch = 0.0;  // rad (the plane's contact has none)
};

// Non-finite inputs give no contact (rest).
PlatformPoseCommand contact_to_platform(double fx, double fy, double phi, const ContactDisplayDef& def = {}) noexcept;

// The commanded pose as a platform pose xi (rest + press on p_z, roll, pitch) and the cable
// tensions that hold it against the fingertip: eq. 8 gives the wrench, eq. 6 the tensions (least
// squares; a tension the geometry wants negative is shown as 0 and the status says so). For
// drawings and reports, not the servo tick (it allocates nothing but solves a 6x3 COD).
struct PlatformDisplayState {
    PlatformPoseCommand command;
    Pose pose = Pose::Zero();
    Eigen::Vector3d tension = Eigen::Vector3d::Zero();  // N
    StaticsStatus statics = StaticsStatus::ok;
    bool reachable = false;  // inverse kinematics succeeded at the pose
};
PlatformDisplayState platform_display_state(double fx, double fy, double phi, const PlatformDef& platform = {},
                                            const Mat6& stiffness = finger_stiffness(),
                                            const ContactDisplayDef& def = {});

}  // namespace contactlab::wearable
