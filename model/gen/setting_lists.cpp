#include "gen/setting_lists.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace vbsim {

std::vector<double> number_list(const ScenarioSettings& settings, const std::string& key,
                                const std::vector<double>& fallback) {
  const std::string unset(1, '\0');  // no value given on a command line can equal it
  const std::string text = settings.text(key, unset);
  if (text == unset) return fallback;
  std::vector<double> out;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    errno = 0;
    const double d = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || errno != 0 || !std::isfinite(d))
      throw std::runtime_error(
          fmt::format("option '--set {}={}': '{}' is not a finite number", key, text, item));
    out.push_back(d);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::vector<double> log_spaced(double lo, double hi, int count) {
  std::vector<double> out;
  for (int i = 0; i < count; ++i)
    out.push_back(count == 1 ? lo : lo * std::pow(hi / lo, static_cast<double>(i) / (count - 1)));
  return out;
}

}  // namespace vbsim
