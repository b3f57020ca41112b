// ReadColorClasses on any bytes (YAML), and the look-up tables built from what reads.
#include "fuzz_input.h"
#include "p4/core/error.h"
#include "p4/io/color_class_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string path = p4::fuzz::WriteInput(data, size, ".yaml");
  try {
    const p4::segment::ColorClassSet classes = p4::ReadColorClasses(path);
    (void)classes.BuildLut();
    (void)classes.MaskOf("ball");
  } catch (const p4::Error&) {
  }
  return 0;
}
