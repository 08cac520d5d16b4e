"""A case as the command line reads it, from what Python hands over: a Path, TOML
text or a dict."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from mdcalc.errors import InputError, Problem

#: The file name of a case given as TOML text, and as a dict, in messages.
STRING, DICT = "<string>", "<dict>"


def case_of(case: Path | str | Mapping[str, Any], problem: str | None) -> Any:
    """The case as the command line reads it (:class:`~mdcalc.input.casefile.CaseText`)."""
    from mdcalc.input.casefile import case_from_text, read_case, with_base

    if isinstance(case, Path):
        return read_case(case)
    if isinstance(case, str):
        if "\n" not in case and "=" not in case and case.strip().endswith(".toml"):
            why = f"{case!r} is a file name, and a str is TOML text: give Path({case!r})"
            raise InputError(STRING, [Problem(why)])
        read = case_from_text(Path(STRING), case)
    elif isinstance(case, Mapping):
        import tomli_w

        data = plain(case)
        try:
            text = tomli_w.dumps(data)
        except (TypeError, ValueError) as exc:
            raise InputError(DICT, [Problem(f"not a case TOML can hold: {exc}")]) from None
        read = case_from_text(Path(DICT), text)
    else:
        raise TypeError(f"a case is a Path, TOML text or a dict, not {type(case).__name__}")
    if problem is not None and "problem" not in read.data:
        read.data = {"problem": problem, **read.data}
    return with_base(read)


def plain(value: Any) -> Any:
    """A mapping of the caller's (numpy numbers, tuples) as TOML's plain types."""
    if isinstance(value, Mapping):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [plain(v) for v in value]
    if hasattr(value, "item") and callable(value.item):  # a numpy scalar
        return value.item()
    return value


def lineless(problem: Problem) -> Problem:
    return Problem(problem.message, problem.path)
