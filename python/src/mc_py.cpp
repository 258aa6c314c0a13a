// kestrel.monte_carlo: make_mc_plan + run_mc_runs (+ write_mc_outputs).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <system_error>

#include "common.h"
#include "harness/mc/monte_carlo.h"
#include "harness/mc/mc_journal.h"
#include "harness/output/results_dir.h"
#include "scenario/scenario_limits.h"  // kMaxMcRuns

namespace kpy {

namespace fs = std::filesystem;

namespace {

// A campaign's outcome.  Without out_dir the runs' folders live in a
// temporary folder removed with this object (retained runs readable until then).
struct McResults {
  harness::McPlan plan;
  std::vector<harness::McRecord> records;
  fs::path dir;        // the campaign folder (out_dir or the temporary one)
  bool temporary = false;
  bool stopped = false;
  double wall_seconds = 0.0;
  ~McResults()
  {
    if (temporary && !dir.empty()) {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  }
};

py::array_t<double> table(const std::vector<harness::McRecord>& recs, bool drawn, size_t ncols)
{
  py::array_t<double> a({static_cast<py::ssize_t>(recs.size()), static_cast<py::ssize_t>(ncols)});
  double* p = a.mutable_data();
  for (size_t i = 0; i < recs.size(); ++i) {
    const std::vector<double>& v = drawn ? recs[i].drawn : recs[i].metrics;
    for (size_t j = 0; j < ncols; ++j) p[i * ncols + j] = j < v.size() ? v[j] : std::nan("");
  }
  return a;
}

// one value per record, as a NumPy array
template <class T, class F>
py::array_t<T> per_run(const std::vector<harness::McRecord>& recs, F f)
{
  py::array_t<T> a(static_cast<py::ssize_t>(recs.size()));
  for (size_t i = 0; i < recs.size(); ++i) a.mutable_at(i) = f(recs[i]);
  return a;
}

std::vector<std::string> names(const std::vector<harness::McColumn>& c)
{
  std::vector<std::string> v;
  for (const auto& x : c) v.push_back(x.name);
  return v;
}

}  // namespace

void bind_mc(py::module_& m)
{
  py::class_<McResults, std::shared_ptr<McResults>>(m, "MonteCarlo",
                                                    "A Monte Carlo campaign's records as NumPy arrays (one row per run, "
                                                    "by index)")
      .def_property_readonly("runs", [](const McResults& r) { return r.records.size(); })
      .def_property_readonly("master_seed", [](const McResults& r) { return r.plan.master_seed; })
      .def_property_readonly("index", [](const McResults& r) { return per_run<uint64_t>(r.records, [](const harness::McRecord& x) { return x.index; }); })
      .def_property_readonly("seed", [](const McResults& r) { return per_run<uint64_t>(r.records, [](const harness::McRecord& x) { return x.seed; }); },
                             "each run's Scenario seed")
      .def_property_readonly("passed", [](const McResults& r) { return per_run<bool>(r.records, [](const harness::McRecord& x) { return x.pass; }); },
                             "pass: complete, valid and every criterion met")
      .def_property_readonly("complete", [](const McResults& r) { return per_run<bool>(r.records, [](const harness::McRecord& x) { return x.complete; }); })
      .def_property_readonly("invalid", [](const McResults& r) { return per_run<bool>(r.records, [](const harness::McRecord& x) { return x.invalid; }); })
      .def_property_readonly("reason",
                             [](const McResults& r) {
                               std::vector<std::string> v;
                               for (const auto& x : r.records) v.push_back(x.reason);
                               return v;
                             })
      .def_property_readonly("drawn", [](const McResults& r) { return table(r.records, true, r.plan.drawn.size()); },
                             "(runs, drawn columns) the drawn values (NaN: not drawn)")
      .def_property_readonly("drawn_names", [](const McResults& r) { return names(r.plan.drawn); })
      .def_property_readonly("drawn_units",
                             [](const McResults& r) {
                               std::vector<std::string> v;
                               for (const auto& x : r.plan.drawn) v.push_back(x.unit);
                               return v;
                             })
      .def_property_readonly("metrics",
                             [](const McResults& r) { return table(r.records, false, r.plan.metrics.size()); },
                             "(runs, metrics) each run's figures (NaN: not computed)")
      .def_property_readonly("metric_names",
                             [](const McResults& r) {
                               std::vector<std::string> v;
                               for (const auto& x : r.plan.metrics) v.push_back(x.col.name);
                               return v;
                             })
      .def_property_readonly("metric_units",
                             [](const McResults& r) {
                               std::vector<std::string> v;
                               for (const auto& x : r.plan.metrics) v.push_back(x.col.unit);
                               return v;
                             })
      .def(
          "metric",
          [](const McResults& r, const std::string& name) {
            for (size_t j = 0; j < r.plan.metrics.size(); ++j)
              if (r.plan.metrics[j].col.name == name) {
                py::array_t<double> a(static_cast<py::ssize_t>(r.records.size()));
                for (size_t i = 0; i < r.records.size(); ++i)
                  a.mutable_at(i) = j < r.records[i].metrics.size() ? r.records[i].metrics[j] : std::nan("");
                return a;
              }
            throw py::key_error("no metric '" + name + "'");
          },
          py::arg("name"), "One metric over the runs (runs,)")
      .def_property_readonly("series_t", [](const McResults& r) { return py::array(py::cast(r.plan.series_t)); },
                             "[s] times of the thinned samples")
      .def_property_readonly("series_columns", [](const McResults& r) { return r.plan.series_columns; })
      .def_property_readonly("series",
                             [](const McResults& r) {
                               const size_t ns = r.plan.series_t.size(), nc = r.plan.series_columns.size();
                               py::array_t<double> a({static_cast<py::ssize_t>(r.records.size()),
                                                      static_cast<py::ssize_t>(ns), static_cast<py::ssize_t>(nc)});
                               double* p = a.mutable_data();
                               for (size_t i = 0; i < r.records.size(); ++i)
                                 for (size_t k = 0; k < ns * nc; ++k)
                                   p[i * ns * nc + k] = k < r.records[i].series.size()
                                                            ? static_cast<double>(r.records[i].series[k])
                                                            : std::nan("");
                               return a;
                             },
                             "(runs, samples, series columns) the thinned channels (float32 values as float64)")
      .def_property_readonly("retained",
                             [](const McResults& r) {
                               std::vector<uint64_t> v;
                               for (const auto& x : r.records)
                                 if (x.full) v.push_back(x.index);
                               return v;
                             },
                             "indices of the runs that kept full results (retention policy)")
      .def(
          "run_dir",
          [](const McResults& r, uint64_t k) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%06llu", static_cast<unsigned long long>(k));
            return (r.dir / "runs" / buf).string();
          },
          py::arg("index"),
          "The folder of run k (manifest.json; results.h5 and the report when retained).  Without out_dir it "
          "is removed with this object.")
      .def_readonly("temporary", &McResults::temporary)
      .def_property_readonly("out_dir", [](const McResults& r) { return r.dir.string(); })
      .def_readonly("stopped", &McResults::stopped)
      .def_readonly("wall_seconds", &McResults::wall_seconds)
      .def("__len__", [](const McResults& r) { return r.records.size(); })
      .def("__repr__", [](const McResults& r) {
        size_t pass = 0;
        for (const auto& x : r.records) pass += x.pass ? 1 : 0;
        return "<kestrel.MonteCarlo " + std::to_string(r.records.size()) + " runs, " + std::to_string(pass) + " passed>";
      });

