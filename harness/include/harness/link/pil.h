// pil: processor in the loop (docs/pil.md).  `--fsw pil:TARGET` starts the
// cross-built FSW program under QEMU, connects the FSW link to it and stops
// it when the link is closed:
//
//   aarch64-linux, armhf-linux   kestrel-fsw under qemu-user, loopback UDP
//   cortex-m4f, cortex-m4f-float kestrel-fsw-m4f.elf on qemu-system-arm
//                                mps2-an386, UART0 on a unix socket
//
// The configuration image of the run is written to a private temporary
// folder and handed to the program (--config for Linux, loaded into the
// board's flash at 0x00380000 for the Cortex-M4F).  The emulator runs in a
// process group of its own, which is killed when the transport is destroyed
// (end of run, error, Ctrl-C) and, through PR_SET_PDEATHSIG, when the
// harness dies.  Failures say which side failed.
#ifndef HARNESS_PIL_H
#define HARNESS_PIL_H

#include <memory>
#include <string>
#include <vector>

#include "harness/link/remote_fsw.h"

namespace harness {

struct PilTarget {
  std::string name;                   // "aarch64-linux", ...
  std::string default_bin;            // the build's cross-built program ("" : not built)
  std::vector<std::string> emulator;  // the emulator command before the program
  bool bare_metal = false;            // UART on a socket; else UDP
};

// The known targets (default binaries from the build, cmake/KestrelPil.cmake).
const std::vector<PilTarget>& pil_targets();

// spec: "pil:TARGET".  Starts the emulated FSW with cfg's configuration
// image and connects; the start-up is bounded by opt.timeout_s.  Throws
// FswEndpointError naming the side that failed.
std::unique_ptr<LinkTransport> open_pil_transport(const std::string& spec, const FswAcsConfig& cfg,
                                                  const LinkOptions& opt);

// "pil:..." through open_pil_transport, "cfs:..." through open_cfs_transport
// (cfs_link.h; its start-up bounded by opt.timeout_s), anything else
// open_link_transport.
std::unique_ptr<LinkTransport> open_fsw_transport(const std::string& spec, const FswAcsConfig& cfg,
                                                  const LinkOptions& opt);

}  // namespace harness

#endif  // HARNESS_PIL_H
