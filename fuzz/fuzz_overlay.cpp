// libFuzzer target for the overlay reader (built with -DLIFTMAP_FUZZ=ON, run by `make fuzz`): its three files in
// one input, read against the octahedron and used as `liftmap transfer` uses them (overlay_as_fuzzed). Bad input
// must end in IoError or InvalidInputError; anything else (a crash, a sanitizer report, another exception, a hang)
// is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/errors.h"
#include "overlay_as_fuzzed.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    liftmap::fuzz::overlay_as_fuzzed(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const liftmap::IoError&) {
  } catch (const liftmap::InvalidInputError&) {
  }
  return 0;
}
