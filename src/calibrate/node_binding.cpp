#include "calibrate/node_binding.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>

#include <linux/mempolicy.h>  // MPOL_BIND, MPOL_DEFAULT: the uapi header, without libnuma's numaif.h
#include <sched.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace pagecache::calibrate {

namespace {

constexpr std::size_t kBits = 8 * sizeof(unsigned long);

bool has(const std::vector<unsigned long>& mask, int bit) {
  const auto word = static_cast<std::size_t>(bit) / kBits;
  return word < mask.size() && (mask[word] >> (static_cast<std::size_t>(bit) % kBits) & 1UL) != 0;
}

void set(std::vector<unsigned long>& mask, int bit) {
  const auto word = static_cast<std::size_t>(bit) / kBits;
  if (word >= mask.size()) mask.resize(word + 1, 0);
  mask[word] |= 1UL << (static_cast<std::size_t>(bit) % kBits);
}

// The calling thread's CPU affinity, in a mask as large as the kernel's CPU count needs (it
// refuses a smaller one with EINVAL).
std::vector<unsigned long> current_affinity() {
  for (std::size_t words = 1024 / kBits; words <= (std::size_t{1} << 20) / kBits; words *= 2) {
    std::vector<unsigned long> mask(words, 0);
    if (::sched_getaffinity(0, words * sizeof(unsigned long), reinterpret_cast<cpu_set_t*>(mask.data())) == 0) return mask;
    if (errno != EINVAL) break;
  }
  throw BindingError(errno, "sched_getaffinity of this thread");
}

int set_affinity(const std::vector<unsigned long>& mask) {
  return ::sched_setaffinity(0, mask.size() * sizeof(unsigned long), reinterpret_cast<const cpu_set_t*>(mask.data()));
}

}  // namespace

int SystemNodeBinding::run_on(const NumaNode& node) {
  if (saved_.empty()) saved_ = current_affinity();
  std::vector<unsigned long> mask(saved_.size(), 0);
  std::vector<int> allowed;
  for (const int cpu : node.cpus) {
    if (!has(saved_, cpu)) continue;  // outside this process's affinity or cpuset
    set(mask, cpu);
    allowed.push_back(cpu);
  }
  if (allowed.empty()) {
    throw BindingError(EINVAL, fmt::format("none of node {}'s CPUs ({}) is among this process's (its affinity, or its cpuset)", node.id,
                                           kernel_list_text(node.cpus)));
  }
  if (set_affinity(mask) != 0) throw BindingError(errno, fmt::format("sched_setaffinity to node {}'s CPUs {}", node.id, kernel_list_text(allowed)));
  return static_cast<int>(allowed.size());
}

void SystemNodeBinding::allocate_on(int node) {
  std::vector<unsigned long> nodes;
  set(nodes, node);
  // The kernel reads maxnode - 1 bits (a historical off-by-one libnuma also passes for).
  if (::syscall(SYS_set_mempolicy, MPOL_BIND, nodes.data(), nodes.size() * kBits + 1) != 0) {
    throw BindingError(errno, fmt::format("set_mempolicy(MPOL_BIND) to node {}", node));
  }
}

std::string SystemNodeBinding::release() noexcept {
  std::string failed;
  if (::syscall(SYS_set_mempolicy, MPOL_DEFAULT, nullptr, 0) != 0) failed = fmt::format("set_mempolicy(MPOL_DEFAULT): {}", std::strerror(errno));
  if (!saved_.empty() && set_affinity(saved_) != 0) {
    failed += fmt::format("{}sched_setaffinity back to the CPUs before: {}", failed.empty() ? "" : "; ", std::strerror(errno));
  }
  return failed;
}

}  // namespace pagecache::calibrate
