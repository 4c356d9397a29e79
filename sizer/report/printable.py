"""Text from files made safe to print on a terminal: control characters escaped.

Names and ids come from the user's files (motor ids, design names, law specs, file
names). Printed as they are, an ESC could recolour or clear the terminal, a CR or a
backspace overwrite what came before, a bidi override (U+202E) reverse what follows.
:func:`printable` escapes them the way Python writes them (``\\x1b``, ``\\r``, ``\\u202e``);
every human-readable output (error and warning lines, terminal, plain and Markdown
tables) goes through it. JSON and CSV keep the exact text (JSON escapes control
characters itself; CSV quotes them).

Escaped: the C0 controls (U+0000-U+001F) but the kept ones (a newline in multi-line
text), DEL and the C1 controls (U+007F-U+009F), and the Unicode format characters that
steer the direction or visibility of text (U+061C, U+200B-U+200F, U+202A-U+202E,
U+2060-U+2069, U+FEFF). The result holds none of them, so escaping twice changes nothing.
"""

from __future__ import annotations

import re

_NAMED = {"\t": "\\t", "\n": "\\n", "\r": "\\r"}

_UNSAFE = re.compile("[\x00-\x1f\x7f-\x9f\u061c\u200b-\u200f\u202a-\u202e\u2060-\u2069\ufeff]")
_UNSAFE_BUT_NEWLINE = re.compile(
    "[\x00-\x09\x0b-\x1f\x7f-\x9f\u061c\u200b-\u200f\u202a-\u202e\u2060-\u2069\ufeff]")


def _escape(match: re.Match[str]) -> str:
    char = match.group()
    if char in _NAMED:
        return _NAMED[char]
    code = ord(char)
    return f"\\x{code:02x}" if code <= 0xFF else f"\\u{code:04x}"


def printable(text: str, *, keep_newlines: bool = False) -> str:
    """``text`` with terminal control characters escaped (``\\x1b``, ``\\u202e``...).

    With ``keep_newlines`` a newline stays a line break (multi-line reports); otherwise
    it is escaped too (one line: an error message, a table cell).
    """
    pattern = _UNSAFE_BUT_NEWLINE if keep_newlines else _UNSAFE
    return pattern.sub(_escape, text)
