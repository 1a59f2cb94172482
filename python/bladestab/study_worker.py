"""What a study's workers run: one task's points through one analysis, each answer reduced to
its scalar fields (nested objects' fields as "object.field"; strings and lists left out) and
`passed`, False where the answer is negative (results.Result.passed)."""

from bladestab import _core
from bladestab.arguments import command_line
from bladestab.errors import InputError, NumericalError
from bladestab.results import json


def scalar_fields(document, prefix=""):
    fields = {}
    for key, value in document.items():
        if isinstance(value, dict):
            fields.update(scalar_fields(value, f"{prefix}{key}."))
        elif isinstance(value, (bool, int, float)) or value is None:
            fields[prefix + key] = value
    return fields


def run_task(command, scene_name, scene_text, options, points):
    """[fields of each point's answer, or ("input" | "numerical", the one-line reason it failed)]:
    a point refused as bad input or failing its checks fails alone."""
    answers = []
    for point in points:
        try:
            answer = _core.run(command_line(command, scene_name, {**options, **point}), scene_text, None)
            fields = scalar_fields(json.loads(answer["json"]))
            # A negative answer (a check not met, a crosscheck that disagrees) is `passed` False.
            fields.setdefault("passed", not answer["negative"])
            answers.append(fields)
        except InputError as error:
            answers.append(("input", str(error)))
        except NumericalError as error:
            answers.append(("numerical", str(error)))
    return answers
