#!/usr/bin/env python3
"""Summary and failure catalogue of bench/eval/run_sets.sh (issue 15).

Usage: bench/eval/summarise.py <sets> <results> [set ...] > summary.md
Also writes <results>/cases.jsonl: one line per (set, input, domain) with every figure used here.

A case is one (input, domain) of a set. End to end it is
  - "input failed"        the input never became a tet mesh (TetGen, decimation, checks): 6 cases;
  - "surface-map failed"  volmap-dataset (or volmap-surface-map for g1sphere) dropped that domain;
  - "volume certified"    volmap-run's exact re-check passed on what volmap-map wrote;
  - "volume not certified" otherwise.
Growth: "volume growth" = volmap-map output tets / the set's mesh tets - 1 (volmap-run's figure);
"total growth" = output tets / the tets before any surface-map split - 1 (TetGen's count for the
dataset-made sets, the G1 mesh for g1sphere), i.e. surface-map splits included as issue 15 asks.
Sphere maps are also checked without options (kernel = centroid of the boundary image): a
certified case whose sphere map fails that check is not counted as certified in "strict".
"""
import glob
import json
import os
import statistics
import sys

DOMAINS = ["cube", "tet", "pyr", "octa", "star", "sphere"]


def load_json(path, default=None):
    try:
        with open(path) as f:
            return json.load(f)
    except Exception:
        return default


def jsonl(path):
    out = []
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                try:
                    out.append(json.loads(line))
                except Exception:
                    pass
    return out


def medit_tets(path):
    """Tet count of a Medit file (keyword and count on separate lines, or on one line)."""
    try:
        with open(path) as f:
            for line in f:
                t = line.split()
                if t and t[0] == "Tetrahedra":
                    return int(t[1]) if len(t) > 1 else int(next(f).split()[0])
    except Exception:
        pass
    return None


def first_line(path):
    try:
        with open(path) as f:
            return next((l.strip() for l in f if l.strip()), "")
    except Exception:
        return ""


def inputs_of(sets_dir, name):
    """{(group, mesh name): {...}} from the set's logs: original tets, failed domains, input failure."""
    root = os.path.join(sets_dir, name)
    inputs = {}
    if name == "g1sphere":
        for mesh in sorted(glob.glob(os.path.join(root, "G1", "*.mesh"))):
            n = os.path.basename(mesh)[:-5]
            tets = medit_tets(mesh)
            log = load_json(os.path.join(root, "logs", "sphere_%s.json" % n), {})
            err = first_line(os.path.join(root, "logs", "sphere_%s.err" % n))
            refined = os.path.exists(os.path.join(root, "G2", n + ".mesh"))
            failed = {}
            if not log.get("ok", False):
                failed["sphere"] = err or log.get("error", "volmap-surface-map failed")
            inputs[("G1", n)] = {"original_tets": tets, "failed": failed, "input_failure": "",
                                 "sphere_group": "G2" if refined else "G1", "faces": None, "decimated": 0}
        return inputs
    for log in sorted(glob.glob(os.path.join(root, "logs", "*.json"))):
        base = os.path.basename(log)
        if base.startswith("sphere_"):
            continue
        group = base.split("_", 1)[0]
        d = load_json(log, {})
        for s in d.get("surfaces", []):
            failed = {f["domain"]: f["reason"] for f in s.get("failed_domains", [])}
            inputs[(group, s["name"])] = {
                "original_tets": s.get("tetgen_tets") or None, "failed": failed,
                "input_failure": "" if s.get("added") else s.get("reason", "?"),
                "faces": s.get("faces"), "decimated": s.get("decimated_faces", 0), "sphere_group": group,
                "set_tets": s.get("tets")}
    return inputs


def candidate_json(results_dir, group, name, dom):
    return load_json(os.path.join(results_dir, "cases", "map", group, "%s_%s" % (name, dom), "candidate.out"), {}) or {}


def stage_trail(cand):
    """'name:bad' per stage (the first 4 and the last 6 when longer), and the fewest bad tets seen."""
    st = [(s.get("name"), s.get("nonpositive_after")) for s in cand.get("stages", [])]
    if not st:
        return ""
    shown = st if len(st) <= 10 else st[:4] + [("...", len(st) - 10)] + st[-6:]
    fewest = min((b for n, b in st if isinstance(b, int) and n not in ("feasibility", "chord-split")), default=None)
    text = " ".join("(%d more)" % b if n == "..." else "%s:%s" % (n, b) for n, b in shown)
    return text + ("; fewest %s" % fewest if fewest is not None else "")


