#!/usr/bin/env python3
"""An Evrard sphere (the standard test of SPH codes with self-gravity: gas of density
rho ~ 1 / r inside radius R, at rest) written as SWIFT writes a snapshot, in cgs units: a
solar mass in a parsec, so that render_particles can be tried on a GADGET-format file without
running an astrophysics code.

    python3 examples/gadget/evrard_snapshot.py evrard.hdf5 [--particles 50000]
    build/tools/render_particles --config examples/gadget/gas.yaml evrard.hdf5

Needs numpy and h5py (Debian: python3-numpy, python3-h5py)."""
import argparse

import h5py
import numpy

PARSEC = 3.0857e18  # cm
SOLAR_MASS = 1.989e33  # g


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", help="the snapshot to write (.hdf5)")
    parser.add_argument("--particles", type=int, default=50000)
    args = parser.parse_args()
    n = args.particles
    rng = numpy.random.default_rng(1)
    # rho ~ 1 / r: the mass inside r grows as r^2, so r = R sqrt(u) for u uniform.
    r = numpy.sqrt(rng.random(n)) * PARSEC
    mu = rng.uniform(-1, 1, n)
    phi = rng.uniform(0, 2 * numpy.pi, n)
    s = numpy.sqrt(1 - mu ** 2)
    xyz = numpy.stack([r * s * numpy.cos(phi), r * s * numpy.sin(phi), r * mu], axis=1)
    mass = numpy.full(n, SOLAR_MASS / n)
    density = SOLAR_MASS / (2 * numpy.pi * PARSEC ** 2 * r)
    # SWIFT's h for its cubic spline: 1.2348 mean spacings.
    h = 1.2348 * (mass / density) ** (1 / 3)
    with h5py.File(args.out, "w") as f:
        header = f.create_group("Header")
        header.attrs["Time"] = [0.0]
        header.attrs["NumPart_ThisFile"] = numpy.array([n, 0, 0, 0, 0, 0], dtype=numpy.uint32)
        header.attrs["MassTable"] = numpy.zeros(6)
        header.attrs["NumFilesPerSnapshot"] = [1]
        gas = f.create_group("PartType0")
        gas["Coordinates"] = xyz
        gas["Velocities"] = numpy.zeros((n, 3), dtype=numpy.float32)
        gas["Masses"] = mass.astype(numpy.float32)
        gas["Densities"] = density.astype(numpy.float32)
        gas["SmoothingLengths"] = h.astype(numpy.float32)
        gas["InternalEnergies"] = numpy.full(n, 0.05 * 6.674e-8 * SOLAR_MASS / PARSEC,
                                             dtype=numpy.float32)
        gas["ParticleIDs"] = numpy.arange(n, dtype=numpy.uint64)
    print(f"{n} gas particles in {args.out}")


if __name__ == "__main__":
    main()
