// snapshot.hpp — golden-image comparison for the render tests.
//
// Tolerance: exact by default (every channel of every pixel equal) — lavapipe output is
// bit-stable for this renderer (UNORM, 1x sampling, geometric anti-aliasing). On another driver
// set CONTACTLAB_SNAPSHOT_TOLERANCE=N to accept per-channel differences up to N (0..255).
// CONTACTLAB_UPDATE_SNAPSHOTS=1 (or render_tests --update-snapshots) rewrites the goldens.
#pragma once

#include "engine/render/image.hpp"

#include <string>

namespace render_test {

struct SnapshotResult {
    bool ok = false;
    std::string message;     // what happened, for the test log
};

// Set by test_main.cpp from --update-snapshots.
extern bool g_update_snapshots;

// Compares `image` with tests/snapshots/NAME.png. On a difference writes NAME.new.png and
// NAME.diff.png into the build folder's snapshot-failures/ and reports the count of differing
// pixels and the largest channel difference. A missing golden is a failure with instructions.
SnapshotResult check_snapshot(const std::string& name, const contactlab::render::Image& image);

// Pixels whose channels differ by more than `tolerance`, and the largest difference (0..255).
struct ImageDiff {
    long long differing = 0;
    int max_diff = 0;
};
ImageDiff diff_images(const contactlab::render::Image& a, const contactlab::render::Image& b, int tolerance);

}  // namespace render_test
