// test_device_sections.cpp — issue 29's pieces that need no window: the wearable's live tuning
// reaches the simulated platform (gains, fit mode, FSR noise) and is refused past its limits; the
// roller's feed-forward is live; the Plots panel's per-column envelope keeps a one-tick spike that
// one-sample-per-column thinning drops; its ticks are round; and the layout gives the Plots panel
// the height of all its plots at 1280 x 720.
#include "drivers/sim/sim_wearable_device.hpp"
#include "engine/editor/layout.hpp"
#include "engine/editor/live_plot.hpp"
#include "engine/editor/parameter_edit.hpp"
#include "engine/editor/plot_envelope.hpp"
#include "haptics/wearable/rig_tuning.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace contactlab;
using namespace contactlab::editor;

TEST_CASE("wearable tuning: set_tuning reaches the running rig at the next advance and survives a reopen") {
    drivers::sim::SimWearableDevice dev;
    REQUIRE(dev.open());
    dev.advance(0.001);
    REQUIRE(dev.rig() != nullptr);
    CHECK(dev.rig()->def().force.kp == doctest::Approx(4.0e-3));
    CHECK(dev.rig()->def().reference_time_constant == doctest::Approx(1.0 / (2.0 * 3.141592653589793 * 3.5)));
    wearable::RigTuning t = dev.tuning();
    t.force_kp = 2.5e-3;      // N m/N
    t.force_kd = 2.0e-5;      // N m s/N
    t.position_kp = 0.9;      // N m/m
    t.position_kd = 1.0e-3;   // N m s/m
    t.seed_fit = false;
    t.fsr_noise = 0.004;      // N
    dev.set_tuning(t);
    CHECK(dev.rig()->def().force.kp == doctest::Approx(4.0e-3));  // not before the servo's next advance
    dev.advance(0.001);
    const wearable::RigDef& d = dev.rig()->def();
    CHECK(d.force.kp == 2.5e-3);
    CHECK(d.force.kd == 2.0e-5);
    CHECK(d.position.kp == 0.9);
    CHECK(d.position.kd == 1.0e-3);
    CHECK(d.reference_time_constant == 0.0);
    CHECK(dev.rig()->plant().def().fsr_noise == 0.004);
    dev.close();
    REQUIRE(dev.open());  // a reopened rig is assembled as tuned
    CHECK(dev.rig()->def().force.kp == 2.5e-3);
    CHECK(dev.rig()->plant().def().fsr_noise == 0.004);
}

TEST_CASE("wearable tuning: negative, non-finite and absurd values are refused with the name") {
    wearable::RigTuning t;
    CHECK(wearable::rig_tuning_problem(t).empty());
    t.force_kp = -1e-3;
    CHECK(wearable::rig_tuning_problem(t).find("force_kp") != std::string::npos);
    t = {};
    t.position_kd = std::numeric_limits<double>::infinity();
    CHECK(wearable::rig_tuning_problem(t).find("position_kd") != std::string::npos);
    t = {};
    t.fsr_noise = 0.2;  // N, past kMaxFsrNoise
    CHECK(wearable::rig_tuning_problem(t).find("fsr_noise") != std::string::npos);
}

TEST_CASE("wearable tuning: the editor's parameters write s.wearable, live and not undoable, and keep a refused value out") {
    EditorState s;
    const std::size_t undo = s.doc.undo_depth();
    REQUIRE(set_parameter(s, "wearable_force_kp", 3e-3));
    CHECK(s.wearable.force_kp == 3e-3);
    CHECK(*parameter_value(s, "wearable_force_kp") == 3e-3);
    CHECK(s.doc.undo_depth() == undo);
    CHECK_FALSE(set_parameter(s, "wearable_force_kp", -3e-3));
    CHECK(s.wearable.force_kp == 3e-3);
    CHECK(s.message.find("wearable_force_kp") != std::string::npos);
    REQUIRE(set_parameter(s, "wearable_fit", 0.0));
    CHECK_FALSE(s.wearable.seed_fit);
    REQUIRE(set_parameter(s, "fsr_noise", 0.003));
    CHECK(s.wearable.fsr_noise == 0.003);
    // The roller's feed-forward: default 864.88 V s/m (Kd + back-EMF), live.
    CHECK(*parameter_value(s, "roller_kff") == doctest::Approx(864.88));
    CHECK(*parameter_value(s, "ff_cutoff_hz") == doctest::Approx(20.0));
    REQUIRE(set_parameter(s, "roller_kff", 0.0));
    REQUIRE(set_parameter(s, "ff_cutoff_hz", 35.0));
    CHECK(s.roller.kff == 0.0);
    CHECK(s.roller.ff_cutoff_hz == 35.0);
}

