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

PAR_CASES = {
    'structure-preserveaspectratio-xMidYMid-meet': 'xMidYMid meet',
    'structure-preserveaspectratio-xMinYMax-meet': 'xMinYMax meet',
    'structure-preserveaspectratio-xMaxYMin-slice': 'xMaxYMin slice',
    'structure-preserveaspectratio-none': 'none',
}


def main():
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'cases')
    os.makedirs(here, exist_ok=True)
    for name, (title, body) in CASES.items():
        with open(os.path.join(here, name + '.svg'), 'w') as f:
            f.write(HEAD.format(title=title) + '  ' + body + '\n</svg>\n')
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
    eq = os.path.join(os.path.dirname(here), 'equivalent')
    for name, (title, body) in rules.EQUIVALENT.items():
        os.makedirs(eq, exist_ok=True)
        with open(os.path.join(eq, name + '.svg'), 'w') as f:
            f.write(HEAD.format(title=title) + '  ' + body + '\n</svg>\n')


if __name__ == '__main__':
    main()
