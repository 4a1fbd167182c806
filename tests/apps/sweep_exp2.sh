# Sourced by the sweep tests.

# The shipped sweep of the paper's Exp 2 (128 runs).
exp2_sweep_file() { echo "$1/scenarios/sweeps/exp2.toml"; }

# results.csv without its last two columns (wall_s, sim_wall_s: the only ones that vary).
without_wall_times() {
  sed -E 's/,[^,]*,[^,]*$//' "$1"
}
