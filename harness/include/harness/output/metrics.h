// metrics: figures computed from a run's recorded rows as they stream, and
// the scenario's requirement lines (monte_carlo.criteria) evaluated on them.
// A Monte Carlo campaign records them for every run (harness/mc/monte_carlo.h);
// a single run evaluates the criteria on its own rows and writes PASS or FAIL
// per line into summary.txt and the report (docs/report.md).
#ifndef HARNESS_OUTPUT_METRICS_H
#define HARNESS_OUTPUT_METRICS_H

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "harness/core/recorder.h"
#include "harness/scenario/mc_column.h"
#include "harness/scenario/scenario.h"

namespace harness {

// A figure computed from each run's recorded rows: `stat` of `column` over
// after <= t <= until (CriterionSpec); a criterion adds a threshold.
struct McMetric {
  McColumn col;             // name, unit, description
  std::string column;       // column, quantity (norm per row) or prefix*
  std::string stat;         // max, min, max_abs, final, mean, rms, error_count, drop
  double after = 0.0;
  double until = -1.0;      // < 0: to the end
  int criterion = -1;       // index into the criteria, -1: a plain metric
  bool below = true;        // criterion: pass when value < threshold (else >)
  double threshold = 0.0;
};

// The columns a metric reads, and whether it takes their norm per row.
struct MetricSelection {
  std::vector<size_t> cols;
  bool norm = false;
};

// column: exact name; a quantity's name (its columns, norm per row); a
// prefix ending in '*'.  Empty when nothing matches.
MetricSelection select_columns(const RecordLayout& l, const std::string& column);
std::string unit_of(const RecordLayout& l, const MetricSelection& s);

// Criterion i of nominal.monte_carlo as a metric (throws ScenarioError when
// its column is not recorded).
McMetric criterion_metric(const Scenario& nominal, const RecordLayout& l, size_t i);
// Every criterion of the scenario (none without a monte_carlo section).
std::vector<McMetric> criterion_metrics(const Scenario& sc, const RecordLayout& l);

// A criterion met by value v (NaN never meets one).
bool criterion_met(const McMetric& m, double v);
// "name: what = v, not below threshold unit" ("" when met).
std::string criterion_failure(const McMetric& m, double v);

// The recorded rows reduced to metrics, streaming (memory bounded for any
// duration).
class MetricSink : public RecordSink {
 public:
  explicit MetricSink(std::vector<McMetric> metrics) : metrics_(std::move(metrics)) {}
  void begin(const RecordLayout& layout, uint64_t expected_rows) override;
  void write(const double* rows, size_t n) override;
  void end(bool) override {}
  const std::vector<McMetric>& specs() const { return metrics_; }
  std::vector<double> values() const;  // NaN: no row in range, or a NaN value

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  // One metric's running figures.
  struct Acc {
    uint64_t n = 0, errors = 0;
    bool nan = false;
    double mx = -kInf, mn = kInf, mxabs = 0.0, sum = 0.0, sum2 = 0.0;
    double first = NAN, last = NAN;  // first / last value (several columns: their maximum)
    double row_max = -kInf;
    void add(double v);
    void end_row(size_t k);  // a row of k separate columns ends
    double value(const std::string& stat) const;
  };
  std::vector<McMetric> metrics_;
  std::vector<MetricSelection> sel_;
  std::vector<Acc> acc_;
  size_t ncols_ = 0;
};

// One requirement line of a single run.
struct RequirementResult {
  std::string name;
  std::string what;    // e.g. "max of pointing_error_deg for t >= 550 s"
  std::string unit;
  bool below = true;   // pass when value < threshold (else >)
  double threshold = 0.0;
  double value = 0.0;  // measured (NaN: not available)
  bool pass = false;
};
std::vector<RequirementResult> requirement_results(const MetricSink& sink);

}  // namespace harness

#endif  // HARNESS_OUTPUT_METRICS_H
