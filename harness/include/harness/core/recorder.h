// recorder: samples messages (or values derived from them) into rows and
// streams the rows to sinks in fixed-size chunks.
//
// Columns are declared at setup, grouped into quantities: a quantity is one
// physical value of one message, with a unit, a frame and its components
// (e.g. group "truth", quantity "omega_BN_B", unit rad/s, frame B, columns
// omega_BN_B_x/_y/_z).  allocate(rows) freezes the layout and reserves one
// chunk of `chunk_rows` rows; sample() writes a row into the chunk and hands
// every full chunk to the sinks (RecordSink): memory grows with the chunk,
// never with the run's duration.  The row count of a whole run is known from
// the rate-group math (RateGroup::count_due); a sample beyond it is refused
// and counted in overflow() (the run then fails instead of losing data).
//
// Sinks (harness/sinks.h): MemorySink keeps every row (tests, the C++ API,
// short runs); Hdf5Sink, CsvSink and ReportSink (harness_io) stream to files.
// A sink is attached before the first sample and told the layout and the
// expected row count at once (RecordSink::begin); finish() flushes the last
// partial chunk and ends every sink.
#ifndef HARNESS_RECORDER_H
#define HARNESS_RECORDER_H

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "harness/core/messages.h"

namespace harness {

// One recorded quantity of a message: `columns` are the flat column names of
// its components, in order (one for a scalar).
struct Quantity {
  std::string name;                  // e.g. "omega_BN_B" (dataset name in its group)
  std::string unit;                  // e.g. "rad/s", "-", "N*m"
  std::string frame;                 // e.g. "B", "N", "N->B" (attitude of B rel. N); "" for scalars
  std::vector<std::string> columns;  // e.g. {"omega_BN_B_x", "omega_BN_B_y", "omega_BN_B_z"}
};

// A flat column (CSV, the report and the in-memory table use these).
struct Column {
  std::string name;  // unique within a recorder
  std::string unit;
  std::string group = "";     // message the quantity belongs to ("" : top level, e.g. t)
  std::string quantity = "";  // quantity name (the column name for a scalar)
  std::string frame = "";
  int component = 0;          // index within the quantity
};

// A quantity's place in the row.
struct QuantityInfo {
  std::string group, name, unit, frame;
  size_t first_col = 0;
  size_t num_cols = 0;
};

struct RecordLayout {
  std::string name;                       // the recorder's name
  std::vector<Column> columns;            // row order
  std::vector<QuantityInfo> quantities;   // declaration order; columns are contiguous per quantity
  size_t column_index(const std::string& col) const;  // throws std::out_of_range
};

// Where recorded rows go.  Calls: begin once, write any number of times (n
// rows, row-major, valid only during the call), end once.
class RecordSink {
 public:
  virtual ~RecordSink() = default;
  // expected_rows: the rows a complete run produces.
  virtual void begin(const RecordLayout& layout, uint64_t expected_rows) = 0;
  virtual void write(const double* rows, size_t n) = 0;
  // complete: false when the run stopped before its last row.
  virtual void end(bool complete) = 0;
};

class Recorder {
 public:
  using FillFn = std::function<void(double* out)>;  // writes exactly its columns

  explicit Recorder(std::string name) : name_(std::move(name)) {}

  // Generic source in message group `group`: `fill` writes the columns of
  // every quantity, in order.
  void add_source(const std::string& group, const std::vector<Quantity>& qs, FillFn fill);
  // Scalars only, each column its own quantity, in the recorder's group.
  void add_source(const std::vector<Column>& cols, FillFn fill);

  // Records a message: `fill(msg, out)` writes the quantities' columns from
  // the latest value of channel `c` (group = the message name).
  template <class T>
  void record(const Channel<T>& c, const std::vector<Quantity>& qs, std::function<void(const T&, double*)> fill)
  {
    const Channel<T>* ch = &c;
    add_source(c.name(), qs, [ch, fill](double* out) { fill(ch->value(), out); });
    messages_.push_back(c.name());
  }

