// Strict parsing of coordinates and CSV point rows for the CLI, with
// messages that name the row and the offending value.
#pragma once

#include <optional>
#include <string>
#include <string_view>

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

// Parses "lat,lon[,time]". Returns the error (naming the row number and the
// value) or empty on success.
std::string parsePointRow(std::string_view line, long rowNumber, PointRow& out);

// True for a header row such as "lat,lon,time".
bool isHeaderRow(std::string_view line);

}  // namespace geocean::app
