#include "harness/core/fsw_endpoint.h"

#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" {
#include "fsw/fsw_acs_save.h"
}

namespace harness {


void InProcessFsw::state_io(sim::StateIO& io)
{
  std::vector<uint8_t> image(fsw_acs_save_size());
  size_t len = 0;
  if (!io.loading() && fsw_acs_save(&st_, image.data(), image.size(), &len) != FSW_OK)
    throw FswEndpointError("fsw_acs_save failed");
  io.bytes("fsw.state", image.data(), image.size());
  if (io.loading() && fsw_acs_restore(&st_, image.data(), image.size()) != FSW_OK)
    throw std::runtime_error("checkpoint: the flight software's image does not fit this build (fsw_acs_save tag)");
  io.value("fsw.command", cmd_);
  io.value("fsw.have_command", have_cmd_);
}

InProcessFsw::InProcessFsw(const FswAcsConfig& cfg) : cfg_(cfg)
{
  std::memset(&st_, 0, sizeof st_);
  const char* bad = nullptr;
  const FswStatus s = fsw_acs_init(&st_, &cfg_, &bad);
  if (s != FSW_OK)
    throw std::invalid_argument(std::string("fsw_acs_init: field '") + (bad ? bad : "(unknown)") +
                                "': " + fsw_status_name(s));
}

void InProcessFsw::cycle(const FswAcsSensorMsg& in, FswAcsActuatorMsg& out, FswAcsHealthMsg& health)
{
  fsw_acs_cycle(&st_, &cfg_, &in, have_cmd_ ? &cmd_ : nullptr, &out, &health);
  have_cmd_ = false;
}

namespace {
const char* mode_name(int mode)
{
  switch (mode) {
    case FSW_ACS_MODE_SUN_SAFE: return "sun_safe";
    case FSW_ACS_MODE_INERTIAL: return "inertial";
    case FSW_ACS_MODE_DETUMBLE: return "detumble";
    case FSW_ACS_MODE_NADIR: return "nadir";
    default: return "unknown";
  }
}
}  // namespace

std::vector<std::string> fsw_health_summary(const FswAcsHealthMsg& h)
{
  std::vector<std::string> out;
  std::ostringstream os;
  os << "fsw_acs last cycle: status=" << fsw_status_name(h.status) << " safe_output=" << int(h.safe_output)
     << " mode=" << mode_name(h.mode)
     << " actuation=" << (h.actuation == FSW_ACS_ACT_THRUSTERS ? "thrusters" : "wheels") << " cycles=" << h.cycles
     << " mode_changes=" << h.mode_changes;
  out.push_back(os.str());
  std::ostringstream ss;
  ss << "fsw_acs last cycle stages:";
  for (int i = 0; i < FSW_ACS_NUM_STAGES; ++i) ss << " " << fsw_acs_stage_name(i) << "=" << fsw_status_name(h.stage_status[i]);
  out.push_back(ss.str());
  return out;
}

std::vector<std::string> InProcessFsw::module_health_lines() const
{
  std::vector<std::string> out;
  auto line = [&out](const char* name, const FswHealth& hh) {
    std::ostringstream os;
    os << name << ": calls=" << hh.calls << " bad_input=" << hh.bad_input << " bad_time=" << hh.bad_time
       << " saturated=" << hh.saturated << " singular=" << hh.singular << " other_error=" << hh.other_error
       << " last=" << fsw_status_name(hh.last);
    out.push_back(os.str());
  };
  line("fsw_acs", st_.health);
  if (cfg_.initial_mode == FSW_ACS_MODE_SUN_SAFE) {
    line("css_sun", st_.css.health);
    line("guid_sunsafe", st_.sunsafe.health);
  } else {
    line("guid_inertial", st_.inertial.health);
    line("att_track", st_.track.health);
  }
  if (cfg_.has_mtq) {
    line("bdot", st_.bdot.health);
    line("mtq_map", st_.mtq_map.health);
  }
  if (cfg_.has_orbit && st_.orbit.health.calls > 0) line("guid_orbit", st_.orbit.health);
  if (cfg_.use_mtq_desat) line("mtq_desat", st_.mtq_desat.health);
  if (cfg_.use_thr_mom) line("thr_momentum", st_.thr_mom.health);
  if (cfg_.use_bias) line("rw_bias", st_.rw_bias.health);
  line("mrp_fb", st_.mrp_fb.health);
  if (cfg_.has_wheels) {
    line("rw_map", st_.rw_map.health);
    if (cfg_.use_null) line("rw_null", st_.rw_null.health);
    line("rw_sat", st_.rw_sat.health);
  }
  if (cfg_.has_thrusters) {
    line("thr_map", st_.thr_map.health);
    if (cfg_.pulser == FSW_ACS_PULSE_REMAINDER) line("thr_pulse_rem", st_.pulse_rem.common.health);
    else line("thr_pulse_schmitt", st_.pulse_schmitt.common.health);
  }
  return out;
}

}  // namespace harness
