//! Block-sparse Newton matrix of the collocation system and its faer LU.
//!
//! The pattern depends only on the layout (nodes, n, k, scheme), so it is built once per layout
//! together with the symbolic factorization (column ordering, elimination tree) and cached (the
//! last few layouts); Newton iterations and repeated solves on a mesh of the same size only redo
//! the numeric factorization. The matrix is assembled by writing the dense blocks in a fixed
//! order and scattering them through a precomputed position map — no triplets are sorted per
//! iteration.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::lu::{
    factorize_symbolic_lu, LuRef, LuSymbolicParams, NumericLu, SymbolicLu,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par};

/// Sizes of the global system on one mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Layout {
    /// Mesh nodes `N`.
    pub nodes: usize,
    /// States.
    pub n: usize,
    /// Unknown parameters.
    pub k: usize,
    /// Unknown columns (and equation rows) per interval.
    pub stride: usize,
}

impl Layout {
    /// Intervals.
    pub fn intervals(&self) -> usize {
        self.nodes - 1
    }
    /// Width of an interval's dense block: its own columns, the right node, the parameters.
    pub fn width(&self) -> usize {
        self.stride + self.n + self.k
    }
    /// First parameter column.
    pub fn pcol(&self) -> usize {
        self.intervals() * self.stride + self.n
    }
    /// Unknowns = equations.
    pub fn dim(&self) -> usize {
        self.pcol() + self.k
    }
    /// First boundary-condition row.
    pub fn bcrow(&self) -> usize {
        self.intervals() * self.stride
    }
    /// Offset of the boundary block in the block-value array.
    pub fn bc_offset(&self) -> usize {
        self.intervals() * self.stride * self.width()
    }
    /// Length of the block-value array.
    pub fn block_len(&self) -> usize {
        self.bc_offset() + (self.n + self.k) * (2 * self.n + self.k)
    }
}

/// Number of layouts whose pattern and symbolic LU are kept (mesh passes alternate between a
/// few sizes, e.g. a benchmark or continuation restarting from the same coarse guess).
const CACHE: usize = 4;

/// The pattern of one layout with its symbolic and numeric LU storage.
struct Pattern {
    layout: Layout,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Position in the CSC value array of each block entry.
    pos: Vec<usize>,
    vals: Vec<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    mem: MemBuffer,
}

/// Pattern, values and LU of the Newton matrix.
pub(crate) struct SparseSystem {
    /// Most recently used last; the current layout is the last entry.
    cache: Vec<Pattern>,
    /// Block values, in the layout order (see [`Layout`]); the assembly writes here.
    pub blocks: Vec<f64>,
    factored: bool,
    /// Symbolic factorizations computed (for tests of buffer reuse).
    pub symbolic_count: usize,
}

impl std::fmt::Debug for SparseSystem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseSystem")
            .field(
                "layouts",
                &self.cache.iter().map(|p| p.layout).collect::<Vec<_>>(),
            )
            .finish()
    }
}

impl Clone for SparseSystem {
    /// Work buffers are not shared: a clone starts empty.
    fn clone(&self) -> Self {
        Self::new()
    }
}

/// Why the linear algebra failed.
#[derive(Debug)]
pub(crate) enum LinError {
    Singular,
}

impl Pattern {
    fn build(l: Layout) -> Result<Self, LinError> {
        let dim = l.dim();
        let w = l.width();
        // Entries in block order: (row, col).
        let mut entries: Vec<(usize, usize)> = Vec::with_capacity(l.block_len());
        for i in 0..l.intervals() {
            for rr in 0..l.stride {
                let row = i * l.stride + rr;
                for c in 0..w {
                    let col = if c < l.stride + l.n {
                        i * l.stride + c
                    } else {
                        l.pcol() + c - l.stride - l.n
                    };
                    entries.push((row, col));
                }
            }
        }
        for rb in 0..l.n + l.k {
            let row = l.bcrow() + rb;
            for c in 0..2 * l.n + l.k {
                let col = if c < l.n {
                    c
                } else if c < 2 * l.n {
                    l.intervals() * l.stride + c - l.n
                } else {
                    l.pcol() + c - 2 * l.n
                };
                entries.push((row, col));
            }
        }
        // Counting sort by column; within a column the block order is already by row.
        let mut col_ptr = vec![0; dim + 1];
        for &(_, c) in &entries {
            col_ptr[c + 1] += 1;
        }
        for c in 0..dim {
            col_ptr[c + 1] += col_ptr[c];
        }
        let mut next = col_ptr[..dim].to_vec();
        let mut row_idx = vec![0; entries.len()];
        let mut pos = vec![0; entries.len()];
        for (e, &(r, c)) in entries.iter().enumerate() {
            let p = next[c];
            next[c] += 1;
            row_idx[p] = r;
            pos[e] = p;
        }
        let sym = SymbolicSparseColMatRef::new_checked(dim, dim, &col_ptr, None, &row_idx);
        // Supernodal LU measured faster than simplicial here for all sizes (dense blocks).
        let params = LuSymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_lu(sym, params).map_err(|_| LinError::Singular)?;
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        Ok(Pattern {
            layout: l,
            vals: vec![0.0; entries.len()],
            col_ptr,
            row_idx,
            pos,
            symbolic,
            numeric: NumericLu::new(),
            mem: MemBuffer::new(req),
        })
    }
}

