//! A banded matrix and its LU factorisation with partial pivoting (LAPACK `gbtf2` scheme).
//!
//! The beam's node-ordered DOFs give a half-bandwidth of 5 (one element couples 6 consecutive
//! DOFs), so factorisation costs O(n·kl·(kl + ku)) and a solve O(n·(2kl + ku)): linear in the
//! number of elements. faer 0.24 has no banded solver and its general sparse LU/Cholesky carries
//! a symbolic/permutation overhead that dominates at the sizes the rig uses (≈ 100 DOFs, 20 µs
//! per step budget), hence this small dedicated kernel; dense/sparse faer is used for the
//! eigenproblem ([`crate::modal`]).

use crate::BeamError;

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
        }
    }
    /// Dimension n.
    pub fn n(&self) -> usize {
        self.n
    }
    /// Zeroes every entry (keeps the allocation).
    pub fn clear(&mut self) {
        self.data.iter_mut().for_each(|x| *x = 0.0);
        self.factored = false;
    }
    #[inline]
    fn idx(&self, i: usize, j: usize) -> usize {
        j * self.ld + self.kl + self.ku + i - j
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
    #[inline]
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
    /// LU factorisation in place with partial pivoting. `what` names the matrix in the error
    /// raised on a (numerically) zero pivot.
    ///
    /// The beam's band shapes (kl = ku = 5 for the 3-DOF nodes, 7 for ANCF) run kernels with the
    /// bandwidths as constants (fixed-length column updates that the compiler unrolls and
    /// vectorises); the last columns, where the matrix's end cuts the band, and any other shape
    /// run the general loop. Both do the same operations in the same order.
    pub fn factorize(&mut self, what: &str) -> Result<(), BeamError> {
        self.factored = false;
        let tiny = self.max_abs() * 1e-14;
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
    fn factorize_fixed<const KL: usize, const W: usize>(
        &mut self,
        tiny: f64,
    ) -> Result<usize, usize> {
        debug_assert!(self.kl == KL && self.kl + self.ku == W);
        let (n, ld) = (self.n, self.ld);
        let end = n.saturating_sub(W + 1);
        // row j of column c sits at c·ld + W + j − c: column c's rows j+1..=j+KL start at
        // c·ld + W + j + 1 − c
        for j in 0..end {
            let p = self.pivot(j, j + KL, tiny)?;
            self.pivots[j] = p;
            self.swap_rows(j, p, j + W);
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
            for c in j + 1..=j + W {
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

    /// Solves A x = b in place (after [`BandMatrix::factorize`]).
    pub fn solve_in_place(&self, b: &mut [f64]) {
        assert!(self.factored, "BandMatrix::solve_in_place before factorize");
        assert_eq!(
            b.len(),
            self.n,
            "BandMatrix::solve_in_place: right-hand side length"
        );
        match (self.kl, self.ku) {
            (5, 5) => self.solve_fixed::<5, 10>(b),
            (7, 7) => self.solve_fixed::<7, 14>(b),
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
    /// updates away from the matrix's ends (the same operations as the general loop).
    fn solve_fixed<const KL: usize, const W: usize>(&self, b: &mut [f64]) {
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
        // backward: U (kl + ku super-diagonals after the interchanges)
        for j in (0..n).rev() {
            let diag = j * ld + W;
            b[j] /= self.data[diag];
            let bj = b[j];
            if j >= W {
                let u: &[f64; W] = self.data[diag - W..diag].try_into().expect("band");
                let seg: &mut [f64; W] = (&mut b[j - W..j]).try_into().expect("rhs");
                for i in 0..W {
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
}
