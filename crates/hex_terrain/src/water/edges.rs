//! Rivers on the edges between tiles (`rivers.model: Edges`), built with the per-map tile table
//! of a bounded map: the network of corners (the points where three tiles meet) and the edges
//! between them, from the tiles' center heights, kinds, lakes and rain.
//!
//! A corner's height is the mean of its tiles' in the map; a corner touching the sea, a lake or
//! the map's edge is an outlet. Every other corner drains into one of its three neighbors
//! ([`super::descent`]: down the steepest slope, and out of a depression over its spill point,
//! the depression filled to that height), so every path downstream ends at an outlet, never
//! rises in water level and never loops. Each land tile's rain goes a sixth to each of its
//! corners and flows downstream, added up from the top of each path down. An edge carries a
//! river where the flow of its upstream corner reaches `rivers.threshold`, unless every source
//! of that river rises nearer the sea than `rivers.sea_distance` tiles. A river set by hand
//! ([`RiverEdit`]) rises at its tile's lowest corner that drains (`Source`, wherever it lies),
//! or keeps every corner of its tile, and all that drains through them, dry (`Dry`). A corner
//! that drains has three land tiles of the map, so every river edge lies between two land
//! tiles of the map.
//!
//! The corners are kept in a grid over the map, two a tile ([`super::corners`]), and read
//! their tiles and neighbors from a few stencils: fixed index shifts away from the map's edges.

use hexx::{EdgeDirection, GridEdge, GridVertex, Hex, HexOrientation};
use serde::{Deserialize, Serialize};

use super::corners::{CornerGrid, Owners, Shape, Stencils};
use super::descent::{Drainage, NONE, Role, drain};
use super::sources::{SourceInput, distances, relief_sources};
use crate::chunk::TileRect;
use crate::config::{RiverConfig, RiverEdit, RiverSources};
use crate::geometry::{Geometry, OFFSET_MODE};
use crate::vocab::TileKind;

/// A river edge of a tile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct RiverEdge {
    /// The edge, from the tile asked about toward the neighbor across the river.
    pub edge: GridEdge,
    /// Water the river carries along it.
    pub flow: f32,
    /// The corner it flows toward, one of the edge's two (as seen from the tile asked about).
    pub downstream: GridVertex,
    /// Water level (normalised height) at the corner it flows from; a river's level never rises
    /// downstream.
    pub level: f32,
}

/// The edge river network of a bounded map.
#[derive(Debug, Clone)]
pub struct EdgeRivers {
    /// The map's orientation, to name its tiles.
    orientation: HexOrientation,
    /// Where the corners are kept, how a tile names its corners, and each corner's neighbors.
    grid: CornerGrid,
    shape: Shape,
    owners: Owners,
    stencils: Stencils,
    /// Downstream corner of each corner; [`NONE`] for outlets and unused corners.
    down: Vec<u32>,
    /// Water level of each corner.
    level: Vec<f32>,
    /// Water each corner collects from itself and upstream.
    flow: Vec<f32>,
    /// Whether the edge from each corner to its downstream corner carries a river.
    river: Vec<bool>,
    /// Per map tile, row-major: bit `d` set when its edge toward `all_neighbors()[d]` carries a
    /// river.
    edges: Vec<u8>,
    /// Per map tile with a river edge, its place in `widths` ([`NONE`] for the others).
    river_tile: Vec<u32>,
    /// Per map tile with a river edge, the channel's half-width in lattice steps along each of
    /// its six edges (0: no river there); the two tiles of an edge give it the same.
    widths: Vec<[f32; 6]>,
}

/// The figures of an edge river network ([`EdgeRivers::figures`]).
pub(crate) struct EdgeFigures {
    pub systems: u32,
    pub tiles: u32,
    pub edges: u32,
    pub longest: u32,
    /// Each source's length in edges and its tiles (map tile indices).
    pub sources: Vec<(u32, Vec<usize>)>,
    /// Each system's mouth: the last edge's downstream corner, as its tiles (map tile indices;
    /// `None` past the map).
    pub mouths: Vec<[Option<usize>; 3]>,
}

