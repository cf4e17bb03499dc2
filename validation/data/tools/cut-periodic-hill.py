#!/usr/bin/env python3
"""Cuts validation/data/periodic-hill-xiao-2020-{profiles,wall}.csv from the OpenFOAM case
pehill-5-cases-OpenFOAM/case_1p0 of github.com/xiaoh/para-database-for-PIML (the DNS of Xiao,
Wu, Laizet and Duan 2020 mapped onto a 99 x 149 RANS mesh). validation/data/README.md describes
what is kept and how. Usage: cut-periodic-hill.py CASE_DIR OUT_DIR (pure Python, no packages)."""
import re
import sys


def foam_list(path):
    """The entries of an OpenFOAM ASCII list file (points, faces, owner, fields) as strings."""
    text = open(path).read()
    start = text.index('\n(\n', text.index('FoamFile'))
    count = int(text[:start].split()[-1])
    lines = text[start + 3:].splitlines()
    return [l.strip() for l in lines[:count]]


def vectors(path):
    return [[float(v) for v in e[1:-1].split()] for e in foam_list(path)]


def main(case, out):
    mesh = case + '/constant/polyMesh/'
    points = vectors(mesh + 'points')
    faces = [[int(v) for v in re.match(r'\d+\((.*)\)', e).group(1).split()]
             for e in foam_list(mesh + 'faces')]
    owner = [int(e) for e in foam_list(mesh + 'owner')]
    neighbour = [int(e) for e in foam_list(mesh + 'neighbour')]
    u = vectors(case + '/0/UDNS')
    tau = vectors(case + '/0/TauDNS')  # symmetric tensor xx xy xz yy yz zz
    # Cell centres: the mean of each hexahedron's eight vertices (x and y; z is the empty axis).
    verts = [set() for _ in u]
    for f, fv in enumerate(faces):
        verts[owner[f]].update(fv)
        if f < len(neighbour):
            verts[neighbour[f]].update(fv)
    centre = [(sum(points[v][0] for v in vs) / len(vs), sum(points[v][1] for v in vs) / len(vs))
              for vs in verts]
    ni, nj = 99, 149  # the mesh is structured: cell = j * 99 + i, j = 0 at the upper wall
    cell = lambda i, j: j * ni + i

    # Bulk velocity: the flux through a column (trapezoids, u = 0 at both walls) / 2.036 h,
    # averaged over the 99 columns (they agree to 0.2 %).
    def flux(i):
        ys = [centre[cell(i, j)][1] for j in reversed(range(nj))]
        us = [u[cell(i, j)][0] for j in reversed(range(nj))]
        y_wall = ys[0] - (ys[1] - ys[0]) / 2
        s = us[0] * (ys[0] - y_wall) / 2 + us[-1] * (3.036 - ys[-1]) / 2
        for a in range(nj - 1):
            s += 0.5 * (us[a] + us[a + 1]) * (ys[a + 1] - ys[a])
        return s
    ub = sum(flux(i) for i in range(ni)) / ni / 2.036

    with open(out + '/periodic-hill-xiao-2020-profiles.csv', 'w') as f:
        f.write('x_over_h,y_over_h,u_over_Ub,v_over_Ub,k_over_Ub2\n')
        for xs in [0.5, 1, 2, 3, 4, 5, 6, 7, 8]:
            for j in range(nj - 1, -1, -3):  # every third mesh line from the wall up
                row = sorted((centre[cell(i, j)][0], centre[cell(i, j)][1], u[cell(i, j)][0],
                              u[cell(i, j)][1], 0.5 * (tau[cell(i, j)][0] + tau[cell(i, j)][3] +
                                                       tau[cell(i, j)][5])) for i in range(ni))
                for a in range(ni - 1):
                    if row[a][0] <= xs <= row[a + 1][0]:  # linear in x along the mesh line
                        w = (xs - row[a][0]) / (row[a + 1][0] - row[a][0])
                        v = [row[a][q] * (1 - w) + row[a + 1][q] * w for q in range(5)]
                        f.write('%.3f,%.4f,%.4f,%.4f,%.5f\n' %
                                (xs, v[1], v[2] / ub, v[3] / ub, v[4] / ub ** 2))
                        break
    with open(out + '/periodic-hill-xiao-2020-wall.csv', 'w') as f:
        f.write('x_over_h,y_over_h,u_over_Ub\n')
        for x, y, ux in sorted((centre[cell(i, nj - 1)][0], centre[cell(i, nj - 1)][1],
                                u[cell(i, nj - 1)][0]) for i in range(ni)):
            f.write('%.4f,%.5f,%.5f\n' % (x, y, ux / ub))
    print('Ub = %.6g (Re_h = Ub h / nu = %.0f with nu = 5e-6)' % (ub, ub / 5e-6))


if __name__ == '__main__':
    main(sys.argv[1], sys.argv[2])
