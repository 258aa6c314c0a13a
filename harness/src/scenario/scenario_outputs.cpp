// scenario_outputs.cpp: `outputs` (which result files a run writes).
#include "scenario/scenario_schema.h"

namespace harness::schema {

const Section& outputs_section()
{
  static const Section s{
      "outputs",
      {
          boolean("hdf5", [](auto& sc, size_t) -> auto& { return sc.outputs.hdf5; }).unit("default true"),
          boolean("csv", [](auto& sc, size_t) -> auto& { return sc.outputs.csv; }).unit("default false"),
          boolean("report_data", [](auto& sc, size_t) -> auto& { return sc.outputs.report_data; }).unit("default true"),
      },
      {}};
  return s;
}

void read_outputs(MapReader r, Scenario& sc)
{
  read_keys(r, outputs_section(), sc);
  r.finish();
}

}  // namespace harness::schema
