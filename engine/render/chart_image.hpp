// chart_image.hpp — a chart (chart.hpp) rendered offscreen with Vulkan, through the same path as
// every frame (draw list -> OffscreenTarget), and written as a PNG (image.hpp, libstb).
#pragma once

#include "engine/render/chart.hpp"
#include "engine/render/context.hpp"
#include "engine/render/image.hpp"

#include <string>

namespace contactlab::render {

// The chart's pixels on a white background. Throws ChartError for charts layout_chart rejects,
// VulkanError when rendering fails.
Image render_chart(const VulkanContext& ctx, const Chart& chart);

// render_chart, then write_png to `path` (atomically). Returns the layout (skipped points etc.).
ChartLayout write_chart_png(const VulkanContext& ctx, const Chart& chart, const std::string& path);

}  // namespace contactlab::render
