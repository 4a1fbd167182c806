// libFuzzer target: the sweep readers (fuzz/sweep_property.hpp states their contracts). An
// input that begins with '{' is a results file (JSON lines: no sweep file, TOML, can begin so),
// any other a sweep file, read as if it were PAGECACHE_FUZZ_SOURCE_NAME so that the shipped
// sweeps among the seeds find their base scenarios. Run it with fuzz/run.

#include "sweep_property.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const bool results = !text.empty() && text.front() == '{';
  const std::string broken =
      results ? pagecache::fuzz::check_results_bytes(text) : pagecache::fuzz::check_sweep_text(text, PAGECACHE_FUZZ_SOURCE_NAME);
  if (!broken.empty()) {
    std::fprintf(stderr, "%s property broken: %s\n", results ? "results file" : "sweep file", broken.c_str());
    std::abort();
  }
  return 0;
}
