"""The program's hostile input replayed through the API (scripts/fuzz.py's mutation class: one
scene key, option or the scene file's bytes mutated; a fixed seed): every call returns a Result
with a finite JSON answer, or raises InputError naming the mutated key or option in one line, or
NumericalError or TimeLimitReached — never another exception, and never a crash of the
interpreter (which would end this test)."""

import math
import os
import random
import sys

import bladestab
from conftest import SCENE, SOURCE_DIR

sys.path.insert(0, os.path.join(SOURCE_DIR, "scripts"))
import fuzz  # noqa: E402

CASES = 200


def as_call(args):
    """`bladestab COMMAND SCENE --opt value --set k=v …` as (command, scene, keyword arguments)."""
    command, scene, rest = args[0], args[1], args[2:]
    options = {}
    for option, value in zip(rest[0::2], rest[1::2]):
        if option == "--set":
            key, _, text = value.partition("=")
            options[key] = text
        else:
            options[option[2:].replace("-", "_")] = value
    return command, scene, options


def finite(value):
    if isinstance(value, dict):
        return all(finite(v) for v in value.values())
    if isinstance(value, list):
        return all(finite(v) for v in value)
    return not isinstance(value, float) or math.isfinite(value)


def test_hostile_corpus_through_the_api(tmp_path):
    rng = random.Random(1)
    ctx = fuzz.Context(str(tmp_path), SCENE)
    outcomes = {"answered": 0, "refused": 0, "failed": 0}
    for k in range(CASES):
        case = fuzz.mutation_case(rng, ctx, k)
        command, scene, options = as_call(case.args)
        options.setdefault("model.terms", "4")  # small models throughout (the campaigns' 80 %): seconds in all
        try:
            result = bladestab.run(command, scene, **options)
        except bladestab.InputError as error:
            message = str(error)
            assert "\n" not in message and message, case.args
            if case.named:  # as the campaigns judge the program's line
                assert fuzz.names_cause(message, case.named), (case.args, message)
            outcomes["refused"] += 1
        except (bladestab.NumericalError, bladestab.TimeLimitReached) as error:
            assert "\n" not in str(error), case.args
            outcomes["failed"] += 1
        else:
            assert finite(result.to_dict()), case.args
            outcomes["answered"] += 1
    assert outcomes["refused"] > CASES / 2 and outcomes["answered"] > 0, outcomes
