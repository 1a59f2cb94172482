"""Ctrl-C during a long analysis: KeyboardInterrupt at the run's next progress report, from any of
its threads, and the interpreter intact (it goes on to answer another run)."""

import os
import signal
import subprocess
import sys
import time

from conftest import SCENE

# A child that prints "ready" at the run's first progress report, then "interrupted <time>" if
# KeyboardInterrupt ends the run, then what `AFTER` prints.
CHILD = """
import time
import bladestab
started = []
def ready(label, done, total):
    if not started:
        started.append(print("ready", flush=True))
try:
    {run}
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", time.monotonic(), flush=True)
{after}
"""


def interrupt_when_ready(run, after=""):
    """Ctrl-C 0.5 s after the child's run first reports; its output lines, the seconds from the
    signal to the interruption, and its exit status."""
    script = CHILD.format(run=run, after=after)
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=os.environ)
    assert child.stdout.readline().strip() == "ready"
    time.sleep(0.5)
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=120)
    lines = out.split("\n")
    assert lines[0].startswith("interrupted"), out
    return lines, float(lines[0].split()[1]) - sent, child.returncode


def test_ctrl_c_stops_a_long_map_and_the_interpreter_goes_on():
    # A map of ~90 s; "ready" once its points have started (its set-up before them reports nothing).
    lines, delay, status = interrupt_when_ready(
        f'bladestab.map({SCENE!r}, plane="theta-fmax", theta="100:1000:80", fmax="0:5:60", trace=5, '
        f'max_order=1, threads=2, progress=ready)',
        f'print("then", bladestab.stability({SCENE!r}).stable, flush=True)')
    # At its next report, once the points under way are done (under 1 s when run alone here, 1.2 s
    # beside the whole suite on 2 cores at load 9.8), not at the map's end a minute later.
    assert delay < 5.0
    assert lines[1] == "then False" and status == 0


def test_ctrl_c_stops_a_transient_inside_its_contact_pieces_and_its_richer_run():
    # ~30 s on two cores: one contact of half a revolution cut into 100 pieces, on the scene's model
    # and, beside it for the error estimate, on the richer one; "ready" at the first piece.
    lines, delay, status = interrupt_when_ready(
        f'bladestab.transient({SCENE!r}, revolutions=60, chart="none", threads=2, progress=ready, '
        f'**{{"load.contact_time_rev": 0.5}})')
    # Within a contact piece of each run (0.2 s here), not at the richer run's end ~30 s later.
    assert delay < 5.0 and status == 0


def test_ctrl_c_after_a_run_inside_a_progress_callback_stops_the_next_run_and_only_it():
    # A run started inside another's progress callback, then Ctrl-C during a later run: that run
    # stops; the analysis after it, on another thread, is not stopped by the Ctrl-C before it.
    lines, delay, status = interrupt_when_ready(
        f'inner = []; bladestab.stability({SCENE!r}, progress=lambda *report: inner or '
        f'inner.append(bladestab.modes({SCENE!r}, count=2))); '
        f'bladestab.transient({SCENE!r}, revolutions=60, chart="none", threads=2, progress=ready, '
        f'**{{"load.contact_time_rev": 0.5}})',
        'import concurrent.futures\n'
        f'print("then", concurrent.futures.ThreadPoolExecutor(1).submit(bladestab.stability, {SCENE!r}).result().stable, '
        'flush=True)')
    assert delay < 5.0
    assert lines[1] == "then False" and status == 0


def test_a_sigint_handler_of_the_callers_own_that_does_not_raise_lets_the_run_finish():
    script = f"""
import signal, bladestab
calls = []
signal.signal(signal.SIGINT, lambda number, frame: calls.append(number))
def ready(label, done, total):
    if not calls and done == 1:
        print("ready", flush=True)
answer = bladestab.stability({SCENE!r}, tolerance=1e-9, threads=1, progress=ready)
print(len(calls), answer.stable, flush=True)
"""
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=os.environ)
    assert child.stdout.readline().strip() == "ready"
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=120)
    assert out.strip() == "1 False" and child.returncode == 0
