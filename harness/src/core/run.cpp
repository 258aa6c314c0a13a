// run.cpp: builds a run from its parts and steps it.  The parts live in
// their own files: plant_builder (plant, burn schedule), fsw_config (the
// FSW's configuration), sensor_suite (sensor models), tasks (the tick
// protocol's tasks), telemetry_columns (what is recorded).
#include "harness/core/run.h"
#include "harness/core/loop_error.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "core/build_error.h"
#include "core/event_task.h"
#include "core/fsw_config.h"
#include "core/plant_builder.h"
#include "core/sensor_suite.h"
#include "sim/environment.h"
#include "sim/units.h"
#include "core/tasks.h"
#include "core/telemetry_columns.h"

#ifndef KESTREL_VERSION
#define KESTREL_VERSION "0.0.0"
#endif

namespace harness {

const char* version() { return KESTREL_VERSION; }

namespace {

constexpr double kRadToDeg = 180.0 / sim::kPi;

// Whether a scenario event commands the flight software (device fsw).
bool commands_fsw(const Scenario& sc)
{
  for (const EventSpec& e : sc.events)
    for (const EventActionSpec& a : e.actions)
      if (a.device == "fsw") return true;
  return false;
}

// What the configuration's mode points by (DETUMBLE: the mode it leaves for).
PointingReference configured_reference(const FswSpec& f)
{
  const FswMode m = f.mode == FswMode::Detumble ? f.detumble_exit : f.mode;
  switch (m) {
    case FswMode::SunSafe: return PointingReference::SunAxis;
    case FswMode::Nadir: return PointingReference::OrbitFrame;
    default: return PointingReference::Inertial;  // inertial; DETUMBLE staying ("none")
  }
}

// TruthReaders: due when a reader of `truth` is (the FSW input, metrics and
// recorder; every tick when the burn monitor runs), not at every tick.
enum class Group { EveryTick, Fsw, Record, TruthReaders };
struct Slot {
  const char* task;
  Group group;
};
// The tick protocol: the order of the tasks within a tick (run.h).  A task a
// run does not need (no thrusters, no sampled sensors, ...) is skipped.
// A task's state for a checkpoint: a task whose operator() is const keeps
// none of its own (what it drives, the plant or the sensors, is saved with
// them); any other must have state_io (Run::state_io calls it).  Checked at
// compile time for every task type, so that a task with state cannot be
// added without being in the checkpoint.
template <class T, class = void>
struct HasStateIo : std::false_type {};
template <class T>
struct HasStateIo<T, std::void_t<decltype(std::declval<T&>().state_io(std::declval<sim::StateIO&>()))>>
    : std::true_type {};
template <class T, class = void>
struct ConstCall : std::false_type {};
template <class T>
struct ConstCall<T, std::void_t<decltype(std::declval<const T&>()(uint64_t{0}))>> : std::true_type {};
template <class... T>
constexpr bool kTasksCheckpointed = ((ConstCall<T>::value || HasStateIo<T>::value) && ...);
static_assert(kTasksCheckpointed<TruthTask, BurnMonitor, SampleSensorsTask, CssTask, FswInputTask, FswTask, ActuatorTask,
                                 PlantInputTask, MetricsTask, EventTask, MagnetometerTask, MagnetorquerTask, MtqStateTask>,
              "a task with state of its own (non-const operator()) needs state_io, called by Run::state_io");

constexpr Slot kTickProtocol[] = {
    {"events", Group::EveryTick},
    {"truth", Group::TruthReaders},      {"mtq_state", Group::Record},
    {"burn_monitor", Group::EveryTick},  {"sample_sensors", Group::EveryTick},
    {"magnetometer", Group::EveryTick},  {"css", Group::Fsw},
    {"sensors", Group::Fsw},             {"fsw_acs", Group::Fsw},
    {"actuators", Group::Fsw},           {"plant_input", Group::Fsw},
    {"magnetorquers", Group::Fsw},       {"metrics", Group::Record},
    {"recorder", Group::Record},
};

}  // namespace

struct Run::Impl {
  Scenario sc;
  bool accept_events = false;  // RunConfig::accept_events
  EnvEffectors env{};  // filled by build_plant (before plant_owner)
  SettableParts mag{};  // likewise
  std::optional<SunSource> sun;  // the run's Sun (TruthTask: illumination)
  std::unique_ptr<sim::Plant> plant_owner;
  sim::Plant& plant;
  FswSetup fsw_setup;
  std::unique_ptr<FswEndpoint> fsw;
  std::unique_ptr<SensorSuite> sensors;
  Scheduler sched;
  DataFlow flow;
  Recorder rec{"telemetry"};
  size_t n_truth_sources = 0;  // callers' truth sources (Python sensors): state outside the run
  std::optional<MemorySink> mem;
  uint64_t tick = 0;
  uint64_t n_ticks = 0;
  std::string failure;
  int64_t substep_ns = 0;           // plant step: dt / rates.plant_substeps
  std::vector<int> jitter_wheels;   // wheels whose imbalance makes jitter
  double max_jitter_Omega = 0.0;    // [rad/s] largest |Omega| of those at a tick
  uint64_t plant_ns = 0;            // [ns] plant steps while profiling (set_profiling)

