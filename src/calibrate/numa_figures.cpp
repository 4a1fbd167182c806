#include "calibrate/numa_figures.hpp"

#include "calibrate/text.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::calibrate {

namespace {

std::string nodes_toml(const NumaFigures& n) {
  std::string cpus;
  for (const NumaNode& node : n.topology.nodes) {
    cpus += fmt::format("{}node {}: {}", cpus.empty() ? "" : ", ", node.id, node.cpus.empty() ? "none" : kernel_list_text(node.cpus));
  }
  return fmt::format("# the online nodes, {}/online: {} (CPUs: {}); memory placed with set_mempolicy(MPOL_BIND), threads with "
                     "sched_setaffinity\nnodes = {}\n",
                     n.topology.root.string(), n.topology.online, cpus, n.topology.nodes.size());
}

std::string ratio_toml(const NumaFigures& n, const NumaKey& k) {
  const NumaPair& p = n.*k.pair;
  if (!p.measured()) return fmt::format("# {} not set: {} / {}\n", k.key, p.remote.how, p.local.how);
  std::string out = fmt::format("# {}: remote / local\n", p.placement);
  out += fmt::format("#   remote, node {}: {}: {}\n#   local, node {}: {}: {}\n", n.remote, rate_text(p.remote.value), p.remote.how, n.local,
                     rate_text(p.local.value), p.local.how);
  if (p.ratio() > 1.0) out += "#   above 1: written as measured (see the notes)\n";
  return out + fmt::format("{} = {:.3f}\n", k.key, p.ratio());
}

// A ratio above 1 or from noisy figures, nodes of unequal CPUs.
std::vector<std::string> measured_notes(const NumaFigures& n) {
  std::vector<std::string> notes;
  for (const NumaKey& k : kNumaKeys) {
    const NumaPair& p = n.*k.pair;
    if (p.measured() && p.ratio() > 1.0) {
      notes.push_back(fmt::format("{} is {:.3f}, above 1: the {} went faster with node {}'s memory than with its own node {}'s (noise, or nodes "
                                  "equally near); written as measured",
                                  k.key, p.ratio(), k.what, n.remote, n.local));
    }
    if (const double spread = std::max(p.local.spread_pct, p.remote.spread_pct); p.measured() && spread > 20.0) {
      notes.push_back(fmt::format("{}: a measurement of it varied by {:.0f} % between repetitions; the ratio is of the medians", k.key, spread));
    }
  }
  std::string counts;
  bool even = true;
  for (const NumaNode& node : n.topology.nodes) {
    counts += fmt::format("{}node {}: {}", counts.empty() ? "" : ", ", node.id, node.cpus.size());
    even = even && node.cpus.size() == n.topology.nodes.front().cpus.size();
  }
  if (!even) notes.push_back(fmt::format("the NUMA nodes have unequal CPUs ({}); [hosts.numa] splits the cores evenly", counts));
  return notes;
}

}  // namespace

std::string numa_toml(const NumaFigures& n) {
  if (!n.measured || n.topology.nodes.size() > kMaxModelledNodes) return "";
  std::string out = "\n[hosts.numa]\n" + nodes_toml(n);
  for (const NumaKey& k : kNumaKeys) out += ratio_toml(n, k);
  return out;
}

std::vector<std::string> numa_notes(const NumaFigures& n) {
  std::vector<std::string> notes;
  if (n.measured) notes = measured_notes(n);
  else notes.push_back(n.why);
  if (n.measured && n.topology.nodes.size() > kMaxModelledNodes) {
    notes.push_back(fmt::format("{} NUMA nodes: pcsim models at most {}, so the platform has no [hosts.numa]; the ratios measured between "
                                "node {} and node {} are in these notes",
                                n.topology.nodes.size(), kMaxModelledNodes, n.local, n.remote));
  }
  if (!n.release_failed.empty()) {
    notes.push_back(fmt::format("after the NUMA measurements, {} failed: what calibrate measured after them ran where they had left it",
                                n.release_failed));
  }
  return notes;
}

}  // namespace pagecache::calibrate
