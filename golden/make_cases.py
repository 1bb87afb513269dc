"""Write the golden SVG cases (one property per file, 200x200 viewBox, a
<title> and a frame).  Run once when adding cases; the SVG files are
committed, and their reference PNGs are made by regenerate.py on request."""

import os

import rules

HEAD = ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
        'width="200" height="200" viewBox="0 0 200 200">\n  <title>{title}</title>\n'
        '  <rect x="1" y="1" width="198" height="198" fill="none" stroke="#777" stroke-width="2"/>\n')

CASES = {
    # --- shapes -------------------------------------------------------------
    'shapes-rect': ('rect', '<rect x="30" y="40" width="140" height="100" fill="#2a9d8f"/>'),
    'shapes-rect-rounded': ('rect with rx and ry', '<rect x="30" y="40" width="140" height="100" rx="30" ry="15" fill="#2a9d8f"/>'),
    'shapes-rect-rx-only': ('rect with only rx (ry auto)', '<rect x="30" y="40" width="140" height="100" rx="25" fill="#e76f51"/>'),
    'shapes-rect-rx-clamped': ('rect rx larger than half width is clamped', '<rect x="30" y="40" width="140" height="100" rx="200" fill="#264653"/>'),
    'shapes-circle': ('circle', '<circle cx="100" cy="100" r="70" fill="#e9c46a"/>'),
    'shapes-ellipse': ('ellipse', '<ellipse cx="100" cy="100" rx="80" ry="40" fill="#f4a261"/>'),
    'shapes-line': ('line with stroke', '<line x1="20" y1="30" x2="180" y2="170" stroke="#264653" stroke-width="8"/>'),
    'shapes-polyline': ('polyline stroked and filled', '<polyline points="20,180 60,40 100,160 140,40 180,180" fill="#a8dadc" stroke="#1d3557" stroke-width="4"/>'),
    'shapes-polygon': ('polygon', '<polygon points="100,20 180,180 20,180" fill="#457b9d"/>'),
    'shapes-percent-units': ('lengths in percent', '<rect x="10%" y="20%" width="50%" height="30%" fill="#6a4c93"/><circle cx="75%" cy="75%" r="15%" fill="#1982c4"/>'),
    'shapes-mm-units': ('lengths in mm, pt and pc', '<rect x="5mm" y="5mm" width="20mm" height="10mm" fill="#8ac926"/><rect x="60pt" y="90pt" width="6pc" height="3pc" fill="#ff595e"/>'),
    'path-lines-relative': ('path with relative line commands', '<path d="m20 20 h160 v40 l-80 60 l-80 -60 z" fill="#2a9d8f"/>'),
    'path-cubic-smooth': ('path with C and S commands', '<path d="M20 150 C 40 20, 90 20, 100 100 S 160 180, 180 50" fill="none" stroke="#e63946" stroke-width="6"/>'),
    'path-quad-smooth': ('path with Q and T commands', '<path d="M20 100 Q 50 20 80 100 T 140 100 T 190 100" fill="none" stroke="#1d3557" stroke-width="6"/>'),
    'path-arcs': ('path with elliptical arcs and flags', '<path d="M30 100 A 40 25 30 1 1 100 100 A 30 30 0 0 0 170 100" fill="#ffb703" stroke="#023047" stroke-width="4"/>'),
    'path-arc-radii-correction': ('arc with radii too small is scaled up', '<path d="M40 100 A 10 10 0 0 1 160 100 Z" fill="#219ebc"/>'),
    'path-implicit-repeat': ('implicit lineto after moveto', '<path d="M20,180 100,20 180,180 z" fill="#8338ec"/>'),
    'path-compact-numbers': ('compact number syntax', '<path d="M20.5.5L180-0 180 180-.5 180z" transform="translate(0 10) scale(1 .9)" fill="#3a86ff"/>'),
    # --- fill ---------------------------------------------------------------
    'fill-rule-evenodd': ('fill-rule evenodd star', '<polygon points="100,10 155,180 10,70 190,70 45,180" fill="#ef476f" fill-rule="evenodd"/>'),
    'fill-rule-nonzero': ('fill-rule nonzero star', '<polygon points="100,10 155,180 10,70 190,70 45,180" fill="#ef476f" fill-rule="nonzero"/>'),
    'fill-overlapping-subpaths': ('two overlapping circles in one path, evenodd', '<path d="M30 100 a45 45 0 1 0 90 0 a45 45 0 1 0 -90 0 Z M80 100 a45 45 0 1 0 90 0 a45 45 0 1 0 -90 0 Z" fill="#118ab2" fill-rule="evenodd"/>'),
    'fill-opacity': ('fill-opacity over another shape', '<rect x="20" y="20" width="110" height="110" fill="#073b4c"/><circle cx="120" cy="120" r="60" fill="#ffd166" fill-opacity="0.6"/>'),
    'fill-none': ('fill none with stroke', '<circle cx="100" cy="100" r="60" fill="none" stroke="#06d6a0" stroke-width="10"/>'),
    # --- colours ------------------------------------------------------------
    'color-syntaxes': ('colour syntaxes', '<rect x="20" y="20" width="50" height="50" fill="#f80"/><rect x="75" y="20" width="50" height="50" fill="#ff880080"/>'
                        '<rect x="130" y="20" width="50" height="50" fill="rgb(10%, 50%, 90%)"/><rect x="20" y="75" width="50" height="50" fill="rgba(200, 30, 60, 0.5)"/>'
                        '<rect x="75" y="75" width="50" height="50" fill="hsl(120, 60%, 40%)"/><rect x="130" y="75" width="50" height="50" fill="DarkSlateBlue"/>'
                        '<rect x="20" y="130" width="50" height="50" fill="#1a2b3c4d"/><rect x="75" y="130" width="50" height="50" fill="hsla(300, 100%, 50%, 0.4)"/>'
                        '<rect x="130" y="130" width="50" height="50" fill="transparent" stroke="black"/>'),
    'color-currentcolor': ('currentColor inherited from color', '<g color="#e76f51"><rect x="30" y="30" width="140" height="140" fill="currentColor" stroke="#264653" stroke-width="6"/></g>'),
    # --- strokes ------------------------------------------------------------
    'stroke-linejoin-miter': ('stroke-linejoin miter', '<polyline points="30,170 70,40 110,170 150,60" fill="none" stroke="#264653" stroke-width="18" stroke-linejoin="miter"/>'),
    'stroke-linejoin-round': ('stroke-linejoin round', '<polyline points="30,170 70,40 110,170 150,60" fill="none" stroke="#264653" stroke-width="18" stroke-linejoin="round"/>'),
    'stroke-linejoin-bevel': ('stroke-linejoin bevel', '<polyline points="30,170 70,40 110,170 150,60" fill="none" stroke="#264653" stroke-width="18" stroke-linejoin="bevel"/>'),
    'stroke-miterlimit': ('stroke-miterlimit turning sharp miters into bevels', '<polyline points="20,60 180,80 20,100" fill="none" stroke="#264653" stroke-width="14" stroke-miterlimit="3"/><polyline points="20,120 180,140 20,160" fill="none" stroke="#e76f51" stroke-width="14" stroke-miterlimit="30"/>'),
    'stroke-linecap-butt': ('stroke-linecap butt', '<line x1="40" y1="100" x2="160" y2="100" stroke="#2a9d8f" stroke-width="30" stroke-linecap="butt"/>'),
    'stroke-linecap-round': ('stroke-linecap round', '<line x1="40" y1="100" x2="160" y2="100" stroke="#2a9d8f" stroke-width="30" stroke-linecap="round"/>'),
    'stroke-linecap-square': ('stroke-linecap square', '<line x1="40" y1="100" x2="160" y2="100" stroke="#2a9d8f" stroke-width="30" stroke-linecap="square"/>'),
    'stroke-dasharray': ('stroke-dasharray on a curve', '<path d="M20 160 C 60 0, 140 0, 180 160" fill="none" stroke="#8338ec" stroke-width="8" stroke-dasharray="20 10 5 10"/>'),
    'stroke-dasharray-odd': ('odd-length dasharray is repeated', '<line x1="20" y1="100" x2="180" y2="100" stroke="#3a86ff" stroke-width="12" stroke-dasharray="15 5 5"/>'),
    'stroke-dashoffset': ('stroke-dashoffset on a closed rect', '<rect x="40" y="40" width="120" height="120" fill="none" stroke="#fb5607" stroke-width="8" stroke-dasharray="30 15" stroke-dashoffset="20"/>'),
    'stroke-dash-round-caps': ('dashes with round caps', '<circle cx="100" cy="100" r="60" fill="none" stroke="#ff006e" stroke-width="10" stroke-dasharray="1 20" stroke-linecap="round"/>'),
    'stroke-opacity': ('stroke-opacity shows the fill under it', '<rect x="40" y="40" width="120" height="120" fill="#ffbe0b" stroke="#3a0ca3" stroke-width="24" stroke-opacity="0.5"/>'),
    'stroke-zero-length-caps': ('zero-length subpaths draw round and square caps', '<path d="M60 100 z M140 100 L140 100" stroke="#7209b7" stroke-width="40" stroke-linecap="round"/><path d="M100 40 z" stroke="#f72585" stroke-width="30" stroke-linecap="square"/>'),
    'stroke-nonuniform-scale': ('stroke under non-uniform scale', '<g transform="scale(3 1)"><circle cx="33" cy="100" r="20" fill="none" stroke="#4361ee" stroke-width="6"/></g>'),
    'stroke-skew': ('stroke under skew', '<rect x="50" y="50" width="80" height="100" fill="none" stroke="#4cc9f0" stroke-width="10" transform="skewX(20)"/>'),
    'stroke-hairline': ('hairline strokes thinner than a pixel', '<g fill="none" stroke="black"><line x1="20" y1="40" x2="180" y2="60" stroke-width="0.5"/><line x1="20" y1="80" x2="180" y2="100" stroke-width="0.25"/><circle cx="100" cy="150" r="30" stroke-width="0.3"/></g>'),
    'stroke-cusp': ('stroke of a curve with a cusp', '<path d="M30 150 C 170 20, 30 20, 170 150" fill="none" stroke="#2b2d42" stroke-width="16"/>'),
    # --- opacity and paint order -------------------------------------------
    'opacity-group': ('group opacity composites the group as one layer', '<g opacity="0.5"><rect x="30" y="30" width="100" height="100" fill="#d62828"/><rect x="70" y="70" width="100" height="100" fill="#003049"/></g>'),
    'opacity-element': ('element opacity with stroke', '<circle cx="100" cy="100" r="60" fill="#fcbf49" stroke="#003049" stroke-width="20" opacity="0.5"/>'),
    'paint-order-stroke': ('paint-order stroke draws the fill on top', '<rect x="40" y="40" width="120" height="120" fill="#80b918" stroke="#007f5f" stroke-width="30" paint-order="stroke"/>'),
    'shape-rendering-crisp': ('shape-rendering crispEdges disables anti-aliasing', '<circle cx="100" cy="100" r="70" fill="#5f0f40" shape-rendering="crispEdges"/>'),
    # --- transforms ---------------------------------------------------------
    'transform-list': ('transform list', '<rect x="0" y="0" width="60" height="40" fill="#0f4c5c" transform="translate(100 100) rotate(30) scale(1.5) translate(-30 -20)"/>'),
    'transform-matrix': ('transform matrix', '<rect x="0" y="0" width="80" height="60" fill="#e36414" transform="matrix(1 0.3 -0.4 1 70 50)"/>'),
    'transform-rotate-center': ('rotate about a centre point', '<rect x="60" y="80" width="80" height="40" fill="#9a031e" transform="rotate(45 100 100)"/>'),
    # --- structure ----------------------------------------------------------
    'structure-use': ('use with x and y', '<defs><rect id="r" width="50" height="50" fill="#588157"/></defs><use xlink:href="#r" x="20" y="20"/><use href="#r" x="120" y="120"/>'),
    'structure-use-inherit': ('use content inherits from the use element', '<defs><circle id="c" r="30"/></defs><use xlink:href="#c" x="60" y="100" fill="#bc4749"/><use xlink:href="#c" x="140" y="100" fill="#386641"/>'),
    'structure-symbol': ('symbol with viewBox instantiated by use', '<defs><symbol id="s" viewBox="0 0 10 10"><circle cx="5" cy="5" r="4" fill="#6d597a"/></symbol></defs><use xlink:href="#s" x="20" y="20" width="80" height="80"/><use xlink:href="#s" x="110" y="110" width="60" height="60"/>'),
    'structure-nested-svg': ('nested svg clips to its viewport', '<svg x="40" y="40" width="120" height="120" viewBox="0 0 60 60"><circle cx="30" cy="30" r="40" fill="#b56576"/></svg>'),
    'structure-style-css': ('style sheet selectors and precedence', '<style>circle { fill: #999 } .a { fill: #e56b6f } #b { fill: #355070 } g > .c { fill: #eaac8b } .d { fill: #6d597a !important }</style>'
                            '<circle cx="55" cy="55" r="35"/><rect class="a" x="110" y="20" width="70" height="70"/><rect id="b" class="a" x="20" y="110" width="70" height="70"/>'
                            '<g><rect class="c d" x="110" y="110" width="70" height="70" style="fill:red"/></g>'),
    'structure-style-attribute': ('style attribute beats presentation attribute', '<rect x="40" y="40" width="120" height="120" fill="red" style="fill: #2d6a4f; stroke: #081c15; stroke-width: 6"/>'),
    'structure-display-none': ('display none hides the subtree', '<g display="none"><rect x="20" y="20" width="160" height="160" fill="red"/></g><circle cx="100" cy="100" r="50" fill="#40916c"/>'),
    'structure-visibility': ('visible child of a hidden group is drawn', '<g visibility="hidden"><rect x="20" y="20" width="160" height="160" fill="red"/><circle cx="100" cy="100" r="50" fill="#1b4332" visibility="visible"/></g>'),
    'structure-switch': ('switch picks the first matching child', '<switch><rect systemLanguage="xx" x="20" y="20" width="160" height="160" fill="red"/><circle cx="100" cy="100" r="60" fill="#52b788"/><rect x="20" y="20" width="160" height="160" fill="red"/></switch>'),
    'structure-inherit-keyword': ('inherit keyword', '<g fill="#9d4edd" stroke="#240046" stroke-width="8"><rect x="40" y="40" width="120" height="120" fill="inherit" stroke="inherit"/></g>'),
    # --- paint servers (issue 4) -------------------------------------------
    'gradient-linear': ('linearGradient with stops', '<defs><linearGradient id="g"><stop offset="0" stop-color="#264653"/><stop offset="0.5" stop-color="#e9c46a"/><stop offset="1" stop-color="#e76f51"/></linearGradient></defs><rect x="20" y="40" width="160" height="120" fill="url(#g)"/>'),
    'gradient-linear-userspace-reflect': ('linearGradient userSpaceOnUse with spreadMethod reflect', '<defs><linearGradient id="g" gradientUnits="userSpaceOnUse" x1="60" y1="0" x2="100" y2="0" spreadMethod="reflect"><stop offset="0" stop-color="#023047"/><stop offset="1" stop-color="#8ecae6"/></linearGradient></defs><rect x="20" y="20" width="160" height="160" fill="url(#g)"/>'),
    'gradient-linear-transform-repeat': ('gradientTransform and spreadMethod repeat', '<defs><linearGradient id="g" x2="0.25" spreadMethod="repeat" gradientTransform="rotate(30 0.5 0.5)"><stop offset="0" stop-color="#ffb703"/><stop offset="1" stop-color="#fb8500"/></linearGradient></defs><circle cx="100" cy="100" r="80" fill="url(#g)"/>'),
    'gradient-radial': ('radialGradient', '<defs><radialGradient id="g"><stop offset="0" stop-color="#fff"/><stop offset="1" stop-color="#6a040f"/></radialGradient></defs><rect x="20" y="20" width="160" height="160" fill="url(#g)"/>'),
    'gradient-radial-focal': ('radialGradient with a focal point and fr', '<defs><radialGradient id="g" fx="0.3" fy="0.3" fr="0.05"><stop offset="0" stop-color="#ffd60a"/><stop offset="1" stop-color="#003566"/></radialGradient></defs><circle cx="100" cy="100" r="80" fill="url(#g)"/>'),
    'gradient-href-stops': ('gradient inheriting stops through href', '<defs><linearGradient id="base"><stop offset="0" stop-color="#2b9348"/><stop offset="1" stop-color="#d4d700"/></linearGradient><linearGradient id="g" href="#base" x1="0" y1="0" x2="0" y2="1"/></defs><rect x="30" y="30" width="140" height="140" fill="url(#g)" stroke="url(#base)" stroke-width="10"/>'),
    'gradient-stop-opacity': ('stop-opacity over a checker', '<rect x="20" y="20" width="80" height="80" fill="#333"/><rect x="100" y="100" width="80" height="80" fill="#333"/><defs><linearGradient id="g"><stop offset="0" stop-color="#e63946" stop-opacity="0"/><stop offset="1" stop-color="#e63946"/></linearGradient></defs><rect x="20" y="20" width="160" height="160" fill="url(#g)"/>'),
    'paint-fallback': ('missing paint server falls back to the given colour', '<rect x="30" y="30" width="140" height="140" fill="url(#missing) #52b788"/>'),
    'pattern-basic': ('pattern in userSpaceOnUse', '<defs><pattern id="p" width="20" height="20" patternUnits="userSpaceOnUse"><rect width="10" height="10" fill="#7209b7"/><circle cx="15" cy="15" r="4" fill="#f72585"/></pattern></defs><rect x="20" y="20" width="160" height="160" fill="url(#p)"/>'),
    'pattern-viewbox-transform': ('pattern with viewBox and patternTransform', '<defs><pattern id="p" width="0.25" height="0.25" viewBox="0 0 10 10" patternTransform="rotate(20)"><path d="M0 0 L10 10 M10 0 L0 10" stroke="#0077b6" stroke-width="2"/></pattern></defs><circle cx="100" cy="100" r="80" fill="url(#p)" stroke="#03045e" stroke-width="3"/>'),
    # --- clipping, masking, compositing ------------------------------------------
    'clip-path-basic': ('clipPath of a circle', '<defs><clipPath id="c"><circle cx="100" cy="100" r="70"/></clipPath></defs><g clip-path="url(#c)"><rect x="20" y="20" width="160" height="80" fill="#ef476f"/><rect x="20" y="100" width="160" height="80" fill="#118ab2"/></g>'),
    'clip-path-objectboundingbox-evenodd': ('clipPath in objectBoundingBox units with clip-rule evenodd', '<defs><clipPath id="c" clipPathUnits="objectBoundingBox"><path clip-rule="evenodd" d="M0.1 0.1 H0.9 V0.9 H0.1 Z M0.3 0.3 H0.7 V0.7 H0.3 Z"/></clipPath></defs><rect x="30" y="30" width="140" height="140" fill="#06d6a0" clip-path="url(#c)"/>'),
    'clip-path-nested': ('clip-path on a clipPath', '<defs><clipPath id="a"><rect x="20" y="20" width="120" height="160"/></clipPath><clipPath id="b" clip-path="url(#a)"><circle cx="110" cy="100" r="75"/></clipPath></defs><rect x="0" y="0" width="200" height="200" fill="#8338ec" clip-path="url(#b)"/>'),
    'mask-luminance': ('luminance mask with a gradient', '<defs><linearGradient id="g"><stop offset="0" stop-color="white"/><stop offset="1" stop-color="black"/></linearGradient><mask id="m"><rect x="20" y="20" width="160" height="160" fill="url(#g)"/></mask></defs><rect x="20" y="20" width="160" height="160" fill="#d00000" mask="url(#m)"/>'),
    'mask-alpha': ('mask-type alpha', '<defs><mask id="m" mask-type="alpha"><circle cx="100" cy="100" r="70" fill="black" fill-opacity="0.5"/></mask></defs><rect x="20" y="20" width="160" height="160" fill="#3a0ca3" mask="url(#m)"/>'),
    'blend-multiply': ('mix-blend-mode multiply', '<circle cx="80" cy="80" r="55" fill="#00b4d8"/><circle cx="120" cy="80" r="55" fill="#ffb703" style="mix-blend-mode: multiply"/><circle cx="100" cy="125" r="55" fill="#e63946" style="mix-blend-mode: multiply"/>'),
    'blend-screen-isolated': ('mix-blend-mode screen inside an isolated group', '<rect x="20" y="20" width="160" height="160" fill="#264653"/><g style="isolation: isolate"><circle cx="80" cy="100" r="55" fill="#2a9d8f"/><circle cx="120" cy="100" r="55" fill="#f4a261" style="mix-blend-mode: screen"/></g>'),
    # --- markers -----------------------------------------------------------------
    'marker-auto': ('markers with orient auto on a polyline', '<defs><marker id="m" markerWidth="10" markerHeight="10" refX="5" refY="5" orient="auto"><path d="M0 0 L10 5 L0 10 Z" fill="#d62828"/></marker></defs><polyline points="30,170 70,40 120,150 170,50" fill="none" stroke="#003049" stroke-width="3" marker-start="url(#m)" marker-mid="url(#m)" marker-end="url(#m)"/>'),
    'marker-auto-start-reverse-viewbox': ('marker with viewBox, userSpaceOnUse units and auto-start-reverse', '<defs><marker id="m" viewBox="0 0 10 10" markerWidth="20" markerHeight="20" refX="10" refY="5" markerUnits="userSpaceOnUse" orient="auto-start-reverse"><path d="M0 0 L10 5 L0 10 z" fill="#2a9d8f"/></marker></defs><path d="M40 100 C 80 20, 120 180, 160 100" fill="none" stroke="#264653" stroke-width="4" marker-start="url(#m)" marker-end="url(#m)"/>'),
    'marker-context-fill': ('context-fill and context-stroke in a marker', '<defs><marker id="m" markerWidth="8" markerHeight="8" refX="4" refY="4"><circle cx="4" cy="4" r="3" fill="context-stroke" stroke="context-fill"/></marker></defs><path d="M30 60 H170" stroke="#e76f51" fill="#264653" stroke-width="4" marker-start="url(#m)" marker-end="url(#m)"/><path d="M30 140 H170" stroke="#2a9d8f" fill="#e9c46a" stroke-width="4" marker-start="url(#m)" marker-end="url(#m)"/>'),
    # --- images ------------------------------------------------------------------
    'image-data-uri-optimizespeed': ('PNG data URI drawn with image-rendering optimizeSpeed (nearest neighbour) and preserveAspectRatio', '<image x="20" y="40" width="160" height="120" image-rendering="optimizeSpeed" preserveAspectRatio="xMidYMid meet" href="data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAQAAAADCAYAAAC09K7GAAAAKUlEQVR4nGN4Zun2/+Ovd/9X3Lrz37V67n8GZM4zS7f/DMicj7/e/QcAllEj4JIVAnkAAAAASUVORK5CYII="/>'),
    'image-svg-data-uri': ('SVG image from a data URI', '<image x="30" y="30" width="140" height="140" href="data:image/svg+xml;utf8,%3Csvg xmlns=%27http://www.w3.org/2000/svg%27 viewBox=%270 0 10 10%27%3E%3Ccircle cx=%275%27 cy=%275%27 r=%274%27 fill=%27%23ff006e%27/%3E%3C/svg%3E"/>'),
}

