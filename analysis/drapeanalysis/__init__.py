"""drapelab analysis: metrics, plots and reports over the files runs write (docs/outputs.md).

    import drapeanalysis
    drapeanalysis.vibration_rms(t, x, cutoff_hz)      # motion above the cutoff [m]
    drapeanalysis.vibration_cutoff(summary)            # the cutoff from a run's model [Hz]
    drapeanalysis.summarise(df, ["integrator"], ["vibration_rms_final"])

New code imports it as drapelab.analysis, the same module (docs/python.md); the name
drapeanalysis stays for the scripts and tests that use it.
"""
from .results_file import results_table
from .runfiles import (read_energy, read_hands, read_json, read_state, read_summary, read_table,
                       read_trace, trace_frames)
from .spectral import (model_frequencies, slow_motion_rms, split_motion, vibration_cutoff,
                       vibration_rms)
from .stats import summarise, t_quantile

__all__ = ["read_energy", "read_hands", "read_json", "read_state", "read_summary", "read_table",
           "read_trace", "results_table", "trace_frames", "model_frequencies", "slow_motion_rms",
           "split_motion", "vibration_cutoff", "vibration_rms", "summarise", "t_quantile"]
