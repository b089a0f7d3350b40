// energy_balance.hpp — where the energy a servo tick gives the finger comes from, term by term.
//
// The device and the finger meet at one port: the force F (N) the motors hold over a period (a
// zero-order hold) and the finger's motion dx (m). A passive display never gives the finger more
// energy than the virtual spring stored: per tick, F_{k-1} . dx + U_k - U_{k-1} <= 0, U (J) the
// spring's potential. That sum is what the passivity observer watches (haptics/safety.hpp,
// Hannaford & Ryu 2002). Split along the tick's own steps it says where a surplus comes from:
//
//   hold      F_{k-1} . dx + U(x_k; a_{k-1}) - U(x_{k-1}; a_{k-1}): the sampled spring with its
//             anchor a held, i.e. the zero-order hold's K |dx|^2 / 2 (Colgate & Schenkel 1997's
//             K T / 2 of negative damping, per tick K T v^2 T / 2), plus the virtual damper's work
//             (negative: it dissipates). The only term the device's physical damping must pay for.
//   field     the pseudo-ellipsoidal field (seed 004) is central but anisotropic, so it has no
//             potential: U here is the work along the ray from the anchor, |E p| |p| / 2, and
//             turning the penetration p against the field's axes changes it by (|p|^2 / 2) dg
//             with no motion along p. Zero for the spring (g = K in every direction).
//   turn      U(x_k; p_turned) - U(x_k; p_start): the finger angle phi turned the pad into the
//             surface and pushed the proxy out. The hand drives phi, the device renders no
//             torque: this is the hand's work, and it is not counted against the loop. Turning
//             the pad back out pushes nothing: the walk then brings the proxy back toward the
//             finger and releases that energy. So on a tick whose phi changed, what the walk
//             releases beyond this tick's `hold` (the share a slide along the surface gives back)
//             is the hand's too and moves here (negative): a pad toggled in and out at a contact
//             nets zero, instead of crediting the loop with dissipation it never did.
//   edit      U(x_k; p_start) - U(x_k; p_{k-1}) on a tick that swapped in a new scene: the swap
//             placed the proxy on the new geometry (Proxy::place), the user's edit, not counted
//             either. (On other ticks the same difference is the exact-curve refinement of the
//             last output, Proxy::refine_on_curves, and belongs to `proxy`.)
//   proxy     U(x_k; p_k) - U(x_k; p_turned): the god-object's walk toward the finger with phi
//             held. It moves along the constraint toward the nearest point, so this is <= 0 for
//             the Euclidean spring (the property tests hold it to that). For the ellipsoid, whose
//             U is not the Euclidean distance the walk minimises, it can be either sign.
//   friction  the change of (U(x; a) - U(x; p)), the stiction point's offset from the proxy:
//             positive while the stick spring loads, negative when it slips (dynamic friction).
//             (A scene swap starts a new proxy with no stiction point: that tick's change is the
//             edit's.)
//   damping   -b (n . dx)^2 / T: what the device's own damping b (N s/m) dissipated along the
//             spring's line of action n (motion across it is the hand's).
//
// generated() = hold + field + proxy + friction + damping: what the loop itself made. hold + field
// + turn + edit + proxy + friction = F_{k-1} . dx + U_k - U_{k-1} exactly (telescoped).
//
// Not in the balance: the roller (seed 000's contact element) moves along the pad under its own
// position loop and exerts no force on the finger's x, so it is another port; the summed contact
// law (ContactForce::sum) adds second-surface springs whose energy U leaves out (their work lands
// in `hold`); the ramp and a stiffness edit rescale U with the finger still (both evaluated with
// this tick's share and stiffness, so neither reads as generated).
#pragma once

#include "haptics/force_law.hpp"
#include "haptics/vec2.hpp"

namespace contactlab {

// Energy (J) stored in the rendered spring at penetration `depth` (m) with stiffness k (N/m) and
// the force clamped at max_force (N): quadratic up to the clamp, linear beyond.
double spring_energy(double depth, double k, double max_force) noexcept;

// The force law's potential (J) for the finger at x (m) against anchor a (m) with contact normal
// n (unit, from the finger toward the proxy): the work the law's force does along the ray from a
// to x, with the clamp at max_force (N): quadratic up to the clamp, linear beyond. stiffness: Ke
// (N/m) for the spring; the ellipsoid uses its own k_tangential and k_normal.
double law_energy(const ForceLaw& law, double stiffness, double max_force, Vec2 x, Vec2 a, Vec2 n) noexcept;

// One tick's energy terms (J); see the file comment.
struct EnergyTerms {
    double hold = 0.0;
    double field = 0.0;
    double turn = 0.0;
    double edit = 0.0;
    double proxy = 0.0;
    double friction = 0.0;
    double damping = 0.0;
    // What the loop generated this tick (the observer's input): the hand's and the user's terms
    // (turn, edit) left out.
    double generated() const noexcept { return hold + field + proxy + friction + damping; }
};

// What the balance reads from a tick.
struct EnergySample {
    Vec2 finger{0.0};     // x_k, m
    Vec2 start{0.0};      // proxy at the start of the update (after a scene swap), m
    Vec2 turned{0.0};     // proxy after the finger angle's re-projection, m
    Vec2 proxy{0.0};      // proxy after the walk (the frictionless anchor), m
    Vec2 anchor{0.0};     // where the force points (stiction point or proxy), m
    Vec2 applied{0.0};    // F_{k-1}: the force held on the device since the last tick, N
    // Fraction of the law's force the device passes on this tick (the safety ramp's scale times
    // what the per-axis saturation kept), 0..1.
    double share = 1.0;
    double dt = 1e-3;     // s since the last tick
    bool swapped = false; // a new scene was swapped in this tick (start is where place() put it)
    double phi = 0.0;     // rad, the finger angle this tick
};

// The law the spring follows this tick.
struct EnergyLaw {
    ForceLaw law;
    double stiffness = 1000.0;     // N/m
    double max_force = 1.5;        // N
    double device_damping = 1.0;   // b, N s/m
};

// Keeps the last tick's finger, proxy and anchor. O(1), no allocation: safe in the servo tick.
class EnergyBalance {
public:
    void reset() noexcept {
        primed_ = false;
        line_ = motion_ = Vec2{0.0};
    }
    // This tick's terms (all zero on the first tick after a reset).
    EnergyTerms step(const EnergySample& s, const EnergyLaw& law) noexcept;
    Vec2 motion() const noexcept { return motion_; }  // m: the finger's motion in the last step
    Vec2 line() const noexcept { return line_; }      // unit (or zero): the spring's line of action

private:
    Vec2 motion_{0.0};
    double prev_phi_ = 0.0;  // rad
    bool primed_ = false;
    Vec2 prev_x_{0.0}, prev_proxy_{0.0}, prev_anchor_{0.0}, prev_normal_{0.0, 1.0};
    Vec2 line_{0.0};  // unit: the spring's line of action (last non-zero force's direction)
};

}  // namespace contactlab
