//! Structured LU of the collocation Newton matrix (almost block diagonal, with border columns).
//!
//! Unknowns are ordered `(z_0, W_0, z_1, W_1, …, z_N, p)` (`W_i` the internal stages of interval
//! `i`, empty for Lobatto4); interval `i` owns `stride` rows that touch only `(z_i, W_i)`,
//! `z_{i+1}` and `p`, and the `n + k` boundary rows touch `z_0`, `z_N` and `p` (separated or not).
//!
//! The factorization is Gaussian elimination with partial pivoting in the natural column order
//! `(z_0, W_0), (z_1, W_1), …`, with `z_N` and `p` as border columns. The columns of interval `i`
//! are nonzero only in its own rows and in the `n + k` rows carried from the previous window
//! (at first the boundary rows), so each step is a dense elimination of `stride` columns in a
//! window of `n + k + stride` rows; what is left is `n + k` rows in `z_{i+1}` and the border
//! `(z_N, p)`, carried on. The last carry is a dense `(n + k)²` system for `(z_N, p)`; then back
//! substitution, window by window. This is GEPP of the whole matrix (rows only swapped inside a
//! window, which holds every row with a nonzero in the columns eliminated there).
//!
//! Why this order: the carried rows start as the boundary rows (entries of order 1, while
//! interval rows scale like `1/h`), so pivots normally come from the interval rows, back
//! substitution is local to each interval, and the rounding that accumulates along the carry
//! stays in rows of order 1: the Newton residual after an exact step grows like `N ε`, not `N² ε`
//! (measured: carrying interval rows with `z_0` as border instead gave 1.8e-9 against 4.5e-12 at
//! `N = 10⁴` on `samples::LinearNonSeparated`). Stability is that of GEPP: backward stable up to
//! the growth factor, which for a carried row follows the solution operator between the ends
//! (Wright 1993, SIAM J. Sci. Comput. 14, 231–238, gives BVP matrices with exponential growth;
//! pivoting caps it once a carried entry outgrows the interval rows' `1/h`).
//!
//! Cost per interval `O(stride² (stride + 2n + k))` for dense blocks. The eliminations and
//! substitutions visit only the nonzeros (bit-set patterns of rows and columns kept through
//! fill-in, [`eliminate`]): the same operations in the same order as dense, so the same
//! factors, at a cost that follows the fill-in instead of the window's size (uncoupled states:
//! linear in `n` per row). Storage follows the nonzeros too: the assembled rows and the
//! factored windows are kept packed (their nonzeros and patterns); only two windows are dense,
//! `(n + k + stride) × (stride + 2n + k)` each, the one being eliminated and the one before.
//! Buffers are sized in [`AbdSystem::prepare`] (the packed ones reserved for the dense bound,
//! untouched until used); factorizations and solves on the same layout never allocate.
//!
//! A narrow layout (windows at most [`DENSE_COLS`] columns: a few states, the rod in time's six
//! with Lobatto6 among them) stores its rows whole, and where at least a fifth of their entries
//! are nonzero skips the patterns: its windows are eliminated and kept dense
//! ([`eliminate_dense`]), the same pivots and the same subtractions on the nonzeros in the same
//! order, so the same factors and solutions to the bit (tested against the sparse path). There
//! the bookkeeping of the patterns cost more than the zeros it skipped: one Newton solve on a
//! fixed mesh (Bratu, the cantilever, Eigen, the non-separated sample; `cargo bench -p bvp
//! --bench collocation`) is 1.4–1.6× faster, the rod in time's ten-slip drag 1.7×.
//!
//! # Singularity
//!
//! A pivot is suspect when `|u_jj| ≤ PIVOT_TOL · max |a_·j|`, the largest entry of that column in
//! the assembled matrix (relative per column, so rescaling an unknown does not change the
//! verdict). That test is cheap but blind to rows of a smaller scale: the last carry of a stiff
//! problem condenses the far boundary condition into rows far smaller than the interval rows'
//! `1/h`, and their exact, uncancelled pivots fell below it (Troesch's problem at μ = 25: pivot
//! 4.1e-7 against 1e-14 · 4.2e7, a matrix singular in no sense). A suspect factorization is
//! therefore redone tracking `|L||U|` (the magnitudes each entry was computed from,
//! `m_rc ← m_rc + |l_rj| m_jc`), and a pivot is declared zero only when
//! `|u_jj| ≤ PIVOT_TOL · m_jj`: it is at the rounding level of its own computation (exact
//! cancellation, an all-zero column). That test is invariant to row and column scaling alike.
//! Near-singular but exactly factored matrices are left to the conditioning check of the
//! collocation solver. NaN/∞ in the matrix or the solution are reported as singular too.

/// Relative pivot threshold (about 45 ε): matrices singular to working precision.
const PIVOT_TOL: f64 = 1e-14;

/// Widest window (columns) factored dense, [`AbdSystem::factor_dense`], if at least
/// `1/DENSE_SHARE` of the assembled interval rows' entries are nonzero. There the patterns'
/// bookkeeping costs more than the zeros it skips: the rod in time (`n = 6`, Lobatto6: 30
/// columns, 31 % of the assembled entries and 56 % of the factored window nonzero) is 1.7× faster
/// dense. Where the states are uncoupled the factors stay sparse and dense lost: scipy's pairs,
/// 10 states with Lobatto4 (30 columns, 15 % assembled, 9 % factored) 12 %, 20 states (60
/// columns, 5 % factored) 38 %, 10 states with Lobatto6 (50 columns, 10 %) 30 %; with two
/// parameters (32 columns, 23 % assembled) it gained 10 % (`cargo bench -p bvp --bench large`).
const DENSE_COLS: usize = 32;
const DENSE_SHARE: usize = 5;

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
    /// Offset of the boundary block in a dense block-value array (the tests' format).
    #[cfg(test)]
    pub fn bc_offset(&self) -> usize {
        self.intervals() * self.stride * self.width()
    }
    /// Length of a dense block-value array: interval rows, then the boundary block.
    #[cfg(test)]
    pub fn block_len(&self) -> usize {
        self.bc_offset() + (self.n + self.k) * (2 * self.n + self.k)
    }
    /// Rows carried from window to window (at first the boundary rows).
    fn carry(&self) -> usize {
        self.n + self.k
    }
    /// Rows of a window: the carried rows, then the interval's.
    fn wrows(&self) -> usize {
        self.carry() + self.stride
    }
    /// Columns of a window: eliminated (`stride`), next node (`n`), `z_N` (`n`), `p` (`k`).
    fn wcols(&self) -> usize {
        self.stride + 2 * self.n + self.k
    }
}

/// Why the linear algebra failed.
#[derive(Debug)]
pub(crate) enum LinError {
    Singular,
}

/// Block values, factors and work buffers of the Newton matrix.
#[derive(Debug, Default)]
pub(crate) struct AbdSystem {
    layout: Option<Layout>,
    /// Boundary block `[g_a | g_b | g_p]`, `(n + k) × (2n + k)` row-major; the assembly writes
    /// every entry.
    pub bc: Vec<f64>,
    /// The interval rows (`width` each, see [`Layout`]), packed as [`AbdSystem::push_row`]
    /// stores them: row `e`'s nonzeros are `bcol`/`bval` from `boff[e]` to `boff[e + 1]`; for
    /// a narrow layout (`narrow`) the whole row is in `bval` there and `bcol` is empty.
    /// Why packed: dense, they were mostly zeros for a large system (0.9 MB for 60 states and
    /// 16 intervals), paid by a fresh solver in page faults.
    bcol: Vec<u32>,
    bval: Vec<f64>,
    boff: Vec<usize>,
    /// The row being assembled (dense, `width`), see [`AbdSystem::row_mut`].
    row: Vec<f64>,
    /// Two dense `wrows × wcols` row-major windows (the one being eliminated and the previous
    /// one, whose carried rows it takes), zero outside `spat`. Why only two: a window of a large
    /// system is mostly zeros, and per-interval dense windows (2.8 MB for 60 states and 16
    /// intervals) cost a fresh solver a page fault per 4 KB, more than the elimination itself.
    win: Vec<f64>,
    /// Nonzero patterns of the two windows of `win` (`words(wcols)` per row).
    spat: Vec<u64>,
    /// Factored windows, packed: the entries of each row in `rpat` in column order, row `r` of
    /// interval `i` from `roff[i * wrows + r]`.
    vals: Vec<f64>,
    roff: Vec<usize>,
    /// Row interchanges of each window (`stride` slots each), LAPACK style.
    piv: Vec<usize>,
    /// Nonzero patterns of the factored windows' rows (`words(wcols)` each), of the final
    /// system's rows, and (scratch) of the columns being eliminated; see [`eliminate`].
    rpat: Vec<u64>,
    frpat: Vec<u64>,
    cpat: Vec<u64>,
    /// Pivot row's nonzero columns (scratch of [`eliminate`]).
    idx: Vec<usize>,
    /// Final dense system for `(z_N, p)` and its interchanges.
    fin: Vec<f64>,
    fpiv: Vec<usize>,
    /// `|L||U|` magnitudes of `win` and `fin`, only for a factorization with a suspect pivot.
    mwin: Vec<f64>,
    mfin: Vec<f64>,
    /// Column maxima of the assembled matrix (pivot thresholds), then of the final system.
    colmax: Vec<f64>,
    fscale: Vec<f64>,
    /// Right-hand side of one window; known `(z_{i+1}, z_N, p)` during back substitution.
    t: Vec<f64>,
    v: Vec<f64>,
    factored: bool,
    /// The factored windows of a narrow layout, dense (`wrows × wcols` each, in order), and
    /// whether the last factorization left its factors there instead of in `vals`.
    dense: Vec<f64>,
    dense_factors: bool,
    /// The layout's windows are at most [`DENSE_COLS`] wide: rows stored whole, windows
    /// factored dense if the rows are not too sparse (`dense_enough`, set by the column maxima).
    narrow: bool,
    dense_enough: bool,
    /// Times the work buffers had to grow (a layout larger than any seen before).
    pub buffer_growths: usize,
}

