"""What every benchmark script of coulomb-adapt shares: running the program
(with a timeout and, if asked, a memory limit), the state of the machine
(machine description, waiting for idle CPUs, the CPU time other processes
take during a run), the run's summary.json, and the CSV files.

Every number a benchmark records comes from the summary.json that the
program writes into its output directory, except the few that the program
only prints (see the section 'What summary.json does not have' below).

Only the Python standard library is used here (the report scripts add
matplotlib).
"""

import csv
import json
import math
import os
import platform
import re
import resource
import shlex
import shutil
import signal
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_EXE = os.path.join(ROOT, "build", "coulomb-adapt")
PRM_DIR = os.path.join(ROOT, "prm")
LIBRARY = "libcoulomb_adapt.so"


# ----------------------------------------------------------------- machine

def busy_seconds():
    """CPU seconds (all cores) spent non-idle since boot."""
    with open("/proc/stat") as f:
        v = [int(x) for x in f.readline().split()[1:]]
    # user nice system idle iowait irq softirq steal (guest is in user)
    busy = v[0] + v[1] + v[2] + v[5] + v[6] + (v[7] if len(v) > 7 else 0)
    return busy / os.sysconf("SC_CLK_TCK")


def children_cpu():
    """CPU seconds used by the finished child processes of this script."""
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def busy_cores(window=2.0):
    """Average number of busy cores over 'window' seconds (this script
    sleeps meanwhile, so the load is the other processes')."""
    b0, t0 = busy_seconds(), time.perf_counter()
    time.sleep(window)
    return (busy_seconds() - b0) / (time.perf_counter() - t0)


def wait_for_quiet(max_wait, threshold=0.3, window=2.0):
    """Waits until other processes use less than 'threshold' cores
    (measured over 'window' seconds), at most 'max_wait' seconds; returns
    the last measurement (NaN when max_wait <= 0: no measurement)."""
    if max_wait <= 0:
        return float("nan")
    start = time.perf_counter()
    load = busy_cores(window)
    announced = False
    while load > threshold and time.perf_counter() - start < max_wait:
        if not announced:
            print("    machine busy (%.2f cores used by other processes); "
                  "waiting up to %.0f s" % (load, max_wait), flush=True)
            announced = True
        time.sleep(4)
        load = busy_cores(window)
    return load


# A run is 'clean' if the other processes on the machine used less than
# this many CPU seconds per second of the run (plus a small allowance).
CLEAN_FRACTION = 0.1
CLEAN_ALLOWANCE_S = 0.05


def is_clean(other_cpu_s, wall_s):
    return other_cpu_s < CLEAN_FRACTION * wall_s + CLEAN_ALLOWANCE_S


def loadavg():
    try:
        with open("/proc/loadavg") as f:
            return float(f.read().split()[0])
    except OSError:
        return float("nan")


def machine_info():
    """One line: CPU model, logical CPUs, memory, OS, kernel, Python."""
    cpu, osname, mem = "unknown CPU", platform.system(), ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        with open("/etc/os-release") as f:
            for line in f:
                if line.startswith("PRETTY_NAME="):
                    osname = line.split("=", 1)[1].strip().strip('"')
    except OSError:
        pass
    try:
        with open("/proc/meminfo") as f:
            mem = ", %.1f GiB RAM" % (int(f.readline().split()[1]) / 2 ** 20)
    except (OSError, ValueError, IndexError):
        pass
    return "%s, %d logical CPUs%s, %s (kernel %s), Python %s" % (
        cpu, os.cpu_count() or 0, mem, osname, platform.release(),
        platform.python_version())


def print_header(exe):
    """What a sweep prints first: the machine and the executable."""
    print("machine:", machine_info(), flush=True)
    print("executable:", exe, time.ctime(os.path.getmtime(exe)), flush=True)


# ------------------------------------------------------------- executable

def check_executable(exe):
    """The absolute path of 'exe'; exits with a message if it is missing."""
    exe = os.path.abspath(exe)
    if not os.access(exe, os.X_OK):
        raise SystemExit("executable not found: %s (build it, or give "
                         "--exe)" % exe)
    return exe


def snapshot_executable(exe):
    """Copies the executable and the project library next to it into a
    private directory, so that a rebuild during a sweep cannot change or
    crash the runs. Returns the copied executable (remove its directory
    when done)."""
    target = tempfile.mkdtemp(prefix="coulomb-bench-bin-")
    shutil.copy2(exe, target)
    library = os.path.join(os.path.dirname(exe), LIBRARY)
    if os.path.exists(library):
        shutil.copy2(library, target)
    return os.path.join(target, os.path.basename(exe))


