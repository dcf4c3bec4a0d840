"""The report's 3-D viewer pages (docs/analysis.md, Viewer pages): one `drapelab view` page per
run that has frames, and per scene one page with an explicit and an implicit run side by side,
each written by the drapelab program itself (docs/viewer.md), so the report and `drapelab view`
show a run alike."""
import subprocess

from . import plots, runfiles
from .fileio import OutputError, output_folder

# drapelab's exit status for an output it could not write (README, exit status).
WRITE_FAILED = 4

# Integrators that solve for the new state (docs/integrators/README.md); the rest step
# explicitly.
IMPLICIT = ("implicit-euler", "arkode-dirk", "arkode-imex")
# Preferred order within each kind: the paper's leap-frog first, then the cheapest implicit one.
PREFERENCE = ("leapfrog", "symplectic-euler", "arkode-erk", "implicit-euler", "arkode-dirk", "arkode-imex")


def missing_frames(directory, row):
    """Why a run gets no page (None when it gets one): the viewer plays trace.csv."""
    run = runfiles.run_dir(directory, row)
    if not (run / "summary.json").exists():
        return f"no page: the run did not finish (status {row.get('status', '?')})"
    if not (run / "trace.csv").exists():
        return "no page: no trace.csv (output.trace_interval = 0)"
    return None


def _rank(row):
    name = row.get("integrator", "")
    return (PREFERENCE.index(name) if name in PREFERENCE else len(PREFERENCE), plots.step(row))


def side_by_side(rows):
    """The runs of one scene's comparison page: the preferred explicit and implicit runs at
    their smallest steps; without both kinds, the reference (or finest run) and the next
    finest; nothing for a single run."""
    methods = sorted((r for r in rows if not r.get("is_reference")), key=_rank)
    explicit = [r for r in methods if r.get("integrator") not in IMPLICIT]
    implicit = [r for r in methods if r.get("integrator") in IMPLICIT]
    if explicit and implicit:
        return [explicit[0], implicit[0]]
    ranked = sorted(rows, key=lambda r: (not r.get("is_reference"), plots.step(r)))
    return ranked[:2] if len(ranked) >= 2 else []


def _view(drapelab, directory, chosen, page):
    """Runs `drapelab view`; None when written, else its error (a malformed file of one run must
    not stop the report). A page it could not write is an OutputError: the report would look
    whole with a page missing for want of disk."""
    args = [drapelab, "view", *(str(runfiles.run_dir(directory, r)) for r in chosen), "--out", str(page)]
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode:
        lines = (done.stderr or done.stdout).strip().splitlines()
        words = lines[-1] if lines else f"exit {done.returncode}"
        if done.returncode == WRITE_FAILED:
            raise OutputError(f"{page}: drapelab view failed ({words})")
        return f"no page: drapelab view failed ({words})"
    return None


def write_pages(directory, out_dir, rows, drapelab):
    """Writes out_dir/view/RUN_ID.html per run with frames and out_dir/view/scenes/SCENE.html per scene
    with two such runs. Returns (links, notes, scenes): run id -> page path relative to out_dir,
    run id -> why it has none, scene -> (page path, the runs shown)."""
    view_dir = output_folder(out_dir / "view")
    links, notes, by_scene = {}, {}, {}
    for row in rows:
        note = missing_frames(directory, row)
        page = view_dir / f"{row['id']}.html"
        note = note or _view(drapelab, directory, [row], page)
        if note:
            notes[row["id"]] = note
        else:
            links[row["id"]] = f"view/{page.name}"
            by_scene.setdefault(plots.scene_name(row), []).append(row)
    scenes = {}
    for scene, scene_rows in by_scene.items():
        chosen = side_by_side(scene_rows)
        page = view_dir / "scenes" / f"{scene}.html"
        if chosen and not _view(drapelab, directory, chosen, page):
            scenes[scene] = (f"view/scenes/{page.name}", chosen)
    return links, notes, scenes