/// The channel half-widths of a tile without a river edge.
const NO_WIDTHS: [f32; 6] = [0.0; 6];

/// What the network is built from: the map's tiles, row by row.
pub(crate) struct EdgeInput<'a> {
    /// The map's tiles' rectangle.
    pub rect: TileRect,
    /// Each tile's six neighbors (`hydrology::tile_links`: the tile itself past the map).
    pub links: &'a [[u32; 6]],
    /// Each tile's center height, raw.
    pub raw: &'a [f32],
    /// Each tile's kind.
    pub kinds: &'a [TileKind],
    /// Whether each tile is a lake tile.
    pub lakes: &'a [bool],
    /// Each tile's rain.
    pub rain: &'a [f32],
    /// Each tile's river set by hand (empty when no tile has one).
    pub by_hand: &'a [Option<RiverEdit>],
    /// Whether each tile is hills or a mountain (read by [`RiverSources::Relief`]; empty
    /// otherwise).
    pub relief: &'a [bool],
}

/// What the corner pass gives each corner.
struct Corners {
    roles: Vec<Role>,
    /// Whether its tiles all lie at least `sea_distance` from the sea.
    inland: Vec<bool>,
    /// Its height (the mean of its tiles'), to become its water level.
    level: Vec<f32>,
    /// The rain falling on it.
    rain: Vec<f32>,
    /// The corners across its edges, the corner itself past the grid.
    links: Vec<[u32; 3]>,
}

impl EdgeRivers {
    /// Builds the network.
    pub(crate) fn build(config: &RiverConfig, geometry: &Geometry, input: &EdgeInput<'_>) -> Self {
        let grid = CornerGrid::new(input.rect, geometry.wrap().is_some());
        let shape = Shape::new();
        let owners = Owners::new(geometry, &shape);
        let stencils = Stencils::new(geometry);
        let near = near_sea(input, config.sea_distance);
        let Corners { roles, inland, mut level, rain, links } = corners(&grid, &stencils, input, &near);
        let n = grid.len();
        let Drainage { down, order } = drain(&roles, &mut level, &links);
        let mut flow = rain;
        // Rivers set by hand: a dry tile's corners, and every corner draining through them,
        // carry nothing; a source rises at the tile's lowest corner that drains.
        let mut source = vec![false; n];
        let mut dry = vec![false; n];
        if !input.by_hand.is_empty() {
            for (i, edit) in input.by_hand.iter().enumerate() {
                let Some(edit) = edit else { continue };
                let ring = grid.tile_corners(&shape, &owners, grid.tile_offset(i));
                match edit {
                    RiverEdit::Dry => ring.iter().for_each(|&c| dry[c as usize] = true),
                    RiverEdit::Source => {
                        let lowest = ring
                            .iter()
                            .map(|&c| c as usize)
                            .filter(|&c| down[c] != NONE)
                            .min_by(|&a, &b| level[a].total_cmp(&level[b]));
                        if let Some(c) = lowest {
                            source[c] = true;
                        }
                    }
                }
            }
            // Downstream first: a corner is dry when it or the corner it drains into is.
            for c in order.iter().map(|&c| c as usize) {
                dry[c] |= down[c] != NONE && dry[down[c] as usize];
                if dry[c] {
                    flow[c] = 0.0;
                    source[c] = false;
                } else if source[c] {
                    flow[c] = flow[c].max(config.threshold);
                }
            }
        }
        for c in order.iter().rev().map(|&c| c as usize) {
            if down[c] != NONE {
                flow[down[c] as usize] += flow[c];
            }
        }
        let count = input.raw.len();
        let mut network = Self {
            orientation: geometry.layout().orientation,
            grid,
            shape,
            owners,
            stencils,
            down,
            level,
            flow,
            river: Vec::new(),
            edges: vec![0; count],
            river_tile: vec![NONE; count],
            widths: Vec::new(),
        };
        network.river = match config.sources {
            RiverSources::Flow => network.rivers(config, &order, &inland, &source),
            RiverSources::Relief { tiles_per_edge } => {
                let corner_tiles: Vec<[u32; 3]> = (0..n).map(|c| network.corner_tiles(c)).collect();
                let lake = input.lakes;
                let sea: Vec<bool> = input.kinds.iter().map(|&k| k == TileKind::Sea).collect();
                let choice = SourceInput {
                    down: &network.down,
                    order: &order,
                    corner_tiles: &corner_tiles,
                    links: input.links,
                    sea: &sea,
                    lake,
                    relief: input.relief,
                    dry: &dry,
                    by_hand: &source,
                };
                relief_sources(&choice, tiles_per_edge, config.sea_distance)
            }
        };
        let width = |flow: f32| config.width * (flow / config.threshold).sqrt().clamp(1.0, 2.0);
        for (c, links) in links.iter().enumerate() {
            if network.river[c] {
                let (i, d) = network.edge_down(c, links);
                let other = input.links[i][d] as usize;
                debug_assert_ne!(other, i, "a river edge lies between map tiles");
                let w = width(network.flow[c]);
                for (tile, d) in [(i, d), (other, (d + 3) % 6)] {
                    if network.river_tile[tile] == NONE {
                        network.river_tile[tile] = network.widths.len() as u32;
                        network.widths.push(NO_WIDTHS);
                    }
                    network.edges[tile] |= 1 << d;
                    network.widths[network.river_tile[tile] as usize][d] = w;
                }
            }
        }
        network
    }

