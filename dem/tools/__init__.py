"""Post-processing tools installed with dem, each a module with a `main(argv)` and a console script:

    dem-plot             dem.tools.plot_series      time series of `fix print/series` to a PNG
    dem-frames           dem.tools.drum_frames      PNG frames of a drum from an HDF5 dump
    dem-drum-analysis    dem.tools.drum_analysis    drum plots over rotation rates (Part III sec 4.2.3)
    dem-convert-restart  dem.tools.convert_restart  old pickle restarts to the current format
    dem-hooke-from-hertz dem.tools.hooke_from_hertz the Hooke kn and time step equivalent to Hertz

`python -m dem.tools.NAME ...` runs the same; the source tree's `tools/NAME.py` are wrappers of these.
"""
