"""Batched geometry in the renderer (flatten_many / coverage_many) gives
the same pixels as drawing every path on its own."""

import numpy as np
import pytest

import importlib
from raster.renderer import batch as batch_mod
from raster.geometry.path import Path
from raster.tree import Fill, Group, PathNode, SolidPaint, Stroke, Tree
from raster.renderer import render_tree
from raster.geometry.transform import Affine
from _geometry import kappa_circle as circle



def scene(seed):
    """Overlapping translucent discs and squares in nested groups with
    transforms, thin (hairline) and thick strokes, one layered group, and
    a shape shared by two parents."""
    rng = np.random.default_rng(seed)
    kids = []
    shared = PathNode(path=circle(0, 0, 3), fill=Fill(SolidPaint((0, 0.5, 0, 0.7))))
    for i in range(60):
        cx, cy = rng.uniform(0, 64, 2)
        col = tuple(rng.uniform(0, 1, 3)) + (float(rng.uniform(0.3, 1)),)
        p = circle(cx, cy, rng.uniform(0.5, 9)) if i % 3 else Path.polygon(
            [[cx, cy], [cx + 7, cy + 1], [cx + 6, cy + 8], [cx - 1, cy + 5]])
        stroke = None
        if i % 4 == 0:
            stroke = Stroke.of(SolidPaint((0, 0, 0, 1)), width=float(rng.choice([0.3, 2.0])))
        kids.append(PathNode(path=p, fill=Fill(SolidPaint(col),
                                               rule=('nonzero', 'evenodd')[i % 2]),
                             stroke=stroke))
    inner = Group(transform=Affine.rotate(20, 32, 32), children=kids[20:40] + [shared])
    layered = Group(opacity=0.5, children=kids[40:50])
    root = Group(children=kids[:20] + [inner, layered, shared] + kids[50:],
                 transform=Affine.scale(1.5))
    return Tree(100, 100, root)


@pytest.mark.parametrize('seed', range(4))
def test_batched_render_equals_unbatched(seed, monkeypatch):
    batched = render_tree(scene(seed)).data.copy()
    monkeypatch.setattr(batch_mod.Masks, 'plan', lambda self, *a, **k: None)
    single = render_tree(scene(seed)).data
    assert np.array_equal(batched, single)


def test_small_batches_change_nothing(monkeypatch):
    ref = render_tree(scene(9)).data.copy()
    monkeypatch.setattr(batch_mod, 'BATCH_VERBS', 7)
    monkeypatch.setattr(batch_mod, 'BATCH_AREA', 400)
    assert np.array_equal(render_tree(scene(9)).data, ref)


def stroke_scene(seed):
    """Stroked discs, some dashed, under transforms of different scales (so
    stroke_many's shared user-space outlines round differently)."""
    rng = np.random.default_rng(seed)
    kids = []
    for i in range(40):
        cx, cy = rng.uniform(5, 60, 2)
        dash = (3.0, 2.0) if i % 3 == 0 else None
        st = Stroke.of(SolidPaint((0.1, 0.2, 0.9, 0.8)), width=float(rng.uniform(1.2, 4)), dash=dash)
        node = PathNode(path=circle(cx, cy, rng.uniform(1, 8)), stroke=st)
        kids.append(Group(transform=Affine.scale(float(rng.choice([0.8, 1.0, 1.3]))),
                          children=[node]))
    return Tree(100, 100, Group(children=kids))


@pytest.mark.parametrize('seed', range(3))
def test_batched_strokes_match_single_strokes(seed, monkeypatch):
    """Batched stroke outlines equal single ones up to float rounding: the
    8-bit images agree within 1 level everywhere."""
    batched = render_tree(stroke_scene(seed)).to_rgba8().astype(int)
    monkeypatch.setattr(batch_mod.Masks, 'plan', lambda self, *a, **k: None)
    single = render_tree(stroke_scene(seed)).to_rgba8().astype(int)
    assert batched.max() > 0
    assert np.abs(batched - single).max() <= 1
