"""Export a sized motion as a controller's cam, with a certificate (issue 37).

Pure numpy (scipy lazily for the root finder): no printing, no files. The CLI
(sizer.cli.cam_command) writes the text the writers return.

- :mod:`sizer.export.profile`: the move to export, in the file's units (a law scaled to
  its stroke over a master span of time or of master angle).
- :mod:`sizer.export.linear_certificate`: the true largest position and velocity errors
  of a linearly interpolated point table against the law.
- :mod:`sizer.export.sampling`: equidistant point tables and the number of points an
  error budget needs, clipped to a target's limit.
- :mod:`sizer.export.targets` and one writer module per target (csv_table, codesys_xy,
  sew_table).
"""
