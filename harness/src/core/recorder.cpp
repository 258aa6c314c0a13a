#include "harness/core/recorder.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace harness {

size_t RecordLayout::column_index(const std::string& col) const
{
  for (size_t i = 0; i < columns.size(); ++i)
    if (columns[i].name == col) return i;
  throw std::out_of_range("recorder '" + name + "': no column '" + col + "'");
}

void Recorder::add_source(const std::string& group, const std::vector<Quantity>& qs, FillFn fill)
{
  if (allocated_) throw std::logic_error("recorder '" + name_ + "': add a source before allocate()");
  if (!fill) throw std::invalid_argument("recorder '" + name_ + "': source without a fill function");
  const size_t first = layout_.columns.size();
  std::vector<Column> added;
  for (const Quantity& q : qs) {
    if (q.name.empty() || q.columns.empty())
      throw std::invalid_argument("recorder '" + name_ + "': a quantity needs a name and at least one column");
    for (const QuantityInfo& d : layout_.quantities)
      if (d.group == group && d.name == q.name)
        throw std::invalid_argument("recorder '" + name_ + "': quantity '" + group + "/" + q.name + "' declared twice");
    QuantityInfo info{group, q.name, q.unit, q.frame, first + added.size(), q.columns.size()};
    for (size_t k = 0; k < q.columns.size(); ++k) {
      const std::string& c = q.columns[k];
      if (c.empty()) throw std::invalid_argument("recorder '" + name_ + "': empty column name");
      auto same = [&c](const Column& d) { return d.name == c; };
      if (std::any_of(layout_.columns.begin(), layout_.columns.end(), same) ||
          std::any_of(added.begin(), added.end(), same))
        throw std::invalid_argument("recorder '" + name_ + "': column '" + c + "' declared twice");
      added.push_back(Column{c, q.unit, group, q.name, q.frame, static_cast<int>(k)});
    }
    layout_.quantities.push_back(info);
  }
  sources_.push_back(Source{first, added.size(), std::move(fill)});
  layout_.columns.insert(layout_.columns.end(), added.begin(), added.end());
}

void Recorder::add_source(const std::vector<Column>& cols, FillFn fill)
{
  std::vector<Quantity> qs;
  for (const Column& c : cols) qs.push_back(Quantity{c.name, c.unit, c.frame, {c.name}});
  add_source(name_, qs, std::move(fill));
}

void Recorder::allocate(uint64_t rows, size_t chunk_rows)
{
  if (allocated_) throw std::logic_error("recorder '" + name_ + "': allocate() called twice");
  if (chunk_rows == 0) throw std::invalid_argument("recorder '" + name_ + "': chunk_rows must be > 0");
  layout_.name = name_;
  chunk_rows_ = chunk_rows;
  chunk_.assign(chunk_rows_ * std::max<size_t>(1, layout_.columns.size()), 0.0);
  capacity_ = rows;
  allocated_ = true;
}

void Recorder::add_sink(RecordSink& sink)
{
  if (!allocated_) throw std::logic_error("recorder '" + name_ + "': add a sink after allocate()");
  if (rows_ > 0 || finished_) throw std::logic_error("recorder '" + name_ + "': add a sink before the first sample");
  sink.begin(layout_, capacity_);
  sinks_.push_back(&sink);
}

bool Recorder::sample()
{
  if (rows_ >= capacity_ || finished_) {
    ++overflow_;
    return false;
  }
  double* row = chunk_.data() + pending_ * layout_.columns.size();
  for (const Source& s : sources_) s.fill(row + s.first_col);
  ++rows_;
  if (++pending_ == chunk_rows_) flush();
  return true;
}

void Recorder::flush()
{
  if (pending_ == 0) return;
  const size_t n = pending_;
  pending_ = 0;  // a throwing sink must not see the same rows twice
  for (RecordSink* s : sinks_) s->write(chunk_.data(), n);
}

void Recorder::finish(bool complete)
{
  if (finished_ || !allocated_) return;
  finished_ = true;
  flush();
  for (RecordSink* s : sinks_) s->end(complete);
}

void Recorder::state_io(sim::StateIO& io)
{
  const size_t ncol = layout_.columns.size();
  uint64_t cols = ncol, pending = pending_, chunk = chunk_rows_;
  io.value("recorder.columns", cols);
  io.value("recorder.chunk_rows", chunk);
  if (cols != ncol) throw std::runtime_error("checkpoint: the recorder has other columns");
  if (io.loading() && chunk != chunk_rows_) {  // the saved run's chunk size (a Python run hands on every row)
    if (chunk == 0 || chunk > (uint64_t{1} << 20))
      throw std::runtime_error("checkpoint: the recorder's chunk size " + std::to_string(chunk) + " is out of range");
    chunk_rows_ = static_cast<size_t>(chunk);
    chunk_.assign(chunk_rows_ * std::max<size_t>(1, ncol), 0.0);
  }
  io.value("recorder.rows", rows_);
  io.value("recorder.overflow", overflow_);
  io.value("recorder.pending", pending);
  if (pending > chunk_rows_ || pending > rows_) throw std::runtime_error("checkpoint: the recorder's chunk does not fit");
  pending_ = static_cast<size_t>(pending);
  // the waiting rows fill slots 0 .. pending - 1 (the chunk is handed on whole)
  io.bytes("recorder.chunk", chunk_.data(), pending_ * ncol * sizeof(double));
  if (rows_ > 0) {
    const size_t slot = static_cast<size_t>((rows_ - 1) % chunk_rows_);
    io.bytes("recorder.last_row", chunk_.data() + slot * ncol, ncol * sizeof(double));
  }
}

const double* Recorder::last_row() const
{
  if (rows_ == 0) return nullptr;
  // row r sits in chunk slot r % chunk_rows (a flush does not clear it)
  const size_t slot = static_cast<size_t>((rows_ - 1) % chunk_rows_);
  return chunk_.data() + slot * layout_.columns.size();
}

void MemorySink::begin(const RecordLayout& layout, uint64_t expected_rows)
{
  layout_ = layout;
  capacity_ = expected_rows;
  rows_ = 0;
  data_.assign(static_cast<size_t>(expected_rows) * layout_.columns.size(), 0.0);
}

void MemorySink::write(const double* rows, size_t n)
{
  if (rows_ + n > capacity_) throw std::logic_error("memory sink: more rows than announced");
  const size_t nc = layout_.columns.size();
  if (n > 0 && nc > 0) std::memcpy(data_.data() + static_cast<size_t>(rows_) * nc, rows, n * nc * sizeof(double));
  rows_ += n;
}

std::vector<double> MemorySink::column(const std::string& name) const
{
  const size_t c = column_index(name);
  std::vector<double> out(static_cast<size_t>(rows_));
  for (uint64_t r = 0; r < rows_; ++r) out[static_cast<size_t>(r)] = at(r, c);
  return out;
}

}  // namespace harness
