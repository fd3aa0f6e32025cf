#!/usr/bin/env python3
"""Every plot in book/figures/ has a recipe, and is what its recipe draws from the CSVs there.

    tools/check_figures.py [--update]

Runs each chapter's recipe (tools/figures_NN.py; the concept diagrams' tools/diagrams_NN.py) into a temporary folder holding a copy of the CSVs, then fails (exit 1)
when an SVG of book/figures/ is made by no recipe, or differs from what its recipe makes now
(a CSV changed and the plots were not redrawn, or a plot was edited by hand). --update
copies the recipes' SVGs into book/figures/.
"""
import filecmp
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FIGURES = ROOT / "book" / "figures"
RECIPES = sorted((ROOT / "tools").glob("figures_[0-9][0-9].py")) + sorted((ROOT / "tools").glob("diagrams_[0-9][0-9].py"))


def main() -> int:
    update = "--update" in sys.argv
    problems = []
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        for csv in FIGURES.glob("*.csv"):
            shutil.copy(csv, out / csv.name)
        for recipe in RECIPES:
            r = subprocess.run([sys.executable, str(recipe), str(out)], capture_output=True, text=True)
            if r.returncode != 0:
                problems.append(f"{recipe.relative_to(ROOT)} failed: {r.stderr.strip()[-500:]}")
        made = {p.name: p for p in out.glob("*.svg")}
        for svg in sorted(FIGURES.glob("*.svg")):
            if svg.name not in made:
                problems.append(f"book/figures/{svg.name} is made by no recipe (tools/figures_NN.py, tools/diagrams_NN.py)")
            elif not filecmp.cmp(svg, made[svg.name], shallow=False):
                if update:
                    shutil.copy(made[svg.name], svg)
                    print(f"updated book/figures/{svg.name}")
                else:
                    problems.append(f"book/figures/{svg.name} differs from what its recipe draws now "
                                    "(run tools/check_figures.py --update)")
        for name in sorted(set(made) - {p.name for p in FIGURES.glob("*.svg")}):
            if update:
                shutil.copy(made[name], FIGURES / name)
                print(f"added book/figures/{name}")
            else:
                problems.append(f"the recipes draw {name}, which book/figures/ does not have")
    for p in problems:
        print(p)
    print(f"{len(RECIPES)} recipes, {len(list(FIGURES.glob('*.svg')))} plots checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