impl Clone for AbdSystem {
    /// Work buffers are not shared: a clone starts empty.
    fn clone(&self) -> Self {
        Self::new()
    }
}

fn resize<T: Clone + Default>(v: &mut Vec<T>, len: usize) {
    v.clear();
    v.resize(len, T::default());
}

/// Words of a bit set of `bits` bits.
fn words(bits: usize) -> usize {
    bits.div_ceil(64)
}

/// The set bits of `set` in `lo..hi`, ascending (`hi ≤ 64 · set.len()`).
struct Ones<'a> {
    set: &'a [u64],
    word: usize,
    cur: u64,
    hi: usize,
}

fn ones(set: &[u64], lo: usize, hi: usize) -> Ones<'_> {
    if lo >= hi {
        // Empty (`hi = 0` ends the iteration at once).
        return Ones {
            set,
            word: 0,
            cur: 0,
            hi: 0,
        };
    }
    Ones {
        set,
        word: lo / 64,
        cur: set[lo / 64] & (!0u64 << (lo % 64)),
        hi,
    }
}

impl Iterator for Ones<'_> {
    type Item = usize;
    fn next(&mut self) -> Option<usize> {
        loop {
            if self.cur != 0 {
                let b = self.word * 64 + self.cur.trailing_zeros() as usize;
                if b >= self.hi {
                    return None;
                }
                self.cur &= self.cur - 1;
                return Some(b);
            }
            self.word += 1;
            if self.word * 64 >= self.hi {
                return None;
            }
            self.cur = self.set[self.word];
        }
    }
}

fn has(set: &[u64], b: usize) -> bool {
    set[b / 64] >> (b % 64) & 1 == 1
}

fn put(set: &mut [u64], b: usize, on: bool) {
    let bit = 1u64 << (b % 64);
    if on {
        set[b / 64] |= bit;
    } else {
        set[b / 64] &= !bit;
    }
}

/// Calls `f(c, x)` for the nonzero entries `x = row[c]`, in order (runs of zeros skipped eight
/// at a time; NaN counts as nonzero).
fn nonzeros(row: &[f64], mut f: impl FnMut(usize, f64)) {
    for (q, sub) in row.chunks(8).enumerate() {
        // Bits without the sign: -0.0 is zero too.
        if sub.iter().fold(0u64, |a, x| a | (x.to_bits() << 1)) != 0 {
            for (b, &x) in sub.iter().enumerate() {
                if x != 0.0 {
                    f(8 * q + b, x);
                }
            }
        }
    }
}

/// Nonzero patterns of the row-major `rows × cols` matrix `w` (with `mag`: of either, the
/// magnitudes' support can outgrow the values' by cancellation): `rpat` by rows (`words(cols)`
/// words each), `cpat` by columns `< ne` (`words(rows)` words each).
fn scan(
    w: &[f64],
    mag: Option<&[f64]>,
    rows: usize,
    cols: usize,
    ne: usize,
    rpat: &mut [u64],
    cpat: &mut [u64],
) {
    let (rw, cw) = (words(cols), words(rows));
    cpat[..ne * cw].fill(0);
    let bits = |chunk: &[f64]| {
        chunk
            .iter()
            .enumerate()
            .fold(0u64, |m, (b, &x)| m | (u64::from(x != 0.0) << b))
    };
    for r in 0..rows {
        let pat = &mut rpat[r * rw..(r + 1) * rw];
        for (k, chunk) in w[r * cols..(r + 1) * cols].chunks(64).enumerate() {
            pat[k] = bits(chunk);
        }
        if let Some(m) = mag {
            for (k, chunk) in m[r * cols..(r + 1) * cols].chunks(64).enumerate() {
                pat[k] |= bits(chunk);
            }
        }
        for c in ones(pat, 0, ne) {
            put(&mut cpat[c * cw..(c + 1) * cw], r, true);
        }
    }
}

/// Gaussian elimination with partial pivoting of the first `ne` columns of the row-major
/// `rows × cols` matrix `w`, updating all columns. Multipliers are stored below the diagonal.
/// Pivot test: with `mag` (the `|L||U|` magnitudes of `w`'s entries, updated alongside),
/// `|u_jj| ≤ PIVOT_TOL · m_jj`; without, `|u_jj| ≤ PIVOT_TOL · scale[j]` (`scale[j]` the size
/// of column `j`). See the module docs.
///
/// Sparse: only the entries in the patterns of [`scan`] are visited (pivot candidates by the
/// column's pattern, updates by the pivot row's), which the elimination keeps up to date (fill-in
/// sets bits, interchanges swap them); entries outside them are exactly zero. The operations on
/// the nonzeros, their order and the pivots are those of the dense elimination, so the factors
/// are the same to the bit. Why: a large system's blocks are mostly zeros (`∂F/∂z` of 60
/// uncoupled pairs, scipy's test problem), and walking the columns of a dense window (a cache
/// line per row) was most of the time.
#[allow(clippy::too_many_arguments)]
fn eliminate(
    w: &mut [f64],
    mut mag: Option<&mut [f64]>,
    rows: usize,
    cols: usize,
    ne: usize,
    piv: &mut [usize],
    scale: &[f64],
    rpat: &mut [u64],
    cpat: &mut [u64],
    idx: &mut Vec<usize>,
) -> Result<(), LinError> {
    let (rw, cw) = (words(cols), words(rows));
    for j in 0..ne {
        let mut p = j;
        let mut best = w[j * cols + j].abs();
        for r in ones(&cpat[j * cw..(j + 1) * cw], j + 1, rows) {
            let v = w[r * cols + j].abs();
            if v > best {
                best = v;
                p = r;
            }
        }
        let floor = mag.as_deref().map_or(scale[j], |m| m[p * cols + j]);
        // Also catches all-zero columns (0 ≤ 0) and NaN from overflow during the elimination.
        if best.is_nan() || best <= PIVOT_TOL * floor {
            return Err(LinError::Singular);
        }
        piv[j] = p;
        if p != j {
            // Only the two rows' nonzeros (the magnitudes' too) need to move.
            for k in 0..rw {
                let mut u = rpat[j * rw + k] | rpat[p * rw + k];
                while u != 0 {
                    let c = k * 64 + u.trailing_zeros() as usize;
                    u &= u - 1;
                    w.swap(j * cols + c, p * cols + c);
                    if let Some(m) = mag.as_deref_mut() {
                        m.swap(j * cols + c, p * cols + c);
                    }
                }
            }
            let (a, b) = rpat.split_at_mut(p * rw);
            a[j * rw..(j + 1) * rw].swap_with_slice(&mut b[..rw]);
            // Column patterns from the pivot column on (those left of it are not read again).
            for k in j / 64..words(ne) {
                let mut u = rpat[j * rw + k] | rpat[p * rw + k];
                if k == j / 64 {
                    u &= !0u64 << (j % 64);
                }
                while u != 0 {
                    let c = k * 64 + u.trailing_zeros() as usize;
                    u &= u - 1;
                    if c >= ne {
                        break;
                    }
                    let col = &mut cpat[c * cw..(c + 1) * cw];
                    let (bj, bp) = (has(col, j), has(col, p));
                    put(col, j, bp);
                    put(col, p, bj);
                }
            }
        }
        idx.clear();
        idx.extend(ones(&rpat[j * rw..(j + 1) * rw], j + 1, cols));
        let inv = 1.0 / w[j * cols + j];
        let (cdone, crest) = cpat.split_at_mut((j + 1) * cw);
        for r in ones(&cdone[j * cw..], j + 1, rows) {
            let (top, bottom) = w.split_at_mut(r * cols);
            let (prow, row) = (&top[j * cols..(j + 1) * cols], &mut bottom[..cols]);
            let l = row[j] * inv;
            row[j] = l;
            if l == 0.0 {
                continue;
            }
            for &c in idx.iter() {
                row[c] -= l * prow[c];
            }
            if let Some(m) = mag.as_deref_mut() {
                let (mt, mb) = m.split_at_mut(r * cols);
                let (mp, mr) = (&mt[j * cols..(j + 1) * cols], &mut mb[..cols]);
                for &c in idx.iter() {
                    mr[c] += l.abs() * mp[c];
                }
            }
            // Fill-in: row r takes the pivot row's pattern right of the pivot.
            for k in (j + 1) / 64..rw {
                let mut new = rpat[j * rw + k] & !rpat[r * rw + k];
                if k == (j + 1) / 64 {
                    new &= !0u64 << ((j + 1) % 64);
                }
                rpat[r * rw + k] |= new;
                while new != 0 {
                    let c = k * 64 + new.trailing_zeros() as usize;
                    new &= new - 1;
                    if c >= ne {
                        break;
                    }
                    let at = (c - j - 1) * cw;
                    put(&mut crest[at..at + cw], r, true);
                }
            }
        }
    }
    Ok(())
}

