// limits.hpp — what an analysis could not do, said once at the top of its report: the rows it
// left out, the values it could not estimate and why (a fit the data do not bound, a test with
// no variance, a track that did not converge), and what a test cannot show with this many
// participants. Collected from the analysis JSON (analysis.hpp, threshold_analysis.hpp) after
// every part has run, so that each part keeps its reasons beside its own values and this list
// only gathers them: result["limits"], an array of sentences.
#pragma once

#include <nlohmann/json_fwd.hpp>

namespace contactlab::experiments {

void add_limits(nlohmann::json& result);

}  // namespace contactlab::experiments