    /// Which corners' downstream edges carry a river: those whose flow reaches the threshold,
    /// downstream of a source (a river corner no river flows into) whose tiles all lie at least
    /// `sea_distance` from the sea, or downstream of a corner set by hand (whatever flows into
    /// it).
    fn rivers(&self, config: &RiverConfig, order: &[u32], inland: &[bool], by_hand: &[bool]) -> Vec<bool> {
        let (down, flow) = (&self.down, &self.flow);
        let n = down.len();
        let wet: Vec<bool> = (0..n).map(|c| down[c] != NONE && flow[c] >= config.threshold).collect();
        let mut fed = vec![false; n];
        for c in 0..n {
            if wet[c] {
                fed[down[c] as usize] = true;
            }
        }
        let mut keep = vec![false; n];
        for c in order.iter().rev().map(|&c| c as usize) {
            if !wet[c] {
                continue;
            }
            // A river set by hand rises here even where a stream dropped for rising too near
            // the sea already flows in.
            if by_hand[c] || (!fed[c] && inland[c]) {
                keep[c] = true;
            }
            let next = down[c] as usize;
            if keep[c] && wet[next] {
                keep[next] = true;
            }
        }
        keep
    }

    /// The edge from corner `c` (its `links`) to its downstream corner: a map tile beside it and
    /// its direction from that tile.
    fn edge_down(&self, c: usize, links: &[u32; 3]) -> (usize, usize) {
        let m = links.iter().position(|&j| j == self.down[c]).expect("the downstream corner is a neighbor");
        let (owner, k) = self.grid.owner(c);
        let ([dc, dr], direction) = self.stencils.of(owner, k).edges[m];
        let tile = self.grid.tile([owner[0] + dc, owner[1] + dr]).expect("a river edge lies between map tiles");
        (tile, usize::from(direction))
    }

    /// The network's figures: river systems (one a last edge, whose downstream corner no
    /// river leaves), map tiles with a river edge, river edges, the most edges from a source to
    /// its mouth, and each source (a river corner no river flows into) with its length in edges
    /// and its tiles (map tile indices, row by row).
    pub(crate) fn figures(&self) -> EdgeFigures {
        let n = self.down.len();
        let river = |c: usize| self.river[c];
        let next = |c: usize| Some(self.down[c] as usize).filter(|&d| self.down[c] != NONE && river(d));
        let to_mouth = super::steps_to_mouth(n, (0..n).filter(|&c| river(c)), next);
        let mut fed = vec![false; n];
        for d in (0..n).filter(|&c| river(c)).filter_map(next) {
            fed[d] = true;
        }
        let sources = (0..n)
            .filter(|&c| river(c) && !fed[c])
            .map(|c| {
                let tiles = self.corner_tiles(c).into_iter().filter(|&i| i != NONE).map(|i| i as usize).collect();
                (to_mouth[c], tiles)
            })
            .collect();
        let tile = |i: u32| (i != NONE).then_some(i as usize);
        EdgeFigures {
            mouths: (0..n)
                .filter(|&c| river(c) && next(c).is_none())
                .map(|c| self.corner_tiles(self.down[c] as usize).map(tile))
                .collect(),
            systems: (0..n).filter(|&c| river(c) && next(c).is_none()).count() as u32,
            tiles: self.edges.iter().filter(|&&e| e != 0).count() as u32,
            edges: (0..n).filter(|&c| river(c)).count() as u32,
            longest: to_mouth.into_iter().max().unwrap_or(0),
            sources,
        }
    }