def program_env(exe):
    """The environment of a run: one thread per process, Open MPI allowed
    as root and on more ranks than cores, and the project library next to
    the executable found first."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1",
               OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    d = os.path.dirname(os.path.abspath(exe))
    if os.path.exists(os.path.join(d, LIBRARY)):
        env["LD_LIBRARY_PATH"] = d + (":" + env["LD_LIBRARY_PATH"]
                                      if env.get("LD_LIBRARY_PATH") else "")
    return env


def program_command(exe, settings, prm=None, ranks=1):
    """The command line: [mpirun -np N] exe [prm] -s setting ..."""
    args = [exe] + ([prm] if prm else [])
    for s in settings:
        args += ["-s", s]
    if ranks > 1:
        args = ["mpirun", "-np", str(ranks), "--oversubscribe"] + args
    return args


def shell_command(args):
    """A run's command line for a page: paths relative to the repository,
    the build's executable, the output directory /tmp/run."""
    out = []
    for a in args:
        if os.path.basename(a) == "coulomb-adapt":
            a = "build/coulomb-adapt"
        elif a.startswith(ROOT + "/"):
            a = os.path.relpath(a, ROOT)
        elif a.startswith("Output/Output directory="):
            a = "Output/Output directory=/tmp/run"
        out.append(shlex.quote(a))
    return " ".join(out)


# ----------------------------------------------------------------- running

class Run:
    """One finished process: exit code (None when killed), output, wall
    time, the CPU time other processes used meanwhile, peak resident
    memory (only when watched), and why it was killed."""

    def __init__(self, rc, stdout, stderr, wall_s, other_cpu_s,
                 peak_rss_MiB, killed):
        self.rc, self.stdout, self.stderr = rc, stdout, stderr
        self.wall_s, self.other_cpu_s = wall_s, other_cpu_s
        self.peak_rss_MiB, self.killed = peak_rss_MiB, killed

    @property
    def clean(self):
        return is_clean(self.other_cpu_s, self.wall_s)

    def failure(self):
        """(status, message) of a run that did not end well, else None:
        'timeout', 'killed' (memory limit or SIGKILL from outside, e.g.
        the kernel's out-of-memory killer) or 'failed' (non-zero exit,
        with the program's error message)."""
        if self.killed:
            return ("timeout" if self.killed.startswith("no result")
                    else "killed"), self.killed
        if self.rc in (-9, 137):
            return "killed", "killed by SIGKILL (likely out of memory)"
        if self.rc != 0:
            return "failed", "exit code %s: %s" % (
                self.rc, error_message(self.stderr, self.stdout))
        return None


# Wall time of all runs of this script (waits for a quiet machine not
# counted): the time budgets of the sweeps are kept against it.
RUN_SECONDS = [0.0]


def _rss_MiB(pid):
    """Resident memory of pid and its children (MiB)."""
    total, pids = 0, [pid]
    try:
        with open("/proc/%d/task/%d/children" % (pid, pid)) as f:
            pids += [int(x) for x in f.read().split()]
    except OSError:
        pass
    for p in pids:
        try:
            with open("/proc/%d/status" % p) as f:
                for line in f:
                    if line.startswith("VmRSS:"):
                        total += int(line.split()[1])
        except OSError:
            pass
    return total / 1024.0


def run(args, timeout, env=None, max_rss_MiB=None, cwd=None):
    """Runs args in its own session; the whole process group is killed
    after 'timeout' seconds or when its resident memory exceeds
    max_rss_MiB (watched every 0.1 s only when given)."""
    cpu0, busy0 = children_cpu(), busy_seconds()
    start = time.perf_counter()
    killed, peak = "", None
    with tempfile.TemporaryFile("w+") as out, \
            tempfile.TemporaryFile("w+") as err:
        proc = subprocess.Popen(args, stdout=out, stderr=err, text=True,
                                env=env, cwd=cwd, start_new_session=True)
        while True:
            try:
                proc.wait(timeout=0.1 if max_rss_MiB else timeout)
                break
            except subprocess.TimeoutExpired:
                pass
            if max_rss_MiB:
                m = _rss_MiB(proc.pid)
                peak = max(peak or 0.0, m)
                if m > max_rss_MiB:
                    killed = "resident memory %.0f MiB > %.0f MiB" % (
                        m, max_rss_MiB)
            if not killed and time.perf_counter() - start > timeout:
                killed = "no result within %g s (killed)" % timeout
            if killed:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
                break
        wall = time.perf_counter() - start
        out.seek(0)
        err.seek(0)
        stdout, stderr = out.read(), err.read()
    RUN_SECONDS[0] += wall
    other = (busy_seconds() - busy0) - (children_cpu() - cpu0)
    return Run(None if killed else proc.returncode, stdout, stderr, wall,
               max(0.0, other), peak, killed)


def run_program(exe, settings, timeout, prm=None, ranks=1, max_rss_MiB=None,
                keep=False):
    """Runs the program with the -s settings (plus a fresh output directory
    and no VTU output); returns (Run, summary.json or None). The output
    directory is removed unless 'keep'."""
    out_dir = tempfile.mkdtemp(prefix="coulomb-bench-")
    args = program_command(exe, list(settings) + [
        "Output/Write VTU=false", "Output/Output directory=" + out_dir],
        prm, ranks)
    result = run(args, timeout, program_env(exe), max_rss_MiB)
    summary = read_summary(out_dir)
    if keep:
        print("    output kept in " + out_dir, flush=True)
    else:
        shutil.rmtree(out_dir, ignore_errors=True)
    return result, summary


