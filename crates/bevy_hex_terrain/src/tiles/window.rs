//! The GPU side of the tile store, on the CPU: a window of `width x height` tiles in offset
//! coordinates, its texels addressed modulo the window size (so moving the window rewrites only
//! the strip that enters it), and the rows changed since the last upload.

use bevy::prelude::*;

/// One tile's state as the shader reads it (an `Rgba16Uint` texel):
/// `[fog | highlights << 2, owner, overlay r | g << 8, overlay b | a << 8]`.
#[doc(hidden)] // The GPU layout of `TileStateUpload`, hidden with it.
pub type Texel = [u16; 4];

/// Where the window's texels come from: the store of every tile's state.
pub(crate) trait TexelSource {
    /// The texel of a tile (`[0; 4]` when nothing is stored for it).
    fn texel(&self, oc: IVec2) -> Texel;
    /// Calls `f` for every tile inside `rect` (max exclusive) that has a stored texel, and
    /// returns true, when the source can list them for less than a lookup of every tile of
    /// `rect` costs; else calls nothing and returns false.
    fn each_stored_in(&self, rect: IRect, f: &mut dyn FnMut(IVec2, Texel)) -> bool;
}

/// Bytes of one texel.
pub(crate) const TEXEL_BYTES: usize = std::mem::size_of::<Texel>();

/// The changed part of the texture since the last upload: whole rows or spans of rows, ready to
/// be copied into the texture.
///
/// Hidden from the docs: the material plugin's internal; public so the tests can mirror the
/// texture the GPU receives and compare it with [`TileStates`](crate::TileStates).
#[doc(hidden)]
#[derive(Resource, Debug, Clone, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct TileStateUpload {
    /// Texture generation the spans belong to (a new window size makes a new texture).
    pub texture: u64,
    /// Texture size in texels.
    pub size: UVec2,
    /// `(texel column, texel row, texel count)` of each span, in the order of `data`.
    pub spans: Vec<UVec3>,
    /// The spans' texels, one after the other.
    pub data: Vec<Texel>,
}

impl TileStateUpload {
    /// Bytes this upload copies to the GPU.
    #[must_use]
    pub fn bytes(&self) -> usize {
        self.data.len() * TEXEL_BYTES
    }
}

/// The window: which tiles the texture holds, their texels, and what changed.
#[derive(Debug, Clone)]
pub(crate) struct TexelWindow {
    /// First column and row (offset coordinates) inside.
    origin: IVec2,
    size: UVec2,
    texels: Vec<Texel>,
    /// Per texture row, the changed texel columns `[min, max]` (`min > max`: unchanged).
    dirty: Vec<[u32; 2]>,
    dirty_rows: Vec<u32>,
    /// Increases each time the size changes (a new texture).
    texture: u64,
}

impl Default for TexelWindow {
    fn default() -> Self {
        Self::new(IVec2::ZERO, UVec2::ONE)
    }
}

impl TexelWindow {
    pub fn new(origin: IVec2, size: UVec2) -> Self {
        let size = size.max(UVec2::ONE);
        let mut window = Self {
            origin,
            size,
            texels: vec![[0; 4]; (size.x * size.y) as usize],
            dirty: vec![[u32::MAX, 0]; size.y as usize],
            dirty_rows: Vec::new(),
            texture: 0,
        };
        window.mark_all();
        window
    }

    pub fn origin(&self) -> IVec2 {
        self.origin
    }

    pub fn size(&self) -> UVec2 {
        self.size
    }

    pub fn texture(&self) -> u64 {
        self.texture
    }

    /// Whether offset coordinate `oc` is inside.
    pub fn contains(&self, oc: IVec2) -> bool {
        let d = oc - self.origin;
        d.x >= 0 && d.y >= 0 && (d.x as u32) < self.size.x && (d.y as u32) < self.size.y
    }

    /// Texture column and row of an offset coordinate (inside or not).
    pub fn texel_of(&self, oc: IVec2) -> UVec2 {
        UVec2::new(oc.x.rem_euclid(self.size.x as i32) as u32, oc.y.rem_euclid(self.size.y as i32) as u32)
    }

    /// Writes the texel of a tile inside the window (others are ignored).
    pub fn write(&mut self, oc: IVec2, texel: Texel) {
        if !self.contains(oc) {
            return;
        }
        let t = self.texel_of(oc);
        let i = (t.y * self.size.x + t.x) as usize;
        if self.texels[i] != texel {
            self.texels[i] = texel;
            self.mark(t);
        }
    }

    fn mark(&mut self, t: UVec2) {
        let row = &mut self.dirty[t.y as usize];
        if row[0] > row[1] {
            self.dirty_rows.push(t.y);
            *row = [t.x, t.x];
        } else {
            *row = [row[0].min(t.x), row[1].max(t.x)];
        }
    }

