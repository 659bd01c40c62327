// cli_numbers.h: the numbers of command-line options, parsed whole and checked, for the
// example programs.

#ifndef IGAPARAM_CLI_NUMBERS_H
#define IGAPARAM_CLI_NUMBERS_H

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace cli {

/// A command-line mistake: reported with the usage text and exit code 2.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// A finite number that must be the whole text ("1e-3", not "1e-3x").
inline double number(const std::string &option, const std::string &text) {
  size_t used = 0;
  double v = NAN;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception &) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw UsageError(option + " expects a number, not '" + text + "'");
  return v;
}

/// A number > 0.
inline double positive(const std::string &option, const std::string &text) {
  const double v = number(option, text);
  if (!(v > 0.0)) throw UsageError(option + " expects a positive number, not '" + text + "'");
  return v;
}

/// An integer in [lo, hi].
inline int integer(const std::string &option, const std::string &text, int lo, int hi) {
  const double v = number(option, text);
  if (v != std::floor(v) || v < lo || v > hi)
    throw UsageError(option + " expects an integer from " + std::to_string(lo) + " to " + std::to_string(hi) +
                     ", not '" + text + "'");
  return int(v);
}

/// "A,B,C": from `least` to `most` numbers separated by commas.
inline std::vector<double> numbers(const std::string &option, const std::string &text, size_t least, size_t most) {
  std::vector<double> v;
  size_t at = 0;
  while (true) {
    const size_t comma = text.find(',', at);
    v.push_back(number(option, text.substr(at, comma == std::string::npos ? std::string::npos : comma - at)));
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  if (v.size() < least || v.size() > most)
    throw UsageError(option + " expects " + std::to_string(least) + (least == most ? "" : " to " + std::to_string(most)) +
                     " numbers separated by commas, not '" + text + "'");
  return v;
}

}  // namespace cli

#endif  // IGAPARAM_CLI_NUMBERS_H
