#include "calibrate/numa_steps.hpp"

#include "calibrate/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>

namespace pagecache::calibrate {

namespace {

// The binding undone when the step ends, however it ends; what failed kept for the notes.
class Release {
 public:
  Release(NodeBinding& binding, std::string& failed) : binding_(binding), failed_(failed) {}
  ~Release() { failed_ = binding_.release(); }
  Release(const Release&) = delete;
  Release& operator=(const Release&) = delete;

 private:
  NodeBinding& binding_;
  std::string& failed_;
};

// Each probe with the memory local, then remote, one after the other so that the two see the
// machine alike.
void measure_pairs(NumaFigures& n, Session& s, NodeBinding& binding, const NumaProbes& probes) {
  const auto place = [&binding](int node) { return [&binding, node] { binding.allocate_on(node); }; };
  const auto both = [&](NumaPair& pair, const std::function<Figure(int node)>& measure) {
    pair.local = measure(n.local);
    pair.remote = measure(n.remote);
  };
  n.first_touch.placement = fmt::format("one thread on node {}'s CPUs touching new memory on node {} or {}", n.local, n.remote, n.local);
  both(n.first_touch, [&](int node) {
    binding.allocate_on(node);
    return probes.first_touch();
  });
  n.copy.placement = fmt::format("one thread on node {}'s CPUs copying memory on node {} or {} into a buffer on node {}", n.local, n.remote,
                                 n.local, n.local);
  // The buffers are fresh mappings (256 MiB, 32 with --quick): each page goes where the policy
  // says at its first touch, the source's before the destination's policy is set.
  both(n.copy, [&](int node) { return probes.copy(place(node), place(n.local)); });
  n.aggregate_read.placement = fmt::format("{} threads on node {}'s CPUs reading a cached file whose pages are on node {} or {}, into buffers on "
                                           "node {}",
                                           n.threads, n.local, n.remote, n.local, n.local);
  both(n.aggregate_read, [&](int node) {
    const std::filesystem::path file = s.scratch.file(fmt::format("numa-node-{}", node));
    binding.allocate_on(node);  // the page cache takes the writer's memory policy
    probes.cache(file);
    binding.allocate_on(n.local);  // the readers' threads and buffers take it from here
    const Figure f = probes.read_together(file, n.threads);
    s.scratch.remove(file);  // its cached pages go with it
    return f;
  });
}

}  // namespace

NumaProbes numa_probes(const Session& s, int nodes) {
  // A node holds its share of the memory: MPOL_BIND does not fall back to another node.
  const std::int64_t touch = touch_bytes(s.sys) / std::max(1, nodes);
  return NumaProbes{
      [&s](const std::function<void()>& source, const std::function<void()>& destination) {
        return copy_figure(s, s.budget.repeat, source, destination);
      },
      [&s, touch] { return first_touch_figure(s, touch); },
      [&s](const std::filesystem::path& file) { write_cached(s, file); },
      [&s](const std::filesystem::path& file, int threads) { return cached_reads_figure(s, file, threads); }};
}

void measure_numa(Calibration& c, Session& s, NodeBinding& binding, const NumaProbes& probes) {
  NumaFigures& n = c.numa;
  const std::vector<NumaNode>& nodes = n.topology.nodes;
  if (nodes.size() < 2) {
    n.why = kOneNumaNode;
    return;
  }
  const auto home = std::find_if(nodes.begin(), nodes.end(), [](const NumaNode& node) { return !node.cpus.empty(); });
  if (home == nodes.end()) {
    n.why = fmt::format("no online NUMA node lists a CPU ({}): the ratios were not measured; the platform has no [hosts.numa]",
                        n.topology.root.string());
    return;
  }
  n.local = home->id;
  n.remote = (home == nodes.begin() ? nodes[1] : nodes.front()).id;
  s.next(fmt::format("memory: node {}'s and node {}'s, from node {}'s CPUs", n.local, n.remote, n.local));
  try {
    const Release release(binding, n.release_failed);
    n.threads = binding.run_on(*home);
    measure_pairs(n, s, binding, probes);
    n.measured = true;
  } catch (const BindingError& e) {
    n.why = fmt::format("the NUMA ratios were not measured: {}; the platform has no [hosts.numa]", e.what());
  }
}

}  // namespace pagecache::calibrate
