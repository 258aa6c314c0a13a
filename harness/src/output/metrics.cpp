// metrics.cpp: metrics of a run's recorded rows and the requirement lines
// (harness/output/metrics.h).
#include "harness/output/metrics.h"

#include <algorithm>

#include "scenario/yaml_reader.h"  // fmt

namespace harness {

MetricSelection select_columns(const RecordLayout& l, const std::string& column)
{
  MetricSelection s;
  if (column.empty()) return s;
  if (column.back() == '*') {
    const std::string pre = column.substr(0, column.size() - 1);
    for (size_t i = 0; i < l.columns.size(); ++i)
      if (l.columns[i].name.compare(0, pre.size(), pre) == 0) s.cols.push_back(i);
    return s;
  }
  for (size_t i = 0; i < l.columns.size(); ++i)
    if (l.columns[i].name == column) {
      s.cols.push_back(i);
      return s;
    }
  for (const QuantityInfo& q : l.quantities)
    if (q.name == column && q.num_cols > 1) {
      for (size_t c = 0; c < q.num_cols; ++c) s.cols.push_back(q.first_col + c);
      s.norm = true;
      return s;
    }
  return s;
}

std::string unit_of(const RecordLayout& l, const MetricSelection& s)
{
  return s.cols.empty() ? "" : l.columns[s.cols.front()].unit;
}

McMetric criterion_metric(const Scenario& nominal, const RecordLayout& l, size_t i)
{
  const CriterionSpec& c = nominal.monte_carlo->criteria[i];
  const MetricSelection s = select_columns(l, c.column);
  if (s.cols.empty()) {
    ScenarioIssue is;
    is.file = nominal.source_file;
    is.line = c.line;
    is.column = c.column_no;
    is.key = "monte_carlo.criteria[" + std::to_string(i) + "].column";
    is.message = "'" + c.column + "' is not recorded by this scenario (a column, a vector quantity or a prefix*; "
                 "see the columns of results.h5 / telemetry.csv)";
    throw ScenarioError({is});
  }
  McMetric m;
  std::string range = c.after > 0.0 ? " for t >= " + fmt(c.after) + " s" : "";
  if (c.until) range += (range.empty() ? " for t <= " : " and t <= ") + fmt(*c.until) + " s";
  m.col = {c.name, c.stat == "error_count" ? "-" : unit_of(l, s), c.stat + " of " + c.column + range};
  m.column = c.column;
  m.stat = c.stat;
  m.after = c.after;
  m.until = c.until ? *c.until : -1.0;
  m.criterion = static_cast<int>(i);
  m.below = c.below.has_value();
  m.threshold = c.below ? *c.below : *c.above;
  return m;
}

std::vector<McMetric> criterion_metrics(const Scenario& sc, const RecordLayout& l)
{
  std::vector<McMetric> out;
  if (!sc.monte_carlo) return out;
  for (size_t i = 0; i < sc.monte_carlo->criteria.size(); ++i) out.push_back(criterion_metric(sc, l, i));
  return out;
}

bool criterion_met(const McMetric& m, double v) { return m.below ? v < m.threshold : v > m.threshold; }

std::string criterion_failure(const McMetric& m, double v)
{
  if (criterion_met(m, v)) return "";
  return m.col.name + ": " + m.col.what + " = " + (std::isnan(v) ? std::string("not available") : fmt(v)) +
         (m.below ? ", not below " : ", not above ") + fmt(m.threshold) +
         (m.col.unit.empty() || m.col.unit == "-" ? "" : " " + m.col.unit);
}

void MetricSink::Acc::add(double v)
{
  if (std::isnan(v)) nan = true;
  ++n;
  mx = std::max(mx, v);
  mn = std::min(mn, v);
  mxabs = std::max(mxabs, std::fabs(v));
  sum += v;
  sum2 += v * v;
  if (v < 0.0) ++errors;
  row_max = std::max(row_max, v);
}

void MetricSink::Acc::end_row(size_t k)
{
  if (k == 0) return;
  if (std::isnan(first)) first = row_max;
  last = row_max;
  row_max = -kInf;
}

double MetricSink::Acc::value(const std::string& stat) const
{
  if (n == 0 || nan) return NAN;
  if (stat == "max") return mx;
  if (stat == "min") return mn;
  if (stat == "max_abs") return mxabs;
  if (stat == "mean") return sum / static_cast<double>(n);
  if (stat == "rms") return std::sqrt(sum2 / static_cast<double>(n));
  if (stat == "error_count") return static_cast<double>(errors);
  if (stat == "final") return last;
  if (stat == "drop") return first - last;
  return NAN;
}

void MetricSink::begin(const RecordLayout& layout, uint64_t)
{
  sel_.clear();
  for (const McMetric& m : metrics_) sel_.push_back(select_columns(layout, m.column));
  acc_.assign(metrics_.size(), Acc{});
  ncols_ = layout.columns.size();
}

void MetricSink::write(const double* rows, size_t n)
{
  for (size_t r = 0; r < n; ++r) {
    const double* x = rows + r * ncols_;
    const double t = x[0];
    for (size_t m = 0; m < metrics_.size(); ++m) {
      const McMetric& mt = metrics_[m];
      if (t < mt.after || (mt.until >= 0.0 && t > mt.until)) continue;
      const MetricSelection& s = sel_[m];
      if (s.norm) {
        double q = 0.0;
        for (size_t c : s.cols) q += x[c] * x[c];
        acc_[m].add(std::sqrt(q));
        acc_[m].end_row(1);
      } else {
        for (size_t c : s.cols) acc_[m].add(x[c]);
        acc_[m].end_row(s.cols.size());
      }
    }
  }
}

std::vector<double> MetricSink::values() const
{
  std::vector<double> out;
  for (size_t m = 0; m < metrics_.size(); ++m) out.push_back(acc_[m].value(metrics_[m].stat));
  return out;
}

std::vector<RequirementResult> requirement_results(const MetricSink& sink)
{
  std::vector<RequirementResult> out;
  const std::vector<double> v = sink.values();
  for (size_t i = 0; i < v.size(); ++i) {
    const McMetric& m = sink.specs()[i];
    if (m.criterion < 0) continue;
    out.push_back({m.col.name, m.col.what, m.col.unit, m.below, m.threshold, v[i], criterion_met(m, v[i])});
  }
  return out;
}

}  // namespace harness
