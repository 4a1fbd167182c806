// libFuzzer target: the bytes as each file of the validation data and of the measurements
// `validate --here` keeps, through their readers (fuzz/validation_property.hpp states the
// contract). Run it with fuzz/run.

#include "validation_property.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string broken = pagecache::fuzz::check_validation_text(text);
  if (!broken.empty()) {
    std::fprintf(stderr, "validation data property broken: %s\n", broken.c_str());
    std::abort();
  }
  return 0;
}