# ------------------------------------------------------------ summary.json

def read_summary(out_dir):
    """The run's summary.json as a dict, or None if missing or unreadable
    (nlohmann::json writes a NaN as null; that is left to the caller)."""
    try:
        with open(os.path.join(out_dir, "summary.json")) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def last_cycle(summary):
    """The last cycle of a summary (None if the run ended before one)."""
    if not summary or not summary.get("cycles"):
        return None
    return summary["cycles"][-1]


def timing(cycle, section, default=""):
    """A TimerOutput section's wall time of the cycle (timings_s)."""
    return (cycle or {}).get("timings_s", {}).get(section, default)


def body_field(cycle, i, key, default=""):
    """bodies[i][key] of the cycle (0: body 1)."""
    bodies = (cycle or {}).get("bodies", [])
    return bodies[i].get(key, default) if len(bodies) > i else default


# ------------------------------------------- What summary.json does not have
# The program prints, but does not write into summary.json:
#  - the wall time of each Newton step, split into assembly and solve
#    ("Newton  k: ... (assembly A s, solve S s)"): the contact benchmark's
#    time per Newton step;
#  - the wall time of each body's elastic solve ("BODY: solved by METHOD
#    (N iterations) in T s"): summary.json has only the 'solve' section of
#    both bodies together; the elasticity benchmark's one-body times and the
#    contact benchmark's elastic reference;
#  - the Newton steps made by a run that stopped without converging (its
#    summary.json has no cycle): the stability sweep;
#  - the error message, on stderr.

NEWTON_STEP = re.compile(
    r"^\s*Newton\s+(?P<k>\d+):.*\(assembly (?P<a>[0-9.eE+-]+) s, "
    r"solve (?P<s>[0-9.eE+-]+) s(?:, [^)]*)?\)\s*$", re.M)
BODY_SOLVE = re.compile(
    r"^\s*(?P<body>.+?): solved by (?P<method>.+?)"
    r"(?: \((?P<its>\d+) iterations\))? in (?P<t>[0-9.eE+-]+) s\s*$", re.M)


def newton_step_times(stdout):
    """[(assembly s, solve s)] of every Newton step printed."""
    return [(float(m.group("a")), float(m.group("s")))
            for m in NEWTON_STEP.finditer(stdout)]


def newton_steps_run(stdout):
    """The number of the last Newton step printed (0 if none)."""
    steps = re.findall(r"^\s*Newton\s+(\d+):", stdout, re.M)
    return int(steps[-1]) if steps else 0


def body_solve_times(stdout):
    """[(method, seconds)] of every elastic body solve printed."""
    return [(m.group("method"), float(m.group("t")))
            for m in BODY_SOLVE.finditer(stdout)]


def error_message(stderr, stdout="", limit=300):
    """The program's error message (the last 'limit' characters of stderr,
    or of stdout if stderr is empty), on one line."""
    text = " ".join((stderr or stdout or "").strip().split())
    return text.replace("coulomb-adapt: error: ", "")[-limit:]


# --------------------------------------------------------------------- CSV

def cell(value, float_format="%.6g"):
    """A value as the CSV writes it: floats with 'float_format', None as
    an empty cell."""
    if value is None:
        return ""
    if isinstance(value, float):
        return "nan" if math.isnan(value) else float_format % value
    return value


def write_csv(path, rows, fields, float_format="%.6g"):
    """Writes the rows (dicts; other keys ignored) atomically, so that an
    interrupted sweep leaves the last complete file."""
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: cell(r.get(k, ""), float_format) for k in fields})
    os.replace(tmp, path)


def read_csv(path, text=(), ints=(), empty=""):
    """Rows of a CSV (an empty list if the file is missing): the columns in
    'text' stay strings, those in 'ints' become int, the others float where
    they parse; an empty cell becomes 'empty'."""
    rows = []
    if not os.path.exists(path):
        return rows
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            for k, v in r.items():
                if k in text:
                    continue
                if v in ("", None):
                    r[k] = empty
                    continue
                try:
                    r[k] = int(float(v)) if k in ints else float(v)
                except ValueError:
                    pass
            rows.append(r)
    return rows


def fmt(x, digits=3):
    """x with 'digits' significant digits; '-' for a missing value."""
    if x == "" or x is None:
        return "-"
    x = float(x)
    if x == 0:
        return "0"
    return "%.*g" % (digits, x)


def loglog_slope(points):
    """Least-squares slope of log(y) over log(x) (NaN below 2 points)."""
    pts = [(math.log(x), math.log(y)) for x, y in points if x > 0 and y > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return float("nan")
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx


def pyplot():
    """matplotlib's pyplot with the file backend."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt
