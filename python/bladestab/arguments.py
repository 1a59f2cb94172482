"""Keyword arguments to the program's command line: dotted names are scene overrides (`--set
section.key=value`), plain names the command's options (`tolerance=1e-6` is `--tolerance 1e-6`,
`cutoff_hz` is `--cutoff-hz`); True adds a flag, False leaves it out. The answer is always the
command's JSON (`--format json`)."""

import functools
import math
import numbers
import os

from bladestab import _core
from bladestab.errors import InputError

# Options the package sets itself.
RESERVED = {"--format": "the answer is always the command's JSON document (to_dict())"}


@functools.lru_cache(maxsize=None)
def command_options():
    """Each command's long option names, as the program registers them."""
    return {name: frozenset(options) for name, options in _core.command_options().items()}


def scene_value(value):
    """A Python value as a `--set` value: TOML syntax for numbers, booleans and lists, a string as
    it is (a bare word, or TOML text the caller quoted)."""
    if hasattr(value, "item") and not isinstance(value, (list, tuple)):
        value = value.item()  # NumPy scalars
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        value = float(value)
        return repr(value) if math.isfinite(value) else {"inf": "inf", "-inf": "-inf"}.get(repr(value), "nan")
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_list_item(v) for v in value) + "]"
    return str(value)


def _list_item(value):
    return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"' if isinstance(value, str) else scene_value(value)


def option_value(value):
    """A Python value as an option's text: numbers in their shortest round-trip form, lists joined
    by commas (--engine-orders 1,2,3), strings as they are (--speeds 0:600:61)."""
    if hasattr(value, "item") and not isinstance(value, (list, tuple)):
        value = value.item()
    if isinstance(value, (list, tuple)):
        return ",".join(option_value(v) for v in value)
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return repr(value) if isinstance(value, float) else str(value)
    return str(value)


def command_line(command, scene_name, options):
    """The arguments of `bladestab COMMAND SCENE --format json …` for `options`; InputError naming
    a key that is no option of the command."""
    known = command_options()[command]
    arguments = [command, scene_name, "--format", "json"]
    for key, value in options.items():
        if "." in key:
            arguments += ["--set", f"{key}={scene_value(value)}"]
            continue
        option = "--" + key.replace("_", "-")
        if option in RESERVED:
            raise InputError(f"{key}: not an option here: {RESERVED[option]}")
        if option not in known or option in ("--set", "--help"):
            names = sorted(o[2:].replace("-", "_") for o in known if o not in RESERVED and o not in ("--set", "--help"))
            raise InputError(f"{key}: not an option of {command}; its options: {', '.join(names)} "
                             "(and scene keys as section.key)")
        if value is True:
            arguments.append(option)
        elif value is not False and value is not None:
            arguments += [option, option_value(value)]
    return arguments


def _plain(value):
    """A scene dict with NumPy scalars and arrays as the Python numbers and lists TOML writes."""
    if isinstance(value, dict):
        return {key: _plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(item) for item in value]
    return value.tolist() if hasattr(value, "tolist") else value


def scene_source(scene):
    """(name, text) of a scene given as a file path, TOML text or a dict of its tables: a path is
    read by the program (text empty); text and dicts are handed over, named "<text>" and "<dict>"."""
    if isinstance(scene, dict):
        import toml  # Debian's python3-toml writes TOML

        # A newline at least: empty text would name a file; the program then says what is missing.
        return "<dict>", toml.dumps(_plain(scene)) or "\n"
    if isinstance(scene, os.PathLike):
        return os.fspath(scene), ""
    if not isinstance(scene, str):
        raise InputError(f"scene: must be a path, TOML text or a dict, not {type(scene).__name__}")
    if "\n" in scene or ("=" in scene and not os.path.exists(scene)):
        return "<text>", scene
    return scene, ""