def collect(sets_dir, results_dir, name):
    """One dict per case of the set."""
    root = os.path.join(sets_dir, name)
    res = os.path.join(results_dir, name)
    inputs = inputs_of(sets_dir, name)
    records = {r["case"]: r for r in jsonl(os.path.join(res, "results.jsonl")) if r.get("label", "map") == "map"}
    spheres = {c["case"]: c for c in jsonl(os.path.join(res, "sphere_checks.jsonl"))}
    alone = {(c["group"], c["name"], c["domain"]): c for c in jsonl(os.path.join(res, "surface_standalone.jsonl"))}
    cases = []
    for (group, n), info in sorted(inputs.items()):
        for dom in DOMAINS:
            g = info["sphere_group"] if dom == "sphere" else group
            case = {"set": name, "case": "%s/%s_%s" % (g, n, dom), "group": g, "name": n, "domain": dom,
                    "mesh": os.path.join(root, g, n + ".mesh"),
                    "map": os.path.join(root, "%s_%s" % (g, dom), "%s_%s.txt" % (n, dom)),
                    "original_tets": info["original_tets"], "faces": info.get("faces"),
                    "set_tets": info.get("set_tets") if g == group else None,
                    "decimated_faces": info.get("decimated")}
            if info["input_failure"] and not os.path.exists(case["mesh"]):
                case["status"] = "input failed"
                case["reason"] = info["input_failure"]
            elif dom in info["failed"] or not os.path.exists(case["map"]):
                case["status"] = "surface-map failed"
                case["reason"] = info["failed"].get(dom, "no map")
                kept = os.path.join(root, group + "_failed", "%s_%s.mesh" % (n, dom))
                case["mesh"] = kept if os.path.exists(kept) else None
                case["map"] = None
                case["failed_mesh_tets"] = medit_tets(kept) if os.path.exists(kept) else None
            else:
                r = records.get(case["case"])
                if r is None:
                    case["status"] = "not run"
                else:
                    cand = candidate_json(res, g, n, dom)
                    case.update({
                        "status": "volume certified" if r.get("certified") else "volume not certified",
                        "tets_in": r.get("tets_in"), "tets_out": r.get("tets_out"), "time_s": r.get("time_s"),
                        "cpu_s": r.get("cpu_s") if (r.get("cpu_s") or -1) >= 0 else None,
                        "exit_code": r.get("exit_code"), "timed_out": r.get("timed_out"),
                        "bad_tets": (r.get("negative", 0) or 0) + (r.get("zero", 0) or 0)
                        if (r.get("negative", -1) or 0) >= 0 else None,
                        "volume_growth": (r["tets_out"] / r["tets_in"] - 1) if r.get("tets_in", 0) > 0 and r.get("tets_out", 0) > 0 else None,
                        "certified_by": r.get("certified_by") or cand.get("certified_by"),
                        "failure": r.get("failure", ""), "stages": stage_trail(cand),
                        "stderr": first_line(os.path.join(res, "cases", "map", g, "%s_%s" % (n, dom), "candidate.err")),
                    })
                    if case["original_tets"] and r.get("tets_out", 0) > 0:
                        case["total_growth"] = r["tets_out"] / case["original_tets"] - 1
                    elif case["original_tets"] and case.get("tets_in"):
                        case["total_growth"] = None
            a = alone.get((group, n, dom))
            if a is not None:
                case["alone_exit"] = a["exit_code"]
                case["alone_error"] = a.get("error", "")
                if a["exit_code"] == 0 and a.get("tets") and info["original_tets"]:
                    case["alone_split_growth"] = a["tets"] / info["original_tets"] - 1
                    if case.get("volume_growth") is not None:
                        case["total_growth_alone_estimate"] = (1 + case["alone_split_growth"]) * (1 + case["volume_growth"]) - 1
            if dom == "sphere" and case["case"] in spheres:
                sc = spheres[case["case"]]
                case["sphere_plain_ok"] = bool(sc["plain"].get("ok"))
                case["sphere_plain_negative"] = sc["plain"].get("negative", 0) + sc["plain"].get("zero", 0)
                case["sphere_domain_ok"] = bool(sc["domain"].get("ok"))
            cases.append(case)
    return cases


def median_max(values):
    values = [v for v in values if v is not None]
    if not values:
        return "-"
    return values, statistics.median(values), max(values)


def pct(x):
    return "%.1f %%" % (100 * x)


