#!/usr/bin/env python3
"""The flight library inside cFS, flown closed loop through cFS's own path.

Builds a native cFS (cFE, OSAL, PSP, ci_lab, to_lab, sch_lab) with the
KESTREL_ACS application added out of tree (apps/cfs/kestrel_acs/tools/
cfs_build.sh), then for S1 (all 600 s) and S2 (to 420 s: 60 s into the
burn), bounded by --s1-seconds and --s2-seconds:

  * writes the scenario's configuration table (kestrel fsw-config, then
    kestrel_acs_tbl.py) into a fresh copy of the installed cpu1 directory,
  * starts core-cpu1 there (as user 65534 through setpriv when run as root,
    else as the current user), waits for OPERATIONAL,
  * flies the scenario with `kestrel run --fsw cfs:127.0.0.1:1234:1235`
    (sensor packets into ci_lab, actuator packets back from to_lab), and
  * compares every result file with the in-process run of the same bounded
    scenario, bit for bit: every HDF5 dataset and attribute, telemetry.csv,
    manifest.json, summary.txt, report_data.json and dataflow.dot, without
    the lines that only a linked run writes (the link_* figures, the FSW
    node's label); fsw_health.txt, which names the endpoint's own counters,
    must show every cycle answered and KESTREL_ACS's housekeeping count them;
  * stops core-cpu1 (SIGINT) and removes its state (SysV shared memory it
    created, /dev/shm/osal:RAM, the reset key files).

Then a bad configuration table (S1's image with initial_mode = 99 and its
CRC recomputed): the harness refuses to fly ("without a valid configuration
table") and core-cpu1's output holds the validation event naming the field.

The cFS tree: KESTREL_CFS_SOURCE (a bundle tarball or an unpacked
directory), else the one cfs-*.tar.* in ../shared/cfs next to the
repository; neither: skipped (exit 77) with the reason.  Prints the build
time, each run's wall time and the mean cycle time through cFS.

  cfs_closed_loop_test.py --kestrel BIN --repo DIR --work DIR [--s1-seconds S] [--s2-seconds S]
"""
import argparse
import ctypes
import glob
import json
import os
import re
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_digest  # noqa: E402  (the digests of the results regression)

SKIP = 77
CI_PORT, TLM_PORT = 1234, 1235  # ci_lab's (fixed at its build) and to_lab's
NOBODY = 65534
START_TIMEOUT = 60.0  # [s] core-cpu1 to OPERATIONAL (a loaded 2-core machine)
STOP_TIMEOUT = 15.0   # [s] SIGINT to exit
LINK_TIMEOUT = "20"   # [s] harness: link start-up and each reply
SCENARIOS = ["s1_sun_pointing", "s2_mars_orbit_insertion"]  # flown for --s1-seconds, --s2-seconds
BAD_FIELD = "initial_mode"  # the first field of the image's body (offset 20, i32 big-endian)
running = []  # core-cpu1 processes still up: stopped on any exit


def log(msg):
    print(msg, flush=True)


def fail(msg):
    log("FAIL: " + msg)
    sys.exit(1)


def cfs_source(repo):
    v = os.environ.get("KESTREL_CFS_SOURCE", "")
    if v:
        if not os.path.exists(v):
            fail(f"KESTREL_CFS_SOURCE={v}: no such file or directory")
        return v
    shared = os.path.normpath(os.path.join(repo, "..", "shared", "cfs"))
    found = sorted(glob.glob(os.path.join(shared, "cfs-*.tar.*")))
    if not found:
        log(f"SKIP: no cFS tree: KESTREL_CFS_SOURCE is not set and {shared} holds no cfs-*.tar.* bundle")
        sys.exit(SKIP)
    return found[-1]


def check_ports():
    for host, port in (("0.0.0.0", CI_PORT), ("127.0.0.1", TLM_PORT)):
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            s.bind((host, port))
        except OSError as e:
            fail(f"UDP port {port} is in use ({e}): is a core-cpu1 still running? (ss -uapn | grep {port})")
        finally:
            s.close()


def crc16(data):
    """CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF), written here."""
    crc = 0xFFFF
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) & 0xFFFF if crc & 0x8000 else (crc << 1) & 0xFFFF
    return crc