impl SparseSystem {
    pub fn new() -> Self {
        SparseSystem {
            cache: Vec::new(),
            blocks: Vec::new(),
            factored: false,
            symbolic_count: 0,
        }
    }

    /// Makes `layout` current: pattern and symbolic factorization from the cache or new.
    pub fn prepare(&mut self, layout: Layout) -> Result<(), LinError> {
        self.factored = false;
        if self.cache.last().map(|p| p.layout) != Some(layout) {
            if let Some(i) = self.cache.iter().position(|p| p.layout == layout) {
                let p = self.cache.remove(i);
                self.cache.push(p);
            } else {
                let p = Pattern::build(layout)?;
                self.symbolic_count += 1;
                if self.cache.len() == CACHE {
                    self.cache.remove(0);
                }
                self.cache.push(p);
            }
        }
        self.blocks.clear();
        self.blocks.resize(layout.block_len(), 0.0);
        Ok(())
    }

    /// Numeric LU of the matrix whose block values are in `self.blocks`.
    pub fn factor(&mut self) -> Result<(), LinError> {
        self.factored = false;
        let Some(p) = self.cache.last_mut() else {
            return Err(LinError::Singular);
        };
        if self.blocks.len() != p.pos.len() || self.blocks.iter().any(|v| !v.is_finite()) {
            return Err(LinError::Singular);
        }
        for (e, &q) in p.pos.iter().enumerate() {
            p.vals[q] = self.blocks[e];
        }
        let dim = p.layout.dim();
        let sym = SymbolicSparseColMatRef::new_checked(dim, dim, &p.col_ptr, None, &p.row_idx);
        let a = SparseColMatRef::new(sym, &p.vals);
        p.symbolic
            .factorize_numeric_lu(
                &mut p.numeric,
                a,
                Par::Seq,
                MemStack::new(&mut p.mem),
                Default::default(),
            )
            .map_err(|_| LinError::Singular)?;
        self.factored = true;
        Ok(())
    }

    /// Solves `A x = rhs` in place with the last factorization; non-finite output means singular.
    pub fn solve(&mut self, rhs: &mut [f64]) -> Result<(), LinError> {
        let Some(p) = self.cache.last_mut().filter(|_| self.factored) else {
            return Err(LinError::Singular);
        };
        let nrows = rhs.len();
        if nrows != p.layout.dim() {
            return Err(LinError::Singular);
        }
        let lu = LuRef::new_unchecked(&p.symbolic, &p.numeric);
        lu.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, nrows, 1),
            Par::Seq,
            MemStack::new(&mut p.mem),
        );
        if rhs.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(LinError::Singular)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_block_system() {
        // n = 1, k = 0, 3 nodes, stride 1: rows (y1 - y0) = 1, (y2 - y1) = 1, bc y0 = 2.
        let l = Layout {
            nodes: 3,
            n: 1,
            k: 0,
            stride: 1,
        };
        let mut s = SparseSystem::new();
        s.prepare(l).unwrap();
        assert_eq!(s.blocks.len(), l.block_len());
        // interval blocks: [d/dy_i, d/dy_{i+1}]; bc block: [d/dy0, d/dyN]
        s.blocks.copy_from_slice(&[-1.0, 1.0, -1.0, 1.0, 1.0, 0.0]);
        s.factor().unwrap();
        let mut x = vec![1.0, 1.0, 2.0];
        s.solve(&mut x).unwrap();
        assert!(
            (x[0] - 2.0).abs() < 1e-14 && (x[1] - 3.0).abs() < 1e-14 && (x[2] - 4.0).abs() < 1e-14
        );
        // Singular: bc row zero.
        s.blocks.copy_from_slice(&[-1.0, 1.0, -1.0, 1.0, 0.0, 0.0]);
        let r = s.factor().and_then(|_| s.solve(&mut x));
        assert!(r.is_err());
        assert_eq!(s.symbolic_count, 1);
    }
}
