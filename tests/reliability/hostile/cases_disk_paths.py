"""Hostile cases: a full disk (the LD_PRELOAD shim) and careless output paths."""

import os

from gale_run import leftovers, snapshot, write_text
from scenes import SMALL_SOLVE, SMALL_UNSTEADY, SLOW_SOLVE, tiny

NO_SPACE = "No space left on device"


def describe(r, extra=""):
    lines = r.error_lines() or r.err.strip().splitlines()[-1:]
    return "%s; %s%s" % (r.ended(), " / ".join(lines)[:220], extra)


def one_error(r, code, *fragments):
    """Exit `code` with exactly one error line holding every fragment."""
    lines = r.error_lines()
    return (r.rc == code and len(lines) == 1 and all(f in lines[0] for f in fragments))


def full_disk(ctx):
    gale, table = ctx["gale"], ctx["table"]
    tiny_text = tiny(ctx["repo"])
    cases = [
        # The last budget is a fraction of what the complete run wrote (a fixed byte count stops
        # filling the disk when the frames compress better; the C++ full-disk test does the same).
        ("render", tiny_text, ["render", "scene.toml", "-o", "frames"], "frames",
         [0, 5000, 12000, 0.8]),
        ("terrain", tiny_text, ["terrain", "scene.toml", "-o", "out/hill.png"], "out",
         [0, 100, 400]),
        ("solve, steady", SMALL_SOLVE, ["solve", "scene.toml", "-o", "field/wind.vdb"], "field",
         [0, 1000, 100000]),
        ("solve, unsteady", SMALL_UNSTEADY, ["solve", "scene.toml", "-o", "field/wind.vdb"],
         "field", [0, 60000, 300000]),
    ]
    for verb, scene, args, out, budgets in cases:
        cwd = gale.folder("disk-" + verb)
        write_text(os.path.join(cwd, "scene.toml"), scene)
        os.makedirs(os.path.join(cwd, out), exist_ok=True)
        first = gale.run(args, cwd)
        before = snapshot(os.path.join(cwd, out))
        total = sum(os.path.getsize(os.path.join(cwd, out, f)) for f in before
                    if os.path.isfile(os.path.join(cwd, out, f)))
        for budget in budgets:
            if isinstance(budget, float):
                budget = int(budget * total)  # a fraction of the complete run's bytes
            def case(budget=budget):
                if first.rc != 0 or not before:
                    return False, "the first, complete run failed: " + describe(first)
                r = gale.run(args, cwd, env=gale.full_disk_env(os.path.join(cwd, out), budget))
                same = snapshot(os.path.join(cwd, out)) == before
                left = leftovers(cwd)
                ok = one_error(r, 1, out + "/", NO_SPACE) and same and not left
                return ok, describe(r, "; earlier %d files %s; leftovers %s" %
                                    (len(before), "byte for byte" if same else "CHANGED", left))
            table.check("disk", "%s, disk full after %d bytes (%s)" % (verb, budget, " ".join(args)),
                        "exit 1, one line naming the file and '%s'; the earlier run's files byte "
                        "for byte; no temporary" % NO_SPACE, case)

    # Free-space checks against the space the disk reports (the shim's statvfs): hopeless runs are
    # refused before anything is written, the rest after the first file's measured size.
    def free_space_case(verb, scene, args, out, free_of_first):
        cwd = gale.folder("free-" + verb)
        write_text(os.path.join(cwd, "scene.toml"), scene)
        os.makedirs(os.path.join(cwd, out), exist_ok=True)
        first = gale.run(args, cwd)
        before = snapshot(os.path.join(cwd, out))
        first_file = min((os.path.getsize(os.path.join(cwd, out, f)) for f in before
                          if f.endswith((".png", ".vdb"))), default=0)
        budget = int(free_of_first * first_file)
        r = gale.run(args, cwd, env=gale.full_disk_env(os.path.join(cwd, out), budget, True))
        same = snapshot(os.path.join(cwd, out)) == before
        left = leftovers(cwd)
        ok = first.rc == 0 and one_error(r, 2, "free but") and same and not left
        return ok, describe(r, "; %d B free (%.1f first files); earlier files %s; leftovers %s" %
                            (budget, free_of_first, "unchanged" if same else "CHANGED", left))

    table.check("disk", "render of 40 frames with room for 3 frames (statvfs reports it)",
                "exit 2 before any frame (the 0.5 B/pixel floor), 'free but', earlier frames "
                "byte for byte",
                lambda: free_space_case("render", tiny_text,
                                        ["render", "scene.toml", "-o", "frames", "--frames", "40"],
                                        "frames", 3.0))
    table.check("disk", "render of 40 frames with room for them at 0.5 B/pixel (the old guess) but "
                "not at the first frame's measured size",
                "exit 2 after the first frame, 'free but', earlier frames byte for byte",
                lambda: free_space_case("render", tiny_text,
                                        ["render", "scene.toml", "-o", "frames", "--frames", "40"],
                                        "frames", 40.0))
    table.check("disk", "unsteady solve of 11 .vdb files with room for 3",
                "exit 2 after the first .vdb, 'free but', earlier sequence byte for byte",
                lambda: free_space_case("unsteady", SMALL_UNSTEADY.replace(
                    "duration_s = 0.6", "duration_s = 2.0"),
                    ["solve", "scene.toml", "-o", "field/wind.vdb"], "field", 3.0))


