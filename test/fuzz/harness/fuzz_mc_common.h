// Shared by the Monte Carlo shard reader harnesses: a refusal must name the
// file and the field and say why; anything else thrown is a finding.
#ifndef KESTREL_FUZZ_MC_COMMON_H
#define KESTREL_FUZZ_MC_COMMON_H

#include <cstdio>
#include <cstdlib>
#include <string>

#include "mc/mc_validate.h"

namespace kestrel_fuzz {

inline void finding(const char* what)
{
  std::fprintf(stderr, "%s\n", what);
  std::abort();
}

inline void check_refusal(const harness::McShardError& e, const std::string& file)
{
  if (e.file() != file || e.field().empty() || std::string(e.what()).size() <= file.size() + e.field().size() + 4)
    finding("a refusal without its file, field or reason");
}

inline bool is_hash(const std::string& h)
{
  return h.size() == 16 && h.find_first_not_of("0123456789abcdef") == std::string::npos;
}

}  // namespace kestrel_fuzz

#endif  // KESTREL_FUZZ_MC_COMMON_H
