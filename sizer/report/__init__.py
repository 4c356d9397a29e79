"""Formatting of results: tables, CSV, Markdown, JSON, files. No physics here.

Each document type (the law coefficients, a sampled motion...) turns plain results from
the core into text; ``publish`` picks the format and the destination.
"""