def set_summary(name, cases):
    total = len(cases)
    by = lambda s: [c for c in cases if c["status"] == s]
    cert = by("volume certified")
    strict = [c for c in cert if c.get("sphere_plain_ok", True)]
    inputs = len({(c["group"] if c["domain"] != "sphere" else c["case"].split("/")[0], c["name"]) for c in cases if c["domain"] == "cube"})
    lines = ["### %s" % name, "",
             "%d inputs, %d cases (inputs x 6 domains)." % (inputs, total), "",
             "| | cases | % |", "|:--|--:|--:|"]
    for label, group in [("certified end to end", cert), ("  of which the sphere map fails the plain check", [c for c in cert if c.get("sphere_plain_ok") is False]),
                         ("certified, strict (sphere maps pass the plain check)", strict),
                         ("input failed (TetGen / checks)", by("input failed")),
                         ("surface-map failed", by("surface-map failed")), ("volume not certified", by("volume not certified")),
                         ("not run", by("not run"))]:
        lines.append("| %s | %d | %s |" % (label, len(group), pct(len(group) / total) if total else "-"))
    vg = [c["volume_growth"] for c in cert if c.get("volume_growth") is not None]
    tg = [c["total_growth"] for c in cert if c.get("total_growth") is not None]
    ts = [c["time_s"] for c in cases if c.get("time_s") is not None]
    sg = [c["alone_split_growth"] for c in cases if c.get("alone_split_growth") is not None]
    te = [c["total_growth_alone_estimate"] for c in cert if c.get("total_growth_alone_estimate") is not None]
    shared = {}
    for c in cases:
        if c.get("tets_in") and c.get("original_tets"):
            shared[(c["group"], c["name"])] = c["tets_in"] / c["original_tets"] - 1
    lines.append("")
    if shared:
        v = list(shared.values())
        lines.append("Surface-map splits on the shared mesh (all domains' splits on one mesh, as published): median %s / max %s over %d meshes." % (
            pct(statistics.median(v)), pct(max(v)), len(v)))
    if sg:
        lines.append("Surface-map splits per domain alone (each domain mapped alone on the unrefined mesh): median %s / max %s; %d of %d standalone surface maps failed." % (
            pct(statistics.median(sg)), pct(max(sg)), sum(c.get("alone_exit", 0) != 0 for c in cases if "alone_exit" in c),
            sum("alone_exit" in c for c in cases)))
    if vg:
        lines.append("Certified: volume growth median %s / max %s; total growth (shared-mesh surface splits included) median %s / max %s%s." % (
            pct(statistics.median(vg)), pct(max(vg)), pct(statistics.median(tg)) if tg else "-", pct(max(tg)) if tg else "-",
            "; estimated with per-domain splits only median %s / max %s" % (pct(statistics.median(te)), pct(max(te))) if te else ""))
    if ts:
        lines.append("Time (volmap-map wall clock, all run cases): median %.2f s / max %.2f s; %d cases over 10 s, %d over 60 s." % (
            statistics.median(ts), max(ts), sum(t > 10 for t in ts), sum(t > 60 for t in ts)))
    cpu = [c["cpu_s"] for c in cases if c.get("cpu_s") is not None]
    if cpu:
        lines.append("CPU time (user + system, %d cases): median %.2f s / max %.2f s; CPU / wall median %.2f (the machine's load)." % (
            len(cpu), statistics.median(cpu), max(cpu),
            statistics.median([c["cpu_s"] / c["time_s"] for c in cases if c.get("cpu_s") is not None and c.get("time_s")])))
    per_dom = ["", "| domain | cases | certified | surface-map failed | volume not certified |", "|:--|--:|--:|--:|--:|"]
    for dom in DOMAINS:
        dc = [c for c in cases if c["domain"] == dom]
        per_dom.append("| %s | %d | %d | %d | %d |" % (dom, len(dc), sum(c["status"] == "volume certified" for c in dc),
                                                     sum(c["status"] in ("surface-map failed", "input failed") for c in dc),
                                                     sum(c["status"] == "volume not certified" for c in dc)))
    return lines + per_dom + [""]


def size_of(c):
    for key in ("tets_in", "set_tets", "failed_mesh_tets", "original_tets"):
        if (c.get(key) or 0) > 0:
            return c[key]
    return 10 ** 12


