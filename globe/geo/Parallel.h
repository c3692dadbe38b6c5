// geo::parallelFor: tbb::parallel_for whose fork and join ThreadSanitizer
// sees. Debian's libtbb is not instrumented, so under TSan the hand-off to
// a worker and the caller's wait look unsynchronised: a buffer filled
// before the loop, read by a worker and freed after it is reported as a
// race (CI's tsan stage, CoastField's outer phase). The suppression of
// libtbb frames cannot catch it when the worker's stack is too old to be
// restored. Here each task acquires the caller's release before the loop
// and releases into a token the caller acquires after it: exactly the
// ordering TBB guarantees. Tasks do not synchronise with each other, so a
// race between two workers is still reported. Without TSan: plain TBB.
#pragma once

#include <tbb/parallel_for.h>

#include <type_traits>
#include <utility>

#if defined(__SANITIZE_THREAD__)
#define GEOCEAN_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define GEOCEAN_TSAN 1
#endif
#endif

#if defined(GEOCEAN_TSAN)
#include <sanitizer/tsan_interface.h>
#endif

namespace geocean::geo {

namespace detail {
// The body run by a worker, bracketed by the fork/join annotations.
template <class F>
auto annotated(F& f, [[maybe_unused]] char* fork, [[maybe_unused]] char* join) {
#if defined(GEOCEAN_TSAN)
  return [&f, fork, join](const auto& a) {
    __tsan_acquire(fork);
    f(a);
    __tsan_release(join);
  };
#else
  return [&f](const auto& a) { f(a); };
#endif
}

template <class Run>
void forkJoin(Run&& run, [[maybe_unused]] char* fork, [[maybe_unused]] char* join) {
#if defined(GEOCEAN_TSAN)
  __tsan_release(fork);
#endif
  run();
#if defined(GEOCEAN_TSAN)
  __tsan_acquire(join);
#endif
}
}  // namespace detail

// parallelFor(first, last, f): f(i) for i in [first, last).
template <class Index, class F>
void parallelFor(Index first, Index last, F&& f) {
  char fork = 0, join = 0;
  auto body = detail::annotated(f, &fork, &join);
  detail::forkJoin([&] { tbb::parallel_for(first, last, body); }, &fork, &join);
}

// parallelFor(range, f, partitioner...): f(subrange) over a TBB range.
template <class Range, class F, class... Partitioner>
  requires(!std::is_integral_v<Range>)
void parallelFor(const Range& range, F&& f, Partitioner&&... partitioner) {
  char fork = 0, join = 0;
  auto body = detail::annotated(f, &fork, &join);
  detail::forkJoin([&] { tbb::parallel_for(range, body, std::forward<Partitioner>(partitioner)...); }, &fork, &join);
}

}  // namespace geocean::geo
