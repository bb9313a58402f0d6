#!/usr/bin/env python
"""Wrapper of dem.tools.plot_series (see its docstring), which is installed with dem as the command
`dem-plot` and also runs as `python -m dem.tools.plot_series`. It runs the installed dem."""
import sys

from dem.tools.plot_series import main

if __name__ == "__main__":
    sys.exit(main())
