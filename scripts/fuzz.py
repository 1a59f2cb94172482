#!/usr/bin/python3
"""Random hostile runs of bladestab, for campaigns longer than the suite's fixed corpus
(tests/test_fuzz.cpp). docs/guide/reliability.md describes the classes and the last campaign.

    /usr/bin/python3 scripts/fuzz.py [--runs 1000] [--seed 1] [--jobs 2] [--timeout 20]
                                     [--classes mutation,extreme,threads,signal,full,toml]
                                     [--exe build/bladestab] [--scene stability_maps/sinha2005/blade.toml]

Each case is drawn from one class (--classes; all by default, in the proportions of CLASSES):
  mutation  the paper's scene and one command, with one thing mutated: a scene key (a value
            outside its range, of the wrong type, at the edge of its range, text with newlines), a
            numeric option (malformed or extreme text), or the scene file's bytes;
  extreme   several extreme but valid settings at once: buckled, diverging and near-limit blades
            (speeds up to 1e5 rad/s, static tip compression up to 2 F_cr), 1 to 24 terms, every
            theory, basis and axial setting, load profiles, up to 12 pulses per revolution,
            slenderness from its least (1e-4) to thick blades (0.99), on every command (check over
            such ranges too);
  threads   one run with --threads 1 and the same with --threads 2 (often on an extreme scene):
            stdout, stderr and every output file must be byte-identical;
  signal    SIGINT or SIGTERM to the program or its process group (as Ctrl-C), while its chart is
            drawn (once the python3 drawer runs) or at a random moment of the run;
  full      outputs that cannot be written: stdout on /dev/full, a file-size limit (RLIMIT_FSIZE
            with SIGXFSZ ignored: a disk that fills at a random byte), a tiny tmpfs (as root), a
            read-only --out (a read-only tmpfs as root, else mode 0555);
  toml      the scene rewritten: equivalent TOML (dotted keys, inline tables, quoted keys, number
            and string forms, CRLF, comments, shuffled tables) must give the original's answer
            byte for byte; odd TOML (duplicates, deep nesting, NUL bytes, bad UTF-8, other types)
            must be refused in one line or answered as the original.
Every run is judged alike. A run is a finding when it
  crash       ends by a signal (a stopped one: other than 128 + the signal sent),
  sanitizer   prints a sanitizer's report (a build with -DBLADESTAB_SANITIZE),
  hang        outlives --timeout (then it is killed), though every run is given --max-seconds of
              half of it,
  time-limit  is stopped at its own --max-seconds: a run it accepted must end or be refused at once
              (a note only, not a finding, when it had less than half the limit's CPU: a loaded
              machine),
  memory      uses more than --max-rss MB,
  status      exits other than 0, 1, 2, 130 or 143 (1 only for `check` and failures, 130/143 only
              for a signal sent),
  multiline   fails with other than exactly one line on stderr, "bladestab: …" (`check` answering
              that a requirement is not met: exit 1, the answer on stdout, nothing on stderr),
  unnamed     refuses its input (exit 2) without naming the key or option that was mutated,
  nonfinite   exits 0 with nan or inf in its stdout or in an output file, or with a JSON output
              that does not parse,
  past-limit  `modes` exits 0 with a mode at 0 Hz or |ζ| ≥ 1 on an undamped blade,
  leftover    fails and leaves files in its --out directory, or leaves a temporary (".*.tmp.*")
              there in any case,
  orphan      its chart drawer outlives it,
  differs     (threads, toml) an answer that should be identical is not.
Findings (and notes) are printed as command lines that reproduce them, grouped by kind, then
counted; the exit status is 1 if there are findings.
"""

import argparse
import concurrent.futures
import json
import os
import random
import re
import resource
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import tomllib
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The share of each class in a campaign.
CLASSES = {"mutation": 0.30, "extreme": 0.22, "threads": 0.16, "signal": 0.10, "full": 0.10, "toml": 0.12}

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

# Numeric options per command, and what each command needs besides (small sizes: runs stay short).
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
THREADED = ["campbell", "map", "sweep", "stability", "boundaries"]
COMMON_OPTIONS = ["--max-seconds", "--max-memory"]

HOSTILE_NUMBERS = ["nan", "inf", "-inf", "1e308", "-1e308", "1e-308", "-1e-308", "0", "-0", "-1", "1e30",
                   "9e99", "\"x\"", "[1, 2]", "true", "{ a = 1 }", "1979-05-27", "\"a\\nb\"", "0x10", "1e999",
                   "\"" + "y" * 5000 + "\"", "[" + ", ".join(["1"] * 20000) + "]"]