  m.def(
      "monte_carlo",
      [](const py::object& sc_or_path, const py::object& runs, unsigned jobs, const py::object& seed,
         const py::object& out_dir, bool force) {
        harness::Scenario sc;
        std::string source;
        if (py::isinstance<PyScenario>(sc_or_path)) {
          sc = sc_or_path.cast<const PyScenario&>().sc;
          source = sc.source_file;
        } else {
          source = py::str(sc_or_path).cast<std::string>();
          py::gil_scoped_release nogil;
          sc = harness::load_scenario(source);
        }
        if (!sc.monte_carlo)
          throw py::value_error((source.empty() ? sc.name : source) +
                                ": no monte_carlo section: nothing to disperse (docs/monte-carlo.md)");
        auto count = [](const py::object& o, const char* what) {
          if (!py::isinstance<py::int_>(o)) throw py::type_error(std::string("monte_carlo: ") + what + " is an int");
          if (o.cast<py::int_>() < py::int_(0)) throw py::value_error(std::string("monte_carlo: ") + what + " >= 0");
          const unsigned long long v = PyLong_AsUnsignedLongLong(o.ptr());
          if (PyErr_Occurred()) {
            PyErr_Clear();
            throw py::value_error(std::string("monte_carlo: ") + what + " beyond 64 bits");
          }
          return static_cast<uint64_t>(v);
        };
        const uint64_t n = runs.is_none() ? sc.monte_carlo->runs : count(runs, "runs");
        const uint64_t s = seed.is_none() ? sc.monte_carlo->seed : count(seed, "seed");
        // the limit of the scenario key monte_carlo.runs and of kestrel mc --runs
        // (runs=10**9 once went on to 8.4 GB before MemoryError)
        if (n == 0 || n > harness::kMaxMcRuns)
          throw py::value_error("monte_carlo: runs must be in [1, " + std::to_string(harness::kMaxMcRuns) + "], got " +
                                std::to_string(n));
        if (jobs == 0 || jobs > 1024) throw py::value_error("monte_carlo: jobs in 1..1024 (as kestrel mc -j)");
        auto res = std::make_shared<McResults>();
        {
          py::gil_scoped_release nogil;
          validate_like_cli(sc, false);
          res->plan = harness::make_mc_plan(sc, s, n);
        }
        std::optional<harness::ResultsDir> rdir;
        if (out_dir.is_none()) {
          std::string tmpl = (fs::temp_directory_path() / "kestrel_py_mc_XXXXXX").string();
          if (mkdtemp(tmpl.data()) == nullptr) throw py::value_error("monte_carlo: cannot create a temporary folder");
          res->dir = tmpl;
          res->temporary = true;
        } else {
          rdir.emplace(py::str(out_dir).cast<std::string>(), force);
          res->dir = rdir->work();
        }
        harness::McRunOptions ro;
        ro.jobs = jobs;
        for (uint64_t k = 0; k < n; ++k) ro.indices.push_back(k);
        {
          py::gil_scoped_release nogil;
          const auto t0 = std::chrono::steady_clock::now();
          res->records = harness::run_mc_runs(res->plan, res->dir, ro, res->stopped);
          res->wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          if (rdir) {
            harness::McSummaryInfo info;
            info.source = source;
            info.complete = !res->stopped && res->records.size() == n;
            info.wall_seconds = res->wall_seconds;
            harness::write_mc_outputs(res->plan, res->records, info, res->dir);
            if (info.complete) harness::remove_mc_journal(res->dir);  // the summary holds every record
            rdir->commit();
            res->dir = rdir->target();
          }
        }
        return res;
      },
      py::arg("scenario"), py::arg("runs") = py::none(), py::arg("jobs") = 1, py::arg("seed") = py::none(),
      py::arg("out_dir") = py::none(), py::arg("force") = false,
      "Runs a Monte Carlo campaign of a scenario (kestrel.Scenario or a path) with a monte_carlo section "
      "(docs/monte-carlo.md) on `jobs` threads (the GIL released).  runs, seed: default the scenario's.  With "
      "out_dir, the summary files of `kestrel mc` are written there (summary.csv, summary.h5, report).");
}

}  // namespace kpy
