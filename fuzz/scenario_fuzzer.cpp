// libFuzzer target: the bytes as scenario text, through pagecache::parse_scenario and back
// through to_toml (fuzz/scenario_property.hpp states the contract). Run it with fuzz/run.

#include "scenario_property.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string broken = pagecache::fuzz::check_scenario_text(text, PAGECACHE_FUZZ_SOURCE_NAME);
  if (!broken.empty()) {
    std::fprintf(stderr, "scenario property broken: %s\n", broken.c_str());
    std::abort();
  }
  return 0;
}
