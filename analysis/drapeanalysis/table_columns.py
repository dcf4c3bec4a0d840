"""The report's runs table: its metric columns and the units it shows them in (docs/analysis.md
defines each metric; metrics.csv keeps every length in m, every time in s; the tables show
lengths in mm, as the summary and the figures do: cloth errors and vibrations are millimetres)."""

# Columns of the report's table besides the parameters; every column is in metrics.csv.
TABLE_COLUMNS = (
    "status", "sim_time", "reason", "steps", "rhs_evals", "wall_seconds", "cpu_seconds",
    "energy_drift_max_rel", "energy_drift_final_rel", "energy_drift_exponent", "attach_error_mean", "vibration_rms_final",
    "vibration_rms_events", "vibration_rms_holding", "hand_jitter_rms_holding", "settle_time", "contact_switch_rate_final", "hand_jitter_rms_final",
    "mapping_gap_mean_mapped", "mapping_gap_mean_final", "mapping_gap_max_final",
    "spring_strain_rms_mapped", "spring_strain_rms_final", "spring_strain_max_final",
    "restart_error_start", "restart_error_events", "short_error_start", "short_error_events", "error_rms",
    "error_max", "stable_value", "slow_motion_rms_final", "vibration_cutoff_hz",
)

# Column -> unit; a column not named here is a count, a status or a parameter's own value
# (`stable_value`: the bisected parameter's).
UNITS = {
    "wall_seconds": "s",
    "cpu_seconds": "s",
    "sim_time": "s",
    "energy_drift_max_rel": "of E(0)",
    "energy_drift_final_rel": "of E(0)",
    "energy_drift_exponent": "1",
    "attach_error_mean": "mm",
    "vibration_rms_final": "mm",
    "vibration_rms_events": "mm",
    "vibration_rms_holding": "mm",
    "hand_jitter_rms_holding": "mm",
    "hand_jitter_rms_final": "mm",
    "settle_time": "s",
    "contact_switch_rate_final": "1/s",
    "mapping_gap_mean_mapped": "mm",
    "mapping_gap_mean_final": "mm",
    "mapping_gap_max_final": "mm",
    "spring_strain_rms_mapped": "1",
    "spring_strain_rms_final": "1",
    "spring_strain_max_final": "1",
    "restart_error_start": "mm",
    "restart_error_events": "mm",
    "short_error_start": "mm",
    "short_error_events": "mm",
    "error_rms": "mm",
    "error_max": "mm",
    "slow_motion_rms_final": "mm",
    "vibration_cutoff_hz": "Hz",
    "integrator.dt": "s",
    "duration": "s",
}


# A shown unit -> the factor from the unit metrics.csv keeps (m for every length).
SCALES = {"mm": 1e3}


def shown_value(column, value):
    """A number of metrics.csv's `column` in the unit its heading names."""
    return value * SCALES.get(UNITS.get(column), 1.0)


def heading(column):
    """`column` with its unit in brackets, when it has one."""
    unit = UNITS.get(column)
    return f"{column} [{unit}]" if unit else column
