// test_wearable_scene.cpp — the scene's `wearable.finger_stiffness` (seed 003's K of eq. 8, 6x6):
// read, written back bit for bit, and refused when it is not a spring's.
#include "haptics/scene_io.hpp"
#include "haptics/wearable/finger_stiffness.hpp"

#include <doctest/doctest.h>

#include <string>

using namespace contactlab;

namespace {
std::string scene_with(const std::string& wearable) {
    return R"({"version": 1, "contours": [], "wearable": )" + wearable + "}";
}
std::string diag_rows(double kt, double kn, double kb, double ks, double off = 0.0) {
    const double d[6] = {kt, kt, kn, kb, kb, ks};
    std::string s = "{\"finger_stiffness\": [";
    for (int r = 0; r < 6; ++r) {
        s += r ? ", [" : "[";
        for (int c = 0; c < 6; ++c) {
            const double v = r == c ? d[r] : ((r == 0 && c == 2) || (r == 2 && c == 0) ? off : 0.0);
            s += (c ? ", " : "") + std::to_string(v);
        }
        s += "]";
    }
    return s + "]}";
}
}  // namespace

TEST_CASE("wearable scene stiffness: the seed's anisotropic K is read, round-trips and is a spring") {
    const Scene s = parse_scene(scene_with(diag_rows(500.0, 2000.0, 0.01, 0.005, 100.0)));
    REQUIRE(s.wearable.has_finger_stiffness);
    CHECK(s.wearable.finger_stiffness[0] == 500.0);
    CHECK(s.wearable.finger_stiffness[2 * 6 + 2] == 2000.0);
    CHECK(s.wearable.finger_stiffness[0 * 6 + 2] == 100.0);
    const Scene back = parse_scene(scene_to_json_text(s));
    CHECK(back.wearable.finger_stiffness == s.wearable.finger_stiffness);
    const wearable::Mat6 k =
        Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(s.wearable.finger_stiffness.data());
    CHECK(wearable::check_stiffness(k).ok);
    CHECK(k == wearable::finger_stiffness_diag(500.0, 2000.0, 0.01, 0.005) +
                   (wearable::Mat6() << 0, 0, 100, 0, 0, 0, 0, 0, 0, 0, 0, 0, 100, 0, 0, 0, 0, 0,
                    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0).finished());
    // Without the key nothing changes for other scenes, and nothing is written.
    const Scene plain = parse_scene(R"({"version": 1, "contours": []})");
    CHECK_FALSE(plain.wearable.has_finger_stiffness);
    CHECK(scene_to_json_text(plain).find("wearable") == std::string::npos);
}

TEST_CASE("wearable scene stiffness: wrong shape, asymmetry, a non-positive diagonal are refused by path") {
    auto error_of = [](const std::string& text) {
        try {
            parse_scene(text);
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(error_of(scene_with(R"({"finger_stiffness": [[1, 2], [3, 4]]})")).find("wearable.finger_stiffness") != std::string::npos);
    CHECK(error_of(scene_with(R"({"stiffness": 3})")).find("unknown key") != std::string::npos);
    std::string asym = diag_rows(500.0, 2000.0, 0.01, 0.005);
    asym.replace(asym.find(", 0.000000"), 10, ", 7.000000");  // entry 0,1 only
    CHECK(error_of(scene_with(asym)).find("symmetric") != std::string::npos);
    CHECK(error_of(scene_with(diag_rows(500.0, 0.0, 0.01, 0.005))).find("diagonal entry 2") != std::string::npos);
    // Symmetric with a positive diagonal but not positive definite: the scene loads, the platform
    // refuses it (check_stiffness), which is where simulate reports it.
    const Scene s = parse_scene(scene_with(diag_rows(100.0, 100.0, 0.01, 0.005, 500.0)));
    const wearable::Mat6 k =
        Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(s.wearable.finger_stiffness.data());
    CHECK_FALSE(wearable::check_stiffness(k).ok);
}
