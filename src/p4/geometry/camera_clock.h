// A camera's clock in the rig's world time (beyond the paper, whose cameras were triggered
// together): free-running webcams and phones start recording at their own moments, tick at their
// own rates and, with a rolling shutter, expose their rows one after another.
//
// World time is the rig's reference clock (by convention the first camera's: offset 0, rate 1).
// A frame stamped `stamp` by its source (the file's timestamp, seconds from the recording's start)
// exposed its top row around
//     t_world = time_offset_s + clock_rate * stamp
// and its row v (pixel rows, centres at integers) line_time_s * v later. Rig files carry the three
// as optional keys per camera (docs/FORMATS.md); a camera without them is in step with the rig's
// clock and has a global shutter.
#pragma once

#include <string>

#include "p4/core/time.h"

namespace p4 {

struct CameraClock {
  double time_offset_s = 0.0;  // world time of the camera's stamp 0, seconds
  double clock_rate = 1.0;     // world seconds per second of the camera's stamps (drift: 1 +- ppm)
  double line_time_s = 0.0;    // rolling shutter: delay of each row after the one above (0: none)
  bool has_offset = false;     // the rig gave the offset (false: unknown, 0 assumed)

  // World time of a stamp (the top row's exposure).
  TimeNs WorldTime(TimeNs stamp) const {
    return FromSeconds(time_offset_s) +
           static_cast<TimeNs>(std::llround(clock_rate * static_cast<double>(stamp)));
  }
  // The camera's stamp of a world time (inverse of WorldTime).
  TimeNs Stamp(TimeNs world) const {
    return static_cast<TimeNs>(
        std::llround(static_cast<double>(world - FromSeconds(time_offset_s)) / clock_rate));
  }
  // Delay of row v's exposure after the top row's, seconds.
  double RowDelay(double row) const { return line_time_s * row; }
  bool InStep() const { return time_offset_s == 0.0 && clock_rate == 1.0 && line_time_s == 0.0; }
};

// Finite numbers, a clock rate within 1 +- 1 % (drift is parts per million: anything more is a
// wrong key), a line time in [0, 1 ms). On failure *error names the key.
bool ValidateCameraClock(const CameraClock& clock, std::string* error);

}  // namespace p4
