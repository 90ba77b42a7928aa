#!/usr/bin/env python3
"""Writes src/sampler/sobol_table.rs: the Sobol' generator matrices for the first
SOBOL_DIMENSIONS dimensions, from the Joe & Kuo (2008) direction numbers embedded below.

    python3 scripts/sobol_table.py            # rewrite src/sampler/sobol_table.rs
    python3 scripts/sobol_table.py --check    # exit 1 if the committed table differs

Sources:
- S. Joe and F. Y. Kuo, "Constructing Sobol sequences with better two-dimensional
  projections", SIAM J. Sci. Comput. 30 (2008) 2635-2654; direction numbers file
  "new-joe-kuo-6.21201" from https://web.maths.unsw.edu.au/~fkuo/sobol/ (its first 63
  data lines are embedded below, unchanged: d, s, a, m_1..m_s).
- The recurrence for the direction numbers v_k (Joe & Kuo, "Notes on generating Sobol'
  sequences", 2008, eq. (2) and their reference code sobol.cc):
      v_k = m_k 2^(32-k)                                       for k <= s
      v_k = a_1 v_{k-1} ^ ... ^ a_{s-1} v_{k-s+1} ^ v_{k-s} ^ (v_{k-s} >> s)  for k > s
  kept to 32 bits, for k = 1..SOBOL_MATRIX_SIZE (52 columns, as pbrt-v4's
  SobolMatrices32, so indices up to 2^52 are defined; columns past 32 hold the recurrence
  truncated to 32 bits, exactly as pbrt-v4's table).
- Dimension 0 is the van der Corput sequence: v_k = 2^(32-k) (zero past k = 32).

The direction numbers are Copyright (c) 2008, Frances Y. Kuo and Stephen Joe, All rights
reserved, redistributed under their BSD-style licence (retain this notice; see
https://web.maths.unsw.edu.au/~fkuo/sobol/). No network access: the data are embedded.
"""
import sys
from pathlib import Path

SOBOL_DIMENSIONS = 64
SOBOL_MATRIX_SIZE = 52
OUT = Path(__file__).resolve().parent.parent / "src" / "sampler" / "sobol_table.rs"

# new-joe-kuo-6.21201, data lines d = 2..64 (dimension d of the file is our dimension d-1).
JOE_KUO = """\
2       1       0       1
3       2       1       1 3
4       3       1       1 3 1
5       3       2       1 1 1
6       4       1       1 1 3 3
7       4       4       1 3 5 13
8       5       2       1 1 5 5 17
9       5       4       1 1 5 5 5
10      5       7       1 1 7 11 19
11      5       11      1 1 5 1 1
12      5       13      1 1 1 3 11
13      5       14      1 3 5 5 31
14      6       1       1 3 3 9 7 49
15      6       13      1 1 1 15 21 21
16      6       16      1 3 1 13 27 49
17      6       19      1 1 1 15 7 5
18      6       22      1 3 1 15 13 25
19      6       25      1 1 5 5 19 61
20      7       1       1 3 7 11 23 15 103
21      7       4       1 3 7 13 13 15 69
22      7       7       1 1 3 13 7 35 63
23      7       8       1 3 5 9 1 25 53
24      7       14      1 3 1 13 9 35 107
25      7       19      1 3 1 5 27 61 31
26      7       21      1 1 5 11 19 41 61
27      7       28      1 3 5 3 3 13 69
28      7       31      1 1 7 13 1 19 1
29      7       32      1 3 7 5 13 19 59
30      7       37      1 1 3 9 25 29 41
31      7       41      1 3 5 13 23 1 55
32      7       42      1 3 7 3 13 59 17
33      7       50      1 3 1 3 5 53 69
34      7       55      1 1 5 5 23 33 13
35      7       56      1 1 7 7 1 61 123
36      7       59      1 1 7 9 13 61 49
37      7       62      1 3 3 5 3 55 33
38      8       14      1 3 1 15 31 13 49 245
39      8       21      1 3 5 15 31 59 63 97
40      8       22      1 3 1 11 11 11 77 249
41      8       38      1 3 1 11 27 43 71 9
42      8       47      1 1 7 15 21 11 81 45
43      8       49      1 3 7 3 25 31 65 79
44      8       50      1 3 1 1 19 11 3 205
45      8       52      1 1 5 9 19 21 29 157
46      8       56      1 3 7 11 1 33 89 185
47      8       67      1 3 3 3 15 9 79 71
48      8       70      1 3 7 11 15 39 119 27
49      8       84      1 1 3 1 11 31 97 225
50      8       97      1 1 1 3 23 43 57 177
51      8       103     1 3 7 7 17 17 37 71
52      8       115     1 3 1 5 27 63 123 213
53      8       122     1 1 3 5 11 43 53 133
54      9       8       1 3 5 5 29 17 47 173 479
55      9       13      1 3 3 11 3 1 109 9 69
56      9       16      1 1 1 5 17 39 23 5 343
57      9       22      1 3 1 5 25 15 31 103 499
58      9       25      1 1 1 11 11 17 63 105 183
59      9       44      1 1 5 11 9 29 97 231 363
60      9       47      1 1 5 15 19 45 41 7 383
61      9       52      1 3 7 7 31 19 83 137 221
62      9       55      1 1 1 3 23 15 111 223 83
63      9       59      1 1 5 13 31 15 55 25 161
64      9       62      1 1 3 13 25 47 39 87 257
"""

