// messages: typed message channels and the data-flow map.
//
// A message is a plain struct.  A Channel<T> holds the latest value, its time
// stamp and a write counter.  Components do not touch channels directly: at
// setup each obtains a Writer<T> or Reader<T> from the DataFlow registry,
// which records who writes and who reads which message (one writer per
// message).  DataFlow::to_dot() writes that map as Graphviz DOT.
// No allocation happens after setup: write() and read() copy plain structs;
// a writer that fills a large message field by field does it in place
// (edit(), then publish()), without a copy.
#ifndef HARNESS_MESSAGES_H
#define HARNESS_MESSAGES_H

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "sim/state_io.h"

namespace harness {

class ChannelBase {
 public:
  explicit ChannelBase(std::string name) : name_(std::move(name)) {}
  virtual ~ChannelBase() = default;
  const std::string& name() const { return name_; }
  uint64_t write_count() const { return writes_; }
  uint64_t t_ns() const { return t_ns_; }
  // The value, its time stamp and write count, for a checkpoint (sim/state_io.h).
  virtual void state_io(sim::StateIO& io)
  {
    io.value("message.writes", writes_);
    io.value("message.t_ns", t_ns_);
  }

 protected:
  std::string name_;
  uint64_t writes_ = 0;  // [-]  number of writes so far
  uint64_t t_ns_ = 0;    // [ns] time stamp of the latest write
};

template <class T>
class Channel : public ChannelBase {
  static_assert(std::is_trivially_copyable<T>::value, "messages are plain structs");

 public:
  explicit Channel(std::string name) : ChannelBase(std::move(name)), value_{} {}
  const T& value() const { return value_; }
  void write(const T& v, uint64_t t_ns)
  {
    value_ = v;
    publish(t_ns);
  }
  // In place: the latest value, to be changed by its writer, then published
  // as a write at t_ns (tasks run one at a time, so no reader sees it
  // half-filled).  Fields the writer leaves alone keep their latest value.
  T& edit() { return value_; }
  void publish(uint64_t t_ns)
  {
    t_ns_ = t_ns;
    ++writes_;
  }
  void state_io(sim::StateIO& io) override
  {
    io.value(name_.c_str(), value_);
    ChannelBase::state_io(io);
  }

 private:
  T value_;
};

template <class T>
class Writer {
 public:
  Writer() = default;
  explicit Writer(Channel<T>* c) : c_(c) {}
  bool valid() const { return c_ != nullptr; }
  void write(const T& v, uint64_t t_ns) const { c_->write(v, t_ns); }
  T& edit() const { return c_->edit(); }                       // Channel::edit
  void publish(uint64_t t_ns) const { c_->publish(t_ns); }     // Channel::publish
  const Channel<T>& channel() const { return *c_; }

 private:
  Channel<T>* c_ = nullptr;
};

template <class T>
class Reader {
 public:
  Reader() = default;
  explicit Reader(const Channel<T>* c) : c_(c) {}
  bool valid() const { return c_ != nullptr; }
  const T& read() const { return c_->value(); }
  uint64_t write_count() const { return c_->write_count(); }
  uint64_t t_ns() const { return c_->t_ns(); }
  const Channel<T>& channel() const { return *c_; }

 private:
  const Channel<T>* c_ = nullptr;
};

struct DataFlowEdge {
  std::string component;
  std::string message;
  bool writes = false;  // true: component -> message, false: message -> component
};

// Owns the channels; records writers and readers.
class DataFlow {
 public:
  template <class T>
  Channel<T>& add_message(const std::string& name)
  {
    check_new_message(name);
    auto c = std::make_unique<Channel<T>>(name);
    Channel<T>& ref = *c;
    channels_.push_back(std::move(c));
    return ref;
  }

  void add_component(const std::string& name, const std::string& kind = "");

  template <class T>
  Writer<T> writer(const std::string& component, Channel<T>& c)
  {
    add_edge(component, c.name(), true);
    return Writer<T>(&c);
  }
  template <class T>
  Reader<T> reader(const std::string& component, const Channel<T>& c)
  {
    add_edge(component, c.name(), false);
    return Reader<T>(&c);
  }

  const std::vector<DataFlowEdge>& edges() const { return edges_; }
  std::vector<std::string> messages() const;
  const std::vector<std::pair<std::string, std::string>>& components() const { return components_; }
  // Name of the component writing `message`, or "" if none.
  std::string writer_of(const std::string& message) const;
  std::vector<std::string> readers_of(const std::string& message) const;

  // Graphviz DOT: components as boxes, messages as ellipses, edges in the
  // data direction.  Deterministic (registration order).
  std::string to_dot(const std::string& graph_name = "kestrel") const;

  // Every message's value, time stamp and write count, in registration
  // order, for a checkpoint (sim/state_io.h).
  void state_io(sim::StateIO& io)
  {
    for (auto& c : channels_) c->state_io(io);
  }

 private:
  void check_new_message(const std::string& name) const;
  void add_edge(const std::string& component, const std::string& message, bool writes);
  bool has_message(const std::string& name) const;

  std::vector<std::unique_ptr<ChannelBase>> channels_;
  std::vector<std::pair<std::string, std::string>> components_;  // name, kind
  std::vector<DataFlowEdge> edges_;
};

}  // namespace harness

#endif  // HARNESS_MESSAGES_H
