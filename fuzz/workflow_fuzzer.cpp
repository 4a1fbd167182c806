// libFuzzer target: the bytes as a workflow JSON file, through
// pagecache::formats::wfformat::read_workflow_json (fuzz/workflow_property.hpp states the contract).
// Seed it with the workflows in inputs/ (wfcommons/instances/*.json, wrench-cache/*.json) and
// fuzz/workflow.dict (fuzz/run does).

#include "import_property.hpp"
#include "workflow_property.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string broken = pagecache::fuzz::check_workflow_text(text, "fuzz.json");
  // What the reader accepts goes on into a scenario (workflow_import.cpp, the loader's checks).
  if (broken.empty() && pagecache::fuzz::reads_as_workflow(text)) broken = pagecache::fuzz::check_workflow_import(text);
  if (!broken.empty()) {
    std::fprintf(stderr, "workflow property broken: %s\n", broken.c_str());
    std::abort();
  }
  return 0;
}
