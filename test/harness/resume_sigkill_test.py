#!/usr/bin/env python3
"""`kestrel run --checkpoint-every` killed with SIGKILL and `--resume`d gives
the results folder of an uninterrupted run, byte for byte (docs/checkpoint.md,
"Continuing a kestrel run").

For S1 (with telemetry.csv), S2 and S1's Monte Carlo nominal (events and
requirement lines): an uninterrupted run without checkpoints; the same run
with --checkpoint-every, killed (SIGKILL) once a randomly drawn number of
checkpoints has been written plus a random delay; `kestrel run --resume`;
every file of the two folders compared byte for byte.  The draws come from
one seed, printed (--seed reruns them).  Then the refusals: a damaged
checkpoint, damaged rows, a checkpoint of another run's folder, another
scenario given, a run without checkpoints, a finished run, --fsw.

Usage: resume_sigkill_test.py --kestrel K --scenarios DIR --work DIR [--seed N]
"""
import argparse
import os
import random
import shutil
import signal
import subprocess
import sys
import time

FAILS = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what, flush=True)
    if not cond:
        FAILS.append(what)


def run(args, **kw):
    return subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def work_folder(target):
    """The working folder a killed run of `target` left (None: none)."""
    parent, name = os.path.split(target)
    found = [os.path.join(parent, n) for n in os.listdir(parent) if n.startswith("." + name + ".kestrel-work-")]
    return found[0] if len(found) == 1 else None


