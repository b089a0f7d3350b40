// test_chart.cpp — report charts (engine/render/chart.hpp): the data -> pixel formula of linear
// and log axes, ranges and ticks, bad data skipped or rejected with a message, and the rendered
// PNG showing each series' colour where its data points must land.
#include "render_fixture.hpp"

#include "engine/render/chart.hpp"
#include "engine/render/chart_image.hpp"
#include "engine/render/matrix_chart.hpp"
#include "engine/render/offscreen.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <limits>

using namespace render_test;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Pixel positions are floats (DrawList vertices): exact to float rounding, ~1e-4 px at 1000 px.
constexpr double kPxTol = 1e-3;

Chart explicit_chart(AxisScale xs, double x0, double x1, AxisScale ys, double y0, double y1) {
    Chart c;
    c.title = "test";
    c.x.title = "x (m)";
    c.x.scale = xs;
    c.x.min = x0;
    c.x.max = x1;
    c.y.title = "y (N)";
    c.y.scale = ys;
    c.y.min = y0;
    c.y.max = y1;
    c.width = 640;
    c.height = 400;
    return c;
}

// Some pixel within `radius` px of p has exactly the colour's RGB.
bool color_near(const Image& img, P2 p, Color c, int radius) {
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            const int x = static_cast<int>(std::floor(p.x)) + dx, y = static_cast<int>(std::floor(p.y)) + dy;
            if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
            const uint8_t* q = img.pixel(x, y);
            if (q[0] == c.r && q[1] == c.g && q[2] == c.b) return true;
        }
    return false;
}

ChartSeries series(std::string name, std::vector<double> x, std::vector<double> y, Color color,
                   Marker marker = Marker::disc) {
    ChartSeries s;
    s.name = std::move(name);
    s.x = std::move(x);
    s.y = std::move(y);
    s.color = color;
    s.marker = marker;
    return s;
}

P2 at(const ChartLayout& l, double x, double y) {
    return P2(static_cast<float>(l.x.to_px(x)), static_cast<float>(l.y.to_px(y)));
}

}  // namespace

TEST_CASE("chart: linear axes map data to pixels by the axis formula, y growing upwards") {
    const Chart c = explicit_chart(AxisScale::linear, 0.0, 10.0, AxisScale::linear, -50.0, 150.0);
    const ChartLayout l = layout_chart(c);
    const double w = l.plot_hi.x - l.plot_lo.x, h = l.plot_hi.y - l.plot_lo.y;
    REQUIRE(w > 100.0);
    REQUIRE(h > 100.0);
    // x: px = left + (x - 0) / 10 * w; y: px = bottom - (y + 50) / 200 * h.
    CHECK(std::abs(l.x.to_px(0.0) - l.plot_lo.x) < kPxTol);
    CHECK(std::abs(l.x.to_px(2.5) - (l.plot_lo.x + 0.25 * w)) < kPxTol);
    CHECK(std::abs(l.x.to_px(10.0) - l.plot_hi.x) < kPxTol);
    CHECK(std::abs(l.y.to_px(-50.0) - l.plot_hi.y) < kPxTol);
    CHECK(std::abs(l.y.to_px(0.0) - (l.plot_hi.y - 0.25 * h)) < kPxTol);
    CHECK(std::abs(l.y.to_px(150.0) - l.plot_lo.y) < kPxTol);
    // Beyond the range the formula extrapolates (the drawing clips).
    CHECK(std::abs(l.x.to_px(20.0) - (l.plot_lo.x + 2.0 * w)) < kPxTol);
}