# Text cases: drawn with the resvg suite's fonts and its harness's generic
# families (golden/regenerate.py and tests/test_golden.py use
# raster.testing.suite_fonts), one rule per file, several files per rule.
SANS = 'font-family="Noto Sans"'
TEXT_CASES = {
    # --- bidi -----------------------------------------------------------------
    'text-bidi-arabic-in-latin': ('bidi: an Arabic word inside Latin text is reordered right to left (one font with both scripts)', '<text x="10" y="100" font-family="Amiri" font-size="22">one سلام two</text>'),
    'text-bidi-numbers-in-arabic': ('bidi: European digits inside Arabic keep left-to-right order', '<text x="190" y="100" font-family="Amiri" font-size="24" text-anchor="end">العدد 123 هنا</text>'),
    'text-bidi-arabic-tspans': ('bidi: an Arabic run over tspans of different fills keeps its visual order and joining', '<text x="20" y="100" font-family="Amiri" font-size="36">ab <tspan fill="#d62828">سلا</tspan><tspan fill="#1d3557">م</tspan> cd</text>'),
    'text-bidi-mixed-anchor-middle': ('bidi: mixed runs anchored at the middle', '<text x="100" y="100" font-family="Amiri" font-size="20" text-anchor="middle">A مرحبا B عالم C</text>'),
    # --- shaping across tspans ---------------------------------------------------
    'text-tspan-kerning-across': ('shaping across tspans: kerning between A and V of different tspans', '<text x="20" y="80" ' + SANS + ' font-size="48">A<tspan fill="#e63946">V</tspan>A<tspan fill="#457b9d">W</tspan></text><text x="20" y="150" ' + SANS + ' font-size="48">AVAW</text>'),
    'text-tspan-arabic-joining': ('shaping across tspans: Arabic letters join across a tspan boundary', '<text x="100" y="110" font-family="Amiri" font-size="48" text-anchor="middle">بي<tspan fill="#2a9d8f">ت</tspan>نا</text>'),
    'text-tspan-font-size-change': ('shaping across tspans: a tspan of another size continues the pen', '<text x="10" y="110" ' + SANS + ' font-size="30">Ab<tspan font-size="50" fill="#e76f51">Cd</tspan>Ef</text>'),
    'text-tspan-dy-chain': ('tspans with dy lists move each character', '<text x="20" y="100" ' + SANS + ' font-size="28">a<tspan dy="-10 -10 20">bcd</tspan><tspan dy="15" fill="#264653">e</tspan>f</text>'),
    # --- vertical writing ----------------------------------------------------------
    'text-vertical-latin': ('writing-mode tb: Latin letters turned with the line', '<text x="100" y="20" ' + SANS + ' font-size="28" writing-mode="tb">Hello</text>'),
    'text-vertical-cjk-upright': ('writing-mode tb: Japanese set upright', '<text x="100" y="20" font-family="Mplus 1p" font-size="30" writing-mode="tb">日本語です</text>'),
    'text-vertical-mixed': ('writing-mode tb: CJK upright, Latin rotated', '<text x="100" y="15" font-family="Mplus 1p" font-size="24" writing-mode="tb">漢字ABC混合</text>'),
    'text-vertical-letter-spacing': ('writing-mode tb with letter-spacing', '<text x="100" y="15" font-family="Mplus 1p" font-size="22" writing-mode="tb" letter-spacing="6">縦書き文字</text>'),
    # --- textLength and lengthAdjust -------------------------------------------------
    'text-textlength-spacing-stretch': ('textLength longer than the text, lengthAdjust spacing', '<text x="20" y="80" ' + SANS + ' font-size="24" textLength="160">Hello</text><line x1="20" y1="90" x2="180" y2="90" stroke="#999"/>'),
    'text-textlength-spacing-shrink': ('textLength shorter than the text, lengthAdjust spacing', '<text x="20" y="80" ' + SANS + ' font-size="24" textLength="90">Hello world</text><line x1="20" y1="90" x2="110" y2="90" stroke="#999"/>'),
    'text-textlength-glyphs-stretch': ('textLength with lengthAdjust spacingAndGlyphs stretches the glyphs', '<text x="20" y="100" ' + SANS + ' font-size="32" textLength="160" lengthAdjust="spacingAndGlyphs">Wide</text>'),
    'text-textlength-glyphs-shrink': ('textLength with lengthAdjust spacingAndGlyphs squeezes the glyphs', '<text x="20" y="100" ' + SANS + ' font-size="32" textLength="80" lengthAdjust="spacingAndGlyphs">Narrowed</text>'),
    'text-textlength-tspan': ('textLength on a tspan', '<text x="20" y="100" ' + SANS + ' font-size="22">ab<tspan textLength="100" fill="#e63946">cd</tspan>ef</text>'),
    # --- decorations -------------------------------------------------------------------
    'text-decoration-kinds': ('underline, overline and line-through (baselines chosen so that the 1 px lines of Noto Sans at 20 px fall half on two pixel rows)', '<text x="20" y="60" ' + SANS + ' font-size="20" text-decoration="underline">Under</text><text x="20" y="110.38" ' + SANS + ' font-size="20" text-decoration="overline">Over</text><text x="20" y="160.44" ' + SANS + ' font-size="20" text-decoration="line-through">Through</text>'),
    'text-decoration-declaring-element-paint': ('a decoration is painted with the fill and stroke of the element that declares it', '<text x="15" y="100" ' + SANS + ' font-size="30" fill="#1d3557" text-decoration="underline">ab<tspan fill="#e63946">cd</tspan>ef</text>'),
    'text-decoration-tspan-own': ('a tspan declaring its own decoration paints it with its fill', '<text x="15" y="100" ' + SANS + ' font-size="30" fill="#1d3557">ab<tspan fill="#e63946" text-decoration="line-through">cd</tspan>ef</text>'),
    'text-decoration-from-group': ('text-decoration on an ancestor group decorates the text', '<g text-decoration="underline overline" fill="#2a9d8f"><text x="20" y="100" ' + SANS + ' font-size="30">Group</text></g>'),
    'text-decoration-stroked': ('a decorated text with a stroke: the line is stroked too', '<text x="20" y="100" ' + SANS + ' font-size="40" fill="#ffb703" stroke="#023047" stroke-width="1.5" text-decoration="underline">Stroke</text>'),
    # --- baselines -------------------------------------------------------------------------
    'text-baseline-shift-sub-super': ('baseline-shift sub and super', '<line x1="10" y1="100" x2="190" y2="100" stroke="#bbb"/><text x="15" y="100" ' + SANS + ' font-size="28">x<tspan baseline-shift="super" font-size="18">2</tspan>+y<tspan baseline-shift="sub" font-size="18">i</tspan></text>'),
    'text-baseline-shift-length-percent': ('baseline-shift as a length and a percentage', '<line x1="10" y1="100" x2="190" y2="100" stroke="#bbb"/><text x="15" y="100" ' + SANS + ' font-size="28">a<tspan baseline-shift="10">b</tspan>c<tspan baseline-shift="-30%">d</tspan>e</text>'),
    'text-dominant-baseline-values': ('dominant-baseline auto, middle, central, hanging, text-before-edge', '<line x1="5" y1="100" x2="195" y2="100" stroke="#bbb"/><g ' + SANS + ' font-size="20"><text x="5" y="100">Ab</text><text x="42" y="100" dominant-baseline="middle">Ab</text><text x="80" y="100" dominant-baseline="central">Ab</text><text x="118" y="100" dominant-baseline="hanging">Ab</text><text x="156" y="100" dominant-baseline="text-before-edge">Ab</text></g>'),
    'text-alignment-baseline-tspan': ('alignment-baseline on tspans', '<line x1="5" y1="100" x2="195" y2="100" stroke="#bbb"/><text x="10" y="100" ' + SANS + ' font-size="22">a<tspan alignment-baseline="middle">b</tspan>c<tspan alignment-baseline="hanging">d</tspan>e<tspan alignment-baseline="central">f</tspan></text>'),
    # --- small caps and features -------------------------------------------------------------
    'text-small-caps': ('font-variant small-caps (the font\'s smcp feature)', '<text x="15" y="80" font-family="Source Sans Pro" font-size="30" font-variant="small-caps">Small Caps</text><text x="15" y="140" font-family="Source Sans Pro" font-size="30">Small Caps</text>'),
    'text-font-feature-settings': ('font-feature-settings turning ligatures off', '<text x="15" y="80" font-family="Source Sans Pro" font-size="36">office fjord</text><text x="15" y="140" font-family="Source Sans Pro" font-size="36" font-feature-settings="\'liga\' 0">office fjord</text>'),
    'text-font-kerning-none': ('font-kerning none', '<text x="15" y="80" ' + SANS + ' font-size="44">AVATAR</text><text x="15" y="150" ' + SANS + ' font-size="44" font-kerning="none">AVATAR</text>'),
    # --- font matching and fallback -------------------------------------------------------------
    'text-font-weights': ('font-weight 300 to 900 over Noto Sans Light, Regular, Bold and Black', '<g ' + SANS + ' font-size="24"><text x="10" y="35" font-weight="300">Weight 300</text><text x="10" y="65" font-weight="400">Weight 400</text><text x="10" y="95" font-weight="500">Weight 500</text><text x="10" y="125" font-weight="600">Weight 600</text><text x="10" y="155" font-weight="800">Weight 800</text><text x="10" y="185" font-weight="900">Weight 900</text></g>'),
    'text-font-relative-weights': ('font-weight bolder and lighter', '<desc>CSS Fonts 4, 2.2: lighter than 700 is 400, bolder than 300 is 400.  resvg takes 100 off for lighter (600: the bold face), so the reference is made from golden/equivalent/text-font-relative-weights.svg with the computed weights written out.</desc><g ' + SANS + ' font-size="22"><text x="10" y="60" font-weight="bold">bold <tspan font-weight="lighter">lighter</tspan></text><text x="10" y="120" font-weight="300">light <tspan font-weight="bolder">bolder</tspan></text></g>'),
    'text-font-italic': ('font-style italic picks the italic face', '<text x="15" y="80" ' + SANS + ' font-size="30" font-style="italic">Italic text</text><text x="15" y="140" ' + SANS + ' font-size="30" font-style="oblique">Oblique</text>'),
    'text-font-generic-families': ('the generic families serif, sans-serif, monospace, cursive and fantasy', '<g font-size="22"><text x="10" y="35" font-family="serif">serif text</text><text x="10" y="70" font-family="sans-serif">sans-serif text</text><text x="10" y="105" font-family="monospace">monospace text</text><text x="10" y="140" font-family="cursive">cursive text</text><text x="10" y="175" font-family="fantasy">fantasy text</text></g>'),
    'text-font-family-list': ('the first available family of a list is used', '<g font-size="24"><text x="10" y="60" font-family="No Such Font, Noto Serif">Second</text><text x="10" y="120" font-family="\'Missing One\', \'Missing Two\', Noto Mono">Third</text></g>'),
    'text-font-fallback-per-character': ('characters the chosen font lacks come from other fonts: Devanagari and Arabic after Latin', '<text x="10" y="100" ' + SANS + ' font-size="24">Aa नमस्ते سلام</text>'),
    'text-font-default-family': ('text without font-family uses the default family', '<text x="20" y="100" font-size="30">Default</text>'),
    'text-font-variation-weight': ('a variable font at several weights', '<g font-family="Roboto Flex" font-size="26"><text x="10" y="50" font-weight="200">Flex 200</text><text x="10" y="100" font-weight="500">Flex 500</text><text x="10" y="150" font-weight="900">Flex 900</text></g>'),
    # --- colour glyphs ---------------------------------------------------------------------------
    'text-color-colrv1': ('COLRv1 glyphs: layers, gradients and transforms', '<text x="100" y="110" font-family="Noto Color Emoji COLR" font-size="36" text-anchor="middle">🐶🐝🌓🥳</text>'),
    'text-color-colrv1-large': ('one COLRv1 glyph, large', '<text x="100" y="150" font-family="Noto Color Emoji COLR" font-size="120" text-anchor="middle">🥳</text>'),
    'text-color-colrv0': ('COLRv0 glyphs with plain glyphs', '<text x="100" y="110" font-family="Noto Znamenny Musical Notation" font-size="40" text-anchor="middle">𜽜𜼽 𜽱𜼆</text>'),
    'text-color-cbdt': ('a CBDT bitmap glyph', '<text x="100" y="130" font-family="Noto Color Emoji" font-size="80" text-anchor="middle">😀</text>'),
    'text-color-svg-glyphs': ('SVG glyphs of an OpenType-SVG font', '<text x="100" y="120" font-family="Twitter Color Emoji" font-size="50" text-anchor="middle">😀🦀</text>'),
    'text-color-zwj-sequence': ('an emoji ZWJ sequence shaped into one glyph', '<text x="60" y="120" font-family="Twitter Color Emoji" font-size="70">🏳️‍🌈</text>'),
    'text-color-emoji-fallback': ('emoji taken from a colour font after a text font', '<text x="15" y="110" font-family="Noto Sans, Twitter Color Emoji" font-size="26">Hi 😀 there 🦀</text>'),
    'text-color-vertical': ('colour glyphs in vertical text stay upright', '<text x="100" y="15" font-family="Twitter Color Emoji" font-size="40" writing-mode="tb">😀😁🦀</text>'),
    'text-color-rotate': ('colour glyphs turned by rotate', '<text x="30" y="110" font-family="Noto Color Emoji COLR" font-size="40" rotate="0 20 -30 45">🐶🐝🌓🥳</text>'),
    # --- @font-face (stand-in references: resvg ignores @font-face) -------------------------------------
    'text-fontface-file': ('@font-face with a font file next to the document', '<desc>resvg ignores @font-face: the reference is golden/equivalent/text-fontface-file.svg, the same text in the installed family (Yellowtail) the file holds.</desc><style>@font-face { font-family: "Doc Script"; src: url(fonts/yellowtail-subset.ttf) format("truetype"); }</style><text x="20" y="110" font-family="Doc Script" font-size="48">Hello</text>'),
    'text-fontface-woff2-data': ('@font-face with a WOFF2 data URI', None),
    'text-fontface-local-and-weight': ('@font-face local() with a weight descriptor', '<desc>resvg ignores @font-face: the reference is golden/equivalent/text-fontface-local-and-weight.svg, where the family is the installed Noto Sans Black that local() names.</desc><style>@font-face { font-family: "Heavy"; src: local("Nope"), local("NotoSans-Black"); font-weight: 700; }</style><text x="20" y="110" font-family="Heavy" font-size="40" font-weight="bold">Heavy</text>'),
    # --- @font-face unicode-range (CSS Fonts 4, 4.5) ---------------------------------------------------
    'text-fontface-unicode-range-digits': ('unicode-range: a face for the digits only', '<desc>A face declared with unicode-range U+30-39 draws the digits only; the other characters (the spaces too) come from the next family of font-family. resvg ignores @font-face: the reference is golden/equivalent/text-fontface-unicode-range-digits.svg, the digits in a tspan of the installed family (Noto Serif).</desc><style>@font-face { font-family: "Digits"; src: local("NotoSerif-Regular"); unicode-range: U+30-39; }</style><text x="15" y="110" font-family="Digits, Noto Sans" font-size="30">Ab 2024 x9</text>'),
    'text-fontface-unicode-range-composite': ('unicode-range: one family split over two faces, the last rule first', '<desc>Two rules of one family: Noto Sans for U+0-7F and Noto Serif for the capitals U+41-5A. Where their ranges overlap the rule defined last is used (CSS Fonts 4, 4.5): the capitals are Noto Serif, the rest Noto Sans. resvg ignores @font-face: the reference is golden/equivalent/text-fontface-unicode-range-composite.svg, with tspans of the installed families.</desc><style>@font-face { font-family: "Split"; src: local("NotoSans-Regular"); unicode-range: U+0-7F; } @font-face { font-family: "Split"; src: local("NotoSerif-Regular"); unicode-range: U+41-5A; }</style><text x="15" y="110" font-family="Split" font-size="28">Hello World</text>'),
    'text-fontface-unicode-range-wildcard-list': ('unicode-range: a wildcard and a comma list', '<desc>unicode-range U+4??, U+26 (Cyrillic U+400-4FF and the ampersand) on a Noto Serif face: those characters are Noto Serif, the Latin ones and spaces the next family (Noto Sans). resvg ignores @font-face: the reference is golden/equivalent/text-fontface-unicode-range-wildcard-list.svg, with tspans of the installed families.</desc><style>@font-face { font-family: "Cyr"; src: local("NotoSerif-Regular"); unicode-range: u+4??, U+26; }</style><text x="15" y="110" font-family="Cyr, Noto Sans" font-size="30">Мир &amp; peace</text>'),
    'text-fontface-unicode-range-invalid': ('unicode-range: an invalid range drops the descriptor', '<desc>unicode-range U+0041, U+00FF-0025 has a range that ends before it starts: the descriptor is invalid and ignored, so the face (Noto Serif) draws every character. resvg ignores @font-face: the reference is golden/equivalent/text-fontface-unicode-range-invalid.svg, the text in the installed Noto Serif.</desc><style>@font-face { font-family: "Whole"; src: local("NotoSerif-Regular"); unicode-range: U+0041, U+00FF-0025; }</style><text x="15" y="110" font-family="Whole, Noto Sans" font-size="30">Ab 2024 x9</text>'),
}


