#!/usr/bin/env python3
"""Reads a Value Change Dump (IEEE 1364-2005, section 18) back and prints
each timestamp's values, one line per time:

    #4 go=1 q=1 step=8

An independent reader of what `netlift reach --trace-vcd` and `check
--trace-dir` write (issue 40): it checks the structure as a VCD viewer
needs it (declarations before $enddefinitions, every change to a
declared identifier, a value per declared width, times that never go
back) and exits 1 naming the first violation.

Usage: read-vcd.py FILE [SIGNAL...]   (all signals when none are named)
"""
import sys


def fail(message):
    sys.stderr.write("read-vcd: " + message + "\n")
    sys.exit(1)


def tokens(text):
    for line_no, line in enumerate(text.splitlines(), 1):
        for word in line.split():
            yield line_no, word


def until_end(words):
    """The words of a declaration up to its $end."""
    out = []
    for _, w in words:
        if w == "$end":
            return out
        out.append(w)
    fail("a declaration without its $end")


def main():
    if len(sys.argv) < 2:
        fail("usage: read-vcd.py FILE [SIGNAL...]")
    text = open(sys.argv[1]).read()
    wanted = sys.argv[2:]
    words = tokens(text)
    names = {}  # identifier -> (name, kind, width)
    order = []
    timescale = None
    # Declarations.
    for line_no, word in words:
        if word == "$enddefinitions":
            next(words)  # $end
            break
        if word == "$timescale":
            timescale = "".join(until_end(words))
            if timescale not in {f"{n}{u}" for n in ("1", "10", "100")
                                 for u in ("s", "ms", "us", "ns", "ps", "fs")}:
                fail(f"line {line_no}: timescale '{timescale}'")
            continue
        if word == "$var":
            fields = until_end(words)
            if len(fields) < 4:
                fail(f"line {line_no}: $var needs a kind, width, id, name")
            kind, width, ident, name = fields[0], int(fields[1]), fields[2], fields[3]
            if kind not in ("wire", "reg", "integer", "real"):
                fail(f"line {line_no}: unknown kind '{kind}'")
            if ident in names:
                fail(f"line {line_no}: identifier '{ident}' declared twice")
            names[ident] = (name, kind, width)
            order.append(ident)
            continue
        if word.startswith("$"):  # $version, $scope, $comment...: skip
            until_end(words)
    else:
        fail("no $enddefinitions")
    if timescale is None:
        fail("no $timescale")
    values = {}
    lines = []
    time = None

    def flush():
        if time is None:
            return
        # The signals asked for, in the order asked; else all, declared.
        by_name = {names[i][0]: i for i in order}
        for w in wanted:
            if w not in by_name:
                fail(f"no signal '{w}'")
        shown = [by_name[w] for w in wanted] if wanted else order
        lines.append(f"#{time} " + " ".join(
            f"{names[i][0]}={values.get(i, '?')}" for i in shown))

    pending = None  # a vector's value waiting for its identifier
    for line_no, word in words:
        if pending is not None:
            kind, value = pending
            pending = None
            if word not in names:
                fail(f"line {line_no}: change to undeclared '{word}'")
            _, declared, width = names[word]
            if kind == "r":
                if declared != "real":
                    fail(f"line {line_no}: a real value for '{word}'")
                try:  # one spelling per number: r-1 and r-1.0 are one
                    values[word] = repr(float(value))
                except ValueError:
                    fail(f"line {line_no}: '{value}' is not a real")
            else:
                if declared == "real":
                    fail(f"line {line_no}: a vector for real '{word}'")
                if len(value) > width:
                    fail(f"line {line_no}: {len(value)} bits for '{word}' "
                         f"of width {width}")
                if set(value) <= {"0", "1"}:
                    number = int(value, 2)
                    if value[0] == "1" and len(value) == width:
                        number -= 1 << width
                    values[word] = str(number)
                else:
                    values[word] = value
            continue
        if word.startswith("#"):
            t = int(word[1:])
            if time is not None and t < time:
                fail(f"line {line_no}: time {t} after {time}")
            if time is not None and t != time:
                flush()
            time = t
            continue
        if word in ("$dumpvars", "$end", "$dumpall", "$dumpon", "$dumpoff"):
            continue
        if word[0] in "bB" or word[0] in "rR":
            pending = (word[0].lower(), word[1:])
            continue
        if word[0] in "01xXzZ":
            ident = word[1:]
            if ident not in names:
                fail(f"line {line_no}: change to undeclared '{ident}'")
            values[ident] = word[0].lower()
            continue
        fail(f"line {line_no}: unexpected '{word}'")
    if pending is not None:
        fail("a value without its identifier at the end")
    flush()
    print(f"timescale {timescale}")
    for line in lines:
        print(line)


if __name__ == "__main__":
    main()
