"""``python -m sizer``: the same as the ``sizer`` command."""

from sizer.cli.process import main

if __name__ == "__main__":
    main()
