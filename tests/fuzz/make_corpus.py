#!/usr/bin/env python3
# SPDX-FileCopyrightText: 2026 The xeno authors
# SPDX-License-Identifier: MIT
#
# Writes the seed corpora of the fuzz targets (tests/fuzz/corpus/<target>/seed-N): a few small,
# fixed pseudo-random byte strings of different lengths (libFuzzer's FuzzedDataProvider decodes
# any bytes, so random seeds reach every shape kind, pose and operation quickly), plus an empty
# and an all-zero input. Deterministic: running it again rewrites the same files.
import os
import random

here = os.path.dirname(os.path.abspath(__file__))
for target, lengths in (("narrowphase", (24, 64, 96, 160, 256)), ("world", (48, 128, 256, 384, 512))):
    folder = os.path.join(here, "corpus", target)
    os.makedirs(folder, exist_ok=True)
    rng = random.Random("xeno-" + target)
    seeds = [b"", bytes(64)] + [bytes(rng.randrange(256) for _ in range(n)) for n in lengths]
    for i, seed in enumerate(seeds):
        with open(os.path.join(folder, "seed-%d" % i), "wb") as f:
            f.write(seed)
