// geocean._geocean: the pybind11 binding over the ocean façade
// (plugin/ocean/Ocean.h) and the picker (plugin/pick). The Python package
// (geocean/__init__.py) wraps Core in the public Ocean class.
//
// Rules every entry point keeps:
//  - inputs go through py::array_t<double, c_style | forcecast>: a
//    C-contiguous float64 array is used in place (no copy); anything else
//    is converted once;
//  - outputs are numpy arrays allocated here and written by the façade;
//  - the GIL is released for validation and the batch itself, so other
//    Python threads run meanwhile (the façade's snapshot is immutable);
//  - bad input throws std::invalid_argument (Python ValueError) naming the
//    argument, the index and the value.
#include "globe/geo/Ellipsoid.h"
#include "globe/geo/Parallel.h"
#include "globe/raster/Raster.h"
#include "plugin/ocean/Ocean.h"
#include "plugin/pick/Picker.h"
#include "plugin/waves/TimeRange.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <tbb/blocked_range.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;
namespace oc = geocean::ocean;

namespace {

using InArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string num(double v) {
  char b[40];
  const auto r = std::to_chars(b, b + sizeof b, v);
  return std::string(b, r.ptr);
}

std::vector<py::ssize_t> shapeOf(const py::array& a) { return {a.shape(), a.shape() + a.ndim()}; }

std::string shapeText(const std::vector<py::ssize_t>& s) {
  std::string t = "(";
  for (std::size_t i = 0; i < s.size(); ++i) t += (i ? ", " : "") + std::to_string(s[i]);
  return t + (s.size() == 1 ? ",)" : ")");
}

// "lat[3]" or "lat[1, 2]": the element's index in the caller's shape.
std::string at(const char* name, std::size_t flat, const std::vector<py::ssize_t>& shape) {
  std::vector<std::size_t> idx(shape.size());
  for (std::size_t d = shape.size(); d-- > 0;) {
    idx[d] = flat % std::size_t(shape[d]);
    flat /= std::size_t(shape[d]);
  }
  std::string t = std::string(name) + "[";
  for (std::size_t d = 0; d < idx.size(); ++d) t += (d ? ", " : "") + std::to_string(idx[d]);
  return t + "]";
}

// The CLI's ranges (globe/app/QueryIo.cpp checkLatLon): lat [-90, 90], lon [-180, 360].
void checkLatLon(const double* lat, const double* lon, std::size_t n, const std::vector<py::ssize_t>& shape) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!(lat[i] >= -90.0 && lat[i] <= 90.0))
      throw std::invalid_argument(at("lat", i, shape) + " = " + num(lat[i]) +
                                  (std::isnan(lat[i]) ? " is not a number" : " is outside [-90, 90] degrees"));
    if (!(lon[i] >= -180.0 && lon[i] <= 360.0))
      throw std::invalid_argument(at("lon", i, shape) + " = " + num(lon[i]) +
                                  (std::isnan(lon[i]) ? " is not a number" : " is outside [-180, 360] degrees"));
  }
}

// lat and lon: same shape, any number of dimensions.
std::vector<py::ssize_t> pointShape(const InArray& lat, const InArray& lon) {
  const auto s = shapeOf(lat);
  if (shapeOf(lon) != s)
    throw std::invalid_argument("lat has shape " + shapeText(s) + " but lon has shape " + shapeText(shapeOf(lon)));
  return s;
}

template <class T>
py::array_t<T> newArray(std::vector<py::ssize_t> shape, std::size_t trailing = 0) {
  if (trailing) shape.push_back(py::ssize_t(trailing));
  return py::array_t<T>(shape);
}

