// mc_sensitivity: which dispersions drive a campaign's failures
// (docs/monte-carlo.md, "What drives the failures").
//
// For each criterion and each drawn value x, over the valid runs (a draw
// that was run; an invalid draw has no outcome):
//   AUC    = P(x of a run failing the criterion > x of a run meeting it)
//            + 1/2 P(equal), the Mann-Whitney U statistic over n_F n_P,
//            from mid-ranks: AUC = (R_F - n_F (n_F + 1) / 2) / (n_F n_P),
//            R_F the sum of the failing runs' ranks of x;
//   delta  = 2 AUC - 1 in [-1, 1] (Cliff's delta): +1 when every failing
//            run drew more than every passing one, -1 when less, ~0 when x
//            does not separate them; |delta| ranks the dispersions;
//   p      = two-sided p-value of U against "x does not matter", normal
//            approximation with the tie correction;
//   rho    = Spearman's rank correlation of x with the criterion's metric
//            (finite metrics), which ranks also when nothing failed.
// Rank-based: any monotone transform of x or of the metric gives the same
// figures, and outliers weigh as their rank.
#ifndef HARNESS_MC_MC_SENSITIVITY_H
#define HARNESS_MC_MC_SENSITIVITY_H

#include <cstddef>
#include <vector>

#include "harness/mc/monte_carlo.h"

namespace harness {

// Mid-ranks (1-based; tied values share the mean of their ranks).
std::vector<double> mid_ranks(const std::vector<double>& x);
// AUC of x between the runs with fail[i] and the others (NaN when a group is empty).
double mann_whitney_auc(const std::vector<double>& x, const std::vector<char>& fail);
// Two-sided p-value of the same U (normal approximation, tie-corrected; NaN
// when a group is empty, 1 when every x is equal).
double mann_whitney_p(const std::vector<double>& x, const std::vector<char>& fail);
// Spearman's rho of x and y (Pearson's correlation of their mid-ranks; NaN
// for fewer than 3 pairs or a constant one).
double spearman_rho(const std::vector<double>& x, const std::vector<double>& y);

struct McDriver {
  size_t drawn = 0;    // index into McPlan::drawn
  size_t n = 0;        // runs with this value drawn
  double auc = NAN, delta = NAN, p = NAN, rho = NAN;
};
struct McCriterionDrivers {
  size_t metric = 0;   // index into McPlan::metrics (a criterion)
  size_t runs = 0, failed = 0;   // valid runs; those failing this criterion
  std::vector<uint64_t> failing;  // their indices (the first kMaxListed)
  std::vector<McDriver> ranked;   // strongest first: |delta| (rho when nothing or everything failed)
};
constexpr size_t kSensitivityMaxRuns = 100000;  // runs used (the first by index)
constexpr size_t kMaxListed = 200;

// Per criterion, the drawn values ranked (from the first kSensitivityMaxRuns
// records of `src`, in index order).
std::vector<McCriterionDrivers> mc_sensitivity(const McPlan& plan, const McRecordSource& src);

}  // namespace harness

#endif  // HARNESS_MC_MC_SENSITIVITY_H
