//! A banded matrix and its LU factorisation with partial pivoting (LAPACK `gbtf2` scheme), or,
//! for an exactly symmetric band whose pivots all come out positive (a symmetric positive
//! definite matrix: the ANCF iteration matrix and mass matrix, the linear model's matrices), an
//! LDLᵀ factorisation without pivoting at about a third of the LU's operations; for an
//! unsymmetric band that eliminates as stably as a positive definite one (the corotational
//! dynamic step's matrix), LU without row interchanges at half the pivoting LU's updates.
//!
//! The beam's node-ordered DOFs give a half-bandwidth of 5 (one element couples 6 consecutive
//! DOFs), so factorisation costs O(n·kl·(kl + ku)) and a solve O(n·(2kl + ku)): linear in the
//! number of elements. faer 0.24 has no banded solver and its general sparse LU/Cholesky carries
//! a symbolic/permutation overhead that dominates at the sizes the rig uses (≈ 100 DOFs, 20 µs
//! per step budget), hence this small dedicated kernel; dense/sparse faer is used for the
//! eigenproblem ([`crate::modal`]).
//!
//! **One file, one concept** (about 800 lines before its tests): the band matrix and its three
//! factorisations with their solves, which share the storage layout and the bounds that choose
//! between them.

use crate::BeamError;

/// Relative difference |a_ij − a_ji| / (|a_ij| + |a_ji|) up to which a band counts as
/// symmetric for the LDLᵀ factorisation: a few units of round-off (the ANCF element tangent's
/// mirrored entries are computed in different orders and differ by ≈ 1e-16 relative).
pub const SYMMETRY_TOLERANCE: f64 = 1e-14;

/// A square banded matrix with `kl` sub- and `ku` super-diagonals, stored by columns with `kl`
/// extra rows for the fill-in of pivoting.
#[derive(Debug, Clone, PartialEq)]
pub struct BandMatrix {
    n: usize,
    kl: usize,
    ku: usize,
    ld: usize,
    data: Vec<f64>,
    pivots: Vec<usize>,
    factored: bool,
    /// LDLᵀ factors when the last factorisation was the symmetric one (see
    /// `factorize_ldlt`); empty until first needed.
    ldl: Vec<f64>,
    /// True when `ldl` holds the factorisation (else `data` holds the LU factors).
    symmetric: bool,
    /// True when the LU factorisation interchanged rows (else U has only `ku` super-diagonals).
    interchanged: bool,
    /// The matrix as given, while the factorisation without interchanges is tried (see
    /// `factorize_diagonal`); reserved by `zeros` for the beam's band shapes.
    given: Vec<f64>,
}

impl BandMatrix {
    /// A zero `n`×`n` matrix with `kl` sub- and `ku` super-diagonals.
    pub fn zeros(n: usize, kl: usize, ku: usize) -> Self {
        let ld = 2 * kl + ku + 1;
        BandMatrix {
            n,
            kl,
            ku,
            ld,
            data: vec![0.0; ld * n],
            pivots: vec![0; n],
            factored: false,
            ldl: Vec::with_capacity(if kl == ku { (n + kl) * (2 * kl + 2) } else { 0 }),
            symmetric: false,
            interchanged: false,
            given: Vec::with_capacity(if matches!((kl, ku), (5, 5) | (7, 7)) {
                ld * n
            } else {
                0
            }),
        }
    }
    /// Dimension n.
    pub fn n(&self) -> usize {
        self.n
    }
    /// Zeroes every entry (keeps the allocation). The pivoting LU's fill-in rows are zeroed
    /// by the LU itself, so the beam's band shapes clear only the rows of the band (fixed-size
    /// column stores instead of a memset of the whole storage).
    pub fn clear(&mut self) {
        match (self.kl, self.ku) {
            (5, 5) => self.clear_band::<5, 16>(),
            (7, 7) => self.clear_band::<7, 22>(),
            _ => self.data.iter_mut().for_each(|x| *x = 0.0),
        }
        self.factored = false;
        self.symmetric = false;
    }
    #[inline]
    fn idx(&self, i: usize, j: usize) -> usize {
        j * self.ld + self.kl + self.ku + i - j
    }
    /// Zeroes the band rows (storage offsets K … 3K) of every column, kl = ku = K, LD = 3K + 1.
    fn clear_band<const K: usize, const LD: usize>(&mut self) {
        let (cols, _) = self.data.as_chunks_mut::<LD>();
        for col in cols {
            for x in &mut col[K..] {
                *x = 0.0;
            }
        }
    }

    /// Zeroes the LU's fill-in rows (storage offsets 0 … kl − 1) of every column.
    fn clear_fill(&mut self) {
        let (kl, ld) = (self.kl, self.ld);
        for col in self.data.chunks_exact_mut(ld) {
            col[..kl].iter_mut().for_each(|x| *x = 0.0);
        }
    }

