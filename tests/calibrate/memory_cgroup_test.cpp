// calibrate::MemoryCgroup, the memory cgroup of `validate --here --fio --memory-max`, made for
// real: a child writing four times its limit of page cache inside it is held to the limit (the
// cache reclaimed as it goes, the write still whole), and the group is gone with the object.
// Skipped (with a warning) where this user may not make one; CI runs as root.
#include "calibrate/memory_cgroup.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

#include <unistd.h>

namespace fs = std::filesystem;
using pagecache::calibrate::MemoryCgroup;

TEST_CASE("validate --fio --memory-max's MemoryCgroup holds a writer's page cache to its limit and is removed with it", "[fio][calibrate]") {
  constexpr std::int64_t kLimit = std::int64_t{64} << 20;
  std::unique_ptr<MemoryCgroup> group;
  try {
    group = std::make_unique<MemoryCgroup>(kLimit);
  } catch (const pagecache::Error& e) {
    WARN("skipped: " << e.what());
    return;
  }
  const fs::path dir = group->dir();
  CHECK(dir.filename().string().rfind(fmt::format("pcsim-fio-{}-", ::getpid()), 0) == 0);
  CHECK(fs::exists(group->procs()));

  const fs::path file = fs::temp_directory_path() / fmt::format("pcsim-memory-cgroup-test-{}", ::getpid());
  const std::string command =
      fmt::format(R"(sh -c 'echo $$ > "{}" && exec dd if=/dev/zero of="{}" bs=1M count=256 2>/dev/null')", group->procs().string(), file.string());
  const int status = std::system(command.c_str());
  CHECK(status == 0);
  std::error_code ec;
  CHECK(fs::file_size(file, ec) == std::uintmax_t{256} << 20);
  fs::remove(file, ec);

  const std::int64_t peak = group->peak();
  INFO("peak " << peak << " bytes, " << (group->v2() ? "cgroup v2" : "cgroup v1"));
  if (peak >= 0) {  // -1: a v2 kernel without memory.peak
    CHECK(peak > 0);
    CHECK(peak <= kLimit + (std::int64_t{4} << 20));
  }
  group.reset();
  CHECK(!fs::exists(dir));
}
