// scene_loader_check.hpp — the property the scene-loader fuzzer checks, shared by the libFuzzer
// target (scene_loader_fuzz.cpp) and the corpus replay that ctest runs (scene_loader_replay.cpp).
//
// For any bytes at all, parse_scene() must either return a scene or throw SceneError whose message
// is in the project's style ("ORIGIN: ..."), never leak another exception or nlohmann's raw text.
// A scene it accepts must save to text that reads back to exactly the same text (lossless doubles).
#pragma once

#include "haptics/scene_io.hpp"

#include <exception>
#include <string>
#include <string_view>

namespace contactlab::fuzz {

inline constexpr const char* kOrigin = "fuzz-input";

// Returns "" when the input behaved, otherwise a description of the bug.
inline std::string check_scene_input(std::string_view bytes) {
    Scene scene;
    try {
        scene = parse_scene(bytes, kOrigin);
    } catch (const SceneError& e) {
        const std::string msg = e.what();
        if (msg.rfind(std::string(kOrigin) + ": ", 0) != 0)
            return "SceneError message does not start with the origin: " + msg;
        // parse_scene turns unforeseen library exceptions into SceneError too, as "ORIGIN: " plus
        // nlohmann's raw text: an error path nobody wrote a message for. (Only the start is looked
        // at: a syntax error quotes the input, which may contain any text.)
        if (msg.rfind(std::string(kOrigin) + ": [json.exception", 0) == 0)
            return "SceneError carries nlohmann's raw message (no path): " + msg;
        return {};
    } catch (const std::exception& e) {
        return std::string("parse_scene threw something other than SceneError: ") + e.what();
    } catch (...) {
        return "parse_scene threw a non-std::exception";
    }

    try {
        const std::string text = scene_to_json_text(scene);
        const std::string again = scene_to_json_text(parse_scene(text, "round trip"));
        if (again != text) return "save -> load changed the scene:\n" + text + "\n--- became ---\n" + again;
    } catch (const std::exception& e) {
        return std::string("the saved text of an accepted scene was refused: ") + e.what();
    }
    return {};
}

}  // namespace contactlab::fuzz
