#include "harness/recorder.h"

#include <stdexcept>

namespace harness {

void Recorder::add_source(const std::vector<Column>& cols, FillFn fill)
{
  if (allocated_) throw std::logic_error("recorder '" + name_ + "': add a source before allocate()");
  if (!fill) throw std::invalid_argument("recorder '" + name_ + "': source without a fill function");
  for (const Column& c : cols) {
    if (c.name.empty()) throw std::invalid_argument("recorder '" + name_ + "': empty column name");
    for (const Column& d : columns_)
      if (d.name == c.name)
        throw std::invalid_argument("recorder '" + name_ + "': column '" + c.name + "' declared twice");
  }
  sources_.push_back(Source{columns_.size(), cols.size(), std::move(fill)});
  columns_.insert(columns_.end(), cols.begin(), cols.end());
}

void Recorder::allocate(uint64_t rows)
{
  if (allocated_) throw std::logic_error("recorder '" + name_ + "': allocate() called twice");
  data_.assign(static_cast<size_t>(rows) * columns_.size(), 0.0);
  capacity_ = rows;
  allocated_ = true;
}

bool Recorder::sample()
{
  if (rows_ >= capacity_) {
    ++overflow_;
    return false;
  }
  double* row = data_.data() + static_cast<size_t>(rows_) * columns_.size();
  for (const Source& s : sources_) s.fill(row + s.first_col);
  ++rows_;
  return true;
}

size_t Recorder::column_index(const std::string& name) const
{
  for (size_t i = 0; i < columns_.size(); ++i)
    if (columns_[i].name == name) return i;
  throw std::out_of_range("recorder '" + name_ + "': no column '" + name + "'");
}

std::vector<double> Recorder::column(const std::string& name) const
{
  const size_t c = column_index(name);
  std::vector<double> out(static_cast<size_t>(rows_));
  for (uint64_t r = 0; r < rows_; ++r) out[static_cast<size_t>(r)] = at(r, c);
  return out;
}

}  // namespace harness
