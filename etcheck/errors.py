"""Typed errors the user can cause; the CLI prints them and exits 2 (or 3)."""

from __future__ import annotations


class EtcheckError(Exception):
    """Base class of the errors etcheck reports to the user without a traceback."""

    exit_code = 2


class MissionError(EtcheckError):
    """A mission file or mission value is unusable.

    ``source`` is the file (or "mission" for the Python API), ``field`` the
    dotted field name (e.g. ``tether.length``), ``problem`` what is wrong and
    ``fix`` what would make it right.
    """

    def __init__(self, source: str, field: str | None, problem: str, fix: str = "") -> None:
        self.source = source
        self.field = field
        self.problem = problem
        self.fix = fix
        where = f"{source}: [{field}]" if field else source
        text = f"{where}: {problem}"
        if fix:
            text += f" — {fix}"
        super().__init__(text)


class SolverError(EtcheckError):
    """A numerical solve did not converge; nothing is reported from it."""

    exit_code = 3


class ReportError(EtcheckError):
    """A report could not be written (e.g. PDF engine missing, disk full)."""

    exit_code = 2
