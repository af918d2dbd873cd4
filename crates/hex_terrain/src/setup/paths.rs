//! Paths over land: path costs from starts (Dijkstra over the movement costs, across the seam
//! on a wrapping map), the land each start reaches before any rival, and the land masses.

use super::survey::{NONE, Survey};

/// Unreached.
pub(crate) const FAR: u32 = u32::MAX;

/// Path cost from `sources` to every tile (entering a tile costs its movement cost, crossing a
/// river on an edge the movement model's river cost more; impassable
/// tiles are never entered). Each tile also gets the source nearest it, and whether two
/// sources reach it at the same cost (contested).
pub(crate) struct Costs {
    pub dist: Vec<u32>,
    pub owner: Vec<u32>,
    pub contested: Vec<bool>,
}

/// Dijkstra from several sources at once; `sources[k]` is owner `k`. Movement costs are small
/// integers, so the queue is a ring of buckets, one a cost (Dial's algorithm): linear in the
/// tiles, and the order tiles settle in is fixed by the costs and the tile order alone.
pub(crate) fn costs(survey: &Survey, sources: &[usize]) -> Costs {
    let n = survey.len();
    let mut dist = vec![FAR; n];
    let mut owner = vec![NONE; n];
    let mut contested = vec![false; n];
    let ring = (survey.cost.iter().copied().max().unwrap_or(0) + survey.river_cost) as usize + 1;
    let mut buckets: Vec<Vec<u32>> = vec![Vec::new(); ring];
    let mut queued = 0usize;
    for (k, &s) in sources.iter().enumerate() {
        if dist[s] == 0 {
            contested[s] = true;
            continue;
        }
        dist[s] = 0;
        owner[s] = k as u32;
        buckets[0].push(s as u32);
        queued += 1;
    }
    let mut d = 0u32;
    while queued > 0 {
        let slot = d as usize % ring;
        let mut bucket = std::mem::take(&mut buckets[slot]);
        queued -= bucket.len();
        for &u in &bucket {
            let u = u as usize;
            if dist[u] != d {
                continue;
            }
            for (k, &v) in survey.neighbors[u].iter().enumerate() {
                if v == NONE {
                    continue;
                }
                let v = v as usize;
                let c = survey.cost[v];
                if c == 0 {
                    continue;
                }
                let across = if survey.crossing[u] & (1 << k) != 0 { survey.river_cost } else { 0 };
                let nd = d + c + across;
                if nd < dist[v] {
                    dist[v] = nd;
                    owner[v] = owner[u];
                    contested[v] = contested[u];
                    buckets[nd as usize % ring].push(v as u32);
                    queued += 1;
                } else if nd == dist[v] && (owner[v] != owner[u] || contested[u]) {
                    contested[v] = true;
                }
            }
        }
        bucket.clear();
        // Keep the allocation for the bucket's next turn, unless it filled again meanwhile.
        if buckets[slot].is_empty() {
            buckets[slot] = bucket;
        }
        d += 1;
    }
    Costs { dist, owner, contested }
}

/// How many passable tiles each of `sources` reaches at a lower path cost than any other.
pub(crate) fn reach(survey: &Survey, sources: &[usize]) -> Vec<u32> {
    let c = costs(survey, sources);
    let mut reach = vec![0; sources.len()];
    for i in 0..survey.len() {
        if c.dist[i] != FAR && !c.contested[i] {
            reach[c.owner[i] as usize] += 1;
        }
    }
    reach
}

/// The land mass (connected passable tiles) of each tile, `NONE` for impassable ones, and the
/// size of each mass.
pub(crate) fn land_masses(survey: &Survey) -> (Vec<u32>, Vec<u32>) {
    let mut mass = vec![NONE; survey.len()];
    let mut sizes = Vec::new();
    let mut stack = Vec::new();
    for start in 0..survey.len() {
        if survey.cost[start] == 0 || mass[start] != NONE {
            continue;
        }
        let id = sizes.len() as u32;
        let mut size = 0;
        mass[start] = id;
        stack.push(start);
        while let Some(u) = stack.pop() {
            size += 1;
            for &v in &survey.neighbors[u] {
                if v != NONE && survey.cost[v as usize] > 0 && mass[v as usize] == NONE {
                    mass[v as usize] = id;
                    stack.push(v as usize);
                }
            }
        }
        sizes.push(size);
    }
    (mass, sizes)
}