  // Freezes the layout; `rows` is the number of rows of a complete run (the
  // capacity); reserves one chunk (the only allocation of the recorder).
  void allocate(uint64_t rows, size_t chunk_rows = 1024);
  // Attaches a sink (owned by the caller, alive until finish()): begin() is
  // called at once.  Only after allocate() and before the first sample.
  void add_sink(RecordSink& sink);

  // Appends one row from every source; a full chunk goes to the sinks.
  // False (and overflow()++) beyond the capacity.
  bool sample();
  // Hands the last partial chunk to the sinks and ends them (once; later
  // calls do nothing).  complete: the run reached its last row.
  void finish(bool complete);
  bool finished() const { return finished_; }

  const std::string& name() const { return name_; }
  const RecordLayout& layout() const { return layout_; }
  const std::vector<Column>& columns() const { return layout_.columns; }
  size_t num_columns() const { return layout_.columns.size(); }
  size_t column_index(const std::string& col) const { return layout_.column_index(col); }
  uint64_t rows() const { return rows_; }          // sampled so far
  uint64_t capacity() const { return capacity_; }  // rows of a complete run
  uint64_t overflow() const { return overflow_; }
  size_t chunk_rows() const { return chunk_rows_; }
  // The latest row (num_columns() values), nullptr before the first sample.
  const double* last_row() const;
  const std::vector<std::string>& recorded_messages() const { return messages_; }
  const double* chunk_address() const { return chunk_.data(); }  // for no-realloc tests
  // Rows handed to the sinks so far (the rest waits in the chunk).
  uint64_t sink_rows() const { return rows_ - pending_; }
  // For a checkpoint (sim/state_io.h): the rows sampled, the overflow, the
  // rows waiting in the chunk and the latest row (events watch it).  A
  // restored recorder hands its sinks the rows from sink_rows() on.
  void state_io(sim::StateIO& io);

 private:
  void flush();
  struct Source {
    size_t first_col;
    size_t n_cols;
    FillFn fill;
  };
  std::string name_;
  RecordLayout layout_;
  std::vector<Source> sources_;
  std::vector<std::string> messages_;
  std::vector<RecordSink*> sinks_;
  std::vector<double> chunk_;  // chunk_rows_ x num_columns(), row-major
  size_t chunk_rows_ = 0;
  size_t pending_ = 0;         // rows in the chunk not yet handed to the sinks
  uint64_t capacity_ = 0;
  uint64_t rows_ = 0;
  uint64_t overflow_ = 0;
  bool allocated_ = false;
  bool finished_ = false;
};

// Keeps every row in memory, preallocated at begin() for the expected rows
// (a row beyond them is an error, never a reallocation).
class MemorySink : public RecordSink {
 public:
  void begin(const RecordLayout& layout, uint64_t expected_rows) override;
  void write(const double* rows, size_t n) override;
  void end(bool complete) override { complete_ = complete; }

  const std::vector<Column>& columns() const { return layout_.columns; }
  size_t num_columns() const { return layout_.columns.size(); }
  uint64_t rows() const { return rows_; }
  bool complete() const { return complete_; }
  const double* data() const { return data_.data(); }  // rows() x num_columns(), row-major
  double at(uint64_t row, size_t col) const { return data_[static_cast<size_t>(row) * layout_.columns.size() + col]; }
  size_t column_index(const std::string& name) const { return layout_.column_index(name); }
  std::vector<double> column(const std::string& name) const;
  const double* storage_address() const { return data_.data(); }  // for no-realloc tests

 private:
  RecordLayout layout_;
  std::vector<double> data_;
  uint64_t capacity_ = 0;
  uint64_t rows_ = 0;
  bool complete_ = false;
};

}  // namespace harness

#endif  // HARNESS_RECORDER_H
