// The machine's floating-point limit, measured in the same run as the
// query benchmarks: independent double FMA chains (a = a * x + y) in the
// widest vectors Highway dispatches to on this CPU (the same dispatch as the
// SIMD batch), enough chains to cover the FMA latency on every pipe.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "tests/waves/bench_fp_peak.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "tests/waves/bench_fp_peak.h"

HWY_BEFORE_NAMESPACE();
namespace geocean::waves::bench {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

double FmaChains(std::uint64_t iters) {
  const hn::ScalableTag<double> d;
  const auto x = hn::Set(d, 0.999999), y = hn::Set(d, 1e-3);
  auto a0 = hn::Set(d, 1.0), a1 = hn::Set(d, 2.0), a2 = hn::Set(d, 3.0), a3 = hn::Set(d, 4.0), a4 = hn::Set(d, 5.0),
       a5 = hn::Set(d, 6.0), a6 = hn::Set(d, 7.0), a7 = hn::Set(d, 8.0), a8 = hn::Set(d, 9.0), a9 = hn::Set(d, 10.0),
       a10 = hn::Set(d, 11.0), a11 = hn::Set(d, 12.0);
  for (std::uint64_t i = 0; i < iters; ++i) {
    a0 = hn::MulAdd(a0, x, y), a1 = hn::MulAdd(a1, x, y), a2 = hn::MulAdd(a2, x, y), a3 = hn::MulAdd(a3, x, y);
    a4 = hn::MulAdd(a4, x, y), a5 = hn::MulAdd(a5, x, y), a6 = hn::MulAdd(a6, x, y), a7 = hn::MulAdd(a7, x, y);
    a8 = hn::MulAdd(a8, x, y), a9 = hn::MulAdd(a9, x, y), a10 = hn::MulAdd(a10, x, y), a11 = hn::MulAdd(a11, x, y);
  }
  const auto s = hn::Add(hn::Add(hn::Add(a0, a1), hn::Add(a2, a3)),
                         hn::Add(hn::Add(hn::Add(a4, a5), hn::Add(a6, a7)), hn::Add(hn::Add(a8, a9), hn::Add(a10, a11))));
  volatile double sink = hn::GetLane(s);
  (void)sink;
  // An FMA is 2 flops per lane (what the query counts are in).
  return double(iters) * 12.0 * double(hn::Lanes(d)) * 2.0;
}

}  // namespace HWY_NAMESPACE
}  // namespace geocean::waves::bench
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace geocean::waves::bench {
HWY_EXPORT(FmaChains);
double fmaChains(std::uint64_t iters) { return HWY_DYNAMIC_DISPATCH(FmaChains)(iters); }
}  // namespace geocean::waves::bench
#endif
