// Strict parsing of coordinates and CSV point rows for the CLI, with
// messages that name the row and the offending value.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace geocean::app {

struct PointRow {
  double latDeg = 0, lonDeg = 0;
  std::optional<double> timeS;
};

// Parses a finite double consuming the whole token (spaces trimmed).
std::optional<double> parseNumber(std::string_view token);

// Validates latitude in [-90, 90] and longitude in [-180, 360]; returns an
// error message naming `what` and the value, or empty.
std::string checkLatLon(double latDeg, double lonDeg, std::string_view what);

// Validates a finite simulation time against waves::kMaxTimeS
// (plugin/waves/TimeRange.h); returns an error starting with `what` and
// naming the value, or empty.
std::string checkTime(double tS, std::string_view what);

// Parses "lat,lon[,time]". Returns the error (naming the row number and the
// value) or empty on success.
std::string parsePointRow(std::string_view line, long rowNumber, PointRow& out);

// True for a header row such as "lat,lon,time".
bool isHeaderRow(std::string_view line);

// Splits "a,b,c" into exactly n finite numbers; the error names `what`, the
// token and the text, or is empty.
std::string parseNumberList(std::string_view text, std::size_t n, std::string_view what, std::vector<double>& out);

// A row of `geocean pick --rays`: ECEF origin (m) and direction.
struct RayRow {
  double origin[3] = {0, 0, 0}, direction[3] = {0, 0, 0};
};

// True for the first row of a --rays file when it is a header ("ox,oy,oz,dx,dy,dz").
bool isRayHeaderRow(std::string_view line);

// Parses "ox,oy,oz,dx,dy,dz" (six finite numbers, a direction of non-zero
// length). Returns the error, starting with `what`, or empty on success.
std::string parseRayRow(std::string_view line, std::string_view what, RayRow& out);

}  // namespace geocean::app
