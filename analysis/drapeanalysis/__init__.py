"""drapelab analysis: metrics, plots and reports over the files runs write (docs/outputs.md)."""
