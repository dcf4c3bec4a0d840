"""The order integrators take their colours in (style.declare_integrators): the registry's, as
`drapelab integrators --json` lists the declarations, so that leapfrog .. arkode-imex keep
tab10's first six colours and a new integrator takes the next; without a drapelab that lists
them (none given, an older build, an error), the table's integrator names sorted, a
deterministic order for the same table."""
import json
import subprocess


def declared_integrators(drapelab):
    """The integrator names `drapelab integrators --json` prints, in registry order; [] when
    `drapelab` is None or does not list them."""
    if drapelab is None:
        return []
    try:
        done = subprocess.run([str(drapelab), "integrators", "--json"], capture_output=True, text=True,
                              timeout=30, check=True)
        return [d["name"] for d in json.loads(done.stdout) if isinstance(d.get("name"), str)]
    except (OSError, subprocess.SubprocessError, ValueError, TypeError, AttributeError):
        return []


def integrator_order(drapelab, rows):
    """The declared integrators, then the table's other integrator names sorted."""
    declared = declared_integrators(drapelab)
    rest = sorted({str(row["integrator"]) for row in rows if row.get("integrator")} - set(declared))
    return declared + rest
