// The calibration's inputs on any bytes: the marker layout (YAML) or the table points (CSV), by
// the first byte.
#include "fuzz_input.h"
#include "p4/core/error.h"
#include "p4/io/calib_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  try {
    if ((data[0] & 1) != 0) {
      (void)p4::ReadMarkerLayout(p4::fuzz::WriteInput(data + 1, size - 1, ".yaml"));
    } else {
      (void)p4::ReadPointMatches(p4::fuzz::WriteInput(data + 1, size - 1, ".csv"));
    }
  } catch (const p4::Error&) {
  }
  return 0;
}
