"""An analysis's answer: the command's JSON document, its lists as NumPy arrays."""

import copy
import json

import numpy as np


def as_arrays(value):
    """JSON values with their lists of numbers as NumPy arrays (null as NaN), lists of {re, im} as
    complex arrays and rectangular lists of lists as 2-D arrays; other values as they are."""
    if isinstance(value, dict):
        return {k: as_arrays(v) for k, v in value.items()}
    if not isinstance(value, list) or not value:
        return value
    if all(isinstance(v, bool) for v in value):
        return np.array(value, dtype=bool)
    if all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)) for v in value):
        if all(isinstance(v, int) and not isinstance(v, bool) for v in value):
            return np.array(value, dtype=np.int64)
        return np.array([np.nan if v is None else v for v in value], dtype=float)
    if all(isinstance(v, dict) and v.keys() == {"re", "im"} for v in value):
        return np.array([complex(v["re"], v["im"]) for v in value])
    items = [as_arrays(v) for v in value]
    if all(isinstance(v, np.ndarray) and v.ndim == 1 and v.shape == items[0].shape for v in items):
        return np.stack(items)
    return items


class Result:
    """One command's answer. `to_dict()` is its JSON document as the program prints it with
    `--format json`; its fields are also attributes and items, lists as NumPy arrays. `document`
    is the fuller JSON file the command wrote beside it where it writes one (a transient's
    history, a map's grid: what its chart is drawn from); `notes` the notes beside the answer;
    `passed` False where the answer is negative (`check`: a requirement not met)."""

    def __init__(self, command, answer):
        self.command = command
        self._answer = json.loads(answer["json"])
        self.document = None
        for path in answer["files"]:
            if path.endswith(".json"):
                with open(path, encoding="utf-8") as fh:
                    self.document = json.load(fh)
        self.files = list(answer["files"])
        self.notes = list(answer["notes"])
        self.passed = not answer["negative"]
        self.failure = answer["negative_reason"] or None

    def to_dict(self):
        return copy.deepcopy(self._answer)

    def keys(self):
        return self._answer.keys()

    def __getitem__(self, key):
        if key in self._answer:
            return as_arrays(self._answer[key])
        if self.document is not None and key in self.document:
            return as_arrays(self.document[key])
        raise KeyError(key)

    def __contains__(self, key):
        return key in self._answer or (self.document is not None and key in self.document)

    def __iter__(self):
        return iter(self._answer)

    def __len__(self):
        return len(self._answer)

    def get(self, key, default=None):
        return self[key] if key in self else default

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return self[name]
        except KeyError:
            raise AttributeError(f"{self.command} result has no field {name!r}; fields: {', '.join(self.keys())}") \
                from None

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self._answer))

    def __repr__(self):
        """The answer's plain fields, each whole, as many as fit in about 300 characters."""
        fields, length = [], 0
        for key, value in self._answer.items():
            if isinstance(value, (list, dict)):
                continue
            field = f"{key}={value!r}"
            if length + len(field) > 300:
                fields.append("…")
                break
            fields.append(field)
            length += len(field) + 2
        return f"<bladestab {self.command} result: {', '.join(fields)}>"

    def plot(self, path=None):
        """The program's chart of this answer (campbell, map, sweep, transient), drawn by its chart
        modules: saved to `path` (.png or .svg) as the program saves it, else returned as a
        matplotlib Figure."""
        from bladestab import plotting

        return plotting.plot(self.command, self.document or self._answer, path)
