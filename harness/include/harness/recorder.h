// recorder: records messages (or any derived values) into a preallocated
// row-major table of doubles.  Columns are declared at setup; allocate(rows)
// reserves the whole table once, so sample() never allocates and never
// reallocates in the loop.  The harness computes the exact row count from
// the rate-group math (RateGroup::count_due), so the table never fills up;
// if it ever did, sample() refuses the row and counts it in overflow() (the
// run then reports an error instead of silently losing data).
#ifndef HARNESS_RECORDER_H
#define HARNESS_RECORDER_H

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "harness/messages.h"

namespace harness {

struct Column {
  std::string name;  // unique within a recorder
  std::string unit;  // e.g. "rad/s", "-", "N*m"
};

class Recorder {
 public:
  using FillFn = std::function<void(double* out)>;  // writes exactly its columns

  explicit Recorder(std::string name) : name_(std::move(name)) {}

  // Generic source: `fill` writes cols.size() values.
  void add_source(const std::vector<Column>& cols, FillFn fill);

  // Records a message: `fill(msg, out)` writes cols.size() values from the
  // latest value of channel `c`.
  template <class T>
  void record(const Channel<T>& c, const std::vector<Column>& cols,
              std::function<void(const T&, double*)> fill)
  {
    const Channel<T>* ch = &c;
    add_source(cols, [ch, fill](double* out) { fill(ch->value(), out); });
    messages_.push_back(c.name());
  }

  // Reserves `rows` rows (the only allocation).  Columns are frozen after.
  void allocate(uint64_t rows);

  // Appends one row from every source.  False (and overflow()++) if full.
  bool sample();

  const std::string& name() const { return name_; }
  const std::vector<Column>& columns() const { return columns_; }
  size_t num_columns() const { return columns_.size(); }
  uint64_t rows() const { return rows_; }
  uint64_t capacity() const { return capacity_; }
  uint64_t overflow() const { return overflow_; }
  const double* data() const { return data_.data(); }  // rows() x num_columns(), row-major
  double at(uint64_t row, size_t col) const { return data_[row * columns_.size() + col]; }
  // Column index by name; throws std::out_of_range if absent.
  size_t column_index(const std::string& name) const;
  std::vector<double> column(const std::string& name) const;
  const std::vector<std::string>& recorded_messages() const { return messages_; }
  const double* storage_address() const { return data_.data(); }  // for no-realloc tests

 private:
  struct Source {
    size_t first_col;
    size_t n_cols;
    FillFn fill;
  };
  std::string name_;
  std::vector<Column> columns_;
  std::vector<Source> sources_;
  std::vector<std::string> messages_;
  std::vector<double> data_;
  uint64_t capacity_ = 0;
  uint64_t rows_ = 0;
  uint64_t overflow_ = 0;
  bool allocated_ = false;
};

}  // namespace harness

#endif  // HARNESS_RECORDER_H
