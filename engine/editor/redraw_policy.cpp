// redraw_policy.cpp — the on-demand drawing rule (see redraw_policy.hpp).
#include "engine/editor/redraw_policy.hpp"

#include <cmath>

namespace contactlab::editor {
namespace {

bool near(Vec2 a, Vec2 b, double tol) { return std::abs(a.x - b.x) <= tol && std::abs(a.y - b.y) <= tol; }
bool near(double a, double b, double tol) { return std::abs(a - b) <= tol; }

}  // namespace

bool looks_same(const ServoSnapshot& a, const ServoSnapshot& b) {
    // Tolerances far below a pixel at any zoom the editor offers and below the panels' digits, so
    // a device that settles to float noise (sim-cld's arm) does not keep the editor drawing.
    constexpr double um = 1e-6;
    return near(a.finger, b.finger, um) && near(a.phi, b.phi, 1e-5) && near(a.proxy, b.proxy, um) &&
           a.contact == b.contact && a.contact_count == b.contact_count && near(a.depth, b.depth, 0.1 * um) &&
           near(a.force, b.force, 1e-4) && near(a.l_d, b.l_d, um) && near(a.roller_l, b.roller_l, um) &&
           near(a.roller_target, b.roller_target, um) && near(a.stiffness, b.stiffness, 1e-3) &&
           near(a.max_force, b.max_force, 1e-6) && a.state == b.state && a.fault == b.fault &&
           a.fault_count == b.fault_count && a.scene_swaps == b.scene_swaps;
}

bool RedrawPolicy::should_draw(const RedrawInputs& in, double now) const {
    if (!have_) return true;
    if (in.events != last_.events || after_input_ > 0) return true;
    if (in.doc_revision != last_.doc_revision || in.servo_generation != last_.servo_generation) return true;
    if (in.snapshot && !looks_same(*in.snapshot, snapshot_)) return true;
    if (in.message && *in.message != message_) return true;
    return now - drawn_at_ >= kRefresh;
}

void RedrawPolicy::drawn(const RedrawInputs& in, double now) {
    // Input restarts the count of frames drawn after it; each frame drawn without input uses one.
    if (!have_ || in.events != last_.events) after_input_ = kAfterInput;
    else if (after_input_ > 0) --after_input_;
    have_ = true;
    last_ = in;
    if (in.snapshot) snapshot_ = *in.snapshot;
    last_.snapshot = nullptr;
    if (in.message) message_ = *in.message;
    last_.message = nullptr;
    drawn_at_ = now;
}

}  // namespace contactlab::editor
