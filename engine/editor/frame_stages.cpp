// frame_stages.cpp — stage names and the summary line (see frame_stages.hpp).
#include "engine/editor/frame_stages.hpp"

#include <cstdio>

namespace contactlab::editor {

const char* stage_name(Stage s) {
    switch (s) {
        case Stage::events: return "events";
        case Stage::ui: return "ui";
        case Stage::plots: return "plots";
        case Stage::imgui: return "imgui";
        case Stage::servo_sync: return "servo_sync";
        case Stage::scene_geometry: return "scene_geometry";
        case Stage::overlays: return "overlays";
        case Stage::frame_wait: return "frame_wait";
        case Stage::record: return "record";
        case Stage::submit: return "submit";
        case Stage::rasterise: return "rasterise";
        case Stage::present: return "present";
        case Stage::kCount: break;
    }
    return "?";
}

std::string FrameStages::summary() const {
    std::string out;
    double sum = 0.0;
    char buf[64];
    for (int i = 0; i < kStageCount; ++i) {
        const Stage s = static_cast<Stage>(i);
        sum += mean_ms(s);
        std::snprintf(buf, sizeof buf, "%s%s %.2f", out.empty() ? "" : ", ", stage_name(s), mean_ms(s));
        out += buf;
    }
    std::snprintf(buf, sizeof buf, " (sum %.2f ms/frame)", sum);
    return out + buf;
}

}  // namespace contactlab::editor
