"""What tools/plot_energy.py and tools/plot_sweep.py share: importing matplotlib without a
display (or exiting with a message that says what to install), the colour of each line, and
writing the PNG whole or not at all.

The scripts run as `/usr/bin/python3 tools/plot_X.py ...` from anywhere, so they import this
module from their own directory (see the top of each), not from an installed package.
"""

import os
import sys
import tempfile

MISSING_MATPLOTLIB = 3  # sweep_command.cpp relies on this exit code (plot_sweep.py --check)


def import_pyplot(script, quiet=False):
    """matplotlib.pyplot on the Agg backend (no display needed). When matplotlib is missing,
    exits with MISSING_MATPLOTLIB after saying so as `script`, unless `quiet`."""
    try:
        import matplotlib
    except ImportError:
        if not quiet:
            sys.stderr.write(f"{script}: matplotlib is missing: apt-get install python3-matplotlib\n")
        sys.exit(MISSING_MATPLOTLIB)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def line_colour(plt, index, count):
    """The colour of line `index` of `count`: viridis, stopping short of its pale yellow end."""
    return plt.get_cmap("viridis")(0.85 * index / max(1, count - 1))


def save_png(fig, png, prefix):
    """Writes `fig` to `png` whole or not at all: drawn to a temporary file beside the target
    (named `prefix`...), then renamed into place."""
    directory = os.path.dirname(os.path.abspath(png))
    handle, temporary = tempfile.mkstemp(prefix=prefix, suffix=".png", dir=directory)
    try:
        with os.fdopen(handle, "wb") as f:
            fig.savefig(f, format="png", dpi=110)
        # mkstemp makes the file private; give it the permissions a plain open() would.
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)
        os.replace(temporary, png)
    except BaseException:
        os.unlink(temporary)
        raise
