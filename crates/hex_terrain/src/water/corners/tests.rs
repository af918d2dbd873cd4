//! Unit tests of the corners' names, stencils and shifts.

use super::*;

/// A corner's three names give one corner; the shape's owners name a tile's corners, and
/// the ends of each edge are two of them, next to each other around the tile.
#[test]
fn corners_have_one_name_and_edges_two_ends() {
    for t in [Hex::ZERO, Hex::new(3, -5), Hex::new(-7, 2)] {
        for v in t.all_vertices() {
            let c = canonical(v);
            assert!(c.equivalent(&v) && c.direction.index() < 2);
            let names = [
                v,
                GridVertex { origin: v.origin + v.direction.direction_cw(), direction: v.direction.rotate_ccw(2) },
                GridVertex { origin: v.origin + v.direction.direction_ccw(), direction: v.direction.rotate_cw(2) },
            ];
            for name in names {
                assert_eq!(canonical(name), c, "{v:?} as {name:?}");
            }
        }
    }
    let shape = Shape::new();
    for (j, v) in Hex::ZERO.all_vertices().into_iter().enumerate() {
        let (owner, k) = shape.owners[j];
        assert!(
            GridVertex { origin: owner, direction: hexx::VertexDirection::ALL_DIRECTIONS[usize::from(k)] }
                .equivalent(&v)
        );
    }
    for &(a, b) in &shape.ends {
        assert!(a != b && (a + 1) % 6 == b || (b + 1) % 6 == a, "{a} {b}");
    }
    // A tile's corners from the owners' offset tables are the corners its vertices name,
    // for both layouts, wrapping or not.
    // Both layouts, wrapping or not, down to the narrowest wrapping map (4 columns).
    let maps = [
        (crate::Orientation::Pointy, false, 12, 9),
        (crate::Orientation::Flat, true, 12, 9),
        (crate::Orientation::Pointy, true, 4, 3),
        (crate::Orientation::Flat, true, 4, 2),
    ];
    for (orientation, wrap, x, z) in maps {
        let mut config = crate::MapConfig { size: crate::MapSize::Bounded { x, z }, wrap, ..Default::default() };
        config.layout.orientation = orientation;
        let geometry = Geometry::new(&config);
        let rect = geometry.bounds().unwrap();
        let grid = CornerGrid::new(rect, wrap);
        let owners = Owners::new(&geometry, &shape);
        let stencils = Stencils::new(&geometry);
        for oc in rect.iter() {
            let tile = geometry.tile_from_offset(oc);
            let named = tile.all_vertices().map(|v| {
                let c = canonical(v);
                let owner = if wrap { geometry.wrap_tile(c.origin) } else { c.origin };
                grid.index(&geometry, owner, c.direction.index()) as u32
            });
            let ring = grid.tile_corners(&shape, &owners, oc);
            assert_eq!(ring, named, "{orientation:?} {oc:?}");
            // Each corner's stencil names this tile among its tiles, and the corner next to
            // it around the tile among its links, with an edge that is the tile's edge
            // between them; the tile's neighbors by offset are its neighbors.
            let i = grid.tile(oc).unwrap();
            assert_eq!(grid.tile_offset(i), oc);
            for (d, &(a, b)) in shape.ends.iter().enumerate() {
                let (owner, k) = grid.owner(ring[a] as usize);
                let stencil = stencils.of(owner, k);
                let at = |[dc, dr]: [i32; 2]| [owner[0] + dc, owner[1] + dr];
                assert!(stencil.tiles.iter().any(|&t| grid.tile(at(t)) == Some(i)), "{oc:?} corner {a}");
                let m = (0..3)
                    .find(|&m| grid.at(at(stencil.links[m].0), stencil.links[m].1) == Some(ring[b] as usize))
                    .expect("the next corner around the tile is a link");
                let (t, direction) = stencil.edges[m];
                let edge = GridEdge {
                    origin: geometry.tile_from_offset(at(t)),
                    direction: EdgeDirection::ALL_DIRECTIONS[usize::from(direction)],
                };
                let mine = GridEdge { origin: tile, direction: EdgeDirection::ALL_DIRECTIONS[d] };
                let same = |e: GridEdge| [e.origin, e.destination()].map(|h| grid.tile(geometry.offset_of(h)));
                let (mut x, mut y) = (same(edge), same(mine));
                x.sort();
                y.sort();
                assert_eq!(x, y, "{orientation:?} {oc:?} edge {d}");
                let [dc, dr] = stencils.neighbors(oc)[d];
                let nb = geometry.offset_of(tile.all_neighbors()[d]);
                assert_eq!(grid.tile([oc[0] + dc, oc[1] + dr]), grid.tile(nb));
            }
        }
        // Away from the map's edges, the shifts give the stencils' tiles and links.
        let (width, height) = grid.size();
        let (cols, rows) = grid.map_size();
        let shifts = stencils.shifts(cols as isize, width as isize * 2);
        let reach = stencils.reach();
        assert!((1..=2).contains(&reach), "{reach}");
        let mut inside = 0;
        for c in 0..width * height * 2 {
            let (owner, k) = grid.owner(c);
            let (mc, mr) = grid.map_col_row(owner);
            if mc < reach || mc >= cols - reach || mr < reach || mr >= rows - reach {
                continue;
            }
            inside += 1;
            let stencil = stencils.of(owner, k);
            let (tiles, links) = shifts.of(owner, k);
            let base = (mr * cols + mc) as isize;
            let by_stencil = stencil.tiles.map(|[dc, dr]| grid.tile([owner[0] + dc, owner[1] + dr]));
            assert_eq!(tiles.map(|d| Some((base + d) as usize)), by_stencil, "{orientation:?} corner {c}");
            assert_eq!(
                links.map(|d| (c as isize + d) as u32),
                grid.links(stencil, owner, c),
                "{orientation:?} corner {c}"
            );
        }
        assert!(inside > 0 || x < 6 || z < 6);
        // A corner among three map tiles has three other corners as its links.
        for c in 0..width * height * 2 {
            let (owner, k) = grid.owner(c);
            let stencil = stencils.of(owner, k);
            if stencil.tiles.iter().all(|&[dc, dr]| grid.tile([owner[0] + dc, owner[1] + dr]).is_some()) {
                let links = grid.links(stencil, owner, c);
                assert!(
                    links[0] != links[1] && links[1] != links[2] && links[0] != links[2],
                    "{orientation:?} {x}x{z} corner {c}: {links:?}"
                );
                assert!(!links.contains(&(c as u32)), "{orientation:?} {x}x{z} corner {c}: {links:?}");
            }
        }
    }
    // `all_neighbors` runs in the edge directions' order.
    for (d, nb) in Hex::ZERO.all_neighbors().into_iter().enumerate() {
        assert_eq!(Hex::ZERO + EdgeDirection::ALL_DIRECTIONS[d], nb);
    }
}