    /// Corner `c`'s map tiles ([`NONE`] past the map).
    fn corner_tiles(&self, c: usize) -> [u32; 3] {
        let (owner, k) = self.grid.owner(c);
        self.stencils
            .of(owner, k)
            .tiles
            .map(|[dc, dr]| self.grid.tile([owner[0] + dc, owner[1] + dr]).map_or(NONE, |i| i as u32))
    }

    /// The river edges of map tile `i`, a bit for each neighbor direction.
    #[must_use]
    #[inline]
    pub(crate) fn edges_of(&self, i: usize) -> u8 {
        self.edges[i]
    }

    /// The channel half-widths of map tile `i` along its six edges, in lattice steps (0: none).
    #[must_use]
    #[inline]
    pub(crate) fn widths(&self, i: usize) -> &[f32; 6] {
        self.widths.get(self.river_tile[i] as usize).unwrap_or(&NO_WIDTHS)
    }

    /// Map tile `i`'s hexagon.
    fn tile(&self, i: usize) -> Hex {
        Hex::from_offset_coordinates(self.grid.tile_offset(i), OFFSET_MODE, self.orientation)
    }

    /// The links of corner `c`: the corners across its edges (the corner itself past the grid).
    fn links(&self, c: usize) -> [u32; 3] {
        let (owner, k) = self.grid.owner(c);
        self.grid.links(self.stencils.of(owner, k), owner, c)
    }

    /// The two corners at the ends of map tile `i`'s edge `d`, in the order of the edge's
    /// vertices.
    fn ends(&self, i: usize, d: usize) -> (usize, usize) {
        let ring = self.grid.tile_corners(&self.shape, &self.owners, self.grid.tile_offset(i));
        let (a, b) = self.shape.ends[d];
        (ring[a] as usize, ring[b] as usize)
    }

    /// The river edges of `tile` (map tile `i`), from its side.
    pub(crate) fn river_edges(&self, tile: Hex, i: usize) -> Vec<RiverEdge> {
        let mask = self.edges[i];
        EdgeDirection::ALL_DIRECTIONS
            .into_iter()
            .enumerate()
            .filter(|&(d, _)| mask & (1 << d) != 0)
            .map(|(d, direction)| {
                let edge = GridEdge { origin: tile, direction };
                let [p, q] = edge.vertices();
                let (a, b) = self.ends(i, d);
                // The river runs from one end to the other: the end whose downstream is the other.
                let (from, to) = if self.river[a] && self.down[a] == b as u32 { (a, q) } else { (b, p) };
                RiverEdge { edge, flow: self.flow[from], downstream: to, level: self.level[from] }
            })
            .collect()
    }

    /// The river's course from map tile `i`'s edge `d` (a river edge) down to where it ends:
    /// each edge, named from a map tile beside it, in order.
    pub(crate) fn course(&self, i: usize, d: usize) -> Vec<GridEdge> {
        let (a, b) = self.ends(i, d);
        let mut at = if self.river[a] && self.down[a] == b as u32 {
            a
        } else if self.river[b] && self.down[b] == a as u32 {
            b
        } else {
            return Vec::new();
        };
        let mut out = Vec::new();
        while self.river[at] {
            let (tile, d) = self.edge_down(at, &self.links(at));
            out.push(GridEdge { origin: self.tile(tile), direction: EdgeDirection::ALL_DIRECTIONS[d] });
            at = self.down[at] as usize;
        }
        out
    }

