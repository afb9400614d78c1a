// libFuzzer target for liftmap's file readers (built with -DLIFTMAP_FUZZ=ON, run by `make fuzz`). The reader
// is chosen at compile time by LIFTMAP_FUZZ_READER (see read_as_fuzzed). Bad input must end in IoError or
// InvalidInputError; anything else (a crash, a sanitizer report, another exception, a hang) is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/errors.h"
#include "read_as_fuzzed.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    liftmap::fuzz::read_as_fuzzed(LIFTMAP_FUZZ_READER, std::string(reinterpret_cast<const char*>(data), size));
  } catch (const liftmap::IoError&) {
  } catch (const liftmap::InvalidInputError&) {
  }
  return 0;
}