PAR_CASES = {
    'structure-preserveaspectratio-xMidYMid-meet': 'xMidYMid meet',
    'structure-preserveaspectratio-xMinYMax-meet': 'xMinYMax meet',
    'structure-preserveaspectratio-xMaxYMin-slice': 'xMaxYMin slice',
    'structure-preserveaspectratio-none': 'none',
}


SUITE_FONTS = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..',
                                           '..', 'shared', 'resvg-suite', 'fonts'))
#: Stand-in documents for the references of cases resvg cannot draw (see
#: golden/regenerate.py): the @font-face family replaced by the installed one.
STANDINS = {
    'text-fontface-file': [('font-family="Doc Script"', 'font-family="Yellowtail"')],
    'text-fontface-woff2-data': [('font-family="Inline Script"', 'font-family="Yellowtail"')],
    'text-fontface-local-and-weight': [('font-family="Heavy"', 'font-family="Noto Sans"'),
                                       ('font-weight="bold"', 'font-weight="900"')],
    'text-fontface-unicode-range-digits': [
        ('font-family="Digits, Noto Sans" font-size="30">Ab 2024 x9',
         'font-family="Noto Sans" font-size="30">Ab <tspan font-family="Noto Serif">2024</tspan> '
         'x<tspan font-family="Noto Serif">9</tspan>')],
    'text-fontface-unicode-range-composite': [
        ('font-family="Split" font-size="28">Hello World',
         'font-family="Noto Sans" font-size="28"><tspan font-family="Noto Serif">H</tspan>ello '
         '<tspan font-family="Noto Serif">W</tspan>orld')],
    'text-fontface-unicode-range-wildcard-list': [
        ('font-family="Cyr, Noto Sans" font-size="30">Мир &amp; peace',
         'font-family="Noto Sans" font-size="30"><tspan font-family="Noto Serif">Мир</tspan> '
         '<tspan font-family="Noto Serif">&amp;</tspan> peace')],
    'text-fontface-unicode-range-invalid': [('font-family="Whole, Noto Sans"',
                                             'font-family="Noto Serif"')],
    'text-font-relative-weights': [('font-weight="lighter"', 'font-weight="400"'),
                                   ('font-weight="bolder"', 'font-weight="400"')],
}


