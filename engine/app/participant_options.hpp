// participant_options.hpp — the one reader of --participant / --participants (sim, sim:N, sim:A-B,
// observer:...), shared by `experiment run` and `experiment slurm`, so that a range a cluster job
// splits is read exactly as the run that will take each part reads it.
#pragma once

#include "engine/experiments/participants/model_observer.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace contactlab::app {

// Participant numbers run from 1 to this: a run takes at most this many (the limit was once on B - A
// alone, so "sim:99999999999999999999-99999999999999999999" saturated to one participant and passed).
inline constexpr std::uint64_t kMaxParticipant = 10000;

// "sim" -> {1}; "sim:3" -> {3}; "sim:1-20" -> {1..20}; "observer:FN:KEY=V,...[:N|:A-B]" ->
// model observers (the observer's spec into `observer`; with observer null, such a spec is
// refused as any other non-sim one), numbered the same way. BadInput (exit 2) naming `option`.
std::vector<std::uint64_t> sim_participants(const std::string& given_spec, const char* option,
                                            std::optional<experiments::ObserverSpec>* observer = nullptr);

}  // namespace contactlab::app
