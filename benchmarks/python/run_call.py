"""The cost of one pcsim.run call, in one process: REPS calls, each timed, the median printed in
seconds (benchmarks/api_run.cpp is the same through the C++ API).
    run_call.py SCENARIO REPS [KEY=VALUE ...]"""

import statistics
import sys
import time

import pcsim

scenario, reps = sys.argv[1], int(sys.argv[2])
sets = dict(arg.split("=", 1) for arg in sys.argv[3:])
seconds = []
for _ in range(reps):
    start = time.perf_counter()
    pcsim.run(scenario, set=sets)
    seconds.append(time.perf_counter() - start)
print(f"{statistics.median_low(seconds):.9f}")
