//! The pixels of a polygon's edges on a picture (a camera's view on the ground).

use super::Minimap;

impl Minimap {
    /// The pixels on the edges of a polygon of world `(x, z)` points (a camera's view on the
    /// ground), each once: clipped to the picture, and wrapped east-west on a wrapping picture.
    /// Non-finite points give nothing.
    #[must_use]
    pub fn outline(&self, polygon: &[[f64; 2]]) -> Vec<u32> {
        if polygon.len() < 2 || polygon.iter().flatten().any(|v| !v.is_finite()) {
            return Vec::new();
        }
        let [w, h] = self.size.map(f64::from);
        let mut points: Vec<[f64; 2]> = polygon
            .iter()
            .map(|&[x, z]| [(x - self.origin[0]) / self.step, (z - self.origin[1]) / self.step])
            .collect();
        if self.wraps {
            // One shift for the whole polygon, so its edges stay whole across the seam.
            let shift = (points[0][0] / w).floor() * w;
            points.iter_mut().for_each(|p| p[0] -= shift);
        }
        let mut out = Vec::new();
        for k in 0..points.len() {
            let (a, b) = (points[k], points[(k + 1) % points.len()]);
            let x_range = if self.wraps { [f64::NEG_INFINITY, f64::INFINITY] } else { [0.0, w] };
            let Some((a, b)) = clip_segment(a, b, x_range, [0.0, h]) else { continue };
            // Sample the segment at least twice a pixel; a segment is at most a few picture
            // widths long (the polygon's far corners may be far out).
            let steps = ((b[0] - a[0]).abs().max((b[1] - a[1]).abs()) * 2.0).ceil().clamp(1.0, 8.0 * (w + h));
            for s in 0..=steps as u32 {
                let f = f64::from(s) / steps;
                let (x, y) = (a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f);
                let (mut px, py) = (x.floor(), y.floor().min(h - 1.0));
                if self.wraps {
                    px = px.rem_euclid(w);
                }
                let px = px.min(w - 1.0);
                if px >= 0.0 && py >= 0.0 {
                    out.push((py as u32) * self.size[0] + px as u32);
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }
}

/// The part of segment `a`-`b` inside `x` × `y` (Liang-Barsky); `None` when it misses.
fn clip_segment(a: [f64; 2], b: [f64; 2], x: [f64; 2], y: [f64; 2]) -> Option<([f64; 2], [f64; 2])> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-d[0], a[0] - x[0]), (d[0], x[1] - a[0]), (-d[1], a[1] - y[0]), (d[1], y[1] - a[1])] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then(|| ([a[0] + d[0] * t0, a[1] + d[1] * t0], [a[0] + d[0] * t1, a[1] + d[1] * t1]))
}