TEST_CASE("chart: log10 axes map each decade to an equal pixel span") {
    const Chart c = explicit_chart(AxisScale::log10, 1.0, 1e5, AxisScale::log10, 1e-6, 1e-2);
    const ChartLayout l = layout_chart(c);
    const double w = l.plot_hi.x - l.plot_lo.x, h = l.plot_hi.y - l.plot_lo.y;
    // x: 5 decades; 100 is 2/5 of the way. y: 4 decades; 1e-4 is half way up.
    CHECK(std::abs(l.x.to_px(100.0) - (l.plot_lo.x + 0.4 * w)) < kPxTol);
    CHECK(std::abs(l.x.to_px(1e5) - l.plot_hi.x) < kPxTol);
    CHECK(std::abs(l.y.to_px(1e-4) - (l.plot_hi.y - 0.5 * h)) < kPxTol);
    // Between decades: log10(3) of a decade's span.
    CHECK(std::abs(l.x.to_px(3.0) - (l.plot_lo.x + std::log10(3.0) / 5.0 * w)) < kPxTol);
    CHECK(l.x.accepts(1e-300));
    CHECK_FALSE(l.x.accepts(0.0));
    CHECK_FALSE(l.x.accepts(-1.0));
    CHECK_FALSE(l.x.accepts(kNaN));
}

TEST_CASE("chart: ranges from the data widen to whole decades (log) and tick steps (linear)") {
    Chart c;
    c.title = "auto";
    c.x.scale = AxisScale::log10;
    c.y.scale = AxisScale::linear;
    c.series.push_back(series("s", {3.0, 40.0, 4500.0}, {0.3, 8.7, 2.0}, chart_color(0)));
    const ChartLayout l = layout_chart(c);
    CHECK(l.x.lo == doctest::Approx(1.0));
    CHECK(l.x.hi == doctest::Approx(1e4));
    // Span 8.4: step 1 (at most 10 intervals of 1/2/5 x 10^k), so [0, 9].
    CHECK(l.y.lo == doctest::Approx(0.0));
    CHECK(l.y.hi == doctest::Approx(9.0));
    CHECK(l.skipped_points == 0);

    c.y.include_zero = true;
    c.series[0].y = {5.0, 7.0, 6.0};
    CHECK(layout_chart(c).y.lo == doctest::Approx(0.0));
}

TEST_CASE("chart: a reference line that would lie on the frame's edge gets room beyond it") {
    // The bench's tail chart: p99.9 from 3 us to 90 us and the 1 ms line, a whole decade, which
    // the range out to whole decades put on the top edge, where it reads as the frame.
    Chart c;
    c.title = "edge";
    c.x.scale = AxisScale::log10;
    c.y.scale = AxisScale::log10;
    c.series.push_back(series("s", {10.0, 1e5}, {3e3, 9e4}, chart_color(0)));
    c.references.push_back({"", false, 1e5});
    c.references.push_back({"", false, 1e6});
    ChartLayout l = layout_chart(c);
    CHECK(l.y.lo == doctest::Approx(1e3));  // from the data, no reference there
    CHECK(l.y.hi == doctest::Approx(2e6));  // the next minor tick beyond 1e6
    CHECK(l.y.to_px(1e6) > l.y.to_px(l.y.hi) + 20.0);  // well inside the frame (pixel y grows downwards)
    // Linear: a reference on the last tick step gets one step more; one inside the range changes nothing.
    c.y.scale = AxisScale::linear;
    c.series[0].y = {1.0, 8.7};
    c.references = {{"", false, 9.0}};
    l = layout_chart(c);
    CHECK(l.y.hi == doctest::Approx(10.0));
    c.references = {{"", false, 5.0}};
    CHECK(layout_chart(c).y.hi == doctest::Approx(9.0));
    // An explicit limit is kept as asked.
    c.references = {{"", false, 9.0}};
    c.y.max = 9.0;
    CHECK(layout_chart(c).y.hi == doctest::Approx(9.0));
}

