#pragma once
// FileTable: the files a host's page cache knows: name, size and the device holding them.

#include "cache/block.hpp"

#include <pagecache/devices.hpp>
#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cstdint>
#include <string>
#include <deque>

namespace pagecache::cache {

class IoController;

/// A file stored on another host and reached over a network route (an NFS mount): reads go to
/// that host's I/O controller, which serves them from its page cache or its disk.
struct RemoteFile {
  IoController* server = nullptr;
  FileId server_file = 0;
  const Route* route = nullptr;
};

struct FileInfo {
  std::string name;
  std::int64_t size = 0;
  const Disk* disk = nullptr;  // local files
  RemoteFile remote;           // remote files (disk == nullptr)
  bool is_remote() const noexcept { return remote.server != nullptr; }
};

// Files are added while the simulation runs (remote files, on first use) and processes hold
// references to their FileInfo across waits: a deque keeps those references valid.
class FileTable {
 public:
  FileId add(std::string name, std::int64_t size, const Disk& disk) {
    if (size < 0) throw ConfigError(fmt::format("file '{}': negative size {} bytes", name, size));
    files_.push_back({std::move(name), size, &disk, RemoteFile{}});
    return static_cast<FileId>(files_.size() - 1);
  }
  FileId add_remote(std::string name, std::int64_t size, RemoteFile remote) {
    files_.push_back({std::move(name), size, nullptr, remote});
    return static_cast<FileId>(files_.size() - 1);
  }
  const FileInfo& operator[](FileId file) const { return files_.at(file); }
  FileInfo& operator[](FileId file) { return files_.at(file); }
  std::size_t size() const noexcept { return files_.size(); }

 private:
  std::deque<FileInfo> files_;
};

}  // namespace pagecache::cache
