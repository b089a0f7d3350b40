// frame_stages.hpp — where a drawn frame's time goes, stage by stage, for `contactlab edit
// --frames N` (printed with the fps at exit) and the Haptics panel. Each stage is named after what
// the frame loop really does in it; the clock is steady_clock and the hot path only adds doubles
// into a fixed array (no allocation).
#pragma once

#include <array>
#include <chrono>
#include <string>

namespace contactlab::editor {

enum class Stage {
    events,          // glfwPollEvents: the window system's input
    ui,              // ImGui new frame, input or script, menus and panels (the plots apart)
    plots,           // the Plots panel's rolling plots (five or six, min/max envelopes)
    imgui,           // ImGui::Render: the panels' vertices
    servo_sync,      // scene/parameters published, tick records drained (plots, recording)
    scene_geometry,  // grid and solids into the draw list (or the cached layer reused)
    overlays,        // finger, proxy, force, contacts, c-space/zones, legend, canvas marks, rulers
    frame_wait,      // waiting for this frame slot's previous frame to finish
    record,          // acquire, upload the vertices, record the command buffer (ImGui's too)
    submit,          // vkQueueSubmit
    rasterise,       // waiting for the queue after submit (measuring only: set_stage_timing)
    present,         // vkQueuePresentKHR (lavapipe: the image copied to the X server)
    kCount
};
inline constexpr int kStageCount = static_cast<int>(Stage::kCount);
const char* stage_name(Stage s);

class FrameStages {
public:
    using Clock = std::chrono::steady_clock;

    void add(Stage s, Clock::duration d) { total_[static_cast<int>(s)] += std::chrono::duration<double>(d).count(); }
    // One frame drawn (presented): the means are per drawn frame.
    void frame_drawn() { ++frames_; }
    long frames() const { return frames_; }
    double mean_ms(Stage s) const { return frames_ ? 1e3 * total_[static_cast<int>(s)] / frames_ : 0.0; }
    // "scene_geometry 0.12 ms, overlays 0.30 ms, ..." (means per drawn frame) and their sum.
    std::string summary() const;

private:
    std::array<double, kStageCount> total_{};  // s
    long frames_ = 0;
};

// Adds the time from construction to destruction (or to stop()) to one stage.
class StageTimer {
public:
    StageTimer(FrameStages* stages, Stage s) : stages_(stages), stage_(s), t0_(FrameStages::Clock::now()) {}
    ~StageTimer() { stop(); }
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;
    void stop() {
        if (stages_) stages_->add(stage_, FrameStages::Clock::now() - t0_);
        stages_ = nullptr;
    }

private:
    FrameStages* stages_;
    Stage stage_;
    FrameStages::Clock::time_point t0_;
};

}  // namespace contactlab::editor
