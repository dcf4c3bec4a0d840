"""The figures' shared drawing rules (analysis/drapeanalysis/style.py) on synthetic points."""
import math
import unittest

import matplotlib.pyplot as plt
import numpy as np

from drapeanalysis import style


class LogErrorBarTest(unittest.TestCase):
    def bars(self, ax, **kwargs):
        # Two points of one series: the first interval stays above 0, the second reaches it.
        return style.log_errorbar(ax, [1e-3, 1e-2], [2.0, 1.0], [1.0, 3.0], **kwargs)

    def test_an_interval_reaching_zero_ends_in_an_arrow_at_a_tenth_of_its_mean(self):
        fig, ax = plt.subplots()
        ax.set_yscale("log")
        bars = self.bars(ax, dodge=False)
        segments = bars.lines[2][0].get_segments()
        # The first bar spans mean +- half; the second from a tenth of its mean to mean + half.
        np.testing.assert_allclose(segments[0][:, 1], [1.0, 3.0])
        np.testing.assert_allclose(segments[1][:, 1], [0.1, 4.0])
        arrows = [line for line in ax.lines if line.get_marker() == style.ZERO_MARK]
        self.assertEqual(len(arrows), 1)
        np.testing.assert_allclose(arrows[0].get_xydata(), [[1e-2, 0.1]])
        plt.close(fig)

    def test_on_a_linear_axis_the_interval_is_drawn_as_it_is(self):
        fig, ax = plt.subplots()
        bars = self.bars(ax, dodge=False, log_y=False)
        np.testing.assert_allclose(bars.lines[2][0].get_segments()[1][:, 1], [-2.0, 4.0])
        self.assertFalse([line for line in ax.lines if line.get_marker() == style.ZERO_MARK])
        plt.close(fig)

    def test_series_at_the_same_step_are_dodged_symmetrically_on_the_log_axis(self):
        fig, ax = plt.subplots()
        xs = [bar.lines[0].get_xdata()[0] for bar in
              (self.bars(ax, index=k, count=3) for k in range(3))]
        ratios = [math.log10(x / 1e-3) for x in xs]
        np.testing.assert_allclose(ratios, [-0.015, 0.0, 0.015], atol=1e-12)
        plt.close(fig)

    def test_a_single_run_has_no_bar(self):
        fig, ax = plt.subplots()
        bars = style.log_errorbar(ax, [1.0], [2.0], [math.nan], dodge=False)
        np.testing.assert_allclose(bars.lines[2][0].get_segments()[0][:, 1], [2.0, 2.0])
        plt.close(fig)



class LogTicksTest(unittest.TestCase):
    def test_every_value_is_a_labelled_tick_and_nothing_else(self):
        fig, ax = plt.subplots()
        ax.plot([0.0333333, 0.1], [1.0, 2.0])
        style.log_x_ticks_at(ax, [0.0333333, 0.1])
        fig.canvas.draw()
        self.assertEqual([t.get_text() for t in ax.get_xticklabels()], ["0.0333", "0.1"])
        self.assertEqual(len(ax.xaxis.get_minor_ticks()), 0)
        plt.close(fig)



def bar_axes():
    """A 4 x 3 in figure with log axes from 1 to 100 and from 1e-4 to 0.1."""
    fig, ax = plt.subplots(figsize=(4, 3))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(1, 100)
    ax.set_ylim(1e-4, 1e-1)
    return fig, ax


