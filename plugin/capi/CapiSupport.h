// Internal to the plugin's C ABI (never installed): the handle, its
// immutable snapshot, and the guard every entry point runs in. Shared by
// geocean_ocean.cpp (state and queries) and geocean_draw.cpp (GL).
#pragma once

#include "geocean/geocean_ocean.h"

#include "globe/raster/Raster.h"
#include "plugin/landsea/LandSea.h"
#include "plugin/waves/SeaQuery.h"
#include "plugin/waves/WaveField.h"

#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

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

// Everything a query reads. Immutable once published: setters build a new
// snapshot and swap the pointer, so queries never lock while they work.
struct Snapshot {
  std::shared_ptr<const Raster> mask, elevation;
  std::shared_ptr<const geocean::ocean::LandSea> landSea;
  std::shared_ptr<const geocean::waves::WaveField> waves;
  // The query path shared with `geocean query` (rebuilt when either changes).
  std::shared_ptr<const geocean::waves::SeaQuery> sea;
  // What `waves` was made from: the renderer builds its own field from it.
  geocean::waves::Model model = geocean::waves::Model::Noise;
  geocean::waves::SeaState seaState;
};

// Render-thread state of one ocean (geocean_draw.cpp).
struct DrawState;
struct DrawStateDeleter {
  void operator()(DrawState* d) const;
};
// Frees a draw state: its GL names only if their context is current, its
// CPU side always.
void releaseDrawState(std::unique_ptr<DrawState, DrawStateDeleter>& d);

}  // namespace geocean::capi

struct geocean_ocean {
  using Snapshot = geocean::capi::Snapshot;
  mutable std::mutex mutex;  // guards `snapshot` (the pointer, not its contents)
  std::shared_ptr<const Snapshot> snapshot = std::make_shared<Snapshot>();
  // Render-thread state (update/draw/release_gl never overlap, header rule).
  std::unique_ptr<geocean::capi::DrawState, geocean::capi::DrawStateDeleter> draw;
  std::shared_ptr<const Snapshot> current() const {
    std::lock_guard lock(mutex);
    return snapshot;
  }
  // Applies `edit` to a copy of the current snapshot and publishes it.
  // Setters are serialised so two concurrent edits cannot lose one another.
  template <class Edit>
  void update(Edit&& edit) {
    std::lock_guard editLock(editMutex);
    auto next = std::make_shared<Snapshot>(*current());
    edit(*next);
    if (next->mask || next->elevation)
      next->landSea = std::make_shared<geocean::ocean::LandSea>(next->mask, next->elevation);
    else
      next->landSea.reset();
    if (next->waves)
      next->sea = std::make_shared<geocean::waves::SeaQuery>(*next->waves, next->landSea);
    else
      next->sea.reset();
    std::lock_guard lock(mutex);
    snapshot = std::move(next);
  }

 private:
  std::mutex editMutex;
};
