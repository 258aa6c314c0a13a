// mc_sensitivity.cpp: rank statistics of the drawn values against each
// criterion's outcome (harness/mc/mc_sensitivity.h).
#include "harness/mc/mc_sensitivity.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace harness {

std::vector<double> mid_ranks(const std::vector<double>& x)
{
  std::vector<size_t> idx(x.size());
  std::iota(idx.begin(), idx.end(), size_t{0});
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return x[a] < x[b]; });
  std::vector<double> r(x.size());
  for (size_t i = 0; i < idx.size();) {
    size_t j = i;
    while (j + 1 < idx.size() && x[idx[j + 1]] == x[idx[i]]) ++j;
    const double mid = 0.5 * static_cast<double>(i + j) + 1.0;  // ranks i+1 .. j+1
    for (size_t k = i; k <= j; ++k) r[idx[k]] = mid;
    i = j + 1;
  }
  return r;
}

namespace {

struct U {
  double nf = 0.0, np = 0.0, auc = NAN, var = 0.0;
};

U mann_whitney(const std::vector<double>& x, const std::vector<char>& fail)
{
  U u;
  const std::vector<double> r = mid_ranks(x);
  double rf = 0.0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (fail[i]) {
      u.nf += 1.0;
      rf += r[i];
    } else {
      u.np += 1.0;
    }
  }
  if (u.nf == 0.0 || u.np == 0.0) return u;
  u.auc = (rf - u.nf * (u.nf + 1.0) / 2.0) / (u.nf * u.np);
  // Var(U) = nf np / 12 ((n + 1) - sum(t^3 - t) / (n (n - 1))), t: tie group sizes
  std::vector<double> s = x;
  std::sort(s.begin(), s.end());
  double ties = 0.0;
  for (size_t i = 0; i < s.size();) {
    size_t j = i;
    while (j + 1 < s.size() && s[j + 1] == s[i]) ++j;
    const double t = static_cast<double>(j - i + 1);
    ties += t * t * t - t;
    i = j + 1;
  }
  const double n = u.nf + u.np;
  u.var = u.nf * u.np / 12.0 * ((n + 1.0) - ties / (n * (n - 1.0)));
  return u;
}

}  // namespace

double mann_whitney_auc(const std::vector<double>& x, const std::vector<char>& fail) { return mann_whitney(x, fail).auc; }

double mann_whitney_p(const std::vector<double>& x, const std::vector<char>& fail)
{
  const U u = mann_whitney(x, fail);
  if (std::isnan(u.auc)) return NAN;
  if (!(u.var > 0.0)) return 1.0;
  const double z = (u.auc - 0.5) * u.nf * u.np / std::sqrt(u.var);
  return std::erfc(std::fabs(z) / std::sqrt(2.0));
}

double spearman_rho(const std::vector<double>& x, const std::vector<double>& y)
{
  if (x.size() != y.size() || x.size() < 3) return NAN;
  const std::vector<double> a = mid_ranks(x), b = mid_ranks(y);
  const double n = static_cast<double>(a.size()), mean = (n + 1.0) / 2.0;
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - mean) * (b[i] - mean);
    saa += (a[i] - mean) * (a[i] - mean);
    sbb += (b[i] - mean) * (b[i] - mean);
  }
  return saa > 0.0 && sbb > 0.0 ? sab / std::sqrt(saa * sbb) : NAN;
}

namespace {

// Criterion m's drivers from the columns of the valid runs.
McCriterionDrivers drivers_of(const McPlan& plan, size_t m, const std::vector<uint64_t>& index,
                              const std::vector<std::vector<double>>& drawn, const std::vector<double>& metric)
{
  McCriterionDrivers c;
  c.metric = m;
  c.runs = metric.size();
  std::vector<char> fail(metric.size());
  for (size_t i = 0; i < metric.size(); ++i) {
    fail[i] = criterion_met(plan.metrics[m], metric[i]) ? 0 : 1;
    if (!fail[i]) continue;
    ++c.failed;
    if (c.failing.size() < kMaxListed) c.failing.push_back(index[i]);
  }
  for (size_t d = 0; d < drawn.size(); ++d) {
    std::vector<double> x, xm, ym;
    std::vector<char> f;
    for (size_t i = 0; i < metric.size(); ++i) {
      if (!std::isfinite(drawn[d][i])) continue;
      x.push_back(drawn[d][i]);
      f.push_back(fail[i]);
      if (std::isfinite(metric[i])) {
        xm.push_back(drawn[d][i]);
        ym.push_back(metric[i]);
      }
    }
    McDriver r;
    r.drawn = d;
    r.n = x.size();
    r.auc = mann_whitney_auc(x, f);
    r.delta = 2.0 * r.auc - 1.0;
    r.p = mann_whitney_p(x, f);
    r.rho = spearman_rho(xm, ym);
    c.ranked.push_back(r);
  }
  const bool split = c.failed > 0 && c.failed < c.runs;
  auto key = [split](const McDriver& r) {
    const double k = std::fabs(split ? r.delta : r.rho);
    return std::isnan(k) ? -1.0 : k;
  };
  std::stable_sort(c.ranked.begin(), c.ranked.end(),
                   [&](const McDriver& a, const McDriver& b) { return key(a) > key(b); });
  return c;
}

}  // namespace

std::vector<McCriterionDrivers> mc_sensitivity(const McPlan& plan, const McRecordSource& src)
{
  std::vector<size_t> crit;
  for (size_t m = 0; m < plan.metrics.size(); ++m)
    if (plan.metrics[m].criterion >= 0) crit.push_back(m);
  std::vector<uint64_t> index;
  std::vector<std::vector<double>> drawn(plan.drawn.size());
  std::vector<std::vector<double>> metric(crit.size());
  for (size_t i = 0; i < src.size() && index.size() < kSensitivityMaxRuns; ++i) {
    if (src.state(i).invalid) continue;
    const McRecord r = src.record(i);
    index.push_back(r.index);
    for (size_t d = 0; d < drawn.size(); ++d) drawn[d].push_back(d < r.drawn.size() ? r.drawn[d] : NAN);
    for (size_t c = 0; c < crit.size(); ++c) metric[c].push_back(crit[c] < r.metrics.size() ? r.metrics[crit[c]] : NAN);
  }
  std::vector<McCriterionDrivers> out;
  for (size_t c = 0; c < crit.size(); ++c) out.push_back(drivers_of(plan, crit[c], index, drawn, metric[c]));
  return out;
}

}  // namespace harness
