// redraw_policy.hpp — when the interactive editor draws a frame. It used to draw every frame
// whether or not anything had changed (a core of lavapipe for a still picture). Now, between
// frames, the loop sleeps in glfwWaitEventsTimeout for at most kPoll (it wakes at once on input),
// drains the servo's records (plots, recording) and asks should_draw(): a frame is drawn when
// there was input (and for kAfterInput frames after it: ImGui opens popups and settles hover one
// frame later), when the document changed, when the servo shows something different (finger,
// proxy, force, contact, roller, state: moved past the tolerances below), and otherwise once
// every kRefresh so the period statistics and plots stay current. --frames, scripts (outside
// their `idle`) and experiments draw every frame as before.
#pragma once

#include "haptics/servo_tick.hpp"

#include <cstdint>
#include <string>

namespace contactlab::editor {

// What the loop saw at a wake.
struct RedrawInputs {
    std::uint64_t events = 0;           // Window::events()
    std::uint64_t doc_revision = 0;     // Document::revision()
    std::uint64_t servo_generation = 0; // HapticsHost::generation(): a device or rate switch
    const ServoSnapshot* snapshot = nullptr;
    const std::string* message = nullptr;  // the status row's message
};

class RedrawPolicy {
public:
    static constexpr double kPoll = 0.010;   // s: longest sleep between wakes (10 ms)
    static constexpr double kRefresh = 1.0;  // s: an unchanged editor still draws this often
    static constexpr int kAfterInput = 3;    // frames drawn after the last input

    // Whether to draw a frame now (`now` in s, monotonic).
    bool should_draw(const RedrawInputs& in, double now) const;
    // A frame was drawn with these inputs.
    void drawn(const RedrawInputs& in, double now);

private:
    bool have_ = false;
    RedrawInputs last_{};
    ServoSnapshot snapshot_{};
    std::string message_;
    double drawn_at_ = 0.0;
    int after_input_ = 0;
};

// Whether two snapshots would draw differently: positions within 1 um, force within 0.1 mN,
// depth within 0.1 um, the same contact, state and fault.
bool looks_same(const ServoSnapshot& a, const ServoSnapshot& b);

}  // namespace contactlab::editor