HOSTILE_TEXT = ["", " ", " 1", "1 ", "0x10", "0x1p3", "nan", "inf", "-inf", "1e999", "1e308", "-1e308", "1e-308",
                "abc", "1,2", ",", "1:2", "1:2:3", "0:0:2", "1e308:1e309:3", "-5", "0", "1\n2", "\t1",
                "9" * 400, "1x1", "0x0", "4097x1", "1,1", "2,1,2", "+1", "1.", ".5", "1e+2", "0.0", "-0.0",
                "1_000", "１", "1e-400"]

# Extreme but valid settings (each within its scene range): the limits of the blade itself.
EXTREME_VALUES = {
    "operation.speed_rad_s": ["0", "1e-3", "300", "3000", "9000", "20000", "99999", "1e5"],
    "operation.tip_compression_over_fcr": ["0", "0.5", "0.99", "0.99923", "0.9993", "1", "1.5", "2", "4.9", "4.96"],
    "model.terms": [str(n) for n in range(1, 25)],
    "model.theory": ["\"timoshenko\"", "\"euler-bernoulli\""],
    "model.basis": ["\"sine\"", "\"legendre\""],
    "model.axial": ["true", "false"],
    "model.coriolis": ["true", "false"],
    "load.profile": ["\"half-sine\"", "\"cosine\"", "\"triangular\"", "\"saw-tooth\"", "\"rectangular\"",
                     "\"impulse\""],
    "load.approximation": ["\"cosine\"", "\"fourier\"", "\"exact\""],
    "load.pulses_per_rev": [str(n) for n in range(1, 13)],
    "load.fmax_over_fcr": ["0", "1e-6", "1", "5", "50", "500"],
    "load.contact_time_rev": ["1e-4", "0.01", "0.05", "0.08"],
    "blade.slenderness": ["1e-4", "1.0001e-4", "3e-4", "1e-3", "0.01", "0.1", "0.3", "0.6", "0.99"],
    "damping.model": ["\"none\"", "\"paper\"", "\"rayleigh\""],
}
# Small runs of each command for extreme scenes, each a choice of ranges that reach the blade's
# limits (check needs a [requirements] scene).
EXTREME_COMMANDS = {
    "modes": [[]], "stability": [[]], "boundaries": [[]],
    "crosscheck": [["--points", "1", "--revolutions", "4"]],
    "campbell": [["--speeds", speeds, "--chart", "none"]
                 for speeds in ["0:600:4", "9000:12000:5", "0:100000:4", "99000:100000:3"]],
    "map": [["--plane", "theta-fmax", "--chart", "none", "--theta", "100:1000:3", "--fmax", "0:5:3", "--trace", "4",
             "--resolution", "4x4"],
            ["--plane", "speed-fmax", "--chart", "none", "--speeds", "0:9000:3", "--fmax", "0:5:3", "--trace", "4",
             "--resolution", "4x4"]],
    "transient": [["--chart", "none", "--revolutions", "0.3"]],
    "sweep": [["--key", key, "--values", values, "--chart", "none"]
              for key, values in [("operation.speed_rad_s", "0:9000:3"), ("operation.speed_rad_s", "0:1e5:3"),
                                  ("operation.tip_compression_over_fcr", "0:2:4"),
                                  ("blade.slenderness", "1e-4:0.99:4")]],
    "check": [[]],
}
REQUIREMENT_RANGES = ["[245.0, 280.0]", "[0.0, 1e-300]", "[0.0, 600.0]", "[99999.0, 100000.0]", "[9000.0, 12000.0]",
                      "[1e-3, 2e-3]"]

# Drawing runs for the signal class: each draws a PNG in well under a few seconds.
DRAWING = {
    "sweep": ["--key", "operation.speed_rad_s", "--values", "0:300:3"],
    "campbell": ["--speeds", "0:600:3"],
    "map": ["--plane", "theta-fmax", "--theta", "100:1000:3", "--fmax", "0:5:3", "--trace", "4", "--resolution", "4x4"],
    "transient": ["--revolutions", "0.5"],
}

NONFINITE = re.compile(r"(?<![A-Za-z])[-+]?(nan|inf|infinity)(?![A-Za-z])", re.IGNORECASE)
SCENE_KEY = re.compile(r"\b(blade|model|operation|damping|load|requirements)\.[a-z_]+")
SANITIZER = re.compile(r"(AddressSanitizer|LeakSanitizer|ThreadSanitizer|UndefinedBehaviorSanitizer|"
                       r"runtime error:)")
TEMPORARY = re.compile(r"^\..*\.tmp(\.|$)")
STOP_LINE = {signal.SIGINT: "interrupted (SIGINT)", signal.SIGTERM: "terminated (SIGTERM)"}


