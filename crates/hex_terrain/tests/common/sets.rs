//! Union-find over tile indices, for the tests that recount groups of tiles (landmasses, seas,
//! ranges) another way than the library's searches.

/// Each index's parent; a root is its own.
pub struct Sets(pub Vec<usize>);

impl Sets {
    /// `n` indices, each alone.
    pub fn new(n: usize) -> Self {
        Self((0..n).collect())
    }

    /// The root of `i`'s set (compressing the path).
    pub fn find(&mut self, i: usize) -> usize {
        let mut root = i;
        while self.0[root] != root {
            root = self.0[root];
        }
        let mut i = i;
        while self.0[i] != root {
            let next = self.0[i];
            self.0[i] = root;
            i = next;
        }
        root
    }

    /// Joins the sets of `a` and `b` (the lower root stays).
    pub fn join(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        self.0[a.max(b)] = a.min(b);
    }
}
