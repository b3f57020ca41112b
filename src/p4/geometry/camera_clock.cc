#include "p4/geometry/camera_clock.h"

#include <cmath>
#include <sstream>

namespace p4 {

bool ValidateCameraClock(const CameraClock& clock, std::string* error) {
  std::ostringstream why;
  if (!std::isfinite(clock.time_offset_s) || std::abs(clock.time_offset_s) > 86400.0) {
    why << "time_offset_s: must be a finite number of seconds within a day (got "
        << clock.time_offset_s << ")";
  } else if (!std::isfinite(clock.clock_rate) || std::abs(clock.clock_rate - 1.0) > 0.01) {
    why << "clock_rate: must be within 1 +- 0.01 (a drift of parts per million; got "
        << clock.clock_rate << ")";
  } else if (!std::isfinite(clock.line_time_s) || clock.line_time_s < 0.0 ||
             clock.line_time_s >= 1e-3) {
    why << "line_time_s: must be in [0, 0.001) seconds a row (got " << clock.line_time_s << ")";
  }
  const std::string message = why.str();
  if (message.empty()) return true;
  if (error) *error = message;
  return false;
}

}  // namespace p4
