"""Run every benchmark (`make bench`, or `python -m bench [NAME ...]`), one process each so
that peak-memory figures are not mixed. Results are printed and saved to out/bench.json."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def available() -> list[str]:
    return sorted(p.stem for p in (ROOT / "bench").glob("bench_*.py"))


def main(argv: list[str] | None = None) -> int:
    names = (argv if argv is not None else sys.argv[1:]) or available()
    unknown = sorted(set(names) - set(available()))
    if unknown:
        print(f"unknown benchmark(s): {', '.join(unknown)}; available: {', '.join(available())}",
              file=sys.stderr)
        return 2
    results: dict[str, object] = {}
    failed = 0
    for name in names:
        print(f"== {name}", flush=True)
        started = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", f"bench.{name}"], cwd=ROOT,
                              capture_output=True, text=True)
        sys.stdout.write(proc.stdout)
        sys.stderr.write(proc.stderr)
        if proc.returncode != 0:
            failed += 1
            results[name] = {"error": f"exit status {proc.returncode}"}
            continue
        # The last line that parses as JSON is the benchmark's result.
        for line in reversed(proc.stdout.strip().splitlines()):
            try:
                results[name] = json.loads(line)
                break
            except json.JSONDecodeError:
                continue
        print(f"   ({time.perf_counter() - started:.1f} s)", flush=True)
    out = ROOT / "out" / "bench.json"
    out.parent.mkdir(exist_ok=True)
    out.write_text(json.dumps(results, indent=2), encoding="utf-8")
    print(f"results written to {out.relative_to(ROOT)}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
