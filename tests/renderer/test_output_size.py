"""Output sizes follow resvg: the natural pixel size is the document size
rounded half up; a requested width or height scales that integer size and
rounds the other side up (values measured with resvg-py 0.5.0)."""

import pytest

from raster.renderer import output_size


@pytest.mark.parametrize('doc, width, expected', [
    ((1000, 507.224), None, (1000, 507)),
    ((1000, 507.224), 2000, (2000, 1014)),
    ((100, 50.5), None, (100, 51)),
    ((100, 50.5), 2000, (2000, 1020)),
    ((100, 50.49), None, (100, 50)),
    ((100, 50.49), 2000, (2000, 1000)),
    ((10.5, 10), None, (11, 10)),
    ((10.5, 10), 2000, (2000, 1819)),
    ((100.5, 50.5), 2000, (2000, 1010)),
])
def test_sizes_match_resvg(doc, width, expected):
    assert output_size(*doc, width=width)[:2] == expected
