// report_sink.cpp: what the HTML report shows, bounded for any duration.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

#include "harness/output/outputs.h"

namespace harness {

namespace {

void put_number(std::string& out, double v)
{
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest text that reads back exactly
  out.append(buf, r.ptr);
}

void put_string(std::string& out, const std::string& s)
{
  out += '"';
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;  // column names and units are plain text
    out += c;
  }
  out += '"';
}

}  // namespace

void ReportSink::begin(const RecordLayout& layout, uint64_t expected_rows)
{
  layout_ = layout;
  const size_t nc = layout_.columns.size();
  endpoint_col_.assign(nc, 0);
  for (size_t c = 0; c < nc; ++c)
    endpoint_col_[c] = (layout_.columns[c].name == "t" || layout_.columns[c].quantity == "q_BN") ? 1 : 0;
  bucket_rows_ = expected_rows <= 2 * kReportBuckets
                     ? 1
                     : static_cast<size_t>((expected_rows + kReportBuckets - 1) / kReportBuckets);
  rows_seen_ = 0;
  in_bucket_ = 0;
  points_.clear();
  const uint64_t max_points = bucket_rows_ == 1 ? expected_rows : 2 * kReportBuckets + 2;
  points_.reserve(static_cast<size_t>(max_points) * nc);
  first_.assign(nc, 0.0);
  last_.assign(nc, 0.0);
  lo_.assign(nc, 0.0);
  hi_.assign(nc, 0.0);
  lo_at_.assign(nc, 0);
  hi_at_.assign(nc, 0);
  spec_cols_.clear();
  ring_.clear();
  ring_n_ = 0;
  if (bucket_rows_ > 1) {
    for (const char* name : {"t", "omega_BN_B_x", "omega_BN_B_y", "omega_BN_B_z", "pointing_error_deg"})
      for (size_t c = 0; c < nc; ++c)
        if (layout_.columns[c].name == name) spec_cols_.push_back(c);
    ring_.assign(kSpectrumRows * spec_cols_.size(), 0.0);
  }
}

void ReportSink::write(const double* rows, size_t n)
{
  const size_t nc = layout_.columns.size();
  for (size_t r = 0; r < n; ++r) {
    const double* row = rows + r * nc;
    ++rows_seen_;
    if (bucket_rows_ == 1) {
      points_.insert(points_.end(), row, row + nc);
      continue;
    }
    // full-rate ring for the spectrum
    double* slot = ring_.data() + static_cast<size_t>(ring_n_ % kSpectrumRows) * spec_cols_.size();
    for (size_t k = 0; k < spec_cols_.size(); ++k) slot[k] = row[spec_cols_[k]];
    ++ring_n_;
    // the open bucket; NaN never wins a comparison, so a NaN-only column stays NaN
    if (in_bucket_ == 0) {
      std::copy(row, row + nc, first_.begin());
      std::copy(row, row + nc, lo_.begin());
      std::copy(row, row + nc, hi_.begin());
      std::fill(lo_at_.begin(), lo_at_.end(), 0);
      std::fill(hi_at_.begin(), hi_at_.end(), 0);
    } else {
      for (size_t c = 0; c < nc; ++c) {
        const double v = row[c];
        if (v < lo_[c] || std::isnan(lo_[c])) {
          lo_[c] = v;
          lo_at_[c] = in_bucket_;
        }
        if (v > hi_[c] || std::isnan(hi_[c])) {
          hi_[c] = v;
          hi_at_[c] = in_bucket_;
        }
      }
    }
    std::copy(row, row + nc, last_.begin());
    if (++in_bucket_ == bucket_rows_) close_bucket();
  }
}

void ReportSink::close_bucket()
{
  if (in_bucket_ == 0) return;
  const size_t nc = layout_.columns.size();
  if (in_bucket_ == 1) {
    points_.insert(points_.end(), first_.begin(), first_.end());
  } else {
    // two points: at the bucket's first and last rows; a column shows its
    // extremes in the order they occurred
    const size_t a = points_.size();
    points_.resize(a + 2 * nc);
    double* pa = points_.data() + a;
    double* pb = pa + nc;
    for (size_t c = 0; c < nc; ++c) {
      if (endpoint_col_[c]) {
        pa[c] = first_[c];
        pb[c] = last_[c];
      } else if (lo_at_[c] <= hi_at_[c]) {
        pa[c] = lo_[c];
        pb[c] = hi_[c];
      } else {
        pa[c] = hi_[c];
        pb[c] = lo_[c];
      }
    }
  }
  in_bucket_ = 0;
}

void ReportSink::end(bool) { close_bucket(); }

std::string ReportSink::series_json() const
{
  const size_t nc = layout_.columns.size();
  const size_t np = nc ? points_.size() / nc : 0;
  std::string out;
  out.reserve(np * nc * 14 + 4096);
  auto column_array = [&](size_t c) {
    out += '[';
    for (size_t p = 0; p < np; ++p) {
      if (p) out += ',';
      put_number(out, points_[p * nc + c]);
    }
    out += ']';
  };
  out += "\"series\":{";
  bool first = true;
  for (size_t c = 0; c < nc; ++c) {
    if (layout_.columns[c].quantity == "q_BN") continue;  // in `attitude`
    if (!first) out += ',';
    first = false;
    put_string(out, layout_.columns[c].name);
    out += ':';
    column_array(c);
  }
  out += "},\"units\":{";
  first = true;
  for (size_t c = 0; c < nc; ++c) {
    if (layout_.columns[c].quantity == "q_BN") continue;
    if (!first) out += ',';
    first = false;
    put_string(out, layout_.columns[c].name);
    out += ':';
    put_string(out, layout_.columns[c].unit);
  }
  out += "},\"attitude\":{\"t\":";
  size_t t_col = nc, q_col = nc;
  for (size_t c = 0; c < nc; ++c) {
    if (layout_.columns[c].name == "t") t_col = c;
    if (layout_.columns[c].name == "q_BN_0") q_col = c;
  }
  if (t_col < nc) column_array(t_col);
  else out += "[]";
  out += ",\"q_BN\":[";
  if (q_col + 4 <= nc)
    for (size_t p = 0; p < np; ++p) {
      if (p) out += ',';
      out += '[';
      for (size_t k = 0; k < 4; ++k) {
        if (k) out += ',';
        put_number(out, points_[p * nc + q_col + k]);
      }
      out += ']';
    }
  out += "]}";
  if (bucket_rows_ > 1) {
    // the last rows at full rate (oldest first), for the jitter spectrum
    const uint64_t n = std::min<uint64_t>(ring_n_, kSpectrumRows);
    const uint64_t first_row = ring_n_ - n;
    out += ",\"spectrum\":{";
    for (size_t k = 0; k < spec_cols_.size(); ++k) {
      if (k) out += ',';
      put_string(out, layout_.columns[spec_cols_[k]].name);
      out += ":[";
      for (uint64_t i = 0; i < n; ++i) {
        if (i) out += ',';
        put_number(out, ring_[static_cast<size_t>((first_row + i) % kSpectrumRows) * spec_cols_.size() + k]);
      }
      out += ']';
    }
    out += "},\"decimation\":{\"rows\":" + std::to_string(rows_seen_) + ",\"bucket_rows\":" +
           std::to_string(bucket_rows_) + ",\"points\":" + std::to_string(np) +
           ",\"rule\":\"min and max of each column per bucket, in the order they occurred, at the times of the "
           "bucket's first and last rows; t and q_BN at those rows\"}";
  }
  return out;
}

}  // namespace harness