class Case:
    """One command line to run and how to judge it."""

    def __init__(self, kind, args, named=None, out=None):
        self.kind, self.args, self.named, self.out = kind, args, named, out
        self.stdout_path = None  # stdout to this file instead of a capture (/dev/full)
        self.file_bytes = None   # RLIMIT_FSIZE of the run
        self.stop = None         # (signal, to its group, "drawing" or seconds after the start)
        self.pair = None         # (threads) the second run's args and out
        self.same_as = None      # (toml) args whose stdout must equal this run's
        self.mounts = []         # (full) tmpfs mounted for this case, unmounted after it
        self.equivalent = True   # (toml) the rewritten scene means the same as the original


def edge_value(rng):
    """A number from the edges of any plausible range: tiny, huge, around 0 and 1."""
    return rng.choice([
        f"{rng.uniform(-1, 1):.6g}e{rng.randint(-320, 320)}",
        f"{10 ** rng.uniform(-8, 16):.6g}",
        rng.choice(["0", "1", "0.5", "1e-6", "1e-3", "1e5", "1e13", "1e15", "1000", "100000", "0.4999999",
                    "-0.9999999", "90", "-90"]),
    ])


def write_scene(workdir, run_id, text, suffix=""):
    path = os.path.join(workdir, f"scene_{run_id}{suffix}.toml")
    with open(path, "wb") as f:
        f.write(text if isinstance(text, bytes) else text.encode())
    return path


def with_out(args, command, workdir, name):
    """`args` with --out DIR for commands that write; returns (args, DIR or None)."""
    if command not in WRITES:
        return args, None
    out = os.path.join(workdir, name)
    return args + ["--out", out], out


def mutation_case(rng, ctx, run_id):
    """The paper's scene and one command, one thing mutated."""
    command = rng.choice(sorted(COMMANDS))
    needs, options = COMMANDS[command]
    scene = write_scene(ctx.workdir, run_id, ctx.scene_text)
    args, out = with_out([command, scene] + list(needs), command, ctx.workdir, f"out_{run_id}")
    if rng.random() < 0.8:
        args += ["--set", "model.terms=4"]
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
            value = rng.choice(["-1", "0", "2.5", "201", "99999999999", "1000", "nan", "\"x\"", "16.0", "1e1",
                                str(rng.randint(-5, 300))])
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
        data = bytearray(ctx.scene_text.encode())
        for _ in range(rng.randint(1, 8)):
            action = rng.random()
            at = rng.randrange(len(data))
            if action < 0.4:
                data[at] = rng.randrange(256)
            elif action < 0.7:
                data.insert(at, rng.randrange(256))
            else:
                del data[at]
        write_scene(ctx.workdir, run_id, bytes(data))
    return Case("mutation", args, named, out)


def extreme_settings(rng):
    """--set arguments for 2 to 6 extreme but valid settings at once."""
    keys = rng.sample(sorted(EXTREME_VALUES), rng.randint(2, 6))
    sets = []
    for key in keys:
        sets += ["--set", f"{key}={rng.choice(EXTREME_VALUES[key])}"]
    if "model.terms" not in keys:
        sets += ["--set", f"model.terms={rng.choice([4, 4, 6, 8])}"]
    return sets


def extreme_scene(rng, ctx, run_id, command):
    """The scene file for an extreme run: the paper's, or for `check` one with [requirements]."""
    if command != "check":
        return write_scene(ctx.workdir, run_id, ctx.scene_text)
    requirements = (f"\n[requirements]\nspeed_range_rad_s = {rng.choice(REQUIREMENT_RANGES)}\n"
                    f"engine_orders = {rng.choice(['[1, 2, 3]', '[1]', '[12]', '[1, 2, 3, 4, 5, 6, 7, 8]'])}\n")
    if rng.random() < 0.7:
        requirements += f"frequency_margin = {rng.choice(['0.1', '0.999', '0.5', '1e-9'])}\n"
    if rng.random() < 0.5 or "frequency_margin" not in requirements:
        requirements += f"max_fmax_over_fcr = {rng.choice(['0.5', '0.0', '2.0'])}\n"
    return write_scene(ctx.workdir, run_id, ctx.scene_text + requirements)


def extreme_case(rng, ctx, run_id):
    command = rng.choice(sorted(EXTREME_COMMANDS))
    scene = extreme_scene(rng, ctx, run_id, command)
    args, out = with_out([command, scene] + rng.choice(EXTREME_COMMANDS[command]), command, ctx.workdir,
                         f"out_{run_id}")
    args += extreme_settings(rng)
    if command in THREADED:
        args += ["--threads", rng.choice(["1", "2"])]
    if rng.random() < 0.3 and command != "check":
        args += ["--format", rng.choice(["json", "csv"]) if command != "modes" else "json"]
    return Case("extreme", args, None, out)


