// libFuzzer target: the bytes as a SimGrid platform file, through read_simgrid_platform
// (fuzz/platform_property.hpp states the contract).

#include "platform_property.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string broken = pagecache::fuzz::check_platform_text(text, "fuzz.xml");
  if (!broken.empty()) {
    std::fprintf(stderr, "platform property broken: %s\n", broken.c_str());
    std::abort();
  }
  return 0;
}