def sh(cmd, what, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        fail(f"{what}: {' '.join(cmd)}: exit {r.returncode}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return r


def shm_created_by(pid):
    ids = []
    with open("/proc/sysvipc/shm") as f:
        next(f)
        for line in f:
            v = line.split()
            if int(v[4]) == pid:  # key shmid perms size cpid lpid ...
                ids.append(v[1])
    return ids


def set_pdeathsig():
    ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG


class Cpu1:
    """core-cpu1 in its own copy of the installed cpu1 directory."""

    def __init__(self, exe_dir, run_dir, table):
        shutil.rmtree(run_dir, ignore_errors=True)
        shutil.copytree(exe_dir, run_dir, symlinks=True)
        shutil.copyfile(table, os.path.join(run_dir, "cf", "kestrel_acs_cfg.tbl"))
        self.dir, self.logfile = run_dir, os.path.join(run_dir, "core-cpu1.log")
        self.remove_ram_disk()
        argv = ["stdbuf", "-oL", "-eL"]
        if os.geteuid() == 0:  # never as root (the notes on message queue depths and the clock)
            for root, dirs, files in os.walk(run_dir):
                for n in dirs + files:
                    os.lchown(os.path.join(root, n), NOBODY, NOBODY)
            os.chown(run_dir, NOBODY, NOBODY)
            argv += ["setpriv", f"--reuid={NOBODY}", f"--regid={NOBODY}", "--clear-groups", "--pdeathsig=KILL"]
        argv += ["./core-cpu1"]
        self.out = open(self.logfile, "wb")
        self.p = subprocess.Popen(argv, cwd=run_dir, stdout=self.out, stderr=subprocess.STDOUT,
                                  preexec_fn=set_pdeathsig, start_new_session=True)
        running.append(self)

    @staticmethod
    def remove_ram_disk():
        shutil.rmtree("/dev/shm/osal:RAM", ignore_errors=True)  # OSAL's RAM disk: a directory

    def text(self):
        with open(self.logfile, "rb") as f:
            return f.read().decode("utf-8", "replace")

    def wait_operational(self):
        end = time.monotonic() + START_TIMEOUT
        while time.monotonic() < end:
            if "entering OPERATIONAL state" in self.text():
                return
            if self.p.poll() is not None:
                fail(f"core-cpu1 exited ({self.p.returncode}) before OPERATIONAL:\n{self.text()[-3000:]}")
            time.sleep(0.1)
        fail(f"core-cpu1 not OPERATIONAL within {START_TIMEOUT} s:\n{self.text()[-3000:]}")

    def stop(self):
        if self in running:
            running.remove(self)
        if self.p.poll() is None:
            os.killpg(self.p.pid, signal.SIGINT)
            try:
                self.p.wait(STOP_TIMEOUT)
            except subprocess.TimeoutExpired:
                os.killpg(self.p.pid, signal.SIGKILL)
                self.p.wait()
        self.out.close()
        # its state: the shared memory segments it made (keys from the key
        # files below), the RAM disk and the reset key files
        for shmid in shm_created_by(self.p.pid):
            subprocess.run(["ipcrm", "-m", shmid], capture_output=True)
        self.remove_ram_disk()
        for n in (".cdskeyfile", ".reservedkeyfile", ".resetkeyfile", "EEPROM.DAT"):
            try:
                os.remove(os.path.join(self.dir, n))
            except FileNotFoundError:
                pass
        return self.p.returncode


def stop_all(*_):
    for c in list(running):
        c.stop()


# ---- comparing a results folder with the in-process one ------------------

LINK_ONLY_LINE = re.compile(r'^link_|"c:fsw_acs" \[')  # summary.txt / dataflow.dot lines a linked run writes


def normalized(path):
    """A copy of a text result without what only a linked run writes."""
    with open(path, "rb") as f:
        raw = f.read()
    if path.endswith("report_data.json"):
        o = json.loads(raw)
        o["summary"] = {k: v for k, v in o.get("summary", {}).items() if not k.startswith("link_")}
        o["summary_order"] = [k for k in o.get("summary_order", []) if not str(k).startswith("link_")]
        if "dataflow_dot" in o:
            o["dataflow_dot"] = "\n".join(ln for ln in o["dataflow_dot"].split("\n") if not LINK_ONLY_LINE.search(ln))
        raw = json.dumps(o, sort_keys=True).encode()
    elif not path.endswith(".json"):
        raw = b"\n".join(ln for ln in raw.split(b"\n") if not LINK_ONLY_LINE.search(ln.decode("utf-8", "replace")))
    fd, tmp = tempfile.mkstemp(suffix=os.path.splitext(path)[1])
    with os.fdopen(fd, "wb") as f:
        f.write(raw)
    return tmp


def digests(d):
    out = {}
    for n in sorted(os.listdir(d)):
        p = os.path.join(d, n)
        if n == "fsw_health.txt" or n.endswith(".html"):
            continue  # the endpoint's own counters (checked apart); the page is report_data.json
        if n.endswith(".h5"):
            results_digest.digest_h5(p, out, n)
        else:
            tmp = normalized(p)
            out[n] = results_digest.digest_text(tmp)
            os.remove(tmp)
    return out


def compare(local, linked, name):
    a, b = digests(local), digests(linked)
    bad = [k for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]
    for k in bad:
        log(f"DIFFERS {name} {k}: in process {a.get(k, '(absent)')}, through cFS {b.get(k, '(absent)')}")
    if bad:
        fail(f"{name}: {len(bad)} of {len(a)} items differ from the in-process run")
    with open(os.path.join(linked, "fsw_health.txt")) as f:
        health = f.read()
    m = re.search(r"cycles=(\d+) sent=(\d+) .* replies=(\d+) missing=(\d+) .* rejected=(\d+) stale=(\d+)", health)
    if not m or m.group(1) != m.group(3) or m.group(4) != "0" or m.group(5) != "0":
        fail(f"{name}: not every cycle answered through cFS:\n{health}")
    # the application's own count, from its housekeeping (asked for with every 64th packet)
    hk = re.search(r"link \(FSW end\): .* config_loaded=1 cycles=(\d+) ", health)
    n = int(m.group(1))
    if not hk or not n - 64 < int(hk.group(1)) <= n:
        fail(f"{name}: KESTREL_ACS's housekeeping does not count the cycles flown ({n}):\n{health}")
    log(f"{name}: {len(a)} items bit-identical to the in-process run; {n} cycles, all answered "
        f"(KESTREL_ACS counted {hk.group(1)} by its last housekeeping)")
    return int(m.group(1))


# ---- the test -------------------------------------------------------------

def write_table(a, tools, scenario, out_dir, sets=(), patch=None):
    img, tbl = os.path.join(out_dir, "cfg.img"), os.path.join(out_dir, "kestrel_acs_cfg.tbl")
    cmd = [a.kestrel, "fsw-config", scenario, "-o", img]
    for s in sets:
        cmd += ["--set", s]
    sh(cmd, "fsw-config")
    if patch:
        with open(img, "rb") as f:
            b = bytearray(f.read())
        patch(b)
        b[-2:] = struct.pack(">H", crc16(b[:-2]))
        with open(img, "wb") as f:
            f.write(b)
    sh([sys.executable, os.path.join(tools, "kestrel_acs_tbl.py"), img, tbl], "kestrel_acs_tbl.py")
    return tbl


def fly(a, exe_dir, tools, name, seconds):
    scenario = os.path.join(a.repo, "scenarios", name + ".yaml")
    d = os.path.join(a.work, name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    dur = f"duration={seconds}"
    tbl = write_table(a, tools, scenario, d, [dur])
    t0 = time.monotonic()
    sh([a.kestrel, "run", scenario, "--set", dur, "--csv", "-o", os.path.join(d, "local")], "in-process run")
    t_local = time.monotonic() - t0
    cpu = Cpu1(exe_dir, os.path.join(d, "cpu1"), tbl)
    cpu.wait_operational()
    t0 = time.monotonic()
    r = subprocess.run([a.kestrel, "run", scenario, "--set", dur, "--csv", "-o", os.path.join(d, "cfs"),
                        "--fsw", f"cfs:127.0.0.1:{CI_PORT}:{TLM_PORT}", "--link-timeout", LINK_TIMEOUT],
                       capture_output=True, text=True)
    t_cfs = time.monotonic() - t0
    rc = cpu.stop()
    if r.returncode != 0:
        fail(f"{name} through cFS: exit {r.returncode}\n{r.stdout}\n{r.stderr}\ncore-cpu1:\n{cpu.text()[-4000:]}")
    if rc != 0:
        log(f"note: core-cpu1 exited {rc} after SIGINT")
    cycles = compare(os.path.join(d, "local"), os.path.join(d, "cfs"), name)
    log(f"{name}: {seconds} s simulated: in process {t_local:.2f} s, through cFS {t_cfs:.2f} s wall: "
        f"{1e3 * (t_cfs - t_local) / cycles:.2f} ms a cycle through ci_lab, KESTREL_ACS and to_lab "
        f"(link start included)")
    return t_cfs


def bad_table(a, exe_dir, tools):
    scenario = os.path.join(a.repo, "scenarios", "s1_sun_pointing.yaml")
    d = os.path.join(a.work, "bad_table")
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)

    def initial_mode_99(b):
        b[20:24] = struct.pack(">i", 99)

    tbl = write_table(a, tools, scenario, d, patch=initial_mode_99)
    cpu = Cpu1(exe_dir, os.path.join(d, "cpu1"), tbl)
    cpu.wait_operational()
    r = subprocess.run([a.kestrel, "run", scenario, "--set", "duration=1", "-o", os.path.join(d, "run"),
                        "--fsw", f"cfs:127.0.0.1:{CI_PORT}:{TLM_PORT}", "--link-timeout", LINK_TIMEOUT],
                       capture_output=True, text=True)
    cpu.stop()
    text = cpu.text()
    want = f"config table refused: field '{BAD_FIELD}'"
    if want not in text:
        fail(f"bad table: core-cpu1's output lacks \"{want}\":\n{text[-4000:]}")
    if r.returncode == 0 or "without a valid configuration table" not in r.stderr:
        fail(f"bad table: the harness flew, or said something else (exit {r.returncode}):\n{r.stderr}")
    line = next(ln for ln in text.splitlines() if want in ln)
    log(f"bad table refused: {line.strip()}; harness: {r.stderr.strip().splitlines()[-1]}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kestrel", required=True)
    ap.add_argument("--repo", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--s1-seconds", default="600", help="S1's simulated time [s] (default: all of it)")
    ap.add_argument("--s2-seconds", default="420", help="S2's simulated time [s] (default: to 60 s into the burn)")
    a = ap.parse_args()
    a.kestrel, a.repo, a.work = (os.path.abspath(x) for x in (a.kestrel, a.repo, a.work))
    try:
        import h5py  # noqa: F401
    except ImportError:
        log("SKIP: h5py is missing (scripts/install-deps.sh host installs python3-h5py)")
        return SKIP
    src = cfs_source(a.repo)
    for tool in ("gcc", "cmake", "make", "setpriv", "stdbuf", "ipcrm"):
        if shutil.which(tool) is None:
            fail(f"{tool} is not installed (scripts/install-deps.sh)")
    check_ports()
    os.makedirs(a.work, exist_ok=True)
    signal.signal(signal.SIGTERM, lambda *_: (stop_all(), sys.exit(1)))
    tools = os.path.join(a.repo, "apps", "cfs", "kestrel_acs", "tools")
    t0 = time.monotonic()
    r = sh(["sh", os.path.join(tools, "cfs_build.sh"), src, os.path.join(a.work, "cfs")], "cFS build")
    exe_dir = r.stdout.strip().splitlines()[-1]
    log(f"cFS with KESTREL_ACS built from {src} in {time.monotonic() - t0:.0f} s: {exe_dir}")
    try:
        for name, seconds in zip(SCENARIOS, (a.s1_seconds, a.s2_seconds)):
            fly(a, exe_dir, tools, name, seconds)
        bad_table(a, exe_dir, tools)
    finally:
        stop_all()
    return 0


if __name__ == "__main__":
    t = time.monotonic()
    rc = main()
    log(f"cfs_closed_loop_test: {time.monotonic() - t:.0f} s wall in all")
    sys.exit(rc)
