"""drapelab.analysis: the metrics, plots and reports over run files (docs/analysis.md).

It is the package drapeanalysis under the name new code uses; `import drapeanalysis`, which the
scripts and tests use, keeps working and gives the same module.
"""
import sys

import drapeanalysis

sys.modules[__name__] = drapeanalysis
