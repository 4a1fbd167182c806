"""How long pcsim.Result takes to build its DataFrames from a run of 10^6 timeline rows:
111,112 pipelines of three tasks (9 phases each), small files, one host scaled for them.
Prints the rows and the seconds of each table's first access (the run itself not counted).
    PYTHONPATH=build/python python3 benchmarks/python/frames.py [PIPELINES]"""

import sys
import time

import pcsim

pipelines = int(sys.argv[1]) if len(sys.argv) > 1 else 111_112
scenario = f"""
title = "{pipelines} pipelines of small files"
memory_sample_interval = "100 s"
[[hosts]]
name = "node"
cores = {pipelines}
memory = "{pipelines} GB"
memory_read_bw = "{pipelines} GB/s"
memory_write_bw = "{pipelines} GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "{pipelines * 100} MB/s"
write_bw = "{pipelines * 100} MB/s"
capacity = "{pipelines} GB"
[pipelines]
count = {pipelines}
file_size = "1 MB"
tasks = 3
cpu_time = "1 s"
chunk_size = "1 MB"
"""
start = time.perf_counter()
result = pcsim.run(scenario, cache_contents=False)
print(f"run: {time.perf_counter() - start:.2f} s")
for table in ("timeline", "memory"):
    start = time.perf_counter()
    frame = getattr(result, table)
    print(f"{table}: {len(frame)} rows, {time.perf_counter() - start:.3f} s")
