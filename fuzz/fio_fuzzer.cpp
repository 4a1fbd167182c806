// libFuzzer target: the bytes as an fio job file, through
// pagecache::formats::fio::read_fio_job_file (fuzz/fio_property.hpp states the contract). Seed it
// with fuzz/seeds/*.fio and fio's examples (/usr/share/doc/fio/examples/, package fio-examples)
// and fuzz/fio.dict (fuzz/run does).

#include "fio_property.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string broken = pagecache::fuzz::check_fio_text(text, "fuzz.fio");
  if (!broken.empty()) {
    std::fprintf(stderr, "fio property broken: %s\n", broken.c_str());
    std::abort();
  }
  return 0;
}
