// plots.cpp — bench results -> charts -> PNG files (plots.hpp).
#include "engine/bench/plots.hpp"

#include "engine/bench/anticipation_spread.hpp"

#include "engine/render/chart_image.hpp"
#include "engine/render/context.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>

namespace contactlab::bench {
namespace {

using render::AxisScale;
using render::Chart;
using render::ChartReference;
using render::ChartSeries;
using render::Marker;

Chart base_chart(std::string title, std::string x_title, AxisScale xs, std::string y_title, AxisScale ys) {
    Chart c;
    c.title = std::move(title);
    c.x.title = std::move(x_title);
    c.x.scale = xs;
    c.y.title = std::move(y_title);
    c.y.scale = ys;
    c.width = kPlotWidth;
    c.height = kPlotHeight;
    return c;
}

ChartSeries series(std::string name, int colour, Marker marker, bool dashed = false, float width = 2.0f) {
    ChartSeries s;
    s.name = std::move(name);
    s.color = render::chart_color(colour);
    s.marker = marker;
    s.dashed = dashed;
    s.line_width = width;
    return s;
}

const char* kind_name(SegmentKind k) {
    switch (k) {
    case SegmentKind::lines: return "lines";
    case SegmentKind::arcs: return "arcs";
    case SegmentKind::curves: return "curves";
    }
    return "?";
}

// One colour per segment kind; the method by line and marker: ContactLab solid with discs, brute
// force dashed with squares, point finger thin dashed with triangles.
Chart cost_chart(const BenchResults& r, Growth growth) {
    Chart c = base_chart(growth == Growth::extent ? "Cost growth by extent (5 mm segments, longer contour)"
                                                  : "Cost growth by density (one 0.4 m sinusoid, cut finer)",
                         "segments N", AxisScale::log10, "ns per tick (median)", AxisScale::log10);
    int colour = 0;
    for (const SegmentKind kind : {SegmentKind::lines, SegmentKind::arcs, SegmentKind::curves}) {
        ChartSeries proxy = series(kind_name(kind), colour, Marker::disc);
        ChartSeries brute = series(std::string(kind_name(kind)) + ", brute force", colour, Marker::square, true);
        ChartSeries point = series(std::string(kind_name(kind)) + ", point finger", colour, Marker::triangle, true, 1.5f);
        for (const CostRow& row : r.cost) {
            if (row.scene.kind != kind || row.scene.growth != growth) continue;
            const double n = row.scene.segments;
            proxy.x.push_back(n);
            proxy.y.push_back(row.proxy.median_ns);
            point.x.push_back(n);
            point.y.push_back(row.point_finger.median_ns);
            if (row.brute_force) {
                brute.x.push_back(n);
                brute.y.push_back(row.brute_force->median_ns);
            }
        }
        for (ChartSeries* s : {&proxy, &brute, &point})
            if (!s->x.empty()) c.series.push_back(std::move(*s));
        ++colour;
    }
    return c;
}

// Error (um) against ns per tick; each flatten point labelled with its chord tolerance; exact
// mode is the reference (zero error by definition), a vertical line at its cost.
Chart pareto_chart(const BenchResults& r) {
    Chart c = base_chart("Speed against accuracy: curve modes on seed 002's bumps", "ns per tick (median)",
                         AxisScale::log10, "error against exact mode (um)", AxisScale::log10);
    ChartSeries depth_max = series("depth error, max", 1, Marker::square, true);
    ChartSeries depth_p99 = series("depth error, p99", 0, Marker::disc);
    ChartSeries proxy_p99 = series("proxy error, p99", 2, Marker::triangle);
    for (const ParetoRow& p : r.pareto) {
        if (p.mode == "exact") {
            c.references.push_back({"exact mode (reference)", true, p.stats.median_ns, render::Color{90, 90, 90, 255}});
            continue;
        }
        char label[32];
        std::snprintf(label, sizeof label, "%g um", p.tolerance * 1e6);
        for (ChartSeries* s : {&depth_max, &depth_p99, &proxy_p99}) s->x.push_back(p.stats.median_ns);
        depth_max.y.push_back(p.depth_error_max * 1e6);
        depth_p99.y.push_back(p.depth_error_p99 * 1e6);
        proxy_p99.y.push_back(p.proxy_error_p99 * 1e6);
        depth_p99.labels.push_back(std::string("tol ") + label);
    }
    for (ChartSeries* s : {&depth_p99, &depth_max, &proxy_p99})
        if (!s->x.empty()) c.series.push_back(std::move(*s));
    return c;
}

Chart stability_chart(const BenchResults& r) {
    Chart c = base_chart("Largest stable stiffness against servo rate (simulated arm)", "servo rate (Hz)",
                         AxisScale::log10, "Ke (N/m)", AxisScale::log10);
    ChartSeries bound = series("2b/T, b along the normal", 6, Marker::none, true);
    ChartSeries declared = series("2b/T, b declared (servo's)", 3, Marker::none, true);
    ChartSeries settles = series("settles", 0, Marker::disc);
    ChartSeries no_fault = series("no fault", 1, Marker::square);
    ChartSeries ideal = series("ideal arm, settles", 2, Marker::triangle, true);
    for (const StabilityRow& s : r.stability) {
        for (ChartSeries* x : {&bound, &declared, &settles, &no_fault, &ideal}) x->x.push_back(s.rate_hz);
        bound.y.push_back(s.passivity_bound);
        declared.y.push_back(s.bound_declared);
        settles.y.push_back(s.k_settles);
        no_fault.y.push_back(s.k_no_fault);
        ideal.y.push_back(s.k_ideal_settles);
    }
    if (!r.stability.empty()) c.series = {bound, declared, settles, no_fault, ideal};
    return c;
}

// Z-width (Colgate and Brown's figure): the largest stable K against the virtual damping B, one
// colour per servo rate. Measured (markers): pressed and sliding, stable (no fault and settled),
// and no fault alone (the detectors quiet: where the loop itself is stable). Theory (lines, no
// markers): Colgate and Schenkel's passivity bound 2 (b - |B_a|) / T with b along the normal
// (dashed) and the declared b (thin dashed), and the first-order stability limit 2 (b + B_a) / T
// (thin solid), B_a the damping the servo applies for the scene's B (ZWidthRow::damping_applied).
// On the log K axis a bound is drawn down to kZWidthFloor, where it dives to 0 at |B_a| = b.
constexpr double kZWidthFloor = 100.0;  // N/m

Chart zwidth_chart(const BenchResults& r) {
    Chart c = base_chart("Z-width: largest stable stiffness against virtual damping (simulated arm, 2 mm press)",
                         "virtual damping B, scene force.damping (N s/m)", AxisScale::linear, "K (N/m)",
                         AxisScale::log10);
    c.x.include_zero = true;
    std::vector<double> rates;
    for (const ZWidthRow& z : r.zwidth)
        if (std::find(rates.begin(), rates.end(), z.rate_hz) == rates.end()) rates.push_back(z.rate_hz);
    int colour = 0;
    for (const double rate : rates) {
        char tag[32];
        std::snprintf(tag, sizeof tag, rate >= 1000.0 ? "%g kHz" : "%g Hz", rate >= 1000.0 ? rate / 1000.0 : rate);
        const std::string t = tag;
        ChartSeries press = series(t + " press: stable", colour, Marker::disc);
        ChartSeries slide = series(t + " slide: stable", colour, Marker::square);
        ChartSeries no_fault = series(t + " press: no fault", colour, Marker::triangle, true, 1.5f);
        ChartSeries passive = series(t + " passive: 2(b_n - B_a)/T", colour, Marker::none, true);
        ChartSeries declared = series(t + " passive: 2(b_d - B_a)/T", colour, Marker::none, true, 1.0f);
        ChartSeries stable = series(t + " stable: 2(b_n + B_a)/T", colour, Marker::none, false, 1.0f);
        double b_max = 0.0, applied_per_b = 1.0, b_normal = 0.0, b_declared = 0.0;  // N s/m
        for (const ZWidthRow& z : r.zwidth) {
            if (z.rate_hz != rate) continue;
            // 0: not even the bracket's low end held (drawn nowhere; the table says "<").
            auto add = [&](ChartSeries& s, double k) {
                if (k > 0.0) {
                    s.x.push_back(z.damping);
                    s.y.push_back(k);
                }
            };
            add(press, z.k_press);
            add(slide, z.k_slide);
            add(no_fault, z.k_press_no_fault);
            b_max = std::max(b_max, z.damping);
            if (z.damping > 0.0) applied_per_b = z.damping_applied / z.damping;
            b_normal = z.b_normal;
            b_declared = z.b_declared;
        }
        // The lines, sampled finely (straight in B, curved on the log axis).
        const int n = 200;
        for (int i = 0; i <= n; ++i) {
            const double b = b_max * i / n, ba = std::abs(applied_per_b * b);
            const double k_passive = 2.0 * (b_normal - ba) * rate, k_declared = 2.0 * (b_declared - ba) * rate;
            if (k_passive >= kZWidthFloor) {
                passive.x.push_back(b);
                passive.y.push_back(k_passive);
            }
            if (k_declared >= kZWidthFloor) {
                declared.x.push_back(b);
                declared.y.push_back(k_declared);
            }
            stable.x.push_back(b);
            stable.y.push_back(2.0 * (b_normal + ba) * rate);
        }
        for (ChartSeries* s : {&press, &slide, &no_fault, &passive, &declared, &stable})
            if (!s->x.empty()) c.series.push_back(std::move(*s));
        ++colour;
    }
    return c;
}

// One colour per pole scale and feed-forward: the tracking max (outside the jumps of l_d) solid,
// the max over every tick in contact (jumps included) dashed.
Chart roller_chart(const BenchResults& r) {
    Chart c = base_chart("Roller tracking error against finger speed (seed 000 block task)", "finger speed (mm/s)",
                         AxisScale::linear, "roller error (um)", AxisScale::linear);
    c.x.include_zero = true;
    c.y.include_zero = true;
    std::vector<std::pair<double, bool>> groups;  // (gain scale, feed-forward)
    for (const RollerTrackingRow& t : r.roller)
        if (std::find(groups.begin(), groups.end(), std::pair{t.gain_scale, t.feed_forward}) == groups.end())
            groups.emplace_back(t.gain_scale, t.feed_forward);
    int colour = 0;
    for (const auto& [g, ff] : groups) {
        char name[64];
        std::snprintf(name, sizeof name, "pole x%.2g%s, tracking", g, ff ? "" : " no FF");
        ChartSeries track = series(name, colour, Marker::disc);
        std::snprintf(name, sizeof name, "pole x%.2g%s, all", g, ff ? "" : " no FF");
        ChartSeries all = series(name, colour, Marker::square, true);
        for (const RollerTrackingRow& t : r.roller) {
            if (t.gain_scale != g || t.feed_forward != ff) continue;
            track.x.push_back(t.finger_speed * 1e3);
            track.y.push_back(t.max_tracking_error * 1e6);
            all.x.push_back(t.finger_speed * 1e3);
            all.y.push_back(t.max_error * 1e6);
        }
        c.series.push_back(std::move(track));
        c.series.push_back(std::move(all));
        ++colour;
    }
    return c;
}

Chart render_chart(const BenchResults& r) {
    Chart c = base_chart("Offscreen frame time, 1280x720 (" + r.render.device + ")", "segments N", AxisScale::log10,
                         "ms per frame", AxisScale::log10);
    ChartSeries median = series("median", 0, Marker::disc);
    ChartSeries p99 = series("p99", 1, Marker::square, true);
    for (const RenderFrameRow& row : r.render.rows) {
        median.x.push_back(row.segments);
        median.y.push_back(row.frame.median_ns / 1e6);
        p99.x.push_back(row.segments);
        p99.y.push_back(row.frame.p99_ns / 1e6);
    }
    c.series = {median, p99};
    // What an editor redrawing at 60 Hz can spend on a frame.
    c.references.push_back({"60 Hz frame, 16.7 ms", false, 1000.0 / 60.0, render::Color{90, 90, 90, 255}});
    return c;
}

// The tail against N on the dense contours: p99.9 in contact (solid, discs) and hovering (dashed,
// squares), one colour per kind, against the 10 kHz and 1 kHz periods (unlabelled lines: the data
// rise toward the right, where a line's label would sit; the axis title names them). The maxima
// are in the table beside it.
Chart tail_chart(const BenchResults& r) {
    Chart c = base_chart("The slowest ticks by density (one 0.4 m sinusoid, cut finer)", "segments N", AxisScale::log10,
                         "ns per tick, p99.9 (grey line 100 us: 10 kHz period; red 1 ms: 1 kHz)", AxisScale::log10);
    int colour = 0;
    for (const SegmentKind kind : {SegmentKind::lines, SegmentKind::arcs, SegmentKind::curves}) {
        ChartSeries contact = series(std::string(kind_name(kind)) + ", in contact", colour, Marker::disc);
        ChartSeries hover = series(std::string(kind_name(kind)) + ", hovering", colour, Marker::square, true);
        // The spread anticipation (an option, kBenchAnticipationBudget segments a tick), measured
        // at the largest size only: a lone marker under the exact hover's last point.
        ChartSeries spread = series(std::string(kind_name(kind)) + ", hovering, spread " + std::to_string(kBenchAnticipationBudget),
                                    colour, Marker::diamond);
        spread.connect = false;
        for (const CostRow& row : r.cost) {
            if (row.scene.kind != kind || row.scene.growth != Growth::dense) continue;
            const double n = row.scene.segments;
            contact.x.push_back(n), contact.y.push_back(row.proxy.p999_ns);
            hover.x.push_back(n), hover.y.push_back(row.hover.p999_ns);
            if (row.hover_spread) spread.x.push_back(n), spread.y.push_back(row.hover_spread->p999_ns);
        }
        for (ChartSeries* s : {&contact, &hover, &spread})
            if (!s->x.empty()) c.series.push_back(std::move(*s));
        ++colour;
    }
    c.references.push_back({"", false, kTenKilohertzPeriodNs, render::Color{90, 90, 90, 255}});
    c.references.push_back({"", false, kOneKilohertzPeriodNs, render::Color{170, 40, 40, 255}});
    return c;
}

}  // namespace

std::vector<ReportChart> report_charts(const BenchResults& r) {
    std::vector<ReportChart> charts;
    if (!r.cost.empty()) {
        charts.push_back({"cost_extent.png", cost_chart(r, Growth::extent)});
        charts.push_back({"cost_dense.png", cost_chart(r, Growth::dense)});
        charts.push_back({"tail_dense.png", tail_chart(r)});
    }
    if (!r.pareto.empty()) charts.push_back({"pareto.png", pareto_chart(r)});
    if (!r.stability.empty()) charts.push_back({"stability.png", stability_chart(r)});
    if (!r.zwidth.empty()) charts.push_back({"zwidth.png", zwidth_chart(r)});
    if (!r.roller.empty()) charts.push_back({"roller_tracking.png", roller_chart(r)});
    if (!r.render.rows.empty()) charts.push_back({"render_frame.png", render_chart(r)});
    return charts;
}

const PlotFile* ReportPlots::find(const std::string& file) const {
    for (const PlotFile& f : files)
        if (f.file == file) return &f;
    return nullptr;
}

ReportPlots write_report_plots(const BenchResults& r, const std::string& dir) {
    ReportPlots out;
    const std::vector<ReportChart> charts = report_charts(r);
    try {
        const render::VulkanContext ctx(render::ContextOptions{});
        for (const ReportChart& c : charts) {
            PlotFile f{c.file, c.chart.title, "", 0};
            try {
                f.skipped_points = render::write_chart_png(ctx, c.chart, dir + "/" + c.file).skipped_points;
            } catch (const std::exception& e) {
                f.error = e.what();  // this figure only: the others and the tables still get written
            }
            out.files.push_back(f);
        }
    } catch (const std::exception& e) {
        out.skipped = e.what();  // no Vulkan device: the Markdown says so
        out.files.clear();
    }
    return out;
}

}  // namespace contactlab::bench
