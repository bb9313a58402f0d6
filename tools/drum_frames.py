#!/usr/bin/env python
"""Wrapper of dem.tools.drum_frames (see its docstring), which is installed with dem as the command
`dem-frames` and also runs as `python -m dem.tools.drum_frames`. It runs the installed dem."""
import sys

from dem.tools.drum_frames import main

if __name__ == "__main__":
    sys.exit(main())