def careless_paths(ctx):
    gale, table, repo = ctx["gale"], ctx["table"], ctx["repo"]

    def refused(args, setup, *fragments, seconds=None):
        def case():
            cwd = gale.folder("paths")
            setup(cwd)
            before = snapshot(cwd)
            r = gale.run(args, cwd)
            same = snapshot(cwd) == before
            # Before any work: no progress line, and well within the solve's seconds.
            quick = seconds is None or (r.seconds < seconds and "solving" not in r.err)
            ok = one_error(r, 2, *fragments) and same and quick and not r.out.strip()
            return ok, describe(r, "; folder %s; %.2f s" % ("byte for byte" if same else "CHANGED",
                                                            r.seconds))
        return case

    def nothing(cwd):
        pass

    def terrain_png(name):
        def setup(cwd):
            write_text(os.path.join(cwd, "tiny.toml"), tiny(repo))
            r = gale.run(["terrain", "tiny.toml", "-o", name], cwd)
            assert r.rc == 0, "terrain export for the set-up failed: " + r.err
        return setup

    heightmap_scene = ("[terrain]\nkind = \"heightmap\"\nimage = \"hill.png\"\n"
                       "metres_per_pixel = 0.5\n")
    frame_scene = ("[terrain]\nkind = \"heightmap\"\nimage = \"frame_0001.png\"\n"
                   "metres_per_pixel = 0.5\n[output]\nfolder = \".\"\nframes = 3\nwidth = 64\n"
                   "height = 48\n")
    texture_scene = (tiny(repo).replace("[grass.generated]\nsize = 64\n", "")
                     .replace("tile_m = 2.0\n", "tile_m = 2.0\ntexture = \"frames/frame_0000.png\"\n"))

    def link(cwd):
        os.symlink("s.toml", os.path.join(cwd, "link.json"))

    def subfolder(cwd):
        os.makedirs(os.path.join(cwd, "sub"))

    def folder_named(name):
        return lambda cwd: os.makedirs(os.path.join(cwd, name))

    def texture_setup(cwd):
        os.makedirs(os.path.join(cwd, "frames"))
        terrain_png("frames/frame_0000.png")(cwd)

    expect = "exit 2, one error line, nothing written or changed (byte for byte)"
    cases = [
        ("solve -o same.vdb --report same.vdb",
         ["solve", "s.toml", "-o", "same.vdb", "--report", "same.vdb"], nothing, ["is also"], None),
        ("solve --report onto the scene", ["solve", "s.toml", "-o", "w.vdb", "--report", "s.toml"],
         nothing, ["the scene"], None),
        ("solve --report onto the scene through a symbolic link",
         ["solve", "s.toml", "-o", "w.vdb", "--report", "link.json"], link, ["the scene"], None),
        ("solve --report onto the scene spelt sub/../s.toml",
         ["solve", "s.toml", "-o", "w.vdb", "--report", "sub/../s.toml"], subfolder, ["the scene"],
         None),
        ("solve -o onto the scene", ["solve", "s.toml", "-o", "s.toml"], nothing, [], None),
        ("terrain -o onto the scene's own heightmap", ["terrain", "h.toml", "-o", "hill.png"],
         terrain_png("hill.png"), ["(the heightmap)"], heightmap_scene),
        ("terrain -o onto the scene file", ["terrain", "s.toml", "-o", "s.toml"], nothing, [], None),
        ("render with folder = \".\" over a heightmap named frame_0001.png", ["render", "h.toml"],
         terrain_png("frame_0001.png"), ["(a frame)"], frame_scene),
        ("render -o over its own grass texture frames/frame_0000.png",
         ["render", "t.toml", "-o", "frames"], texture_setup, ["(the grass texture)"],
         texture_scene),
        ("solve -o naming a folder (a slow solve: refused before any work)",
         ["solve", "s.toml", "-o", "w.vdb"], folder_named("w.vdb"), ["is a folder"], None),
        ("solve --report naming a folder", ["solve", "s.toml", "-o", "x.vdb", "--report", "w.json"],
         folder_named("w.json"), ["is a folder"], None),
        ("terrain -o naming a folder", ["terrain", "s.toml", "-o", "h.png"], folder_named("h.png"),
         ["is a folder"], None),
        ("render -o naming a file", ["render", "t.toml", "-o", "frames"],
         lambda cwd: write_text(os.path.join(cwd, "frames"), "a file"), ["frames"], tiny(repo)),
    ]
    for name, args, setup, fragments, scene in cases:
        scene_name = args[1]
        text = scene if scene is not None else SLOW_SOLVE if "before any work" in name else SMALL_SOLVE

        def full_setup(cwd, setup=setup, scene_name=scene_name, text=text):
            write_text(os.path.join(cwd, scene_name), text)
            setup(cwd)
        # A slow solve takes seconds; refused up front it takes a fraction of one.
        seconds = 5.0 if "before any work" in name else None
        table.check("paths", name + " (" + " ".join(args) + ")", expect,
                    refused(args, full_setup, *fragments, seconds=seconds))
