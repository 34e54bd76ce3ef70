"""Reading plain coordinate lines many at a time, with NumPy instead of a loop.

A CAM finishing program is millions of lines like ``X12.345 Y-6.7 Z0.25`` or
``N1234 G1 X1.5 Y2 F800``. ``scan_plain`` finds, among the lines of a block of the file,
those made only of such words and reads their numbers, all at once: no Python object per
line. A line is *plain* when, with upper and lower case alike,

- it holds only letters of ``letters`` (the machine's linear axes, F, G, N), digits, '.', '+',
  '-' and spaces;
- every letter is followed directly by its number (``X 1`` is left to the interpreter, which
  reads spaces inside a number as LinuxCNC does) and no letter comes twice;
- every number is a sign, at most 9 digits before the point and 15 digits in all (so that it
  converts exactly, see below), and at least one digit;
- an N word comes first and is a whole number; a G word is G0 or G1 written without a point.

Any other line (a comment, an O-word, a parameter, an M code, an arc, a tab, a number with an
exponent...) is not plain, and the interpreter reads it as it reads every line; so does it
for a plain line whose meaning depends on a state this module does not know (that is the
interpreter's ``bulk_lines``).

Numbers convert to exactly the float Python's ``float()`` gives: the digits make an integer
M below 2**53 (exact in a double, and so are the partial sums), the digits after the point
make e <= 15, and M / 10**e is one correctly rounded division of two exact doubles, which is
the correctly rounded value of the decimal, as ``float()`` returns.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PlainBlock", "scan_plain"]

MAX_DIGITS = 15  # 10**15 < 2**53: the integer of the digits is exact
MAX_INT_DIGITS = 9  # below 1e9, the interpreter's limit of a word's value

_DIGIT_LO, _DIGIT_HI = ord("0"), ord("9")
_NL, _SPACE, _DOT, _MINUS, _PLUS = 10, 32, ord("."), ord("-"), ord("+")
_POW10 = 10.0 ** np.arange(MAX_DIGITS + 1)


@dataclass(frozen=True, slots=True)
class PlainBlock:
    """The lines of a block: which are plain, and their words' values."""

    plain: np.ndarray  # (n_lines,) bool
    values: np.ndarray  # (n_lines, len(letters)) float, NaN where the line has no such word
    words: np.ndarray  # (n_lines,) int: how many words the line has


PIECE_BYTES = 1 << 22  # one NumPy pass over 4 MB holds the GIL a few milliseconds


def newline_offsets(data: np.ndarray) -> np.ndarray:
    """Offsets of the newline bytes of ``data``, found a piece at a time: one pass over a
    250 MB program held the GIL, and with it the panel's GUI thread, for a third of a second."""
    parts = [np.flatnonzero(data[lo: lo + PIECE_BYTES] == 10) + lo for lo in range(0, len(data), PIECE_BYTES)]
    return np.concatenate(parts) if parts else np.zeros(0, dtype=np.intp)


#: the longest line the bulk reader scans: a plain CAM line is a few words (80 bytes in the
#: longest of the shared CAM programs); a longer one goes to the line reader unscanned
MAX_PLAIN_BYTES = 1024


def _without_lines(arr: np.ndarray, starts: np.ndarray, ends: np.ndarray, drop: np.ndarray) -> np.ndarray:
    """``arr`` with the content of the lines ``drop`` taken out (their newlines kept): the same
    lines, those empty."""
    mark = np.zeros(arr.shape[0] + 1, np.int32)
    np.add.at(mark, starts[drop], 1)
    np.add.at(mark, ends[drop], -1)
    return arr[np.cumsum(mark[:-1]) == 0]