def threads_case(rng, ctx, run_id):
    """The same run on 1 and on 2 threads."""
    command = rng.choice(THREADED)
    scene = write_scene(ctx.workdir, run_id, ctx.scene_text)
    base = [command, scene] + rng.choice(EXTREME_COMMANDS[command])
    base += extreme_settings(rng) if rng.random() < 0.7 else ["--set", "model.terms=4"]
    if command in WRITES and rng.random() < 0.15:
        base = [a for a in base if a not in ("--chart", "none")] + ["--chart", "png"]
    if rng.random() < 0.3:
        base += ["--format", "json"]
    first, out1 = with_out(base + ["--threads", "1"], command, ctx.workdir, f"out_{run_id}_t1")
    second, out2 = with_out(base + ["--threads", "2"], command, ctx.workdir, f"out_{run_id}_t2")
    case = Case("threads", first, None, out1)
    case.pair = (second, out2)
    return case


def signal_case(rng, ctx, run_id):
    command = rng.choice(sorted(DRAWING))
    scene = write_scene(ctx.workdir, run_id, ctx.scene_text)
    args, out = with_out([command, scene, "--set", "model.terms=4", "--chart", rng.choice(["png", "png", "svg"])]
                         + DRAWING[command], command, ctx.workdir, f"out_{run_id}")
    # At a random moment after its start (by 0.1 s the handlers are installed, even under ASan).
    when = "drawing" if rng.random() < 0.7 else rng.uniform(0.1, 1.5)
    case = Case("signal", args, None, out)
    case.stop = (rng.choice([signal.SIGINT, signal.SIGTERM]), rng.random() < 0.5, when)
    return case


def mount_tmpfs(path, options):
    """A tmpfs at `path` (as root); False where mounting is not allowed."""
    os.makedirs(path, exist_ok=True)
    return subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", path], stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL).returncode == 0


def full_case(rng, ctx, run_id):
    """A run whose outputs cannot all be written."""
    command = rng.choice(sorted(WRITES | {"modes", "stability"}))
    needs = DRAWING.get(command, []) if command in WRITES else []
    scene = write_scene(ctx.workdir, run_id, ctx.scene_text)
    args = [command, scene, "--set", "model.terms=4"] + needs
    if command in WRITES:
        args += ["--chart", rng.choice(["none", "png", "png"])]
    case = Case("full", args)
    how = rng.choice(["dev-full", "file-size", "tmpfs", "read-only"])
    if how == "dev-full" or command not in WRITES:
        case.stdout_path = "/dev/full"
        case.args, case.out = with_out(case.args, command, ctx.workdir, f"out_{run_id}")
        return case
    out_root = os.path.join(ctx.workdir, f"mount_{run_id}")
    if how == "file-size":
        case.file_bytes = int(10 ** rng.uniform(2, 5.5))
        os.makedirs(out_root)
    elif how == "tmpfs" and ctx.root and mount_tmpfs(out_root, f"size={rng.choice([4, 8, 16, 32, 64, 128])}k"):
        case.mounts.append(out_root)
    elif ctx.root and mount_tmpfs(out_root, "ro,size=64k"):
        case.mounts.append(out_root)
    else:
        os.makedirs(out_root, exist_ok=True)
        os.chmod(out_root, 0o555)
    case.out = os.path.join(out_root, "out") if rng.random() < 0.5 else out_root
    case.args += ["--out", case.out]
    return case


def toml_number_forms(value, rng):
    """An equivalent TOML spelling of the number text `value` (the scene's are non-negative integers
    and floats)."""
    if re.fullmatch(r"\d+", value):
        n = int(value)
        return rng.choice([f"+{n}", hex(n), oct(n), bin(n), f"{n:_}"])
    x = float(value)
    return rng.choice([repr(x), f"{x:.17e}", f"{x:.17E}", ("+" if x >= 0 else "") + repr(x)])


def scene_tables(text):
    """The scene as {table: [(key, value text)]}, in order (comments dropped)."""
    tables, current = {}, None
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()  # the scene's strings hold no '#'
        if not line:
            continue
        if line.startswith("["):
            current = line.strip("[] ")
            tables[current] = []
        else:
            key, value = (part.strip() for part in line.split("=", 1))
            tables[current].append((key, value))
    return tables


