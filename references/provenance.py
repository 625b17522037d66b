"""What every reference script records about where its numbers came from, and how it writes them."""
import json
import platform
import sys

import numpy
import scipy


def versions(**more):
    """Python, numpy and scipy versions, plus any other library passed as name=module."""
    found = {"python": platform.python_version(), "numpy": numpy.__version__, "scipy": scipy.__version__}
    found.update({name: module.__version__ for name, module in more.items()})
    return found


def emit(document, indent=1):
    """The reference document, as JSON on standard output (make references redirects it atomically)."""
    json.dump(document, sys.stdout, indent=indent)
    sys.stdout.write("\n")
