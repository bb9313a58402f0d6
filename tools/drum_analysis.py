#!/usr/bin/env python
"""Wrapper of dem.tools.drum_analysis (see its docstring), which is installed with dem as the command
`dem-drum-analysis` and also runs as `python -m dem.tools.drum_analysis`. It runs the installed dem."""
import sys

from dem.tools.drum_analysis import main

if __name__ == "__main__":
    sys.exit(main())
