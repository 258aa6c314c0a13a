// FSW assert hook for the scenario input harnesses: a programmer error in the
// flight library reached from a scenario is a finding.
#include <cstdio>
#include <cstdlib>

extern "C" void fsw_assert_failed(const char* file, int line)
{
  std::fprintf(stderr, "FSW assertion failed at %s:%d\n", file, line);
  std::abort();
}