def start_and_kill(cmd, target, rng, every_count, low=1):
    """Starts `cmd`, kills it with SIGKILL after the checkpoint number drawn
    in [low, every_count // 2] (plus 0-20 ms); True when it was killed."""
    nth = rng.randint(low, max(low, every_count // 2))
    extra = rng.uniform(0.0, 0.02)
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    seen, last = 0, None
    deadline = time.time() + 60
    while p.poll() is None and time.time() < deadline:
        w = work_folder(target)
        if w:
            try:
                st = os.stat(os.path.join(w, "checkpoint.kckp"))
                m = (st.st_ino, st.st_mtime_ns)  # each checkpoint is a new file renamed into place
            except OSError:
                m = None
            if m is not None and m != last:
                seen, last = seen + 1, m
                if seen >= nth:
                    time.sleep(extra)
                    break
        time.sleep(0.0005)
    if p.poll() is not None:
        return False
    os.kill(p.pid, signal.SIGKILL)
    p.wait()
    print(f"      killed after checkpoint {seen} (drawn {nth}) + {extra * 1e3:.1f} ms", flush=True)
    return True


def same_folders(a, b):
    fa, fb = sorted(os.listdir(a)), sorted(os.listdir(b))
    if fa != fb:
        return f"files differ: {fa} vs {fb}"
    for f in fa:
        with open(os.path.join(a, f), "rb") as x, open(os.path.join(b, f), "rb") as y:
            if x.read() != y.read():
                return f"{f} differs"
    return ""


def killed_run(k, sc, sets, target, every, count, rng, low=1):
    """A run with checkpoints killed mid-way (retried with new draws when it
    ended first); its working folder."""
    for _ in range(4):
        shutil.rmtree(target, ignore_errors=True)
        cmd = [k, "run", sc, "-o", target, "--checkpoint-every", str(every)] + sets
        if start_and_kill(cmd, target, rng, count, low):
            return work_folder(target)
        print("      the run ended before the kill; drawing again", flush=True)
    return None


def case(k, work, name, sc, sets, every, count, rng):
    ref, res = os.path.join(work, name + "_ref"), os.path.join(work, name + "_resumed")
    t0 = time.time()
    r = run([k, "run", sc, "-o", ref, "--force"] + sets)
    check(r.returncode == 0, f"{name}: uninterrupted run ({r.stderr.strip()[-200:]})")
    w = killed_run(k, sc, sets, res, every, count, rng)
    check(w is not None and not os.path.exists(res), f"{name}: killed, its working folder left ({w})")
    r = run([k, "run", "--resume", res])
    check(r.returncode == 0, f"{name}: --resume ({r.stderr.strip()[-300:]})")
    diff = same_folders(ref, res) if r.returncode == 0 else "not resumed"
    check(diff == "", f"{name}: every file of the resumed run equals the uninterrupted run's {diff}")
    check(work_folder(res) is None, f"{name}: no working folder left after the resumed run")
    print(f"      {name}: {time.time() - t0:.1f} s", flush=True)
    return ref, res


def refusals(k, work, s1, s2, rng):
    sets = ["--set", "duration=300"]
    # a finished run: its checkpoint is removed; --resume says so
    fin = os.path.join(work, "finished")
    r = run([k, "run", s1, "-o", fin, "--force", "--checkpoint-every", "50"] + sets)
    check(r.returncode == 0 and not any(n.startswith("checkpoint") for n in os.listdir(fin)),
          "a finished run with checkpoints holds no checkpoint files")
    r = run([k, "run", "--resume", fin])
    check(r.returncode == 5 and "finished run" in r.stderr, f"--resume of a finished run refused: {r.stderr.strip()}")
    # a run without checkpoints, killed: nothing to resume
    plain = os.path.join(work, "plain")
    shutil.rmtree(plain, ignore_errors=True)
    p = subprocess.Popen([k, "run", s1, "-o", plain], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    while p.poll() is None and work_folder(plain) is None:
        time.sleep(0.001)
    time.sleep(0.05)
    if p.poll() is None:
        os.kill(p.pid, signal.SIGKILL)
    p.wait()
    r = run([k, "run", "--resume", plain])
    check(r.returncode == 5 and "--checkpoint-every" in r.stderr,
          f"--resume of a run without checkpoints refused: {r.stderr.strip()}")
    # --fsw: the state is on the other side of the link
    r = run([k, "run", s1, "-o", os.path.join(work, "fsw"), "--checkpoint-every", "10", "--fsw", "udp:127.0.0.1:9"])
    check(r.returncode == 2 and "other side of the link" in r.stderr, f"--checkpoint-every with --fsw refused: {r.stderr.strip()}")
    # damaged checkpoint, damaged rows, a foreign checkpoint, another scenario
    a = os.path.join(work, "dmg_a")
    wa = killed_run(k, s1, sets, a, 10, 50, rng, 15)  # past the first chunk of rows (t = 102.4 s)
    b = os.path.join(work, "dmg_b")
    wb = killed_run(k, s2, sets, b, 10, 30, rng)
    check(wa is not None and wb is not None, "two killed runs for the refusals")
    if wa is None or wb is None:
        return
    ck = os.path.join(wa, "checkpoint.kckp")
    good = open(ck, "rb").read()
    bad = bytearray(good)
    bad[len(bad) // 2] ^= 0x10
    open(ck, "wb").write(bytes(bad))
    r = run([k, "run", "--resume", a])
    check(r.returncode == 5 and "checksum mismatch" in r.stderr, f"a damaged checkpoint refused: {r.stderr.strip()}")
    wa = work_folder(a)  # a refused resume leaves the folder (under its own pid)
    open(os.path.join(wa, "checkpoint.kckp"), "wb").write(good)
    rows = os.path.join(wa, "checkpoint.rows")
    rb = bytearray(open(rows, "rb").read())
    rb[-100] ^= 0x01
    open(rows, "wb").write(bytes(rb))
    r = run([k, "run", "--resume", a])
    check(r.returncode == 5 and "rows differ" in r.stderr, f"damaged rows refused: {r.stderr.strip()}")
    rb[-100] ^= 0x01
    open(os.path.join(work_folder(a), "checkpoint.rows"), "wb").write(bytes(rb))
    wa = work_folder(a)
    r = run([k, "run", s2, "--resume", a] + sets)
    check(r.returncode == 5 and "not of the one given" in r.stderr, f"another scenario refused: {r.stderr.strip()}")
    wa = work_folder(a)
    shutil.copy(os.path.join(work_folder(b), "checkpoint.kckp"), os.path.join(wa, "checkpoint.kckp"))
    r = run([k, "run", "--resume", a])
    check(r.returncode == 5 and "cannot be continued" in r.stderr,
          f"another run's checkpoint in the folder refused: {r.stderr.strip()}")
    open(os.path.join(work_folder(a), "checkpoint.kckp"), "wb").write(good)
    r = run([k, "run", s1, "--resume", a] + sets)
    check(r.returncode == 0, f"the repaired folder resumes ({r.stderr.strip()[-200:]})")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--kestrel", required=True)
    ap.add_argument("--scenarios", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--seed", type=int, default=None)
    a = ap.parse_args()
    seed = a.seed if a.seed is not None else int.from_bytes(os.urandom(4), "little")
    print(f"seed {seed} (rerun the same draws with --seed {seed})", flush=True)
    rng = random.Random(seed)
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    k = os.path.abspath(a.kestrel)
    s1 = os.path.join(a.scenarios, "s1_sun_pointing.yaml")
    s2 = os.path.join(a.scenarios, "s2_mars_orbit_insertion.yaml")
    mc = os.path.join(a.scenarios, "s1_monte_carlo.yaml")
    t0 = time.time()
    case(k, a.work, "s1", s1, ["--csv"], 10, 60, rng)
    case(k, a.work, "s2", s2, [], 20, 60, rng)
    case(k, a.work, "s1_mc_events", mc, ["--set", "duration=400"], 5, 80, rng)
    refusals(k, a.work, s1, s2, rng)
    print(f"{len(FAILS)} failures in {time.time() - t0:.1f} s (seed {seed})")
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
