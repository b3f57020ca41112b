// What eval and replay read back of a run, and the simulator's truth, on any bytes (by the first
// byte): trajectory.csv, events.jsonl, truth.csv, truth_visibility.csv (for a 2-camera rig), and a
// TT3D flight file.
#include "fuzz_input.h"
#include "p4/core/error.h"
#include "p4/geometry/rig.h"
#include "p4/io/event_files.h"
#include "p4/io/flight_file.h"
#include "p4/io/run_files.h"
#include "p4/io/truth_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const uint8_t which = data[0] % 5;
  const std::string path = p4::fuzz::WriteInput(data + 1, size - 1, which == 1 ? ".jsonl" : ".csv");
  try {
    switch (which) {
      case 0:
        (void)p4::ReadTrajectoryCsv(path);
        break;
      case 1:
        (void)p4::ReadEventsJsonl(path);
        break;
      case 2:
        (void)p4::ReadTruthCsv(path);
        break;
      case 3: {
        p4::Rig rig;
        rig.cameras.resize(2);
        rig.cameras[0].name = "cam0";
        rig.cameras[1].name = "cam1";
        (void)p4::ReadVisibilityCsv(path, rig);
        break;
      }
      default:
        (void)p4::ReadTt3dFlight(path, 0.0);
        break;
    }
  } catch (const p4::Error&) {
  }
  return 0;
}
