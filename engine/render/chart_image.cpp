// chart_image.cpp — chart -> draw list -> offscreen render -> PNG.
#include "engine/render/chart_image.hpp"

#include "engine/render/offscreen.hpp"

namespace contactlab::render {
namespace {

const Color kPaper{255, 255, 255, 255};  // the chart colours are chosen for white

Image render_chart_with_layout(const VulkanContext& ctx, const Chart& chart, ChartLayout& layout) {
    DrawList list(chart.width, chart.height);
    layout = draw_chart(chart, list);  // throws ChartError before any Vulkan object is made
    OffscreenTarget target(ctx, chart.width, chart.height);
    return target.render(list, kPaper);
}

}  // namespace

Image render_chart(const VulkanContext& ctx, const Chart& chart) {
    ChartLayout layout;
    return render_chart_with_layout(ctx, chart, layout);
}

ChartLayout write_chart_png(const VulkanContext& ctx, const Chart& chart, const std::string& path) {
    ChartLayout layout;
    write_png(path, render_chart_with_layout(ctx, chart, layout));
    return layout;
}

}  // namespace contactlab::render