/// Applies the interchanges and then the multipliers of [`eliminate`] to a right-hand side
/// (`P A = L U` with whole rows swapped, so all interchanges come first); by rows, over the
/// nonzeros of `rpat` (the same subtractions in the same order as by columns).
fn forward(w: &impl Rows, rows: usize, cols: usize, piv: &[usize], rpat: &[u64], t: &mut [f64]) {
    for (j, &p) in piv.iter().enumerate() {
        t.swap(j, p);
    }
    let rw = words(cols);
    for r in 1..rows {
        let pat = &rpat[r * rw..(r + 1) * rw];
        let mut acc = t[r];
        for (j, x) in w.entries(r, pat, 0, r.min(piv.len())) {
            acc -= x * t[j];
        }
        t[r] = acc;
    }
}

/// [`forward`] on a dense window (row stride `cols`): the same subtractions on the nonzeros.
fn forward_dense(w: &[f64], rows: usize, cols: usize, piv: &[usize], t: &mut [f64]) {
    for (j, &p) in piv.iter().enumerate() {
        t.swap(j, p);
    }
    for r in 1..rows {
        let row = &w[r * cols..r * cols + r.min(piv.len())];
        let mut acc = t[r];
        for (&x, &tj) in row.iter().zip(t.iter()) {
            acc -= x * tj;
        }
        t[r] = acc;
    }
}

/// [`back`] on a dense window (row stride `cols`, `ne` eliminated columns, the known values
/// multiplying the columns from `ne` on).
fn back_dense(w: &[f64], cols: usize, ne: usize, x: &mut [f64], known: &[f64]) {
    for j in (0..ne).rev() {
        let row = &w[j * cols..(j + 1) * cols];
        let mut acc = x[j];
        for (&u, &xc) in row[j + 1..ne].iter().zip(&x[j + 1..ne]) {
            acc -= u * xc;
        }
        for (&u, &kc) in row[ne..].iter().zip(known) {
            acc -= u * kc;
        }
        x[j] = acc / row[j];
    }
}

/// Rows of a factored matrix whose entries outside the nonzero patterns are zero.
trait Rows {
    /// `(column, value)` of row `r`'s entries in `pat` (its pattern) within `lo..hi`.
    fn entries<'a>(
        &'a self,
        r: usize,
        pat: &'a [u64],
        lo: usize,
        hi: usize,
    ) -> impl Iterator<Item = (usize, f64)> + 'a;
    /// Entry `(r, c)` (zero outside the pattern `pat` of row `r`).
    fn at(&self, r: usize, pat: &[u64], c: usize) -> f64;
}

/// A dense row-major matrix.
struct Dense<'a> {
    w: &'a [f64],
    cols: usize,
}

impl Rows for Dense<'_> {
    fn entries<'a>(
        &'a self,
        r: usize,
        pat: &'a [u64],
        lo: usize,
        hi: usize,
    ) -> impl Iterator<Item = (usize, f64)> + 'a {
        let row = &self.w[r * self.cols..(r + 1) * self.cols];
        ones(pat, lo, hi).map(move |c| (c, row[c]))
    }
    fn at(&self, r: usize, _: &[u64], c: usize) -> f64 {
        self.w[r * self.cols + c]
    }
}

/// Packed rows: the entries of row `r` in its pattern, in column order, from `roff[r]`.
struct Packed<'a> {
    vals: &'a [f64],
    roff: &'a [usize],
}

/// Set bits of `pat` below `c`.
fn rank(pat: &[u64], c: usize) -> usize {
    let (q, b) = (c / 64, c % 64);
    let full: u32 = pat[..q.min(pat.len())].iter().map(|x| x.count_ones()).sum();
    let part = if b > 0 && q < pat.len() {
        (pat[q] & ((1u64 << b) - 1)).count_ones()
    } else {
        0
    };
    (full + part) as usize
}

impl Rows for Packed<'_> {
    fn entries<'a>(
        &'a self,
        r: usize,
        pat: &'a [u64],
        lo: usize,
        hi: usize,
    ) -> impl Iterator<Item = (usize, f64)> + 'a {
        let at = self.roff[r] + rank(pat, lo);
        ones(pat, lo, hi)
            .zip(&self.vals[at..])
            .map(|(c, &x)| (c, x))
    }
    fn at(&self, r: usize, pat: &[u64], c: usize) -> f64 {
        if has(pat, c) {
            self.vals[self.roff[r] + rank(pat, c)]
        } else {
            0.0
        }
    }
}

/// Calls `f(c, x)` for the nonzeros of assembled interval row `e` (see [`AbdSystem::bval`]).
fn row_entries(
    narrow: bool,
    bcol: &[u32],
    bval: &[f64],
    boff: &[usize],
    e: usize,
    mut f: impl FnMut(usize, f64),
) {
    let at = boff[e]..boff[e + 1];
    if narrow {
        nonzeros(&bval[at], f);
    } else {
        for (&c, &x) in bcol[at.clone()].iter().zip(&bval[at]) {
            f(c as usize, x);
        }
    }
}

/// The final system in `(z_N, p)` from the last window `last` (`wrows × wcols`): its carried
/// rows, the two `z_N` column blocks added.
fn final_system(fin: &mut [f64], last: &[f64], l: Layout) {
    let (n, s, m, wc) = (l.n, l.stride, l.carry(), l.wcols());
    for r in 0..m {
        let src = &last[(s + r) * wc..(s + r + 1) * wc];
        let dst = &mut fin[r * m..(r + 1) * m];
        for c in 0..n {
            dst[c] = src[s + c] + src[s + n + c];
        }
        dst[n..].copy_from_slice(&src[s + 2 * n..]);
    }
}

/// [`eliminate`] without patterns and magnitudes: GEPP of the first `ne` columns of the dense
/// row-major `rows × cols` matrix `w`, pivot test `|u_jj| ≤ PIVOT_TOL · scale[j]`. The same
/// pivots and the same subtractions on the nonzeros in the same order, so the same factors to
/// the bit (an entry that is zero may differ in its sign: `x − l·0`); the zeros' subtractions
/// are the price of rows without bookkeeping, cheap where the window is narrow.
fn eliminate_dense(
    w: &mut [f64],
    rows: usize,
    cols: usize,
    ne: usize,
    piv: &mut [usize],
    scale: &[f64],
) -> Result<(), LinError> {
    for j in 0..ne {
        let mut p = j;
        let mut best = w[j * cols + j].abs();
        for r in j + 1..rows {
            let v = w[r * cols + j].abs();
            if v > best {
                best = v;
                p = r;
            }
        }
        if best.is_nan() || best <= PIVOT_TOL * scale[j] {
            return Err(LinError::Singular);
        }
        piv[j] = p;
        if p != j {
            let (a, b) = w.split_at_mut(p * cols);
            a[j * cols..(j + 1) * cols].swap_with_slice(&mut b[..cols]);
        }
        let inv = 1.0 / w[j * cols + j];
        let (top, bottom) = w.split_at_mut((j + 1) * cols);
        let prow = &top[j * cols + j + 1..(j + 1) * cols];
        for row in bottom[..(rows - j - 1) * cols].chunks_exact_mut(cols) {
            let l = row[j] * inv;
            row[j] = l;
            if l == 0.0 {
                continue;
            }
            for (x, &u) in row[j + 1..].iter_mut().zip(prow) {
                *x -= l * u;
            }
        }
    }
    Ok(())
}

