#include "scenario/toml_reader.hpp"


namespace pagecache::scenario {

std::string location(const toml::source_region& where, const std::string& file) {
  if (where.path != nullptr) {
    // An override's value, or an option's (load_workflow), is parsed with the option as its
    // source (loader.cpp).
    for (const char* option : {"--set ", "--platform ", "--files-host ", "--hosts "}) {
      if (where.path->rfind(option, 0) == 0) return *where.path;
    }
    return fmt::format("{}:{}:{}", *where.path, where.begin.line, where.begin.column);
  }
  // A document pcsim made around a file the command line named (a fio job file's run, a
  // platform shown alone): the file. (A table --set makes has the option as its source.)
  if (where.begin.line == 0) return file;
  return fmt::format("{}:{}:{}", file, where.begin.line, where.begin.column);
}

InputPlace input_place(const toml::source_region& where, const std::string& file, std::string key) {
  if (where.path != nullptr) {
    for (const char* option : {"--set ", "--platform ", "--files-host ", "--hosts "}) {
      if (where.path->rfind(option, 0) == 0) return InputPlace{.file = {}, .line = 0, .key = std::move(key)};
    }
    return InputPlace{.file = *where.path, .line = static_cast<int>(where.begin.line), .key = std::move(key)};
  }
  return InputPlace{.file = file, .line = static_cast<int>(where.begin.line), .key = std::move(key)};
}

}  // namespace pagecache::scenario
