"""Make the batch benchmark's icon documents: every icon of the corpus's
icon sheet (Font Awesome and Twemoji, each a nested ``<svg>``) as a
document of its own, at three sizes (48, 96, 192 px) and, for the
one-colour icons, three fill colours, in a fixed order, until ``--count``
documents (default 200) are written.

    python bench/make_icons.py OUT_DIR [--count 200]
"""

import argparse
import copy
import os
import sys

from lxml import etree

HERE = os.path.dirname(os.path.abspath(__file__))
SHEET = os.path.join(HERE, '..', '..', 'shared', 'corpus', 'icons_fontawesome_twemoji_sheet.svg')
NS = 'http://www.w3.org/2000/svg'
SIZES = (48, 96, 192)
COLOURS = ('#1f2937', '#b91c1c', '#1d4ed8')


def icons(sheet=SHEET):
    """The nested ``<svg>`` elements of the sheet, in document order."""
    root = etree.parse(sheet).getroot()
    return [el for el in root if el.tag == '{%s}svg' % NS]


def documents(count=200, sheet=SHEET):
    """``[(file name, SVG bytes)]``: ``count`` single-icon documents."""
    out = []
    ics = icons(sheet)
    for k in range(3):
        for i, el in enumerate(ics):
            if len(out) == count:
                return out
            doc = copy.deepcopy(el)
            for a in ('x', 'y'):
                doc.attrib.pop(a, None)
            size = SIZES[k]
            doc.set('width', str(size))
            doc.set('height', str(size))
            if doc.get('fill'):
                doc.set('fill', COLOURS[k])
            name = '%03d_%s_%d.svg' % (len(out), doc.get('id', 'icon%d' % i), size)
            out.append((name, etree.tostring(doc)))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('out_dir')
    ap.add_argument('--count', type=int, default=200)
    args = ap.parse_args(argv)
    os.makedirs(args.out_dir, exist_ok=True)
    docs = documents(args.count)
    for name, data in docs:
        with open(os.path.join(args.out_dir, name), 'wb') as f:
            f.write(data)
    print('%d icon documents in %s' % (len(docs), args.out_dir))
    return 0


if __name__ == '__main__':
    sys.exit(main())