  // tasks (optional ones absent when the run does not need them)
  std::optional<TruthTask> truth;
  std::optional<BurnMonitor> burn;
  std::optional<SampleSensorsTask> sample;
  std::optional<CssTask> css;
  std::optional<FswInputTask> fsw_input;
  std::optional<FswTask> fsw_task;
  std::optional<ActuatorTask> actuators;
  std::optional<PlantInputTask> plant_input;
  std::optional<MetricsTask> metrics;
  std::optional<EventTask> events;  // scenarios with events only
  std::optional<MagnetometerTask> magnetometer;  // sensors.magnetometer only
  std::optional<MagnetorquerTask> magnetorquers;  // magnetorquers only
  std::optional<MtqStateTask> mtq_state;          // magnetorquers only

  Channel<TruthMsg>* truth_ch = nullptr;
  Channel<FswAcsHealthMsg>* health_ch = nullptr;

  // The messages of the data flow (optional ones null when the run does not
  // need them).
  struct Messages {
    Channel<TruthMsg>* truth = nullptr;
    Channel<FswAcsSensorMsg>* sens = nullptr;
    Channel<FswAcsActuatorMsg>* act = nullptr;
    Channel<FswAcsHealthMsg>* health = nullptr;
    Channel<PlantCmdMsg>* cmd = nullptr;
    Channel<MetricsMsg>* metrics = nullptr;
    Channel<SunHeadingMsg>* sun = nullptr;
    Channel<BurnStateMsg>* burn = nullptr;
    Channel<SensorSampleMsg>* samples = nullptr;
    Channel<CssMsg>* css = nullptr;
    Channel<MtqCmdMsg>* mtq_cmd = nullptr;
    Channel<MtqStateMsg>* mtq_state = nullptr;
    Channel<MagnetometerMsg>* mag = nullptr;
    Channel<FswAcsCmdMsg>* fsw_cmd = nullptr;  // runs that take FSW commands
  };
  Channel<MtqCmdMsg>* mtq_cmd_ch = nullptr;  // events write it (until the FSW commands the rods)
  Channel<FswAcsCmdMsg>* fsw_cmd_ch = nullptr;  // events write it (runs that take FSW commands)

