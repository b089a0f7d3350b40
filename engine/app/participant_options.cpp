// participant_options.cpp — --participant / --participants read into participant numbers
// (participant_options.hpp).
#include "engine/app/participant_options.hpp"

#include "engine/app/number_options.hpp"
#include "engine/app/subcommands.hpp"
#include "engine/experiments/base/results_table.hpp"

namespace contactlab::app {

std::vector<std::uint64_t> sim_participants(const std::string& given_spec, const char* option,
                                            std::optional<experiments::ObserverSpec>* observer) {
    std::string spec = given_spec;
    if (spec.rfind("observer:", 0) == 0 && observer) {
        std::string rest = spec.substr(9), numbers = "sim";
        // A trailing ":N" or ":A-B" numbers the observers; the observer's own spec has no ':' after its function.
        if (const std::size_t last = rest.rfind(':'); last != std::string::npos && last != rest.find(':') &&
                                                      rest.find_first_not_of("0123456789-", last + 1) == std::string::npos) {
            numbers = "sim:" + rest.substr(last + 1);
            rest = rest.substr(0, last);
        }
        try {
            *observer = experiments::parse_observer(rest);
        } catch (const experiments::ExperimentError& e) {
            throw BadInput(std::string(option) + ": " + e.what());
        }
        spec = numbers;
    }
    if (spec == "sim") return {1};
    if (spec.rfind("sim:", 0) != 0)
        throw BadInput(std::string(option) + ": \"" + spec +
                       "\": a person takes part in the editor's experiment mode (contactlab edit --experiment PROTOCOL "
                       "--participant " + spec + "); headless runs take simulated participants (sim, sim:N or sim:A-B) or model "
                       "observers (observer:logistic:threshold=T,scale=S[,guess=G,lapse=L][:A-B])");
    // N or A-B, each a whole number from 1 to kMaxParticipant (read by whole_number: never wrapped
    // or saturated, "sim:-3" is not participant 18446744073709551613), A <= B.
    const std::string range = spec.substr(4);
    const std::size_t dash = range.find('-');
    const std::string rule = std::string(option) + ": expected sim:N or sim:A-B with whole numbers 1 <= A <= B <= " +
                             std::to_string(kMaxParticipant) + " (at most " + std::to_string(kMaxParticipant) +
                             " participants in a run), got " + app::given(given_spec);
    std::uint64_t a = 0, b = 0;
    try {
        a = whole_number(range.substr(0, dash), option, 1, kMaxParticipant);
        b = dash == std::string::npos ? a : whole_number(range.substr(dash + 1), option, 1, kMaxParticipant);
    } catch (const BadInput&) {
        throw BadInput(rule);
    }
    if (b < a) throw BadInput(rule);
    std::vector<std::uint64_t> out;
    for (std::uint64_t i = a; i <= b; ++i) out.push_back(i);
    return out;
}

}  // namespace contactlab::app
