"""Reports rendered by a second process that loads the report stack while the caller computes.

matplotlib, jinja2 and WeasyPrint take about a second to import, and a check
or a study needs none of them. :func:`renderer` starts a process for that before the
caller's own imports and computation, and returns a function with the signature
of :func:`etcheck.report.render` that hands the results to it: on two or more
cores the report stack costs no wall time. The process is a fork of a small
one (the CLI before numpy is loaded, with one thread), on Linux only; anywhere
else, for data-only formats, or on one core, the reports are rendered in this
process, with the same bytes.

Beside a study (a sweep, a diagram, a damping map: seconds of work on every
core) the report process runs at the lowest priority (nice 19): loading the
report stack (~1.7 CPU-seconds) then takes only what the study leaves idle
(its serial start, the gaps between its parallel steps) instead of slowing
it, and the report is drawn after the study, when nothing else runs. A
check (a second of work, its report the longer part) keeps the normal
priority: its report would wait for the check's cores.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
from collections.abc import Callable, Iterator

from etcheck.errors import EtcheckError, ReportError
from etcheck.report import render
from etcheck.report.figures.common import forking_allowed
from etcheck.runtime.lifetime import die_with_parent

#: the formats a report process is started for (JSON and data files need no report stack)
DRAWN = ("html", "pdf")
#: niceness added to a study's report process (module docstring); a check's keeps its parent's
STUDY_NICE = 19


@contextlib.contextmanager
def renderer(formats: tuple[str, ...], kind: str = "check"
             ) -> Iterator[Callable[[dict | str, tuple[str, ...], str], dict[str, bytes]]]:
    """A ``render(results, formats, kind)`` that runs in a report process started now (when it can help);
    ``kind``: the report it will mostly render (its template is compiled while waiting).

    Use as ``with renderer(fmts) as render: ... write_reports(..., renderer=render)``; leaving the block
    ends the process whether or not it was used.
    """
    if not worth_a_process(formats):
        yield render
        return
    import multiprocessing

    sys.stdout.flush()  # nothing buffered may be written twice
    sys.stderr.flush()
    ctx = multiprocessing.get_context("fork")
    ours, theirs = ctx.Pipe()
    proc = ctx.Process(target=_serve, args=(os.getpid(), theirs, ours, formats, kind), daemon=True,
                       name="etcheck-report")
    proc.start()
    theirs.close()

    def remote(results: dict | str, fmts: tuple[str, ...], kind: str = "check") -> dict[str, bytes]:
        try:
            ours.send((results, fmts, kind))
            status, value = ours.recv()
        except (EOFError, OSError):
            raise ReportError("the report process ended unexpectedly; run again with --format json "
                              "to get the results without the report") from None
        if status == "ok":
            return value
        if status == "report":
            raise ReportError(value)
        raise RuntimeError(value)

    remote.pid = proc.pid  # type: ignore[attr-defined]  # the report process, for the tests
    try:
        yield remote
    except BaseException:  # the report is not needed (a stop signal stops the process already)
        proc.kill()
        raise
    finally:
        ours.close()  # the process reads end-of-file and exits
        proc.join(timeout=5)
        if proc.is_alive():
            proc.kill()
            proc.join()


def worth_a_process(formats: tuple[str, ...]) -> bool:
    """A fork is cheap and safe here: Linux, two or more cores, one thread, numpy not loaded yet."""
    return (any(f in DRAWN for f in formats) and sys.platform.startswith("linux")
            and len(os.sched_getaffinity(0)) >= 2 and threading.active_count() == 1 and "numpy" not in sys.modules)


def _serve(parent: int, conn, parent_end, formats: tuple[str, ...], kind: str) -> None:
    """The report process of ``parent``: load and warm the report stack, then render what the parent sends until it
    closes; it ends with its parent (:func:`~etcheck.runtime.lifetime.die_with_parent`)."""
    die_with_parent(parent)
    parent_end.close()
    if kind != "check":
        os.nice(STUDY_NICE)
    try:
        _warm(formats, kind)
        while True:
            try:
                results, fmts, kind = conn.recv()
            except EOFError:
                return
            try:
                with forking_allowed():  # this process has one thread: the figures may be drawn two at a time
                    rendered = render(results, fmts, kind)
                conn.send(("ok", rendered))
            except EtcheckError as exc:
                conn.send(("report", str(exc)))
            except Exception as exc:  # a bug: the parent reports it as an internal error
                conn.send(("bug", f"{type(exc).__name__}: {exc}"))
    except KeyboardInterrupt:  # Ctrl-C reaches the whole process group; the parent says so
        return


def _warm(formats: tuple[str, ...], kind: str) -> None:
    """Import the report stack (jinja2, matplotlib with the report style and, for a PDF, WeasyPrint) and compile
    the template."""
    from etcheck.report import html
    from etcheck.report.figures.common import pyplot

    html.environment().get_template(html.TEMPLATES[kind])
    plt = pyplot()
    if kind != "check":  # a study runs for seconds: its first figure's font and mathtext set-up is done now
        from etcheck.report.figures.common import image

        fig, ax = plt.subplots(figsize=(2.0, 1.5))
        ax.plot([0.0, 1.0], [0.0, 1.0], label="a")
        ax.set_xlabel(r"measure$_1 = \int_0^1 |x^0|\,ds$ [m]")
        ax.set_title("γ", fontsize=8)
        ax.legend(fontsize=7)
        image(fig)
    if "pdf" in formats:
        with contextlib.suppress(ImportError, OSError):  # a missing PDF engine is reported when a PDF is rendered
            import weasyprint  # noqa: F401