def scan_plain(data: np.ndarray, starts: np.ndarray, ends: np.ndarray, letters: str) -> PlainBlock:
    """Classify and read the lines ``data[starts[k]:ends[k]]`` (uint8; lines separated by one
    newline byte each, ``starts[0] == 0``; ``letters`` upper case, among them ``"N"`` and ``"G"``)."""
    n_lines = int(starts.shape[0])
    n_letters = len(letters)
    values = np.full((n_lines, n_letters), np.nan)
    if n_lines == 0:
        return PlainBlock(np.zeros(0, bool), values, np.zeros(0, np.int64))
    arr = data[: int(ends[-1])]
    bad_line = np.zeros(n_lines + 1, bool)  # one spare slot: bytes past the last line
    long = (ends - starts) > MAX_PLAIN_BYTES
    if long.any():
        # no plain line is that long (a comment, a word list): its bytes are left out of the
        # arrays below, each of which costs bytes for every byte scanned, the line kept as an
        # empty one and refused
        arr = _without_lines(arr, starts, ends, long)
        bad_line[:n_lines] = long
    size = arr.shape[0]
    if size == 0:
        return PlainBlock(~bad_line[:n_lines], values, np.zeros(n_lines, np.int64))
    is_nl = arr == _NL
    line_of = np.cumsum(is_nl, dtype=np.int32)  # line of each byte (a newline belongs to the next line)
    lut = np.full(256, -1, np.int8)
    for code, letter in enumerate(letters):
        lut[ord(letter)] = code
        lut[ord(letter.lower())] = code
    code_of = lut[arr]
    is_letter = code_of >= 0
    is_digit = (arr >= _DIGIT_LO) & (arr <= _DIGIT_HI)
    is_dot = arr == _DOT
    is_sign = (arr == _MINUS) | (arr == _PLUS)
    is_num = is_digit | is_dot | is_sign
    ok_byte = is_num | is_letter | is_nl | (arr == _SPACE)
    prev_num_ok = np.empty(size, bool)  # the byte before a number char is a letter or a number char
    prev_num_ok[0] = False
    prev_num_ok[1:] = is_letter[:-1] | is_num[:-1]
    next_is_num = np.zeros(size, bool)
    next_is_num[:-1] = is_num[1:]
    wrong = ~ok_byte | (is_num & ~prev_num_ok) | (is_letter & ~next_is_num)
    bad_line[line_of[wrong]] = True
    # the words of good lines alone: a bad line is read by the line reader, and its letters
    # (every x of a comment) would each cost a token's arrays
    in_good = ~bad_line[line_of]
    is_letter &= in_good

    pos = np.flatnonzero(is_letter)
    n_tok = pos.shape[0]
    tok_line = line_of[pos]
    tok_code = code_of[pos].astype(np.int64)
    # the token a number byte belongs to: the last letter before it, which is on its own line
    # when that line is good (a number byte follows a letter or a number byte); the bytes of
    # bad lines are left out
    tok_of = np.cumsum(is_letter, dtype=np.int32) - 1
    is_digit &= in_good
    is_dot &= in_good
    is_sign &= in_good
    digits = np.flatnonzero(is_digit)
    d_tok = tok_of[digits]
    n_digit = np.bincount(d_tok, minlength=n_tok)
    dots = np.flatnonzero(is_dot)
    n_dot = np.bincount(tok_of[dots], minlength=n_tok)
    signs = np.flatnonzero(is_sign)
    s_tok = tok_of[signs]
    n_sign = np.bincount(s_tok, minlength=n_tok)
    sign_misplaced = np.zeros(n_tok, bool)
    sign_misplaced[s_tok[signs != pos[s_tok] + 1]] = True
    dot_pos = np.full(n_tok, np.iinfo(np.int64).max)
    dot_pos[tok_of[dots]] = dots
    after_dot = digits > dot_pos[d_tok]
    n_frac = np.bincount(d_tok, weights=after_dot, minlength=n_tok).astype(np.int64)
    tok_bad = ((n_digit == 0) | (n_digit > MAX_DIGITS) | (n_digit - n_frac > MAX_INT_DIGITS)
               | (n_dot > 1) | (n_sign > 1) | sign_misplaced)
    # digit j of a token (0 = first) weighs 10**(n_digit - 1 - j)
    counted = np.cumsum(is_digit, dtype=np.int32)
    digit_ordinal = counted[digits] - 1
    first_ordinal = counted[pos]  # digits before the token's letter
    place = n_digit[d_tok] - 1 - (digit_ordinal - first_ordinal[d_tok])
    place = np.clip(place, 0, MAX_DIGITS)
    weights = (arr[digits] - _DIGIT_LO) * _POW10[place]
    mantissa = np.bincount(d_tok, weights=weights, minlength=n_tok)
    value = mantissa / _POW10[np.clip(n_frac, 0, MAX_DIGITS)]
    negative = np.zeros(n_tok, bool)
    negative[s_tok[arr[signs] == _MINUS]] = True
    value = np.where(negative, -value, value)

    # N first and whole; G0 or G1 without a point or sign; no letter twice on a line
    n_code, g_code = letters.index("N"), letters.index("G")
    first_of_line = np.ones(n_tok, bool)
    first_of_line[1:] = tok_line[1:] != tok_line[:-1]
    is_n = tok_code == n_code
    is_g = tok_code == g_code
    tok_bad |= is_n & (~first_of_line | (n_dot > 0) | (n_sign > 0))
    tok_bad |= is_g & ((n_dot > 0) | (n_sign > 0) | (value > 1.0))
    key = tok_line * n_letters + tok_code
    order = np.argsort(key, kind="stable")
    sk = key[order]
    dup = np.flatnonzero(sk[1:] == sk[:-1])
    bad_line[tok_line[order[dup]]] = True
    bad_line[tok_line[tok_bad]] = True

    plain = ~bad_line[:n_lines]
    good = plain[tok_line]
    values[tok_line[good], tok_code[good]] = value[good]
    words = np.bincount(tok_line, minlength=n_lines)[:n_lines]
    return PlainBlock(plain, values, words)
