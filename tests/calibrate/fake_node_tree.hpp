#pragma once
// A fake /sys/devices/system/node folder in the temporary folder, removed with the object.

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

struct FakeNodeTree {
  std::filesystem::path root = std::filesystem::temp_directory_path() / ("pcsim-numa-" + std::to_string(::getpid()));
  FakeNodeTree() { std::filesystem::remove_all(root); }
  ~FakeNodeTree() { std::filesystem::remove_all(root); }
  FakeNodeTree(const FakeNodeTree&) = delete;
  FakeNodeTree& operator=(const FakeNodeTree&) = delete;
  void write(const std::filesystem::path& file, const std::string& text) const {
    std::filesystem::create_directories((root / file).parent_path());
    std::ofstream(root / file) << text;
  }
};
