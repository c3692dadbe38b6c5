#include "globe/app/QueryIo.h"

#include "plugin/ocean/TimeRange.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace geocean::app {

namespace {
std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}
// Shortest round trip: the value as the user wrote it (1e+33, not 9.99...e+32).
std::string fmtValue(double v) {
  char b[40];
  const auto r = std::to_chars(b, b + sizeof b, v);
  return std::string(b, r.ptr);
}
}  // namespace

std::optional<double> parseNumber(std::string_view token) {
  token = trim(token);
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  double v = 0;
  const auto [p, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || p != token.data() + token.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::string checkTime(double tS, std::string_view what) {
  if (waves::timeInRange(tS)) return {};
  return std::string(what) + " " + fmtValue(tS) + " s is outside " + waves::kTimeRangeText +
         " (beyond, the waves' phase w t keeps no precision)";
}

std::string checkLatLon(double lat, double lon, std::string_view what) {
  if (!(lat >= -90.0 && lat <= 90.0))
    return std::string(what) + ": latitude " + fmtValue(lat) + " is outside [-90, 90]";
  if (!(lon >= -180.0 && lon <= 360.0))
    return std::string(what) + ": longitude " + fmtValue(lon) + " is outside [-180, 360]";
  return {};
}

bool isHeaderRow(std::string_view line) {
  line = trim(line);
  return line.size() >= 3 && (line.substr(0, 3) == "lat" || line.substr(0, 3) == "LAT" || line.substr(0, 3) == "Lat");
}

std::string parsePointRow(std::string_view line, long row, PointRow& out) {
  std::string_view fields[4];
  int n = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    if (n == 3) return "row " + std::to_string(row) + ": more than 3 fields in '" + std::string(trim(line)) + "'";
    fields[n++] = line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  const std::string where = "row " + std::to_string(row);
  if (n < 2) return where + ": expected 'lat,lon[,time]', got '" + std::string(trim(line)) + "'";
  const char* names[3] = {"latitude", "longitude", "time"};
  double v[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const auto p = parseNumber(fields[i]);
    if (!p) return where + ": " + names[i] + " '" + std::string(trim(fields[i])) + "' is not a finite number";
    v[i] = *p;
  }
  if (auto e = checkLatLon(v[0], v[1], where); !e.empty()) return e;
  if (n == 3)
    if (auto e = checkTime(v[2], where + ": time"); !e.empty()) return e;
  out.latDeg = v[0];
  out.lonDeg = v[1];
  out.timeS = n == 3 ? std::optional<double>(v[2]) : std::nullopt;
  return {};
}

std::string parseNumberList(std::string_view text, std::size_t n, std::string_view what, std::vector<double>& out) {
  out.clear();
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = text.find(',', pos);
    const std::string_view tok = text.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos);
    const auto v = parseNumber(tok);
    if (!v)
      return std::string(what) + ": '" + std::string(tok) + "' in '" + std::string(text) + "' is not a finite number";
    out.push_back(*v);
    if (comma == std::string_view::npos) break;
    pos = comma + 1;
  }
  if (out.size() != n)
    return std::string(what) + ": expected " + std::to_string(n) + " comma-separated numbers, got " +
           std::to_string(out.size()) + " in '" + std::string(text) + "'";
  return {};
}

bool isRayHeaderRow(std::string_view line) {
  return line.find_first_of("abcdefghijklmnopqrstuvwxyz") != std::string_view::npos &&
         line.find("ox") != std::string_view::npos;
}

std::string parseRayRow(std::string_view line, std::string_view what, RayRow& out) {
  std::vector<double> v;
  v.reserve(6);
  if (auto e = parseNumberList(line, 6, what, v); !e.empty()) return e;
  if (!(std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]) > 0.0)) {
    char b[120];
    std::snprintf(b, sizeof b, ": direction %g,%g,%g is zero", v[3], v[4], v[5]);
    return std::string(what) + b;
  }
  for (int i = 0; i < 3; ++i) {
    out.origin[i] = v[i];
    out.direction[i] = v[3 + i];
  }
  return {};
}

}  // namespace geocean::app
