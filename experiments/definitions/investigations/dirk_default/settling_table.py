"""Whether each run of a dirk_default experiment settles (docs/findings/dirk_default.md): per
table and start, at time T (default: the end), the energy above the equilibrium, estimated by
the leap-frog reference's energy at its end, and the kinetic energy; the largest total energy
above the start over the whole run; how many runs settled (both within 1 % of the start's energy
above the equilibrium); Newton iterations and wall time; each as mean +- 95 % interval (n),
from the experiment's results.csv and each run's energy.csv.

    PYTHONPATH=analysis /usr/bin/python3 \\
        experiments/definitions/investigations/dirk_default/settling_table.py OUT [T]

Prints a Markdown table."""
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from drapeanalysis.stats import t_quantile


SETTLED = 0.01  # of the start's energy above the equilibrium


def run_energies(run_dir, at=None):
    """(total at the start, total and kinetic at the last row at or before `at` (None: the end),
    largest total above the start) of one run."""
    e = pd.read_csv(Path(run_dir) / "energy.csv")
    row = e.iloc[-1] if at is None else e[e["t"] <= at + 1e-9].iloc[-1]
    return (e["total"].iloc[0], row["total"], row["kinetic"],
            (e["total"] - e["total"].iloc[0]).max())


def interval(values):
    """'mean +- half-width (n)', the half-width Student's 95 %; a single value as it is."""
    v = np.asarray([x for x in values if np.isfinite(x)], dtype=float)
    if len(v) == 0:
        return "-"
    if len(v) == 1:
        return f"{v[0]:.3g} (1)"
    half = t_quantile(0.975, len(v) - 1) * v.std(ddof=1) / np.sqrt(len(v))
    return f"{v.mean():.3g} +- {half:.2g} ({len(v)})"


def main(out, at=None):
    out = Path(out)
    runs = pd.read_csv(out / "results.csv")
    fixed = {"index", "id", "scene", "status", "reason", "is_reference", "reference", "run_dir",
             "perturbation.seed", "integrator"}
    first_metric = list(runs.columns).index("table") if "table" in runs.columns else len(runs.columns)
    params = [c for c in runs.columns[:first_metric] if c not in fixed]
    starts = params
    by_id = runs.set_index("id")
    rows = []
    for _, r in runs[~runs["is_reference"].astype(bool)].iterrows():
        ref = by_id.loc[r["reference"]]
        row = {k: r[k] for k in starts}
        row["table"] = str(r["table"]).replace("ARKODE_", "")
        row["status"] = r["status"]
        row["newton"] = r.get("counters.newton_iters", np.nan)
        row["wall"] = r["wall_seconds"]
        row["settled"] = False
        if r["status"] == "ok" and ref["status"] == "ok":
            start, energy, kinetic, rise = run_energies(out / r["run_dir"], at)
            _, equilibrium, ref_kinetic, _ = run_energies(out / ref["run_dir"])
            bound = SETTLED * (start - equilibrium)
            row.update(above_ref=energy - equilibrium, kinetic=kinetic, rise=rise,
                       ref_kinetic=ref_kinetic,
                       settled=abs(energy - equilibrium) <= bound and kinetic <= bound)
        rows.append(row)
    df = pd.DataFrame(rows)
    when = "the end" if at is None else f"{at:g} s"
    print("| " + " | ".join(starts) + f" | table | ok | settled | E - E_ref at {when} [J] "
          f"| kinetic at {when} [J] | max E - E(0) [J] | Newton its | wall [s] |")
    print("|" + "---|" * (len(starts) + 8))
    for key, g in df.groupby(starts + ["table"], sort=False):
        key = key if isinstance(key, tuple) else (key,)
        ok = (g["status"] == "ok").sum()
        cells = [str(k) for k in key] + [f"{ok}/{len(g)}", f"{int(g['settled'].sum())}/{len(g)}"]
        for col in ("above_ref", "kinetic", "rise", "newton", "wall"):
            cells.append(interval(g[col]) if col in g else "-")
        print("| " + " | ".join(cells) + " |")
    refs = df.groupby(starts)["ref_kinetic"].max() if "ref_kinetic" in df else None
    if refs is not None:
        print("\nleap-frog reference, largest kinetic energy at the end per start [J]:")
        print(refs.to_string())


if __name__ == "__main__":
    main(sys.argv[1], float(sys.argv[2]) if len(sys.argv) > 2 else None)
