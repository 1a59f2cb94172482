"""The program's commands as functions: `bladestab.stability(scene, progress=None, **options)` runs
`bladestab stability SCENE --format json …` in this process (the same options, checks and answer;
arguments.py says how keyword arguments become options) and returns its Result.

The GIL is released while the command computes; Ctrl-C raises KeyboardInterrupt from its next
progress report, and `progress(label, done, total)`, if given, is called at each (from the
command's threads; an exception it raises stops the run and is raised here). Commands that write
files (campbell, map, sweep, transient) write them into `out` if given, else into a scratch
directory removed afterwards (their JSON document is kept as Result.document); they draw no chart
unless `chart` is given (Result.plot() draws it on demand)."""

import contextlib
import tempfile
import warnings

from bladestab import _core
from bladestab.arguments import command_line, command_options, scene_source
from bladestab.errors import InputError, Note
from bladestab.results import Result


def run(command, scene, progress=None, **options):
    """Runs `command` on `scene` (a path, TOML text or a dict) with `options`; its Result."""
    if command not in command_options():
        raise InputError(f"{command}: unknown command; known: {', '.join(sorted(command_options()))}")
    name, text = scene_source(scene)
    writes = "--out" in command_options()[command]
    scratch = writes and options.get("out") is None
    options = {key: value for key, value in options.items() if not (key == "out" and value is None)}
    with tempfile.TemporaryDirectory(prefix="bladestab-") if scratch else contextlib.nullcontext() as out:
        if out is not None:
            options = {"out": out, "chart": "none", **options}
        elif writes:
            options = {"chart": "none", **options}
        answer = _core.run(command_line(command, name, options), text, progress)
        result = Result(command, answer)
        if scratch:
            result.files = []  # the scratch directory and its files are gone when this returns
    for note in result.notes:
        warnings.warn(note, Note, stacklevel=3)
    return result


def _analysis(command):
    def analysis(scene, progress=None, **options):
        return run(command, scene, progress, **options)

    analysis.__name__ = analysis.__qualname__ = command
    analysis.__doc__ = (f"`bladestab {command} SCENE …` in this process: keyword arguments are its options "
                        "(dotted names: scene overrides); returns its Result.")
    return analysis


# One function per command of the program.
ANALYSES = {name: _analysis(name) for name in command_options()}
globals().update(ANALYSES)
__all__ = ["run", "ANALYSES", *ANALYSES]