impl AbdSystem {
    pub fn new() -> Self {
        Self::default()
    }

    /// Makes `layout` current, sizes the buffers for a new layout and forgets the stored rows:
    /// the assembly pushes every interval row and writes every entry of `bc`.
    pub fn prepare(&mut self, l: Layout) -> Result<(), LinError> {
        self.factored = false;
        if l.nodes < 2 || l.n == 0 || l.stride < l.n {
            return Err(LinError::Singular);
        }
        if self.layout != Some(l) {
            // Windows of the same shape (only the mesh changed) stay where they were, zero
            // outside their patterns: kept, not zeroed again.
            let same_shape = self
                .layout
                .is_some_and(|o| (o.n, o.k, o.stride) == (l.n, l.k, l.stride));
            self.layout = Some(l);
            let (fd, dim) = (l.carry(), l.dim());
            let wlen = l.intervals() * l.wrows() * l.wcols();
            let blen = l.intervals() * l.stride * l.width();
            let grows = blen > self.bval.capacity()
                || wlen > self.vals.capacity()
                || l.intervals() * l.stride > self.piv.capacity()
                || fd * fd > self.fin.capacity()
                || dim > self.colmax.capacity()
                || l.wrows() > self.t.capacity();
            self.buffer_growths += usize::from(grows);
            self.narrow = l.wcols() <= DENSE_COLS;
            let dlen = if self.narrow {
                l.intervals() * l.wrows() * l.wcols()
            } else {
                0
            };
            self.buffer_growths += usize::from(!grows && dlen > self.dense.len());
            if dlen > self.dense.len() {
                self.dense.resize(dlen, 0.0);
            }
            let plen = l.intervals() * l.wrows() * words(l.wcols());
            if !same_shape {
                resize(&mut self.win, 2 * l.wrows() * l.wcols());
                resize(&mut self.spat, 2 * l.wrows() * words(l.wcols()));
            }
            // The packed factors' and rows' bounds (all dense), reserved but untouched: fresh
            // allocations, not reallocations that would copy (touch) the old ones.
            if wlen > self.vals.capacity() {
                self.vals = Vec::with_capacity(wlen);
            }
            if blen > self.bval.capacity() {
                self.bval = Vec::with_capacity(blen);
                self.bcol = Vec::with_capacity(blen);
            }
            if l.intervals() * l.stride >= self.boff.capacity() {
                self.boff = Vec::with_capacity(l.intervals() * l.stride + 1);
            }
            resize(&mut self.bc, l.carry() * (2 * l.n + l.k));
            resize(&mut self.row, l.width());
            resize(&mut self.rpat, plen);
            resize(&mut self.roff, l.intervals() * l.wrows());
            resize(&mut self.piv, l.intervals() * l.stride);
            resize(&mut self.fin, fd * fd);
            resize(&mut self.fpiv, fd);
            resize(&mut self.frpat, fd * words(fd));
            resize(
                &mut self.cpat,
                (l.stride * words(l.wrows())).max(fd * words(fd)),
            );
            resize(&mut self.colmax, dim);
            resize(&mut self.fscale, fd);
            resize(&mut self.t, l.wrows());
            resize(&mut self.v, 2 * l.n + l.k);
        }
        self.clear_rows();
        Ok(())
    }

    fn clear_rows(&mut self) {
        self.bcol.clear();
        self.bval.clear();
        self.boff.clear();
        self.boff.push(0);
    }

    /// The next interval row to assemble (rows in order: interval `i`'s row `r` is the
    /// `i * stride + r`-th), dense with `width` entries, to be written in full and then stored
    /// by [`AbdSystem::push_row`].
    pub fn row_mut(&mut self) -> &mut [f64] {
        &mut self.row
    }

    /// Stores the row written in [`AbdSystem::row_mut`] by its nonzeros (`x != 0.0`, NaN
    /// included: those [`nonzeros`] visits, so the factorization sees the same entries).
    pub fn push_row(&mut self) {
        if self.narrow {
            self.bval.extend_from_slice(&self.row);
            self.boff.push(self.bval.len());
            return;
        }
        let (cols, vals) = (&mut self.bcol, &mut self.bval);
        nonzeros(&self.row, |c, x| {
            // Widths are far below 2³²: `width` doubles of a dense row would not fit otherwise.
            cols.push(c as u32);
            vals.push(x);
        });
        self.boff.push(vals.len());
    }

    /// Column maxima of the assembled matrix; `false` if a value is not finite.
    fn column_maxima(&mut self, l: Layout) -> bool {
        let (n, k, s) = (l.n, l.k, l.stride);
        let cm = &mut self.colmax;
        cm.fill(0.0);
        let mut finite = true;
        if self.narrow {
            // Whole rows: the own and next-node columns, then the parameters'.
            let (w, pc) = (l.width(), l.pcol());
            let mut nonzero = 0;
            for i in 0..l.intervals() {
                for row in self.bval[i * s * w..(i + 1) * s * w].chunks_exact(w) {
                    let (own, par) = row.split_at(s + n);
                    for (m, x) in cm[i * s..(i + 1) * s + n].iter_mut().zip(own) {
                        finite &= x.is_finite();
                        nonzero += usize::from(*x != 0.0);
                        *m = m.max(x.abs());
                    }
                    for (m, x) in cm[pc..].iter_mut().zip(par) {
                        finite &= x.is_finite();
                        nonzero += usize::from(*x != 0.0);
                        *m = m.max(x.abs());
                    }
                }
            }
            self.dense_enough = nonzero * DENSE_SHARE >= self.bval.len();
        }
        let mut upd = |c: usize, x: f64| {
            finite &= x.is_finite();
            cm[c] = cm[c].max(x.abs());
        };
        if !self.narrow {
            for i in 0..l.intervals() {
                for e in i * s..(i + 1) * s {
                    // Zeros (not stored) change no maximum.
                    let at = self.boff[e]..self.boff[e + 1];
                    for (&c, &x) in self.bcol[at.clone()].iter().zip(&self.bval[at]) {
                        let c = c as usize;
                        upd(
                            if c < s + n {
                                i * s + c
                            } else {
                                l.pcol() + c - s - n
                            },
                            x,
                        )
                    }
                }
            }
        }
        for row in self.bc.chunks_exact(2 * n + k) {
            for c in 0..n {
                upd(c, row[c]);
                upd(l.bcrow() + c, row[n + c]);
            }
            for e in 0..k {
                upd(l.pcol() + e, row[2 * n + e]);
            }
        }
        finite
    }

    /// Structured LU of the matrix whose rows were stored by [`AbdSystem::push_row`] and whose
    /// boundary block is in `bc`.
    pub fn factor(&mut self) -> Result<(), LinError> {
        self.factored = false;
        let l = self.layout.ok_or(LinError::Singular)?;
        if self.boff.len() != l.intervals() * l.stride + 1 || !self.column_maxima(l) {
            return Err(LinError::Singular);
        }
        if self.factor_windows(l, false).is_err() {
            // A suspect pivot: decide with the magnitudes it was computed from (module docs).
            resize(&mut self.mwin, l.intervals() * l.wrows() * l.wcols());
            resize(&mut self.mfin, self.fin.len());
            self.factor_windows(l, true)?;
        }
        self.factored = true;
        Ok(())
    }

