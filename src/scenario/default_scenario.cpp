// The scenario `pcsim run` uses when given none: the paper's Exp 1 at 100 GB, which shows reads
// from disk, cache hits, the dirty limit and forced flushing, the periodic flusher, and
// eviction under memory pressure.

#include <pagecache/scenario.hpp>

namespace pagecache {

const std::string& default_scenario_text() {
  static const std::string text = R"(# The paper's Exp 1 at 100 GB (embedded default of `pcsim run`).
title = "Exp 1: one pipeline of three tasks, 100 GB files, local disk"
profile = "paper"
memory_sample_interval = "1 s"

[[hosts]]
name = "node"
cores = 32
memory = "268 GB"
memory_read_bw = "4812 MB/s"
memory_write_bw = "4812 MB/s"

[[hosts.disks]]
name = "ssd"
read_bw = "465 MB/s"
write_bw = "465 MB/s"
capacity = "450 GiB"

[pipelines]
count = 1
file_size = "100 GB"
tasks = 3
cpu_time = "155 s"
chunk_size = "100 MB"
)";
  return text;
}

}  // namespace pagecache
