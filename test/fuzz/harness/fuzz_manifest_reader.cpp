// libFuzzer harness: run manifest text (manifest.json, which `kestrel run`
// accepts as a scenario: its "scenario" object is loaded) -> the scenario.
// The input is also tried with "kestrel_manifest" forced in, so a mutation
// that breaks the marker still reaches the manifest path.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  kestrel_fuzz::load_and_check(text, "manifest.json", {});
  // {"kestrel_manifest": 1, "scenario": <input>}: the scenario object as a manifest holds it
  kestrel_fuzz::load_and_check("{\"kestrel_manifest\": 1, \"scenario\": " + text + "\n}", "manifest.json", {});
  return 0;
}
