"""Errors with structured fields; the message is built in ``__str__``.

Exit codes of the command-line contract live on the classes, so the CLI has one
handler: ``InputError`` -> 2 (the case file is wrong), anything unexpected -> 70.
A scene that is valid but has no answer is not an exception: solvers return it as
a result with ``status = "no-answer"`` and the CLI exits 3.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

EXIT_OK = 0
EXIT_MISMATCH = 1
EXIT_INPUT = 2
EXIT_NO_ANSWER = 3
EXIT_BUG = 70
EXIT_INTERRUPTED = 130  # Ctrl-C (128 + SIGINT), as a shell reports it
#: How a case (a file of a batch, a point of a sweep) ended, in words (JSON, tables).
STATUS_OF_EXIT = {
    EXIT_OK: "ok",
    EXIT_NO_ANSWER: "no-answer",
    EXIT_INPUT: "input-error",
    EXIT_BUG: "internal-error",
}


class MdcalcError(Exception):
    """Base of every error mdcalc raises on purpose."""

    exit_code = EXIT_BUG


@dataclass
class Problem:
    """One thing wrong with an input: where it is and what is wrong."""

    message: str
    path: str = ""  # dotted field path, e.g. "load.mass"; "" for the file itself
    line: int | None = None
    column: int | None = None

    def format(self, file: str) -> str:
        place = file
        if self.line is not None:
            place += f":{self.line}"
            if self.column is not None:
                place += f":{self.column}"
        where = f"{self.path}: " if self.path else ""
        return f"{place}: error: {where}{self.message}"


class InputError(MdcalcError, ValueError):
    """The input is wrong: missing file, TOML syntax, validation. Exit code 2."""

    exit_code = EXIT_INPUT

    def __init__(self, file: str | Path, problems: list[Problem]) -> None:
        self.file = str(file)
        self.problems = problems
        super().__init__(str(self))

    def __str__(self) -> str:
        return "\n".join(p.format(self.file) for p in self.problems)


class NoAnswer(MdcalcError):
    """A valid scene without an answer, raised only where asked for
    (``mdcalc.solve(..., raise_on_no_answer=True)``); ``calculation`` says why."""

    exit_code = EXIT_NO_ANSWER

    def __init__(self, message: str, calculation: object = None) -> None:
        super().__init__(message)
        self.message = message
        self.calculation = calculation