    fn mark_all(&mut self) {
        self.dirty_rows.clear();
        for (y, row) in self.dirty.iter_mut().enumerate() {
            *row = [0, self.size.x - 1];
            self.dirty_rows.push(y as u32);
        }
    }

    /// Moves the window to `origin` with `size`, refilling the texels of the tiles that enter it
    /// from `state` (a resize makes a new texture, filled whole).
    pub fn reposition(&mut self, origin: IVec2, size: UVec2, state: &impl TexelSource) {
        let size = size.max(UVec2::ONE);
        if size != self.size {
            let texture = self.texture + 1;
            *self = Self::new(origin, size);
            self.texture = texture;
            self.refill(IRect::from_corners(origin, origin + size.as_ivec2()), state);
            return;
        }
        if origin == self.origin {
            return;
        }
        let old = IRect::from_corners(self.origin, self.origin + size.as_ivec2());
        self.origin = origin;
        let new = IRect::from_corners(origin, origin + size.as_ivec2());
        if old.intersect(new).is_empty() {
            self.refill(new, state);
            return;
        }
        // The entering strips: columns beside the old window, then rows above or below it.
        let cols = if new.min.x < old.min.x {
            IRect::new(new.min.x, new.min.y, old.min.x, new.max.y)
        } else {
            IRect::new(old.max.x, new.min.y, new.max.x, new.max.y)
        };
        let inner = IRect::new(old.min.x.max(new.min.x), 0, old.max.x.min(new.max.x), 0);
        let rows = if new.min.y < old.min.y {
            IRect::new(inner.min.x, new.min.y, inner.max.x, old.min.y)
        } else {
            IRect::new(inner.min.x, old.max.y, inner.max.x, new.max.y)
        };
        self.refill(cols, state);
        self.refill(rows, state);
    }

    /// Refills every texel from `state` (the tiles' offset coordinates changed meaning).
    pub fn refill_all(&mut self, state: &impl TexelSource) {
        let rect = IRect::from_corners(self.origin, self.origin + self.size.as_ivec2());
        self.refill(rect, state);
    }

    /// Rewrites the texels of `rect` (max exclusive) from `state`, row by row (the texel column
    /// wraps at most once a row, so it is stepped, not divided, per tile). A source that can
    /// list its stored tiles more cheaply is asked for those: the rest are cleared.
    fn refill(&mut self, rect: IRect, state: &impl TexelSource) {
        if rect.is_empty() {
            return;
        }
        let mut listed = Vec::new();
        let few = state.each_stored_in(rect, &mut |oc, texel| listed.push((oc, texel)));
        let width = self.size.x;
        for y in rect.min.y..rect.max.y {
            let ty = y.rem_euclid(self.size.y as i32) as u32;
            let mut tx = rect.min.x.rem_euclid(width as i32) as u32;
            for x in rect.min.x..rect.max.x {
                let texel = if few { [0; 4] } else { state.texel(IVec2::new(x, y)) };
                let i = (ty * width + tx) as usize;
                if self.texels[i] != texel {
                    self.texels[i] = texel;
                    self.mark(UVec2::new(tx, ty));
                }
                tx += 1;
                if tx == width {
                    tx = 0;
                }
            }
        }
        for (oc, texel) in listed {
            self.write(oc, texel);
        }
    }

    /// Resets every texel to `[0; 4]` (and uploads the whole texture).
    pub fn clear(&mut self) {
        self.texels.fill([0; 4]);
        self.mark_all();
    }

    /// Whether anything changed since the last [`take_upload`](Self::take_upload).
    pub fn is_dirty(&self) -> bool {
        !self.dirty_rows.is_empty()
    }

    /// The changed spans, and forgets them.
    pub fn take_upload(&mut self) -> TileStateUpload {
        let mut upload = TileStateUpload { texture: self.texture, size: self.size, ..default() };
        self.dirty_rows.sort_unstable();
        for &y in &self.dirty_rows {
            let [min, max] = std::mem::replace(&mut self.dirty[y as usize], [u32::MAX, 0]);
            let start = (y * self.size.x + min) as usize;
            upload.spans.push(UVec3::new(min, y, max - min + 1));
            upload.data.extend_from_slice(&self.texels[start..=start + (max - min) as usize]);
        }
        self.dirty_rows.clear();
        upload
    }

    /// The texel the texture holds for an offset coordinate inside the window.
    #[cfg(test)]
    pub fn texel(&self, oc: IVec2) -> Option<Texel> {
        let t = self.texel_of(oc);
        self.contains(oc).then(|| self.texels[(t.y * self.size.x + t.x) as usize])
    }
}
