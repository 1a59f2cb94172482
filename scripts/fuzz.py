#!/usr/bin/python3
"""Random hostile runs of bladestab, for campaigns longer than the suite's fixed corpus
(tests/test_fuzz.cpp).

    /usr/bin/python3 scripts/fuzz.py [--runs 1000] [--seed 1] [--jobs 2] [--timeout 20]
                                     [--exe build/bladestab] [--scene stability_maps/sinha2005/blade.toml]

Each run takes the paper's scene and one command, and mutates one thing: a scene key (a value
outside its range, of the wrong type, at the edge of its range, or text with newlines), a numeric
option (malformed or extreme text), or the scene file's bytes. Most runs use a small model
(model.terms = 4) so they stay short. A run is a finding when it
  crash      ends by a signal,
  hang       outlives --timeout (then it is killed), though every run is given --max-seconds of
             half of it,
  memory     uses more than --max-rss MB,
  nonfinite  exits 0 with nan or inf in its output,
  multiline  fails with other than exactly one line on stderr,
  unnamed    refuses its input (exit 2) without naming the key or option that was mutated,
  leftover   fails and leaves files in its --out directory.
Findings are printed as command lines that reproduce them; the exit status is 1 if there are any.
"""

import argparse
import concurrent.futures
import os
import random
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Scene keys and, where the scene leaves them unread, what makes them read.
NUMBER_KEYS = {
    "blade.length": [], "blade.hub_radius": [], "blade.area": [], "blade.slenderness": [],
    "blade.youngs_modulus": [], "blade.density": [], "blade.poisson": [], "blade.shear_coefficient": [],
    "blade.stagger_deg": [], "operation.speed_rad_s": [], "operation.tip_compression_over_fcr": [],
    "load.fmax_over_fcr": [],
    "load.contact_time_rev": [], "load.friction": [], "load.clearance": [], "load.pulse_frequency_hz": [],
    "damping.ratio": ["damping.model=modal", "damping.ratio=0.01"],
    "model.cutoff_hz": ["model.reduction=modal"],
    "load.intrusion": ["load.mode=clearance", "load.intrusion=1e-3"],
    "load.contact_stiffness": ["load.mode=clearance", "load.intrusion=1e-3"],
}
INTEGER_KEYS = ["model.terms", "model.reduction_vectors", "load.pulses_per_rev", "load.pulse_count"]
CHOICE_KEYS = {
    "model.basis": ["sine", "legendre"], "model.theory": ["timoshenko", "euler-bernoulli"],
    "model.reduction": ["auto", "modal", "none"], "damping.model": ["none", "modal", "rayleigh", "paper"],
    "load.profile": ["half-sine", "cosine", "triangular", "saw-tooth", "rectangular", "impulse"],
    "load.approximation": ["cosine", "fourier", "exact"], "load.mode": ["force", "clearance"],
    "model.axial": ["true", "false"], "model.coriolis": ["true", "false"],
}

# Numeric options per command, and what each command needs besides.
COMMANDS = {
    "modes": ([], ["--count", "--tolerance"]),
    "campbell": (["--speeds", "0:600:3", "--chart", "none"], ["--count", "--tolerance", "--engine-orders", "--speeds"]),
    "stability": ([], ["--harmonics", "--tolerance", "--cutoff-hz"]),
    "boundaries": ([], ["--approximation", "--tolerance", "--at-theta", "--cutoff-hz", "--max-order", "--range"]),
    "map": (["--plane", "theta-fmax", "--chart", "none", "--theta", "100:1000:3", "--fmax", "0:5:3",
             "--trace", "5", "--resolution", "4x4"],
            ["--trace", "--engine-order", "--approximation", "--max-order", "--tolerance", "--threads",
             "--resolution", "--theta", "--fmax"]),
    "transient": (["--chart", "none", "--revolutions", "0.2"], ["--revolutions", "--tolerance", "--samples-per-rev"]),
    "crosscheck": (["--points", "1", "--revolutions", "6"], ["--points", "--revolutions"]),
    "sweep": (["--key", "operation.speed_rad_s", "--values", "0:300:2", "--chart", "none"], ["--values", "--count"]),
}
WRITES = {"campbell", "map", "transient", "sweep"}
COMMON_OPTIONS = ["--max-seconds", "--max-memory"]

