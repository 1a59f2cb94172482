"""Keyword arguments to the program's command line: dotted names are scene overrides (`--set
section.key=value`), plain names the command's options (`tolerance=1e-6` is `--tolerance 1e-6`,
`cutoff_hz` is `--cutoff-hz`); a flag takes True (given) or False (left out), an option with a
value takes that value, or None for the command's default. The answer is always the command's JSON
(`--format json`)."""

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
    """Each command's long option names, as the program registers them, each mapped to whether it
    takes a value (False for a flag)."""
    return {name: dict(options) for name, options in _core.command_options().items()}


def scene_value(value):
    """A Python value as a `--set` value: TOML syntax for numbers, booleans and lists, a string as
    it is (a bare word, or TOML text the caller quoted)."""
    if hasattr(value, "tolist"):
        value = value.tolist()  # NumPy scalars and arrays
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
    if hasattr(value, "tolist"):
        value = value.tolist()  # NumPy scalars and arrays
    if isinstance(value, (list, tuple)):
        return ",".join(option_value(v) for v in value)
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return repr(value) if isinstance(value, float) else str(value)
    return str(value)


def command_line(command, scene_name, options):
    """The arguments of `bladestab COMMAND --format json … -- SCENE` for `options`; InputError naming
    a key that is no option of the command."""
    known = command_options()[command]
    arguments = [command, "--format", "json"]
    for key, value in options.items():
        if "." in key:
            if "=" in key:
                raise InputError(f"{key}: a scene key has no '='; give its value as the keyword's value")
            arguments += ["--set", f"{key}={scene_value(value)}"]
            continue
        option = "--" + key.replace("_", "-")
        if option in RESERVED:
            raise InputError(f"{key}: not an option here: {RESERVED[option]}")
        if option not in known or option in ("--set", "--help"):
            names = sorted(o[2:].replace("-", "_") for o in known if o not in RESERVED and o not in ("--set", "--help"))
            raise InputError(f"{key}: not an option of {command}; its options: {', '.join(names)} "
                             "(and scene keys as section.key)")
        arguments += _option_arguments(key, option, known, value)
    # After "--" the scene is the scene whatever it starts with ("-blade.toml", "-h").
    return arguments + ["--", scene_name]


def _option_arguments(key, option, known, value):
    """The arguments for one plain option of the command whose options are `known` (command_options):
    a flag's True or False, an option's value (None: the command's default); InputError for a value
    of the other kind."""
    if not known[option]:
        if not isinstance(value, bool):
            raise InputError(f"{key} = {value!r}: a flag, True or False")
        if value:
            return [option]
        # A flag on by default is turned off by its negation ("--no-error-estimate").
        negation = "--no-" + option[2:]
        return [negation] if negation in known else []
    if value is None:
        return []
    if isinstance(value, bool):
        raise InputError(f"{key} = {value!r}: {option} takes a value, not True or False (None leaves its default)")
    return [option, option_value(value)]


def _plain(value, where="scene"):
    """A scene dict with NumPy scalars and arrays as the Python numbers and lists TOML writes, paths
    as strings; InputError for what TOML cannot hold (None, a key that is no string)."""
    if isinstance(value, dict):
        for key in value:
            if not isinstance(key, str):
                raise InputError(f"{where}: the key {key!r} is no string")
        return {key: _plain(item, f"{where}.{key}" if where != "scene" else key) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(item, where) for item in value]
    if value is None:
        raise InputError(f"{where} = None: a scene key takes a value; leave the key out for its default")
    if isinstance(value, os.PathLike):
        return os.fspath(value)
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
    if "\n" in scene:  # a scene's text has its tables on lines of their own
        return "<text>", scene
    if "\0" in scene:
        raise InputError(f"scene: {scene!r}: a path has no NUL character")
    return scene, ""
