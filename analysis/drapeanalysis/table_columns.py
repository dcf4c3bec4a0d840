"""The report's runs table: its metric columns and their units (docs/analysis.md defines each
metric; every length is in m, every time in s)."""

# Columns of the report's table besides the parameters; every column is in metrics.csv.
TABLE_COLUMNS = (
    "status", "sim_time", "reason", "steps", "rhs_evals", "wall_seconds", "energy_drift_max_rel",
    "energy_drift_final_rel", "energy_drift_exponent", "attach_error_mean", "vibration_rms_final",
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
    "sim_time": "s",
    "energy_drift_max_rel": "of E(0)",
    "energy_drift_final_rel": "of E(0)",
    "energy_drift_exponent": "1",
    "attach_error_mean": "m",
    "vibration_rms_final": "m",
    "vibration_rms_events": "m",
    "vibration_rms_holding": "m",
    "hand_jitter_rms_holding": "m",
    "hand_jitter_rms_final": "m",
    "settle_time": "s",
    "contact_switch_rate_final": "1/s",
    "mapping_gap_mean_mapped": "m",
    "mapping_gap_mean_final": "m",
    "mapping_gap_max_final": "m",
    "spring_strain_rms_mapped": "1",
    "spring_strain_rms_final": "1",
    "spring_strain_max_final": "1",
    "restart_error_start": "m",
    "restart_error_events": "m",
    "short_error_start": "m",
    "short_error_events": "m",
    "error_rms": "m",
    "error_max": "m",
    "slow_motion_rms_final": "m",
    "vibration_cutoff_hz": "Hz",
    "integrator.dt": "s",
    "duration": "s",
}


def heading(column):
    """`column` with its unit in brackets, when it has one."""
    unit = UNITS.get(column)
    return f"{column} [{unit}]" if unit else column