# Spot values of pbrt-v4 src/pbrt/util/sobolmatrices.cpp (SobolMatrices32, generated from
# the same file by L. Gruenschloss): (dimension, column) -> value. A cross-check only.
PBRT_SPOT = {
    (0, 0): 0x80000000, (0, 31): 0x00000001, (0, 32): 0,
    (1, 0): 0x80000000, (1, 1): 0xC0000000, (1, 2): 0xA0000000, (1, 31): 0xFFFFFFFF,
    (1, 32): 0x80000000,
    (2, 0): 0x80000000, (2, 2): 0x60000000, (2, 4): 0xE8000000, (2, 5): 0x5C000000,
    (2, 51): 0x90000000,
    (3, 0): 0x80000000, (3, 2): 0x20000000, (3, 3): 0x50000000, (3, 4): 0xF8000000,
    (3, 5): 0x74000000, (4, 3): 0xB0000000, (4, 7): 0x9D000000, (5, 4): 0xC8000000,
    (6, 5): 0x94000000,
}

MASK = 0xFFFFFFFF


def columns(s, a, m):
    """The SOBOL_MATRIX_SIZE columns v_1..v_L of one dimension (Joe & Kuo 2008, eq. (2))."""
    v = [0] * (SOBOL_MATRIX_SIZE + 1)
    for k in range(1, SOBOL_MATRIX_SIZE + 1):
        if k <= s:
            v[k] = (m[k - 1] << (32 - k)) & MASK
        else:
            x = v[k - s] ^ (v[k - s] >> s)
            for j in range(1, s):
                if (a >> (s - 1 - j)) & 1:
                    x ^= v[k - j]
            v[k] = x & MASK
    return v[1:]


def matrices():
    out = [[(1 << (32 - k)) & MASK if k <= 32 else 0 for k in range(1, SOBOL_MATRIX_SIZE + 1)]]
    for line in JOE_KUO.strip().splitlines():
        d, s, a, *m = (int(c) for c in line.split())
        assert len(m) == s and d == len(out) + 1, line
        out.append(columns(s, a, m))
    assert len(out) == SOBOL_DIMENSIONS
    for (dim, col), want in PBRT_SPOT.items():
        assert out[dim][col] == want, (dim, col, hex(out[dim][col]), hex(want))
    return out


def render(mats):
    lines = [
        "// @generated by scripts/sobol_table.py: do not edit by hand (exempt from the",
        "// 500-line rule). Regenerate with `python3 scripts/sobol_table.py`.",
        "//",
        "// Sobol' generator matrices from the Joe & Kuo (2008) direction numbers",
        "// \"new-joe-kuo-6.21201\" (https://web.maths.unsw.edu.au/~fkuo/sobol/),",
        "// Copyright (c) 2008, Frances Y. Kuo and Stephen Joe, All rights reserved; BSD-style",
        "// licence: redistribution must retain this notice.",
        "",
        "//! Sobol' generator matrices (generated, see `scripts/sobol_table.py`): column `k` of",
        "//! dimension `d` is `SOBOL_MATRICES[d][k]`, a 32-bit binary fraction (bit 31 = 1/2).",
        "",
        "/// Number of tabulated Sobol' dimensions.",
        f"pub const SOBOL_DIMENSIONS: usize = {SOBOL_DIMENSIONS};",
        "/// Columns per dimension: indices below `2^SOBOL_MATRIX_SIZE` are defined.",
        f"pub const SOBOL_MATRIX_SIZE: usize = {SOBOL_MATRIX_SIZE};",
        "",
        "/// The generator matrices, one row of columns per dimension.",
        "#[rustfmt::skip]",
        "pub static SOBOL_MATRICES: [[u32; SOBOL_MATRIX_SIZE]; SOBOL_DIMENSIONS] = [",
    ]
    for dim, cols in enumerate(mats):
        lines.append(f"    // dimension {dim}")
        lines.append("    [")
        for i in range(0, len(cols), 6):
            lines.append("        " + " ".join(f"0x{c:08x}," for c in cols[i:i + 6]))
        lines.append("    ],")
    lines.append("];")
    return "\n".join(lines) + "\n"


def main():
    text = render(matrices())
    if "--check" in sys.argv:
        if OUT.read_text() != text:
            print(f"{OUT} is out of date; run scripts/sobol_table.py", file=sys.stderr)
            sys.exit(1)
        return
    OUT.write_text(text)
    print(f"wrote {OUT} ({SOBOL_DIMENSIONS} dimensions x {SOBOL_MATRIX_SIZE} columns)")


if __name__ == "__main__":
    main()
