#!/usr/bin/python3
"""Checks gearkit gmsh meshes with meshio, independently of gmsh and deal.II.

For each <mesh>.msh (with its <mesh>.msh.json sidecar written by meshes/): only hexahedra in the
volume and quadrilaterals on the surfaces, every physical group the sidecar lists present and
non-empty, no inverted or degenerate hexahedron (Jacobian determinant at all eight corners
positive, and the smallest corner Jacobian not below 1e-3 of the element's mean one), and the
mesh volume within 1 % of the analytic segment volume. With --png, a picture of the end face
z = -b/2 is written next to the mesh. Exit status 1 and one line per failure otherwise.

usage: check_mesh.py [--png] mesh.msh [mesh.msh ...]
"""
import json
import sys

import meshio
import numpy as np

# trilinear hexahedron, gmsh/meshio node order: bottom 0-3, top 4-7, counter-clockwise
CORNERS = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                    [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)


def jacobians(x, points):
    """Jacobian determinants of hexahedra x (n, 8, 3) at reference points (m, 3): (n, m)."""
    out = []
    for a, b, c in points:
        grad = np.stack([CORNERS[:, 0] * (1 + CORNERS[:, 1] * b) * (1 + CORNERS[:, 2] * c),
                         CORNERS[:, 1] * (1 + CORNERS[:, 0] * a) * (1 + CORNERS[:, 2] * c),
                         CORNERS[:, 2] * (1 + CORNERS[:, 0] * a) * (1 + CORNERS[:, 1] * b)],
                        axis=1) / 8.0  # (8, 3)
        J = np.einsum('nki,kj->nij', x, grad)
        out.append(np.linalg.det(J))
    return np.stack(out, axis=1)


def check(path, png):
    failures = []
    with open(path + '.json') as f:
        meta = json.load(f)
    mesh = meshio.read(path)
    volume_types = {c.type for c in mesh.cells if c.type in ('hexahedron', 'tetra', 'wedge', 'pyramid')}
    surface_types = {c.type for c in mesh.cells if c.type in ('quad', 'triangle')}
    if volume_types != {'hexahedron'}:
        failures.append(f'{path}: volume elements {sorted(volume_types)}, expected hexahedra only')
    if surface_types - {'quad'}:
        failures.append(f'{path}: surface elements {sorted(surface_types)}, expected quads only')

    tags = {name: tag for name, (tag, dim) in mesh.field_data.items()}
    expected = dict(meta['physical_surfaces'], **meta['physical_volumes'])
    for name, tag in expected.items():
        if tags.get(name) != tag:
            failures.append(f'{path}: physical group "{name}" ({tag}) missing')
    phys = mesh.cell_data.get('gmsh:physical', [])
    for name, tag in meta['physical_surfaces'].items():
        count = sum(int(np.sum(p == tag)) for c, p in zip(mesh.cells, phys) if c.type == 'quad')
        if count == 0:
            failures.append(f'{path}: physical surface "{name}" has no elements')

    hexes = np.concatenate([c.data for c in mesh.cells if c.type == 'hexahedron'])
    x = mesh.points[hexes]
    g = 1 / np.sqrt(3)
    corner_j = jacobians(x, CORNERS)
    gauss_j = jacobians(x, CORNERS * g)
    mean_j = gauss_j.mean(axis=1)
    bad = np.sum(corner_j.min(axis=1) <= 0)
    if bad:
        failures.append(f'{path}: {bad} inverted hexahedra (non-positive corner Jacobian)')
    degenerate = np.sum(corner_j.min(axis=1) < 1e-3 * mean_j)
    if degenerate:
        failures.append(f'{path}: {degenerate} degenerate hexahedra (corner Jacobian < 1e-3 mean)')
    volume = gauss_j.sum()
    error = volume / meta['analytic_volume'] - 1
    if abs(error) > 0.01:
        failures.append(f'{path}: volume {volume:.6e} m^3 is {100 * error:.2f} % off the analytic '
                        f'{meta["analytic_volume"]:.6e} m^3')
    print(f'{path}: {len(hexes)} hexahedra, {len(mesh.points)} nodes, volume error '
          f'{100 * error:+.3f} %, min corner Jacobian / mean {np.min(corner_j.min(axis=1) / mean_j):.3f}')

    if png:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
        from matplotlib.collections import PolyCollection
        z0 = mesh.points[:, 2].min()
        quads = np.concatenate([c.data for c in mesh.cells if c.type == 'quad'])
        front = quads[np.all(np.abs(mesh.points[quads][:, :, 2] - z0) < 1e-9, axis=1)]
        fig, ax = plt.subplots(figsize=(8, 8))
        ax.add_collection(PolyCollection(mesh.points[front][:, :, :2] * 1e3, facecolor='none',
                                         edgecolor='k', linewidth=0.3))
        for name, tag in meta['physical_surfaces'].items():
            if 'tooth' in name:
                sel = np.concatenate([c.data[p == tag] for c, p in zip(mesh.cells, phys)
                                      if c.type == 'quad'])
                pts = mesh.points[np.unique(sel)]
                pts = pts[np.abs(pts[:, 2] - z0) < 1e-9]
                ax.plot(pts[:, 0] * 1e3, pts[:, 1] * 1e3, '.', ms=3,
                        color='tab:red' if 'drive' in name else 'tab:blue')
        ax.autoscale()
        ax.set_aspect('equal')
        ax.set_xlabel('x [mm]')
        ax.set_ylabel('y [mm]')
        flanks = any('tooth' in name for name in meta['physical_surfaces'])
        ax.set_title(f'{meta["gear"]}: end face, {len(hexes)} hexahedra'
                     + (' (drive flank nodes red, coast blue)' if flanks else ''))
        fig.savefig(path[:-4] + '.png', dpi=150, bbox_inches='tight')
        plt.close(fig)
    return failures


def main(argv):
    png = '--png' in argv
    paths = [a for a in argv if a != '--png']
    if not paths:
        print(__doc__)
        return 2
    failures = []
    for p in paths:
        try:
            failures += check(p, png)
        except (OSError, ValueError, KeyError) as e:
            failures.append(f'{p}: cannot be checked: {e}')
    for f in failures:
        print('FAIL', f)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