    /// Whether map tile `i` has the same river edges, as wide, in `self` and `other`.
    #[must_use]
    pub(crate) fn same_tile(&self, other: &Self, i: usize) -> bool {
        self.edges[i] == other.edges[i] && self.widths(i).map(f32::to_bits) == other.widths(i).map(f32::to_bits)
    }
}

/// A tile on water.
const WET: u8 = 1;
/// A tile at least `sea_distance` from the sea.
const INLAND: u8 = 2;

/// What a corner reads of each of its tiles.
#[derive(Clone, Copy)]
struct TileInfo {
    raw: f32,
    /// A sixth of its rain (0 on water).
    rain: f32,
    /// [`WET`], and [`INLAND`] when at least `sea_distance` from the sea.
    flags: u8,
}

/// Each corner's flags, height, rain and links, in one pass over the corner grid's rows.
fn corners(grid: &CornerGrid, stencils: &Stencils, input: &EdgeInput<'_>, near: &[bool]) -> Corners {
    let info: Vec<TileInfo> = (0..input.raw.len())
        .map(|i| {
            let wet = input.kinds[i] == TileKind::Sea || input.lakes[i];
            TileInfo {
                raw: input.raw[i],
                rain: if wet { 0.0 } else { input.rain[i] / 6.0 },
                flags: if wet { WET } else { 0 } | if near[i] { 0 } else { INLAND },
            }
        })
        .collect();
    let n = grid.len();
    let mut out = Corners {
        roles: vec![Role::Unused; n],
        inland: vec![false; n],
        level: vec![0.0; n],
        rain: vec![0.0; n],
        links: vec![[NONE; 3]; n],
    };
    let (width, height) = grid.size();
    let (cols, rows) = grid.map_size();
    // Inside the map by the stencils' reach, a corner's tiles and links lie at fixed distances
    // in the tile rows and the corner grid: no wrap, no bound to check.
    let reach = stencils.reach();
    let inside = |[col, row]: [i32; 2]| {
        let (col, row) = grid.map_col_row([col, row]);
        col >= reach && col < cols - reach && row >= reach && row < rows - reach
    };
    let shifts = stencils.shifts(cols as isize, width as isize * 2);
    for row in 0..height {
        for col in 0..width {
            let owner = grid.offset_at(col, row);
            let inside = inside(owner);
            for k in 0..2 {
                let c = (row * width + col) * 2 + k;
                let (tiles, links) = if inside {
                    let (tiles, links) = shifts.of(owner, k);
                    let (mc, mr) = grid.map_col_row(owner);
                    let base = mr as isize * cols as isize + mc as isize;
                    (tiles.map(|d| (base + d) as u32), links.map(|d| (c as isize + d) as u32))
                } else {
                    let stencil = stencils.of(owner, k);
                    let at = |[dc, dr]: [i32; 2]| [owner[0] + dc, owner[1] + dr];
                    (stencil.tiles.map(|d| grid.tile(at(d)).map_or(NONE, |i| i as u32)), grid.links(stencil, owner, c))
                };
                let (mut sum, mut count, mut rain, mut flags) = (0.0_f32, 0_u8, 0.0_f32, INLAND);
                for i in tiles {
                    if i != NONE {
                        let tile = info[i as usize];
                        sum += tile.raw;
                        count += 1;
                        rain += tile.rain;
                        flags = (flags | (tile.flags & WET)) & (tile.flags | !INLAND);
                    }
                }
                if count > 0 {
                    out.roles[c] = if count < 3 || flags & WET != 0 { Role::Outlet } else { Role::Drains };
                    out.inland[c] = flags & INLAND != 0;
                    out.level[c] = sum / f32::from(count);
                    out.rain[c] = rain;
                    out.links[c] = links;
                }
            }
        }
    }
    out
}

/// Whether each map tile lies nearer the sea than `distance` tiles (steps over the map from the
/// nearest sea tile).
fn near_sea(input: &EdgeInput<'_>, distance: u32) -> Vec<bool> {
    let sea = (0..input.kinds.len()).filter(|&i| input.kinds[i] == TileKind::Sea);
    distances(input.links, sea, distance).into_iter().map(|d| d < distance).collect()
}
