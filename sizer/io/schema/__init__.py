"""The schema of the input files (pydantic): shapes, units to SI, each quantity's range.

It checks what a file says field by field; :mod:`sizer.io` turns the validated models into
the SI domain objects of :mod:`sizer.model`, which knows nothing of the schema.
"""
