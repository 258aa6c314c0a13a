// Every pointer argument NULL in turn (issue 21): the contract of every FSW
// entry point (fsw_status.h, "Assert hook") is that a NULL pointer calls the
// assert hook once and returns FSW_E_NULL_ARG (void functions: return),
// never dereferencing it.  each_null(what, f, p0, p1, ...) calls f k times,
// the i-th time with p_i replaced by nullptr and the others valid, and
// checks the status (for non-void f) and exactly one call of the hook.
#ifndef KESTREL_NULL_ARGS_H
#define KESTREL_NULL_ARGS_H

#include <gtest/gtest.h>

#include <cstddef>
#include <memory>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>

#include "fsw/fsw_status.h"
#include "kestrel_test_support.h"

namespace kt {

template <class F, class Tup, std::size_t... I>
void each_null_impl(const char* what, F& f, const Tup& t, std::index_sequence<I...>)
{
  constexpr std::size_t n = sizeof...(I);
  for (std::size_t k = 0; k < n; k++) {
    kestrel_assert_reset();
    using R = decltype(f(std::get<I>(t)...));
    if constexpr (std::is_void_v<R>) {
      f((I == k ? static_cast<std::tuple_element_t<I, Tup>>(nullptr) : std::get<I>(t))...);
    } else {
      const auto s = f((I == k ? static_cast<std::tuple_element_t<I, Tup>>(nullptr) : std::get<I>(t))...);
      EXPECT_EQ(FSW_E_NULL_ARG, s) << what << ": argument " << k << " NULL";
    }
    EXPECT_EQ(1ul, kestrel_assert_count()) << what << ": argument " << k << " NULL";
  }
  kestrel_assert_reset();
}

template <class F, class... P>
void each_null(const char* what, F f, P*... p)
{
  const std::tuple<P*...> t(p...);
  each_null_impl(what, f, t, std::index_sequence_for<P...>{});
}

// The uniform module shape (check / init / reset / update): every entry
// point with every pointer NULL in turn.  The objects are zero (the NULL
// checks come before any use of the config or the ready flag) and on the
// heap (the bare-metal targets have a small stack).
template <class Cfg, class St, class In, class Out>
void module_null_args(const char* name, FswStatus (*check)(const Cfg*), FswStatus (*init)(St*, const Cfg*),
                      void (*reset)(St*), FswStatus (*update)(St*, const Cfg*, const In*, Out*))
{
  const std::unique_ptr<Cfg> cfg(new Cfg());
  const std::unique_ptr<St> st(new St());
  const std::unique_ptr<In> in(new In());
  const std::unique_ptr<Out> out(new Out());
  const std::string n(name);
  each_null((n + "_check").c_str(), check, cfg.get());
  each_null((n + "_init").c_str(), init, st.get(), cfg.get());
  each_null((n + "_reset").c_str(), reset, st.get());
  each_null((n + "_update").c_str(), update, st.get(), cfg.get(), in.get(), out.get());
}

}  // namespace kt

#endif
