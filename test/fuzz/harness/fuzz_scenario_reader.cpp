// libFuzzer harness: YAML scenario text -> load_scenario_text ->
// check_run_configuration (what `kestrel validate` does with a file).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  kestrel_fuzz::load_and_check(text, "fuzz.yaml", {});
  return 0;
}