def equivalent_toml(rng, text):
    """The scene in another, equivalent TOML spelling."""
    tables = scene_tables(text)
    order = list(tables)
    if rng.random() < 0.5:
        rng.shuffle(order)
    lines = []
    for table in order:
        entries = []
        for key, value in tables[table]:
            if rng.random() < 0.3 and re.fullmatch(r"[0-9.eE+-]+", value):
                value = toml_number_forms(value, rng)
            elif rng.random() < 0.3 and value.startswith("\""):
                inner = value.strip("\"")
                value = rng.choice([f"'{inner}'", f'"""{inner}"""', "\"" + "".join(f"\\u{ord(c):04x}" for c in inner)
                                    + "\""])
            if rng.random() < 0.2:
                key = rng.choice([f"\"{key}\"", f"'{key}'"])
            entries.append((key, value))
        style = rng.choice(["table", "dotted", "inline", "spaced"])
        if style == "table":
            lines.append(f"[{table}]")
            lines += [f"{k} = {v}" for k, v in entries]
        elif style == "spaced":
            lines.append(f"[ {table} ]  # a comment")
            lines += [f"\t{k}\t=\t{v}   # comment" for k, v in entries]
        elif style == "dotted":
            lines = [f"{table}.{k} = {v}" for k, v in entries] + lines  # before any [table]
        else:
            lines = [f"{table} = {{ " + ", ".join(f"{k} = {v}" for k, v in entries) + " }"] + lines
        lines.append("")
    newline = "\r\n" if rng.random() < 0.3 else "\n"
    return newline.join(lines) + newline


ODD_TOML = [
    lambda t: t + "\n[blade]\nlength = 2.0\n",                             # a table twice
    lambda t: t.replace("length = 1.0", "length = 1.0\nlength = 1.0"),    # a key twice
    lambda t: t.replace("terms = 16", "terms = 16.0"),                    # a float for an integer
    lambda t: t.replace("terms = 16", "terms = 1_6"),
    lambda t: t.replace("length = 1.0", "length = 1"),                   # an integer for a float
    lambda t: t.replace("speed_rad_s = 300.0", "speed_rad_s = 3e2"),
    lambda t: t.replace("speed_rad_s = 300.0", "speed_rad_s = nan"),
    lambda t: t.replace("speed_rad_s = 300.0", "speed_rad_s = +inf"),
    lambda t: t.replace("speed_rad_s = 300.0", "speed_rad_s = 99999999999999999999"),
    lambda t: t.replace("speed_rad_s = 300.0", "speed_rad_s = 0x12C"),
    lambda t: t.replace("speed_rad_s = 300.0", "speed_rad_s = \"300\""),
    lambda t: t.replace("speed_rad_s = 300.0", "speed_rad_s = 1979-05-27T07:32:00Z"),
    lambda t: t.replace("speed_rad_s = 300.0", "speed_rad_s = " + "[" * 5000 + "]" * 5000),
    lambda t: t.replace("speed_rad_s = 300.0", "speed_rad_s = {}"),
    lambda t: t.replace("[blade]", "[[blade]]"),
    lambda t: t.replace("[blade]", "[blade.extra]\n[blade]"),
    lambda t: t.replace("basis = \"legendre\"", "basis = \"legendre\u0000\""),
    lambda t: t.replace("basis = \"legendre\"", "basis = \"leg\\u00e9ndre\""),
    lambda t: t.replace("basis = \"legendre\"", "basis = \"legendre"),
    lambda t: "\ufeff" + t,                                               # a byte-order mark
    lambda t: t.replace("\n", "\r"),                                      # old Mac line ends
    lambda t: t + "\n" + "x" * 200000 + " = 1\n",
    lambda t: t + "\n[unknown]\nkey = 1\n",
    lambda t: t + "\nblade.extra = 1\n",
    lambda t: t.replace("axial = true", "axial = True"),
    lambda t: t.replace("axial = true", "axial = 1"),
]


def toml_case(rng, ctx, run_id):
    """An equivalent or odd spelling of the scene; `modes` or `stability` as JSON, terms = 4."""
    command = rng.choice(["modes", "stability"])
    tail = ["--set", "model.terms=4", "--format", "json"]
    if rng.random() < 0.6:
        text = equivalent_toml(rng, ctx.scene_text)
        equivalent = True
    else:
        text = rng.choice(ODD_TOML)(ctx.scene_text)
        equivalent = False
    scene = write_scene(ctx.workdir, run_id, text.encode("utf-8", "surrogatepass"))
    case = Case("toml", [command, scene] + tail)
    case.equivalent = equivalent
    case.same_as = [command, ctx.original_scene] + tail
    return case


MAKERS = {"mutation": mutation_case, "extreme": extreme_case, "threads": threads_case, "signal": signal_case,
          "full": full_case, "toml": toml_case}