def catalogue(cases, limit=3):
    classes = [
        ("Arc tracing failures (volmap-surface-map: cannot trace arc)",
         lambda c: c["status"] == "surface-map failed" and "cannot trace arc" in c.get("reason", "")),
        ("Other surface-map failures",
         lambda c: c["status"] == "surface-map failed" and "cannot trace arc" not in c.get("reason", "")),
        ("Inputs that never became a tet mesh", lambda c: c["status"] == "input failed" and c["domain"] == "cube"),
        ("Sphere maps failing the plain volmap-surface-map-check (pass with --domain sphere)",
         lambda c: c.get("sphere_plain_ok") is False and c.get("sphere_domain_ok")),
        ("Volume maps left with bad tets (not certified, output written)",
         lambda c: c["status"] == "volume not certified" and (c.get("bad_tets") or 0) > 0),
        ("Bad-input errors (exit 2) from valid inputs",
         lambda c: c["status"] == "volume not certified" and c.get("exit_code") == 2),
        ("Other volume failures (timeout, crash, no output)",
         lambda c: c["status"] == "volume not certified" and not (c.get("bad_tets") or 0) > 0 and c.get("exit_code") != 2),
        ("Certified with volume growth > 25 %", lambda c: c["status"] == "volume certified" and (c.get("volume_growth") or 0) > 0.25),
        ("Certified with total growth (surface-map splits included) > 25 %",
         lambda c: c["status"] == "volume certified" and (c.get("total_growth") or 0) > 0.25),
        ("Time > 60 s", lambda c: (c.get("time_s") or 0) > 60),
    ]
    lines = []
    for title, pred in classes:
        hits = sorted([c for c in cases if pred(c)], key=lambda c: (size_of(c), c["case"]))
        per_set = {}
        for c in hits:
            per_set[c["set"]] = per_set.get(c["set"], 0) + 1
        lines.append("#### %s: %d%s" % (title, len(hits), " (" + ", ".join("%s %d" % kv for kv in per_set.items()) + ")" if per_set else ""))
        if not hits:
            lines.append("")
            continue
        lines.append("")
        for c in hits[:limit]:
            detail = []
            if size_of(c) < 10 ** 12:
                detail.append("%d tets" % size_of(c))
            if c.get("bad_tets"):
                detail.append("%d bad tets" % c["bad_tets"])
            if c.get("sphere_plain_negative"):
                detail.append("%d triangles inverted about the centroid" % c["sphere_plain_negative"])
            if c.get("volume_growth") is not None and "growth" in title:
                detail.append("volume growth %s, total %s" % (pct(c["volume_growth"]), pct(c.get("total_growth") or 0)))
            if c.get("time_s") is not None and ("Time" in title or "Volume" in title or "volume" in title):
                detail.append("%.1f s" % c["time_s"] + (" wall, %.1f s CPU" % c["cpu_s"] if c.get("cpu_s") is not None else ""))
            lines.append("- `%s/%s` (%s)" % (c["set"], c["case"], ", ".join(detail)))
            lines.append("  - mesh `%s`%s" % (c.get("mesh"), ", map `%s`" % c["map"] if c.get("map") else ""))
            why = c.get("reason") or c.get("stderr") or c.get("failure")
            if why:
                lines.append("  - %s" % why[:400].replace("\n", " "))
            if c.get("stages") and c["status"] == "volume not certified":
                lines.append("  - stages (non-positive tets after each): %s" % c["stages"])
        others = ["%s/%s" % (c["set"], c["case"]) for c in hits[limit:]]
        if others:
            lines.append("- also: " + ", ".join(others[:40]) + (" ..." if len(others) > 40 else ""))
        lines.append("")
    return lines


def maps_summary(results_dir):
    rows = jsonl(os.path.join(results_dir, "maps", "results.jsonl"))
    if not rows:
        return []
    lines = ["### maps (initial maps: volmap-map --initial)", "",
             "| case | tets in | certified (re-check) | exit | bad tets left | tets out | growth | time (s) | note |",
             "|:--|--:|:--|--:|--:|--:|--:|--:|:--|"]
    for r in rows:
        m, ch = r.get("map", {}), r.get("check", {})
        ok = bool(ch.get("certified")) and ch.get("exit_code", 1) == 0
        bad = (ch.get("output", {}).get("zero", 0) or 0) + (ch.get("output", {}).get("negative", 0) or 0) if ch else "-"
        note = r.get("note") or (r.get("stderr") if r.get("exit_code") not in (0, "0") else "") or ""
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["name"], m.get("input_tets", "-"), "yes" if ok else "no", r.get("exit_code"), bad,
            m.get("output_tets", "-"), pct(m["growth"]) if "growth" in m else "-",
            "%.2f" % m["seconds"] if "seconds" in m else (r.get("wall_s") or "-"), note[:160]))
    return lines + [""]


def main():
    sets_dir, results_dir = sys.argv[1], sys.argv[2]
    names = sys.argv[3:] or ["thin", "thin_coarse", "coarse", "g1sphere", "tetmeshes", "surfaces"]
    all_cases = []
    out = []
    for name in names:
        if name == "maps":
            continue
        if not os.path.isdir(os.path.join(sets_dir, name)):
            continue
        cases = collect(sets_dir, results_dir, name)
        all_cases += cases
        out += set_summary(name, cases)
        table = os.path.join(results_dir, name, "table.md")
        if os.path.exists(table):
            out.append("<details><summary>volmap-run table (%s)</summary>\n" % table)
            with open(table) as f:
                out.append(f.read().replace("\n### ", "\n##### "))
            out.append("</details>\n")
    out += maps_summary(results_dir)
    out += ["## Failure catalogue (all sets; smallest cases first)", ""]
    out += catalogue(all_cases)
    with open(os.path.join(results_dir, "cases.jsonl"), "w") as f:
        for c in all_cases:
            f.write(json.dumps(c) + "\n")
    print("\n".join(out))


if __name__ == "__main__":
    main()