    /// The window eliminations and the final system; `track`: with `|L||U|` magnitudes.
    fn factor_windows(&mut self, l: Layout, track: bool) -> Result<(), LinError> {
        let (n, s, m) = (l.n, l.stride, l.carry());
        let (wr, wc) = (l.wrows(), l.wcols());
        let (slot, rw, cw) = (wr * wc, words(wc), words(wr));
        self.dense_factors = !track && self.narrow && self.dense_enough;
        if self.dense_factors {
            self.factor_dense(l)?;
            let last = &self.dense[(l.intervals() - 1) * slot..l.intervals() * slot];
            final_system(&mut self.fin, last, l);
            return self.factor_final(l, false);
        }
        self.vals.clear();
        for i in 0..l.intervals() {
            // Window i in scratch i % 2, the previous window in the other.
            let (wa, wb) = self.win.split_at_mut(slot);
            let (pa, pb) = self.spat.split_at_mut(wr * rw);
            let ((cur, prev), (rpat, ppat)) = if i % 2 == 0 {
                ((wa, &*wb), (pa, &*pb))
            } else {
                ((wb, &*wa), (pb, &*pa))
            };
            let mut mcur = None;
            if track {
                // Carried rows keep the magnitudes of their history; new rows start at |a|.
                let (mdone, mrest) = self.mwin.split_at_mut(i * slot);
                let mc = &mut mrest[..slot];
                mc.fill(0.0);
                if i > 0 {
                    let prev = &mdone[(i - 1) * slot..];
                    for r in 0..m {
                        let src = &prev[(s + r) * wc..(s + r + 1) * wc];
                        let dst = &mut mc[r * wc..(r + 1) * wc];
                        dst[..n].copy_from_slice(&src[s..s + n]);
                        dst[s + n..].copy_from_slice(&src[s + n..]);
                    }
                }
                mcur = Some(mc);
            }
            // Entries outside the patterns are zero: clear the window this scratch held, then
            // write and mark the new nonzeros (a window is mostly zeros for large systems).
            for (r, pat) in rpat.chunks_exact_mut(rw).enumerate() {
                for c in ones(pat, 0, wc) {
                    cur[r * wc + c] = 0.0;
                }
                pat.fill(0);
            }
            let cpat = &mut self.cpat[..s * cw];
            cpat.fill(0);
            let mut set = |r: usize, c: usize, x: f64| {
                cur[r * wc + c] = x;
                put(&mut rpat[r * rw..(r + 1) * rw], c, true);
                if c < s {
                    put(&mut cpat[c * cw..(c + 1) * cw], r, true);
                }
            };
            if i == 0 {
                // Boundary rows [g_a | g_b | g_p]: z_0 is eliminated here, z_N is the border.
                for (r, src) in self.bc.chunks_exact(2 * n + l.k).enumerate() {
                    nonzeros(src, |c, x| set(r, if c < n { c } else { s + c }, x));
                }
            } else {
                // Rows left over from the previous window: z_i → eliminated columns.
                for r in 0..m {
                    let pat = &ppat[(s + r) * rw..(s + r + 1) * rw];
                    for c in ones(pat, s, wc) {
                        let x = prev[(s + r) * wc + c];
                        set(r, if c < s + n { c - s } else { c }, x);
                    }
                }
            }
            for r in 0..s {
                row_entries(
                    self.narrow,
                    &self.bcol,
                    &self.bval,
                    &self.boff,
                    i * s + r,
                    |c, x| set(m + r, if c < s + n { c } else { c + n }, x),
                );
            }
            if let Some(mc) = mcur.as_deref_mut() {
                // New rows start at |a|; the patterns cover the magnitudes' support too.
                for r in (if i == 0 { 0 } else { m })..wr {
                    let row = &mut mc[r * wc..(r + 1) * wc];
                    for c in ones(&rpat[r * rw..(r + 1) * rw], 0, wc) {
                        row[c] = cur[r * wc + c].abs();
                    }
                }
            }
            eliminate(
                cur,
                mcur,
                wr,
                wc,
                s,
                &mut self.piv[i * s..(i + 1) * s],
                &self.colmax[i * s..(i + 1) * s],
                rpat,
                cpat,
                &mut self.idx,
            )?;
            // Keep the factors: the pattern and the entries in it, packed.
            self.rpat[i * wr * rw..(i + 1) * wr * rw].copy_from_slice(rpat);
            for r in 0..wr {
                self.roff[i * wr + r] = self.vals.len();
                let row = &cur[r * wc..(r + 1) * wc];
                self.vals
                    .extend(ones(&rpat[r * rw..(r + 1) * rw], 0, wc).map(|c| row[c]));
            }
        }
        // Final system in (z_N, p): the last carry, its two z_N column blocks added.
        let last = &self.win[(l.intervals() - 1) % 2 * slot..];
        final_system(&mut self.fin, last, l);
        if track {
            let mlast = &self.mwin[(l.intervals() - 1) * slot..];
            final_system(&mut self.mfin, mlast, l);
        }
        self.factor_final(l, track)
    }

    /// The window eliminations of a narrow layout, dense ([`eliminate_dense`]), their factors
    /// left in `dense`: each window is written from the assembled rows (and the carried rows of
    /// the one before) and eliminated in place.
    fn factor_dense(&mut self, l: Layout) -> Result<(), LinError> {
        let (n, k, s, m) = (l.n, l.k, l.stride, l.carry());
        let (wr, wc) = (l.wrows(), l.wcols());
        let (slot, width) = (wr * wc, l.width());
        // Every entry of a window is written (the zeros too): no clearing pass.
        for i in 0..l.intervals() {
            let (done, rest) = self.dense.split_at_mut(i * slot);
            let cur = &mut rest[..slot];
            for r in 0..m {
                let dst = &mut cur[r * wc..(r + 1) * wc];
                if i == 0 {
                    let src = &self.bc[r * (2 * n + k)..(r + 1) * (2 * n + k)];
                    dst[..n].copy_from_slice(&src[..n]);
                    dst[s + n..].copy_from_slice(&src[n..]);
                } else {
                    let src =
                        &done[(i - 1) * slot + (s + r) * wc..(i - 1) * slot + (s + r + 1) * wc];
                    dst[..n].copy_from_slice(&src[s..s + n]);
                    dst[s + n..].copy_from_slice(&src[s + n..]);
                }
                dst[n..s + n].fill(0.0);
            }
            for r in 0..s {
                let e = i * s + r;
                let src = &self.bval[e * width..(e + 1) * width];
                let dst = &mut cur[(m + r) * wc..(m + r + 1) * wc];
                dst[..s + n].copy_from_slice(&src[..s + n]);
                dst[s + n..s + 2 * n].fill(0.0);
                dst[s + 2 * n..].copy_from_slice(&src[s + n..]);
            }
            eliminate_dense(
                cur,
                wr,
                wc,
                s,
                &mut self.piv[i * s..(i + 1) * s],
                &self.colmax[i * s..(i + 1) * s],
            )?;
        }
        Ok(())
    }

    /// Factors the final system in `fin` (with `track`, its magnitudes in `mfin` too).
    fn factor_final(&mut self, l: Layout, track: bool) -> Result<(), LinError> {
        let (n, m) = (l.n, l.carry());
        self.fscale[..n].copy_from_slice(&self.colmax[l.bcrow()..l.pcol()]);
        self.fscale[n..].copy_from_slice(&self.colmax[l.pcol()..]);
        let mfin = if track {
            Some(&mut self.mfin[..])
        } else {
            None
        };
        scan(
            &self.fin,
            mfin.as_deref(),
            m,
            m,
            m,
            &mut self.frpat,
            &mut self.cpat,
        );
        eliminate(
            &mut self.fin,
            mfin,
            m,
            m,
            m,
            &mut self.fpiv,
            &self.fscale,
            &mut self.frpat,
            &mut self.cpat,
            &mut self.idx,
        )
    }

