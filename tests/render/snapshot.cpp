// snapshot.cpp — golden files: compare, report, write .new/.diff, update on request.
#include "snapshot.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace render_test {

namespace fs = std::filesystem;
using contactlab::render::Image;

bool g_update_snapshots = false;

namespace {

bool update_requested() {
    const char* env = std::getenv("CONTACTLAB_UPDATE_SNAPSHOTS");
    return g_update_snapshots || (env && std::string(env) == "1");
}

int tolerance() {
    const char* env = std::getenv("CONTACTLAB_SNAPSHOT_TOLERANCE");
    return env ? std::clamp(std::atoi(env), 0, 255) : 0;
}

// Differing pixels in red (brighter = larger difference) over a faded copy of the golden.
Image diff_picture(const Image& golden, const Image& actual, int tol) {
    Image d = actual;
    for (int y = 0; y < d.height; ++y)
        for (int x = 0; x < d.width; ++x) {
            const uint8_t* g = golden.pixel(x, y);
            const uint8_t* a = actual.pixel(x, y);
            int m = 0;
            for (int c = 0; c < 4; ++c) m = std::max(m, std::abs(int(g[c]) - int(a[c])));
            uint8_t* o = d.pixel(x, y);
            if (m > tol) {
                o[0] = static_cast<uint8_t>(std::min(255, 128 + m));
                o[1] = 0;
                o[2] = 0;
            } else {
                const int grey = (g[0] + g[1] + g[2]) / 12;
                o[0] = o[1] = o[2] = static_cast<uint8_t>(grey);
            }
            o[3] = 255;
        }
    return d;
}

}  // namespace

ImageDiff diff_images(const Image& a, const Image& b, int tol) {
    ImageDiff r;
    for (size_t i = 0; i < a.rgba.size(); i += 4) {
        int m = 0;
        for (int c = 0; c < 4; ++c) m = std::max(m, std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])));
        if (m > tol) ++r.differing;
        r.max_diff = std::max(r.max_diff, m);
    }
    return r;
}

SnapshotResult check_snapshot(const std::string& name, const Image& image) {
    const fs::path golden_path = fs::path(CONTACTLAB_SNAPSHOT_DIR) / (name + ".png");
    const fs::path fail_dir = fs::path(CONTACTLAB_FAILURE_DIR);
    if (update_requested()) {
        fs::create_directories(golden_path.parent_path());
        contactlab::render::write_png(golden_path.string(), image);
        return {true, "updated " + golden_path.string()};
    }
    auto write_new = [&] {
        fs::create_directories(fail_dir);
        const fs::path p = fail_dir / (name + ".new.png");
        contactlab::render::write_png(p.string(), image);
        return p.string();
    };
    if (!fs::exists(golden_path)) {
        const std::string p = write_new();
        return {false, "missing golden " + golden_path.string() + " (the new picture is " + p +
                           "); look at it, then create the golden deliberately with "
                           "CONTACTLAB_UPDATE_SNAPSHOTS=1 ctest -L render (or render_tests --update-snapshots)"};
    }
    const Image golden = contactlab::render::read_png(golden_path.string());
    if (golden.width != image.width || golden.height != image.height) {
        const std::string p = write_new();
        return {false, name + ": size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                           " differs from the golden's " + std::to_string(golden.width) + "x" +
                           std::to_string(golden.height) + "; new picture: " + p};
    }
    const int tol = tolerance();
    const ImageDiff d = diff_images(golden, image, tol);
    if (d.differing == 0) return {true, name + ": matches"};
    const std::string p = write_new();
    const fs::path diff_path = fail_dir / (name + ".diff.png");
    contactlab::render::write_png(diff_path.string(), diff_picture(golden, image, tol));
    return {false, name + ": " + std::to_string(d.differing) + " pixels differ (tolerance " + std::to_string(tol) +
                       "), max channel difference " + std::to_string(d.max_diff) + "; new: " + p +
                       ", diff: " + diff_path.string() +
                       "; if the change is intended: CONTACTLAB_UPDATE_SNAPSHOTS=1 ctest -L render"};
}

}  // namespace render_test