TEST_CASE("plots: the per-column envelope keeps a one-tick spike that one sample per column loses") {
    // 5 s at 1 kHz into 300 columns: 16.7 values per column; one tick of 1.2 N among zeros.
    std::vector<float> v(5000, 0.0f);
    v[2503] = 1.2f;
    const int columns = 300;
    const auto env = column_envelope(v, columns);
    REQUIRE(env.size() == static_cast<std::size_t>(columns));
    float peak = 0.0f;
    int peak_columns = 0;
    for (const ColumnRange& c : env) {
        CHECK_FALSE(c.empty);
        peak = std::max(peak, c.hi);
        peak_columns += c.hi > 0.5f;
    }
    CHECK(peak == doctest::Approx(1.2f));
    CHECK(peak_columns >= 1);
    CHECK(peak_columns <= 2);  // its own column, and the next one's join to it
    // Thinning (one value per column, as ImGui's PlotLines) misses it.
    float thinned = 0.0f;
    for (int c = 0; c < columns; ++c) thinned = std::max(thinned, v[static_cast<std::size_t>(c) * v.size() / columns]);
    CHECK(thinned == 0.0f);
    // The newest value lies in the last column; a NaN is skipped.
    v.back() = -0.5f;
    v[10] = std::nanf("");
    const auto env2 = column_envelope(v, columns);
    CHECK(env2.back().lo == doctest::Approx(-0.5f));
    CHECK(std::isfinite(env2.front().lo));
}

TEST_CASE("plots: y ticks are round and inside the range, two at least") {
    const auto t = nice_ticks(0.0, 1.575, 3);
    REQUIRE(t.size() >= 2);
    CHECK(t.size() <= 3);  // 0 and 1 N
    CHECK(t.front() == doctest::Approx(0.0));
    CHECK(t[1] - t[0] == doctest::Approx(1.0));
    const auto u = nice_ticks(-10.0, 10.0, 3);
    REQUIRE(u.size() == 3);
    CHECK(u[0] == doctest::Approx(-10.0));
    CHECK(u[1] == doctest::Approx(0.0));
    CHECK(u[2] == doctest::Approx(10.0));
    const auto w = nice_ticks(912.0, 1088.0, 3);  // a period plot around 1000 us
    REQUIRE(w.size() >= 2);
    for (double x : w) {
        CHECK(x >= 912.0);
        CHECK(x <= 1088.0);
        CHECK(std::fmod(x, 50.0) == doctest::Approx(0.0));
    }
    float lo = 0.0f, hi = 0.0f;
    value_range({3.0f, 3.0f}, lo, hi);  // a constant trace still gets an axis
    CHECK(hi > lo);
}

TEST_CASE("layout: at 1280x720 the Plots panel holds all six plots and the Haptics panel keeps its minimum") {
    const float row = 19.0f;  // px: Dear ImGui's frame height in the default font
    for (int plots : {5, 6}) {
        CAPTURE(plots);
        const EditorLayout l = editor_layout(1280, 720, row, plots);
        CHECK(l.plots.h == doctest::Approx(plots_panel_height(plots, row)));
        CHECK(l.plots.h >= plots * kLivePlotHeight + kTimeAxisHeight);
        CHECK(l.haptics.h >= kMinHapticsHeight);
        CHECK(l.plots.bottom() <= l.message_row.y);
        CHECK_FALSE(overlaps(l.plots, l.haptics));
        CHECK_FALSE(overlaps(l.tuning, l.haptics));
    }
    // Fewer plots leave the Haptics panel more room.
    CHECK(editor_layout(1280, 720, row, 5).haptics.h > editor_layout(1280, 720, row, 6).haptics.h);
}
