# Sourced by the sweep tests: writes the sweep of the paper's Exp 2 the issue asks for, 128 runs
# (pipelines 1..32 x dirty_ratio 0.2, 0.4 x memory 128, 256 GB), to the file $1.
#   exp2_sweep FILE SOURCE_DIR
exp2_sweep() {
  cat >"$1" <<SWEEP
# The paper's Exp 2 (paper profile), 128 runs.
scenario = "$2/scenarios/paper/exp2.toml"

[[axes]]
key = "pipelines.count"
range = { from = 1, to = 32, step = 1 }

[[axes]]
key = "hosts.0.page_cache.dirty_ratio"
values = [0.2, 0.4]

[[axes]]
key = "hosts.0.memory"
values = ["128 GB", "256 GB"]
SWEEP
}

# results.csv without its last two columns (wall_s, sim_wall_s: the only ones that vary).
without_wall_times() {
  sed -E 's/,[^,]*,[^,]*$//' "$1"
}
