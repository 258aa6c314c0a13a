// run_wiring.cpp: a run's parts wired together (Run::Impl, run_impl.h):
// the FSW and the sensors, the messages of the data flow, the tasks, the
// recorder's columns and the events.  The tick protocol's schedule and the
// stepping are in run.cpp.
#include <stdexcept>
#include <utility>

#include "core/build_error.h"
#include "core/run_impl.h"
#include "core/telemetry_columns.h"

namespace harness {

namespace {

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

}  // namespace

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
  sensors = std::make_unique<SensorSuite>(sc, fsw_setup, plant, sun, mag.effector);
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
  truth.emplace(TruthTask{&plant, tk, f.writer("plant", *m.truth), env, &sun});
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
  metrics.emplace(&plant, tk, configured_reference(sc.fsw), sc.fsw.sigma_R0N, sc.fsw.sun_axis_B, &sun,
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
  declare_environment_truth(rec, rc, env_on, sun.dated(), plant.num_rw());
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

}  // namespace harness
