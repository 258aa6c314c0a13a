#!/usr/bin/python3
"""S1 (600 s, 60 000 ticks) through Python and through the CLI: wall times
and equality of the recorded arrays (docs/python.md, "Figures").

  PYTHONPATH=build/host-release/python /usr/bin/python3 bench/python/s1_python_vs_cli.py \
      build/host-release/harness/kestrel scenarios/s1_sun_pointing.yaml

Prints numbers only; not a test (speed figures are not asserted)."""
import os
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

import kestrel


def main():
    cli, scenario = sys.argv[1], sys.argv[2]
    reps = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    with tempfile.TemporaryDirectory() as tmp:
        t_cli, t_mem, t_out = [], [], []
        for i in range(reps):
            d = os.path.join(tmp, "cli%d" % i)
            t0 = time.perf_counter()
            subprocess.run([cli, "run", scenario, "-o", d], check=True, capture_output=True)
            t_cli.append(time.perf_counter() - t0)
            sc = kestrel.Scenario.load(scenario)
            t0 = time.perf_counter()
            res = kestrel.run(sc)
            t_mem.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            kestrel.run(sc, out_dir=os.path.join(tmp, "py%d" % i))
            t_out.append(time.perf_counter() - t0)
        same = True
        with h5py.File(os.path.join(tmp, "cli0", "results.h5"), "r") as f:
            n = 0
            for key in res.quantities:
                if key in f:
                    same = same and np.array_equal(f[key][...], res[key])
                    n += 1
        with open(os.path.join(tmp, "cli0", "summary.txt")) as a, open(os.path.join(tmp, "py0", "summary.txt")) as b:
            same_summary = a.read() == b.read()
    print("scenario            %s (%d ticks, %d rows x %d columns)" % (sc.name, sc.num_ticks, *res.data.shape))
    print("cli run (files)     best %.3f s of %d" % (min(t_cli), reps))
    print("python run()        best %.3f s (in memory, arrays copied out)" % min(t_mem))
    print("python run(out_dir) best %.3f s (the CLI's files)" % min(t_out))
    print("arrays == CLI results.h5: %s (%d quantities); summary.txt identical: %s" % (same, n, same_summary))
    print("final_pointing_error_deg %.10g" % res.summary["final_pointing_error_deg"])
    # the GIL released: two runs on two threads vs one after the other
    import concurrent.futures
    t0 = time.perf_counter()
    seq = [kestrel.run(sc).data for _ in range(2)]
    t_seq = time.perf_counter() - t0
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as ex:
        t0 = time.perf_counter()
        par = list(ex.map(lambda _: kestrel.run(sc).data, range(2)))
        t_par = time.perf_counter() - t0
    print("2 runs sequential   %.3f s; on 2 threads %.3f s (x%.2f); equal: %s"
          % (t_seq, t_par, t_seq / t_par, all(np.array_equal(a, b) for a, b in zip(seq, par))))


if __name__ == "__main__":
    main()
