// scenario_types: the typed scenario a run is built from (harness_core).
// Values are SI.  Reading a scenario from YAML or a manifest, writing it back
// and setting keys by path are the scenario room's (harness/scenario/
// scenario.h); a Run needs only these types.
#ifndef HARNESS_CORE_SCENARIO_TYPES_H
#define HARNESS_CORE_SCENARIO_TYPES_H

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "sim/earth_time.h"
#include "sim/reaction_wheel.h"
#include "sim/spacecraft.h"
#include "sim/surface_forces.h"

namespace harness {

struct ScenarioIssue {
  std::string file;
  int line = 0;        // 1-based; 0 when the location is not in the file (--set)
  int column = 0;      // 1-based
  std::string key;     // dotted path, e.g. wheels[2].J_s
  std::string message;
  std::string where;   // "--set key=value" when the value came from the command line
  std::string str() const;  // "file:line:col: key: message"
};

// `s` with NUL, every other control byte and invalid UTF-8 shown as \xNN,
// and the valid characters that would hide or reorder text (C1 controls,
// bidirectional marks, embeddings, overrides and isolates, zero-width
// characters, the byte-order mark, line and paragraph separators) as
// \uXXXX: what a message quotes from a file or a command line is printable
// on one line and reads as it is stored.  Every message that quotes user
// text goes through it.
std::string escape_bytes(const std::string& s);

class ScenarioError : public std::runtime_error {
 public:
  explicit ScenarioError(std::vector<ScenarioIssue> issues);
  const std::vector<ScenarioIssue>& issues() const { return issues_; }

