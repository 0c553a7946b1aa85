# samples/stone/column.awk — writes a fluted sandstone column as a closed, uv-mapped OBJ
# (y up, standing on y = 0, outward winding): a round plinth with a chamfered moulding, a
# tapering shaft with `flutes` vertical grooves, a flaring capital and a round abacus. No
# ledge is narrower than 4 cm, so a slab shell a few centimetres deep does not fold.
#   awk -f column.awk -v height=2.0 [-v segments=160 -v step=0.02 -v flutes=20] > column.obj
# With -v solid=1 it writes positions only, each vertex once (no uv seam, the discs sharing
# the rims): a connected closed mesh; a coarse one, e.g. segments=12 step=0.3 flutes=0,
# makes the slab mesh for `patina-texgen stone --slab-mesh`.
# The surface of revolution takes v in [0.26, 1] (u = angle / 2 pi from +z towards +x, v up
# the profile by arc length), the bottom and top discs the squares [0.005, 0.12]^2 and
# [0.13, 0.245]^2 of the uv square, as in the project's statue mesh.
function add(y, r, f) { ky[nk] = y; kr[nk] = r; kf[nk] = f; nk++ }
# Positions only, one vertex per ring and angle (index i * segments + j + 1), two disc
# centres last; rings that coincide with the previous one are skipped.
function write_solid(    i, j, m, phi, g, r, a, b, c, d, n) {
    m = 0
    for (i = 0; i < nr; i++) {
        if (i > 0 && ry[i] == ry[i-1] && rr[i] == rr[i-1]) continue
        keep[m++] = i
        for (j = 0; j < segments; j++) {
            phi = 2 * pi * j / segments
            g = sin(flutes * phi / 2); if (g < 0) g = -g
            r = rr[i] * (1 - depth * rf[i] * g)
            printf "v %.6f %.6f %.6f\n", s * r * sin(phi), s * ry[i], s * r * cos(phi)
        }
    }
    n = m * segments
    printf "v 0 0 0\nv 0 %.6f 0\n", s * ry[nr-1]
    for (i = 0; i < m - 1; i++)
        for (j = 0; j < segments; j++) {
            a = i * segments + j + 1; b = i * segments + (j + 1) % segments + 1
            d = a + segments; c = b + segments
            printf "f %d %d %d\nf %d %d %d\n", a, b, c, a, c, d
        }
    for (j = 0; j < segments; j++) {
        printf "f %d %d %d\n", n + 1, (j + 1) % segments + 1, j + 1
        printf "f %d %d %d\n", n + 2, (m - 1) * segments + j + 1, (m - 1) * segments + (j + 1) % segments + 1
    }
}
BEGIN {
    if (height == "") height = 2.0
    if (segments == "") segments = 160
    if (flutes == "") flutes = 20
    if (step == "") step = 0.02      # largest ring spacing along the profile (m, for 2 m)
    depth = 0.09                     # groove depth as a fraction of the shaft radius
    pi = atan2(0, -1)
    s = height / 2.0                 # the profile below is for a 2 m column
    # Profile key points: height, radius (m, for 2 m) and flute weight
    nk = 0
    add(0.00, 0.30, 0); add(0.10, 0.30, 0); add(0.14, 0.27, 0); add(0.20, 0.25, 0)
    add(0.25, 0.22, 1); add(1.70, 0.19, 1); add(1.76, 0.20, 0); add(1.86, 0.28, 0)
    add(1.90, 0.30, 0); add(2.00, 0.30, 0)
    # Rings: each profile segment cut into pieces of at most `step`
    nr = 0
    for (k = 0; k < nk - 1; k++) {
        len = sqrt((ky[k+1] - ky[k])^2 + (kr[k+1] - kr[k])^2)
        pieces = int(len / step) + 1
        for (p = 0; p < pieces; p++) {
            t = p / pieces
            ry[nr] = ky[k] + t * (ky[k+1] - ky[k]); rr[nr] = kr[k] + t * (kr[k+1] - kr[k])
            rf[nr] = kf[k] + t * (kf[k+1] - kf[k]); nr++
        }
    }
    ry[nr] = ky[nk-1]; rr[nr] = kr[nk-1]; rf[nr] = kf[nk-1]; nr++
    # Arc length along the profile for v
    arc[0] = 0
    for (i = 1; i < nr; i++) arc[i] = arc[i-1] + sqrt((ry[i] - ry[i-1])^2 + (rr[i] - rr[i-1])^2)
    print "# fluted column, " height " m, written by samples/stone/column.awk"
    print "o column"
    if (solid) { write_solid(); exit }
    # Surface of revolution: (nr) x (segments + 1) vertices, the seam duplicated for uv
    for (i = 0; i < nr; i++)
        for (j = 0; j <= segments; j++) {
            phi = 2 * pi * j / segments
            g = sin(flutes * phi / 2); if (g < 0) g = -g
            r = rr[i] * (1 - depth * rf[i] * g)
            printf "v %.6f %.6f %.6f\n", s * r * sin(phi), s * ry[i], s * r * cos(phi)
            printf "vt %.6f %.6f\n", j / segments, 0.26 + 0.74 * arc[i] / arc[nr-1]
        }
    nv = nr * (segments + 1)
    # Disc centres and their rims (bottom: ring 0, top: ring nr - 1)
    printf "v 0 0 0\nvt 0.0625 0.0625\n"
    printf "v 0 %.6f 0\nvt 0.1875 0.1875\n", s * ry[nr-1]
    bottom = nv + 1; top = nv + 2
    for (c = 0; c < 2; c++) {
        i = c == 0 ? 0 : nr - 1
        for (j = 0; j <= segments; j++) {
            phi = 2 * pi * j / segments
            printf "v %.6f %.6f %.6f\n", s * rr[i] * sin(phi), s * ry[i], s * rr[i] * cos(phi)
            cx = c == 0 ? 0.0625 : 0.1875
            printf "vt %.6f %.6f\n", cx + 0.0575 * sin(phi), cx + 0.0575 * cos(phi)
        }
    }
    rim0 = nv + 3; rim1 = rim0 + segments + 1
    # Faces (1-based), outward: (a, b, c), (a, c, d) with a lower-left going round +phi
    for (i = 0; i < nr - 1; i++)
        for (j = 0; j < segments; j++) {
            a = i * (segments + 1) + j + 1; b = a + 1; d = a + segments + 1; c = d + 1
            if (ry[i] == ry[i+1] && rr[i] == rr[i+1]) continue
            printf "f %d/%d %d/%d %d/%d\n", a, a, b, b, c, c
            printf "f %d/%d %d/%d %d/%d\n", a, a, c, c, d, d
        }
    for (j = 0; j < segments; j++) {
        printf "f %d/%d %d/%d %d/%d\n", bottom, bottom, rim0 + j + 1, rim0 + j + 1, rim0 + j, rim0 + j
        printf "f %d/%d %d/%d %d/%d\n", top, top, rim1 + j, rim1 + j, rim1 + j + 1, rim1 + j + 1
    }
}
