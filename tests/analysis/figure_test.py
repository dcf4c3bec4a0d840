"""The figure tests' base (test_plots_*.py): a figure drawn into a fresh folder as the report
draws it, kept open to be read back."""
from unittest import mock

import matplotlib.pyplot as plt

from runfolder import RunFolderTest  # puts analysis/ on the path
from drapeanalysis import style  # noqa: E402


class FigureTest(RunFolderTest):
    def drawn(self, make):
        """(stem, figure) of make(out_dir), the figure saved as the report saves it (log ticks,
        layout) but kept open for the test."""
        kept = []
        out = self.directory / "report"
        out.mkdir(exist_ok=True)
        with mock.patch.object(style.plt, "close", kept.append):
            stem = make(out)
        self.addCleanup(plt.close, "all")
        return stem, (kept[0] if kept else None)


def texts(fig):
    return [t.get_text() for ax in fig.axes for t in ax.texts]
