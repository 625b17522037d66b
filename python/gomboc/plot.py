"""The plotters as functions: the scripts in reports/ (installed in PREFIX/share/gomboc/reports) run in-process with
the arguments their command lines take, so that a figure from Python is the command line's figure.

    import gomboc.plot
    gomboc.plot.scan("out/fig10-scan.csv", ["lambda_max", "omega_rms"])        # reports/plot_scan.py
    gomboc.plot.run("out", ["table1-gomboc-I"])                                 # reports/run_report.py
    gomboc.plot.animate("out", "table1-gomboc-I", seconds=4, fps=15)            # reports/animate.py

Each returns what its script wrote (the figure's path, the page's, the animation's), and raises GombocError (status 2)
where the script would exit 2 or 1, with the script's message. The scripts are found at $GOMBOC_REPORTS, beside the
package in the source tree (reports/), or installed (PREFIX/share/gomboc/reports)."""
import contextlib
import importlib
import io
import os
import sys

from . import GombocError

__all__ = ["scan", "run", "animate"]


def _reports():
    here = os.path.dirname(os.path.abspath(__file__))
    for path in (os.environ.get("GOMBOC_REPORTS"), os.path.join(here, "..", "..", "reports"),
                 os.path.join(here, "..", "..", "..", "..", "share", "gomboc", "reports")):
        if path and os.path.exists(os.path.join(path, "plot_scan.py")):
            return os.path.normpath(path)
    raise GombocError(2, "the plotters (plot_scan.py, run_report.py, animate.py) are neither in $GOMBOC_REPORTS, nor in "
                         "the source tree's reports/, nor installed in PREFIX/share/gomboc/reports")


def _call(module_name, argv):
    """module.main(argv) with the script's standard output captured; its exits and input errors as GombocError."""
    folder = _reports()
    if folder not in sys.path:
        sys.path.insert(0, folder)
    module = importlib.import_module(module_name)
    common = importlib.import_module("common")
    said, errors = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(said), contextlib.redirect_stderr(errors):
            status = module.main(argv)
    except common.InputError as e:
        raise GombocError(2, f"{module_name}.py: {e}") from None
    except SystemExit as e:
        if e.code not in (0, None):
            message = e.code if isinstance(e.code, str) else errors.getvalue().strip() or f"exit {e.code}"
            raise GombocError(2, f"{module_name}.py: {message}") from None
        status = 0
    if status not in (0, None):
        raise GombocError(2, f"{module_name}.py: {errors.getvalue().strip() or f'exit {status}'}")
    return said.getvalue().strip()


def scan(csv_path, metrics=(), out=None):
    """One panel a metric over the scan's two axes (reports/plot_scan.py); the figure's path."""
    argv = [os.fspath(csv_path)] + list(metrics) + (["--out", os.fspath(out)] if out else [])
    return _call("plot_scan", argv)


def run(out, names, page=None):
    """The run page and figures of the scenes `names` run into the folder `out` (reports/run_report.py); the page's
    path."""
    names = [names] if isinstance(names, str) else list(names)
    _call("run_report", [os.fspath(out)] + names + (["--page", page] if page else []))
    return os.path.join(os.fspath(out), page or (f"{names[0]}-run.md" if len(names) == 1 else "runs.md"))


def animate(out, name, seconds=4, fps=25, surface=None):
    """The body in motion from its run in `out` (reports/animate.py); what the script printed (the file written)."""
    argv = [os.fspath(out), name, "--seconds", str(seconds), "--fps", str(fps)]
    if surface:
        argv += ["--surface", os.fspath(surface)]
    return _call("animate", argv)
