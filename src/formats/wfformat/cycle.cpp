#include "formats/wfformat/cycle.hpp"

#include <algorithm>
#include <cstdint>

namespace pagecache::formats::wfformat {

std::vector<std::size_t> find_cycle(const std::vector<WfTask>& tasks) {
  enum class Mark : std::uint8_t { Unseen, OnPath, Done };
  std::vector<Mark> mark(tasks.size(), Mark::Unseen);
  struct Step {
    std::size_t task;
    std::size_t next_parent;
  };
  std::vector<Step> path;  // from a root to the current task, each a parent of the one before
  for (std::size_t root = 0; root < tasks.size(); ++root) {
    if (mark[root] != Mark::Unseen) continue;
    mark[root] = Mark::OnPath;
    path.push_back({root, 0});
    while (!path.empty()) {
      Step& top = path.back();
      const std::vector<std::size_t>& parents = tasks[top.task].parents;
      if (top.next_parent == parents.size()) {
        mark[top.task] = Mark::Done;
        path.pop_back();
        continue;
      }
      const std::size_t parent = parents[top.next_parent++];
      if (mark[parent] == Mark::Unseen) {
        mark[parent] = Mark::OnPath;
        path.push_back({parent, 0});  // invalidates `top`, read no more
      } else if (mark[parent] == Mark::OnPath) {
        // The path from `parent` down to here, which lists `parent` again.
        const auto from = std::find_if(path.begin(), path.end(), [&](const Step& s) { return s.task == parent; });
        std::vector<std::size_t> cycle;
        for (auto it = from; it != path.end(); ++it) cycle.push_back(it->task);
        return cycle;
      }
    }
  }
  return {};
}

}  // namespace pagecache::formats::wfformat
