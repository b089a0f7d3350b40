// scene_io.hpp — reading, validating and writing scene files (JSON, format in scenes/README.md).
//
// Every problem is reported as a SceneError whose message names the JSON path and the problem,
// e.g. "contours[1].segments[4]: zero-length line". The parser never crashes, whatever the bytes.
#pragma once

#include "haptics/scene.hpp"

#include <stdexcept>
#include <string>
#include <string_view>

namespace contactlab {

struct SceneError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The SceneError for closed contours that cross themselves or each other (contour_crossing.hpp),
// e.g. "contours[0]: crosses itself at (12.300, 4.000) mm (segments 2 and 5)", with the point
// (m), which the editor marks.
struct ContourCrossingError : SceneError {
    ContourCrossingError(const std::string& what, Vec2 at) : SceneError(what), point(at) {}
    Vec2 point{0.0};
};

// Largest gap (m) allowed between the end of one segment and the start of the next.
inline constexpr double kSceneJoinTolerance = 1e-9;

// Parses and validates scene JSON text. `origin` (a file name) prefixes error messages.
Scene parse_scene(std::string_view json_text, const std::string& origin = "scene");
// Reads a file and parses it; a missing or unreadable file is a SceneError too.
Scene load_scene_file(const std::string& path);
// Reads work in progress (an editor recovery file): the JSON structure, types and keys are
// checked as above, the scene's rules (zero-length segments, gaps, ranges) are not, since a
// half-drawn shape is still the user's work. Callers validate before using it.
Scene load_work_in_progress(const std::string& path);
// Checks a scene built in memory (the same rules the parser applies); throws SceneError.
void validate_scene(const Scene& scene);
// Serialises losslessly (doubles round-trip exactly).
std::string scene_to_json_text(const Scene& scene);
// Atomic save: writes a temporary file beside `path`, flushes it, then renames it over `path`.
void save_scene_file(const Scene& scene, const std::string& path);

}  // namespace contactlab
