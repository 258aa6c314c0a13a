#!/usr/bin/python3
"""Monte Carlo overlay plot from Python: every run's pointing error over
time (passing runs blue, failing red) with the campaign's median and 5-95 %
envelope, as in the papers' Monte Carlo figures (docs/python.md).

  PYTHONPATH=build/host-release/python /usr/bin/python3 examples/mc_overlay.py \
      scenarios/s1_monte_carlo.yaml --runs 50 --jobs 2 -o s1_mc_overlay.png

Headless (no display needed): the Agg backend unless MPLBACKEND says otherwise.
"""
import argparse
import os

import matplotlib

if "MPLBACKEND" not in os.environ:
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import kestrel  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenario", help="scenario with a monte_carlo section")
    ap.add_argument("--runs", type=int, default=None)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--column", default="pointing_error_deg", help="thinned channel to plot")
    ap.add_argument("-o", "--output", default="mc_overlay.png")
    a = ap.parse_args(argv)

    mc = kestrel.monte_carlo(a.scenario, runs=a.runs, jobs=a.jobs, seed=a.seed)
    col = mc.series_columns.index(a.column)
    t = np.asarray(mc.series_t)
    y = mc.series[:, :, col]  # (runs, samples)

    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=120)
    for k in range(len(mc)):
        ax.plot(t, y[k], color="C0" if mc.passed[k] else "C3", lw=0.6, alpha=0.5)
    lo, med, hi = np.nanpercentile(y, [5, 50, 95], axis=0)
    ax.fill_between(t, lo, hi, color="k", alpha=0.12, label="5-95 %")
    ax.plot(t, med, color="k", lw=1.5, label="median")
    if np.all(y[np.isfinite(y)] > 0):
        ax.set_yscale("log")
    ax.set_xlabel("t [s]")
    ax.set_ylabel(a.column)
    ax.set_title("%d runs, %d passed (blue), %d failed (red)" % (len(mc), int(mc.passed.sum()),
                                                                  len(mc) - int(mc.passed.sum())))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="upper right")
    fig.tight_layout()
    fig.savefig(a.output)
    print("%s: %d runs, %d passed" % (a.output, len(mc), int(mc.passed.sum())))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
