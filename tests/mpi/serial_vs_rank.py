#!/usr/bin/env python3
"""serial_vs_rank.py — the plain serial world (no decomposition) against
1 rank's, as tests/mpi/states.h writes them (per particle: id, 13
doubles). Every run sums in the canonical order (broad/canonical.c, issue
29), so the two are the same bits: every state equal, byte for byte.
(Before issue 29 the serial run summed in the search's order and the test
allowed 1e-6 m.)

    serial_vs_rank.py SERIAL.bin RANK1.bin LABEL [COUNT]
"""
import struct
import sys


def load(path):
    b = open(path, 'rb').read()
    rec = 8 + 13 * 8
    return [struct.unpack_from('<Q13d', b, k) for k in range(0, len(b), rec)]


a, b = load(sys.argv[1]), load(sys.argv[2])
want = int(sys.argv[4]) if len(sys.argv) > 4 else len(b)
if not (len(a) == len(b) == want > 0 and all(p[0] == q[0] for p, q in zip(a, b))):
    print(f"{sys.argv[3]}: serial vs 1 rank: {len(a)} and {len(b)} particles (want {want}) or other ids")
    sys.exit(1)
dx = max(abs(p[1 + c] - q[1 + c]) for p, q in zip(a, b) for c in range(3))
same = sum(p == q for p, q in zip(a, b))
print(f"{sys.argv[3]}: serial vs 1 rank: max |dx| = {dx:.3e} m, {same} of {len(a)} states equal to the bit "
      f"(all must be)")
sys.exit(0 if same == len(a) else 1)