def names_cause(message, named):
    """Whether a refusal names what was mutated: the key or option itself, another scene key (a
    consistency error blames the pair, a missing key the one missing), or a work limit."""
    if named in message or "(--max-seconds)" in message:
        return True
    return named.startswith(("blade.", "model.", "operation.", "damping.", "load.")) and bool(SCENE_KEY.search(message))


def process_state(pid):
    """(state letter, parent, name) of `pid` from /proc, or None when it is gone."""
    try:
        with open(f"/proc/{pid}/stat", encoding="utf-8", errors="replace") as f:
            stat = f.read()
    except OSError:
        return None
    name = stat[stat.find("(") + 1:stat.rfind(")")]
    fields = stat[stat.rfind(")") + 2:].split()
    return fields[0], int(fields[1]), name


def find_drawer(program):
    """A python3 process descended from `program` (its chart drawer), or None."""
    states = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            state = process_state(int(entry))
            if state:
                states[int(entry)] = state
    for pid, (_, parent, name) in states.items():
        if not name.startswith("python3"):
            continue
        for _ in range(4):  # the program's child, or a shell's between them
            if parent == program:
                return pid
            parent = states[parent][1] if parent in states else 0
    return None


def alive(pid):
    state = process_state(pid)
    return state is not None and state[0] not in ("Z", "X")


def limit_file_size(file_bytes):
    """preexec_fn: writes past `file_bytes` fail with EFBIG (SIGXFSZ ignored), as on a full disk."""
    def apply():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (file_bytes, resource.RLIM_INFINITY))
    return apply


class Result:
    def __init__(self):
        self.status, self.out, self.err, self.seconds, self.rss_mb = 0, "", "", 0.0, 0.0
        self.timed_out, self.signalled, self.drawer_outlived = False, None, False
        self.cpu_seconds = 0.0


def execute(exe, case, args, timeout):
    """Runs `args` as `case` says; returns a Result."""
    r = Result()
    with tempfile.TemporaryFile() as out_file, tempfile.TemporaryFile() as err_file:
        stdout = open(case.stdout_path, "wb") if case.stdout_path else out_file
        start = time.monotonic()
        proc = subprocess.Popen([exe] + args, stdin=subprocess.DEVNULL, stdout=stdout, stderr=err_file,
                                start_new_session=True, cwd=os.path.dirname(args[1]),  # the scene's folder
                                preexec_fn=limit_file_size(case.file_bytes) if case.file_bytes else None)
        if case.stdout_path:
            stdout.close()
        drawer = None
        while True:  # wait4, not wait: it gives this child's own peak memory
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid == proc.pid:
                break
            now = time.monotonic() - start
            if case.stop and r.signalled is None:
                signum, group, when = case.stop
                if when == "drawing":
                    drawer = find_drawer(proc.pid)
                if (when == "drawing" and drawer) or (when != "drawing" and now >= when):
                    os.kill(-proc.pid if group else proc.pid, signum)
                    r.signalled = signum
            if now > timeout:
                os.killpg(proc.pid, signal.SIGKILL)
                pid, status, usage = os.wait4(proc.pid, 0)
                r.timed_out = True
                break
            time.sleep(0.003 if case.stop else 0.01)
        proc.returncode = os.waitstatus_to_exitcode(status)  # so Popen does not wait again
        r.seconds = time.monotonic() - start
        if drawer is not None:
            for _ in range(200):  # a drawer killed by the program is gone at once; an orphan lives on
                if not alive(drawer):
                    break
                time.sleep(0.01)
            r.drawer_outlived = alive(drawer)
            if r.drawer_outlived:
                os.kill(drawer, signal.SIGKILL)
        r.status = proc.returncode
        out_file.seek(0)
        err_file.seek(0)
        r.out = out_file.read().decode("utf-8", "replace")
        r.err = err_file.read().decode("utf-8", "replace")
    r.rss_mb = usage.ru_maxrss / 1024
    r.cpu_seconds = usage.ru_utime + usage.ru_stime
    return r


def output_files(out):
    """{name: bytes} of every file under `out` (relative names)."""
    files = {}
    if out and os.path.isdir(out):
        for folder, _, names in os.walk(out):
            for name in names:
                path = os.path.join(folder, name)
                with open(path, "rb") as f:
                    files[os.path.relpath(path, out)] = f.read()
    return files


def nonfinite_json(text):
    """Whether `text` is not JSON or holds NaN/Infinity."""
    def refuse(constant):
        raise ValueError(constant)
    try:
        json.loads(text, parse_constant=refuse)
    except ValueError:
        return True
    return False


