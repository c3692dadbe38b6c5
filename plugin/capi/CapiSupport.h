// Internal to the plugin's C ABI (never installed): the handle over the
// ocean façade (plugin/ocean/Ocean.h), and the guard every entry point runs
// in. Shared by geocean_ocean.cpp (state and queries) and geocean_draw.cpp (GL).
#pragma once

#include "geocean/geocean_ocean.h"

#include "plugin/ocean/Ocean.h"
#include "plugin/waves/TimeRange.h"

#include <charconv>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace geocean::ocean_render {
struct Wake;
}

namespace geocean::capi {

using geocean::raster::Raster;
using geocean::raster::RasterError;

// The calling thread's last error; geocean_last_error() returns it.
inline thread_local std::string tlsLastError;
// A failure with a status, thrown inside an entry point and turned into the
// return value by guard().
struct Failure {
  geocean_status status;
  std::string message;
};

[[noreturn]] inline void fail(geocean_status status, std::string message) { throw Failure{status, std::move(message)}; }

// A double as its shortest round trip (what the caller passed, exactly).
inline std::string shortest(double v) {
  char b[40];
  const auto r = std::to_chars(b, b + sizeof b, v);
  return std::string(b, r.ptr);
}

// A finite simulation time beyond the bound the sea is defined at
// (plugin/waves/TimeRange.h): the message names the field and the value.
inline void requireTimeInRange(double t, const std::string& field) {
  if (geocean::waves::timeInRange(t)) return;
  fail(GEOCEAN_ERROR_INVALID_ARGUMENT, field + " " + shortest(t) + " s is outside " +
                                           geocean::waves::kTimeRangeText +
                                           " (beyond, the waves' phase w t keeps no precision)");
}

// The façade's missing prerequisite, with the C functions that provide it.
inline const char* notReadyMessage(geocean::ocean::NotReady::Missing m) {
  using M = geocean::ocean::NotReady::Missing;
  switch (m) {
    case M::Rasters:
      return "no mask or elevation raster: call geocean_set_mask_* or geocean_set_elevation_* "
             "(or geocean_set_default_world) first";
    case M::Elevation:
      return "no elevation raster: call geocean_set_elevation_file, geocean_set_elevation_pixels or "
             "geocean_set_default_world first";
    case M::SeaState: return "no sea state: call geocean_set_sea_state first";
  }
  return "not ready";
}

template <class F>
geocean_status guard(const char* function, F&& body) noexcept {
  tlsLastError.clear();
  geocean_status status = GEOCEAN_OK;
  std::string message;
  try {
    body();
    return GEOCEAN_OK;
  } catch (const Failure& f) {
    status = f.status;
    message = f.message;
  } catch (const geocean::ocean::NotReady& e) {
    status = GEOCEAN_ERROR_NOT_READY;
    message = notReadyMessage(e.missing);
  } catch (const RasterError& e) {
    status = GEOCEAN_ERROR_RASTER;
    message = e.what();
  } catch (const std::invalid_argument& e) {
    status = GEOCEAN_ERROR_INVALID_ARGUMENT;
    message = e.what();
  } catch (const std::bad_alloc&) {
    status = GEOCEAN_ERROR_OUT_OF_MEMORY;
    message = "out of memory";
  } catch (const std::exception& e) {
    status = GEOCEAN_ERROR_INTERNAL;
    message = e.what();
  } catch (...) {
    status = GEOCEAN_ERROR_INTERNAL;
    message = "unknown exception";
  }
  try {
    tlsLastError = std::string(function) + ": " + message;
  } catch (...) {
    // No memory even for the message: the status still says what happened.
  }
  return status;
}

inline void requireNonNull(const void* p, const char* what) {
  if (!p) fail(GEOCEAN_ERROR_NULL_ARGUMENT, std::string(what) + " is NULL");
}

// A struct_size-versioned struct must be at least this version's layout
// (the host filled it with its _init function).
template <class T>
void requireStructSize(const T* s, const char* name, const char* init) {
  if (s->struct_size < sizeof(T))
    fail(GEOCEAN_ERROR_INVALID_ARGUMENT, std::string(name) + "->struct_size " + std::to_string(s->struct_size) +
                                             " is smaller than " + std::to_string(sizeof(T)) + ": call " + init +
                                             " first");
}

// What queries and the draw half read (mask, elevation, landSea, waves,
// model, seaState, maskEncoding); compared by pointer to know when to rebuild.
using Snapshot = geocean::ocean::Snapshot;

// Render-thread state of one ocean (geocean_draw.cpp).
struct DrawState;
struct DrawStateDeleter {
  void operator()(DrawState* d) const;
};
// Frees a draw state: its GL names only if their context is current, its
// CPU side always.
void releaseDrawState(std::unique_ptr<DrawState, DrawStateDeleter>& d);

// The bodies of one set as the draw foams around them (geocean_bodies.cpp):
// their interpolated poses, hull extents and speed through the water.
void appendWakes(const geocean_bodies& bodies, std::vector<geocean::ocean_render::Wake>& out);

}  // namespace geocean::capi

struct geocean_ocean {
  using Snapshot = geocean::capi::Snapshot;
  geocean::ocean::Ocean core;  // rasters, sea state, the snapshot and the queries
  // Render-thread state (update/draw/release_gl never overlap, header rule).
  std::unique_ptr<geocean::capi::DrawState, geocean::capi::DrawStateDeleter> draw;
  // The draw half reads the state through this.
  std::shared_ptr<const Snapshot> current() const { return core.current(); }
  // The body sets on this ocean (geocean_bodies_create adds, _destroy
  // removes): the draw foams around their bodies. Lock order: this mutex,
  // then a set's own.
  std::mutex bodySetsMutex;
  std::vector<const geocean_bodies*> bodySets;
};
