#pragma once
// NumaTopology: the machine's online NUMA nodes and the CPUs of each, as sysfs gives them
// (`online` and `nodeN/cpulist` under /sys/devices/system/node, in the kernel's list format
// "0-15,32-47"). Read, not measured; a kernel without NUMA has no node folder: one node.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::calibrate {

/// Where the kernel lists the nodes.
inline const std::filesystem::path kNodeRoot = "/sys/devices/system/node";

/// One online node: its number and its CPUs (none for a node of memory alone).
struct NumaNode {
  int id = 0;
  std::vector<int> cpus;
};

/// The online nodes in increasing order of number.
struct NumaTopology {
  std::vector<NumaNode> nodes;
  std::filesystem::path root;  ///< the folder read
  std::string online;          ///< its `online`, as written ("0-1"); empty without the folder
};

/// Reads `root`/online and each online node's `root`/nodeN/cpulist. No `root` at all: one node
/// 0 (its CPUs not listed). Throws pagecache::Error naming a file missing or malformed.
NumaTopology read_numa_topology(const std::filesystem::path& root = kNodeRoot);

/// The kernel's list format: numbers and ranges "a-b", comma-separated, in increasing order
/// and not overlapping, an optional final newline; empty for none. Throws
/// std::invalid_argument saying what is not in the format.
std::vector<int> parse_kernel_list(std::string_view text);

/// The list format back ("0-3,8"), for messages and comments.
std::string kernel_list_text(const std::vector<int>& numbers);

}  // namespace pagecache::calibrate
