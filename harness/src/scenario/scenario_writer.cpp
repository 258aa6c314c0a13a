// scenario_writer.cpp: the canonical (SI, fully resolved) form of a scenario,
// written from the key definitions (scenario_schema.h): every key written is
// a key the reader accepts, so a manifest loads back into the same Scenario.
#include "harness/scenario/scenario.h"
#include "scenario/json_util.h"
#include "scenario/scenario_schema.h"

namespace harness {

nlohmann::json scenario_to_json(const Scenario& sc) { return schema::write_section(schema::schema(), sc); }

std::string scenario_to_json_text(const Scenario& sc, int indent) { return scenario_to_json(sc).dump(indent); }

}  // namespace harness
