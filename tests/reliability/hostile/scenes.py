"""Scenes the hostile cases run: small, so the whole list runs in minutes."""

import os


def tiny(repo):
    """The tests' tiny scene: 64 x 48 frames of an 8 m hill, milliseconds a frame."""
    with open(os.path.join(repo, "tests", "data", "scenes", "tiny.toml")) as f:
        return f.read()


HEMISPHERE = "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"

# A steady solve of a few thousand cells: a .vdb of some tens of kB, well under a second.
SMALL_SOLVE = HEMISPHERE + "[wind]\nkind = \"solved\"\n[solver]\nvoxel_size_m = 0.5\n"

# Three .vdb files of the same box (t = 0, 0.2 .. 0.6 s).
SMALL_UNSTEADY = (HEMISPHERE + "[wind]\nkind = \"unsteady\"\nspeed_mps = 2.0\n"
                  "[solver]\nvoxel_size_m = 0.5\n"
                  "[unsteady]\nduration_s = 0.6\noutput_every_s = 0.2\n")

# A steady solve of a few hundred thousand air cells to a tight tolerance: seconds.
SLOW_SOLVE = ("[terrain]\nkind = \"hemisphere\"\nsize_m = [40.0, 40.0]\nradius_m = 6.0\n"
              "[wind]\nkind = \"solved\"\n[solver]\nvoxel_size_m = 0.25\ntolerance = 1e-10\n"
              "max_iterations = 100000\n")

# An unsteady run of 41 files over a few seconds of wall time.
LONG_UNSTEADY = (HEMISPHERE + "[wind]\nkind = \"unsteady\"\nspeed_mps = 2.0\n"
                 "[solver]\nvoxel_size_m = 0.25\n"
                 "[unsteady]\nduration_s = 8.0\noutput_every_s = 0.2\n")

# A flat terrain of 3001 x 3001 samples: about a second to build and export.
BIG_TERRAIN = ("[terrain]\nkind = \"gaussian_hill\"\nsize_m = [3000.0, 3000.0]\nspacing_m = 1.0\n"
               "height_m = 100.0\nradius_m = 600.0\n")


def hill_scene(size_x_m, size_y_m, height_m, rest):
    """A Gaussian hill of size_x_m x size_y_m at 1 m samples, small grass, then `rest`."""
    return ("[terrain]\nkind = \"gaussian_hill\"\nsize_m = [%g, %g]\nspacing_m = 1.0\n"
            "height_m = %g\nradius_m = %g\n\n[grass]\nheight_m = 0.4\nshells = 8\n"
            "tile_m = 2.0\n\n[grass.generated]\nsize = 128\n\n" %
            (size_x_m, size_y_m, height_m, 0.25 * min(size_x_m, size_y_m))) + rest


SOLVED_WIND = ("[wind]\nkind = \"solved\"\nspeed_mps = 5.0\nprofile = \"log\"\n"
               "roughness_m = 0.03\n\n")
UNSTEADY_WIND = SOLVED_WIND.replace("solved", "unsteady")


def solver(voxel_m, top_m, limit_mb=100000):
    return ("[solver]\nvoxel_size_m = %g\ntop_m = %g\nmemory_limit_mb = %d\n" %
            (voxel_m, top_m, limit_mb))
