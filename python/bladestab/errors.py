"""The package's exceptions: the program's bad input and failed checks, as Python errors."""

from bladestab import _core

# Bad input (a scene key, an option, a limit of work): the program's one-line message, naming the
# key or option (exit status 2 on the command line).
InputError = _core.InputError
# A computation that failed its own checks (exit status 1 on the command line).
NumericalError = _core.NumericalError
# A run past its max_seconds (a TimeoutError), stopped at its next progress report.
TimeLimitReached = _core.TimeLimitReached
InputError.__module__ = NumericalError.__module__ = TimeLimitReached.__module__ = "bladestab"


class Note(UserWarning):
    """An answer that stands but is not the whole of what was asked ("bladestab: note: …")."""
