// libFuzzer target: the bytes as a SimGrid platform file, through read_simgrid_platform
// (fuzz/platform_property.hpp states the contract).

#include "import_property.hpp"
#include "platform_property.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string broken = pagecache::fuzz::check_platform_text(text, "fuzz.xml");
  // What the reader accepts within the fuzz limits goes on into a scenario (simgrid_import.cpp,
  // the loader's checks); larger platforms would slow the search.
  if (broken.empty() && pagecache::fuzz::reads_as_small_platform(text)) broken = pagecache::fuzz::check_platform_import(text);
  if (!broken.empty()) {
    std::fprintf(stderr, "platform property broken: %s\n", broken.c_str());
    std::abort();
  }
  return 0;
}