    /// Entry (i, j); zero outside the band.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if i + self.ku >= j && i <= j + self.kl {
            self.data[self.idx(i, j)]
        } else {
            0.0
        }
    }
    /// Adds `value` to entry (i, j), which must lie inside the band.
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, value: f64) {
        debug_assert!(
            i + self.ku >= j && i <= j + self.kl,
            "({i},{j}) outside the band"
        );
        let k = self.idx(i, j);
        self.data[k] += value;
    }
    /// Adds the dense block `block` (by columns: `block[j][i]` is entry (first + i, first + j))
    /// to the rows and columns first … first + N − 1, which must lie inside the band
    /// (N − 1 ≤ kl, ku); the same sums as N² calls of [`BandMatrix::add`].
    #[inline(always)]
    pub fn add_block<const N: usize>(&mut self, first: usize, block: &[[f64; N]; N]) {
        assert!(
            N <= self.kl + 1 && N <= self.ku + 1 && first + N <= self.n,
            "block of {N} at {first} outside the band"
        );
        for (j, col) in block.iter().enumerate() {
            let c = first + j;
            let start = self.idx(first, c);
            let seg = &mut self.data[start..start + N];
            for (x, v) in seg.iter_mut().zip(col) {
                *x += v;
            }
        }
    }
    /// y = A x (before factorisation).
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate().take(self.n) {
            let lo = i.saturating_sub(self.kl);
            let hi = (i + self.ku).min(self.n - 1);
            *yi = (lo..=hi).map(|j| self.data[self.idx(i, j)] * x[j]).sum();
        }
    }
    /// Factorises the matrix for [`BandMatrix::solve_in_place`]. `what` names the matrix in the
    /// error raised on a (numerically) zero pivot.
    ///
    /// An exactly symmetric band of the beam's shapes (kl = ku = 5 or 7) is first factorised as
    /// LDLᵀ without pivoting ([`BandMatrix::is_ldlt`]; it leaves the matrix's entries in place);
    /// if a pivot is not positive (the matrix is not positive definite) or the band is not
    /// symmetric, as LU without row interchanges if that comes out as stable as LDLᵀ of a
    /// positive definite matrix (`factorize_diagonal`: the corotational dynamic step's
    /// matrix, positive definite but for its inertia's and contact's small unsymmetric
    /// terms); failing that, and for any other shape, the LU factorisation with partial
    /// pivoting ([`BandMatrix::factorize_lu`]) is made instead.
    pub fn factorize(&mut self, what: &str) -> Result<(), BeamError> {
        self.factored = false;
        self.symmetric = false;
        let tiny = self.max_abs() * 1e-14;
        let ldlt = match (self.kl, self.ku) {
            (5, 5) => self.symmetric_ldlt::<5, 6, 12, 16>(tiny),
            (7, 7) => self.symmetric_ldlt::<7, 8, 16, 22>(tiny),
            _ => None,
        };
        if let Some(Ok(())) = ldlt {
            self.symmetric = true;
            self.factored = true;
            return Ok(());
        }
        let diagonal = match (self.kl, self.ku) {
            (5, 5) => self.factorize_diagonal::<5, 10>(tiny),
            (7, 7) => self.factorize_diagonal::<7, 14>(tiny),
            _ => false,
        };
        if diagonal {
            self.factored = true;
            return Ok(());
        }
        self.lu(what, tiny)
    }

    /// LU without row interchanges of an unsymmetric band of the beam's shapes (kl = ku = K,
    /// W = 2K, the diagonal's storage offset), in place; `false` (the matrix as given put back)
    /// unless every pivot d_j is above `tiny` and every multiplier l_ij and entry u_ji of U
    /// obeys l_ij² d_j ≤ 2 a_ii and u_ji² / d_j ≤ 2 a_ii, a_ii the given diagonal.
    ///
    /// A positive definite matrix meets these with 1 for 2 (the diagonal of a Schur
    /// complement stays positive and below the given one), and they bound every product
    /// |l_ik u_kj| by 2 (a_ii a_jj)^½: the backward error is then that of LDLᵀ of a positive
    /// definite matrix (Cholesky's), whatever the scaling of the unknowns, which partial
    /// pivoting is not indifferent to. The bound is invariant under a diagonal scaling. The
    /// factors sit where the pivoting LU puts its own (no interchanges, U with K super-diagonals):
    /// its solve uses them. Half the updates of the pivoting LU, which interchanges rows in most
    /// columns of a turned corotational link (its axial stiffness then lies along y as much as
    /// along x) and widens U to 2K super-diagonals.
    ///
    /// On an x86-64 processor with AVX2 it runs compiled for it (as
    /// [`BandMatrix::symmetric_ldlt`]: the same factors bit for bit, tested).
    fn factorize_diagonal<const K: usize, const W: usize>(&mut self, tiny: f64) -> bool {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            return unsafe { self.factorize_diagonal_avx2::<K, W>(tiny) };
        }
        self.factorize_diagonal_portable::<K, W>(tiny)
    }

    /// [`BandMatrix::factorize_diagonal`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn factorize_diagonal_avx2<const K: usize, const W: usize>(&mut self, tiny: f64) -> bool {
        self.factorize_diagonal_portable::<K, W>(tiny)
    }

    /// [`BandMatrix::factorize_diagonal`] for any processor.
    #[inline(always)]
    fn factorize_diagonal_portable<const K: usize, const W: usize>(&mut self, tiny: f64) -> bool {
        debug_assert!(self.kl == K && self.ku == K && W == 2 * K);
        // (the capacity was reserved by `zeros`: no allocation here)
        self.given.clear();
        self.given.extend_from_slice(&self.data);
        let stable = self.eliminate_in_place::<K, W>(tiny);
        if stable {
            self.pivots.iter_mut().enumerate().for_each(|(j, p)| *p = j);
            self.interchanged = false;
        } else {
            self.data.copy_from_slice(&self.given);
        }
        self.given.clear();
        stable
    }

    /// The elimination of [`BandMatrix::factorize_diagonal`]; `false` at the first pivot or
    /// entry out of its bounds.
    #[inline(always)]
    fn eliminate_in_place<const K: usize, const W: usize>(&mut self, tiny: f64) -> bool {
        let (n, ld) = (self.n, self.ld);
        // x²/d ≤ 2 a_ii, a_ii the given diagonal (false for NaN)
        let bounded = |x: f64, d: f64, i: usize, g: &[f64]| x * x <= 2.0 * d * g[i * ld + W];
        for j in 0..n {
            let dstart = j * ld + W;
            let d = self.data[dstart];
            if d.is_nan() || d <= tiny {
                return false;
            }
            let m = K.min(n - 1 - j);
            // the multipliers (rows j + 1 … j + m of column j)
            for i in 0..m {
                let x = self.data[dstart + 1 + i];
                if !bounded(x, d, j + 1 + i, &self.given) {
                    return false;
                }
                self.data[dstart + 1 + i] = x / d;
            }
            // row j of U in columns j + 1 … j + m, and the update of their rows j + 1 … j + m
            for c in 1..=m {
                let base = (j + c) * ld + W - c;
                let ajc = self.data[base];
                if !bounded(ajc, d, j + c, &self.given) {
                    return false;
                }
                if m == K {
                    let (head, tail) = self.data.split_at_mut(base + 1);
                    let l: &[f64; K] = head[dstart + 1..dstart + 1 + K]
                        .try_into()
                        .expect("band column");
                    let seg: &mut [f64; K] = (&mut tail[..K]).try_into().expect("band column");
                    for i in 0..K {
                        seg[i] -= l[i] * ajc;
                    }
                } else {
                    for i in 0..m {
                        let li = self.data[dstart + 1 + i];
                        self.data[base + 1 + i] -= li * ajc;
                    }
                }
            }
        }
        true
    }

    /// True if the last factorisation was the symmetric LDLᵀ one (else the pivoting LU).
    pub fn is_ldlt(&self) -> bool {
        self.factored && self.symmetric
    }

    /// LU factorisation in place with partial pivoting, whatever the symmetry. `what` names
    /// the matrix in the error raised on a (numerically) zero pivot.
    ///
    /// The beam's band shapes (kl = ku = 5 for the 3-DOF nodes, 7 for ANCF) run kernels with the
    /// bandwidths as constants (fixed-length column updates that the compiler unrolls and
    /// vectorises); the last columns, where the matrix's end cuts the band, and any other shape
    /// run the general loop. Both do the same operations in the same order.
    pub fn factorize_lu(&mut self, what: &str) -> Result<(), BeamError> {
        self.factored = false;
        self.symmetric = false;
        let tiny = self.max_abs() * 1e-14;
        self.lu(what, tiny)
    }

    fn lu(&mut self, what: &str, tiny: f64) -> Result<(), BeamError> {
        if matches!((self.kl, self.ku), (5, 5) | (7, 7)) {
            self.clear_fill();
        }
        self.interchanged = false;
        let done = match (self.kl, self.ku) {
            (5, 5) => self.factorize_fixed::<5, 10>(tiny),
            (7, 7) => self.factorize_fixed::<7, 14>(tiny),
            _ => Ok(0),
        };
        let first = done.map_err(|j| Self::singular(what, j))?;
        for j in first..self.n {
            self.factor_column(j, tiny)
                .map_err(|j| Self::singular(what, j))?;
        }
        self.factored = true;
        Ok(())
    }

    /// The largest magnitude of the stored entries (NaN ignored, as by `f64::max`), in four
    /// independent lanes so that the loop vectorises.
    fn max_abs(&self) -> f64 {
        let mut m = [0.0f64; 4];
        let chunks = self.data.chunks_exact(4);
        let rest = chunks.remainder();
        for c in chunks {
            for k in 0..4 {
                let a = c[k].abs();
                m[k] = if a > m[k] { a } else { m[k] };
            }
        }
        for x in rest {
            m[0] = m[0].max(x.abs());
        }
        m[0].max(m[1]).max(m[2].max(m[3]))
    }

    /// The error for a zero pivot in column `dof`.
    fn singular(what: &str, dof: usize) -> BeamError {
        BeamError::Singular {
            what: what.to_string(),
            dof,
            hint: "the structure is a mechanism (e.g. a pinned root without a torsion \
                   spring under a static load), the solution diverged, or the matrix is \
                   too ill-conditioned for double precision (its condition grows as N⁴ \
                   with the number of elements: use fewer)"
                .into(),
        }
    }

    /// Pivot search in column `j` (rows j..=last): the row of the largest magnitude, or the
    /// column as the error if it is below `tiny` (or NaN).
    #[inline(always)]
    fn pivot(&self, j: usize, last: usize, tiny: f64) -> Result<usize, usize> {
        let base = self.idx(j, j);
        let col = &self.data[base..base + last - j + 1];
        let mut p = 0;
        let mut best = col[0].abs();
        for (i, v) in col.iter().enumerate().skip(1) {
            if v.abs() > best {
                best = v.abs();
                p = i;
            }
        }
        if best.is_nan() || best <= tiny {
            return Err(j);
        }
        Ok(j + p)
    }

    /// Swaps rows `j` and `p` over columns j..=cend (the rows' band entries).
    #[inline(always)]
    fn swap_rows(&mut self, j: usize, p: usize, cend: usize) {
        if p != j {
            for c in j..=cend {
                let (a, b) = (self.idx(j, c), self.idx(p, c));
                self.data.swap(a, b);
            }
        }
    }

    /// One column of the general factorisation (any band shape, any position).
    fn factor_column(&mut self, j: usize, tiny: f64) -> Result<(), usize> {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        let last = (j + kl).min(n - 1);
        let p = self.pivot(j, last, tiny)?;
        self.pivots[j] = p;
        self.interchanged |= p != j;
        let cend = (j + ku + kl).min(n - 1);
        self.swap_rows(j, p, cend);
        let d = self.data[self.idx(j, j)];
        for i in j + 1..=last {
            let k = self.idx(i, j);
            self.data[k] /= d;
        }
        let nl = last - j;
        if nl > 0 {
            // column j's multipliers (rows j+1..=last) are contiguous, and so is each column
            // c's segment of the same rows: split the storage and update by slices
            let lstart = self.idx(j + 1, j);
            let (head, tail) = self.data.split_at_mut((j + 1) * self.ld);
            let l = &head[lstart..lstart + nl];
            for c in j + 1..=cend {
                let base = (c - j - 1) * self.ld + self.kl + self.ku + j - c;
                let ajc = tail[base];
                let seg = &mut tail[base + 1..base + 1 + nl];
                for (x, li) in seg.iter_mut().zip(l) {
                    *x -= li * ajc;
                }
            }
        }
        Ok(())
    }

    /// The columns 0..n − KL − W of the factorisation for kl = KL, ku + kl = W (the fill-in
    /// width), with fixed-length updates; returns the first column left to the general loop,
    /// or the column of a zero pivot.
    ///
    /// As LAPACK's `gbtf2`, the updates reach only the columns that the interchanges so far
    /// can have filled (column j + ku without any, up to j + kl + ku): row j's entries beyond
    /// them are zeros, whose updates would leave every entry as it is. Without interchanges (a
    /// diagonally dominant matrix, as a dynamic step's mass-dominated one) half the work.
    fn factorize_fixed<const KL: usize, const W: usize>(
        &mut self,
        tiny: f64,
    ) -> Result<usize, usize> {
        debug_assert!(self.kl == KL && self.kl + self.ku == W);
        let (n, ld, ku) = (self.n, self.ld, self.ku);
        let end = n.saturating_sub(W + 1);
        // the last column that the rows moved up by the interchanges so far reach
        let mut reach = 0;
        // row j of column c sits at c·ld + W + j − c: column c's rows j+1..=j+KL start at
        // c·ld + W + j + 1 − c
        for j in 0..end {
            let p = self.pivot(j, j + KL, tiny)?;
            self.pivots[j] = p;
            self.interchanged |= p != j;
            reach = reach.max(p + ku);
            self.swap_rows(j, p, reach);
            let dstart = j * ld + W;
            let d = self.data[dstart];
            let l: [f64; KL] = {
                let col: &mut [f64; KL] = (&mut self.data[dstart + 1..dstart + 1 + KL])
                    .try_into()
                    .expect("band column");
                for x in col.iter_mut() {
                    *x /= d;
                }
                *col
            };
            for c in j + 1..=reach {
                let base = c * ld + W + j - c;
                let ajc = self.data[base];
                let seg: &mut [f64; KL] = (&mut self.data[base + 1..base + 1 + KL])
                    .try_into()
                    .expect("band column");
                for i in 0..KL {
                    seg[i] -= l[i] * ajc;
                }
            }
        }
        Ok(end)
    }

    /// The symmetric path of [`BandMatrix::factorize`]: `None` if the band is not symmetric to
    /// round-off, else the LDLᵀ factorisation's outcome (kl = ku = K, P = K + 1, S = 2K + 2,
    /// LD = 3K + 1).
    ///
    /// On an x86-64 processor with AVX2 the same code runs compiled for it (4-wide instead of
    /// 2-wide vectors; no fused multiply-add, so the same operations in the same order and the
    /// same factors bit for bit, tested): 40 % fewer instructions for the ANCF band.
    fn symmetric_ldlt<const K: usize, const P: usize, const S: usize, const LD: usize>(
        &mut self,
        tiny: f64,
    ) -> Option<Result<(), ()>> {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            return unsafe { self.symmetric_ldlt_avx2::<K, P, S, LD>(tiny) };
        }
        self.symmetric_ldlt_portable::<K, P, S, LD>(tiny)
    }

    /// [`BandMatrix::symmetric_ldlt`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn symmetric_ldlt_avx2<const K: usize, const P: usize, const S: usize, const LD: usize>(
        &mut self,
        tiny: f64,
    ) -> Option<Result<(), ()>> {
        self.symmetric_ldlt_portable::<K, P, S, LD>(tiny)
    }

    /// [`BandMatrix::symmetric_ldlt`] for any x86-64 (or other) processor.
    #[inline(always)]
    fn symmetric_ldlt_portable<const K: usize, const P: usize, const S: usize, const LD: usize>(
        &mut self,
        tiny: f64,
    ) -> Option<Result<(), ()>> {
        if !self.is_symmetric::<K, LD>() {
            return None;
        }
        Some(self.factorize_ldlt::<K, P, S, LD>(tiny))
    }

    /// True if the stored band is symmetric to round-off: every entry (i, j) within
    /// [`SYMMETRY_TOLERANCE`] (relative) of (j, i) (NaN entries make it unsymmetric), for
    /// kl = ku = K and LD = 3K + 1 (the storage's column length). Factorising the lower
    /// triangle of such a matrix solves a system that differs from the given one by less than
    /// the pivoting LU's own backward error.
    #[inline(always)]
    fn is_symmetric<const K: usize, const LD: usize>(&self) -> bool {
        debug_assert!(self.kl == K && self.ku == K && self.ld == LD);
        let (cols, _) = self.data.as_chunks::<LD>();
        let cols = &cols[..self.n];
        let dg = 2 * K; // the diagonal's offset in a column
        let close = |a: f64, b: f64| (a - b).abs() <= SYMMETRY_TOLERANCE * (a.abs() + b.abs());
        // column c's upper entries (c − d, c) against the lower ones (c, c − d)
        for c in 1..cols.len().min(K) {
            for d in 1..=c {
                if !close(cols[c][dg - d], cols[c - d][dg + d]) {
                    return false;
                }
            }
        }
        for c in K..cols.len() {
            let w = &cols[c - K..=c];
            let mut ok = true;
            for d in 1..=K {
                ok &= close(w[K][dg - d], w[K - d][dg + d]);
            }
            if !ok {
                return false;
            }
        }
        true
    }

    /// LDLᵀ factorisation without pivoting of a band symmetric to round-off (kl = ku = K,
    /// P = K + 1, S = 2K + 2, LD = 3K + 1) from its lower triangle into `ldl`; `Err` if a pivot D_jj is
    /// not above `tiny` (the matrix is then not numerically positive definite and the caller
    /// pivots instead). Every pivot positive means the matrix is positive definite, for which
    /// this factorisation without pivoting is backward stable (it is Cholesky's: L D^½ is the
    /// Cholesky factor).
    ///
    /// `ldl` holds S entries per column, rows j − K … j + K of column j and a zero (K zero
    /// padding columns after the last one): column j's multipliers L_{j+1..=j+K, j} below
    /// 1/D_jj at offset K, then the zero. The update of column j + c by column j then covers
    /// the fixed-length rows j + 1 … j + K + 1, the rows above column j + c's diagonal included
    /// (they are scratch, never read) and a last one that subtracts exactly zero: P = K + 1
    /// multiply-adds per update (8 for the ANCF band: two 4-wide vector operations), in
    /// fixed-length loops that vectorise, against the pivoting LU's 2K-long updates and row
    /// interchanges.
    #[inline(always)]
    fn factorize_ldlt<const K: usize, const P: usize, const S: usize, const LD: usize>(
        &mut self,
        tiny: f64,
    ) -> Result<(), ()> {
        debug_assert!(
            self.kl == K && self.ku == K && P == K + 1 && S == 2 * K + 2 && self.ld == LD
        );
        let n = self.n;
        // (the capacity was reserved by `zeros`: no allocation here)
        self.ldl.resize((n + K) * S, 0.0);
        let (src, _) = self.data.as_chunks::<LD>();
        let (cols, _) = self.ldl.as_chunks_mut::<S>();
        for (col, a) in cols.iter_mut().zip(src) {
            // rows j − K … j + K: storage offsets K … 3K; then the zero
            let (rows, zero) = col.split_at_mut(S - 1);
            rows.copy_from_slice(&a[K..K + S - 1]);
            zero[0] = 0.0;
        }
        // below the matrix's end and in the padding: zero
        for (j, col) in cols.iter_mut().enumerate().skip(n.saturating_sub(K)) {
            for (i, x) in col.iter_mut().enumerate().skip(K) {
                if j + i - K >= n {
                    *x = 0.0;
                }
            }
        }
        for j in 0..n {
            let (head, tail) = cols.split_at_mut(j + 1);
            let cj = &mut head[j];
            let d = cj[K];
            if d.is_nan() || d <= tiny {
                return Err(());
            }
            let dinv = 1.0 / d;
            // the multipliers and the zero below them
            let l: [f64; P] = std::array::from_fn(|i| cj[K + 1 + i]);
            // A_{j+i, j+c} −= A_{j+i, j} A_{j+c, j} / D_jj, i = 1 … K (rows j + i of column
            // j + c sit at offset K + i − c), and 0 from row j + K + 1; the K columns after j
            // exist (padding at the end)
            let next: &mut [[f64; S]; K] = (&mut tail[..K]).try_into().expect("padding columns");
            for (c, col) in next.iter_mut().enumerate() {
                let lc = l[c] * dinv;
                let (_, rows) = col.split_at_mut(K - c);
                let dst: &mut [f64; P] = rows.first_chunk_mut().expect("band column");
                let mut x = *dst;
                for i in 0..P {
                    x[i] -= l[i] * lc;
                }
                *dst = x;
            }
            for i in 0..K {
                cj[K + 1 + i] = l[i] * dinv;
            }
            cj[K] = dinv;
        }
        Ok(())
    }

    /// Solves with the LDLᵀ factors, compiled for AVX2 when the processor has it (as
    /// [`BandMatrix::symmetric_ldlt`]: the same results bit for bit).
    fn solve_ldlt<const K: usize, const P: usize, const S: usize>(&self, b: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            return unsafe { self.solve_ldlt_avx2::<K, P, S>(b) };
        }
        self.solve_ldlt_portable::<K, P, S>(b)
    }

    /// [`BandMatrix::solve_ldlt`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn solve_ldlt_avx2<const K: usize, const P: usize, const S: usize>(&self, b: &mut [f64]) {
        self.solve_ldlt_portable::<K, P, S>(b)
    }

    /// Solves with the LDLᵀ factors (1/D_jj at offset K of column j, L below it, then a zero;
    /// P = K + 1, S = 2K + 2).
    ///
    /// Both sweeps keep the K entries of the right-hand side that the current column touches
    /// in registers (a window moved along by one row per column, built anew each row rather
    /// than shifted in place, which the compiler passed through the stack: a narrow store,
    /// then a wide overlapping load that waits for it) instead of passing them through memory
    /// from one column to the next. The substitutions are sequential: each unknown waits for
    /// the one solved before it. Both sweeps therefore subtract the unknown solved last as
    /// their last term (the column-oriented order: x_j = z_j − L_{j+K,j} x_{j+K} − … −
    /// L_{j+1,j} x_{j+1}), so that only one multiplication and one subtraction wait for it
    /// (the back substitution summed from L_{j+1,j} x_{j+1} outwards before, a chain of K + 1
    /// dependent operations per row: 2.4 times the time per solve). The same products,
    /// summed in another order: the solutions differ from that order's by round-off.
    #[inline(always)]
    fn solve_ldlt_portable<const K: usize, const P: usize, const S: usize>(&self, b: &mut [f64]) {
        debug_assert!(P == K + 1 && S == 2 * K + 2);
        let n = self.n;
        let (cols, _) = self.ldl.as_chunks::<S>();
        let cols = &cols[..n];
        let b = &mut b[..n];
        // the columns with K multipliers inside the matrix
        let full = n.saturating_sub(K);
        // L y = b: rows j + 1 … j + K of the running right-hand side in `w`
        if full > 0 {
            let mut w = [0.0f64; K];
            w.copy_from_slice(&b[1..=K]);
            let mut bj = b[0];
            for j in 0..full {
                let l: &[f64; K] = cols[j][K + 1..2 * K + 1].try_into().expect("band column");
                let mut next = [0.0f64; K];
                for i in 0..K {
                    next[i] = w[i] - l[i] * bj;
                }
                bj = next[0];
                b[j + 1] = bj;
                w[..K - 1].copy_from_slice(&next[1..]);
                w[K - 1] = if j + K + 1 < n { b[j + K + 1] } else { 0.0 };
            }
            b[full + 1..].copy_from_slice(&w[..n - full - 1]);
        }
        for j in full..n {
            let (bj, l) = (b[j], &cols[j]);
            for i in j + 1..n {
                b[i] -= l[K + i - j] * bj;
            }
        }
        // D z = y, Lᵀ x = z (the last K columns first)
        for j in (full..n).rev() {
            let l = &cols[j];
            let mut x = b[j] * l[K];
            for i in (j + 1..n).rev() {
                x -= l[K + i - j] * b[i];
            }
            b[j] = x;
        }
        if full > 0 {
            // x_{j+1} … x_{j+K} in `w`
            let mut w: [f64; K] = b[full..].try_into().expect("the last K rows");
            for j in (0..full).rev() {
                let l: &[f64; K] = cols[j][K + 1..2 * K + 1].try_into().expect("band column");
                let mut x = b[j] * cols[j][K];
                for i in (0..K).rev() {
                    x -= l[i] * w[i];
                }
                b[j] = x;
                let mut shifted = [x; K];
                shifted[1..].copy_from_slice(&w[..K - 1]);
                w = shifted;
            }
        }
    }

    /// Solves A x = b in place (after [`BandMatrix::factorize`]).
    pub fn solve_in_place(&self, b: &mut [f64]) {
        assert!(self.factored, "BandMatrix::solve_in_place before factorize");
        assert_eq!(
            b.len(),
            self.n,
            "BandMatrix::solve_in_place: right-hand side length"
        );
        if self.symmetric {
            return match self.kl {
                5 => self.solve_ldlt::<5, 6, 12>(b),
                _ => self.solve_ldlt::<7, 8, 16>(b),
            };
        }
        match (self.kl, self.ku, self.interchanged) {
            (5, 5, true) => self.solve_fixed::<5, 10, 10>(b),
            (5, 5, false) => self.solve_fixed::<5, 10, 5>(b),
            (7, 7, true) => self.solve_fixed::<7, 14, 14>(b),
            (7, 7, false) => self.solve_fixed::<7, 14, 7>(b),
            _ => self.solve_general(b),
        }
    }

    /// [`BandMatrix::solve_in_place`] for any band shape.
    fn solve_general(&self, b: &mut [f64]) {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        for j in 0..n {
            let p = self.pivots[j];
            if p != j {
                b.swap(p, j);
            }
            let bj = b[j];
            if bj != 0.0 {
                for i in j + 1..=(j + kl).min(n - 1) {
                    b[i] -= self.data[self.idx(i, j)] * bj;
                }
            }
        }
        for j in (0..n).rev() {
            b[j] /= self.data[self.idx(j, j)];
            let bj = b[j];
            if bj != 0.0 {
                for i in j.saturating_sub(kl + ku)..j {
                    b[i] -= self.data[self.idx(i, j)] * bj;
                }
            }
        }
    }

    /// [`BandMatrix::solve_in_place`] for kl = KL, kl + ku = W with fixed-length column
    /// updates away from the matrix's ends (the same operations as the general loop), U's
    /// super-diagonals taken as U = W (after row interchanges) or ku (without any: the
    /// others are zeros, whose updates would leave the solution as it is). Compiled for AVX2
    /// when the processor has it (the same results bit for bit, tested).
    fn solve_fixed<const KL: usize, const W: usize, const U: usize>(&self, b: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            return unsafe { self.solve_fixed_avx2::<KL, W, U>(b) };
        }
        self.solve_fixed_portable::<KL, W, U>(b)
    }

    /// [`BandMatrix::solve_fixed`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn solve_fixed_avx2<const KL: usize, const W: usize, const U: usize>(&self, b: &mut [f64]) {
        self.solve_fixed_portable::<KL, W, U>(b)
    }

    /// [`BandMatrix::solve_fixed`] for any processor.
    #[inline(always)]
    fn solve_fixed_portable<const KL: usize, const W: usize, const U: usize>(&self, b: &mut [f64]) {
        let (n, ld) = (self.n, self.ld);
        if n <= W + 1 {
            return self.solve_general(b);
        }
        // forward: L, with the row interchanges
        for j in 0..n {
            let p = self.pivots[j];
            if p != j {
                b.swap(p, j);
            }
            let bj = b[j];
            let start = j * ld + W + 1;
            if j + KL < n {
                let l: &[f64; KL] = self.data[start..start + KL].try_into().expect("band");
                let seg: &mut [f64; KL] = (&mut b[j + 1..j + 1 + KL]).try_into().expect("rhs");
                for i in 0..KL {
                    seg[i] -= l[i] * bj;
                }
            } else {
                for i in j + 1..n {
                    b[i] -= self.data[start + i - j - 1] * bj;
                }
            }
        }
        // backward: U (kl + ku super-diagonals after the interchanges, ku without)
        for j in (0..n).rev() {
            let diag = j * ld + W;
            b[j] /= self.data[diag];
            let bj = b[j];
            if j >= U {
                let u: &[f64; U] = self.data[diag - U..diag].try_into().expect("band");
                let seg: &mut [f64; U] = (&mut b[j - U..j]).try_into().expect("rhs");
                for i in 0..U {
                    seg[i] -= u[i] * bj;
                }
            } else {
                for i in 0..j {
                    b[i] -= self.data[diag - (j - i)] * bj;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_nonsymmetric_band_system_needing_pivots() {
        let n = 40;
        let (kl, ku) = (3, 2);
        let mut a = BandMatrix::zeros(n, kl, ku);
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                // small diagonal forces pivoting
                let v = if i == j {
                    1e-3 * (i as f64 + 1.0)
                } else {
                    ((i * 7 + j * 3) % 11) as f64 - 5.0
                };
                a.add(i, j, v);
            }
        }
        let x: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut b = vec![0.0; n];
        a.mul_vec(&x, &mut b);
        a.factorize("test").unwrap();
        a.solve_in_place(&mut b);
        for i in 0..n {
            assert!((b[i] - x[i]).abs() < 1e-10, "{i}: {} vs {}", b[i], x[i]);
        }
    }

    /// A band matrix with a small diagonal (forces row interchanges).
    fn pivoting_band(n: usize, kl: usize, ku: usize) -> BandMatrix {
        let mut a = BandMatrix::zeros(n, kl, ku);
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                let v = if i == j {
                    1e-3 * (i as f64 + 1.0)
                } else {
                    5.0 * (1.3 * i as f64 + 0.7 * j as f64 + 0.1 * (i * j) as f64).sin()
                };
                a.add(i, j, v);
            }
        }
        a
    }

    #[test]
    fn fixed_bandwidth_kernels_give_the_general_loops_result_bit_for_bit() {
        // the beam's shapes (5, 5) and (7, 7) run the fixed-bandwidth kernels; the same
        // factorisation by the general loop alone must give identical bits, and both must solve
        for (kl, n) in [(5usize, 40usize), (7, 40), (5, 12), (7, 16), (7, 9)] {
            let a = pivoting_band(n, kl, kl);
            let x: Vec<f64> = (0..n).map(|i| (0.3 * i as f64).sin() + 0.5).collect();
            let mut b = vec![0.0; n];
            a.mul_vec(&x, &mut b);
            let mut slow = a.clone();
            let tiny = 1e-14 * a.data.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for j in 0..n {
                slow.factor_column(j, tiny).unwrap();
            }
            let mut fast = a.clone();
            fast.factorize("fast").unwrap();
            slow.factored = true;
            assert_eq!(fast, slow, "kl {kl} n {n}: factors differ");
            let mut xf = b.clone();
            fast.solve_in_place(&mut xf);
            let mut xs = b.clone();
            slow.solve_general(&mut xs);
            assert_eq!(xf, xs, "kl {kl} n {n}: solutions differ");
            for i in 0..n {
                assert!(
                    (xf[i] - x[i]).abs() < 1e-9,
                    "kl {kl} n {n} [{i}]: {} vs {}",
                    xf[i],
                    x[i]
                );
            }
        }
    }

    #[test]
    fn singular_matrix_is_an_error_not_a_panic() {
        let mut a = BandMatrix::zeros(3, 1, 1);
        a.add(0, 0, 1.0);
        a.add(1, 1, 0.0);
        a.add(2, 2, 1.0);
        assert!(matches!(
            a.factorize("K"),
            Err(BeamError::Singular { dof: 1, .. })
        ));
    }

    /// A deterministic pseudo-random number in [−1, 1) (64-bit LCG).
    fn next(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((*seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }

    /// A random symmetric band (kl = ku = k): random off-diagonals, the diagonal `shift` plus
    /// the row's absolute sum times `dominance` (> 1: positive definite), then scaled
    /// symmetrically by `scale`ⁱ⁻ᵖᵉʳⁱᵒᵈ (rows of very different magnitudes, as the ANCF
    /// positions against slopes).
    fn random_symmetric(
        n: usize,
        k: usize,
        seed: &mut u64,
        dominance: f64,
        scale: f64,
    ) -> BandMatrix {
        let mut dense = vec![vec![0.0; n]; n];
        for i in 0..n {
            for j in i + 1..=(i + k).min(n - 1) {
                let v = next(seed);
                dense[i][j] = v;
                dense[j][i] = v;
            }
        }
        let s: Vec<f64> = (0..n)
            .map(|i| if i % 4 >= 2 { scale } else { 1.0 })
            .collect();
        let mut a = BandMatrix::zeros(n, k, k);
        for i in 0..n {
            let row: f64 = dense[i].iter().map(|v| v.abs()).sum();
            dense[i][i] = dominance * row + 0.1 * next(seed).abs();
            for j in i.saturating_sub(k)..=(i + k).min(n - 1) {
                a.add(i, j, s[i] * dense[i][j] * s[j]);
            }
        }
        a
    }

    #[test]
    fn ldlt_solves_random_spd_bands_as_the_pivoting_lu_does() {
        // Independent reference: the pivoting LU of the same matrix (and the residual of the
        // product). Positive definite (diagonally dominant), slopes-like rows scaled by 1e-2
        // and 1e2, the beam's shapes and sizes down to a matrix shorter than its band.
        let mut seed = 7u64;
        for k in [5usize, 7] {
            for n in [1usize, 3, k + 1, 2 * k + 3, 40, 126] {
                for scale in [1.0, 1e-2, 1e2] {
                    let a = random_symmetric(n, k, &mut seed, 1.05, scale);
                    let x: Vec<f64> = (0..n).map(|_| next(&mut seed)).collect();
                    let mut b = vec![0.0; n];
                    a.mul_vec(&x, &mut b);
                    let mut sym = a.clone();
                    sym.factorize("spd").unwrap();
                    assert!(
                        sym.is_ldlt(),
                        "k {k} n {n}: an SPD band takes the LDLᵀ path"
                    );
                    let mut lu = a.clone();
                    lu.factorize_lu("spd").unwrap();
                    assert!(!lu.is_ldlt());
                    let (mut xs, mut xl) = (b.clone(), b.clone());
                    sym.solve_in_place(&mut xs);
                    lu.solve_in_place(&mut xl);
                    let xmax = xl.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    // 1e-12 relative; the scaled matrices' condition grows as scale²
                    let tol = 1e-12 * (scale * scale).max(1.0 / (scale * scale));
                    for i in 0..n {
                        assert!(
                            (xs[i] - xl[i]).abs() <= tol * xmax,
                            "k {k} n {n} scale {scale} [{i}]: LDLᵀ {} vs LU {}",
                            xs[i],
                            xl[i]
                        );
                    }
                    // the matrix is left in place: its product with the solution is b
                    let mut ax = vec![0.0; n];
                    sym.mul_vec(&xs, &mut ax);
                    let bmax = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    for i in 0..n {
                        assert!((ax[i] - b[i]).abs() <= tol * bmax, "k {k} n {n} [{i}]");
                    }
                }
            }
        }
    }

    #[test]
    fn the_processor_specific_ldlt_gives_the_portable_factors_and_solutions_bit_for_bit() {
        // The dispatched path (AVX2 where the processor has it) against the portable code on
        // the same random SPD bands: identical factors and solutions, to the last bit.
        let mut seed = 11u64;
        for k in [5usize, 7] {
            for n in [1usize, 3, k + 1, k + 2, 2 * k + 3, 40, 128] {
                let a = random_symmetric(n, k, &mut seed, 1.05, 1e-2);
                let b: Vec<f64> = (0..n).map(|_| next(&mut seed)).collect();
                let (mut fast, mut portable) = (a.clone(), a.clone());
                let tiny = a.max_abs() * 1e-14;
                let (x_fast, x_portable) = if k == 5 {
                    let f = fast.symmetric_ldlt::<5, 6, 12, 16>(tiny);
                    let p = portable.symmetric_ldlt_portable::<5, 6, 12, 16>(tiny);
                    assert_eq!((f, p), (Some(Ok(())), Some(Ok(()))), "k {k} n {n}");
                    let (mut xf, mut xp) = (b.clone(), b.clone());
                    fast.solve_ldlt::<5, 6, 12>(&mut xf);
                    portable.solve_ldlt_portable::<5, 6, 12>(&mut xp);
                    (xf, xp)
                } else {
                    let f = fast.symmetric_ldlt::<7, 8, 16, 22>(tiny);
                    let p = portable.symmetric_ldlt_portable::<7, 8, 16, 22>(tiny);
                    assert_eq!((f, p), (Some(Ok(())), Some(Ok(()))), "k {k} n {n}");
                    let (mut xf, mut xp) = (b.clone(), b.clone());
                    fast.solve_ldlt::<7, 8, 16>(&mut xf);
                    portable.solve_ldlt_portable::<7, 8, 16>(&mut xp);
                    (xf, xp)
                };
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&fast.ldl), bits(&portable.ldl), "k {k} n {n}: factors");
                assert_eq!(bits(&x_fast), bits(&x_portable), "k {k} n {n}: solution");
                assert!(x_fast.iter().all(|x| x.is_finite()));
            }
        }
    }

    #[test]
    fn the_processor_specific_lu_gives_the_portable_factors_and_solutions_bit_for_bit() {
        // The dispatched LU without interchanges and its solve (AVX2 where the processor has
        // it) against the portable code on the same random unsymmetric positive definite
        // bands: identical factors and solutions, to the last bit.
        let mut seed = 17u64;
        for k in [5usize, 7] {
            for n in [2usize, 3, k + 1, 2 * k + 2, 2 * k + 3, 48, 126] {
                let mut a = random_symmetric(n, k, &mut seed, 1.05, 1.0);
                for j in 0..n {
                    for i in j.saturating_sub(k)..j {
                        a.add(i, j, 1e-3 * a.get(i, j) * next(&mut seed));
                    }
                }
                let b: Vec<f64> = (0..n).map(|_| next(&mut seed)).collect();
                let (mut fast, mut portable) = (a.clone(), a.clone());
                let tiny = a.max_abs() * 1e-14;
                let (mut xf, mut xp) = (b.clone(), b.clone());
                if k == 5 {
                    assert!(fast.factorize_diagonal::<5, 10>(tiny), "k {k} n {n}");
                    assert!(portable.factorize_diagonal_portable::<5, 10>(tiny));
                    fast.solve_fixed::<5, 10, 5>(&mut xf);
                    portable.solve_fixed_portable::<5, 10, 5>(&mut xp);
                } else {
                    assert!(fast.factorize_diagonal::<7, 14>(tiny), "k {k} n {n}");
                    assert!(portable.factorize_diagonal_portable::<7, 14>(tiny));
                    fast.solve_fixed::<7, 14, 7>(&mut xf);
                    portable.solve_fixed_portable::<7, 14, 7>(&mut xp);
                }
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&fast.data),
                    bits(&portable.data),
                    "k {k} n {n}: factors"
                );
                assert_eq!(bits(&xf), bits(&xp), "k {k} n {n}: solution");
                // an independent check: the factors solve the given system
                let mut ax = vec![0.0; n];
                a.mul_vec(&xf, &mut ax);
                for i in 0..n {
                    assert!((ax[i] - b[i]).abs() <= 1e-12, "k {k} n {n} [{i}]");
                }
            }
        }
    }

    #[test]
    fn unsymmetric_positive_definite_bands_factor_without_interchanges() {
        // Independent reference: the pivoting LU of the same matrix. Positive definite
        // (diagonally dominant) bands, rows scaled by 1e-2 and 1e2 (the pivoting LU then
        // interchanges rows), made unsymmetric by 1e-3 of every entry above the diagonal;
        // and a band with a small diagonal, which must take the pivoting LU.
        let mut seed = 5u64;
        for k in [5usize, 7] {
            for n in [2usize, 3, k + 1, 2 * k + 3, 40, 126] {
                for scale in [1.0, 1e-2, 1e2] {
                    let mut a = random_symmetric(n, k, &mut seed, 1.05, scale);
                    for j in 0..n {
                        for i in j.saturating_sub(k)..j {
                            a.add(i, j, 1e-3 * a.get(i, j) * next(&mut seed));
                        }
                    }
                    let x: Vec<f64> = (0..n).map(|_| next(&mut seed)).collect();
                    let mut b = vec![0.0; n];
                    a.mul_vec(&x, &mut b);
                    let mut diagonal = a.clone();
                    diagonal.factorize("unsymmetric").unwrap();
                    assert!(!diagonal.is_ldlt() && !diagonal.interchanged, "k {k} n {n}");
                    let mut lu = a.clone();
                    lu.factorize_lu("unsymmetric").unwrap();
                    let (mut xd, mut xl) = (b.clone(), b.clone());
                    diagonal.solve_in_place(&mut xd);
                    lu.solve_in_place(&mut xl);
                    let xmax = xl.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    let tol = 1e-12 * (scale * scale).max(1.0 / (scale * scale));
                    for i in 0..n {
                        assert!(
                            (xd[i] - xl[i]).abs() <= tol * xmax,
                            "k {k} n {n} scale {scale} [{i}]: {} vs {}",
                            xd[i],
                            xl[i]
                        );
                    }
                }
            }
            let a = pivoting_band(40, k, k);
            let mut f = a.clone();
            f.factorize("small diagonal").unwrap();
            assert!(f.interchanged, "k {k}: the pivoting LU expected");
            let mut lu = a.clone();
            lu.factorize_lu("small diagonal").unwrap();
            assert_eq!(
                f, lu,
                "k {k}: the matrix as given is put back before the LU"
            );
        }
    }

    #[test]
    fn indefinite_or_unsymmetric_bands_take_an_lu_not_the_ldlt() {
        let mut seed = 11u64;
        for k in [5usize, 7] {
            let n = 40;
            // symmetric indefinite: a negative diagonal entry in the middle
            let mut a = random_symmetric(n, k, &mut seed, 1.05, 1.0);
            a.add(20, 20, -3.0 * a.get(20, 20));
            // unsymmetric by one entry
            let mut u = random_symmetric(n, k, &mut seed, 1.05, 1.0);
            u.add(3, 3 + k, 1e-9);
            for (name, m) in [("indefinite", a), ("unsymmetric", u)] {
                let x: Vec<f64> = (0..n).map(|i| (0.7 * i as f64).cos()).collect();
                let mut b = vec![0.0; n];
                m.mul_vec(&x, &mut b);
                let mut f = m.clone();
                f.factorize(name).unwrap();
                assert!(!f.is_ldlt(), "{name} k {k}: LU expected");
                f.solve_in_place(&mut b);
                for i in 0..n {
                    assert!((b[i] - x[i]).abs() < 1e-10, "{name} k {k} [{i}]");
                }
            }
        }
        // a symmetric singular band is still reported as singular
        let mut s = BandMatrix::zeros(12, 5, 5);
        for i in 0..12 {
            if i != 6 {
                s.add(i, i, 1.0);
            }
        }
        assert!(matches!(
            s.factorize("K"),
            Err(BeamError::Singular { dof: 6, .. })
        ));
    }
}