class PlaceLabelsTest(unittest.TestCase):
    def test_labels_placed_apart_stay_apart_at_the_png_resolution(self):
        # Three points a label's width apart on a log axis: placed on the screen (figure dpi),
        # the labels must not overlap when drawn at the PNG's 200 dpi (offsets in pixels did).
        fig, ax = plt.subplots(figsize=(4, 3))
        xs, ys = [1e2, 1.6e2, 2.6e2], [1e-2, 1.05e-2, 1.1e-2]
        ax.plot(xs, ys, "o")
        ax.set_xscale("log")
        ax.set_yscale("log")
        style.place_labels(ax, list(zip(xs, ys)), ["0.0333 s", "0.01 s", "0.0005 s"], "C0")
        fig.set_dpi(style.DPI)
        fig.canvas.draw()
        boxes = [t.get_window_extent() for t in ax.texts]
        self.assertEqual(len(boxes), 3)
        for i in range(3):
            for j in range(i + 1, 3):
                self.assertFalse(boxes[i].overlaps(boxes[j]), (i, j, boxes[i], boxes[j]))
        plt.close(fig)

    def test_no_label_covers_an_error_bar(self):
        # A point with a long bar between two points a label's width away on either side: beside
        # it the label would cover a neighbour, so it goes above or below, along the bar, unless
        # the bar counts as an obstacle (it did not); it must cross neither the bar nor a point.
        fig, ax = bar_axes()
        xs, ys = [6.0, 10.0, 16.0], [1e-2, 1e-2, 1e-2]
        ax.errorbar(xs, ys, yerr=[[0, 9e-3, 0], [0, 5e-2, 0]], fmt="o")
        style.place_labels(ax, list(zip(xs, ys)), ["", "0.0333 s", ""], "C0", half=[0.0, 5e-2, 0.0])
        fig.set_dpi(style.DPI)
        fig.canvas.draw()
        label = ax.texts[1].get_window_extent()
        (bar_x, low), (_, high) = ax.transData.transform([(10.0, 1e-3), (10.0, 6e-2)])
        crosses_bar = label.x0 < bar_x < label.x1 and label.y0 < high and label.y1 > low
        self.assertFalse(crosses_bar, (label, bar_x, low, high))
        plt.close(fig)

    def test_a_label_keeps_clear_of_the_caps(self):
        # Points on either side push the middle label above or below its bar; placed at the
        # bar's width it would touch a cap. It must stay a few pixels off
        # each cap, CAP_SIZE points either side of the bar at its ends.
        fig, ax = bar_axes()
        xs, ys, half = [6.0, 10.0, 16.0], [1e-2, 1e-2, 1e-2], [0.0, 5e-3, 0.0]
        style.log_errorbar(ax, xs, ys, half, dodge=False, fmt="o")
        style.place_labels(ax, list(zip(xs, ys)), ["", "0.0333 s", ""], "C0", half=half)
        fig.set_dpi(style.DPI)
        fig.canvas.draw()
        label = ax.texts[1].get_window_extent()
        px = style.DPI / 72
        for end in (5e-3, 1.5e-2):
            bar_x, y = ax.transData.transform((10.0, end))
            cap = (bar_x - style.CAP_SIZE * px, y - px, bar_x + style.CAP_SIZE * px, y + px)
            clear = 2 * px
            touches = (label.x0 < cap[2] + clear and label.x1 > cap[0] - clear
                       and label.y0 < cap[3] + clear and label.y1 > cap[1] - clear)
            self.assertFalse(touches, (label, cap))
        plt.close(fig)

    def test_a_label_keeps_clear_of_a_partial_ensembles_note(self):
        # Two points of a joined series, the right one from 4 of its 5 runs: mark_partial writes
        # "4 of 5" above its right, where the label "0.01 s" also fits best unless the note
        # counts as an obstacle (it did not, and the two overlapped in the accuracy-cost figure).
        fig, ax = plt.subplots(figsize=(4, 3))
        xs, ys = [2e-2, 5e-2], [15.0, 17.0]
        ax.plot(xs, ys, "-o")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(5e-3, 10.0)
        ax.set_ylim(0.1, 40.0)
        style.mark_partial(ax, [(5e-2, 17.0, 5.0, 4, 5)])
        style.place_labels(ax, list(zip(xs, ys)), ["0.0333 s", "0.01 s"], "C2", half=[4.0, 6.0], joined=True)
        fig.set_dpi(style.DPI)
        fig.canvas.draw()
        note, *labels = [t for t in ax.texts if t.get_text()]
        self.assertEqual(note.get_text(), "4 of 5")
        for label in labels:
            self.assertFalse(note.get_window_extent().overlaps(label.get_window_extent()),
                             (label.get_text(), note.get_window_extent(), label.get_window_extent()))
        plt.close(fig)

class LabelLogTicksTest(unittest.TestCase):
    def labelled(self, low, high):
        """The labelled major ticks inside a log y axis from low to high, after label_log_ticks."""
        fig, ax = plt.subplots()
        ax.set_yscale("log")
        ax.set_ylim(low, high)
        style.label_log_ticks(ax)
        fig.canvas.draw()
        out = [(tick.get_loc(), tick.label1.get_text()) for tick in ax.yaxis.get_major_ticks()
               if low <= tick.get_loc() <= high and tick.label1.get_text()]
        plt.close(fig)
        return out

    def test_a_range_with_one_power_of_ten_gets_1_2_5_ticks(self):
        # 0.15 to 9: only 1 was labelled; now 0.2, 0.5, 1, 2, 5.
        np.testing.assert_allclose([loc for loc, _ in self.labelled(0.15, 9.0)], [0.2, 0.5, 1, 2, 5])

    def test_a_range_within_a_factor_of_two_gets_evenly_spaced_labelled_ticks(self):
        # 3 to 5.5: no power of ten inside, one 1-2-5 tick (5): matplotlib's even spacing.
        ticks = self.labelled(3.0, 5.5)
        np.testing.assert_allclose([loc for loc, _ in ticks], [3, 3.5, 4, 4.5, 5, 5.5])
        self.assertIn("3.5", ticks[1][1])

    def test_several_decades_keep_their_decade_ticks(self):
        np.testing.assert_allclose([loc for loc, _ in self.labelled(1e-3, 1.0)], [1e-3, 1e-2, 1e-1, 1])


if __name__ == "__main__":
    unittest.main()
