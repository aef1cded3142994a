#!/usr/bin/env python3
"""An independent port of tracer's `sampling::permute`, written from its
description: a bijection of the smallest power-of-two range holding `len`
(xor with the key, an odd multiply, a xorshift by half the range's bits,
the key's high half added, a second odd multiply and xorshift), walked
from `i` until it lands inside `0..len`.

Prints the tables `sampling::tests::permutations_are_those_an_independent_
port_computes` pins, so they can be made again without the Rust code.
"""

WORD = 0xFFFF_FFFF


def permute(i, length, key):
    if length <= 1:
        return 0
    mask = (1 << (length - 1).bit_length()) - 1
    shift = max(bin(mask).count("1") // 2, 1)
    x = i & mask
    while True:
        x ^= key & mask
        x = (x * 0x9E37_79B1) & WORD & mask
        x ^= x >> shift
        x = (x + (key >> 16)) & WORD & mask
        x = (x * 0x85EB_CA6B) & WORD & mask
        x ^= x >> shift
        if x < length:
            return x


for length, key, count in [(16, 0x2545_F491, 16), (100, 0xDEAD_BEEF, 16), (5, 0x9E37_79B9, 5)]:
    print(f"permute(0..{count}, {length}, {key:#x}) =", [permute(i, length, key) for i in range(count)])