    /// Solves `A x = rhs` in place with the last factorization; non-finite output means singular.
    pub fn solve(&mut self, rhs: &mut [f64]) -> Result<(), LinError> {
        let l = self
            .layout
            .filter(|_| self.factored)
            .ok_or(LinError::Singular)?;
        if rhs.len() != l.dim() {
            return Err(LinError::Singular);
        }
        let (n, s, m) = (l.n, l.stride, l.carry());
        let (wr, wc) = (l.wrows(), l.wcols());
        let rw = words(wc);
        let t = &mut self.t;
        // Forward: the carried rows' right-hand side goes from window to window (at first the
        // boundary rows'); the pivot rows' land on their eliminated unknowns' slots.
        t[..m].copy_from_slice(&rhs[l.bcrow()..]);
        let slot = wr * wc;
        for i in 0..l.intervals() {
            if i > 0 {
                t.copy_within(s..s + m, 0);
            }
            t[m..m + s].copy_from_slice(&rhs[i * s..(i + 1) * s]);
            if self.dense_factors {
                forward_dense(
                    &self.dense[i * slot..(i + 1) * slot],
                    wr,
                    wc,
                    &self.piv[i * s..(i + 1) * s],
                    &mut t[..wr],
                );
                rhs[i * s..(i + 1) * s].copy_from_slice(&t[..s]);
                continue;
            }
            let rows = Packed {
                vals: &self.vals,
                roff: &self.roff[i * wr..(i + 1) * wr],
            };
            let rpat = &self.rpat[i * wr * rw..(i + 1) * wr * rw];
            forward(
                &rows,
                wr,
                wc,
                &self.piv[i * s..(i + 1) * s],
                rpat,
                &mut t[..wr],
            );
            rhs[i * s..(i + 1) * s].copy_from_slice(&t[..s]);
        }
        let v = &mut self.v;
        v[..m].copy_from_slice(&t[s..s + m]);
        let fin = Dense {
            w: &self.fin,
            cols: m,
        };
        forward(&fin, m, m, &self.fpiv, &self.frpat, &mut v[..m]);
        back(&fin, m, m, m, &self.frpat, &mut v[..m], &[]);
        rhs[l.bcrow()..].copy_from_slice(&v[..m]);
        // Back substitution, known (z_{i+1}, z_N, p) gathered in v.
        let (zn, p) = rhs[l.bcrow()..].split_at(n);
        v[n..2 * n].copy_from_slice(zn);
        v[2 * n..].copy_from_slice(p);
        for i in (0..l.intervals()).rev() {
            v[..n].copy_from_slice(&rhs[(i + 1) * s..(i + 1) * s + n]);
            if self.dense_factors {
                back_dense(
                    &self.dense[i * slot..(i + 1) * slot],
                    wc,
                    s,
                    &mut rhs[i * s..(i + 1) * s],
                    v,
                );
                continue;
            }
            let rows = Packed {
                vals: &self.vals,
                roff: &self.roff[i * wr..(i + 1) * wr],
            };
            let rpat = &self.rpat[i * wr * rw..(i + 1) * wr * rw];
            back(&rows, wc, s, s, rpat, &mut rhs[i * s..(i + 1) * s], v);
        }
        if rhs.iter().all(|x| x.is_finite()) {
            Ok(())
        } else {
            Err(LinError::Singular)
        }
    }
}

