"""Hostile cases: signals at several moments, a killed run's leftovers, two runs in one folder."""

import os
import re
import signal
import time

from gale_run import json_file, leftovers, png_check, snapshot, vdb_check, write_text
from scenes import BIG_TERRAIN, LONG_UNSTEADY, SLOW_SOLVE, tiny

RENDER_FRAMES = 200


def verbs(repo):
    """verb -> (scene, args, output folder, {moment: (trigger, argument, then seconds)}).
    Triggers: ("time", s) that many seconds from the start (for the terrain export, a fraction
    of a full run's time), ("stderr", regex) a progress line, ("file", None) the first
    temporary in the output folder (the run has started writing)."""
    frames = str(RENDER_FRAMES)
    start = ("time", 0.05, 0.0)
    return {
        "render": (tiny(repo), ["render", "scene.toml", "-o", "out", "--frames", frames], "out",
                   {"start": start,
                    "early": ("stderr", r"rendering", 0.0),
                    "middle": ("stderr", r"frame +%d/%s" % (RENDER_FRAMES // 2, frames), 0.0),
                    "late": ("stderr", r"frame +%s/%s" % (frames, frames), 0.0)}),
        "steady solve": (SLOW_SOLVE, ["solve", "scene.toml", "-o", "out/w.vdb"], "out",
                         {"start": start, "early": ("stderr", r"solving", 0.0),
                          "middle": ("stderr", r"solving", 1.0), "late": ("file", None, 0.0)}),
        "unsteady solve": (LONG_UNSTEADY, ["solve", "scene.toml", "-o", "out/w.vdb"], "out",
                           {"start": start, "early": ("stderr", r"steady solve", 0.0),
                            "middle": ("stderr", r"output +20/40", 0.0),
                            "late": ("stderr", r"output +40/40", 0.0)}),
        "terrain": (BIG_TERRAIN, ["terrain", "scene.toml", "-o", "out/hill.png"], "out",
                    {"start": start, "early": ("time", 0.15, 0.0), "middle": ("time", 0.5, 0.0),
                     "late": ("file", None, 0.0)}),
    }


def reach(run, trigger, argument, then, folder, full_s):
    """Waits for the moment; returns None, or why it never came."""
    if trigger == "stderr" and not run.wait_for(argument, 120):
        return "never reached /%s/: %s" % (argument, run.wait(5).ended())
    if trigger == "file" and not run.wait_for_temporary(folder, 120):
        return "never started writing: %s" % run.wait(5).ended()
    if trigger == "time":
        time.sleep(argument * full_s if full_s and argument > 0.1 else argument)
    time.sleep(then)
    return None


def describe_moment(trigger, argument, then, full_s):
    if trigger == "stderr":
        return "after /%s/%s" % (argument, " + %g s" % then if then else "")
    if trigger == "file":
        return "once its first temporary exists"
    if full_s and argument > 0.1:
        return "at %.0f %% of a full run" % (100 * argument)
    return "%.2f s in" % argument


def complete_files(folder):
    """[] if every file under folder is whole (PNG chunks and CRCs, .vdb read by vdb_print, JSON
    parsed), else the reasons."""
    bad = []
    for rel in snapshot(folder):
        path = os.path.join(folder, rel)
        problem = None
        if rel.endswith(".png"):
            problem = png_check(path)
        elif rel.endswith(".vdb"):
            problem = vdb_check(path)
        elif rel.endswith(".json"):
            try:
                json_file(path)
            except ValueError as e:
                problem = "JSON: %s" % e
        if problem:
            bad.append("%s: %s" % (rel, problem))
    return bad


def listed_outputs(verb, folder):
    """The files the run's report names (plus the report), or None without a report."""
    if verb == "render":
        path = os.path.join(folder, "frame_report.json")
        if not os.path.exists(path):
            return None
        report = json_file(path)
        names = set(report["files"]) | {"frame_report.json"}
        return names, report
    path = os.path.join(folder, "w.json")
    if not os.path.exists(path):
        return None
    report = json_file(path)
    if verb == "unsteady solve":
        names = {os.path.basename(f["path"]) for f in report["outputs"]["vdb_sequence"]}
    else:
        names = {"w.vdb"}
    return names | {"w.json"}, report


def complete_run(verb, report):
    """The report is that of a run that did all its work."""
    if verb == "render":
        return report["frames"] == report["frames_requested"]
    if verb == "unsteady solve":
        return abs(report["summary"]["simulated_s"] - report["settings"]["duration_s"]) < 1e-9
    return True


def judge(verb, sig, r, cwd, out):
    """The invariants after a signal, whatever moment it met: (ok, observed)."""
    folder = os.path.join(cwd, out)
    files = set(snapshot(folder)) if os.path.isdir(folder) else set()
    left = leftovers(cwd)
    broken = complete_files(folder) if files else []
    name = signal.Signals(sig).name
    said = re.search(r"interrupted \(%s\)[^\n]*" % name, r.out + r.err)
    where = said.group(0)[:90] if said else ""
    problems = []
    if r.timed_out:
        problems.append("did not stop")
    elif r.sig:
        # Before the handlers are installed the default action ends it: nothing may exist yet.
        if files:
            problems.append("killed by the signal with files written")
        where = "killed by %s before its handler (nothing written)" % name
    elif r.rc == 0:
        where = "finished before the signal"
    elif r.rc != 128 + sig or not said:
        problems.append("%s without 'interrupted (%s)'" % (r.ended(), name))
    if left:
        problems.append("leftovers %s" % left)
    if broken:
        problems.append("incomplete %s" % broken)
    listed = listed_outputs(verb, folder) if files else None
    if files:
        expected_files = listed[0] if listed else None
        if expected_files is None:
            problems.append("files without a report: %s" % sorted(files)[:4])
        else:
            extra = files - expected_files - ({"frame_sheet.png", "frame.gif"}
                                              if verb == "render" else set())
            missing = expected_files - files
            if extra or missing:
                problems.append("report and folder differ: extra %s missing %s" %
                                (sorted(extra)[:3], sorted(missing)[:3]))
            report = listed[1]
            stopped = report.get("interrupted") and report.get("stopped_by") == name
            if r.rc == 128 + sig and not stopped and not complete_run(verb, report):
                problems.append("report neither says it was stopped by %s nor is complete" % name)
            if r.rc == 0 and report.get("interrupted"):
                problems.append("exit 0 with a report that says it was interrupted")
    if verb == "terrain" and r.rc == 128 + sig and files:
        problems.append("a stopped terrain export left files %s" % sorted(files))
    if verb == "steady solve" and files and files != {"w.vdb", "w.json"}:
        problems.append("a steady solve left %s, not both files" % sorted(files))
    ok = not problems
    observed = "%s; %s; %d files kept%s" % (r.ended(), where, len(files),
                                            "; " + "; ".join(problems) if problems else "")
    return ok, observed


def signals(ctx):
    gale, table = ctx["gale"], ctx["table"]
    for verb, (scene, args, out, moments) in verbs(ctx["repo"]).items():
        # The terrain export prints no progress: its moments are fractions of a full run's time,
        # measured here in the same conditions.
        full_s = None
        if verb == "terrain":
            cwd = gale.folder("signals-terrain-reference")
            write_text(os.path.join(cwd, "scene.toml"), scene)
            os.makedirs(os.path.join(cwd, out))
            full_s = gale.run(args, cwd).seconds
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            for moment, (trigger, argument, then) in moments.items():
                def case(sig=sig, trigger=trigger, argument=argument, then=then):
                    cwd = gale.folder("signals-" + verb)
                    write_text(os.path.join(cwd, "scene.toml"), scene)
                    os.makedirs(os.path.join(cwd, out))
                    run = gale.start(args, cwd)
                    missed = reach(run, trigger, argument, then, os.path.join(cwd, out), full_s)
                    if missed:
                        return False, missed
                    run.signal(sig)
                    return judge(verb, sig, run.wait(120), cwd, out)
                table.check("signals", "%s, %s %s (%s)" % (
                    verb, signal.Signals(sig).name, moment,
                    describe_moment(trigger, argument, then, full_s)),
                    "exit 128+signal saying 'interrupted (SIG..)' (or finished, or killed "
                    "before its handler with nothing written); complete files only, each "
                    "listed by the report; no temporary, no lock", case)


def stale_temporaries(ctx):
    """SIGKILL mid-run leaves temporaries (and the lock): gale check names them, the next run
    removes them."""
    gale, table = ctx["gale"], ctx["table"]
    for verb, (scene, args, out, moments) in verbs(ctx["repo"]).items():
        # The moment where something must be on disk half done: the render and the unsteady
        # solve in the middle of their outputs (after the last output the run may be gone before
        # the kill arrives), the others once their temporary exists.
        trigger, argument, then = moments["middle" if verb in ("render", "unsteady solve")
                                          else "late"]

        def case(scene=scene, args=args, out=out, moment=(trigger, argument, then), verb=verb):
            cwd = gale.folder("stale-" + verb)
            write_text(os.path.join(cwd, "scene.toml"), scene)
            os.makedirs(os.path.join(cwd, out))
            run = gale.start(args, cwd)
            missed = reach(run, *moment, os.path.join(cwd, out), None)
            if missed:
                return False, missed
            run.signal(signal.SIGKILL)
            run.wait(60)
            stale = leftovers(os.path.join(cwd, out))
            temps = [s for s in stale if s != ".gale.lock"]
            check = gale.run(["check", "scene.toml", "-o", out], cwd)
            named = ((not temps or "%d temporary file" % len(temps) in check.out) and
                     (".gale.lock" not in stale or ".gale.lock" in check.out))
            still = leftovers(os.path.join(cwd, out)) == stale
            nxt = gale.run(args, cwd, timeout=300)
            removed = not temps or ("removed %d temporary file" % len(temps)) in nxt.err
            clean = not leftovers(cwd)
            ok = bool(stale) and named and still and nxt.rc == 0 and removed and clean
            return ok, ("left by SIGKILL: %s; check %s them%s; next run %s, %s; leftovers after: "
                        "%s" % (stale[:3] + (["..."] if len(stale) > 3 else []),
                                "names" if named else "does NOT name",
                                " and keeps them" if still else " (and REMOVED some)", nxt.ended(),
                                "removes them" if removed else "does NOT say it removed them",
                                leftovers(cwd)))
        table.check("stale", "%s killed by SIGKILL %s, then gale check and the same run again" %
                    (verb, describe_moment(trigger, argument, then, None)),
                    "something left; check names every temporary and the lock without removing "
                    "them; the next run exits 0, says it removed them, leaves none", case)


def concurrent_renders(ctx):
    gale, table, repo = ctx["gale"], ctx["table"], ctx["repo"]
    scene_a = tiny(repo)
    scene_b = scene_a.replace("height_m = 1.5", "height_m = 3.0")
    frames = ["--frames", "16"]

    def reference(text, count=frames):
        cwd = gale.folder("concurrent-reference")
        write_text(os.path.join(cwd, "scene.toml"), text)
        r = gale.run(["render", "scene.toml", "-o", "out"] + count, cwd)
        assert r.rc == 0, r.err
        snap = snapshot(os.path.join(cwd, "out"))
        return {k: v for k, v in snap.items() if k.endswith(".png") or k.endswith(".gif")}

    def frames_of(folder):
        return {k: v for k, v in snapshot(folder).items() if k.endswith((".png", ".gif"))}

    def started_one_after_the_other():
        # The frames of a run sample its whole duration, so the lone run renders as many frames
        # as the interrupted one for its first ones to be the same.
        slow = ["--frames", "400"]
        ref_a = reference(scene_a, slow)
        cwd = gale.folder("concurrent")
        write_text(os.path.join(cwd, "a.toml"), scene_a)
        write_text(os.path.join(cwd, "b.toml"), scene_b)
        a = gale.start(["render", "a.toml", "-o", "out"] + slow, cwd)
        if not a.wait_for(r"frame +2/400", 120):
            return False, "the first render never started"
        b = gale.run(["render", "b.toml", "-o", "out"] + frames, cwd)
        a.signal(signal.SIGINT)
        ra = a.wait(120)
        report = json_file(os.path.join(cwd, "out", "frame_report.json"))
        got = frames_of(os.path.join(cwd, "out"))
        first16 = {k: v for k, v in got.items() if k in ref_a and k.startswith("frame_00")
                   and int(k[6:10]) < 16}
        same = all(got.get(k) == v for k, v in ref_a.items()
                   if k.startswith("frame_00") and int(k[6:10]) < min(16, report["frames"]))
        names_owner = "PID %d" % a.pid in (b.error_lines() or [""])[0]
        ok = (b.rc == 2 and len(b.error_lines()) == 1 and names_owner and ra.rc == 130 and
              report["scene"].endswith("a.toml") and same and not leftovers(cwd))
        return ok, ("second: %s (%s); first: %s, report scene %s, %d frames, first %d equal to a "
                    "lone run's byte for byte: %s" % (
                        b.ended(), (b.error_lines() or [""])[0][:120], ra.ended(),
                        report["scene"], report["frames"], len(first16), same))

    def started_together():
        many = ["--frames", "48"]
        refs = {"a.toml": reference(scene_a, many), "b.toml": reference(scene_b, many)}
        cwd = gale.folder("concurrent-together")
        write_text(os.path.join(cwd, "a.toml"), scene_a)
        write_text(os.path.join(cwd, "b.toml"), scene_b)
        runs = {s: gale.start(["render", s, "-o", "out"] + many, cwd) for s in refs}
        ends = {s: r.wait(120) for s, r in runs.items()}
        codes = sorted(e.rc for e in ends.values())
        report = json_file(os.path.join(cwd, "out", "frame_report.json"))
        owner = os.path.basename(report["scene"])
        same = owner in refs and frames_of(os.path.join(cwd, "out")) == refs[owner]
        refused = [e for e in ends.values() if e.rc == 2]
        names_pid = all("in use by another gale run (PID" in (e.error_lines() or [""])[0]
                        for e in refused)
        # Both may succeed when one finished before the other took the lock: the folder is then
        # the later run's, whole.
        ok = codes in ([0, 2], [0, 0]) and names_pid and same and not leftovers(cwd)
        return ok, "exit codes %s; report names %s; every frame, GIF and sheet that scene's " \
                   "(byte for byte against a lone run): %s" % (codes, report["scene"], same)

    def dead_lock():
        cwd = gale.folder("concurrent-dead-lock")
        write_text(os.path.join(cwd, "scene.toml"), scene_a)
        os.makedirs(os.path.join(cwd, "out"))
        pid = os.fork()
        if pid == 0:
            os._exit(0)
        os.waitpid(pid, 0)
        write_text(os.path.join(cwd, "out", ".gale.lock"), "%d\n" % pid)
        r = gale.run(["render", "scene.toml", "-o", "out"], cwd)
        noted = "taking over out/.gale.lock from PID %d" % pid in r.err
        return (r.rc == 0 and noted and not leftovers(cwd),
                "%s; note %s; leftovers %s" % (r.ended(), noted, leftovers(cwd)))

    table.check("concurrent", "render b.toml into a folder a.toml's render is writing",
                "the second exits 2 naming the first's PID; the first ends with its own report; "
                "its frames byte for byte those of a lone run", started_one_after_the_other)
    table.check("concurrent", "two renders of different scenes started at the same instant",
                "one exits 0, the other 2 naming the owner (or both 0 if they did not overlap); "
                "the folder holds one scene's frames, GIF and sheet byte for byte, and its report",
                started_together)
    table.check("concurrent", "a lock left by a dead PID", "taken over with a note; exit 0; "
                "no lock left", dead_lock)