 private:
  std::vector<ScenarioIssue> issues_;
};

enum class FswMode { Inertial, SunSafe, Detumble, Nadir };
enum class BdotLaw { Derivative, Gyro };
enum class OrbitFrame { Nadir, Velocity };
enum class MomentumPolicy { None, Thrusters, Magnetorquers };
enum class RwMapMode { MinNorm, Power };
enum class ThrPulseMode { Remainder, Schmitt };
enum class ThrTransient { Instant, FirstOrder };
enum class Actuation { Wheels, Thrusters };
enum class ThrMapMode { MinNorm, Nnls };

struct RatesSpec {
  double dt = 0.0;              // [s]     plant step = base tick, whole nanoseconds
  uint32_t fsw_divisor = 1;     // [ticks] FSW period
  uint32_t fsw_offset = 0;      // [ticks] FSW phase, < fsw_divisor
  uint32_t record_divisor = 1;  // [ticks] recording period
  uint32_t thruster_divisor = 1;// [ticks] thruster latch period T_upd
  uint32_t plant_substeps = 1;  // [-]     plant steps per tick (each dt / plant_substeps)
};

struct InitialSpec {
  Eigen::Vector3d sigma_BN = Eigen::Vector3d::Zero();    // [-]
  Eigen::Vector3d omega_BN_B = Eigen::Vector3d::Zero();  // [rad/s]
  Eigen::Vector3d r_CN_N = Eigen::Vector3d::Zero();      // [m]
  Eigen::Vector3d v_CN_N = Eigen::Vector3d::Zero();      // [m/s]
};

struct SpacecraftSpec {
  double mass = 0.0;                                   // [kg]     hub mass
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();   // [kg*m^2] hub inertia about hub CoM
  Eigen::Vector3d r_BcB_B = Eigen::Vector3d::Zero();   // [m]      hub mass centre Bc rel. B (key: com)
  InitialSpec initial;
  std::vector<sim::Facet> facets;                      // surfaces for solar pressure and drag (none: default)
  Eigen::Vector3d residual_dipole_B = Eigen::Vector3d::Zero();  // [A*m^2] residual magnetic dipole, B
};

// An Earth-orbit disturbance model of the plant (sim/environment_effectors.h):
// on or off and the period its environment is evaluated at (0: every RK4
// stage).  Off by default; a run without any has none of the effectors.
struct EnvModelSpec {
  bool enabled = false;
  double period = 1.0;  // [s] >= 0, whole nanoseconds
};

struct EnvironmentSpec {
  double mu = 0.0;                                             // [m^3/s^2]
  Eigen::Vector3d sun_position_N{1.495978707e11, 0.0, 0.0};    // [m]
  std::string epoch;       // UTC of t = 0, "YYYY-MM-DDThh:mm:ss[.s]Z"; "" none
  EnvModelSpec gravity_gradient{false, 0.0};
  EnvModelSpec solar_pressure;
  EnvModelSpec drag;
  double drag_density_scale = 1.0;  // [-] >= 0
  EnvModelSpec magnetic;
  int igrf_degree = 13;             // [-] 1 .. 13
  bool j2 = false;                  // Earth's J2 in the translational gravity (needs Earth's mu)
};

// The disturbance sources of a run, in the order recorded.
enum class EnvSource { GravityGradient = 0, SolarPressure = 1, Drag = 2, Magnetic = 3 };
constexpr int kNumEnvSources = 4;
const char* env_source_name(EnvSource s);  // "gravity_gradient", ...
const EnvModelSpec& env_model(const EnvironmentSpec& e, EnvSource s);
// "YYYY-MM-DDThh:mm:ss[.s]Z" -> the epoch (sim::validate'd: year 1900 .. 2100);
// nullopt with the reason in *why otherwise.
std::optional<sim::UtcEpoch> parse_utc_epoch(const std::string& text, std::string* why);

struct WheelSpec {
  std::string name;
  sim::ReactionWheelParams params;  // SI; gs_hat_nom_B (key: axis) normalised
};

struct ThrusterSpec {
  std::string name;
  Eigen::Vector3d r_TjB_B = Eigen::Vector3d::Zero();  // [m] nozzle Tj rel. B (key: position)
  Eigen::Vector3d t_hat_B = Eigen::Vector3d::UnitZ(); // [-] nominal unit thrust axis (key: direction)
  double F_max = 0.0;                               // [N]
  double Isp = 0.0;                                 // [s]
  double T_min = 0.0;                               // [s]
  double misalignment = 0.0;                        // [rad] truth-only thrust-axis tilt
  ThrTransient transient = ThrTransient::FirstOrder;
  double omega_on = 10.0;                           // [rad/s]
  double omega_off = 10.0;                          // [rad/s]
  bool acs = true;                                  // false: main engine (not mapped by FSW)
};

struct TankSpec {
  double mass = 0.0;                                  // [kg] initial propellant
  Eigen::Vector3d r_TB_B = Eigen::Vector3d::Zero();   // [m]  tank centre T rel. B (key: position)
};

// Main-engine burn: the named (non-ACS) thruster fires continuously from the
// first thruster command instant at or after `start` until start + duration.
struct BurnSpec {
  std::string thruster;   // name of a thruster with acs: false
  double start = 0.0;     // [s]
  double duration = 0.0;  // [s]
};

// A magnetic torque rod (sim::MagnetorquerParams); scenario key `magnetorquers`.
struct MagnetorquerSpec {
  std::string name;                                   // default mtq<i+1>, unique among devices
  Eigen::Vector3d axis_B = Eigen::Vector3d::UnitX();  // [-] unit dipole axis (key: axis)
  double m_max = 0.0;                                 // [A*m^2] saturation dipole, > 0
  double m_remanent = 0.0;                            // [A*m^2] remanent dipole, in [0, m_max)
  double power_max = 0.0;                             // [W] coil power at m_max, >= 0
};

// How the rods follow their dipole commands (key `magnetorquer_drive`).
// Dipole: each rod holds clamp(command, +-m_max) from the control instant.
// Pwm: each rod is driven at sign(command) m_max for duty x pwm_period from
// the control instant (duty = min(|command| / m_max, 1)), then off
// (remanence) for the rest, repeated every pwm_period until the next command.
enum class MtqDriveMode { Dipole, Pwm };
struct MtqDriveSpec {
  MtqDriveMode mode = MtqDriveMode::Dipole;
  double pwm_period = 0.0;  // [s] 0: the FSW period; the FSW period must be a whole number of it
};

struct CssSpec {
  std::vector<Eigen::Vector3d> normals_B;  // [-] unit
  double fov = 80.0 * 3.14159265358979323846 / 180.0;  // [rad] half angle
  double scale = 1.0;                      // [-]
  double noise_std = 0.0;                  // [-]
};

// Gyro, star tracker and wheel tachometers (sim::Gyro, sim::StarTracker,
// sim::WheelTachometers).  enabled: the model's sampled output feeds the
// FSW; false: the FSW gets that quantity ideal (truth at the FSW tick, the
// pre-sensor behaviour).  divisor: sample period in ticks; 0 in a spec being
// built means "follow rates.fsw_divisor" (load_scenario resolves it).
struct StarTrackerSpec {
  bool enabled = true;
  double sigma_cross = 0.0;    // [rad] 1-sigma about case x, y
  double sigma_bore = 0.0;     // [rad] 1-sigma about the boresight (case z = +z_B)
  double sun_exclusion = 0.0;  // [rad] Sun-to-boresight angle below which no valid sample; 0: off
  uint32_t divisor = 0;        // [ticks]
};

struct GyroSpec {
  bool enabled = true;
  double arw = 0.0;   // [rad/sqrt(s)]
  double rrw = 0.0;   // [rad/s^(3/2)]
  double lsb = 0.0;   // [rad/s] quantisation step; 0: off
  uint32_t divisor = 0;  // [ticks]
};

struct TachSpec {
  bool enabled = true;
  double sigma = 0.0;  // [rad/s] white noise 1-sigma
  double lsb = 0.0;    // [rad/s] quantisation step; 0: off
  uint32_t divisor = 0;  // [ticks]
};

// Three-axis magnetometer (sim::Magnetometer); off by default.
struct MagnetometerSpec {
  bool enabled = false;
  Eigen::Matrix3d dcm_SB = Eigen::Matrix3d::Identity();  // [-] sensor axes S from B (rows: x_S, y_S, z_S in B)
  double period = 0.0;                                    // [s] sample period; 0: the FSW period
  // [s] the field model's own period: 0, the field evaluated at every
  // sample; T > 0 (a whole number of sample periods), evaluated every T and
  // extrapolated linearly from the last two evaluations between them
  double field_period = 0.0;
  double sigma = 0.0;                                     // [T] white noise 1-sigma per axis
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();         // [T] S
  Eigen::Vector3d scale_error = Eigen::Vector3d::Zero();  // [-] per axis, each > -1
  double lsb = 0.0;                                       // [T] quantisation step; 0: off
  double range = 0.0;                                     // [T] per-axis saturation; 0: off
  // [T/(A*m^2)] 3 x (number of magnetorquers), B: column j is rod j's field
  // at the sensor per unit dipole; empty: no interference
  Eigen::Matrix<double, 3, Eigen::Dynamic> interference = Eigen::Matrix<double, 3, Eigen::Dynamic>(3, 0);
};

struct SensorsSpec {
  bool noise = true;  // false: every sensor ideal (sim::SensorContext::noise)
  CssSpec css;
  StarTrackerSpec star_tracker;
  GyroSpec gyro;
  TachSpec tachometer;
  MagnetometerSpec magnetometer;
};

struct MrpFbSpec {
  double K = 0.0;               // [N*m]
  double P = 0.0;               // [N*m*s]
  double K_i = -1.0;            // [1/(kg*m^2)] <= 0 disables
  double integral_limit = 0.0;  // [N*m*s]
  int control_law = 0;          // 0 or 1
  std::optional<Eigen::Matrix3d> inertia;  // [kg*m^2] FSW inertia about C; default: plant truth at t0
};

struct FswSpec {
  FswMode mode = FswMode::Inertial;
  Eigen::Vector3d sigma_R0N = Eigen::Vector3d::Zero();        // [-] inertial mode
  Eigen::Vector3d sun_axis_B = Eigen::Vector3d::UnitZ();      // [-] sun-safe mode
  double sun_small_angle = 0.0;                               // [rad]
  double css_lit_threshold = 0.1;                             // [-] css_sun: y_i above this is lit
  Eigen::Vector3d omega_search_B = Eigen::Vector3d::Zero();   // [rad/s]
  MrpFbSpec mrp_fb;
  RwMapMode rw_map = RwMapMode::MinNorm;
  double eps_P = 1.0;                                         // [rad^2/s^2]
  bool rw_null = false;
  double k_null = 0.0;                                        // [N*m*s]
  bool rw_null_scale_to_fit = true;
  std::vector<double> Omega_des;                              // [rad/s] (num_rw)
  // rw_speed_filter ahead of the wheel chain (docs/fsw/rw_speed_filter.md)
  bool speed_filter = false;
  double sf_noise = 0.0;        // [rad/s] outlier-gate margin (required when enabled)
  int sf_k_reject = 3;          // [-] consecutive outliers that fail a wheel
  int sf_n_recover = 3;         // [-] consistent samples that bring it back
  int sf_n_stale = 0;           // [-] repeats of a bit-identical reading that latch it; 0: off
  int sf_n_window = 0;          // [-] FSW cycles per torque-consistency window; 0: off
  double sf_resid_tol = 0.0;    // [rad/s] allowed torque-window residual
  ThrPulseMode thr_pulse = ThrPulseMode::Remainder;
  Actuation actuation = Actuation::Wheels;                    // default: wheels if any, else thrusters
  ThrMapMode thr_map = ThrMapMode::Nnls;
  double thr_t_min = 0.02;                                    // [s] FSW pulser minimum on-time
  double thr_level_on = 0.75;                                 // [-] Schmitt levels
  double thr_level_off = 0.25;                                // [-]
  // magnetorquers commanded by the FSW (docs/fsw/fsw_acs.md): DETUMBLE and
  // the magnetorquer momentum policy
  bool mtq = false;
  double mtq_duty_max = 1.0;     // [-] fraction of each FSW period the rods may be on
  // DETUMBLE: bdot (docs/fsw/bdot.md)
  BdotLaw bdot_law = BdotLaw::Gyro;
  double bdot_k = 0.0;           // [A*m^2*s/T] (normalize: [N*m*s])
  bool bdot_normalize = false;
  double bdot_tau_f = 0.0;       // [s] derivative filter time constant
  int bdot_max_missed = 3;       // [-]
  Eigen::Vector3d bdot_m_max = Eigen::Vector3d::Zero();  // [A*m^2] per body axis; 0: the rods' limits
  double bdot_omega_done = 0.0;  // [rad/s] detumble-complete rate
  double bdot_omega_reenter = 0.0;  // [rad/s] 0: 2 omega_done
  double bdot_t_persist = 60.0;  // [s]
  FswMode detumble_exit = FswMode::Detumble;  // the mode after detumbling; Detumble ("none"): stay
  // NADIR: guid_orbit (docs/fsw/guid_orbit.md)
  OrbitFrame orbit_frame = OrbitFrame::Nadir;
  Eigen::Vector3d sigma_BdR = Eigen::Vector3d::Zero();  // [-] body relative to the orbit frame
  // momentum management (docs/fsw/thr_momentum.md, mtq_desat.md)
  MomentumPolicy policy = MomentumPolicy::None;
  double mom_h_upper = 0.0;      // [N*m*s] thrusters: dump above
  double mom_h_lower = 0.0;      // [N*m*s] thrusters: down to
  double mom_L_dump = 0.0;       // [N*m]  thrusters: torque of a dump pulse
  double mom_t_pulse_max = 10.0; // [s]
  double mom_t_min_pulse = 0.1;  // [s]
  double mom_t_coast = 10.0;     // [s]
  double mom_Isp = 220.0;        // [s]
  double mom_k_desat = 0.0;      // [1/s] magnetorquers: gain
  double mom_tau_max = 0.0;      // [N*m] magnetorquers: torque limit
  double mom_h_deadband = 0.0;   // [N*m*s]
  // rw_bias (docs/fsw/rw_bias.md): rw_null's desired speeds
  bool rw_bias = false;
  std::vector<double> Omega_bias;  // [rad/s] (num_rw)
  double bias_keepout = 0.0;       // [rad/s]
  double bias_hyst = 0.0;          // [rad/s]
};

// One action of an event (docs/events.md).  `device` names what it acts on:
// a wheel or a thruster by its name, "gyro", "star_tracker", "css<i>"
// (sensors.css.normals[i]) or "fsw"; `action` is one of the words
// docs/events.md lists for that device; `value` is the action's number
// (torque limit [N*m], friction factor [-], tachometer bias [rad/s],
// dropout duration [s]); NaN when the action takes none.
struct EventActionSpec {
  std::string device;
  std::string action;
  double value = std::numeric_limits<double>::quiet_NaN();
};

// A scenario event: a trigger and the actions applied together when it
// fires (once).  Trigger: exactly one of `t` (at the first tick at or after
// t), `after` (the named earlier event's application plus `delay`) and
// `when` (a recorded column, e.g. pointing_error_deg, first seen below
// `below` or above `above` in a recorded row).
struct EventSpec {
  std::string name;                 // unique; default ev<i+1>
  std::optional<double> t;          // [s]
  std::string after;                // name of another event
  double delay = 0.0;               // [s] with `after`
  std::string when;                 // recorded column name
  std::optional<double> below;      // [column unit]
  std::optional<double> above;      // [column unit]
  std::vector<EventActionSpec> actions;
};

// ---- Monte Carlo (docs/monte-carlo.md) ----------------------------------------
// A dispersion: how one key (or one key of every list element, `wheels[*].axis`)
// is drawn for each run.  Numbers are in the unit the key is written with
// (`wheels[0].Omega_0_rpm`: rpm); angles in radians (the _deg spellings
// are converted when read).
enum class DistKind { Normal, TruncatedNormal, Uniform, Choice, UnitVector, NormalVector, Attitude, Inertia };
struct DispersionSpec {
  std::string key;                 // as written; may hold one [*]
  DistKind dist = DistKind::Normal;
  std::optional<double> mean;      // normal, truncated_normal: absent = the nominal value
  double std = 0.0;                // normal, truncated_normal
  std::optional<double> min, max;  // truncated_normal bounds; uniform bounds
  std::optional<double> half_width;  // uniform: nominal +- half_width (instead of min/max)
  std::vector<std::string> values;   // choice: the values as written (YAML scalars)
  std::vector<double> weights;       // choice: relative weights (empty: equal)
  Eigen::Vector3d std_vec = Eigen::Vector3d::Zero();  // normal_vector: per-axis standard deviation
  std::optional<double> angle_std;   // [rad] unit_vector, attitude, inertia
  std::optional<double> angle_max;   // [rad] unit_vector, attitude
  double principal_std_rel = 0.0;    // inertia: principal moments times (1 + N(0, s))
  int line = 0, column = 0;          // where it is written (messages)
};
// A pass/fail criterion on one recorded quantity of a run: `stat` of
// `column` over after <= t <= until; pass when below (or above) threshold.
// `column`: a column (pointing_error_deg), a quantity (omega_BN_B: its norm
// per row) or a prefix ending in * (wheel_speed_rpm_*: every such column).
struct CriterionSpec {
  std::string name;
  std::string column;
  std::string stat = "max";          // max, min, max_abs, final, mean, rms, error_count
  double after = 0.0;                // [s]
  std::optional<double> until;       // [s]
  std::optional<double> below, above;
  int line = 0, column_no = 0;
};
struct RetentionSpec {
  uint32_t keep_first = 3;      // runs 0..keep_first-1 keep full results
  bool keep_failing = true;     // failing runs keep full results ...
  uint32_t max_failing = 100;   // ... at most this many (the first ones by index)
  uint32_t thin_samples = 200;  // every run: this many samples of the thinned channels
};
struct MonteCarloSpec {
  uint64_t runs = 100;  // default of --runs
  uint64_t seed = 1;    // master seed, default of --seed
  std::vector<DispersionSpec> dispersions;
  std::vector<CriterionSpec> criteria;
  RetentionSpec retention;
  int line = 0;
};

struct OutputsSpec {
  bool hdf5 = true;
  bool csv = false;
  bool report_data = true;
};

// The checkpoint a run starts from: the file, the checksum it ends with
// (FNV-1a 64) and the tick it was saved before.
struct CheckpointRef {
  std::string path;
  uint64_t fnv1a64 = 0;
  uint64_t tick = 0;
};

struct Scenario {
  std::string name;
  std::string description;
  uint64_t seed = 0;
  double duration = 0.0;  // [s]
  RatesSpec rates;
  SpacecraftSpec spacecraft;
  EnvironmentSpec environment;
  std::vector<WheelSpec> wheels;
  std::vector<ThrusterSpec> thrusters;
  std::optional<TankSpec> tank;       // feeds every thruster (and the main engine)
  std::optional<TankSpec> rcs_tank;   // if given, feeds the ACS thrusters (acs: true)
  std::optional<BurnSpec> burn;
  std::vector<MagnetorquerSpec> magnetorquers;  // need environment.magnetic (docs/environment.md)
  MtqDriveSpec magnetorquer_drive;
  SensorsSpec sensors;
  FswSpec fsw;
  std::vector<EventSpec> events;  // applied at tick boundaries (docs/events.md)
  std::optional<MonteCarloSpec> monte_carlo;  // `kestrel mc` (docs/monte-carlo.md); runs ignore it
  OutputsSpec outputs;