HOSTILE_NUMBERS = ["nan", "inf", "-inf", "1e308", "-1e308", "1e-308", "-1e-308", "0", "-0", "-1", "1e30",
                   "9e99", "\"x\"", "[1, 2]", "true", "{ a = 1 }", "1979-05-27", "\"a\\nb\"", "0x10", "1e999",
                   "\"" + "y" * 5000 + "\"", "[" + ", ".join(["1"] * 20000) + "]"]
HOSTILE_TEXT = ["", " ", " 1", "1 ", "0x10", "0x1p3", "nan", "inf", "-inf", "1e999", "1e308", "-1e308", "1e-308",
                "abc", "1,2", ",", "1:2", "1:2:3", "0:0:2", "1e308:1e309:3", "-5", "0", "1\n2", "\t1",
                "9" * 400, "1x1", "0x0", "4097x1"]


def edge_value(rng):
    """A number from the edges of any plausible range: tiny, huge, around 0 and 1."""
    return rng.choice([
        f"{rng.uniform(-1, 1):.6g}e{rng.randint(-320, 320)}",
        f"{10 ** rng.uniform(-8, 16):.6g}",
        rng.choice(["0", "1", "0.5", "1e-6", "1e-3", "1e5", "1e13", "1e15", "1000", "100000", "0.4999999",
                    "-0.9999999", "90", "-90"]),
    ])


def mutate(rng, scene_text, workdir, run_id, max_seconds):
    """One hostile command line: (argv, the name it must mention when refused, out dir or None)."""
    command = rng.choice(sorted(COMMANDS))
    needs, options = COMMANDS[command]
    scene = os.path.join(workdir, f"scene_{run_id}.toml")
    with open(scene, "w", encoding="utf-8") as f:
        f.write(scene_text)
    args = [command, scene] + list(needs)
    out = None
    if command in WRITES:
        out = os.path.join(workdir, f"out_{run_id}")
        args += ["--out", out]
    if rng.random() < 0.8:
        args += ["--set", "model.terms=4"]
    # The program's own limit, below the hang timeout: a run it accepts must end within it.
    args += ["--max-seconds", f"{max_seconds:g}"]
    named = None
    kind = rng.random()
    if kind < 0.45:  # a scene key
        group = rng.random()
        if group < 0.6:
            key = rng.choice(sorted(NUMBER_KEYS))
            for context in NUMBER_KEYS[key]:
                args += ["--set", context]
            value = rng.choice(HOSTILE_NUMBERS) if rng.random() < 0.6 else edge_value(rng)
        elif group < 0.8:
            key = rng.choice(INTEGER_KEYS)
            value = rng.choice(["-1", "0", "2.5", "201", "99999999999", "1000", "nan", "\"x\"", str(rng.randint(-5, 300))])
        else:
            key = rng.choice(sorted(CHOICE_KEYS))
            value = rng.choice(CHOICE_KEYS[key] + ["\"nope\"", "1", "", "[\"sine\"]", "\"a\\nb\""])
        args += ["--set", f"{key}={value}"]
        named = key
    elif kind < 0.85:  # an option
        option = rng.choice(options + COMMON_OPTIONS)
        value = rng.choice(HOSTILE_TEXT) if rng.random() < 0.7 else edge_value(rng)
        args += [option, value]
        named = option
    else:  # the scene file's bytes
        data = bytearray(scene_text.encode())
        for _ in range(rng.randint(1, 8)):
            action = rng.random()
            at = rng.randrange(len(data))
            if action < 0.4:
                data[at] = rng.randrange(256)
            elif action < 0.7:
                data.insert(at, rng.randrange(256))
            else:
                del data[at]
        with open(scene, "wb") as f:
            f.write(bytes(data))
    return args, named, out


NONFINITE = re.compile(r"(?<![A-Za-z])[-+]?(nan|inf|infinity)(?![A-Za-z])", re.IGNORECASE)


SCENE_KEY = re.compile(r"\b(blade|model|operation|damping|load)\.[a-z_]+")