  explicit Impl(const Scenario& s)
      : sc(s), plant_owner(build_plant(s, &env, &mag)), plant(*plant_owner), sched(s.tick_ns())
  {
  }
  void wire(RunConfig& cfg);
  void build_fsw(RunConfig& cfg);
  Messages add_messages(bool fsw_commands);
  FswAcsCmdMsg initial_command() const;
  void add_tasks(const Messages& m);
  void add_magnetic_tasks(const Messages& m);
  void add_recorder(const Messages& m);
  void add_events();
  void schedule(const RateGroup& fsw_group, const RateGroup& rec_group);
  bool step_plant();
};

// The run in named steps: the FSW and the sensors, the messages, the tasks,
// the recorder, the events and the tick protocol's schedule.
void Run::Impl::wire(RunConfig& cfg)
{
  n_ticks = sc.num_ticks();
  substep_ns = static_cast<int64_t>(sc.tick_ns() / sc.rates.plant_substeps);  // exact (checked at load)
  for (size_t i = 0; i < sc.wheels.size(); ++i)
    if (wheel_jitters(sc.wheels[i].params)) jitter_wheels.push_back(static_cast<int>(i));
  accept_events = cfg.accept_events;
  build_fsw(cfg);
  // FSW commands come from the events: the scenario's, or the live view's
  // and Python's (accept_events); the message exists only then, so a run
  // without them has the data flow it always had
  const bool fsw_commands = fsw->accepts_commands() && (cfg.accept_events || commands_fsw(sc));
  const Messages m = add_messages(fsw_commands);
  add_tasks(m);
  add_recorder(m);
  for (RunConfig::TruthSource& x : cfg.truth_sources) {  // e.g. Python sensors
    ++n_truth_sources;
    const Channel<TruthMsg>* truth = m.truth;
    auto fill = std::move(x.fill);
    rec.add_source(x.group, x.quantities, [this, truth, fill](double* o) { fill(sched.t_ns(tick), truth->value(), o); });
  }
  const RateGroup fsw_group{"fsw", sc.rates.fsw_divisor, sc.rates.fsw_offset};
  const RateGroup rec_group{"record", sc.rates.record_divisor, 0};
  if (!sc.events.empty() || cfg.accept_events) add_events();
  schedule(fsw_group, rec_group);
  // rows: every due tick in [0, n_ticks] (the final tick is sampled too)
  rec.allocate(rec_group.count_due(n_ticks + 1), cfg.chunk_rows);
  if (cfg.keep_in_memory) {
    mem.emplace();
    rec.add_sink(*mem);
  }
}

// The FSW's configuration, its endpoint (RunConfig's, else in process) and
// the sensor models.
void Run::Impl::build_fsw(RunConfig& cfg)
{
  fsw_setup = make_fsw_setup(sc, plant.mass_props());
  if (cfg.fsw) {
    fsw = std::move(cfg.fsw);
  } else {
    try {
      fsw = std::make_unique<InProcessFsw>(fsw_setup.cfg);
    } catch (const std::invalid_argument& e) {
      throw config_error(sc, "fsw", e.what());
    }
  }
  sensors = std::make_unique<SensorSuite>(sc, fsw_setup, plant, mag.effector);
}

// The command in force before any event: the configuration's mode,
// actuation, reference and gains (a set command changes one field of them).
FswAcsCmdMsg Run::Impl::initial_command() const
{
  FswAcsCmdMsg c{};
  c.mode = fsw_setup.cfg.initial_mode;
  c.actuation = fsw_setup.cfg.initial_actuation;
  for (int a = 0; a < 3; ++a) c.sigma_R0N[a] = fsw_setup.cfg.inertial.sigma_R0N[a];
  c.K = fsw_setup.cfg.mrp_fb.K;
  c.P = fsw_setup.cfg.mrp_fb.P;
  return c;
}

Run::Impl::Messages Run::Impl::add_messages(bool fsw_commands)
{
  DataFlow& f = flow;
  f.add_component("plant", "sim::Plant");
  f.add_component("sensors", "FSW input: sampled sensor outputs (truth where a sensor is disabled)");
  f.add_component("fsw_acs", fsw->describe());
  f.add_component("actuators", "harness: FSW actuator message -> plant commands");
  Messages m;
  m.truth = &f.add_message<TruthMsg>("truth");
  m.sens = &f.add_message<FswAcsSensorMsg>("fsw_sensors");
  m.act = &f.add_message<FswAcsActuatorMsg>("fsw_actuators");
  m.health = &f.add_message<FswAcsHealthMsg>("fsw_health");
  m.cmd = &f.add_message<PlantCmdMsg>("plant_cmd");
  m.metrics = &f.add_message<MetricsMsg>("metrics");
  if (sc.fsw.mode == FswMode::SunSafe) m.sun = &f.add_message<SunHeadingMsg>("sun_heading");
  if (plant.num_thr() > 0) m.burn = &f.add_message<BurnStateMsg>("burn_state");
  if (sensors->has_sampled_models()) m.samples = &f.add_message<SensorSampleMsg>("sensor_samples");
  if (sensors->has_css_models()) m.css = &f.add_message<CssMsg>("css_readings");
  if (mag.effector && mag.effector->num_rods() > 0) {
    m.mtq_cmd = &f.add_message<MtqCmdMsg>("mtq_cmd");
    m.mtq_state = &f.add_message<MtqStateMsg>("mtq_state");
  }
  if (sensors->has_magnetometer()) m.mag = &f.add_message<MagnetometerMsg>("magnetometer");
  if (fsw_commands) {
    m.fsw_cmd = &f.add_message<FswAcsCmdMsg>("fsw_cmd");
    m.fsw_cmd->write(initial_command(), 0);  // in force from the start (not handed to the FSW)
  }
  truth_ch = m.truth;
  mtq_cmd_ch = m.mtq_cmd;
  fsw_cmd_ch = m.fsw_cmd;
  health_ch = m.health;
  return m;
}

void Run::Impl::add_tasks(const Messages& m)
{
  DataFlow& f = flow;
  const uint64_t tk = sc.tick_ns();
  sun.emplace(sc);
  truth.emplace(TruthTask{&plant, tk, f.writer("plant", *m.truth), env, &*sun});
  const BurnSchedule burn_sched = burn_schedule(sc, plant);
  if (m.burn) {
    f.add_component("burn_monitor", "harness");
    const double F_eng = burn_sched.engine >= 0 ? sc.thrusters[static_cast<size_t>(burn_sched.engine)].F_max : 0.0;
    burn.emplace(&plant, tk, sc.rates.dt, sc.environment.mu, burn_sched, F_eng, f.reader("burn_monitor", *m.truth),
                 f.writer("burn_monitor", *m.burn));
  }
  if (m.samples) {
    f.add_component("sample_sensors", "sim::Gyro, sim::StarTracker, sim::WheelTachometers on the plant's sensor truth");
    sample.emplace(SampleSensorsTask{sensors.get(), tk, f.writer("sample_sensors", *m.samples)});
  }
  if (m.css) {
    f.add_component("css", "sim::CoarseSunSensor on the plant's sensor truth");
    css.emplace(CssTask{sensors.get(), tk, f.writer("css", *m.css)});
  }
  fsw_input.emplace(FswInputTask{sensors.get(), tk, f.reader("sensors", *m.truth),
                                 m.samples ? f.reader("sensors", *m.samples) : Reader<SensorSampleMsg>(),
                                 m.css ? f.reader("sensors", *m.css) : Reader<CssMsg>(),
                                 m.mag && sensors->fsw_reads_magnetometer() ? f.reader("sensors", *m.mag)
                                                                            : Reader<MagnetometerMsg>(),
                                 f.writer("sensors", *m.sens)});
  fsw_task.emplace(FswTask{fsw.get(), tk, f.reader("fsw_acs", *m.sens), f.writer("fsw_acs", *m.act),
                           f.writer("fsw_acs", *m.health),
                           m.sun ? f.writer("fsw_acs", *m.sun) : Writer<SunHeadingMsg>(), m.sun != nullptr,
                           m.fsw_cmd ? f.reader("fsw_acs", *m.fsw_cmd) : Reader<FswAcsCmdMsg>(),
                           m.fsw_cmd ? m.fsw_cmd->write_count() : 0});
  const bool fsw_rods = sc.fsw.mtq && m.mtq_cmd;  // the FSW commands the rods: it writes `mtq_cmd`
  actuators.emplace(ActuatorTask{tk, plant.num_rw(), plant.num_thr(), fsw_setup.n_acs, fsw_setup.acs_to_plant,
                                 burn_sched, f.reader("actuators", *m.act), f.writer("actuators", *m.cmd),
                                 fsw_rods ? fsw_setup.cfg.mtq_map.num_mtq : 0,
                                 fsw_rods ? f.writer("actuators", *m.mtq_cmd) : Writer<MtqCmdMsg>()});
  plant_input.emplace(PlantInputTask{&plant, f.reader("plant", *m.cmd)});
  f.add_component("metrics", "harness");
  add_magnetic_tasks(m);
  metrics.emplace(&plant, tk, configured_reference(sc.fsw), sc.fsw.sigma_R0N, sc.fsw.sun_axis_B, sc,
                  sc.environment.mu, f.reader("metrics", *m.truth),
                  m.burn ? f.reader("metrics", *m.burn) : Reader<BurnStateMsg>(), m.burn != nullptr,
                  f.writer("metrics", *m.metrics));
  if (m.fsw_cmd) {
    metrics->cmd = f.reader("metrics", *m.fsw_cmd);
    metrics->cmd_seen = m.fsw_cmd->write_count();
  }
  metrics->frame = sc.fsw.orbit_frame;
  metrics->sigma_BdR = sc.fsw.sigma_BdR;
}

// The magnetometer and the magnetorquers (environment.magnetic, docs/environment.md).
void Run::Impl::add_magnetic_tasks(const Messages& m)
{
  DataFlow& f = flow;
  const uint64_t tk = sc.tick_ns();
  if (m.mag) {
    f.add_component("magnetometer", "sim::Magnetometer on the field model and the rods' dipoles");
    magnetometer.emplace(MagnetometerTask{sensors.get(), tk, f.writer("magnetometer", *m.mag)});
  }
  if (m.mtq_cmd) {
    f.add_component("magnetorquers", mag.pwm ? "harness: dipole commands -> PWM drive of the rods"
                                             : "harness: dipole commands -> the rods (sim::MagneticEffector)");
    magnetorquers.emplace(MagnetorquerTask{mag.effector, mag.pwm, tk, f.reader("magnetorquers", *m.mtq_cmd)});
    mtq_state.emplace(MtqStateTask{mag.effector, tk, f.writer("plant", *m.mtq_state)});
  }
}

void Run::Impl::add_recorder(const Messages& m)
{
  DataFlow& f = flow;
  f.add_component("recorder", "harness: recorded columns -> sinks");
  RecordedChannels rc;
  rc.truth = &f.reader("recorder", *m.truth).channel();
  rc.metrics = &f.reader("recorder", *m.metrics).channel();
  rc.fsw_sensors = &f.reader("recorder", *m.sens).channel();
  rc.fsw_actuators = &f.reader("recorder", *m.act).channel();
  rc.fsw_health = &f.reader("recorder", *m.health).channel();
  if (plant.num_thr() > 0) rc.plant_cmd = &f.reader("recorder", *m.cmd).channel();
  if (m.sun) rc.sun_heading = &f.reader("recorder", *m.sun).channel();
  std::array<bool, kNumEnvSources> env_on{};
  for (size_t s = 0; s < env_on.size(); ++s) env_on[s] = env[s] != nullptr;
  declare_telemetry(rec, rc, plant.num_rw(), plant.num_thr(), sc.environment.mu > 0.0,
                    [this] { return sched.t_ns(tick); });
  declare_disturbances(rec, rc, env_on);
  if (m.mtq_state) {
    const int n = mag.effector->num_rods();
    declare_magnetorquers(rec, f.reader("recorder", *m.mtq_state).channel(), n);
  }
  if (m.mag) declare_magnetometer(rec, f.reader("recorder", *m.mag).channel());
  const FswSpec& fs = sc.fsw;
  if (fs.mtq || fs.policy != MomentumPolicy::None || fs.rw_bias || fs.mode == FswMode::Nadir)
    declare_fsw_momentum(rec, rc);
  declare_environment_truth(rec, rc, env_on, sun->dated(), plant.num_rw());
}

void Run::Impl::add_events()
{
  flow.add_component("events", "harness: scenario events (docs/events.md) -> plant devices, sensor faults, FSW input");
  // the commands start from the configuration's and go to `fsw_cmd`
  events.emplace(sc, plant, *sensors, rec, *fsw, initial_command(),
                 fsw_cmd_ch ? flow.writer("events", *fsw_cmd_ch) : Writer<FswAcsCmdMsg>());
  // rod faults act on the rods; dipole commands are the events' only when
  // the flight software does not command the rods
  if (mtq_cmd_ch)
    events->attach_magnetorquers(mag.effector,
                                 sc.fsw.mtq ? Writer<MtqCmdMsg>() : flow.writer("events", *mtq_cmd_ch));
  if (mag.drag) events->attach_atmosphere(mag.drag, sc.environment.drag_density_scale);
}

// The tick protocol's table: each task the run has, in its rate groups.
void Run::Impl::schedule(const RateGroup& fsw_group, const RateGroup& rec_group)
{
  const RateGroup every{"every_tick", 1, 0};
  auto fn_of = [this](const std::string& name) -> Scheduler::TaskFn {
    if (name == "events" && events) return [t = &*events](uint64_t k) { (*t)(k); };
    if (name == "truth") return [t = &*truth](uint64_t k) { (*t)(k); };
    if (name == "burn_monitor" && burn) return [t = &*burn](uint64_t k) { (*t)(k); };
    if (name == "sample_sensors" && sample) return [t = &*sample](uint64_t k) { (*t)(k); };
    if (name == "magnetometer" && magnetometer) return [t = &*magnetometer](uint64_t k) { (*t)(k); };
    if (name == "magnetorquers" && magnetorquers) return [t = &*magnetorquers](uint64_t k) { (*t)(k); };
    if (name == "mtq_state" && mtq_state) return [t = &*mtq_state](uint64_t k) { (*t)(k); };
    if (name == "css" && css) return [t = &*css](uint64_t k) { (*t)(k); };
    if (name == "sensors") return [t = &*fsw_input](uint64_t k) { (*t)(k); };
    if (name == "fsw_acs") return [t = &*fsw_task](uint64_t k) { (*t)(k); };
    if (name == "actuators") return [t = &*actuators](uint64_t k) { (*t)(k); };
    if (name == "plant_input") return [t = &*plant_input](uint64_t k) { (*t)(k); };
    if (name == "metrics") return [t = &*metrics](uint64_t k) { (*t)(k); };
    if (name == "recorder") return [r = &rec](uint64_t) { r->sample(); };
    return nullptr;
  };
  for (const Slot& s : kTickProtocol) {
    Scheduler::TaskFn fn = fn_of(s.task);
    if (!fn) continue;
    std::vector<RateGroup> g;
    if (s.group == Group::EveryTick || (s.group == Group::TruthReaders && burn)) g = {every};
    else if (s.group == Group::TruthReaders) g = {fsw_group, rec_group};
    else g = {s.group == Group::Fsw ? fsw_group : rec_group};
    sched.add_task(s.task, std::move(g), std::move(fn));
  }
}

FswAcsConfig fsw_acs_config_of(const Scenario& sc)
{
  return make_fsw_setup(sc, build_plant(sc)->mass_props()).cfg;
}

Run::Run(const Scenario& sc, RunConfig cfg) : impl_(std::make_unique<Impl>(sc)) { impl_->wire(cfg); }

Run::~Run() = default;

void Run::add_sink(RecordSink& sink)
{
  if (impl_->tick > 0) throw std::logic_error("Run::add_sink: the run has started");
  impl_->rec.add_sink(sink);
}

// The plant over one tick: rates.plant_substeps steps of dt / n (docs/harness.md).
bool Run::Impl::step_plant()
{
  for (int i : jitter_wheels) max_jitter_Omega = std::max(max_jitter_Omega, std::fabs(plant.Omega(i)));
  const bool timed = sched.profiling();
  const auto t0 = timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  bool ok = true;
  for (uint32_t s = 0; s < sc.rates.plant_substeps && ok; ++s) ok = plant.step(substep_ns) == sim::StepStatus::Ok;
  if (timed)
    plant_ns += static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
  return ok;
}

bool wheel_jitters(const sim::ReactionWheelParams& p)
{
  return p.model != sim::WheelModel::Balanced && (p.U_s > 0.0 || p.U_d > 0.0);
}

uint32_t substeps_for(double Omega_abs, double dt)
{
  const double n = std::ceil(Omega_abs * dt / kJitterStepLimit);
  return n < 1.0 ? 1u : n > 1e9 ? 1000000000u : static_cast<uint32_t>(n);
}

std::vector<std::string> jitter_step_warnings(const Scenario& sc)
{
  std::vector<std::string> out;
  const double h = sc.rates.dt / sc.rates.plant_substeps;
  for (size_t i = 0; i < sc.wheels.size(); ++i) {
    const sim::ReactionWheelParams& p = sc.wheels[i].params;
    const double step = std::fabs(p.Omega_0) * h;
    if (!wheel_jitters(p) || !(step > kJitterStepLimit)) continue;
    std::ostringstream w;
    w.precision(3);
    w << "wheels[" << i << "] (" << sc.wheels[i].name << "): its imbalance jitter is under-resolved: |Omega_0| h = "
      << step << " rad per plant step (h = " << h << " s) > " << kJitterStepLimit
      << " rad; rates.plant_substeps: " << substeps_for(std::fabs(p.Omega_0), sc.rates.dt)
      << " or more keeps it within (docs/performance.md)";
    out.push_back(w.str());
  }
  return out;
}

std::string jitter_reached_warning(double max_step)
{
  std::ostringstream w;
  w.precision(3);
  w << "a jittering wheel reached |Omega| h = " << max_step << " rad per plant step (> " << kJitterStepLimit
    << "): its imbalance jitter is under-resolved; raise rates.plant_substeps (docs/performance.md)";
  return w.str();
}

bool Run::step_ticks(uint64_t n)
{
  Impl& m = *impl_;
  if (!m.failure.empty()) return false;
  // an error of a part outside the run's own code stops the run at this tick, rows kept
  const auto fail = [&](const char* who, const std::exception& e) {
    m.failure = std::string(who) + "at t = " + std::to_string(static_cast<double>(m.sched.t_ns(m.tick)) * 1e-9) +
                " s: " + e.what();
    finish();
    return false;
  };
  for (uint64_t i = 0; i < n && m.tick <= m.n_ticks; ++i) {
    try {
      m.sched.run_tick(m.tick);
    } catch (const FswEndpointError& e) {  // e.g. a remote FSW endpoint's link
      return fail("FSW endpoint ", e);
    } catch (const InLoopError& e) {  // e.g. a Python sensor at a recorded row
      return fail("", e);
    }
    if (m.rec.overflow() > 0) {
      m.failure = "recorder overflow at tick " + std::to_string(m.tick) + " (internal error)";
      finish();
      return false;
    }
    if (m.tick < m.n_ticks) {
      bool stepped = false;
      try {
        stepped = m.step_plant();
      } catch (const InLoopError& e) {  // e.g. a Python effector (docs/python.md)
        return fail("plant ", e);
      }
      if (!stepped) {
        m.failure = "plant state became non-finite at t = " +
                    std::to_string(static_cast<double>(m.sched.t_ns(m.tick)) * 1e-9) + " s";
        ++m.tick;
        finish();
        return false;
      }
    }
    ++m.tick;
  }
  if (m.tick > m.n_ticks) finish();  // the last row reaches the sinks
  return true;
}

void Run::finish() { impl_->rec.finish(impl_->failure.empty() && impl_->tick > impl_->n_ticks); }
bool Run::done() const { return impl_->tick > impl_->n_ticks || !impl_->failure.empty(); }
uint64_t Run::tick() const { return impl_->tick; }
uint64_t Run::total_ticks() const { return impl_->n_ticks + 1; }
const std::string& Run::failure() const { return impl_->failure; }
const Scenario& Run::scenario() const { return impl_->sc; }
const Recorder& Run::recorder() const { return impl_->rec; }
const DataFlow& Run::dataflow() const { return impl_->flow; }
const Scheduler& Run::scheduler() const { return impl_->sched; }
sim::Plant& Run::plant() { return impl_->plant; }
const sim::Plant& Run::plant() const { return impl_->plant; }

void Run::add_event(const EventSpec& e)
{
  Impl& m = *impl_;
  if (!m.events) throw std::logic_error("Run::add_event: the run was built without RunConfig::accept_events");
  m.sc.events.push_back(e);
  try {
    m.events->add();
  } catch (...) {
    m.sc.events.pop_back();
    throw;
  }
}

bool Run::fsw_accepts_commands() const { return impl_->fsw->accepts_commands(); }

bool Run::accepts_events() const { return impl_->accept_events; }

std::array<double, 2> Run::fsw_gains() const
{
  const Impl& m = *impl_;
  if (m.events) return {static_cast<double>(m.events->command().K), static_cast<double>(m.events->command().P)};
  return {static_cast<double>(m.fsw_setup.cfg.mrp_fb.K), static_cast<double>(m.fsw_setup.cfg.mrp_fb.P)};
}

const std::vector<AppliedEvent>& Run::events_applied() const
{
  static const std::vector<AppliedEvent> kNone;
  return impl_->events ? impl_->events->log() : kNone;
}

const MemorySink& Run::memory() const
{
  if (!impl_->mem) throw std::logic_error("Run::memory: this run does not keep its rows in memory");
  return *impl_->mem;
}

double Run::final_pointing_error_deg() const
{
  const double* row = impl_->rec.last_row();
  return row ? row[impl_->rec.column_index("pointing_error_deg")] : std::numeric_limits<double>::quiet_NaN();
}

PointingReference Run::final_pointing_reference() const { return impl_->metrics->ref; }
bool Run::pointing_reference_commanded() const { return impl_->metrics->ref_commanded; }

const char* describe(PointingReference r)
{
  switch (r) {
    case PointingReference::Inertial: return "principal angle from the inertial reference";
    case PointingReference::SunAxis: return "Sun-axis angle";
    case PointingReference::OrbitFrame: return "principal angle from the orbit-frame reference";
  }
  return "?";
}

std::vector<std::array<double, 3>> Run::wheel_axes_B() const
{
  std::vector<std::array<double, 3>> out;
  for (const WheelSpec& w : impl_->sc.wheels)
    out.push_back({w.params.gs_hat_nom_B(0), w.params.gs_hat_nom_B(1), w.params.gs_hat_nom_B(2)});
  return out;
}

std::vector<std::string> Run::fsw_health_lines() const
{
  std::vector<std::string> out = fsw_health_summary(impl_->health_ch->value());
  for (std::string& l : impl_->fsw->module_health_lines()) out.push_back(std::move(l));
  return out;
}

void Run::set_profiling(bool on) { impl_->sched.set_profiling(on); }

std::string Run::checkpoint_refusal() const
{
  const Impl& m = *impl_;
  if (!m.failure.empty()) return "the run failed: " + m.failure;
  if (m.tick > m.n_ticks) return "the run has ended";
  if (!m.fsw->checkpointable())
    return "the flight software (" + m.fsw->describe() + ") keeps state the harness cannot save";
  if (m.n_truth_sources > 0) return "sensors of the caller's own (Python) are in the loop: their state is not the harness's to save";
  return "";
}

void Run::state_io(sim::StateIO& io)
{
  Impl& m = *impl_;
  if (!io.loading()) {
    const std::string why = checkpoint_refusal();
    if (!why.empty()) throw std::logic_error("checkpoint: " + why);
  }
  if (io.loading() && m.tick != 0) throw std::logic_error("checkpoint: restore into a run that has not started");
  uint64_t n_ticks = m.n_ticks;
  io.value("run.num_ticks", n_ticks);
  if (n_ticks != m.n_ticks) throw std::runtime_error("checkpoint: the run has another number of ticks");
  io.value("run.tick", m.tick);
  io.value("run.max_jitter_Omega", m.max_jitter_Omega);
  m.plant.state_io(io);
  m.fsw->state_io(io);
  m.sensors->state_io(io);
  m.flow.state_io(io);
  m.rec.state_io(io);
  if (m.burn) m.burn->state_io(io);
  m.fsw_task->state_io(io);
  m.metrics->state_io(io);
  if (m.events) m.events->state_io(io);
}

std::vector<std::pair<std::string, uint64_t>> Run::profile() const
{
  const Impl& m = *impl_;
  std::vector<std::pair<std::string, uint64_t>> out;
  for (size_t i = 0; i < m.sched.num_tasks(); ++i) out.emplace_back(m.sched.task_name(i), m.sched.elapsed_ns(i));
  out.emplace_back("plant", m.plant_ns);
  return out;
}

double Run::max_jitter_step() const
{
  return impl_->max_jitter_Omega * static_cast<double>(impl_->substep_ns) * 1e-9;
}

// The burn's figures of the summary: start and end, the delivered delta-v
// against the rocket equation, the orbit at burn start (mu > 0).
static void burn_summary(const BurnMonitor& bm, const Scenario& sc, double mu, int num_tanks, double max_err_burn,
                         std::vector<SummaryItem>& out)
{
  if (bm.burn.engine >= 0 && bm.start.set) {
    const BurnMonitor::Snap& a = bm.start;
    const bool ended = bm.end.set;
    const BurnMonitor::Snap& b = ended ? bm.end : a;
    const ThrusterSpec& eng = sc.thrusters[static_cast<size_t>(bm.burn.engine)];
    out.push_back({"burn_start_s", a.t, "s", "engine open (first command instant at or after burn.start)"});
    out.push_back({"burn_end_s", ended ? b.t : std::numeric_limits<double>::quiet_NaN(), "s",
                   "engine closed and its thrust below 1e-3 F_max"});
    out.push_back({"burn_complete", ended ? 1.0 : 0.0, "-", "1 if the burn ended before the end of the run"});
    out.push_back({"max_pointing_error_burn_deg", max_err_burn * kRadToDeg, "deg",
                   "largest recorded pointing error between burn start and end"});
    if (ended) {
      const double m0 = a.m, m1 = b.m;
      // propellant of the engine's tank (tank 0); with rcs_tank the ACS
      // thrusters draw from tank 1, so tank 0 is the engine's alone
      const double dm_main = a.m_p[0] - b.m_p[0];
      const double dm_rcs = num_tanks > 1 ? a.m_p[1] - b.m_p[1] : 0.0;
      const double dv = (b.dv_ng - a.dv_ng).norm();
      const double ve = sim::kG0 * eng.Isp;
      const double dm_rocket = m0 * (1.0 - std::exp(-dv / ve));
      out.push_back({"mass_before_burn_kg", m0, "kg", "total mass at burn start"});
      out.push_back({"mass_after_burn_kg", m1, "kg", "total mass at burn end"});
      out.push_back({"propellant_engine_kg", dm_main, "kg", "tank 0 propellant used during the burn"});
      out.push_back({"propellant_rcs_burn_kg", dm_rcs, "kg", "rcs_tank propellant used during the burn"});
      out.push_back({"dv_nongrav_mps", dv, "m/s",
                     "|v_C(end) - v_C(start) - integral of gravity|: the delivered (sensed) delta-v"});
      out.push_back({"dv_rocket_mps", ve * std::log(m0 / (m0 - dm_main)), "m/s",
                     "g0 Isp ln(m0 / (m0 - engine propellant)): rocket equation"});
      out.push_back({"propellant_rocket_kg", dm_rocket, "kg", "m0 (1 - exp(-dv_nongrav / (g0 Isp)))"});
      out.push_back({"propellant_vs_rocket_rel", dm_main / dm_rocket - 1.0, "-",
                     "engine propellant / rocket-equation propellant - 1"});
    }
    if (mu > 0.0) {
      const sim::OrbitElements o0 = sim::elements_from_rv(mu, a.r, a.v);
      out.push_back({"orbit_before_e", o0.e, "-", "osculating eccentricity at burn start"});
      out.push_back({"orbit_before_r_p_km", o0.r_p * 1e-3, "km", "periapsis radius at burn start"});
    }
  }
}

std::vector<SummaryItem> Run::summary() const
{
  const Impl& m = *impl_;
  std::vector<SummaryItem> out;
  if (m.rec.rows() > 0)  // after a commanded change, it says which reference it is measured from
    out.push_back({"final_pointing_error_deg", final_pointing_error_deg(), "deg",
                   m.metrics->ref_commanded ? std::string(describe(m.metrics->ref)) +
                                                  " at the end of the run (a command changed the reference during the run)"
                                            : std::string("pointing error at the end of the run")});
  if (!m.jitter_wheels.empty())
    out.push_back({"max_jitter_step_rad", max_jitter_step(), "rad",
                   "largest |Omega| h of a jittering wheel (under-resolved above " +
                       std::to_string(static_cast<int>(kJitterStepLimit)) + ": docs/performance.md)"});
  if (m.plant.num_thr() == 0) return out;
  double used = 0.0;
  for (int k = 0; k < m.plant.num_tanks(); ++k) used += m.plant.tanks()[static_cast<size_t>(k)].m_p0 - m.plant.m_prop(k);
  out.push_back({"propellant_used_kg", used, "kg", "all tanks, whole run"});
  double on_total = 0.0;
  for (int j = 0; j < m.plant.num_thr(); ++j) {
    const double on = m.plant.thrusters().valve_open_time(j);
    on_total += on;
    out.push_back({"on_time_" + m.sc.thrusters[static_cast<size_t>(j)].name + "_s", on, "s",
                   "valve-open time, whole run (every latched pulse, exact)"});
  }
  out.push_back({"on_time_total_s", on_total, "s", "valve-open time of all thrusters, whole run"});
  const double mu = m.sc.environment.mu;
  burn_summary(*m.burn, m.sc, mu, m.plant.num_tanks(), m.metrics->max_err_burn, out);
  if (mu > 0.0) {
    const TruthMsg& t = m.truth_ch->value();  // the last tick run
    const Eigen::Vector3d r(t.r_CN_N[0], t.r_CN_N[1], t.r_CN_N[2]), v(t.v_CN_N[0], t.v_CN_N[1], t.v_CN_N[2]);
    const sim::OrbitElements o = sim::elements_from_rv(mu, r, v);
    out.push_back({"orbit_after_e", o.e, "-", "osculating eccentricity at the end of the run"});
    out.push_back({"orbit_after_r_p_km", o.r_p * 1e-3, "km", "periapsis radius"});
    out.push_back({"orbit_after_r_a_km", o.e < 1.0 ? o.r_a * 1e-3 : std::numeric_limits<double>::quiet_NaN(), "km",
                   "apoapsis radius (NaN: not captured)"});
    out.push_back({"orbit_after_period_h",
                   o.e < 1.0 ? 2.0 * sim::kPi * std::sqrt(o.a * o.a * o.a / mu) / 3600.0
                             : std::numeric_limits<double>::quiet_NaN(),
                   "h", "orbital period (NaN: not captured)"});
    out.push_back({"captured", o.e < 1.0 ? 1.0 : 0.0, "-", "1 if the orbit after the run is an ellipse"});
  }
  return out;
}

}  // namespace harness