  // A run that starts from a checkpoint's state instead of tick 0 (a run of a
  // campaign branched from it: docs/checkpoint.md, "Branching a campaign").
  // Not a scenario key: its manifest's `from_checkpoint`.
  std::optional<CheckpointRef> from_checkpoint;

  std::string source_file;  // where it was loaded from (not part of the physics)
  // Where each key was written in the file: dotted path -> (line, column),
  // 1-based; used to name the line of problems found after loading (FSW
  // configuration checks).  Not part of the physics.
  std::map<std::string, std::pair<int, int>> key_lines;
  uint64_t tick_ns() const;    // dt in ns
  uint64_t num_ticks() const;  // duration / dt
  bool has_acs_thrusters() const;  // any thruster with acs: true (the FSW's)
};

const char* to_string(FswMode m);
const char* to_string(RwMapMode m);
const char* to_string(ThrPulseMode m);
const char* to_string(ThrTransient m);
const char* to_string(Actuation m);
const char* to_string(ThrMapMode m);
const char* to_string(MtqDriveMode m);
// Schema name of a wheel model ("balanced", "simple_jitter", "fully_coupled").
const char* wheel_model_key(sim::WheelModel m);

}  // namespace harness

#endif  // HARNESS_CORE_SCENARIO_TYPES_H