def subset_font(dst):
    """golden/cases/fonts/yellowtail-subset.ttf: Yellowtail (Apache 2.0,
    its licence beside it) cut down to the letters of 'Hello'."""
    import shutil
    from fontTools import subset
    os.makedirs(os.path.dirname(dst), exist_ok=True)
    opts = subset.Options()
    opts.name_IDs = ['*']
    font = subset.load_font(os.path.join(SUITE_FONTS, 'Yellowtail-Regular.ttf'), opts)
    sub = subset.Subsetter(opts)
    sub.populate(text='Hello ')
    sub.subset(font)
    subset.save_font(font, dst, opts)
    shutil.copy(os.path.join(SUITE_FONTS, 'Yellowtail-LICENSE-Apache2.txt'),
                os.path.join(os.path.dirname(dst), 'Yellowtail-LICENSE-Apache2.txt'))


def woff2_data_uri(path):
    import base64
    import io
    from fontTools.ttLib import TTFont
    tt = TTFont(path)
    tt.flavor = 'woff2'
    buf = io.BytesIO()
    tt.save(buf)
    return 'data:font/woff2;base64,' + base64.b64encode(buf.getvalue()).decode()


def main():
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'cases')
    os.makedirs(here, exist_ok=True)
    for name, (title, body) in CASES.items():
        with open(os.path.join(here, name + '.svg'), 'w') as f:
            f.write(HEAD.format(title=title) + '  ' + body + '\n</svg>\n')
    font = os.path.join(here, 'fonts', 'yellowtail-subset.ttf')
    subset_font(font)
    standins = os.path.join(os.path.dirname(here), 'equivalent')
    os.makedirs(standins, exist_ok=True)
    for name, (title, body) in TEXT_CASES.items():
        if name == 'text-fontface-woff2-data':
            body = ('<desc>resvg ignores @font-face: the reference is golden/equivalent/%s.svg, '
                    'the same text in the installed family (Yellowtail) the WOFF2 data holds '
                    '(a subset of Yellowtail, Apache 2.0: golden/cases/fonts).</desc><style>'
                    '@font-face { font-family: "Inline Script"; src: url(%s) format("woff2"); }'
                    '</style><text x="20" y="110" font-family="Inline Script" font-size="48">'
                    'Hello</text>' % (name, woff2_data_uri(font)))
        svg = HEAD.format(title=title) + '  ' + body + '\n</svg>\n'
        with open(os.path.join(here, name + '.svg'), 'w') as f:
            f.write(svg)
        if name in STANDINS:
            import re
            stand = re.sub(r'<style>.*?</style>', '', svg, flags=re.S)
            stand = re.sub(r'<desc>.*?</desc>', '', stand, flags=re.S)
            for old, new in STANDINS[name]:
                stand = stand.replace(old, new)
            with open(os.path.join(standins, name + '.svg'), 'w') as f:
                f.write(stand)
    for name, par in PAR_CASES.items():
        body = ('<svg x="20" y="40" width="160" height="120" viewBox="0 0 100 50" preserveAspectRatio="%s">'
                '<rect x="0.5" y="0.5" width="99" height="49" fill="#edf2f4" stroke="#777"/>'
                '<circle cx="25" cy="25" r="20" fill="#ef233c"/><rect x="60" y="10" width="30" height="30" fill="#2b2d42"/>'
                '</svg>' % par)
        svg = HEAD.format(title='preserveAspectRatio ' + par) + '  ' + body + '\n</svg>\n'
        with open(os.path.join(here, name + '.svg'), 'w') as f:
            f.write(svg)
    # the rules of issue 14 (golden/rules.py): a <desc> states each rule
    for name, (title, desc, body) in rules.CASES.items():
        head = HEAD.format(title=title).replace(
            '</title>\n', '</title>\n  <desc>%s</desc>\n' % desc, 1)
        with open(os.path.join(here, name + '.svg'), 'w') as f:
            f.write(head + '  ' + body + '\n</svg>\n')
    for name, doc in rules.DOCS.items():
        with open(os.path.join(here, name + '.svg'), 'w') as f:
            f.write(doc)
    for name, text in rules.CSS_FILES.items():
        os.makedirs(os.path.join(here, 'lib'), exist_ok=True)
        with open(os.path.join(here, 'lib', name), 'w') as f:
            f.write(text)
    eq = os.path.join(os.path.dirname(here), 'equivalent')
    for name, (title, body) in rules.EQUIVALENT.items():
        os.makedirs(eq, exist_ok=True)
        with open(os.path.join(eq, name + '.svg'), 'w') as f:
            f.write(HEAD.format(title=title) + '  ' + body + '\n</svg>\n')


if __name__ == '__main__':
    main()
