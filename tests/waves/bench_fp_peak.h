// FMA peak of this CPU at the widest dispatched vector width (bench only).
#pragma once

#include <cstdint>

namespace geocean::waves::bench {
// Runs `iters` rounds of 12 independent vector FMA chains; returns the flops
// done (2 per FMA lane).
double fmaChains(std::uint64_t iters);
}  // namespace geocean::waves::bench
