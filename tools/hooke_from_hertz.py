#!/usr/bin/env python
"""Wrapper of dem.tools.hooke_from_hertz (see its docstring), which is installed with dem as the command
`dem-hooke-from-hertz` and also runs as `python -m dem.tools.hooke_from_hertz`. It runs the installed dem."""
import sys

from dem.tools.hooke_from_hertz import main

if __name__ == "__main__":
    sys.exit(main())
