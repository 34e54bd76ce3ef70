"""Render every page of the panel in demo mode at 1280x800 and 1920x1080, in English and
Turkish, into ``resources/screenshots/all/`` (the README's gallery):

    python -m tools.screenshots [--out DIR] [--jobs N]

Each picture is the real panel (``cnc-panel --demo --screenshot``), the Auto page after the
demo program has run a few seconds (backplot, spindle and tool showing). The test suite checks
the same pages and sizes for clipping (``tests/app/test_pages.py``).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from app.pages import PAGE_NAMES

ROOT = Path(__file__).resolve().parent.parent
SIZES = ("1280x800", "1920x1080")
LANGUAGES = ("en", "tr")


def shoot(page: str, size: str, language: str, out: Path) -> str:
    target = out / f"{page}_{size}_{language}.png"
    with tempfile.TemporaryDirectory(prefix="cnc-shot-") as state:
        args = [sys.executable, "-m", "app", "--demo", "--page", page, "--size", size, "--lang", language,
                "--state-dir", state, "--screenshot", str(target)]
        if page == "auto":
            args += ["--run-for", "8"]
        env = dict(os.environ, QT_QPA_PLATFORM=os.environ.get("QT_QPA_PLATFORM", "offscreen"))
        done = subprocess.run(args, cwd=ROOT, env=env, capture_output=True, text=True, timeout=120)
    if done.returncode != 0:
        raise RuntimeError(f"{target.name}: {done.stderr.strip()}")
    return target.name


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m tools.screenshots", description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(ROOT / "resources" / "screenshots" / "all"))
    p.add_argument("--jobs", type=int, default=2)
    args = p.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    work = [(page, size, lang) for page in PAGE_NAMES for size in SIZES for lang in LANGUAGES]
    with ThreadPoolExecutor(max_workers=max(args.jobs, 1)) as pool:
        for name in pool.map(lambda w: shoot(*w, out), work):
            print(name)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