def past_limit(args, text):
    """`modes --format json` on an undamped blade: a mode at 0 Hz or |ζ| ≥ 1 is past a static limit."""
    damped = any(a.startswith("damping.model=") and "none" not in a for a in args)
    if args[0] != "modes" or "--format" not in args or damped:
        return False
    try:
        modes = json.loads(text).get("modes", [])
    except (ValueError, AttributeError):
        return False
    return any(isinstance(m, dict) and (m.get("frequency_hz", 1) <= 0 or abs(m.get("damping_ratio", 0)) >= 1)
               for m in modes)


def judge(case, args, out, r, max_rss_mb):
    """The findings of one run."""
    found = []
    lines = r.err.count("\n")
    # stderr is captured in a file, under the run's file-size limit too: a line cut at that limit
    # (as on a full disk) is still the run's one line.
    if case.file_bytes and len(r.err.encode()) >= case.file_bytes and "\n" not in r.err:
        lines = 1
    if r.timed_out:
        return ["hang"]
    if r.status < 0:
        found.append(f"crash (signal {-r.status})")
    if SANITIZER.search(r.err):
        found.append("sanitizer")
    allowed = {0, 1, 2} | ({128 + r.signalled} if r.signalled else set())
    if r.status >= 0 and r.status not in allowed:
        found.append(f"status {r.status}")
    negative_answer = args[0] == "check" and r.status == 1 and not r.err and r.out  # a requirement not met
    if r.status > 0 and not negative_answer and (lines != 1 or not r.err.startswith("bladestab: ")):
        found.append("multiline")
    if r.status == 2 and case.named and not names_cause(r.err, case.named):
        found.append("unnamed")
    if r.status == 1 and "stopped at the time limit" in r.err:
        # On a loaded machine a run that needs a few seconds of CPU outlasts its wall-time limit: a
        # note, not a finding, when it got less than half the limit's CPU.
        limit = float(args[args.index("--max-seconds") + 1])
        loaded = r.cpu_seconds < 0.5 * limit
        found.append(f"{'note: ' if loaded else ''}time-limit ({r.cpu_seconds:.1f} s CPU)")
    if r.signalled and r.status == 128 + r.signalled and STOP_LINE[r.signalled] not in r.err:
        found.append("multiline")
    files = output_files(out)
    if r.status == 0:
        if NONFINITE.search(r.out) or ("--format" in args and args[args.index("--format") + 1] == "json"
                                       and not case.stdout_path and nonfinite_json(r.out)):
            found.append("nonfinite")
        for name, data in files.items():
            text = data.decode("utf-8", "replace")
            if (name.endswith(".csv") and NONFINITE.search(text)) or (name.endswith(".json") and nonfinite_json(text)):
                found.append(f"nonfinite ({name})")
        if past_limit(args, r.out):
            found.append("past-limit")
    if any(TEMPORARY.match(os.path.basename(name)) for name in files):
        found.append("leftover (temporary)")
    elif r.status != 0 and files and not any(
            complete in r.err for complete in ("its output files were written", "cannot write the output to stdout")):
        # (A failed stdout comes after the files are in place: they are the whole set.)
        found.append("leftover")
    if r.drawer_outlived:
        found.append("orphan")
    if r.rss_mb > max_rss_mb:
        found.append(f"memory ({r.rss_mb:.0f} MB)")
    return found


def normalized(text, out):
    return text.replace(out, "OUT") if out else text


