"""Golden images: every golden/cases/*.svg rendered by raster must match its
reference PNG (made by resvg through golden/regenerate.py, on request only)
under the conformance criterion of raster.testing.  A failure writes an
expected|diff|actual strip to tests/_failures/golden/<case>.png.

Text is drawn with the resvg suite's fonts and its harness's generic
families (raster.testing.suite_fonts), as the references are."""

import os

import numpy as np
import pytest
from PIL import Image

import raster
from raster.testing import compare_images, diff_strip, suite_fonts

from _shared import SUITE_FONTS

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = os.path.join(HERE, '..', 'golden', 'cases')
FAILURES = os.path.join(HERE, '_failures', 'golden')
NAMES = sorted(f[:-4] for f in os.listdir(CASES) if f.endswith('.svg'))


def test_every_case_has_a_reference():
    missing = [n for n in NAMES if not os.path.exists(os.path.join(CASES, n + '.png'))]
    assert not missing, 'run golden/regenerate.py for: %s' % ', '.join(missing)


@pytest.mark.parametrize('name', NAMES)
def test_golden(name):
    svg = os.path.join(CASES, name + '.svg')
    expected = np.asarray(Image.open(os.path.join(CASES, name + '.png')).convert('RGBA'))
    actual = raster.render(svg, fonts=suite_fonts(SUITE_FONTS))
    result = compare_images(expected, actual)
    if not result.passed:
        os.makedirs(FAILURES, exist_ok=True)
        Image.fromarray(diff_strip(expected, actual, result)).save(
            os.path.join(FAILURES, name + '.png'))
    assert result.passed, '%s: %s, SSIM %s (strip in tests/_failures/golden/)' % (
        name, result.reason, _ssim(expected, actual))


def _ssim(expected, actual):
    """Structural similarity of the two images over white (scikit-image),
    as a second opinion in failure reports; 'n/a' for different sizes."""
    from skimage.metrics import structural_similarity
    from raster.testing import over_white
    if expected.shape != actual.shape:
        return 'n/a'
    a, b = over_white(expected), over_white(actual)
    win = min(7, min(a.shape[:2]) // 2 * 2 - 1)
    if win < 3:
        return 'n/a'
    return '%.4f' % structural_similarity(a, b, channel_axis=-1, data_range=255, win_size=win)