// A query whose prerequisite (raster, sea state) is missing: geocean.NotReadyError.
class NotReadyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Runs f(begin, end) over [0, n) on all cores in blocks of 4096 (the
// façade's own grain for querySurface).
template <class F>
void parallelBlocks(std::size_t n, F&& f) {
  geocean::geo::parallelFor(tbb::blocked_range<std::size_t>(0, n, 4096),
                            [&](const tbb::blocked_range<std::size_t>& r) { f(r.begin(), r.end()); });
}

class Core {
 public:
  Core(std::optional<std::string> mask, std::optional<std::string> elevation, const std::string& georef,
       bool fewLookups, std::optional<std::string> maskEncoding, const std::string& waves, double windMps,
       double windFromDeg, double fetchM, std::uint32_t seed, int gerstnerComponents, int noiseOctaves,
       double anchorLatDeg, double anchorLonDeg, double referenceDepthM) {
    geocean::raster::OpenOptions ro;
    if (georef == "global")
      ro.georef = geocean::raster::Georef::GlobalEquirect;
    else if (georef != "file")
      throw std::invalid_argument("georef = '" + georef + "' is neither 'file' nor 'global'");
    ro.fewLookups = fewLookups;
    const auto model = geocean::waves::parseModel(waves);
    if (!model && waves != "none")
      throw std::invalid_argument("waves = '" + waves + "' is not a wave model (noise, noise-paper, gerstner, fft, none)");
    if (!(anchorLatDeg >= -90.0 && anchorLatDeg <= 90.0) || !(anchorLonDeg >= -180.0 && anchorLonDeg <= 360.0))
      throw std::invalid_argument("anchor = (" + num(anchorLatDeg) + ", " + num(anchorLonDeg) +
                                  ") is outside lat [-90, 90], lon [-180, 360] degrees");
    // The encoding before the rasters: the land/sea is then built once.
    if (maskEncoding) ocean_.setMaskEncoding(geocean::ocean::MaskEncoding::parse(*maskEncoding));
    std::shared_ptr<const geocean::raster::Raster> m, e;
    if (mask) m = geocean::raster::Raster::open(*mask, ro);
    if (elevation) e = geocean::raster::Raster::open(*elevation, ro);
    ocean_.setRasters(std::move(m), std::move(e));
    if (model) {
      geocean::waves::SeaState sea;
      sea.windSpeedMps = windMps;
      sea.windFromDeg = windFromDeg;
      sea.fetchM = fetchM;
      sea.seed = seed;
      sea.gerstnerComponents = gerstnerComponents;
      sea.noiseOctaves = noiseOctaves;
      sea.anchorLatDeg = anchorLatDeg;
      sea.anchorLonDeg = anchorLonDeg;
      sea.referenceDepthM = referenceDepthM;
      ocean_.setSeaState(*model, sea);  // std::invalid_argument naming the field and value
    }
  }

  py::dict query(const InArray& lat, const InArray& lon, const InArray& t, bool horizontalVelocity) const {
    const auto shape = pointShape(lat, lon);
    const std::size_t n = std::size_t(lat.size());
    const bool perPoint = t.ndim() != 0;
    if (perPoint && shapeOf(t) != shape)
      throw std::invalid_argument("t has shape " + shapeText(shapeOf(t)) + ": expected a scalar or lat's shape " +
                                  shapeText(shape));
    const auto snap = ocean_.current();
    auto surface = newArray<std::uint8_t>(shape);
    auto elevation = newArray<float>(shape);
    auto height = newArray<double>(shape);
    auto normal = newArray<double>(shape, 3);
    auto vvel = newArray<double>(shape);
    py::array_t<double> hvel;
    if (horizontalVelocity) hvel = newArray<double>(shape, 2);
    oc::SurfaceOutputs out;
    out.surface = reinterpret_cast<oc::Surface*>(surface.mutable_data());  // bytes: the façade memcpys
    out.elevationM = elevation.mutable_data();
    const bool sea = snap->sea != nullptr;
    if (sea) {
      out.heightM = height.mutable_data();
      out.normalEnu = normal.mutable_data();
      out.verticalVelocityMps = vvel.mutable_data();
      if (horizontalVelocity) out.horizontalVelocityEnMps = hvel.mutable_data();
    }
    const double* la = lat.data();
    const double* lo = lon.data();
    const double* ts = t.data();
    {
      py::gil_scoped_release release;
      checkLatLon(la, lo, n, shape);
      for (std::size_t i = 0, nt = perPoint ? n : 1; i < nt; ++i)
        if (!geocean::waves::timeInRange(ts[i]))
          throw std::invalid_argument((perPoint ? at("t", i, shape) : std::string("t")) + " = " + num(ts[i]) +
                                      (std::isfinite(ts[i]) ? std::string(" s is outside ") +
                                                                  geocean::waves::kTimeRangeText +
                                                                  " (beyond, the waves' phase w t keeps no precision)"
                                                            : std::string(" s is not finite")));
      try {
        snap->querySurface({la, lo, n, ts, perPoint && n > 1}, out);
      } catch (const oc::NotReady& e) {
        throw NotReadyError(std::string("Ocean.query: ") + e.what());
      }
      if (!sea) {  // waves='none': class and elevation only
        std::fill_n(height.mutable_data(), n, kNaN);
        std::fill_n(normal.mutable_data(), 3 * n, kNaN);
        std::fill_n(vvel.mutable_data(), n, kNaN);
        if (horizontalVelocity) std::fill_n(hvel.mutable_data(), 2 * n, kNaN);
      }
    }
    py::dict d;
    d["surface"] = surface;
    d["elevation_m"] = elevation;
    d["sea_height_m"] = height;
    d["normal_enu"] = normal;
    d["vertical_velocity_mps"] = vvel;
    if (horizontalVelocity) d["horizontal_velocity_en_mps"] = hvel;
    return d;
  }

  // The local sea state (the query's hs_m, peak_period_s, peak_wavelength_m,
  // wave_from_deg); NaN where the point is not ocean.
  py::dict seaState(const InArray& lat, const InArray& lon) const {
    const auto shape = pointShape(lat, lon);
    const std::size_t n = std::size_t(lat.size());
    const auto snap = ocean_.current();
    auto hs = newArray<double>(shape), tp = newArray<double>(shape), lp = newArray<double>(shape),
         from = newArray<double>(shape);
    oc::SurfaceOutputs out;
    out.hsM = hs.mutable_data();
    out.peakPeriodS = tp.mutable_data();
    out.peakWavelengthM = lp.mutable_data();
    out.waveFromDeg = from.mutable_data();
    const double* la = lat.data();
    const double* lo = lon.data();
    {
      py::gil_scoped_release release;
      checkLatLon(la, lo, n, shape);
      const double t = 0.0;  // the sea state does not depend on time
      try {
        snap->querySurface({la, lo, n, &t, false}, out);
      } catch (const oc::NotReady& e) {
        throw NotReadyError(std::string("Ocean.sea_state: ") + e.what());
      }
    }
    py::dict d;
    d["hs_m"] = hs;
    d["peak_period_s"] = tp;
    d["peak_wavelength_m"] = lp;
    d["wave_from_deg"] = from;
    return d;
  }

  py::array_t<std::uint8_t> classify(const InArray& lat, const InArray& lon) const {
    const auto shape = pointShape(lat, lon);
    const std::size_t n = std::size_t(lat.size());
    const auto snap = ocean_.current();
    if (!snap->landSea) throw NotReadyError("Ocean.classify: no mask or elevation raster (pass mask= or elevation=)");
    auto out = newArray<std::uint8_t>(shape);
    auto* o = reinterpret_cast<oc::Surface*>(out.mutable_data());
    const double *la = lat.data(), *lo = lon.data();
    {
      py::gil_scoped_release release;
      checkLatLon(la, lo, n, shape);
      parallelBlocks(n, [&](std::size_t b, std::size_t e) { snap->classify(la + b, lo + b, e - b, o + b); });
    }
    return out;
  }

  py::array_t<float> elevation(const InArray& lat, const InArray& lon) const {
    const auto shape = pointShape(lat, lon);
    const std::size_t n = std::size_t(lat.size());
    const auto snap = ocean_.current();
    if (!snap->elevation) throw NotReadyError("Ocean.elevation: no elevation raster (pass elevation=)");
    auto out = newArray<float>(shape);
    float* o = out.mutable_data();
    const double *la = lat.data(), *lo = lon.data();
    {
      py::gil_scoped_release release;
      checkLatLon(la, lo, n, shape);
      parallelBlocks(n, [&](std::size_t b, std::size_t e) { snap->elevationAt(la + b, lo + b, e - b, o + b); });
    }
    return out;
  }

  py::dict pick(const InArray& origins, const InArray& directions) {
    const auto shape = shapeOf(origins);
    if (shape.size() != 2 || shape[1] != 3)
      throw std::invalid_argument("origins has shape " + shapeText(shape) + ": expected (n, 3) ECEF metres");
    if (shapeOf(directions) != shape)
      throw std::invalid_argument("directions has shape " + shapeText(shapeOf(directions)) +
                                  " but origins has shape " + shapeText(shape));
    const std::size_t n = std::size_t(shape[0]);
    const double *o = origins.data(), *d = directions.data();
    std::vector<py::ssize_t> rows{py::ssize_t(n)};
    auto hit = newArray<bool>(rows);
    auto kind = newArray<std::uint8_t>(rows);
    auto surface = newArray<std::uint8_t>(rows);
    auto lat = newArray<double>(rows), lon = newArray<double>(rows), h = newArray<double>(rows),
         dist = newArray<double>(rows);
    auto p = newArray<double>(rows, 3);
    {
      py::gil_scoped_release release;
      std::vector<geocean::pick::PickRay> rays(n);
      for (std::size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 3; ++k) {
          if (!std::isfinite(o[3 * i + k]))
            throw std::invalid_argument("origins[" + std::to_string(i) + ", " + std::to_string(k) +
                                        "] = " + num(o[3 * i + k]) + " is not finite");
          if (!std::isfinite(d[3 * i + k]))
            throw std::invalid_argument("directions[" + std::to_string(i) + ", " + std::to_string(k) +
                                        "] = " + num(d[3 * i + k]) + " is not finite");
        }
        rays[i] = {{o[3 * i], o[3 * i + 1], o[3 * i + 2]}, {d[3 * i], d[3 * i + 1], d[3 * i + 2]}};
        if (!(glm::length(rays[i].dir) > 0.0))
          throw std::invalid_argument("directions[" + std::to_string(i) + "] is zero");
      }
      std::vector<geocean::pick::PickResult> res(n);
      if (n > 0) pickerFor(rays)->pickBatch(rays.data(), n, res.data());
      auto* hp = hit.mutable_data();
      auto* kp = kind.mutable_data();
      auto* sp = surface.mutable_data();
      double *lap = lat.mutable_data(), *lop = lon.mutable_data(), *hhp = h.mutable_data(),
             *dp = dist.mutable_data(), *pp = p.mutable_data();
      for (std::size_t i = 0; i < n; ++i) {
        const auto& r = res[i];
        hp[i] = r.hit;
        kp[i] = std::uint8_t(r.kind);
        sp[i] = r.hit ? std::uint8_t(r.surface) : std::uint8_t(255);
        lap[i] = r.hit ? r.latDeg : kNaN;
        lop[i] = r.hit ? r.lonDeg : kNaN;
        hhp[i] = r.hit ? r.heightM : kNaN;
        dp[i] = r.hit ? r.distanceM : kNaN;
        for (int k = 0; k < 3; ++k) pp[3 * i + k] = r.hit ? r.pointEcef[k] : kNaN;
      }
    }
    py::dict out;
    out["hit"] = hit;
    out["kind"] = kind;
    out["surface"] = surface;
    out["lat"] = lat;
    out["lon"] = lon;
    out["height_m"] = h;
    out["distance_m"] = dist;
    out["point_ecef_m"] = p;
    return out;
  }

  double significantWaveHeightM() const {
    try {
      return ocean_.current()->significantWaveHeightM();
    } catch (const oc::NotReady& e) {
      throw NotReadyError(std::string("Ocean.significant_wave_height_m: ") + e.what());
    }
  }

  // For the benchmark: the same façade batch as query() into C++ vectors,
  // no Python in the loop; the best of `repeats` wall times in seconds.
  // allocateEach: fresh outputs per call (as query() makes numpy arrays,
  // page faults included); else allocated and touched once before timing.
  double timeFacadeBatch(const InArray& lat, const InArray& lon, double t, int repeats, bool allocateEach) const {
    const std::size_t n = std::size_t(lat.size());
    if (std::size_t(lon.size()) != n) throw std::invalid_argument("lat and lon differ in size");
    const auto snap = ocean_.current();
    const double *la = lat.data(), *lo = lon.data();
    py::gil_scoped_release release;
    struct Buffers {
      std::vector<oc::Surface> s;
      std::vector<float> e;
      std::vector<double> h, nn, v;
      explicit Buffers(std::size_t m) : s(m), e(m), h(m), nn(3 * m), v(m) {}
    };
    std::optional<Buffers> kept;
    if (!allocateEach) kept.emplace(n);
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      std::optional<Buffers> fresh;
      Buffers& b = allocateEach ? fresh.emplace(n) : *kept;
      oc::SurfaceOutputs out{b.s.data(), b.e.data(), nullptr, nullptr, nullptr, nullptr};
      if (snap->sea) out.heightM = b.h.data(), out.normalEnu = b.nn.data(), out.verticalVelocityMps = b.v.data();
      snap->querySurface({la, lo, n, &t, false}, out);
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    return best;
  }

 private:
  // Few rays: a picker over only the cells they cross, with its local
  // origin at the first ray (what `geocean pick --ray` builds, so one ray
  // gives the CLI's answer bit for bit). More: one whole-raster picker per
  // snapshot, built at the first such call (the world's 1.2 M triangles
  // take about a second) around that call's first origin, then reused.
  std::shared_ptr<const geocean::pick::Picker> pickerFor(const std::vector<geocean::pick::PickRay>& rays) {
    const auto snap = ocean_.current();
    if (rays.size() <= kFewRays)
      return std::make_shared<const geocean::pick::Picker>(snap->elevation, snap->classifier(), rays[0].originEcef,
                                                           rays);
    std::lock_guard lock(pickMutex_);
    if (!picker_ || pickerSnap_ != snap) {
      picker_ = std::make_shared<const geocean::pick::Picker>(snap->elevation, snap->classifier(), rays[0].originEcef);
      pickerSnap_ = snap;
    }
    return picker_;
  }
  static constexpr std::size_t kFewRays = 16;

  oc::Ocean ocean_;
  std::mutex pickMutex_;
  std::shared_ptr<const geocean::pick::Picker> picker_;
  std::shared_ptr<const oc::Snapshot> pickerSnap_;
};

}  // namespace

