"""Do the floats of a state netlift wrote agree bit for bit with C's?

Usage: floats-agree.py STATES.csv C-OUTPUT COLUMN=VALUE
Takes the first row of `netlift reach --format csv` whose COLUMN is VALUE and, for
every `name width hexfloat` line of C-OUTPUT (C's printf("%a")), compares the
row's value of `name` with C's, as a binary32 or binary64 bit pattern. Prints
one line per value and exits 1 on the first disagreement.
"""
import csv
import struct
import sys


def bits(value, width):
    return struct.pack(">f" if width == 32 else ">d", value)


def main():
    states, c_output, where = sys.argv[1:4]
    column, wanted = where.split("=")
    rows = [r for r in csv.DictReader(open(states)) if r[column] == wanted]
    if not rows:
        sys.exit(f"no state has {where}")
    row = rows[0]
    ok = True
    for line in open(c_output):
        name, width, hexfloat = line.split()
        ours, theirs = float(row[name]), float.fromhex(hexfloat)
        same = bits(ours, int(width)) == bits(theirs, int(width))
        print(f"{name}: {'same' if same else 'DIFFERENT'} {row[name]} {hexfloat}")
        ok &= same
    sys.exit(0 if ok else 1)


main()
