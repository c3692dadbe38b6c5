// The façade's simulation-time bound, for callers that use the façade only
// (the CLI, tests/deps): |t| <= waves::kMaxTimeS, derived in
// plugin/waves/TimeRange.h. Snapshot::querySurface refuses other times.
#pragma once

#include "plugin/waves/TimeRange.h"