PYBIND11_MODULE(_geocean, m) {
  m.doc() = "Geocean's C++ core (pybind11 over plugin/ocean's façade); use the geocean package.";
  static py::exception<geocean::raster::RasterError> rasterError(m, "RasterError", PyExc_OSError);
  static py::exception<NotReadyError> notReadyError(m, "NotReadyError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const geocean::raster::RasterError& e) {
      rasterError(e.what());
    } catch (const NotReadyError& e) {
      notReadyError(e.what());
    } catch (const oc::NotReady& e) {
      notReadyError(e.what());
    }
  });
  m.attr("SURFACE_NAMES") = py::make_tuple("ocean", "land", "lake");
  m.def(
      "_beaufort_wind_mps",
      [](int b) {
        const auto sea = geocean::waves::SeaState::fromBeaufort(b);
        if (!sea) throw std::invalid_argument("beaufort = " + std::to_string(b) + " is not a Beaufort number 0 .. 12");
        return sea->windSpeedMps;
      },
      "Wind speed (m/s at 19.5 m) of the middle of Beaufort class b (WMO).");
  m.def("_data_address", [](const InArray& a) { return reinterpret_cast<std::uintptr_t>(a.data()); },
        "Address the binding reads an input array at (tests check no copy is made).");

  py::class_<Core>(m, "Core")
      .def(py::init<std::optional<std::string>, std::optional<std::string>, const std::string&, bool,
                    std::optional<std::string>, const std::string&, double, double, double, std::uint32_t, int, int,
                    double, double, double>(),
           py::arg("mask"), py::arg("elevation"), py::arg("georef"), py::arg("few_lookups"), py::arg("mask_encoding"),
           py::arg("waves"), py::arg("wind_mps"), py::arg("wind_from_deg"), py::arg("fetch_m"), py::arg("seed"),
           py::arg("gerstner_components"), py::arg("noise_octaves"), py::arg("anchor_lat_deg"),
           py::arg("anchor_lon_deg"), py::arg("reference_depth_m"))
      .def("query", &Core::query, py::arg("lat"), py::arg("lon"), py::arg("t"), py::arg("horizontal_velocity"))
      .def("sea_state", &Core::seaState, py::arg("lat"), py::arg("lon"))
      .def("classify", &Core::classify, py::arg("lat"), py::arg("lon"))
      .def("elevation", &Core::elevation, py::arg("lat"), py::arg("lon"))
      .def("pick", &Core::pick, py::arg("origins"), py::arg("directions"))
      .def("significant_wave_height_m", &Core::significantWaveHeightM)
      .def("_time_facade_batch", &Core::timeFacadeBatch, py::arg("lat"), py::arg("lon"), py::arg("t"),
           py::arg("repeats"), py::arg("allocate_each"));
}
