//! Block-sparse Newton matrix of the collocation system and its faer LU.
//!
//! The pattern depends only on the layout (nodes, n, k, scheme), so it is built once per layout
//! together with the symbolic factorization (column ordering, elimination tree); Newton iterations
//! and repeated solves on a mesh of the same size only redo the numeric factorization.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::lu::{
    factorize_symbolic_lu, LuRef, LuSymbolicParams, NumericLu, SymbolicLu,
};
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

/// Pattern, values and LU of the Newton matrix.
pub(crate) struct SparseSystem {
    layout: Option<Layout>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Position in the CSC value array of each block entry.
    pos: Vec<usize>,
    /// Block values, in the layout order (see [`Layout`]); the assembly writes here.
    pub blocks: Vec<f64>,
    vals: Vec<f64>,
    symbolic: Option<SymbolicLu<usize>>,
    numeric: NumericLu<usize, f64>,
    mem: MemBuffer,
    factored: bool,
    /// Symbolic factorizations computed (for tests of buffer reuse).
    pub symbolic_count: usize,
}

impl std::fmt::Debug for SparseSystem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseSystem")
            .field("layout", &self.layout)
            .field("nnz", &self.row_idx.len())
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

impl SparseSystem {
    pub fn new() -> Self {
        SparseSystem {
            layout: None,
            col_ptr: Vec::new(),
            row_idx: Vec::new(),
            pos: Vec::new(),
            blocks: Vec::new(),
            vals: Vec::new(),
            symbolic: None,
            numeric: NumericLu::new(),
            mem: MemBuffer::new(StackReq::EMPTY),
            factored: false,
            symbolic_count: 0,
        }
    }

    /// Prepares pattern and symbolic factorization for `layout` (no-op when unchanged).
    pub fn prepare(&mut self, layout: Layout) -> Result<(), LinError> {
        self.factored = false;
        if self.layout == Some(layout) {
            return Ok(());
        }
        self.layout = None;
        // faer's numeric LU does not shrink its column pointers when reused for a smaller matrix.
        self.numeric = NumericLu::new();
        let l = layout;
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
        self.col_ptr.clear();
        self.col_ptr.resize(dim + 1, 0);
        for &(_, c) in &entries {
            self.col_ptr[c + 1] += 1;
        }
        for c in 0..dim {
            self.col_ptr[c + 1] += self.col_ptr[c];
        }
        let mut next = self.col_ptr[..dim].to_vec();
        self.row_idx.clear();
        self.row_idx.resize(entries.len(), 0);
        self.pos.clear();
        self.pos.resize(entries.len(), 0);
        for (e, &(r, c)) in entries.iter().enumerate() {
            let p = next[c];
            next[c] += 1;
            self.row_idx[p] = r;
            self.pos[e] = p;
        }
        self.blocks.clear();
        self.blocks.resize(entries.len(), 0.0);
        self.vals.clear();
        self.vals.resize(entries.len(), 0.0);
        let sym =
            SymbolicSparseColMatRef::new_checked(dim, dim, &self.col_ptr, None, &self.row_idx);
        let symbolic = factorize_symbolic_lu(
            sym,
            LuSymbolicParams {
                supernodal_flop_ratio_threshold:
                    faer::sparse::linalg::SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|_| LinError::Singular)?;
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        self.mem = MemBuffer::new(req);
        self.symbolic = Some(symbolic);
        self.symbolic_count += 1;
        self.layout = Some(layout);
        Ok(())
    }

    /// Numeric LU of the matrix whose block values are in `self.blocks`.
    pub fn factor(&mut self) -> Result<(), LinError> {
        self.factored = false;
        let (Some(l), Some(symbolic)) = (self.layout, self.symbolic.as_ref()) else {
            return Err(LinError::Singular);
        };
        if self.blocks.iter().any(|v| !v.is_finite()) {
            return Err(LinError::Singular);
        }
        for (e, &p) in self.pos.iter().enumerate() {
            self.vals[p] = self.blocks[e];
        }
        let dim = l.dim();
        let sym =
            SymbolicSparseColMatRef::new_checked(dim, dim, &self.col_ptr, None, &self.row_idx);
        let a = SparseColMatRef::new(sym, &self.vals);
        symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                a,
                Par::Seq,
                MemStack::new(&mut self.mem),
                Default::default(),
            )
            .map_err(|_| LinError::Singular)?;
        self.factored = true;
        Ok(())
    }

    /// Solves `A x = rhs` in place with the last factorization; non-finite output means singular.
    pub fn solve(&mut self, rhs: &mut [f64]) -> Result<(), LinError> {
        let Some(symbolic) = self.symbolic.as_ref().filter(|_| self.factored) else {
            return Err(LinError::Singular);
        };
        let lu = LuRef::new_unchecked(symbolic, &self.numeric);
        let nrows = rhs.len();
        lu.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, nrows, 1),
            Par::Seq,
            MemStack::new(&mut self.mem),
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