def names_cause(message, named):
    """Whether a refusal names what was mutated: the key or option itself, another scene key (a
    consistency error blames the pair, a missing key the one missing), or a work limit."""
    if named in message or "(--max-seconds)" in message:
        return True
    return named.startswith(("blade.", "model.", "operation.", "damping.", "load.")) and bool(SCENE_KEY.search(message))


def run_one(exe, args, named, out, timeout, max_rss_mb):
    """Runs one case; returns (findings, exit status or -signal, seconds, stderr's start)."""
    with tempfile.TemporaryFile() as out_file, tempfile.TemporaryFile() as err_file:
        start = time.monotonic()
        proc = subprocess.Popen([exe] + args, stdin=subprocess.DEVNULL, stdout=out_file, stderr=err_file,
                                start_new_session=True)
        timed_out = False
        while True:  # wait4, not wait: it gives this child's own peak memory
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid == proc.pid:
                break
            if time.monotonic() - start > timeout:
                os.killpg(proc.pid, signal.SIGKILL)
                pid, status, usage = os.wait4(proc.pid, 0)
                timed_out = True
                break
            time.sleep(0.005)
        proc.returncode = os.waitstatus_to_exitcode(status)  # so Popen does not wait again
        seconds = time.monotonic() - start
        out_file.seek(0)
        err_file.seek(0)
        text_out = out_file.read().decode("utf-8", "replace")
        text_err = err_file.read().decode("utf-8", "replace")
    rss_mb = usage.ru_maxrss / 1024
    findings = []
    if timed_out:
        findings.append("hang")
    elif proc.returncode < 0:
        findings.append(f"crash (signal {-proc.returncode})")
    else:
        if proc.returncode == 0 and NONFINITE.search(text_out):
            findings.append("nonfinite")
        if proc.returncode != 0 and text_err.count("\n") != 1:
            findings.append("multiline")
        if proc.returncode == 2 and named and not names_cause(text_err, named):
            findings.append("unnamed")
        if proc.returncode != 0 and out and os.path.isdir(out) and os.listdir(out):
            findings.append("leftover")
    if rss_mb > max_rss_mb:
        findings.append(f"memory ({rss_mb:.0f} MB)")
    return findings, proc.returncode, seconds, text_err.strip()[:300]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=20, help="seconds before a run counts as a hang")
    parser.add_argument("--max-rss", type=float, default=1024, help="MB of memory a run may use")
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "bladestab"))
    parser.add_argument("--scene", default=os.path.join(ROOT, "stability_maps", "sinha2005", "blade.toml"))
    a = parser.parse_args()
    with open(a.scene, encoding="utf-8") as f:
        scene_text = f.read()
    rng = random.Random(a.seed)
    workdir = tempfile.mkdtemp(prefix="bladestab_fuzz_")
    # A run the program accepts must end within its --max-seconds (stopped there if its estimate
    # was wrong), well inside the hang timeout.
    cases = [mutate(rng, scene_text, workdir, k, a.timeout / 2) for k in range(a.runs)]
    counts, findings = {}, []
    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            futures = {pool.submit(run_one, a.exe, args, named, out, a.timeout, a.max_rss): (args, named)
                       for args, named, out in cases}
            for k, future in enumerate(concurrent.futures.as_completed(futures), 1):
                args, _ = futures[future]
                found, status, seconds, err = future.result()
                counts[status] = counts.get(status, 0) + 1
                for what in found:
                    findings.append((what, args, status, seconds, err))
                if k % 100 == 0:
                    print(f"{k}/{a.runs} runs, {len(findings)} findings", file=sys.stderr)
    finally:
        shutil.rmtree(workdir, ignore_errors=True)
    print(f"{a.runs} runs (seed {a.seed}); exit statuses: "
          + ", ".join(f"{s}: {n}" for s, n in sorted(counts.items())))
    for what, args, status, seconds, err in sorted(findings, key=lambda f: f[0]):
        print(f"{what}: status {status} after {seconds:.1f} s: {shlex.join([a.exe] + args)}\n    {err}")
    print(f"{len(findings)} findings")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
