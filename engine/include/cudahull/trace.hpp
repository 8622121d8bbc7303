// JSON forms of the engine's records: `cudahull hull --trace` (one line per iteration) and `--stats`.
#pragma once

#include <nlohmann/json.hpp>

#include "cudahull/engine.hpp"

namespace cudahull {

// The whole IterationRecord, with the decision array and every swap (rejected ones with their reasons).
nlohmann::json iteration_to_json(const IterationRecord& record);

}  // namespace cudahull