TEST_CASE("chart: ticks and their labels") {
    const auto lin = axis_ticks(AxisMap{AxisScale::linear, 0.0, 9.0, 0.0, 1.0});
    REQUIRE(lin.size() == 10);
    CHECK(lin.front().value == 0.0);
    CHECK(lin.back().value == doctest::Approx(9.0));
    CHECK(lin[3].label == "3");
    // [1, 1000] on a log axis: 4 labelled decades and minor ticks 2..9 in the three between.
    const auto lg = axis_ticks(AxisMap{AxisScale::log10, 1.0, 1000.0, 0.0, 1.0});
    CHECK(lg.size() == 4 + 3 * 8);
    int labelled = 0;
    for (const ChartTick& t : lg) labelled += t.label.empty() ? 0 : 1;
    CHECK(labelled == 4);
    // Within one decade, 2 and 5 x 10^k are labelled too: 10, 20, 50, 100.
    std::vector<std::string> one_decade;
    for (const ChartTick& t : axis_ticks(AxisMap{AxisScale::log10, 10.0, 100.0, 0.0, 1.0}))
        if (!t.label.empty()) one_decade.push_back(t.label);
    CHECK(one_decade == std::vector<std::string>{"10", "20", "50", "100"});
    CHECK(tick_label(0.0) == "0");
    CHECK(tick_label(0.5) == "0.5");
    CHECK(tick_label(200.0) == "200");
    CHECK(tick_label(1e4) == "1e4");
    CHECK(tick_label(20000.0) == "20000");
    CHECK(tick_label(1e5) == "1e5");
    CHECK(tick_label(1e-6) == "1e-6");
    CHECK(tick_label(-1e5) == "-1e5");
}

TEST_CASE("chart: non-finite points and non-positive points on a log axis are skipped and counted") {
    Chart c;
    c.title = "bad data";
    c.x.scale = AxisScale::log10;
    c.y.scale = AxisScale::log10;
    c.series.push_back(series("s", {10.0, kNaN, 100.0, -1.0, 1000.0, 0.0}, {1.0, 2.0, kInf, 5.0, 10.0, 3.0}, chart_color(0)));
    ChartLayout l;
    REQUIRE_NOTHROW(l = layout_chart(c));
    CHECK(l.skipped_points == 4);
    // The range comes from the drawable points (10, 1) and (1000, 10) only.
    CHECK(l.x.lo == doctest::Approx(10.0));
    CHECK(l.x.hi == doctest::Approx(1000.0));
    DrawList list(c.width, c.height);
    CHECK_NOTHROW(draw_chart(c, list));
}

TEST_CASE("chart: a chart with no drawable data or an impossible range is rejected with a message") {
    Chart empty;
    empty.title = "nothing";
    CHECK_THROWS_WITH_AS(layout_chart(empty), doctest::Contains("chart \"nothing\", x axis: no drawable point"), ChartError);

    Chart all_bad;
    all_bad.title = "all bad";
    all_bad.y.scale = AxisScale::log10;
    all_bad.series.push_back(series("s", {1.0, 2.0}, {0.0, -3.0}, chart_color(0)));
    CHECK_THROWS_WITH_AS(layout_chart(all_bad), doctest::Contains("positive on a log scale"), ChartError);

    Chart ragged = explicit_chart(AxisScale::linear, 0, 1, AxisScale::linear, 0, 1);
    ragged.series.push_back(series("r", {1.0, 2.0}, {1.0}, chart_color(0)));
    CHECK_THROWS_WITH_AS(layout_chart(ragged), doctest::Contains("x and y differ in length"), ChartError);

    CHECK_THROWS_AS(layout_chart(explicit_chart(AxisScale::linear, 1, 1, AxisScale::linear, 0, 1)), ChartError);
    CHECK_THROWS_WITH_AS(layout_chart(explicit_chart(AxisScale::log10, 0, 10, AxisScale::linear, 0, 1)),
                         doctest::Contains("positive limits"), ChartError);
    Chart tiny = explicit_chart(AxisScale::linear, 0, 1, AxisScale::linear, 0, 1);
    tiny.width = 60;
    CHECK_THROWS_WITH_AS(layout_chart(tiny), doctest::Contains("no room for the plot"), ChartError);
}