def run_case(exe, case, timeout, max_rss_mb, baselines):
    """Runs a case; returns (findings [(what, args, status, seconds, stderr)], statuses)."""
    try:
        r = execute(exe, case, case.args, timeout)
        found = [(what, case.args, r) for what in judge(case, case.args, case.out, r, max_rss_mb)]
        statuses = [r.status]
        if case.pair:
            args2, out2 = case.pair
            r2 = execute(exe, case, args2, timeout)
            statuses.append(r2.status)
            found += [(what, args2, r2) for what in judge(case, args2, out2, r2, max_rss_mb)]
            files1, files2 = output_files(case.out), output_files(out2)
            same = (r.status == r2.status and normalized(r.out, case.out) == normalized(r2.out, out2)
                    and normalized(r.err, case.out) == normalized(r2.err, out2)
                    and files1.keys() == files2.keys()
                    and all(normalized(files1[k].decode("latin-1"), case.out)
                            == normalized(files2[k].decode("latin-1"), out2) for k in files1))
            stopped = any(x.timed_out or "stopped at the time limit" in x.err for x in (r, r2))
            if not same and not stopped:
                found.append(("differs (--threads 1 against 2)", args2, r2))
        if case.same_as and (case.equivalent or r.status == 0):
            base = baselines(case.same_as)
            scene = case.args[1]
            if normalized(r.out, scene) != normalized(base.out, case.same_as[1]) or r.status != base.status:
                found.append(("differs (equivalent TOML)" if case.equivalent else "differs (odd TOML answered)",
                              case.args, r))
        return found, statuses
    finally:
        for mount in case.mounts:
            subprocess.run(["umount", "-l", mount], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


class Context:
    def __init__(self, workdir, scene_path):
        self.workdir = workdir
        with open(scene_path, encoding="utf-8") as f:
            self.scene_text = f.read()
        # A section table (blade.sections) is read beside the scene: the scenes written here need it too.
        sections = tomllib.loads(self.scene_text).get("blade", {}).get("sections")
        if isinstance(sections, str) and not os.path.isabs(sections):
            target = os.path.join(workdir, sections)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copy(os.path.join(os.path.dirname(os.path.abspath(scene_path)), sections), target)
        self.original_scene = write_scene(workdir, "original", self.scene_text)
        self.root = os.geteuid() == 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=1000, help="cases to run (a threads case runs twice)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=20, help="seconds before a run counts as a hang")
    parser.add_argument("--max-rss", type=float, default=1024, help="MB of memory a run may use")
    parser.add_argument("--classes", default=",".join(CLASSES), help="comma-separated: " + ", ".join(CLASSES))
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "bladestab"))
    parser.add_argument("--scene", default=os.path.join(ROOT, "stability_maps", "sinha2005", "blade.toml"))
    a = parser.parse_args()
    a.exe = os.path.abspath(a.exe)
    chosen = [c.strip() for c in a.classes.split(",") if c.strip()]
    unknown = [c for c in chosen if c not in CLASSES]
    if unknown or not chosen:
        parser.error(f"--classes {a.classes}: known classes are {', '.join(CLASSES)}")
    rng = random.Random(a.seed)
    workdir = tempfile.mkdtemp(prefix="bladestab_fuzz_")
    ctx = Context(workdir, a.scene)
    weights = [CLASSES[c] for c in chosen]
    cases = []
    for k in range(a.runs):
        kind = rng.choices(chosen, weights)[0]
        case = MAKERS[kind](rng, ctx, k)
        # The program's own limit, below the hang timeout: a run it accepts must end within it.
        if not any(arg == "--max-seconds" for arg in case.args):
            case.args += ["--max-seconds", f"{a.timeout / 2:g}"]
            if case.pair:
                case.pair = (case.pair[0] + ["--max-seconds", f"{a.timeout / 2:g}"], case.pair[1])
        if case.same_as:
            case.same_as = case.same_as + ["--max-seconds", f"{a.timeout / 2:g}"]
        cases.append(case)
    baseline_cache = {}

    def baselines(args):
        key = tuple(args)
        if key not in baseline_cache:
            baseline_cache[key] = execute(a.exe, Case("baseline", args), args, a.timeout)
        return baseline_cache[key]

    counts, by_class, findings = {}, {}, []
    started = time.monotonic()
    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            futures = {pool.submit(run_case, a.exe, case, a.timeout, a.max_rss, baselines): case for case in cases}
            for k, future in enumerate(concurrent.futures.as_completed(futures), 1):
                case = futures[future]
                found, statuses = future.result()
                by_class[case.kind] = by_class.get(case.kind, 0) + 1
                for status in statuses:
                    counts[status] = counts.get(status, 0) + 1
                for what, args, r in found:
                    findings.append((what, case.kind, args, r.status, r.seconds, r.err.strip()[:300]))
                if k % 100 == 0:
                    print(f"{k}/{a.runs} cases, {len(findings)} findings and notes", file=sys.stderr)
    finally:
        shutil.rmtree(workdir, ignore_errors=True)
    runs = sum(counts.values())
    print(f"{a.runs} cases, {runs} runs (seed {a.seed}) in {time.monotonic() - started:.0f} s; classes: "
          + ", ".join(f"{c}: {n}" for c, n in sorted(by_class.items())) + "; exit statuses: "
          + ", ".join(f"{s}: {n}" for s, n in sorted(counts.items())))
    for what, kind, args, status, seconds, err in sorted(findings, key=lambda f: (f[0], f[1])):
        print(f"{what} [{kind}]: status {status} after {seconds:.1f} s: {shlex.join([a.exe] + args)}\n    {err}")
    kinds = {}
    for what, *_ in findings:
        kind = re.sub(r" \(.*", "", what)
        kinds[kind] = kinds.get(kind, 0) + 1
    notes = sum(n for kind, n in kinds.items() if kind.startswith("note: "))
    print(f"{len(findings) - notes} findings, {notes} notes: "
          + ", ".join(f"{kind}: {n}" for kind, n in sorted(kinds.items())))
    return 1 if len(findings) > notes else 0


if __name__ == "__main__":
    sys.exit(main())
