"""Vibration of an elastic load driven by a motion law (book ch. 7).

- :mod:`sizer.vibration.elastic_load`: the 1-DOF model of sec. 7.1.1 (and the n-DOF chain
  of sec. 7.1.2), z = x - y driven by the input acceleration (eq. 7.2);
- :mod:`sizer.vibration.transform`: the Laplace/Fourier transform of a law's derivative,
  the one integration of this package (spectra and exact responses both use it);
- spectra (sec. 7.3), residual vibration and tracking error (sec. 7.2), input shapers
  (sec. 7.4.2) in their own modules.

Pure numpy; scipy only inside functions.
"""