TEST_CASE("chart: the rendered PNG has each series' colour where its data points land") {
    Chart c = explicit_chart(AxisScale::log10, 1.0, 1e4, AxisScale::linear, 0.0, 10.0);
    const Color blue = chart_color(0), red = chart_color(1);
    // A NaN between (10, 2) and (1000, 4) breaks the line: nothing blue half-way between them.
    c.series.push_back(series("blue", {10.0, kNaN, 1000.0}, {2.0, 5.0, 4.0}, blue, Marker::disc));
    c.series.push_back(series("red", {3.0, 300.0}, {8.0, 7.0}, red, Marker::square));
    c.references.push_back({"bound", false, 6.0, Color{90, 90, 90, 255}});
    const Image img = render_chart(lavapipe(), c);
    REQUIRE(img.width == c.width);
    REQUIRE(img.height == c.height);
    const ChartLayout l = layout_chart(c);
    // Markers are 4.5 px in radius and opaque inside: the exact colour within 1 px of the point.
    CHECK(color_near(img, at(l, 10.0, 2.0), blue, 1));
    CHECK(color_near(img, at(l, 1000.0, 4.0), blue, 1));
    CHECK(color_near(img, at(l, 3.0, 8.0), red, 1));
    CHECK(color_near(img, at(l, 300.0, 7.0), red, 1));
    // On the red line half-way (in log x) between its points: 2 px wide, so within 1 px.
    CHECK(color_near(img, at(l, 30.0, 7.5), red, 1));
    CHECK_FALSE(color_near(img, at(l, 100.0, 3.0), blue, 3));
    // The dashed reference at y = 6 (2 px wide, 9 px dashes, 5 px gaps): its colour within 7 px along it.
    bool ref_seen = false;
    for (int dx = -7; dx <= 7 && !ref_seen; ++dx)
        ref_seen = color_near(img, at(l, 100.0, 6.0) + P2(static_cast<float>(dx), 0.f), Color{90, 90, 90, 255}, 0);
    CHECK(ref_seen);
    // Paper elsewhere: a point in the plot far from every line, marker and grid line (1000, 2000; 0, 1).
    const uint8_t* paper = img.pixel(static_cast<int>(l.x.to_px(1500.0)), static_cast<int>(l.y.to_px(0.7)));
    CHECK(paper[0] == 255);
    CHECK(paper[1] == 255);
    CHECK(paper[2] == 255);
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("chart: a categorical axis puts category i at i, one labelled tick each, in [-0.5, n - 0.5]") {
    Chart c = explicit_chart(AxisScale::linear, 0.0, 1.0, AxisScale::linear, 0.0, 1.0);
    c.x = ChartAxis{};
    c.x.title = "bumps";
    c.x.categories = {"0", "1", "2", "3", "4"};
    c.series.push_back(series("s", {0.0, 4.0}, {0.5, 0.5}, chart_color(0)));
    const ChartLayout l = layout_chart(c);
    CHECK(l.x.lo == -0.5);
    CHECK(l.x.hi == 4.5);
    const auto ticks = axis_ticks(c.x, l.x);
    REQUIRE(ticks.size() == 5);
    for (std::size_t i = 0; i < ticks.size(); ++i) {
        CHECK(ticks[i].value == static_cast<double>(i));
        CHECK(ticks[i].label == c.x.categories[i]);
    }
    // Category slots are equal: the centres are (plot width) / 5 apart.
    CHECK(l.x.to_px(1.0) - l.x.to_px(0.0) == doctest::Approx((l.plot_hi.x - l.plot_lo.x) / 5.0).epsilon(1e-6));
    c.x.scale = AxisScale::log10;
    CHECK_THROWS_AS(layout_chart(c), ChartError);
}

TEST_CASE("chart: error bars widen the range and are drawn, unconnected series draw no line between points") {
    Chart c = explicit_chart(AxisScale::linear, 0.0, 1.0, AxisScale::linear, 0.0, 1.0);
    c.y = ChartAxis{};  // from the data
    c.y.title = "proportion";
    c.x = ChartAxis{};
    c.x.title = "condition";
    c.x.categories = {"a", "b"};
    ChartSeries s = series("p", {0.0, 1.0}, {0.5, 0.6}, chart_color(1));
    s.y_low = {0.2, kNaN};  // the second point has no bar
    s.y_high = {0.9, kNaN};
    s.connect = false;
    c.series.push_back(s);
    const ChartLayout l = layout_chart(c);
    CHECK(l.y.lo <= 0.2 + 1e-12);  // the range ends on a tick step: 0.2 itself, to rounding
    CHECK(l.y.hi >= 0.9 - 1e-12);
    // Drawn inside a wider range (at the range's ends the plot's frame covers the caps).
    c.y.min = 0.0;
    c.y.max = 1.0;
    const ChartLayout drawn = layout_chart(c);
    const Image img = render_chart(lavapipe(), c);
    // The bar: the series' colour on the vertical through x = 0, between its ends, and its caps.
    CHECK(color_near(img, at(drawn, 0.0, 0.3), chart_color(1), 1));
    CHECK(color_near(img, at(drawn, 0.0, 0.8), chart_color(1), 1));
    CHECK(color_near(img, at(drawn, 0.0, 0.9) + P2(4.f, 0.f), chart_color(1), 1));
    CHECK(color_near(img, at(drawn, 0.0, 0.2) - P2(4.f, 0.f), chart_color(1), 1));
    CHECK_FALSE(color_near(img, at(drawn, 0.0, 0.95), chart_color(1), 1));
    // No bar at the second point (beyond its marker), and no line between the points.
    CHECK_FALSE(color_near(img, at(drawn, 1.0, 0.8), chart_color(1), 2));
    CHECK_FALSE(color_near(img, at(drawn, 0.5, 0.55), chart_color(1), 2));
    // Mismatched bars are refused.
    c.series[0].y_high.pop_back();
    CHECK_THROWS_AS(layout_chart(c), ChartError);
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("chart: write_chart_png writes the rendered pixels, which read back at the chart's size") {
    Chart c = explicit_chart(AxisScale::linear, 0.0, 1.0, AxisScale::linear, 0.0, 1.0);
    c.series.push_back(series("s", {0.2, 0.8}, {0.2, 0.8}, chart_color(2)));
    const fs::path path = fs::temp_directory_path() / "contactlab_test_chart.png";
    write_chart_png(lavapipe(), c, path.string());
    const Image back = read_png(path.string());
    fs::remove(path);
    CHECK(back.width == c.width);
    CHECK(back.height == c.height);
    CHECK(back.rgba == render_chart(lavapipe(), c).rgba);
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("chart: dashed lines end whatever their length and where the dash pattern stands") {
    // A dash whose remaining length is below float resolution at the segment's position used to
    // stop the pattern advancing (an endless loop in a `contactlab bench` full run's stability
    // plot). Thousands of dashed polylines through random points of a log-log plot, including
    // the full run's bound line, must all be drawn, and draw something.
    Chart c = explicit_chart(AxisScale::log10, 10.0, 1e5, AxisScale::log10, 10.0, 1e6);
    ChartSeries bound = series("2b/T declared", {100, 250, 1000, 4000, 10000, 20000},
                               {229.36184798097, 573.40461995244, 2293.6184798097, 9174.4739192389,
                                22936.184798097, 45872.369596195},
                               Color{0, 0, 0, 255}, Marker::none);
    bound.dashed = true;
    c.series.push_back(bound);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> ex(1.0, 5.0), ey(1.0, 6.0);
    for (int k = 0; k < 200; ++k) {
        ChartSeries s = series("random " + std::to_string(k), {}, {}, Color{200, 0, 0, 255}, Marker::none);
        s.dashed = true;
        for (int i = 0; i < 12; ++i) {
            s.x.push_back(std::pow(10.0, ex(rng)));
            s.y.push_back(std::pow(10.0, ey(rng)));
        }
        c.series.push_back(s);
    }
    DrawList out(c.width, c.height);
    draw_chart(c, out);
    CHECK(out.vertices().size() > 1000);
}

TEST_CASE("matrix chart: each cell is shaded by its share of the row, counts and labels drawn") {
    MatrixChart m;
    m.title = "Confusion: table I";
    m.rows = {"45", "135"};
    m.columns = {"A", "B"};
    m.counts = {{41, 9}, {3, 47}};
    const Image img = [&] {
        const P2 size = matrix_chart_size(m);
        DrawList list(static_cast<int>(size.x), static_cast<int>(size.y));
        draw_matrix_chart(m, list);
        OffscreenTarget target(lavapipe(), static_cast<int>(size.x), static_cast<int>(size.y));
        return target.render(list, Color{255, 255, 255, 255});
    }();
    // Darkness (255 - red) near each cell's corner (clear of its number): ordered as the shares
    // 41/50 > 47/50 ... i.e. cell (1, 1) 0.94 darkest, then (0, 0) 0.82, then (0, 1) 0.18, then (1, 0) 0.06.
    const P2 size = matrix_chart_size(m);
    const float cell = static_cast<float>(m.cell);
    const float x0 = size.x - 16.0f - 2.0f * cell, y0 = size.y - 16.0f - 2.0f * cell;  // the cells' top-left
    auto dark = [&](int r, int c) { return 255 - img.pixel(static_cast<int>(x0 + cell * c + 4), static_cast<int>(y0 + cell * r + 4))[0]; };
    CHECK(dark(1, 1) > dark(0, 0));
    CHECK(dark(0, 0) > dark(0, 1));
    CHECK(dark(0, 1) > dark(1, 0));
    CHECK(dark(1, 0) > 0);
    // Shade share * 225: 0.94 -> 211.5 of 255 - red.
    CHECK(std::abs(dark(1, 1) - 211) <= 2);
    m.counts.pop_back();
    DrawList bad(10, 10);
    CHECK_THROWS_AS(draw_matrix_chart(m, bad), ChartError);
    CHECK(lavapipe().validation_messages() == 0);
}

TEST_CASE("chart: labels never sit on each other or on the data, and those with no room are counted") {
    // The figure: every bin in one pixel column at the right of a wide axis, a label
    // per bin, and two labelled reference lines close together near the plot's right edge.
    Chart c;
    c.title = "crowded";
    c.x.title = "stimulus (mm)";
    c.y.title = "proportion correct";
    c.x.min = -8000.0, c.x.max = 1000.0;
    c.y.min = 0.0, c.y.max = 1.0;
    ChartSeries s;
    s.name = "data (bins)";
    s.connect = false;
    for (int i = 0; i < 9; ++i) {
        s.x.push_back(0.25 + i);
        s.y.push_back(0.5 + 0.05 * i);
        s.y_low.push_back(0.4 + 0.05 * i);
        s.y_high.push_back(0.6 + 0.05 * i);
        s.labels.push_back("n=" + std::to_string(10 * i + 3));
    }
    c.series.push_back(s);
    c.references.push_back({"threshold 1.03", true, 1.03});
    c.references.push_back({"95 % interval", true, 3.17});
    DrawList out(c.width, c.height);
    const ChartLayout l = draw_chart(c, out);
    REQUIRE(l.mark_boxes.size() >= 9);
    for (std::size_t i = 0; i < l.text_boxes.size(); ++i) {
        for (std::size_t j = i + 1; j < l.text_boxes.size(); ++j) {
            INFO("text ", i, " (", l.text_boxes[i].lo.x, ", ", l.text_boxes[i].lo.y, ")-(", l.text_boxes[i].hi.x, ", ", l.text_boxes[i].hi.y,
                 ") and text ", j, " (", l.text_boxes[j].lo.x, ", ", l.text_boxes[j].lo.y, ")-(", l.text_boxes[j].hi.x, ", ",
                 l.text_boxes[j].hi.y, ")");
            CHECK_FALSE(l.text_boxes[i].intersects(l.text_boxes[j]));
        }
        for (const ChartBox& m : l.mark_boxes) CHECK_FALSE(l.text_boxes[i].intersects(m));
    }
    // Nine labels and two reference labels cannot all fit beside one column of bars: some are
    // left out, and they are counted so the caption can give their values.
    int in_plot = 0;  // glyphs inside the plot: the placed labels' only
    for (const ChartBox& b : l.text_boxes)
        in_plot += b.lo.x >= l.plot_lo.x && b.lo.y >= l.plot_lo.y && b.hi.x <= l.plot_hi.x && b.hi.y <= l.plot_hi.y;
    CHECK(l.dropped_labels > 0);
    CHECK(l.placed_labels >= 1);  // beside the column of bars, a pixel clear of their caps
    CHECK(in_plot >= 3 * l.placed_labels);  // each label has at least 3 glyphs ("n=3")
    CHECK(l.placed_labels + l.dropped_labels == 11);
}
