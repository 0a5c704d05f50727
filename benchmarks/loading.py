"""Measure where reading and checking a large library goes, stage by stage (in-process).

Issue 12's goal is 1000 roles x 10 candidates (2.8 MB of YAML, 11 files) read and checked in
at most 1 s. Each run is a fresh child (``--child FOLDER``) that times, in CPU seconds of
that process (``time.process_time``), every stage the loader runs (``loader.load_sources``,
what every command takes): YAML into plain data and its positions table (libyaml's event
stream read once by ``yamlsource``, rosreconf's one reader, for every file), the JSON Schema check
(jsonschema-rs), the value checks, model building, the semantic checks. Imports are excluded
(the whole-process rows of ``run.py`` include them).

``python benchmarks/loading.py --json benchmarks/results.json`` measures and replaces the
``loading`` entry of the results; ``run.py`` calls ``loading`` in a full run.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

STAGES = ("read", "parse", "structure", "values", "build", "check")


def child(folder: str) -> dict[str, float]:
    """Load ``folder``'s libraries and schemas once, timing each stage (this process's CPU).

    As the loader does (``loader._load_one``): every file read once by ``yamlsource.read``.
    """
    import gc

    from rosreconf.formats import loader
    from rosreconf.formats import yamlsource as ys
    from rosreconf.formats.build import build_library, build_schema
    from rosreconf.formats.checks import check
    from rosreconf.formats.structure import DocumentKind, kind_of, structure_problems
    from rosreconf.formats.values import duplicate_edges, value_problems

    d = Path(folder)
    seconds = dict.fromkeys(STAGES, 0.0)
    clock = time.process_time
    gc.disable()  # as the loader does (rosreconf.gcpause.paused_gc)
    t = clock()
    sources = loader.read_sources(loader.discover([d / "libraries", d / "schemas"]))
    seconds["read"] = clock() - t
    libraries, schemas = [], []
    interfaces: dict[Any, Any] = {}  # shared by the library files, as the loader shares it
    for src in sources:
        t = clock()
        tree, plain = ys.read(src.data, src.name)
        seconds["parse"] += clock() - t
        assert tree is not None, f"{src.name}: empty"
        t = clock()
        kind = kind_of(plain)
        assert kind is not None, f"{src.name}: format"
        library = kind is DocumentKind.LIBRARY
        assert not structure_problems(tree, kind, plain), f"{src.name}: structure"
        seconds["structure"] += clock() - t
        t = clock()
        found = value_problems(tree, plain) if library else duplicate_edges(tree, plain)
        assert not found, f"{src.name}: a value problem"
        seconds["values"] += clock() - t
        t = clock()
        if library:
            libraries.append(build_library(plain, src.name, lambda tree=tree: tree, interfaces))
        else:
            schemas.append(build_schema(plain, tree, src.name))
        seconds["build"] += clock() - t
    t = clock()
    problems = check(libraries, schemas, library_complete=True)
    seconds["check"] = clock() - t
    assert not problems, problems[:3]
    seconds["total"] = sum(seconds[s] for s in STAGES)

    seconds["bytes"] = float(sum(len(s.data) for s in sources))
    seconds["libyaml_reader"] = float(ys.BASE_LOADER.__name__ == "CSafeLoader")
    seconds.update(floors([s.data for s in sources]))
    return seconds


FLOORS = ("libyaml", "compose")


def floors(texts: list[bytes]) -> dict[str, float]:
    """Time what a reader over PyYAML's C binding pays before rosreconf's own work.

    ``libyaml``: libyaml parsing the texts with no Python object per event
    (``CParser.raw_parse``); ``compose``: PyYAML's ``yaml.compose`` over libyaml with its own
    (YAML 1.1) resolver: the positioned tree alone, without rosreconf's rules or plain data.
    """
    import yaml

    clock = time.process_time
    t = clock()
    for text in texts:
        yaml.CSafeLoader(text).raw_parse()
    raw = clock() - t
    t = clock()
    for text in texts:
        yaml.compose(text, Loader=yaml.CSafeLoader)
    return {"libyaml": raw, "compose": clock() - t}


def loading(folder: Path, runs: int) -> dict[str, Any]:
    """Return the median CPU seconds of each stage over ``runs`` fresh children."""
    results = []
    load_start = os.getloadavg()
    for _ in range(runs):
        cmd = [sys.executable, str(Path(__file__)), "--child", str(folder)]
        out = subprocess.run(cmd, capture_output=True, text=True, check=True, timeout=600)
        results.append(json.loads(out.stdout))
    medians = {k: statistics.median(r[k] for r in results) for k in (*STAGES, "total")}
    return {
        "scope": "in-process",
        "clock": "CPU seconds of the child (time.process_time), imports excluded",
        "runs": runs,
        "bytes": int(results[0]["bytes"]),
        "seconds": medians,
        "floor_seconds": {k: statistics.median(r[k] for r in results) for k in FLOORS},
        "floors": ("libyaml: CParser.raw_parse (no Python objects); compose: yaml.compose"),
        "reader": (
            "every file: libyaml's event stream (yaml.CSafeLoader) into YAML 1.2 plain data "
            "and a positions table"
            if all(r["libyaml_reader"] for r in results)
            else "PyYAML's pure-Python event parser (no libyaml)"
        ),
        "goal_seconds": 1.0,
        "met": medians["total"] <= 1.0,
        "load_average": {"start": list(load_start), "end": list(os.getloadavg())},
    }


def markdown(doc: dict[str, Any]) -> str:
    """Render a ``loading`` entry as a Markdown table (one row per stage)."""
    s = doc["seconds"]
    rows = ["| stage (in-process, CPU s) | " + " | ".join(STAGES) + " | total |"]
    rows.append("| --- " * (len(STAGES) + 2) + "|")
    rows.append(
        f"| {doc['instance']} ({doc['bytes'] / 1e6:.1f} MB) | "
        + " | ".join(f"{s[k]:.3f}" for k in STAGES)
        + f" | {s['total']:.3f} |"
    )
    return "\n".join(rows)


def main() -> None:
    """Measure the loading stages on a generated library and update the results' entry."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--child")
    ap.add_argument("--json", type=Path, default=Path(__file__).resolve().parent / "results.json")
    ap.add_argument("--roles", type=int, default=1000)
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    if args.child:
        print(json.dumps(child(args.child)))
        return
    run = Path(__file__).resolve().parent / "run.py"
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "lib"
        split = [sys.executable, str(run), "--child", f"split:{args.roles}x10", str(folder)]
        subprocess.run(split, check=True, capture_output=True)
        result = loading(folder, args.runs)
    result["instance"] = f"{args.roles} x 10"
    doc = json.loads(args.json.read_text(encoding="utf-8")) if args.json.exists() else {}
    doc["loading"] = result
    args.json.write_text(json.dumps(doc, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    print(markdown(result))


if __name__ == "__main__":
    main()
