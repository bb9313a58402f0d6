#!/usr/bin/env python
"""Wrapper of dem.tools.convert_restart (see its docstring), which is installed with dem as the command
`dem-convert-restart` and also runs as `python -m dem.tools.convert_restart`. It runs the installed dem."""
import sys

from dem.tools.convert_restart import main

if __name__ == "__main__":
    sys.exit(main())