/// Back substitution with the `ne × ne` upper triangle of `w` (row stride `cols`, nonzero
/// patterns `rpat`), whose columns from `known_at` on multiply the known values `known`:
/// `x ← U⁻¹ (x − W_k known)`.
fn back(
    w: &impl Rows,
    cols: usize,
    ne: usize,
    known_at: usize,
    rpat: &[u64],
    x: &mut [f64],
    known: &[f64],
) {
    let rw = words(cols);
    for j in (0..ne).rev() {
        let pat = &rpat[j * rw..(j + 1) * rw];
        let mut acc = x[j];
        for (c, v) in w.entries(j, pat, j + 1, ne) {
            acc -= v * x[c];
        }
        for (c, v) in w.entries(j, pat, known_at, cols) {
            acc -= v * known[c - known_at];
        }
        x[j] = acc / w.at(j, pat, j);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::{norm_max, DenseLu};

    /// Deterministic uniform numbers in [-1, 1) (xorshift64*).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            let u = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
            u as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    /// Stores dense block values (interval rows, then the boundary block; `Layout::block_len`)
    /// as the assembly does: rows by [`AbdSystem::push_row`], the boundary block in `bc`.
    fn load(s: &mut AbdSystem, l: Layout, blocks: &[f64]) {
        s.clear_rows();
        for row in blocks[..l.bc_offset()].chunks_exact(l.width()) {
            s.row_mut().copy_from_slice(row);
            s.push_row();
        }
        s.bc.copy_from_slice(&blocks[l.bc_offset()..]);
    }

    /// The assembled matrix, row-major `dim × dim`, from the block values (the layout's map,
    /// written independently of the window code).
    fn dense(l: Layout, blocks: &[f64]) -> Vec<f64> {
        let dim = l.dim();
        let mut a = vec![0.0; dim * dim];
        let w = l.width();
        for i in 0..l.intervals() {
            for r in 0..l.stride {
                let row = i * l.stride + r;
                for c in 0..w {
                    let col = if c < l.stride + l.n {
                        i * l.stride + c
                    } else {
                        l.pcol() + c - l.stride - l.n
                    };
                    a[row * dim + col] = blocks[(i * l.stride + r) * w + c];
                }
            }
        }
        let bw = 2 * l.n + l.k;
        for r in 0..l.n + l.k {
            let row = l.bcrow() + r;
            for c in 0..bw {
                let col = if c < l.n {
                    c
                } else if c < 2 * l.n {
                    l.bcrow() + c - l.n
                } else {
                    l.pcol() + c - 2 * l.n
                };
                a[row * dim + col] = blocks[l.bc_offset() + r * bw + c];
            }
        }
        a
    }

    #[derive(Clone, Copy, PartialEq)]
    enum Kind {
        /// Collocation-like: `∓1/h` on the node and stage diagonals plus O(1) entries.
        Collocation,
        /// Every block entry random: pivots often come from the carried rows.
        Random,
        /// Collocation-like with most O(1) entries zero (the patterns of [`eliminate`]).
        Sparse,
    }

    /// Fills random blocks; `separated`: the first `n − 1` boundary rows see only `z_0`, the
    /// others only `z_N` and `p`.
    fn fill(l: Layout, kind: Kind, separated: bool, rng: &mut Rng, blocks: &mut [f64]) {
        for (e, x) in blocks.iter_mut().enumerate() {
            *x = rng.next();
            // Boundary rows kept full: the sparse ones would often be singular.
            if kind == Kind::Sparse && e < l.bc_offset() && x.abs() > 0.2 {
                *x = 0.0;
            }
        }
        let w = l.width();
        if kind != Kind::Random {
            let h = 1.0 / l.intervals() as f64;
            for i in 0..l.intervals() {
                for r in 0..l.stride {
                    let row = &mut blocks[(i * l.stride + r) * w..(i * l.stride + r + 1) * w];
                    row[r % l.n] -= 1.0 / h;
                    row[l.n + r] += 1.0 / h;
                }
            }
        }
        if separated {
            let bw = 2 * l.n + l.k;
            for r in 0..l.n + l.k {
                let row = &mut blocks[l.bc_offset() + r * bw..l.bc_offset() + (r + 1) * bw];
                if r + 1 < l.n {
                    row[l.n..].fill(0.0);
                } else {
                    row[..l.n].fill(0.0);
                }
            }
        }
    }

    /// ABD solution against dense LU of the assembled matrix; returns the relative difference.
    fn compare(l: Layout, kind: Kind, separated: bool, seed: u64) -> f64 {
        compare_with(&mut AbdSystem::new(), l, kind, separated, seed)
    }

    /// [`compare`] with a given (possibly used) system.
    fn compare_with(s: &mut AbdSystem, l: Layout, kind: Kind, separated: bool, seed: u64) -> f64 {
        let mut rng = Rng(seed);
        s.prepare(l).unwrap();
        let mut blocks = vec![0.0; l.block_len()];
        fill(l, kind, separated, &mut rng, &mut blocks);
        load(s, l, &blocks);
        let a = dense(l, &blocks);
        let dim = l.dim();
        let b: Vec<f64> = (0..dim).map(|_| rng.next()).collect();
        let mut lu = DenseLu::new(dim);
        lu.matrix_mut().copy_from_slice(&a);
        lu.factor().expect("dense LU");
        let mut xd = b.clone();
        lu.solve(&mut xd);
        s.factor().expect("ABD factor");
        let mut x = b.clone();
        s.solve(&mut x).expect("ABD solve");
        // Backward error: ‖b − A x‖ / (‖A‖ ‖x‖) at rounding level.
        let amax = norm_max(&a);
        let mut res = 0.0_f64;
        for r in 0..dim {
            let ax: f64 = (0..dim).map(|c| a[r * dim + c] * x[c]).sum();
            res = res.max((ax - b[r]).abs());
        }
        let xmax = norm_max(&x);
        assert!(
            res <= 1e-13 * amax * xmax * dim as f64,
            "{l:?} {separated}: residual {res:e} (|A| {amax:e}, |x| {xmax:e})"
        );
        let diff = x
            .iter()
            .zip(&xd)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max);
        diff / norm_max(&xd)
    }

    fn layouts() -> Vec<Layout> {
        let mut v = Vec::new();
        for n in 1..=4 {
            for k in 0..=2 {
                for stride in [n, 3 * n] {
                    for nodes in [2, 3, 7, 40] {
                        v.push(Layout {
                            nodes,
                            n,
                            k,
                            stride,
                        });
                    }
                }
            }
        }
        v
    }

    #[test]
    fn matches_dense_lu_on_collocation_like_systems() {
        let mut worst = 0.0_f64;
        for (t, l) in layouts().into_iter().enumerate() {
            for separated in [false, true] {
                if separated && l.n < 2 {
                    continue;
                }
                let d = compare(l, Kind::Collocation, separated, 1 + t as u64);
                // Well conditioned (cond ≲ 1e4 here): both solutions agree to ~1e-12.
                assert!(
                    d <= 1e-10,
                    "{l:?} separated {separated}: relative difference {d:e}"
                );
                worst = worst.max(d);
            }
        }
        eprintln!("worst relative difference from dense LU: {worst:e}");
    }

    #[test]
    fn matches_dense_lu_on_sparse_blocks() {
        // Scaled up: patterns of several words (rows and columns beyond 64).
        for (t, l) in layouts().into_iter().filter(|l| l.nodes <= 7).enumerate() {
            let l = Layout {
                n: 9 * l.n,
                stride: 9 * l.stride,
                ..l
            };
            for separated in [false, true] {
                let d = compare(l, Kind::Sparse, separated, 2000 + t as u64);
                assert!(
                    d <= 1e-9,
                    "{l:?} separated {separated}: relative difference {d:e}"
                );
            }
        }
    }

    #[test]
    fn matches_dense_lu_on_random_blocks() {
        // Few intervals: random block chains grow ill-conditioned with their length.
        for (t, l) in layouts().into_iter().filter(|l| l.nodes <= 7).enumerate() {
            for separated in [false, true] {
                if separated && l.n < 2 {
                    continue;
                }
                let d = compare(l, Kind::Random, separated, 1000 + t as u64);
                assert!(
                    d <= 1e-8,
                    "{l:?} separated {separated}: relative difference {d:e}"
                );
            }
        }
    }

    /// `y = A x` from the block values (no dense matrix), and `max_r Σ_c |a_rc|`.
    fn block_matvec(l: Layout, blocks: &[f64], x: &[f64], y: &mut [f64]) -> f64 {
        let (n, s, w) = (l.n, l.stride, l.width());
        let mut norm = 0.0_f64;
        for i in 0..l.intervals() {
            for r in 0..s {
                let row = &blocks[(i * s + r) * w..(i * s + r + 1) * w];
                let xs = x[i * s..i * s + s + n].iter().chain(&x[l.pcol()..]);
                y[i * s + r] = row.iter().zip(xs).map(|(a, b)| a * b).sum();
                norm = norm.max(row.iter().map(|a| a.abs()).sum());
            }
        }
        let bw = 2 * n + l.k;
        for r in 0..n + l.k {
            let row = &blocks[l.bc_offset() + r * bw..l.bc_offset() + (r + 1) * bw];
            let xs = x[..n].iter().chain(&x[l.bcrow()..]);
            y[l.bcrow() + r] = row.iter().zip(xs).map(|(a, b)| a * b).sum();
            norm = norm.max(row.iter().map(|a| a.abs()).sum());
        }
        norm
    }

    #[test]
    fn backward_error_does_not_grow_with_the_mesh() {
        // Non-separated, with a parameter, 10⁴ intervals: ‖b − A x‖ / (‖A‖ ‖x‖) stays at a few ε
        // (carrying interval rows with z_0 as the border instead gave 65 ε on this system).
        for stride in [2, 6] {
            let l = Layout {
                nodes: 10_001,
                n: 2,
                k: 1,
                stride,
            };
            let mut rng = Rng(11);
            let mut s = AbdSystem::new();
            s.prepare(l).unwrap();
            let mut blocks = vec![0.0; l.block_len()];
            fill(l, Kind::Collocation, false, &mut rng, &mut blocks);
            load(&mut s, l, &blocks);
            let b: Vec<f64> = (0..l.dim()).map(|_| rng.next()).collect();
            let mut x = b.clone();
            s.factor().unwrap();
            s.solve(&mut x).unwrap();
            let mut ax = vec![0.0; l.dim()];
            let anorm = block_matvec(l, &blocks, &x, &mut ax);
            let res = ax
                .iter()
                .zip(&b)
                .map(|(p, q)| (p - q).abs())
                .fold(0.0, f64::max);
            let rel = res / (anorm * norm_max(&x)) / f64::EPSILON;
            eprintln!("stride {stride}: backward error {rel:.2} ε");
            assert!(rel <= 20.0, "stride {stride}: backward error {rel} ε");
        }
    }

    #[test]
    fn solves_small_block_system_exactly() {
        // n = 1, k = 0, 3 nodes, stride 1: rows (y1 - y0) = 1, (y2 - y1) = 1, bc y0 = 2.
        let l = Layout {
            nodes: 3,
            n: 1,
            k: 0,
            stride: 1,
        };
        let mut s = AbdSystem::new();
        s.prepare(l).unwrap();
        assert_eq!(l.block_len(), 6);
        // interval blocks: [d/dy_i, d/dy_{i+1}]; bc block: [d/dy0, d/dyN]
        load(&mut s, l, &[-1.0, 1.0, -1.0, 1.0, 1.0, 0.0]);
        s.factor().unwrap();
        let mut x = vec![1.0, 1.0, 2.0];
        s.solve(&mut x).unwrap();
        assert_eq!(x, [2.0, 3.0, 4.0]);
        assert_eq!(s.buffer_growths, 1);
    }

    #[test]
    fn singular_and_non_finite_matrices_are_reported() {
        let l = Layout {
            nodes: 6,
            n: 2,
            k: 1,
            stride: 6,
        };
        let mut s = AbdSystem::new();
        let mut rng = Rng(7);
        let bw = 2 * l.n + l.k;
        // (a) Two equal boundary rows; (b) an internal-stage column zero; (c) a NaN.
        for case in 0..3 {
            s.prepare(l).unwrap();
            let mut blocks = vec![0.0; l.block_len()];
            fill(l, Kind::Collocation, false, &mut rng, &mut blocks);
            match case {
                0 => {
                    let (r0, r1) = blocks[l.bc_offset()..].split_at_mut(bw);
                    r1[..bw].copy_from_slice(r0);
                }
                1 => {
                    let w = l.width();
                    for r in 0..l.stride {
                        blocks[(3 * l.stride + r) * w + l.n + 1] = 0.0;
                    }
                }
                _ => blocks[5] = f64::NAN,
            }
            load(&mut s, l, &blocks);
            assert!(s.factor().is_err(), "case {case}");
            assert!(s.solve(&mut vec![1.0; l.dim()]).is_err(), "case {case}");
        }
        // Exactly singular like y'' = 0 with Neumann ends: constants are in the kernel.
        let l = Layout {
            nodes: 5,
            n: 2,
            k: 0,
            stride: 2,
        };
        s.prepare(l).unwrap();
        let mut blocks = vec![0.0; l.block_len()];
        for i in 0..4 {
            let h = 0.25;
            // (z_{i+1} - z_i)/h - [z2; 0] averaged: rows [-1/h, -1/2, 1/h, -1/2], [0, -1/h, 0, 1/h].
            let b = &mut blocks[i * 8..(i + 1) * 8];
            b.copy_from_slice(&[-1.0 / h, -0.5, 1.0 / h, -0.5, 0.0, -1.0 / h, 0.0, 1.0 / h]);
        }
        blocks[32..].copy_from_slice(&[0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
        load(&mut s, l, &blocks);
        assert!(s.factor().is_err());
    }

    /// A small collocation system (5 nodes, n = 2, k = 1) with random blocks (also returned).
    fn small_random_system() -> (Layout, AbdSystem, Vec<f64>) {
        let l = Layout {
            nodes: 5,
            n: 2,
            k: 1,
            stride: 2,
        };
        let mut s = AbdSystem::new();
        s.prepare(l).unwrap();
        let mut blocks = vec![0.0; l.block_len()];
        fill(l, Kind::Collocation, false, &mut Rng(3), &mut blocks);
        load(&mut s, l, &blocks);
        (l, s, blocks)
    }

    #[test]
    fn pivot_test_is_relative_per_column() {
        // Scaling one unknown (a column) by 1e-200 leaves the system solvable.
        let (l, mut s, mut blocks) = small_random_system();
        let w = l.width();
        for i in 0..l.intervals() {
            for r in 0..l.stride {
                blocks[(i * l.stride + r) * w + w - 1] *= 1e-200;
            }
        }
        let bw = 2 * l.n + l.k;
        for r in 0..l.n + l.k {
            blocks[l.bc_offset() + r * bw + bw - 1] *= 1e-200;
        }
        load(&mut s, l, &blocks);
        s.factor().expect("scaled column is not singular");
        let mut x = vec![1.0; l.dim()];
        s.solve(&mut x).unwrap();
    }

    #[test]
    fn pivot_test_is_relative_per_row_too() {
        // Scaling the boundary rows by 1e-20 leaves the system solvable, with the same solution.
        // Those rows reach the final system (the boundary conditions at both ends), whose pivots
        // then fall far below 1e-14 of the interval rows' column maxima: once reported singular.
        let (l, mut s, mut blocks) = small_random_system();
        s.factor().unwrap();
        let mut want = vec![1.0; l.dim()];
        s.solve(&mut want).unwrap();
        for v in &mut blocks[l.bc_offset()..] {
            *v *= 1e-20;
        }
        load(&mut s, l, &blocks);
        s.factor().expect("row-scaled system is not singular");
        let mut x = vec![1.0; l.dim()];
        x[l.bcrow()..].iter_mut().for_each(|v| *v *= 1e-20);
        s.solve(&mut x).unwrap();
        for (a, b) in x.iter().zip(&want) {
            assert!((a - b).abs() <= 1e-10 * (1.0 + b.abs()), "{a} vs {b}");
        }
    }

    #[test]
    fn one_system_reused_across_shrinking_and_changing_layouts() {
        // As in a solve (coarsening shrinks the mesh) and across problems (n, k change): stale
        // buffers from a larger layout must not leak into a smaller one.
        let mut s = AbdSystem::new();
        let mut seq = layouts();
        seq.sort_by_key(|l| std::cmp::Reverse(l.intervals() * l.wrows() * l.wcols()));
        for (t, l) in seq.into_iter().enumerate() {
            let d = compare_with(&mut s, l, Kind::Collocation, false, 500 + t as u64);
            assert!(d <= 1e-10, "{l:?}: relative difference {d:e}");
        }
    }

    #[test]
    fn buffers_grow_only_for_larger_layouts() {
        let mut s = AbdSystem::new();
        let l = |nodes| Layout {
            nodes,
            n: 2,
            k: 0,
            stride: 2,
        };
        s.prepare(l(50)).unwrap();
        s.prepare(l(20)).unwrap();
        s.prepare(l(50)).unwrap();
        assert_eq!(s.buffer_growths, 1);
        s.prepare(l(51)).unwrap();
        assert_eq!(s.buffer_growths, 2);
    }

    #[test]
    fn ones_visits_the_set_bits_of_a_range() {
        let set = [!0u64, !0u64, 0x7f];
        assert!(ones(&set, 0, 135).eq(0..135));
        assert!(ones(&set, 60, 70).eq(60..70));
        assert!(ones(&set, 81, 135).eq(81..135));
        assert_eq!(ones(&set, 81, 81).count(), 0);
        assert_eq!(ones(&set, 100, 81).count(), 0);
        assert!(ones(&[0b1010, 0, 1], 0, 129).eq([1, 3, 128]));
    }

    #[test]
    fn packed_rows_read_as_the_dense_ones() {
        // Patterns over several words, entries at word boundaries: ranks and lookups.
        let (rows, cols) = (3, 135);
        let rw = words(cols);
        let mut w = vec![0.0; rows * cols];
        for (r, cs) in [[0, 63, 64], [1, 127, 128], [5, 70, 134]]
            .iter()
            .enumerate()
        {
            for (t, &c) in cs.iter().enumerate() {
                w[r * cols + c] = (10 * r + t + 1) as f64;
            }
        }
        let (mut rpat, mut cpat) = (vec![0; rows * rw], vec![0; 0]);
        scan(&w, None, rows, cols, 0, &mut rpat, &mut cpat);
        let (mut vals, mut roff) = (Vec::new(), Vec::new());
        for r in 0..rows {
            roff.push(vals.len());
            let row = &w[r * cols..(r + 1) * cols];
            vals.extend(ones(&rpat[r * rw..(r + 1) * rw], 0, cols).map(|c| row[c]));
        }
        let (d, p) = (
            Dense { w: &w, cols },
            Packed {
                vals: &vals,
                roff: &roff,
            },
        );
        for r in 0..rows {
            let pat = &rpat[r * rw..(r + 1) * rw];
            for c in 0..cols {
                assert_eq!(d.at(r, pat, c), p.at(r, pat, c), "({r}, {c})");
                assert_eq!(rank(pat, c), ones(pat, 0, c).count());
            }
            for (lo, hi) in [(0, cols), (1, 64), (64, 129), (65, cols), (cols, cols)] {
                assert!(d.entries(r, pat, lo, hi).eq(p.entries(r, pat, lo, hi)));
            }
        }
    }

    #[test]
    fn narrow_windows_factor_and_solve_as_the_sparse_path_to_the_bit() {
        let mut narrow = 0;
        for (t, l) in layouts().into_iter().enumerate() {
            for kind in [Kind::Collocation, Kind::Random, Kind::Sparse] {
                for separated in [false, true] {
                    let mut rng = Rng(3000 + t as u64);
                    let mut blocks = vec![0.0; l.block_len()];
                    fill(l, kind, separated, &mut rng, &mut blocks);
                    let b: Vec<f64> = (0..l.dim()).map(|_| rng.next()).collect();
                    let run = |force_sparse: bool| {
                        let mut s = AbdSystem::new();
                        s.prepare(l).unwrap();
                        if force_sparse {
                            s.narrow = false;
                        }
                        load(&mut s, l, &blocks);
                        let mut x = b.clone();
                        let ok = s.factor().and_then(|()| s.solve(&mut x)).is_ok();
                        (ok, s.dense_factors, s.piv.clone(), x)
                    };
                    let (ok_d, dense, piv_d, xd) = run(false);
                    let (ok_s, sparse_dense, piv_s, xs) = run(true);
                    assert!(!sparse_dense);
                    narrow += usize::from(dense);
                    assert_eq!(ok_d, ok_s, "{l:?}");
                    if ok_d {
                        assert_eq!(piv_d, piv_s, "{l:?}");
                        for (p, q) in xd.iter().zip(&xs) {
                            assert!(p == q, "{l:?} {separated}: {p:e} vs {q:e}");
                        }
                    }
                }
            }
        }
        assert!(narrow > 100, "{narrow} dense factorizations");
    }

    #[test]
    fn sparse_elimination_is_dense_elimination_to_the_bit() {
        // Several words per row and column; about 10 % nonzeros plus the diagonal.
        let (rows, cols, ne) = (108, 135, 81);
        let mut rng = Rng(5);
        let mut w = vec![0.0; rows * cols];
        for (e, x) in w.iter_mut().enumerate() {
            let v = rng.next();
            if v.abs() < 0.1 || e / cols == e % cols {
                *x = v;
            }
        }
        // Reference: the dense GEPP that the sparse one replaced.
        let mut d = w.clone();
        let mut dpiv = vec![0; ne];
        for j in 0..ne {
            let mut p = j;
            for r in j + 1..rows {
                if d[r * cols + j].abs() > d[p * cols + j].abs() {
                    p = r;
                }
            }
            dpiv[j] = p;
            for c in 0..cols {
                d.swap(j * cols + c, p * cols + c);
            }
            let inv = 1.0 / d[j * cols + j];
            for r in j + 1..rows {
                let l = d[r * cols + j] * inv;
                d[r * cols + j] = l;
                if l != 0.0 {
                    for c in j + 1..cols {
                        d[r * cols + c] -= l * d[j * cols + c];
                    }
                }
            }
        }
        let (rw, cw) = (words(cols), words(rows));
        let (mut rpat, mut cpat) = (vec![0; rows * rw], vec![0; ne * cw]);
        scan(&w, None, rows, cols, ne, &mut rpat, &mut cpat);
        let mut piv = vec![0; ne];
        let scale = vec![0.0; ne];
        let mut idx = Vec::new();
        eliminate(
            &mut w, None, rows, cols, ne, &mut piv, &scale, &mut rpat, &mut cpat, &mut idx,
        )
        .unwrap();
        assert_eq!(piv, dpiv);
        for r in 0..rows {
            for c in 0..cols {
                let (x, y) = (w[r * cols + c], d[r * cols + c]);
                assert!(x == y || (x == 0.0 && y == 0.0), "({r}, {c}): {x} vs {y}");
                assert!(
                    x == 0.0 || has(&rpat[r * rw..], c),
                    "({r}, {c}) not in the pattern"
                );
            }
        }
    }
}
