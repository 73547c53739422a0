#!/usr/bin/env python3
"""Finds code written twice in src/ and include/: runs of six or more lines that are the same,
or of the same shape once names, numbers and strings are set aside, in two places.

Blank lines, comments, lone braces and #include lines are not counted: they say nothing of what
the code does. A pair of files named on the allow-list (tools/duplicates_allow.txt, one
`file file  # why` a line) is reported but does not fail. With --check the exit status is 1 when
a pair off the list is found, so that ctest fails on new duplicates. Python 3, stdlib only.
"""

import argparse
import re
import sys
from pathlib import Path

MIN_LINES = 6
# A window needs this many different line shapes to count.
MIN_DISTINCT = 5
ROOTS = ("src", "include")
SUFFIXES = {".cpp", ".hpp", ".h", ".proto"}

KEYWORDS = set("""
    alignas alignof auto bool break case catch char class const consteval constexpr constinit
    continue co_await co_return co_yield decltype default delete do double else enum explicit
    export extern false float for friend goto if inline int long mutable namespace new noexcept
    nullptr operator override private protected public return short signed sizeof static
    static_assert static_cast dynamic_cast reinterpret_cast const_cast struct switch template
    this throw true try typedef typename union unsigned using virtual void volatile while final
    optional repeated required message
""".split())

TOKEN = re.compile(
    r'"(?:\\.|[^"\\])*"'          # string literal
    r"|'(?:\\.|[^'\\])*'"         # character literal
    r"|[A-Za-z_][A-Za-z0-9_]*"    # identifier or keyword
    r"|\d[\w.']*"                 # number
    r"|\S"                        # punctuation, one character at a time
)
SKIPPED = re.compile(r"^(#\s*include\b|#\s*pragma once|[{}();,]*$)")


def shape(line):
    """The line with its names, numbers and literals replaced, keywords and punctuation kept."""
    out = []
    for token in TOKEN.findall(line):
        if token[0] in "\"'":
            out.append("S")
        elif token[0].isdigit():
            out.append("N")
        elif token[0].isalpha() or token[0] == "_":
            out.append(token if token in KEYWORDS else "I")
        else:
            out.append(token)
    return " ".join(out)


def code_lines(text):
    """(line number, shape) of each line that counts, comments removed."""
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    lines = []
    for number, line in enumerate(text.splitlines(), 1):
        line = re.sub(r"//.*$", "", line).strip()
        if line and not SKIPPED.match(line):
            lines.append((number, shape(line)))
    return lines


def find_runs(files):
    """Pairs of places (file, first line, last line) whose MIN_LINES-line windows match."""
    windows = {}
    for path, lines in files.items():
        for i in range(len(lines) - MIN_LINES + 1):
            key = tuple(s for _, s in lines[i:i + MIN_LINES])
            if len(set(key)) < MIN_DISTINCT:
                continue  # a table of like lines (cases, fields) is not written twice
            windows.setdefault(key, []).append((path, i))
    matches = {}
    for places in windows.values():
        for a in range(len(places)):
            for b in range(a + 1, len(places)):
                (pa, ia), (pb, ib) = places[a], places[b]
                if pa == pb and abs(ia - ib) < MIN_LINES:
                    continue
                matches.setdefault((pa, pb, ia - ib), []).append(ia)
    runs = []
    for (pa, pb, delta), starts in matches.items():
        starts.sort()
        first = previous = starts[0]
        for start in starts[1:] + [None]:
            if start is not None and start == previous + 1:
                previous = start
                continue
            la, lb = files[pa], files[pb]
            end = previous + MIN_LINES - 1
            runs.append((pa, la[first][0], la[end][0], pb, lb[first - delta][0],
                         lb[end - delta][0], end - first + 1))
            if start is not None:
                first = previous = start
    return sorted(runs)


def read_allow_list(path):
    allowed = set()
    if not path.exists():
        return allowed
    for line in path.read_text().splitlines():
        line = line.split("#", 1)[0].split()
        if len(line) == 2:
            allowed.add(tuple(sorted(line)))
    return allowed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=Path(__file__).resolve().parent.parent, type=Path)
    parser.add_argument("--check", action="store_true", help="exit 1 on a pair not allowed")
    args = parser.parse_args()
    files = {}
    for root in ROOTS:
        for path in sorted((args.root / root).rglob("*")):
            if path.suffix in SUFFIXES and path.is_file():
                text = path.read_text(encoding="utf-8", errors="replace")
                files[str(path.relative_to(args.root))] = code_lines(text)
    allowed = read_allow_list(args.root / "tools" / "duplicates_allow.txt")
    new = 0
    for pa, a1, a2, pb, b1, b2, count in find_runs(files):
        known = tuple(sorted((pa, pb))) in allowed
        new += not known
        print(f"{'allowed' if known else 'DUPLICATE'}: {count} lines "
              f"{pa}:{a1}-{a2} and {pb}:{b1}-{b2}")
    print(f"{new} pair(s) not on the allow-list")
    return 1 if args.check and new else 0


if __name__ == "__main__":
    sys.exit(main())
