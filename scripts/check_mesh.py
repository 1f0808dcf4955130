#!/usr/bin/python3
"""Checks gearkit gmsh meshes with meshio, independently of gmsh and deal.II.

For each <mesh>.msh (with its <mesh>.msh.json sidecar written by meshes/): only hexahedra in the
volume and quadrilaterals on the surfaces, every physical group the sidecar lists present and
non-empty, no inverted or degenerate hexahedron (Jacobian determinant at all eight corners
positive, and the smallest corner Jacobian not below 1e-3 of the element's mean one), and the
mesh volume within 1 % of the analytic segment volume. With --png, a picture of the front end
face ("end_front": z = -b/2, or a bevel segment's toe; else the plane z = z_min) in its
best-fitting plane is written next to the mesh. Exit status 1 and one line per failure otherwise.

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
        # the front end face (a plane for involute segments, the toe's back cone for bevel
        # ones), drawn in its best-fitting plane
        quads = np.concatenate([c.data for c in mesh.cells if c.type == 'quad'])
        if 'end_front' in meta['physical_surfaces']:
            quads = np.concatenate([c.data[p == meta['physical_surfaces']['end_front']]
                                    for c, p in zip(mesh.cells, phys) if c.type == 'quad'])
        else:  # the plane z = z_min
            z = mesh.points[:, 2]
            quads = quads[np.all(np.abs(z[quads] - z.min()) < 1e-9, axis=1)]
        on_face = np.unique(quads)
        centre = mesh.points[on_face].mean(axis=0)
        axes = np.linalg.svd(mesh.points[on_face] - centre)[2]
        if abs(axes[2, 2]) > 1 - 1e-9:  # a plane z = const: x and y as they are
            axes = np.eye(3)
        axes = axes[:2]
        # across the teeth toward growing polar angle, and up toward the teeth (radially out)
        radial, tangential = np.array([centre[0], centre[1], 0]), np.array([-centre[1], centre[0], 0])
        if np.abs(axes[0] @ radial) > np.abs(axes[1] @ radial):
            axes = axes[::-1].copy()
        axes[0] *= np.sign(axes[0] @ tangential)
        axes[1] *= np.sign(axes[1] @ radial)
        flat = (mesh.points - centre) @ axes.T
        fig, ax = plt.subplots(figsize=(8, 8))
        ax.add_collection(PolyCollection(flat[quads] * 1e3, facecolor='none',
                                         edgecolor='k', linewidth=0.3))
        for name, tag in meta['physical_surfaces'].items():
            if 'tooth' in name:
                sel = np.concatenate([c.data[p == tag] for c, p in zip(mesh.cells, phys)
                                      if c.type == 'quad'])
                pts = np.intersect1d(np.unique(sel), on_face)
                ax.plot(flat[pts, 0] * 1e3, flat[pts, 1] * 1e3, '.', ms=3,
                        color='tab:red' if 'drive' in name else 'tab:blue')
        ax.autoscale()
        ax.set_aspect('equal')
        ax.set_xlabel('in the end face [mm]')
        ax.set_ylabel('[mm]')
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
