// force_law.hpp — the force laws applied between the finger and the proxy's anchor point.
//
//   spring     F = Ke (x_s - x_f)                           (seed 000 eq. 1)
//   ellipsoid  F = -(|E p| / |p|) p,  p = x_f - x_s,  E = diag(k_tangential, k_normal) in the
//              contact's (tangent, normal) frame             (seed 004 eq. 2: the pseudo-ellipsoidal
//              field, always pointing at the anchor; e = k_normal / k_tangential = 1 is the spring)
// The anchor x_s is the frictionless proxy, or with friction the stiction point of the friction
// cone (seed 004 §II, after [11]): it holds while |F_t| <= mu_s F_n and otherwise slides along the
// surface until |F_t| = mu_d F_n. Optional normal damping B adds B v_n along the normal while the
// penetration grows or shrinks (never pulling the finger in).
#pragma once

#include "haptics/vec2.hpp"

namespace contactlab {

enum class ForceModel { spring, ellipsoid };

// What the finger feels when it presses on more than one surface (a concave corner of the
// contour, the onset of a bump).
//   proxy  the god-object force toward the proxy: one spring, however many contacts (seed 000);
//   sum    seed 002's penalty force: the sum over every contact pair the finger has entered of
//          k d_i n_i, d_i its depth behind that pair's c-space piece along the piece's normal n_i
//          (seed 002 §2.3: "the sum of the forces at each contact point pair"). Pressing into a
//          narrow V feels stiffer than pressing on one wall, as two springs in parallel, and the
//          second wall pushes as soon as the finger reaches it, not when the proxy does. With one
//          surface under the finger both are the same.
enum class ContactForce { proxy, sum };

struct ForceLaw {
    ForceModel model = ForceModel::spring;
    double k_tangential = 1000.0;  // N/m, ellipsoid only (seed 004's k1)
    double k_normal = 1000.0;      // N/m, ellipsoid only (seed 004's k2)
    // rad, ellipsoid only: the field's axes turned counter-clockwise from the contact's (tangent,
    // normal) frame. Seed 004 tilts the most compliant axis a1 to alpha = 45 or 135 deg from the
    // surface; with e < 1 (k2 < k1) a1 is the k_normal axis, so alpha = 90 deg + field_angle.
    double field_angle = 0.0;
    double damping = 0.0;          // B, N s/m along the normal; 0: none
    double mu_static = 0.0;        // friction cone; 0: frictionless (the stiction point is the proxy)
    double mu_dynamic = 0.0;       // <= mu_static
    ContactForce contacts = ContactForce::proxy;  // several contacts: one spring, or their sum
};

// The pseudo-ellipsoidal field for penetration p = x_f - x_s (m) at a contact with free-side unit
// normal n: magnitude |E p| along -p, E's axes turned by `field_angle` (rad) from (tangent, n).
// Zero at p = 0 (no division by zero).
Vec2 ellipsoid_force(Vec2 p, Vec2 n, double k_tangential, double k_normal, double field_angle = 0.0);

// Seed 004 eq. 3 characterises the field by eccentricity e = k2 / k1 and total stiffness
// k = sqrt((k1^2 + 2 k2^2) / 3). Its E = diag(k1, k1, k2) has two tangential axes, which suggests
// k = sqrt((2 k1^2 + k2^2) / 3) instead (the RMS of E's diagonal). ContactLab uses the printed
// formula; the other is available as TotalStiffness::diagonal_rms.
enum class TotalStiffness { printed, diagonal_rms };
// k1 (tangential stiffness, N/m) for total stiffness k (N/m) and eccentricity e.
double tangential_stiffness_from(double k, double e, TotalStiffness formula = TotalStiffness::printed);

}  // namespace contactlab
