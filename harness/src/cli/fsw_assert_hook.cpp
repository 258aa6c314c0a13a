// The integrator's FSW assert hook for the kestrel program: report the
// programmer error and return, so the module returns FSW_E_NULL_ARG and the
// harness sees the failure in the module's health counters.
#include <cstdio>

extern "C" void fsw_assert_failed(const char* file, int line)
{
  std::fprintf(stderr, "kestrel: FSW assertion failed at %s:%d\n", file, line);
}
